// RMTR's coarse-level model, eq. (4.3)–(4.4) (see coarse_level_model.hpp).
#include "mlshell/coarse_level_model.hpp"

namespace mlshell {

CoarseLevelModel::CoarseLevelModel(Objective& level) : level_(level) {}

CoarseLevelModel::~CoarseLevelModel() {
  VecDestroy(&x0_);
  VecDestroy(&delta_g_);
  VecDestroy(&work_);
  VecDestroy(&product_);
}

PetscErrorCode CoarseLevelModel::set_start(Vec x0) {
  PetscFunctionBeginUser;
  if (!x0_) {
    PetscCall(VecDuplicate(x0, &x0_));
    PetscCall(VecDuplicate(x0, &delta_g_));
    PetscCall(VecDuplicate(x0, &work_));
  }
  PetscCall(VecCopy(x0, x0_));
  PetscFunctionReturn(0);
}

PetscErrorCode CoarseLevelModel::initialize(Vec x0, Vec restricted_gradient, PetscReal* h0) {
  PetscFunctionBeginUser;
  PetscCall(set_start(x0));
  galerkin_ = nullptr;
  PetscReal f0;
  PetscCall(level_.objective(x0_, &f0, delta_g_));          // ∇f(x₀)
  PetscCall(VecAYPX(delta_g_, -1.0, restricted_gradient));  // δg = R∇h_fine − ∇f(x₀)
  PetscCall(VecNorm(delta_g_, NORM_2, &delta_g_norm_));
  if (h0) *h0 = f0;
  PetscFunctionReturn(0);
}

PetscErrorCode CoarseLevelModel::initialize_galerkin(Vec x0, Vec restricted_gradient,
                                                     Mat galerkin) {
  PetscFunctionBeginUser;
  PetscCall(set_start(x0));
  galerkin_ = galerkin;
  if (!product_) PetscCall(VecDuplicate(x0, &product_));
  PetscCall(VecCopy(restricted_gradient, delta_g_));  // r = R∇h_fine
  PetscCall(VecNorm(delta_g_, NORM_2, &delta_g_norm_));
  PetscFunctionReturn(0);
}

PetscErrorCode CoarseLevelModel::set_unmodified(Vec x0) {
  PetscFunctionBeginUser;
  PetscCall(set_start(x0));
  galerkin_ = nullptr;
  PetscCall(VecSet(delta_g_, 0.0));
  delta_g_norm_ = 0.0;
  PetscFunctionReturn(0);
}

PetscErrorCode CoarseLevelModel::initialize_unmodified(Vec x0, PetscReal* f0, Vec g0) {
  PetscFunctionBeginUser;
  PetscCall(set_unmodified(x0));
  PetscCall(level_.objective(x0_, f0, g0));
  PetscFunctionReturn(0);
}

PetscReal CoarseLevelModel::evaluation_error() const {
  PetscReal step = 0.0;  // work_ holds x − x₀ of the last objective()
  PetscCallAbort(PetscObjectComm((PetscObject)work_), VecNorm(work_, NORM_2, &step));
  if (galerkin_) return 8.0 * PETSC_MACHINE_EPSILON * (delta_g_norm_ + product_norm_) * step;
  return level_.evaluation_error() + 8.0 * PETSC_MACHINE_EPSILON * delta_g_norm_ * step;
}

PetscErrorCode CoarseLevelModel::hessian(Vec x, Mat H) {
  PetscFunctionBeginUser;
  if (!galerkin_) {
    PetscCall(level_.hessian(x, H));
    PetscFunctionReturn(0);
  }
  // H may hold the level's own Hessian (the full-multigrid start) where G has no entry.
  PetscCall(MatZeroEntries(H));
  PetscCall(MatCopy(galerkin_, H, SUBSET_NONZERO_PATTERN));
  PetscFunctionReturn(0);
}

PetscErrorCode CoarseLevelModel::objective(Vec x, PetscReal* h, Vec g) {
  PetscFunctionBeginUser;
  if (galerkin_) {  // ⟨r, w⟩ + ½ wᵀGw and r + Gw, w = x − x₀
    PetscCall(VecWAXPY(work_, -1.0, x0_, x));
    PetscCall(MatMult(galerkin_, work_, product_));
    PetscReal wr, wgw;  // one reduction for both dots and the norm
    PetscCall(VecDotBegin(work_, delta_g_, &wr));
    PetscCall(VecDotBegin(work_, product_, &wgw));
    PetscCall(VecNormBegin(product_, NORM_2, &product_norm_));
    PetscCall(VecDotEnd(work_, delta_g_, &wr));
    PetscCall(VecDotEnd(work_, product_, &wgw));
    PetscCall(VecNormEnd(product_, NORM_2, &product_norm_));
    *h = wr + 0.5 * wgw;
    if (g) PetscCall(VecWAXPY(g, 1.0, delta_g_, product_));
    PetscFunctionReturn(0);
  }
  PetscCall(level_.objective(x, h, g));
  PetscCall(VecWAXPY(work_, -1.0, x0_, x));  // x − x₀
  PetscReal coupling;
  PetscCall(VecDot(delta_g_, work_, &coupling));
  *h += coupling;
  if (g) PetscCall(VecAXPY(g, 1.0, delta_g_));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
