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
// of A in place: an owned point's from the rank's diagonal and off-diagonal parts, a ghost
// point's (owned by another rank) from a submatrix of those rows alone (MatCreateSubMatrices,
// refreshed in place when A changes). Each patch keeps L_i⁻¹ for the Cholesky
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

/// Rows of a sequential AIJ matrix with each column mapped to a local dof of the rank
/// (3 × local point + component), or -1 for columns outside the rank's local points.
struct MappedRows {
  Mat mat = nullptr;
  const PetscInt *ia = nullptr, *ja = nullptr;
  const PetscScalar* values = nullptr;
  std::vector<int> column_dof;
  PetscErrorCode open(Mat m) {
    PetscInt n;
    PetscBool done;
    PetscFunctionBeginUser;
    mat = m;
    PetscCall(MatGetRowIJ(mat, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
    PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "vpatch: no row access to the operator");
    PetscCall(MatSeqAIJGetArrayRead(mat, &values));
    PetscFunctionReturn(0);
  }
  PetscErrorCode close() {
    PetscInt n;
    PetscBool done;
    PetscFunctionBeginUser;
    if (!mat) PetscFunctionReturn(0);
    PetscCall(MatSeqAIJRestoreArrayRead(mat, &values));
    PetscCall(MatRestoreRowIJ(mat, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
    mat = nullptr;
    PetscFunctionReturn(0);
  }
};

struct VertexPatchPc {
  const VertexPatches* patches = nullptr;
  IS local_is = nullptr;         // the local points' dofs, sorted (block size 3)
  std::vector<int> position;     // local point → its block position in local_is
  VecScatter scatter = nullptr;  // global → local_is order
  Vec local_r = nullptr, local_z = nullptr;
  // Where the rows of each local point are: an owned point's in the rank's diagonal and
  // off-diagonal parts of A (block row `row[q]`), another rank's point's in `ghost_rows`, the
  // submatrix of those rows alone (block row `row[q]`).
  std::vector<int> row;
  IS ghost_is = nullptr;
  Mat* ghost_rows = nullptr;
  MappedRows diagonal, off_diagonal, ghost;
  std::vector<std::pair<PetscInt, int>> ghost_of_block;  // (PETSc block, local point), sorted
  std::vector<std::size_t> offset;                       // each patch's start in `factor`
  std::unique_ptr<double[]> factor;  // L_i⁻¹ for L_i L_iᵀ = |A_i|, lower triangle packed by rows
  std::vector<int> slot;             // local point → index in the current patch, or -1
  long shifted = 0;                  // patches that were not positive definite (last setup)
  std::size_t largest = 0;           // dofs of the largest patch
};

PetscErrorCode reset(PC pc) {
  auto* p = static_cast<VertexPatchPc*>(pc->data);
  PetscFunctionBeginUser;
  if (p->ghost_rows) PetscCall(MatDestroySubMatrices(1, &p->ghost_rows));
  PetscCall(ISDestroy(&p->ghost_is));
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

/// L⁻¹ for the Cholesky factor L L^T = A of the symmetric m × m matrix A (its lower triangle is
/// read), packed by rows into `Linv`: Linv[i(i+1)/2 + j], j ≤ i. `L` and `inverse` are
/// workspace. False if A is not positive definite (a pivot is not positive, or not finite).
bool inverse_cholesky_packed(const Eigen::MatrixXd& A, Eigen::MatrixXd& L, Eigen::MatrixXd& inverse,
                             double* Linv) {
  const int m = static_cast<int>(A.rows());
  L = A;
  const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(L);
  // Eigen's LLT stops at a pivot ≤ 0; a NaN pivot passes that test and shows on the diagonal.
  if (llt.info() != Eigen::Success || !L.diagonal().allFinite()) return false;
  inverse.setIdentity(m, m);
  L.triangularView<Eigen::Lower>().solveInPlace(inverse);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j <= i; ++j) Linv[i * (i + 1) / 2 + j] = inverse(i, j);
  return true;
}

/// Packed L⁻¹ (inverse_cholesky_packed's layout) for |A| of one symmetric patch matrix: A's own
/// factor where A is positive definite, else that of its spectral absolute value with
/// eigenvalues floored at 1e-12 of the largest. Returns 1 if A was not positive definite, -1 if
/// A is not finite.
int factor_patch(Eigen::MatrixXd& A, Eigen::MatrixXd& L, Eigen::MatrixXd& inverse, double* Linv) {
  const int m = static_cast<int>(A.rows());
  if (inverse_cholesky_packed(A, L, inverse, Linv)) return 0;
  if (!A.allFinite()) return -1;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A);
  Eigen::VectorXd lambda = es.eigenvalues().cwiseAbs();
  const double floor = std::max(1e-12 * lambda.maxCoeff(), std::numeric_limits<double>::min());
  for (int k = 0; k < m; ++k) lambda[k] = std::max(lambda[k], floor);
  A = es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
  return inverse_cholesky_packed(A, L, inverse, Linv) ? 1 : -1;
}

/// z = M⁻ᵀ M⁻¹ r for M⁻¹ packed by rows (inverse_cholesky_packed), in one pass over M⁻¹: row i
/// gives y_i = (M⁻¹ r)_i and adds y_i times itself to z = M⁻ᵀ y while it is in cache (the
/// factors of all patches exceed the caches, so the pass is bound by memory traffic).
void solve_packed(const double* Minv, int m, const double* r, double* z) {
  using Row = Eigen::Map<const Eigen::VectorXd>;
  Eigen::Map<Eigen::VectorXd> zm(z, m);
  const Row rm(r, m);
  zm.setZero();
  for (int i = 0; i < m; ++i) {
    const Row Mi(Minv + i * (i + 1) / 2, i + 1);
    zm.head(i + 1) += Mi.dot(rm.head(i + 1)) * Mi;
  }
}

/// One patch matrix A_i from the mapped rows of its points (dense, column-major, m × m).
void extract_patch(const VertexPatchPc& p, const std::vector<int>& patch, Eigen::MatrixXd& D) {
  const int k = static_cast<int>(patch.size()),
            num_owned = static_cast<int>(p.patches->patches.size());
  D.setZero(3 * k, 3 * k);
  // Scalar row r of `rows` into row a of D, entry by entry.
  auto add_row = [&](const MappedRows& rows, PetscInt r, int a) {
    for (PetscInt e = rows.ia[r]; e < rows.ia[r + 1]; ++e) {
      const int dof = rows.column_dof[rows.ja[e]];
      if (dof < 0) continue;
      const int b = p.slot[dof / 3];
      if (b >= 0) D(a, 3 * b + dof % 3) = rows.values[e];
    }
  };
  // Block row r (scalar rows 3r..3r+2) into row block a of D. Rows of mlshell's Hessians store
  // full 3 × 3 blocks (element_matrix_assembly.cpp), and so do the ghost rows taken from them:
  // one slot lookup per block instead of per entry (the per-entry lookups were most of the
  // setup). A block is read whole only if its three rows hold the same three consecutive
  // columns and those are components 0, 1, 2 of one point (or of none here); otherwise the rows
  // are read entry by entry, which rewrites any block already read with the same values.
  auto add_block_row = [&](const MappedRows& rows, PetscInt r, int a) {
    const PetscInt* ia = rows.ia + 3 * r;
    const PetscInt len = ia[1] - ia[0];
    bool blocked = len % 3 == 0 && ia[2] - ia[1] == len && ia[3] - ia[2] == len;
    for (PetscInt e = 0; blocked && e < len; e += 3) {
      const PetscInt col = rows.ja[ia[0] + e];
      for (int c = 0; blocked && c < 3; ++c)
        blocked = rows.ja[ia[c] + e] == col && rows.ja[ia[c] + e + 2] == col + 2;
      const int dof = blocked ? rows.column_dof[col] : -1;
      blocked = blocked && (dof < 0 ? rows.column_dof[col + 1] < 0 && rows.column_dof[col + 2] < 0
                                    : dof % 3 == 0 && rows.column_dof[col + 1] == dof + 1 &&
                                          rows.column_dof[col + 2] == dof + 2);
      if (!blocked || dof < 0) continue;
      const int b = p.slot[dof / 3];
      if (b < 0) continue;
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) D(3 * a + c, 3 * b + d) = rows.values[ia[c] + e + d];
    }
    if (!blocked)
      for (int c = 0; c < 3; ++c) add_row(rows, 3 * r + c, 3 * a + c);
  };
  for (int a = 0; a < k; ++a) {
    const int q = patch[a];
    const PetscInt r = p.row[q];
    if (q < num_owned) {
      add_block_row(p.diagonal, r, a);
      if (p.off_diagonal.mat) add_block_row(p.off_diagonal, r, a);
    } else {
      add_block_row(p.ghost, r, a);
    }
  }
}

/// First setup for a layout: the local ordering, the scatter and the row maps.
PetscErrorCode setup_layout(PC pc, const VertexPatches* patches) {
  auto* p = static_cast<VertexPatchPc*>(pc->data);
  PetscFunctionBeginUser;
  PetscCall(reset(pc));
  p->patches = patches;
  const std::size_t n = patches->blocks.size(), num_owned = patches->patches.size();
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
  Vec global;
  PetscCall(MatCreateVecs(pc->pmat, &global, nullptr));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * static_cast<PetscInt>(n), &p->local_r));
  PetscCall(VecDuplicate(p->local_r, &p->local_z));
  PetscCall(VecScatterCreate(global, p->local_is, p->local_r, nullptr, &p->scatter));
  PetscCall(VecDestroy(&global));
  // Owned points: rows and columns of the rank's diagonal part.
  PetscInt first, last;
  PetscCall(MatGetOwnershipRange(pc->pmat, &first, &last));
  const PetscInt first_block = first / 3;
  p->row.assign(n, -1);
  p->diagonal.column_dof.assign(static_cast<std::size_t>(last - first), -1);
  for (std::size_t q = 0; q < num_owned; ++q) {
    const PetscInt b = patches->blocks[q] - first_block;
    PetscCheck(b >= 0 && 3 * b < last - first, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
               "vpatch: owned point %zu is not in the operator's rows of this rank", q);
    p->row[q] = static_cast<int>(b);
    for (int c = 0; c < 3; ++c) p->diagonal.column_dof[3 * b + c] = 3 * static_cast<int>(q) + c;
  }
  // The other local points: their rows come from the ranks that own them, columns in local_is
  // order.
  std::vector<PetscInt> ghost_blocks;
  p->ghost_of_block.clear();
  for (std::size_t k = 0; k < n; ++k)
    if (static_cast<std::size_t>(order[k]) >= num_owned) {
      p->row[order[k]] = static_cast<int>(ghost_blocks.size());
      ghost_blocks.push_back(sorted[k]);
      p->ghost_of_block.emplace_back(sorted[k], order[k]);
    }
  p->ghost.column_dof.resize(3 * n);
  for (std::size_t k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) p->ghost.column_dof[3 * k + c] = 3 * order[k] + c;
  PetscCall(ISCreateBlock(PETSC_COMM_SELF, 3, static_cast<PetscInt>(ghost_blocks.size()),
                          ghost_blocks.data(), PETSC_COPY_VALUES, &p->ghost_is));
  p->offset.assign(num_owned + 1, 0);
  p->largest = 0;
  for (std::size_t i = 0; i < num_owned; ++i) {
    const std::size_t m = 3 * patches->patches[i].size();
    p->offset[i + 1] = p->offset[i] + m * (m + 1) / 2;
    p->largest = std::max(p->largest, m);
  }
  p->factor.reset(new double[p->offset.back()]);
  p->slot.assign(n, -1);
  PetscFunctionReturn(0);
}

PetscErrorCode setup(PC pc) {
  auto* p = static_cast<VertexPatchPc*>(pc->data);
  PetscFunctionBeginUser;
  const VertexPatches* patches = nullptr;
  PetscCall(vertex_patches_of(pc->pmat, &patches));
  PetscCheck(patches, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONG,
             "PC vpatch needs a matrix that knows its vertex patches (one made by mlshell's "
             "ParallelLayout::create_matrix)");
  const bool first = patches != p->patches;  // first setup, or another operator layout
  if (first) PetscCall(setup_layout(pc, patches));
  // The rank's rows of A: the diagonal part and the off-diagonal part (its compressed columns
  // mapped through their global indices), or A itself on one process.
  PetscBool mpiaij, seqaij;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc->pmat, MATMPIAIJ, &mpiaij));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc->pmat, MATSEQAIJ, &seqaij));
  PetscCheck(mpiaij || seqaij, PetscObjectComm((PetscObject)pc), PETSC_ERR_SUP,
             "PC vpatch needs an AIJ operator");
  Mat diagonal = pc->pmat, off_diagonal = nullptr;
  if (mpiaij) {
    const PetscInt* garray;
    PetscCall(MatMPIAIJGetSeqAIJ(pc->pmat, &diagonal, &off_diagonal, &garray));
    PetscInt columns;
    PetscCall(MatGetSize(off_diagonal, nullptr, &columns));
    p->off_diagonal.column_dof.assign(static_cast<std::size_t>(columns), -1);
    for (PetscInt k = 0; k < columns; ++k) {
      const auto it = std::lower_bound(p->ghost_of_block.begin(), p->ghost_of_block.end(),
                                       std::pair<PetscInt, int>{garray[k] / 3, -1});
      if (it != p->ghost_of_block.end() && it->first == garray[k] / 3)
        p->off_diagonal.column_dof[k] = 3 * it->second + static_cast<int>(garray[k] % 3);
    }
    // Rows of the points other ranks own (collective: every rank calls it).
    // A new pattern under the same matrix (contact pairs: LevelProblem::hessian) takes new rows.
    const bool reuse = !first && pc->flag != DIFFERENT_NONZERO_PATTERN && p->ghost_rows;
    if (!first && !reuse && p->ghost_rows) PetscCall(MatDestroySubMatrices(1, &p->ghost_rows));
    PetscCall(MatCreateSubMatrices(pc->pmat, 1, &p->ghost_is, &p->local_is,
                                   reuse ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &p->ghost_rows));
    PetscCall(p->ghost.open(p->ghost_rows[0]));
  }
  PetscCall(p->diagonal.open(diagonal));
  if (off_diagonal) PetscCall(p->off_diagonal.open(off_diagonal));
  // Each patch matrix, then its inverse factor.
  p->shifted = 0;
  Eigen::MatrixXd D, L, inverse;
  long bad = -1;  // the first patch that is not finite
  for (std::size_t i = 0; i < patches->patches.size() && bad < 0; ++i) {
    const auto& patch = patches->patches[i];
    const int m = static_cast<int>(3 * patch.size());
    for (std::size_t a = 0; a < patch.size(); ++a) p->slot[patch[a]] = static_cast<int>(a);
    extract_patch(*p, patch, D);
    for (int q : patch) p->slot[q] = -1;
    // The patch matrix is symmetric up to round-off: symmetrise (in place, no temporary).
    for (int j = 0; j < m; ++j)
      for (int r = j + 1; r < m; ++r) D(r, j) = D(j, r) = 0.5 * (D(r, j) + D(j, r));
    const int kind = factor_patch(D, L, inverse, p->factor.get() + p->offset[i]);
    if (kind < 0) bad = static_cast<long>(i);
    p->shifted += kind > 0;
  }
  PetscCall(p->diagonal.close());
  PetscCall(p->off_diagonal.close());
  PetscCall(p->ghost.close());
  PetscCheck(bad < 0, PETSC_COMM_SELF, PETSC_ERR_FP,
             "vpatch: the patch of owned point %ld has entries that are not finite", bad);
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
  std::vector<double> rp(p->largest), zp(p->largest);
  const auto& patches = p->patches->patches;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const auto& patch = patches[i];
    const int m = static_cast<int>(3 * patch.size());
    for (std::size_t a = 0; a < patch.size(); ++a)
      for (int c = 0; c < 3; ++c) rp[3 * a + c] = rl[3 * p->position[patch[a]] + c];
    solve_packed(p->factor.get() + p->offset[i], m, rp.data(), zp.data());
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

PetscErrorCode share_vertex_patches(Mat from, Mat to) {
  PetscObject container = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectQuery((PetscObject)from, kPatchesKey, &container));
  if (container) PetscCall(PetscObjectCompose((PetscObject)to, kPatchesKey, container));
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
