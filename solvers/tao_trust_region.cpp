// Local_TR (paper Alg. 4.1) as the TAO type "tr": a trust-region method whose subproblem is
// solved by Dogleg with a sparse direct factorisation or by Steihaug–Toint CG.
//
//   -tao_type tr -tao_tr_qp dogleg|stcg -tao_tr_stcg_max_it 10 -tao_tr_delta0 1
//   -tao_tr_eta1 0.1 -tao_tr_eta2 0.75 -tao_tr_gamma1 0.5 -tao_tr_gamma2 2      (paper Table 2)
//   Dogleg factorisation options: -tao_tr_dogleg_pc_type cholesky
//                                 -tao_tr_dogleg_pc_factor_mat_solver_type mumps
//   STCG options: -tao_tr_stcg_ksp_..., -tao_tr_stcg_pc_type ...
//
// A trial point x + s is accepted when ρ = (f(x) − f(x+s)) / (m(0) − m(s)) > η₁; derivatives are
// reassembled only after an accepted step, so a rejected step reuses the Hessian (and the
// Dogleg factorisation). Stopping: TAO's tolerances (-tao_gatol ...), plus the second part of
// eq. (7.1): |Δf| or ‖s‖ below -tao_tr_stagnation (1e-12) while Δ > 1e15; the radius shrinking
// below -tao_tr_min_radius (1e-14 · max(1, ‖x‖)) ends the solve with DIVERGED_TR_REDUCTION.
#include <petsc/private/taoimpl.h>

#include <cmath>
#include <memory>
#include <string>

#include "mlshell/trust_region.hpp"
#include "mlshell/trust_region_qp.hpp"

namespace mlshell {

namespace {

struct TrContext {
  PetscInt qp = 0;  // 0 dogleg, 1 stcg
  PetscInt stcg_max_it = 10;
  PetscReal delta0 = 1.0, eta1 = 0.1, eta2 = 0.75, gamma1 = 0.5, gamma2 = 2.0;
  PetscReal stagnation = 1e-12, min_radius = 1e-14;
  std::unique_ptr<TrustRegionQp> solver;
  Vec trial = nullptr, step = nullptr;
  TrustRegionStatistics stats;
};

const char* const kQpNames[] = {"dogleg", "stcg", "TrQp", "TR_QP_", nullptr};

PetscErrorCode setup(Tao tao) {
  auto* ctx = static_cast<TrContext*>(tao->data);
  PetscFunctionBeginUser;
  if (!tao->gradient) PetscCall(VecDuplicate(tao->solution, &tao->gradient));
  if (!ctx->trial) PetscCall(VecDuplicate(tao->solution, &ctx->trial));
  if (!ctx->step) PetscCall(VecDuplicate(tao->solution, &ctx->step));
  if (!ctx->solver) {
    const char* prefix = nullptr;
    PetscCall(TaoGetOptionsPrefix(tao, &prefix));
    const std::string p = prefix ? prefix : "";
    MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(tao));
    if (ctx->qp == 0)
      ctx->solver = std::make_unique<DoglegQp>(comm, p + "tao_tr_dogleg_");
    else
      ctx->solver = std::make_unique<SteihaugTointQp>(comm, p + "tao_tr_stcg_",
                                                      static_cast<int>(ctx->stcg_max_it));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode solve(Tao tao) {
  auto* ctx = static_cast<TrContext*>(tao->data);
  PetscFunctionBeginUser;
  ctx->stats = TrustRegionStatistics{};
  Vec x = tao->solution, g = tao->gradient, s = ctx->step, xt = ctx->trial;
  PetscReal f, gnorm, delta = ctx->delta0, xnorm;
  PetscCall(TaoComputeObjectiveAndGradient(tao, x, &f, g));
  PetscCall(VecNorm(g, NORM_2, &gnorm));
  PetscCheck(std::isfinite(f) && std::isfinite(gnorm), PetscObjectComm((PetscObject)tao),
             PETSC_ERR_USER, "tr: the objective or gradient is not finite at the initial point");
  PetscCall(TaoComputeHessian(tao, x, tao->hessian, tao->hessian_pre));
  ++ctx->stats.hessians;
  PetscCall(ctx->solver->set_operator(tao->hessian));
  tao->reason = TAO_CONTINUE_ITERATING;
  PetscCall(TaoLogConvergenceHistory(tao, f, gnorm, 0.0, tao->ksp_its));
  PetscCall(TaoMonitor(tao, tao->niter, f, gnorm, 0.0, delta));
  PetscCall((*tao->ops->convergencetest)(tao, tao->cnvP));
  while (tao->reason == TAO_CONTINUE_ITERATING) {
    PetscCall(VecNorm(x, NORM_2, &xnorm));
    if (delta < ctx->min_radius * std::max<PetscReal>(1.0, xnorm)) {
      tao->reason = TAO_DIVERGED_TR_REDUCTION;
      break;
    }
    QpResult qp;
    PetscCall(ctx->solver->solve(g, delta, s, qp));
    ++ctx->stats.qp_solves;
    tao->ksp_its += qp.iterations;
    tao->ksp_tot_its += qp.iterations;
    PetscReal ft = PETSC_INFINITY, rho = -PETSC_INFINITY;
    if (qp.model_decrease > 0.0 && std::isfinite(qp.model_decrease)) {
      PetscCall(VecWAXPY(xt, 1.0, s, x));
      PetscCall(TaoComputeObjective(tao, xt, &ft));
      ++ctx->stats.objectives;
      if (std::isfinite(ft)) rho = (f - ft) / qp.model_decrease;
    }
    ++tao->niter;
    const PetscReal f_old = f;
    if (rho > ctx->eta1) {  // accept; reassemble derivatives
      PetscCall(VecCopy(xt, x));
      PetscCall(TaoComputeObjectiveAndGradient(tao, x, &f, g));
      PetscCall(VecNorm(g, NORM_2, &gnorm));
      PetscCall(TaoComputeHessian(tao, x, tao->hessian, tao->hessian_pre));
      ++ctx->stats.hessians;
      ++ctx->stats.accepted;
      PetscCall(ctx->solver->set_operator(tao->hessian));
    }
    // Radius update (Table 2): shrink on poor agreement, expand on very good agreement at the
    // boundary of the region.
    if (rho < ctx->eta1)
      delta = ctx->gamma1 * std::min(delta, qp.step_norm > 0 ? qp.step_norm : delta);
    else if (rho > ctx->eta2 && qp.step_norm >= 0.99 * delta)
      delta = ctx->gamma2 * delta;
    PetscCall(TaoLogConvergenceHistory(tao, f, gnorm, 0.0, tao->ksp_its));
    PetscCall(TaoMonitor(tao, tao->niter, f, gnorm, 0.0, delta));
    PetscCall((*tao->ops->convergencetest)(tao, tao->cnvP));
    // Eq. (7.1), second part: Newton-like regime and no more progress in floating point.
    if (tao->reason == TAO_CONTINUE_ITERATING && rho > ctx->eta1 && delta > 1e15 &&
        (std::abs(f_old - f) < ctx->stagnation || qp.step_norm < ctx->stagnation))
      tao->reason = TAO_CONVERGED_STEPTOL;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode set_from_options(Tao tao, PetscOptionItems* PetscOptionsObject) {
  auto* ctx = static_cast<TrContext*>(tao->data);
  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Trust region (Local_TR, paper Alg. 4.1)");
  PetscCall(PetscOptionsEnum("-tao_tr_qp", "subproblem solver", "", kQpNames,
                             static_cast<PetscEnum>(ctx->qp),
                             reinterpret_cast<PetscEnum*>(&ctx->qp), nullptr));
  PetscCall(PetscOptionsInt("-tao_tr_stcg_max_it", "STCG iterations per subproblem", "",
                            ctx->stcg_max_it, &ctx->stcg_max_it, nullptr));
  PetscCall(
      PetscOptionsReal("-tao_tr_delta0", "initial radius", "", ctx->delta0, &ctx->delta0, nullptr));
  PetscCall(
      PetscOptionsReal("-tao_tr_eta1", "acceptance threshold", "", ctx->eta1, &ctx->eta1, nullptr));
  PetscCall(
      PetscOptionsReal("-tao_tr_eta2", "expansion threshold", "", ctx->eta2, &ctx->eta2, nullptr));
  PetscCall(
      PetscOptionsReal("-tao_tr_gamma1", "shrink factor", "", ctx->gamma1, &ctx->gamma1, nullptr));
  PetscCall(PetscOptionsReal("-tao_tr_gamma2", "expansion factor", "", ctx->gamma2, &ctx->gamma2,
                             nullptr));
  PetscCall(PetscOptionsReal("-tao_tr_stagnation", "eq. (7.1) floor on |df| and |s|", "",
                             ctx->stagnation, &ctx->stagnation, nullptr));
  PetscCall(PetscOptionsReal("-tao_tr_min_radius", "relative radius at which the solve stops", "",
                             ctx->min_radius, &ctx->min_radius, nullptr));
  PetscOptionsHeadEnd();
  PetscCheck(ctx->eta1 > 0 && ctx->eta1 < ctx->eta2 && ctx->eta2 < 1, PETSC_COMM_SELF,
             PETSC_ERR_ARG_OUTOFRANGE, "tr: need 0 < eta1 < eta2 < 1, got %g and %g",
             (double)ctx->eta1, (double)ctx->eta2);
  PetscCheck(ctx->gamma1 > 0 && ctx->gamma1 < 1 && ctx->gamma2 > 1 && ctx->delta0 > 0,
             PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
             "tr: need 0 < gamma1 < 1 < gamma2 and delta0 > 0");
  PetscFunctionReturn(0);
}

PetscErrorCode view(Tao tao, PetscViewer viewer) {
  auto* ctx = static_cast<TrContext*>(tao->data);
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(
      viewer, "  Local_TR (Alg. 4.1): QP %s%s, delta0 %g, eta1 %g, eta2 %g, gamma1 %g, gamma2 %g\n",
      kQpNames[ctx->qp], ctx->qp == 1 ? " (see -tao_tr_stcg_max_it)" : "", (double)ctx->delta0,
      (double)ctx->eta1, (double)ctx->eta2, (double)ctx->gamma1, (double)ctx->gamma2));
  PetscCall(PetscViewerASCIIPrintf(
      viewer, "  accepted steps %ld, QP solves %ld, objective evaluations %ld, Hessians %ld\n",
      ctx->stats.accepted, ctx->stats.qp_solves, ctx->stats.objectives, ctx->stats.hessians));
  PetscFunctionReturn(0);
}

PetscErrorCode destroy(Tao tao) {
  auto* ctx = static_cast<TrContext*>(tao->data);
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&ctx->trial));
  PetscCall(VecDestroy(&ctx->step));
  delete ctx;
  tao->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode create(Tao tao) {
  PetscFunctionBeginUser;
  tao->data = new TrContext();
  tao->ops->setup = setup;
  tao->ops->solve = solve;
  tao->ops->setfromoptions = set_from_options;
  tao->ops->view = view;
  tao->ops->destroy = destroy;
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode register_trust_region_tao_types() {
  static bool registered = false;
  PetscFunctionBeginUser;
  if (!registered) PetscCall(TaoRegister("tr", create));
  registered = true;
  PetscFunctionReturn(0);
}

PetscErrorCode trust_region_statistics(Tao tao, TrustRegionStatistics* stats) {
  PetscBool is_tr;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(tao), "tr", &is_tr));
  PetscCheck(is_tr, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONG, "not a tr solver");
  *stats = static_cast<TrContext*>(tao->data)->stats;
  PetscFunctionReturn(0);
}

}  // namespace mlshell
