#include "mlshell/proxy_energy.hpp"

#include "mlshell/prolongation/triangle_transfer.hpp"
#include "mlshell/vertex_patches.hpp"

namespace mlshell {

ProxyEnergy::ProxyEnergy(Objective& finest, const LevelTransfer& direct, Vec coarse_template,
                         Mat pattern)
    : finest_(finest), direct_(direct), pattern_(pattern) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(coarse_template));
  PetscCallAbort(comm, finest_.create_hessian(&fine_h_));
  PetscCallAbort(comm, MatCreateVecs(fine_h_, &fine_u_, &fine_g_));
  PetscCallAbort(comm, VecDuplicate(coarse_template, &rest_));
  PetscCallAbort(comm, VecSet(rest_, 0.0));
  if (pattern_) PetscCallAbort(comm, PetscObjectReference(reinterpret_cast<PetscObject>(pattern_)));
}

PetscErrorCode ProxyEnergy::build_galerkin() const {
  PetscFunctionBeginUser;
  if (galerkin_) PetscFunctionReturn(0);
  // The Galerkin product's pattern (symbolic at the rest state; the values come per call), on
  // first use: a proxy whose Newton matrix is another one never needs it.
  PetscCall(MatZeroEntries(fine_h_));
  PetscCall(direct_.coarse_operator(rest_, fine_h_, MAT_INITIAL_MATRIX, &galerkin_));
  PetscCall(MatDuplicate(galerkin_, MAT_DO_NOT_COPY_VALUES, &template_));
  if (pattern_) {
    PetscCall(MatAXPY(template_, 1.0, pattern_, DIFFERENT_NONZERO_PATTERN));
    // The level's vertex patches (-tao_rmtr_smoother_pc vpatch) hold for this pattern too.
    PetscCall(share_vertex_patches(pattern_, template_));
  }
  PetscCall(MatZeroEntries(template_));
  PetscFunctionReturn(0);
}

ProxyEnergy::~ProxyEnergy() {
  VecDestroy(&fine_u_);
  VecDestroy(&fine_g_);
  VecDestroy(&rest_);
  MatDestroy(&pattern_);
  MatDestroy(&fine_h_);
  MatDestroy(&galerkin_);
  MatDestroy(&template_);
}

PetscErrorCode ProxyEnergy::objective(Vec u, PetscReal* f, Vec g) {
  PetscFunctionBeginUser;
  PetscCall(direct_.prolong(u, fine_u_));
  PetscCall(finest_.objective(fine_u_, f, g ? fine_g_ : nullptr));
  if (!g) PetscFunctionReturn(0);
  const auto* shell = dynamic_cast<const ShellTransfer*>(&direct_);
  if (gradient_ == Gradient::kFrozenOffset && shell)
    PetscCall(shell->restrict_intrinsic(fine_g_, g));
  else
    PetscCall(direct_.restrict_gradient(u, fine_g_, g));
  PetscFunctionReturn(0);
}

PetscErrorCode ProxyEnergy::hessian(Vec u, Mat H) {
  PetscFunctionBeginUser;
  PetscCall(build_galerkin());
  PetscCall(direct_.prolong(u, fine_u_));
  PetscCall(finest_.hessian(fine_u_, fine_h_));
  PetscCall(direct_.coarse_operator(u, fine_h_, MAT_REUSE_MATRIX, &galerkin_));
  PetscCall(MatZeroEntries(H));
  PetscCall(MatAXPY(H, 1.0, galerkin_, SUBSET_NONZERO_PATTERN));
  PetscFunctionReturn(0);
}

PetscErrorCode ProxyEnergy::create_hessian(Mat* H) const {
  PetscFunctionBeginUser;
  PetscCall(build_galerkin());
  PetscCall(MatDuplicate(template_, MAT_DO_NOT_COPY_VALUES, H));
  PetscCall(share_vertex_patches(template_, *H));
  PetscFunctionReturn(0);
}

PetscErrorCode ProxyEnergy::force_scale(Vec u, PetscReal* scale) {
  PetscFunctionBeginUser;
  PetscCall(direct_.prolong(u, fine_u_));
  PetscCall(finest_.force_scale(fine_u_, scale));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
