// Projected Newton with a backtracking line search (paper 2 §4.5; Teran et al. 2005), as the
// TAO type "pnewton":
//   H_psd p = −∇f(x)          H_psd: the Hessian with every non-convex element Hessian
//                             projected onto the PSD cone (-mlshell_hessian_psd, on by default
//                             with this type), factorised directly (prefix tao_pnewton_,
//                             default LU by MUMPS)
//   α₀ = min(1, max_step(x, p))   the objective's admissible step (CCD for contact; 1 today)
//   α ← α/2 until f(x + αp) ≤ f(x) + c₁ α ∇fᵀp   (Armijo, -tao_pnewton_c1 1e-4)
// A singular or indefinite H (a free rigid motion, pressure terms) is shifted, H + τI with τ
// from 1e-8·max|diag H| growing ×100, until the solve succeeds and p descends.
// Stopping: TAO's tolerances on ‖∇f‖. When the line search finds no decrease above the rounding
// error of f (Objective::evaluation_error), or 20 steps in a row change f by no more than that
// noise while ‖∇f‖ falls by less than 10 % (projected Hessians of compressed, wrinkling
// membranes converge linearly: slow progress is still progress), the solve ends at the limiting
// accuracy
// (CONVERGED_LIMITING_ACCURACY) if ‖∇f‖ is within -tao_pnewton_limiting_factor (100) of the
// gradient tolerance, and with DIVERGED_LS_FAILURE otherwise.
#include <petsc/private/taoimpl.h>

#include <cmath>
#include <memory>

#include "mlshell/trust_region.hpp"
#include "tao_objective.hpp"
#include "tao_registration.hpp"

namespace mlshell {

namespace {

struct ProjectedNewtonContext {
  KSP ksp = nullptr;
  Vec direction = nullptr, trial = nullptr, trial_gradient = nullptr;
  Objective* source = nullptr;  // for step limits, rounding errors and accepted iterates
  PetscReal c1 = 1e-4, limiting_factor = 100.0;
  PetscInt max_halvings = 60;
  static constexpr int kNoiseSteps = 20;         // steps in the noise of f ...
  static constexpr double kNoiseProgress = 0.9;  // ... without ‖∇f‖ falling below this × its start
  bool limiting = false;
};

PetscErrorCode setup(Tao tao) {
  auto* c = static_cast<ProjectedNewtonContext*>(tao->data);
  PetscFunctionBeginUser;
  if (!tao->gradient) PetscCall(VecDuplicate(tao->solution, &tao->gradient));
  if (!c->direction) {
    PetscCall(VecDuplicate(tao->solution, &c->direction));
    PetscCall(VecDuplicate(tao->solution, &c->trial));
    PetscCall(VecDuplicate(tao->solution, &c->trial_gradient));
  }
  PetscFunctionReturn(0);
}

/// p = −H⁻¹g, shifting H until the factorisation succeeds and p is a descent direction.
PetscErrorCode newton_direction(Tao tao, ProjectedNewtonContext& c, Vec g, PetscBool* found) {
  PetscFunctionBeginUser;
  *found = PETSC_FALSE;
  Mat H = tao->hessian;
  PetscReal shift = 0.0, total = 0.0;
  for (int attempt = 0; attempt < 8; ++attempt) {
    if (shift > 0.0) {
      PetscCall(MatShift(H, shift - total));
      total = shift;
    }
    PetscCall(KSPSetOperators(c.ksp, H, H));
    PetscCall(KSPSolve(c.ksp, g, c.direction));
    KSPConvergedReason reason;
    PetscCall(KSPGetConvergedReason(c.ksp, &reason));
    PetscReal slope = 0.0;
    if (reason >= 0) PetscCall(VecDot(g, c.direction, &slope));
    if (reason >= 0 && slope > 0.0 && std::isfinite(slope)) {
      PetscCall(VecScale(c.direction, -1.0));
      *found = PETSC_TRUE;
      break;
    }
    if (shift == 0.0) {
      Vec d;
      PetscReal dmax;
      PetscCall(MatCreateVecs(H, &d, nullptr));
      PetscCall(MatGetDiagonal(H, d));
      PetscCall(VecNorm(d, NORM_INFINITY, &dmax));
      PetscCall(VecDestroy(&d));
      shift = 1e-8 * (dmax > 0.0 ? dmax : 1.0);
    } else {
      shift *= 100.0;
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode solve(Tao tao) {
  auto* c = static_cast<ProjectedNewtonContext*>(tao->data);
  PetscFunctionBeginUser;
  TaoObjective f_obj(tao, c->source);
  Vec x = tao->solution, g = tao->gradient, p = c->direction;
  c->limiting = false;
  PetscReal f, gnorm;
  PetscCall(f_obj.objective(x, &f, g));
  PetscCall(VecNorm(g, NORM_2, &gnorm));
  tao->reason = TAO_CONTINUE_ITERATING;
  PetscCall(TaoLogConvergenceHistory(tao, f, gnorm, 0.0, tao->ksp_its));
  PetscCall(TaoMonitor(tao, tao->niter, f, gnorm, 0.0, 0.0));
  PetscCall((*tao->ops->convergencetest)(tao, tao->cnvP));
  int noise_steps = 0;
  PetscReal noise_start_gnorm = 0.0;
  const auto end_at_floor = [&]() -> PetscErrorCode {
    PetscReal gatol, grtol, gttol;
    PetscFunctionBeginUser;
    PetscCall(TaoGetTolerances(tao, &gatol, &grtol, &gttol));
    c->limiting = gnorm <= c->limiting_factor * gatol;
    tao->reason = c->limiting ? TAO_CONVERGED_USER : TAO_DIVERGED_LS_FAILURE;
    PetscFunctionReturn(0);
  };
  while (tao->reason == TAO_CONTINUE_ITERATING) {
    if (!std::isfinite(f) || !std::isfinite(gnorm)) {
      tao->reason = TAO_DIVERGED_NAN;
      break;
    }
    PetscCall(f_obj.hessian(x, tao->hessian));
    PetscBool found;
    PetscCall(newton_direction(tao, *c, g, &found));
    if (!found) {
      tao->reason = TAO_DIVERGED_LS_FAILURE;
      break;
    }
    PetscReal slope, alpha = 1.0;
    PetscCall(VecDot(g, p, &slope));  // < 0
    PetscCall(f_obj.max_step(x, p, &alpha));
    alpha = std::min<PetscReal>(alpha, 1.0);
    PetscReal ft = PETSC_INFINITY;
    bool accepted = false;
    const PetscReal noise = f_obj.evaluation_error();
    for (PetscInt k = 0; k <= c->max_halvings; ++k, alpha *= 0.5) {
      PetscCall(VecWAXPY(c->trial, alpha, p, x));
      PetscCall(f_obj.objective(c->trial, &ft, c->trial_gradient));
      if (!std::isfinite(ft)) continue;
      if (ft <= f + c->c1 * alpha * slope) {
        accepted = true;
        break;
      }
      // In the noise of f, trust the directional derivative at the trial point.
      if (std::abs(ft - f) <= 10.0 * noise) {
        PetscReal gts;
        PetscCall(VecDot(c->trial_gradient, p, &gts));
        if (gts <= 0.5 * std::abs(slope)) {
          accepted = true;
          break;
        }
      }
      if (alpha * std::abs(slope) < noise) break;  // the model decrease is below the noise
    }
    if (!accepted) {
      PetscCall(end_at_floor());
      break;
    }
    const bool in_noise = std::abs(ft - f) <= 10.0 * noise;
    PetscCall(VecCopy(c->trial, x));
    PetscCall(VecCopy(c->trial_gradient, g));
    f = ft;
    const long revision = f_obj.revision();
    PetscCall(f_obj.accepted(x));
    if (f_obj.revision() != revision) PetscCall(f_obj.objective(x, &f, g));  // contact's κ
    PetscCall(VecNorm(g, NORM_2, &gnorm));
    ++tao->niter;
    PetscInt its;
    PetscCall(KSPGetIterationNumber(c->ksp, &its));
    tao->ksp_its = its;
    tao->ksp_tot_its += its;
    PetscCall(TaoLogConvergenceHistory(tao, f, gnorm, 0.0, tao->ksp_its));
    PetscCall(TaoMonitor(tao, tao->niter, f, gnorm, 0.0, alpha));
    PetscCall((*tao->ops->convergencetest)(tao, tao->cnvP));
    if (tao->reason != TAO_CONTINUE_ITERATING) break;
    if (!in_noise || noise_steps == 0 ||
        gnorm <= ProjectedNewtonContext::kNoiseProgress * noise_start_gnorm) {
      noise_steps = in_noise ? 1 : 0;
      noise_start_gnorm = gnorm;
    } else if (++noise_steps >= ProjectedNewtonContext::kNoiseSteps) {
      PetscCall(end_at_floor());
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode set_from_options(Tao tao, PetscOptionItems* PetscOptionsObject) {
  auto* c = static_cast<ProjectedNewtonContext*>(tao->data);
  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Projected Newton with backtracking line search");
  PetscCall(PetscOptionsReal("-tao_pnewton_c1", "Armijo constant", "", c->c1, &c->c1, nullptr));
  PetscCall(PetscOptionsInt("-tao_pnewton_max_halvings", "line-search halvings per step", "",
                            c->max_halvings, &c->max_halvings, nullptr));
  PetscCall(PetscOptionsReal("-tao_pnewton_limiting_factor",
                             "a failed line search is the limiting accuracy within this factor "
                             "of the gradient tolerance",
                             "", c->limiting_factor, &c->limiting_factor, nullptr));
  PetscOptionsHeadEnd();
  PetscCheck(c->c1 > 0 && c->c1 < 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_pnewton_c1 must be in (0, 1), got %g", (double)c->c1);
  PetscCheck(c->max_halvings >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_pnewton_max_halvings must be >= 1, got %d", (int)c->max_halvings);
  PetscCheck(c->limiting_factor >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_pnewton_limiting_factor must be >= 1, got %g", (double)c->limiting_factor);
  PetscCall(KSPSetFromOptions(c->ksp));
  PetscFunctionReturn(0);
}

PetscErrorCode view(Tao tao, PetscViewer viewer) {
  auto* c = static_cast<ProjectedNewtonContext*>(tao->data);
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  projected Newton, Armijo c1 = %g\n", (double)c->c1));
  PetscCall(KSPView(c->ksp, viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode destroy(Tao tao) {
  auto* c = static_cast<ProjectedNewtonContext*>(tao->data);
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&c->ksp));
  PetscCall(VecDestroy(&c->direction));
  PetscCall(VecDestroy(&c->trial));
  PetscCall(VecDestroy(&c->trial_gradient));
  delete c;
  tao->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode create(Tao tao) {
  PetscFunctionBeginUser;
  auto* c = new ProjectedNewtonContext();
  tao->data = c;
  tao->ops->setup = setup;
  tao->ops->solve = solve;
  tao->ops->setfromoptions = set_from_options;
  tao->ops->view = view;
  tao->ops->destroy = destroy;
  PetscCall(create_direct_ksp(tao, "tao_pnewton_", &c->ksp));
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode register_projected_newton_tao_type() {
  static bool registered = false;
  PetscFunctionBeginUser;
  if (!registered) PetscCall(TaoRegister("pnewton", create));
  registered = true;
  PetscFunctionReturn(0);
}

PetscErrorCode projected_newton_set_source(Tao tao, Objective* source) {
  PetscFunctionBeginUser;
  static_cast<ProjectedNewtonContext*>(tao->data)->source = source;
  PetscFunctionReturn(0);
}

bool projected_newton_reached_limiting_accuracy(Tao tao) {
  return static_cast<ProjectedNewtonContext*>(tao->data)->limiting;
}

}  // namespace mlshell
