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
// Dogleg factorisation). Stopping: TAO's tolerances (-tao_gatol ...), plus StoppingRule
// (local_trust_region.hpp): the second part of eq. (7.1), relative (-tao_tr_stagnation 1e-12),
// and the radius collapsing below -tao_tr_min_radius (1e-14 · max(1, ‖x‖)). Each is convergence
// (CONVERGED_STEPTOL; at the limiting accuracy, CONVERGED_LIMITING_ACCURACY) if ‖g‖ is within
// -tao_tr_limiting_factor (100) of the gradient tolerance, and a failure otherwise
// (DIVERGED_STAGNATION; DIVERGED_TR_REDUCTION).
#include <petsc/private/taoimpl.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "mlshell/local_trust_region.hpp"
#include "mlshell/trust_region.hpp"
#include "mlshell/vertex_patch_pc.hpp"
#include "tao_objective.hpp"
#include "tao_registration.hpp"

namespace mlshell {

namespace {

struct TrContext {
  PetscInt qp = 0;  // 0 dogleg, 1 stcg
  PetscInt stcg_max_it = 10;
  PetscReal delta0 = 1.0;
  TrustRegionParameters params;
  StoppingRule stopping;
  bool limiting = false;  // the last solve ended at the limiting accuracy
  Objective* error_source = nullptr;
  std::unique_ptr<TaoObjective> objective;
  std::unique_ptr<LocalTrustRegion> tr;
  TrustRegionStatistics stats;
};

const char* const kQpNames[] = {"dogleg", "stcg", "TrQp", "TR_QP_", nullptr};

PetscErrorCode setup(Tao tao) {
  auto* ctx = static_cast<TrContext*>(tao->data);
  PetscFunctionBeginUser;
  if (!tao->gradient) PetscCall(VecDuplicate(tao->solution, &tao->gradient));
  if (!ctx->tr) {
    const char* prefix = nullptr;
    PetscCall(TaoGetOptionsPrefix(tao, &prefix));
    const std::string p = prefix ? prefix : "";
    MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(tao));
    std::unique_ptr<TrustRegionQp> qp;
    if (ctx->qp == 0)
      qp = std::make_unique<DoglegQp>(comm, p + "tao_tr_dogleg_");
    else
      qp = std::make_unique<SteihaugTointQp>(comm, p + "tao_tr_stcg_",
                                             static_cast<int>(ctx->stcg_max_it));
    ctx->objective = std::make_unique<TaoObjective>(tao, ctx->error_source);
    ctx->tr = std::make_unique<LocalTrustRegion>(*ctx->objective, tao->solution, tao->hessian,
                                                 std::move(qp));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode solve(Tao tao) {
  auto* ctx = static_cast<TrContext*>(tao->data);
  LocalTrustRegion& tr = *ctx->tr;
  PetscFunctionBeginUser;
  tr.reset_counters();
  PetscReal delta = ctx->delta0, xnorm;
  PetscCall(tr.start(tao->solution));
  const PetscReal g0 = tr.gradient_norm();
  ctx->limiting = false;
  ctx->stopping.reset();
  tao->reason = TAO_CONTINUE_ITERATING;
  if (!tr.finite()) {  // nothing to iterate on: say so instead of producing NaN
    tao->reason = TAO_DIVERGED_NAN;
    tao->fc = tr.value();
    tao->residual = tr.gradient_norm();
    PetscFunctionReturn(0);
  }
  PetscCall(TaoLogConvergenceHistory(tao, tr.value(), tr.gradient_norm(), 0.0, tao->ksp_its));
  PetscCall(TaoMonitor(tao, tao->niter, tr.value(), tr.gradient_norm(), 0.0, delta));
  PetscCall((*tao->ops->convergencetest)(tao, tao->cnvP));
  while (tao->reason == TAO_CONTINUE_ITERATING) {
    PetscCall(VecNorm(tr.solution(), NORM_2, &xnorm));
    if (ctx->stopping.collapsed(delta, xnorm)) {
      ctx->stopping.end_collapsed(tao, tr.gradient_norm(), g0, &ctx->limiting);
      break;
    }
    TrustRegionIteration it;
    const PetscReal f_before = tr.value();
    PetscCall(tr.iterate(ctx->params, &delta, &it));
    tao->ksp_its += it.qp.iterations;
    tao->ksp_tot_its += it.qp.iterations;
    ++tao->niter;
    PetscCall(VecCopy(tr.solution(), tao->solution));
    PetscCall(VecCopy(tr.gradient(), tao->gradient));
    PetscCall(TaoLogConvergenceHistory(tao, tr.value(), tr.gradient_norm(), 0.0, tao->ksp_its));
    PetscCall(TaoMonitor(tao, tao->niter, tr.value(), tr.gradient_norm(), 0.0, delta));
    PetscCall((*tao->ops->convergencetest)(tao, tao->cnvP));
    // Eq. (7.1), second part: Newton-like regime and no more progress in floating point.
    if (tao->reason == TAO_CONTINUE_ITERATING && it.accepted) {
      PetscCall(VecNorm(tr.solution(), NORM_2, &xnorm));
      if (ctx->stopping.stagnated(delta, it.decrease, tr.value(), it.step_norm, xnorm,
                                  tr.gradient_norm()))
        ctx->stopping.end_stagnated(tao, tr.gradient_norm(), g0);
    }
    if (tao->reason == TAO_CONTINUE_ITERATING &&
        ctx->stopping.at_floor(tao, f_before - tr.value(), tr.objective().evaluation_error(),
                               tr.gradient_norm(), g0))
      ctx->stopping.end_at_floor(tao, &ctx->limiting);
  }
  const TrustRegionCounters& c = tr.counters();
  ctx->stats = TrustRegionStatistics{c.accepted, c.qp_solves, c.objectives, c.hessians};
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
  PetscCall(trust_region_parameter_options(PetscOptionsObject, "-tao_tr_", &ctx->params));
  PetscCall(ctx->stopping.options(PetscOptionsObject, "-tao_tr_"));
  PetscOptionsHeadEnd();
  PetscCall(ctx->params.validate(PetscObjectComm((PetscObject)tao), "-tao_tr_"));
  PetscCheck(ctx->delta0 > 0, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_tr_delta0: must be positive, got %g", (double)ctx->delta0);
  PetscFunctionReturn(0);
}

PetscErrorCode view(Tao tao, PetscViewer viewer) {
  auto* ctx = static_cast<TrContext*>(tao->data);
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(
      viewer, "  Local_TR (Alg. 4.1): QP %s%s, delta0 %g, eta1 %g, eta2 %g, gamma1 %g, gamma2 %g\n",
      kQpNames[ctx->qp], ctx->qp == 1 ? " (see -tao_tr_stcg_max_it)" : "", (double)ctx->delta0,
      (double)ctx->params.eta1, (double)ctx->params.eta2, (double)ctx->params.gamma1,
      (double)ctx->params.gamma2));
  PetscCall(PetscViewerASCIIPrintf(
      viewer, "  accepted steps %ld, QP solves %ld, objective evaluations %ld, Hessians %ld\n",
      ctx->stats.accepted, ctx->stats.qp_solves, ctx->stats.objectives, ctx->stats.hessians));
  PetscFunctionReturn(0);
}

PetscErrorCode destroy(Tao tao) {
  auto* ctx = static_cast<TrContext*>(tao->data);
  PetscFunctionBeginUser;
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
  if (!registered) {
    PetscCall(TaoRegister("tr", create));
    PetscCall(register_rmtr_tao_type());
    PetscCall(register_vertex_patch_pc());
  }
  registered = true;
  PetscFunctionReturn(0);
}

std::string trust_region_converged_reason(Tao tao) {
  TaoType type;
  TaoGetType(tao, &type);
  const std::string t = type ? type : "";
  bool limiting = false;
  if (t == "tr") limiting = static_cast<TrContext*>(tao->data)->limiting;
  if (t == "rmtr") limiting = rmtr_reached_limiting_accuracy(tao);
  if (t == "pnewton") limiting = projected_newton_reached_limiting_accuracy(tao);
  if (limiting) return "CONVERGED_LIMITING_ACCURACY";
  TaoConvergedReason reason;
  TaoGetConvergedReason(tao, &reason);
  if (reason == TAO_DIVERGED_USER && (t == "tr" || t == "rmtr")) return "DIVERGED_STAGNATION";
  return TaoConvergedReasons[reason];
}

PetscErrorCode trust_region_set_error_source(Tao tao, Objective* source) {
  PetscFunctionBeginUser;
  TaoType type;
  PetscCall(TaoGetType(tao, &type));
  const std::string t = type ? type : "";
  if (t == "tr") static_cast<TrContext*>(tao->data)->error_source = source;
  if (t == "rmtr") PetscCall(rmtr_set_error_source(tao, source));
  if (t == "pnewton") PetscCall(projected_newton_set_source(tao, source));
  PetscFunctionReturn(0);
}

PetscErrorCode trust_region_statistics(Tao tao, TrustRegionStatistics* stats) {
  PetscFunctionBeginUser;
  PetscCall(require_tao_type(tao, "tr"));
  *stats = static_cast<TrContext*>(tao->data)->stats;
  PetscFunctionReturn(0);
}

}  // namespace mlshell
