// The graphics community's baselines of paper §7.4.1, as TAO types:
//
//   -tao_type dampednewton   Newton's method with a fixed step x ← x − α H⁻¹∇f, α = 0.3
//                            (-tao_dampednewton_alpha), no line search or trust region: no
//                            convergence control.
//   -tao_type linearized     the "linearized equation" (Baraff & Witkin): a single Newton step
//                            x₁ = x₀ − H(x₀)⁻¹∇f(x₀) per time step. It counts as converged only if
//                            ∇f(x₁) meets TAO's tolerances; otherwise DIVERGED_MAXITS.
//
// The Newton direction comes from a direct solve (options prefix tao_dampednewton_ or
// tao_linearized_; default LU by MUMPS). A non-finite energy or gradient ends the solve with
// DIVERGED_NAN instead of propagating NaN.
#include <petsc/private/taoimpl.h>

#include <cmath>

#include "mlshell/trust_region.hpp"
#include "tao_registration.hpp"

namespace mlshell {

namespace {

struct NewtonContext {
  bool single_step = false;
  PetscReal alpha = 0.3;
  KSP ksp = nullptr;
  Vec direction = nullptr;
};

PetscErrorCode setup(Tao tao) {
  auto* ctx = static_cast<NewtonContext*>(tao->data);
  PetscFunctionBeginUser;
  if (!tao->gradient) PetscCall(VecDuplicate(tao->solution, &tao->gradient));
  if (!ctx->direction) PetscCall(VecDuplicate(tao->solution, &ctx->direction));
  PetscFunctionReturn(0);
}

PetscErrorCode solve(Tao tao) {
  auto* ctx = static_cast<NewtonContext*>(tao->data);
  PetscFunctionBeginUser;
  Vec x = tao->solution, g = tao->gradient, p = ctx->direction;
  PetscReal f, gnorm;
  PetscCall(TaoComputeObjectiveAndGradient(tao, x, &f, g));
  PetscCall(VecNorm(g, NORM_2, &gnorm));
  tao->reason = TAO_CONTINUE_ITERATING;
  PetscCall(TaoLogConvergenceHistory(tao, f, gnorm, 0.0, tao->ksp_its));
  PetscCall(TaoMonitor(tao, tao->niter, f, gnorm, 0.0, 0.0));
  PetscCall((*tao->ops->convergencetest)(tao, tao->cnvP));
  const PetscReal step = ctx->single_step ? 1.0 : ctx->alpha;
  while (tao->reason == TAO_CONTINUE_ITERATING) {
    PetscCall(TaoComputeHessian(tao, x, tao->hessian, tao->hessian_pre));
    PetscCall(KSPSetOperators(ctx->ksp, tao->hessian, tao->hessian_pre));
    PetscCall(KSPSolve(ctx->ksp, g, p));
    KSPConvergedReason ksp_reason;
    PetscCall(KSPGetConvergedReason(ctx->ksp, &ksp_reason));
    if (ksp_reason < 0) {
      tao->reason = TAO_DIVERGED_LS_FAILURE;  // no Newton direction (singular Hessian)
      break;
    }
    PetscCall(VecAXPY(x, -step, p));
    ++tao->niter;
    PetscCall(TaoComputeObjectiveAndGradient(tao, x, &f, g));
    PetscCall(VecNorm(g, NORM_2, &gnorm));
    if (!std::isfinite(f) || !std::isfinite(gnorm)) {
      tao->reason = TAO_DIVERGED_NAN;
      break;
    }
    PetscCall(TaoLogConvergenceHistory(tao, f, gnorm, 0.0, tao->ksp_its));
    PetscCall(TaoMonitor(tao, tao->niter, f, gnorm, 0.0, step));
    PetscCall((*tao->ops->convergencetest)(tao, tao->cnvP));
    if (ctx->single_step && tao->reason == TAO_CONTINUE_ITERATING)
      tao->reason = TAO_DIVERGED_MAXITS;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode set_from_options(Tao tao, PetscOptionItems* PetscOptionsObject) {
  auto* ctx = static_cast<NewtonContext*>(tao->data);
  PetscFunctionBeginUser;
  if (!ctx->single_step) {
    PetscOptionsHeadBegin(PetscOptionsObject, "Damped Newton (fixed step, no convergence control)");
    PetscCall(PetscOptionsReal("-tao_dampednewton_alpha", "step length", "", ctx->alpha,
                               &ctx->alpha, nullptr));
    PetscOptionsHeadEnd();
    PetscCheck(ctx->alpha > 0 && ctx->alpha <= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "-tao_dampednewton_alpha must be in (0, 1], got %g", (double)ctx->alpha);
  }
  PetscCall(KSPSetFromOptions(ctx->ksp));
  PetscFunctionReturn(0);
}

PetscErrorCode view(Tao tao, PetscViewer viewer) {
  auto* ctx = static_cast<NewtonContext*>(tao->data);
  PetscFunctionBeginUser;
  if (ctx->single_step)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  linearized equation: one Newton step per solve\n"));
  else
    PetscCall(PetscViewerASCIIPrintf(
        viewer, "  damped Newton: fixed step %g, no convergence control\n", (double)ctx->alpha));
  PetscCall(KSPView(ctx->ksp, viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode destroy(Tao tao) {
  auto* ctx = static_cast<NewtonContext*>(tao->data);
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&ctx->ksp));
  PetscCall(VecDestroy(&ctx->direction));
  delete ctx;
  tao->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode create(Tao tao, bool single_step) {
  PetscFunctionBeginUser;
  auto* ctx = new NewtonContext();
  ctx->single_step = single_step;
  tao->data = ctx;
  tao->ops->setup = setup;
  tao->ops->solve = solve;
  tao->ops->setfromoptions = set_from_options;
  tao->ops->view = view;
  tao->ops->destroy = destroy;
  PetscCall(
      create_direct_ksp(tao, single_step ? "tao_linearized_" : "tao_dampednewton_", &ctx->ksp));
  PetscFunctionReturn(0);
}

PetscErrorCode create_damped(Tao tao) { return create(tao, false); }
PetscErrorCode create_linearized(Tao tao) { return create(tao, true); }

}  // namespace

PetscErrorCode create_direct_ksp(Tao tao, const char* prefix, KSP* ksp) {
  PetscFunctionBeginUser;
  const char* tao_prefix = nullptr;
  PetscCall(TaoGetOptionsPrefix(tao, &tao_prefix));
  PetscCall(KSPCreate(PetscObjectComm(reinterpret_cast<PetscObject>(tao)), ksp));
  PetscCall(KSPSetOptionsPrefix(*ksp, tao_prefix));
  PetscCall(KSPAppendOptionsPrefix(*ksp, prefix));
  PetscCall(KSPSetType(*ksp, KSPPREONLY));
  PC pc;
  PetscCall(KSPGetPC(*ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscFunctionReturn(0);
}

PetscErrorCode register_newton_baseline_tao_types() {
  static bool registered = false;
  PetscFunctionBeginUser;
  if (!registered) {
    PetscCall(TaoRegister("dampednewton", create_damped));
    PetscCall(TaoRegister("linearized", create_linearized));
  }
  registered = true;
  PetscFunctionReturn(0);
}

}  // namespace mlshell
