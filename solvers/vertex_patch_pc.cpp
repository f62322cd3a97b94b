// PC "vpatch": additive Schwarz over vertex patches with exact patch solves (see
// vertex_patch_pc.hpp).
//
//   M⁻¹ r = Σ_i R_iᵀ |A_i|⁻¹ R_i r,   A_i = R_i A R_iᵀ,
// R_i the restriction to patch i. |A_i| is A_i where A_i is positive definite (a Cholesky
// factorisation exists) and otherwise its spectral absolute value with eigenvalues floored at
// 1e-12 of the largest, so that M⁻¹ is symmetric positive definite for any symmetric A (as
// Steihaug–Toint CG requires), indefinite Hessians of compressed cloth included.
//
// Each rank solves the patches of the points it owns. The patch matrices are read from the rows
// of one sequential submatrix of A over the rank's local (owned + ghost) points, extracted with
// MatCreateSubMatrices (off-rank rows included) and refreshed in place when A changes; on one
// process A is that submatrix and is read directly. Each patch keeps L_i⁻¹ for the Cholesky
// factor L_i of |A_i| (lower triangle, packed): half the memory of |A_i|⁻¹, and a solve is
// two triangular products, z = L_i⁻ᵀ (L_i⁻¹ r), without the serial chain of a substitution.
#include "mlshell/vertex_patch_pc.hpp"

#include <petsc/private/pcimpl.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <vector>

#include "mlshell/vertex_patches.hpp"

namespace mlshell {

namespace {

constexpr const char* kPatchesKey = "mlshell_vertex_patches";

struct PatchContainer {
  std::shared_ptr<const VertexPatches> patches;
};

PetscErrorCode destroy_container(void* ctx) {
  delete static_cast<PatchContainer*>(ctx);
  return 0;
}

struct VertexPatchPc {
  const VertexPatches* patches = nullptr;
  IS local_is = nullptr;         // the local points' dofs, sorted (block size 3)
  std::vector<int> position;     // local point → its block position in local_is
  Mat* sub = nullptr;            // A restricted to local_is (several processes)
  bool direct = false;           // one process: A itself is that submatrix
  VecScatter scatter = nullptr;  // global → local_is order
  Vec local_r = nullptr, local_z = nullptr;
  std::vector<std::size_t> offset;   // start of each patch's factor in `factor`
  std::unique_ptr<double[]> factor;  // L_i⁻¹ for L_i L_iᵀ = |A_i|, lower triangle packed by rows
  std::vector<int> slot;             // block position → index in the current patch, or -1
  long shifted = 0;                  // patches that were not positive definite (last setup)
  std::size_t largest = 0;           // dofs of the largest patch
};

PetscErrorCode reset(PC pc) {
  auto* p = static_cast<VertexPatchPc*>(pc->data);
  PetscFunctionBeginUser;
  if (p->sub) PetscCall(MatDestroySubMatrices(1, &p->sub));
  PetscCall(ISDestroy(&p->local_is));
  PetscCall(VecScatterDestroy(&p->scatter));
  PetscCall(VecDestroy(&p->local_r));
  PetscCall(VecDestroy(&p->local_z));
  p->patches = nullptr;
  p->factor.reset();
  PetscFunctionReturn(0);
}

PetscErrorCode destroy(PC pc) {
  PetscFunctionBeginUser;
  PetscCall(reset(pc));
  delete static_cast<VertexPatchPc*>(pc->data);
  pc->data = nullptr;
  PetscFunctionReturn(0);
}

/// Cholesky factor of the symmetric m × m matrix A (column-major; its lower triangle is read)
/// into L, packed by rows: L[i(i+1)/2 + j], j ≤ i. False if a pivot is not positive.
bool cholesky_packed(const double* A, int m, double* L) {
  for (int i = 0; i < m; ++i) {
    double* Li = L + i * (i + 1) / 2;
    for (int j = 0; j <= i; ++j) {
      const double* Lj = L + j * (j + 1) / 2;
      const double s = A[i + j * m] - Eigen::Map<const Eigen::VectorXd>(Li, j)
                                          .dot(Eigen::Map<const Eigen::VectorXd>(Lj, j));
      if (j < i) {
        Li[j] = s / Lj[j];
      } else {
        if (!(s > 0.0) || !std::isfinite(s)) return false;
        Li[i] = std::sqrt(s);
      }
    }
  }
  return true;
}

/// Factor of |A| for one symmetric patch matrix into `L` (cholesky_packed's layout): A's own
/// where A is positive definite, else that of its spectral absolute value with eigenvalues
/// floored at 1e-12 of the largest. Returns 1 if A was not positive definite, -1 if A is not
/// finite.
int factor_patch(Eigen::MatrixXd& A, double* L) {
  const int m = static_cast<int>(A.rows());
  if (cholesky_packed(A.data(), m, L)) return 0;
  if (!A.allFinite()) return -1;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A);
  Eigen::VectorXd lambda = es.eigenvalues().cwiseAbs();
  const double floor = std::max(1e-12 * lambda.maxCoeff(), std::numeric_limits<double>::min());
  for (int k = 0; k < m; ++k) lambda[k] = std::max(lambda[k], floor);
  A = es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
  return cholesky_packed(A.data(), m, L) ? 1 : -1;
}

/// Replaces a factor packed by cholesky_packed by L⁻¹, in the same layout (`work`: m² doubles).
void invert_lower_packed(double* L, int m, double* work) {
  // Column j of L⁻¹ solves L x = e_j (x_i = 0 for i < j); L is read until the last column.
  for (int j = 0; j < m; ++j) {
    double* x = work + static_cast<std::size_t>(j) * m;
    for (int i = j; i < m; ++i) {
      const double* Li = L + i * (i + 1) / 2;
      double s = i == j ? 1.0 : 0.0;
      for (int k = j; k < i; ++k) s -= Li[k] * x[k];
      x[i] = s / Li[i];
    }
  }
  for (int i = 0; i < m; ++i)
    for (int j = 0; j <= i; ++j) L[i * (i + 1) / 2 + j] = work[static_cast<std::size_t>(j) * m + i];
}

/// z = M⁻ᵀ M⁻¹ r for M⁻¹ packed by rows (invert_lower_packed).
void solve_packed(const double* Minv, int m, const double* r, double* y, double* z) {
  for (int i = 0; i < m; ++i) {  // y = M⁻¹ r: independent row products
    const double* Mi = Minv + i * (i + 1) / 2;
    double s = 0.0;
    for (int k = 0; k <= i; ++k) s += Mi[k] * r[k];
    y[i] = s;
  }
  for (int k = 0; k < m; ++k) z[k] = 0.0;
  for (int i = 0; i < m; ++i) {  // z = M⁻ᵀ y: row i of M⁻¹ scaled by y_i
    const double* Mi = Minv + i * (i + 1) / 2;
    for (int k = 0; k <= i; ++k) z[k] += y[i] * Mi[k];
  }
}

PetscErrorCode setup(PC pc) {
  auto* p = static_cast<VertexPatchPc*>(pc->data);
  PetscFunctionBeginUser;
  const VertexPatches* patches = nullptr;
  PetscCall(vertex_patches_of(pc->pmat, &patches));
  PetscCheck(patches, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONG,
             "PC vpatch needs a matrix that knows its vertex patches (one made by mlshell's "
             "ParallelLayout::create_matrix)");
  if (patches != p->patches) {  // first setup, or another operator layout
    PetscCall(reset(pc));
    p->patches = patches;
    const std::size_t n = patches->blocks.size();
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return patches->blocks[a] < patches->blocks[b]; });
    p->position.assign(n, 0);
    std::vector<PetscInt> sorted(n);
    for (std::size_t k = 0; k < n; ++k) {
      p->position[order[k]] = static_cast<int>(k);
      sorted[k] = patches->blocks[order[k]];
    }
    PetscCall(ISCreateBlock(PETSC_COMM_SELF, 3, static_cast<PetscInt>(n), sorted.data(),
                            PETSC_COPY_VALUES, &p->local_is));
    // On one process the local points are all points, sorted: A is its own submatrix.
    PetscMPIInt size;
    PetscBool seqaij;
    PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)pc->pmat), &size));
    PetscCall(PetscObjectTypeCompare((PetscObject)pc->pmat, MATSEQAIJ, &seqaij));
    p->direct = size == 1 && seqaij && (n == 0 || sorted.back() == static_cast<PetscInt>(n) - 1);
    if (!p->direct)
      PetscCall(MatCreateSubMatrices(pc->pmat, 1, &p->local_is, &p->local_is, MAT_INITIAL_MATRIX,
                                     &p->sub));
    Vec global;
    PetscCall(MatCreateVecs(pc->pmat, &global, nullptr));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * static_cast<PetscInt>(n), &p->local_r));
    PetscCall(VecDuplicate(p->local_r, &p->local_z));
    PetscCall(VecScatterCreate(global, p->local_is, p->local_r, nullptr, &p->scatter));
    PetscCall(VecDestroy(&global));
    p->offset.assign(patches->patches.size() + 1, 0);
    p->largest = 0;
    for (std::size_t i = 0; i < patches->patches.size(); ++i) {
      const std::size_t m = 3 * patches->patches[i].size();
      p->offset[i + 1] = p->offset[i] + m * (m + 1) / 2;
      p->largest = std::max(p->largest, m);
    }
    p->factor.reset(new double[p->offset.back()]);
    p->slot.assign(n, -1);
  } else if (!p->direct) {
    PetscCall(
        MatCreateSubMatrices(pc->pmat, 1, &p->local_is, &p->local_is, MAT_REUSE_MATRIX, &p->sub));
  }
  // Each patch matrix straight from the rows of the (sub)matrix, then its inverse factor.
  Mat local = p->direct ? pc->pmat : p->sub[0];
  PetscInt rows_n;
  const PetscInt *ia, *ja;
  PetscBool done;
  const PetscScalar* values;
  PetscCall(MatGetRowIJ(local, 0, PETSC_FALSE, PETSC_FALSE, &rows_n, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "vpatch: no row access to the patch matrix");
  PetscCall(MatSeqAIJGetArrayRead(local, &values));
  p->shifted = 0;
  Eigen::MatrixXd D;
  std::vector<double> work;
  PetscErrorCode bad = -1;
  for (std::size_t i = 0; i < patches->patches.size() && bad < 0; ++i) {
    const auto& patch = patches->patches[i];
    const int k = static_cast<int>(patch.size()), m = 3 * k;
    for (int a = 0; a < k; ++a) p->slot[p->position[patch[a]]] = a;
    D.setZero(m, m);
    for (int a = 0; a < k; ++a)
      for (int c = 0; c < 3; ++c) {
        const PetscInt row = 3 * p->position[patch[a]] + c;
        for (PetscInt e = ia[row]; e < ia[row + 1]; ++e) {
          const int b = p->slot[ja[e] / 3];
          if (b >= 0) D(3 * a + c, 3 * b + ja[e] % 3) = values[e];
        }
      }
    for (int a = 0; a < k; ++a) p->slot[p->position[patch[a]]] = -1;
    // The patch matrix is symmetric up to round-off: symmetrise (in place, no temporary).
    for (int j = 0; j < m; ++j)
      for (int r = j + 1; r < m; ++r) D(r, j) = D(j, r) = 0.5 * (D(r, j) + D(j, r));
    const int kind = factor_patch(D, p->factor.get() + p->offset[i]);
    if (kind >= 0) {
      work.resize(static_cast<std::size_t>(m) * m);
      invert_lower_packed(p->factor.get() + p->offset[i], m, work.data());
    }
    if (kind < 0) bad = static_cast<PetscErrorCode>(i);
    p->shifted += kind > 0;
  }
  PetscCall(MatSeqAIJRestoreArrayRead(local, &values));
  PetscCall(MatRestoreRowIJ(local, 0, PETSC_FALSE, PETSC_FALSE, &rows_n, &ia, &ja, &done));
  PetscCheck(bad < 0, PETSC_COMM_SELF, PETSC_ERR_FP,
             "vpatch: the patch of owned point %d has entries that are not finite",
             static_cast<int>(bad));
  PetscFunctionReturn(0);
}

PetscErrorCode apply(PC pc, Vec r, Vec z) {
  auto* p = static_cast<VertexPatchPc*>(pc->data);
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(p->scatter, r, p->local_r, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(p->scatter, r, p->local_r, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecSet(p->local_z, 0.0));
  const PetscScalar* rl;
  PetscScalar* zl;
  PetscCall(VecGetArrayRead(p->local_r, &rl));
  PetscCall(VecGetArray(p->local_z, &zl));
  std::vector<double> rp(p->largest), yp(p->largest), zp(p->largest);
  const auto& patches = p->patches->patches;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const auto& patch = patches[i];
    const int m = static_cast<int>(3 * patch.size());
    for (std::size_t a = 0; a < patch.size(); ++a)
      for (int c = 0; c < 3; ++c) rp[3 * a + c] = rl[3 * p->position[patch[a]] + c];
    solve_packed(p->factor.get() + p->offset[i], m, rp.data(), yp.data(), zp.data());
    for (std::size_t a = 0; a < patch.size(); ++a)
      for (int c = 0; c < 3; ++c) zl[3 * p->position[patch[a]] + c] += zp[3 * a + c];
  }
  PetscCall(VecRestoreArrayRead(p->local_r, &rl));
  PetscCall(VecRestoreArray(p->local_z, &zl));
  PetscCall(VecSet(z, 0.0));
  PetscCall(VecScatterBegin(p->scatter, p->local_z, z, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(p->scatter, p->local_z, z, ADD_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

PetscErrorCode view(PC pc, PetscViewer viewer) {
  auto* p = static_cast<VertexPatchPc*>(pc->data);
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (ascii && p->patches)
    PetscCall(PetscViewerASCIIPrintf(
        viewer,
        "  vertex patches (additive Schwarz, exact patch solves): %zu on rank 0, at most %zu "
        "dofs, %ld not positive definite (|A_i| used)\n",
        p->patches->patches.size(), p->largest, p->shifted));
  PetscFunctionReturn(0);
}

PetscErrorCode create(PC pc) {
  PetscFunctionBeginUser;
  pc->data = new VertexPatchPc;
  pc->ops->setup = setup;
  pc->ops->apply = apply;
  pc->ops->applysymmetricleft = nullptr;
  pc->ops->destroy = destroy;
  pc->ops->reset = reset;
  pc->ops->view = view;
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode attach_vertex_patches(Mat A, std::shared_ptr<const VertexPatches> patches) {
  PetscFunctionBeginUser;
  PetscContainer container;
  PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)A), &container));
  PetscCall(PetscContainerSetPointer(container, new PatchContainer{std::move(patches)}));
  PetscCall(PetscContainerSetUserDestroy(container, destroy_container));
  PetscCall(PetscObjectCompose((PetscObject)A, kPatchesKey, (PetscObject)container));
  PetscCall(PetscContainerDestroy(&container));
  PetscFunctionReturn(0);
}

PetscErrorCode vertex_patches_of(Mat A, const VertexPatches** patches) {
  PetscFunctionBeginUser;
  *patches = nullptr;
  PetscObject obj = nullptr;
  PetscCall(PetscObjectQuery((PetscObject)A, kPatchesKey, &obj));
  if (!obj) PetscFunctionReturn(0);
  void* ptr = nullptr;
  PetscCall(PetscContainerGetPointer((PetscContainer)obj, &ptr));
  *patches = static_cast<PatchContainer*>(ptr)->patches.get();
  PetscFunctionReturn(0);
}

PetscErrorCode register_vertex_patch_pc() {
  static bool registered = false;
  PetscFunctionBeginUser;
  if (!registered) PetscCall(PCRegister("vpatch", create));
  registered = true;
  PetscFunctionReturn(0);
}

}  // namespace mlshell
