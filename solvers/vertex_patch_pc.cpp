// PC "vpatch": additive Schwarz over vertex patches with exact patch solves (see
// vertex_patch_pc.hpp).
//
//   M⁻¹ r = Σ_i R_iᵀ |A_i|⁻¹ R_i r,   A_i = R_i A R_iᵀ,
// R_i the restriction to patch i. |A_i| is A_i where A_i is positive definite (a Cholesky
// factorisation exists) and otherwise its spectral absolute value with eigenvalues floored at
// 1e-12 of the largest, so that M⁻¹ is symmetric positive definite for any symmetric A (as
// Steihaug–Toint CG requires), indefinite Hessians of compressed cloth included.
//
// Each rank solves the patches of the points it owns. The patch matrices come from one
// sequential submatrix of A over the rank's local (owned + ghost) points, extracted with
// MatCreateSubMatrices (off-rank rows included) and refreshed in place when A changes.
#include "mlshell/vertex_patch_pc.hpp"

#include <petsc/private/pcimpl.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
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
  Mat* sub = nullptr;            // A restricted to local_is
  VecScatter scatter = nullptr;  // global → local_is order
  Vec local_r = nullptr, local_z = nullptr;
  std::vector<std::size_t> offset;  // start of each patch's inverse in `inverse`
  std::vector<double> inverse;      // |A_i|⁻¹, column-major, patch after patch
  long shifted = 0;                 // patches that were not positive definite (last setup)
  std::size_t largest = 0;          // dofs of the largest patch
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
  PetscFunctionReturn(0);
}

PetscErrorCode destroy(PC pc) {
  PetscFunctionBeginUser;
  PetscCall(reset(pc));
  delete static_cast<VertexPatchPc*>(pc->data);
  pc->data = nullptr;
  PetscFunctionReturn(0);
}

/// |A|⁻¹ of one symmetric patch matrix into `out` (column-major); true if A was not positive
/// definite.
bool invert_patch(const Eigen::MatrixXd& A, double* out) {
  const int m = static_cast<int>(A.rows());
  Eigen::Map<Eigen::MatrixXd> inv(out, m, m);
  Eigen::LLT<Eigen::MatrixXd> llt(A);
  if (llt.info() == Eigen::Success) {
    inv = llt.solve(Eigen::MatrixXd::Identity(m, m));
    if (inv.allFinite()) return false;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A);
  Eigen::VectorXd lambda = es.eigenvalues().cwiseAbs();
  const double floor = std::max(1e-12 * lambda.maxCoeff(), std::numeric_limits<double>::min());
  for (int k = 0; k < m; ++k) lambda[k] = 1.0 / std::max(lambda[k], floor);
  inv = es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
  return true;
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
    PetscCall(
        MatCreateSubMatrices(pc->pmat, 1, &p->local_is, &p->local_is, MAT_INITIAL_MATRIX, &p->sub));
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
      p->offset[i + 1] = p->offset[i] + m * m;
      p->largest = std::max(p->largest, m);
    }
    p->inverse.assign(p->offset.back(), 0.0);
  } else {
    PetscCall(
        MatCreateSubMatrices(pc->pmat, 1, &p->local_is, &p->local_is, MAT_REUSE_MATRIX, &p->sub));
  }
  // Factor every patch.
  p->shifted = 0;
  std::vector<PetscInt> rows;
  std::vector<PetscScalar> values;
  for (std::size_t i = 0; i < patches->patches.size(); ++i) {
    const auto& patch = patches->patches[i];
    const int m = static_cast<int>(3 * patch.size());
    rows.resize(m);
    for (std::size_t a = 0; a < patch.size(); ++a)
      for (int c = 0; c < 3; ++c) rows[3 * a + c] = 3 * p->position[patch[a]] + c;
    values.resize(static_cast<std::size_t>(m) * m);
    PetscCall(MatGetValues(p->sub[0], m, rows.data(), m, rows.data(), values.data()));
    // MatGetValues is row-major; the patch matrix is symmetric up to round-off: symmetrise.
    Eigen::Map<const Eigen::MatrixXd> Arm(values.data(), m, m);
    const Eigen::MatrixXd A = 0.5 * (Arm + Arm.transpose());
    p->shifted += invert_patch(A, p->inverse.data() + p->offset[i]);
  }
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
  Eigen::VectorXd rp(p->largest), zp(p->largest);
  const auto& patches = p->patches->patches;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const auto& patch = patches[i];
    const int m = static_cast<int>(3 * patch.size());
    for (std::size_t a = 0; a < patch.size(); ++a)
      for (int c = 0; c < 3; ++c) rp[3 * a + c] = rl[3 * p->position[patch[a]] + c];
    Eigen::Map<const Eigen::MatrixXd> inv(p->inverse.data() + p->offset[i], m, m);
    zp.head(m).noalias() = inv * rp.head(m);
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
