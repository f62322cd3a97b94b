// Algorithm 1 of paper 2 (see proxy_step.hpp).
#include "mlshell/proxy_step.hpp"

#include <algorithm>
#include <cmath>

namespace mlshell {

namespace {
/// Armijo's sufficient-decrease constant of the backtracking line search.
constexpr double kArmijo = 1e-4;
}  // namespace

ProxyNewton::ProxyNewton(Objective& objective, Mat H, NewtonMatrix newton_matrix, Vec like)
    : objective_(objective), H_(H), newton_matrix_(std::move(newton_matrix)) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(like));
  PetscCallAbort(comm, VecDuplicate(like, &g_));
  PetscCallAbort(comm, VecDuplicate(like, &d_));
  PetscCallAbort(comm, VecDuplicate(like, &trial_));
  PetscCallAbort(comm, KSPCreate(comm, &ksp_));
  PetscCallAbort(comm, KSPSetOptionsPrefix(ksp_, "mlshell_preview_"));
  PetscCallAbort(comm, KSPSetType(ksp_, KSPPREONLY));
  PC pc;
  PetscCallAbort(comm, KSPGetPC(ksp_, &pc));
  PetscCallAbort(comm, PCSetType(pc, PCLU));
  PetscCallAbort(comm, PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCallAbort(comm, KSPSetFromOptions(ksp_));
}

ProxyNewton::~ProxyNewton() {
  KSPDestroy(&ksp_);
  VecDestroy(&g_);
  VecDestroy(&d_);
  VecDestroy(&trial_);
}

PetscErrorCode ProxyNewton::step(Vec x, const ProxyStepSettings& settings,
                                 ProxyStepReport* report) {
  PetscFunctionBeginUser;
  *report = ProxyStepReport{};
  PetscReal f;
  PetscCall(objective_.objective(x, &f, g_));
  PetscReal gnorm;
  PetscCall(VecNorm(g_, NORM_2, &gnorm));
  report->energy = f;
  report->gradient_norm = gnorm;
  if (!std::isfinite(f) || !std::isfinite(gnorm)) {
    report->stop = "NONFINITE";
    PetscFunctionReturn(0);
  }
  report->stop = "MAX_ITERATIONS";
  while (report->iterations < settings.max_iterations) {
    PetscCall(newton_matrix_(x, H_));
    PetscCall(KSPSetOperators(ksp_, H_, H_));
    PetscCall(KSPSolve(ksp_, g_, d_));
    KSPConvergedReason reason;
    PetscCall(KSPGetConvergedReason(ksp_, &reason));
    PetscInt its;
    PetscCall(KSPGetIterationNumber(ksp_, &its));
    report->linear_iterations += static_cast<int>(its);
    PetscCall(VecScale(d_, -1.0));
    PetscReal dnorm, slope;
    PetscCall(VecNorm(d_, NORM_2, &dnorm));
    PetscCall(VecDot(g_, d_, &slope));
    report->step_norm = dnorm;
    // A failed factorisation, or a direction that does not descend (a Newton matrix that is not
    // positive definite), ends the step: the caller reports it.
    if (reason < 0 || !std::isfinite(dnorm) || (dnorm > 0 && !(slope < 0))) {
      report->stop = "LINEAR_SOLVE_FAILED";
      break;
    }
    if (dnorm < settings.tolerance) {
      report->stop = "STEP_NORM";
      break;
    }
    PetscReal alpha = 1.0;
    PetscCall(objective_.max_step(x, d_, &alpha));
    alpha = std::min<PetscReal>(1.0, alpha);
    PetscReal trial_f = INFINITY;
    for (; alpha >= settings.min_step; alpha *= 0.5) {
      PetscCall(VecWAXPY(trial_, alpha, d_, x));
      PetscCall(objective_.objective(trial_, &trial_f, nullptr));
      if (std::isfinite(trial_f) && trial_f <= f + kArmijo * alpha * slope) break;
    }
    report->alpha = alpha;
    if (alpha < settings.min_step) {
      report->stop = "LINE_SEARCH";
      break;
    }
    PetscCall(VecCopy(trial_, x));
    PetscCall(objective_.accepted(x));
    ++report->iterations;
    PetscCall(objective_.objective(x, &f, g_));
    PetscCall(VecNorm(g_, NORM_2, &gnorm));
    report->energy = f;
    report->gradient_norm = gnorm;
    if (!std::isfinite(f) || !std::isfinite(gnorm)) {  // the line search saw f, not ∇F
      report->stop = "NONFINITE";
      break;
    }
  }
  report->equilibrium = report->iterations == 0 && report->stop != "LINEAR_SOLVE_FAILED" &&
                        report->stop != "NONFINITE";
  PetscFunctionReturn(0);
}

}  // namespace mlshell
