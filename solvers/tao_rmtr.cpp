// RMTR, the recursive multilevel trust-region method (paper Alg. 4.2 with the radius update of
// Alg. 4.3), as the TAO type "rmtr".
//
// One iteration of the Tao is one V-cycle. On level l (0 the coarsest, L the finest):
//   1. μ₁ Local_TR pre-smoothing steps on the level model h^l (eq. 4.3; h^L = f^L);
//   2. if l > 0: x₀^{l−1} = P x^l (eq. 4.6), h^{l−1} built with the first-order consistency term
//      so that ∇h^{l−1}(x₀^{l−1}) = R ∇h^l (eq. 4.4–4.5), RMTR on level l−1 with the radius
//      Δ^l bounding its steps in the level norm ‖·‖_{l−1} (eq. 4.8–4.9), and the prolongated
//      correction s = I (x^{l−1} − x₀^{l−1}) (eq. 4.10) accepted if the multilevel ratio
//      ρ = (h^l(x) − h^l(x+s)) / (h^{l−1}(x₀^{l−1}) − h^{l−1}(x^{l−1})) > η₁ (eq. 4.11);
//   3. μ₂ post-smoothing steps.
// The coarsest level takes μ₁ + μ₂ steps (no recursion), with Dogleg and a sparse direct
// factorisation; the other levels smooth with 10 Steihaug–Toint CG iterations (§7.3).
// After every step on a coarse level the radius is capped so that the level's iterates stay
// within the finer radius: with d = ‖x − x₀‖_l, Δ ← min(Δ₊, Δ^{l+1} − d), and the level stops
// when d > (1 − ε^Δ) Δ^{l+1} (Alg. 4.3). A level also stops when ‖∇h^l‖ ≤ ε_g (-tao_gatol).
// Stopping: TAO's tolerances on the finest gradient (eq. 7.1, first part), then StoppingRule
// (local_trust_region.hpp) on the finest level: |Δf| or ‖Δx‖ over a V-cycle below
// -tao_rmtr_stagnation relative to |f| and ‖x‖ while Δ > 1e15, with no V-cycle among the
// last -tao_rmtr_stagnation_window (3) taking ‖g‖ below 0.9 times its lowest before (eq. 7.1,
// second part: CONVERGED_STEPTOL if ‖g‖ is within -tao_rmtr_limiting_factor (100) of the
// tolerance, else DIVERGED_STAGNATION, since V-cycles that converge linearly inflate Δ too), or
// the radius shrinking below -tao_rmtr_min_radius · max(1, ‖x‖): CONVERGED_LIMITING_ACCURACY
// if ‖g‖ is within that factor of the tolerance, else DIVERGED_TR_REDUCTION.
//
// Options (Table 2 defaults):
//   -tao_rmtr_levels <all>           number of levels used (the finest ones of the hierarchy)
//   -tao_rmtr_mu1 1 -tao_rmtr_mu2 1  pre- and post-smoothing steps
//   -tao_rmtr_cycle_type v|w         cycles of a coarse level (above the coarsest) per visit:
//                                    one (V, the paper) or two (W), the second from where the
//                                    first ended, within the same bound on its distance
//   -tao_rmtr_coarse_max_it <μ₁+μ₂>  Local_TR steps on the coarsest level per visit
//   -tao_rmtr_delta0 1 -tao_rmtr_eta1 0.1 -tao_rmtr_eta2 0.75 -tao_rmtr_gamma1 0.5
//   -tao_rmtr_gamma2 2 -tao_rmtr_eps_delta 0.001
//   -tao_rmtr_projection reverse|lsq|restriction   P of eq. (4.6): reverse subdivision Q,
//        least squares (IᵀI)⁻¹Iᵀ, or restriction scaled to preserve constants (diag(R1)⁻¹R)
//   -tao_rmtr_coarse_start projection|iterate   x₀^{l−1} of step 2: the projection above (the
//        paper), or the coarser level's own iterate as its last visit left it (where its
//        correction was accepted, its end point; else its start), projected only on a first
//        visit: the coarse level then models the fine one around a state of its own, which
//        follows the fine iterate's large rotations through the accepted corrections, instead
//        of around a projection of the fine details (full-multigrid starts leave every level
//        its own solution)
//   -tao_rmtr_coarse_model first_order|galerkin   h^{l−1} of step 2: the level's own objective
//        with the first-order consistency term (eq. 4.3, the paper), or the Galerkin model
//        ⟨R∇h^l, w⟩ + ½ wᵀ J_Pᵀ H^l J_P w, w = x − x₀^{l−1}, with H^l the Hessian of the finer
//        level's last subproblem (second order at x₀ whatever the projection gives; the coarse
//        levels never evaluate their energies, CoarseLevelModel)
//   -tao_rmtr_smoother_qp stcg|dogleg   -tao_rmtr_coarse_qp dogleg|stcg
//   -tao_rmtr_coarse_redundant 20000 Dogleg on a coarsest level of at most this many dofs
//                                    factorises it whole on every rank (PC redundant, MUMPS
//                                    Cholesky inside): the same in every run, where MUMPS over
//                                    several ranks varies in the last bits and a hanging cloth's
//                                    path through its V-cycles with it (0: distributed MUMPS;
//                                    -rmtr_coarse_pc_type overrides either)
//   -tao_rmtr_stcg_max_it 10         CG iterations per smoothing step (STCG; Dogleg's inexact
//                                    Newton point with -tao_rmtr_smoother_pc)
//   -tao_rmtr_stcg_target 0.1        STCG stops once its model gradient ‖g + Hs‖ is this fraction
//                                    of -tao_gatol: the model's gradient approximates the next
//                                    iterate's, and a level stops at ‖g‖ ≤ gatol (0: iterate to
//                                    -tao_rmtr_stcg_max_it or the KSP's own tolerances)
//   -tao_rmtr_smoother_pc none       preconditioner of the STCG smoother: none (the paper), or
//                                    vpatch (vertex-patch Schwarz, vertex_patch_pc.hpp), or any PC;
//                                    with Dogleg smoothing, the Newton point comes from CG with
//                                    this PC (at most -tao_rmtr_stcg_max_it iterations, relative
//                                    tolerance -tao_rmtr_newton_rtol 1e-2, H + λI on negative
//                                    curvature; DoglegQp) instead of a factorisation
//   -tao_rmtr_hessian_lag 0          accepted steps a level keeps its Hessian (LocalTrustRegion)
//   -tao_rmtr_fmg_cycles 1000        full-multigrid start: before the first V-cycle, solve each
//                                    coarser level's own problem f^l, coarsest first, from the
//                                    coarser solution prolongated (where that lowers f^l), with
//                                    at most this many V-cycles, to the finest level's tolerances;
//                                    the finest level starts from the prolongated solution if it
//                                    lowers f^L (0: off)
//   -tao_rmtr_fmg_always false       the start before every solve; by default only from the rest
//                                    state x = 0 (a scene's first step), where the iterate says
//                                    nothing about the solution: from a previous step's state it
//                                    can move a folding cloth to another branch
//   -tao_rmtr_retries 0              a rejected smoothing step is retried at once with the
//                                    shrunk radius, up to this many times (0: the paper's one
//                                    Local_TR iteration per smoothing step)
//   -tao_rmtr_subspace 0             after each V-cycle on a level above the coarsest whose
//                                    correction was inside its radius, a trust-region step in
//                                    the span of the correction and m − 1 earlier changes
//                                    (SubspaceAcceleration; 0: off)
//   -tao_rmtr_monitor                one line per V-cycle
//   per-level QP options, PCMG style: -rmtr_levels_<l>_ksp_max_it, -rmtr_levels_<l>_pc_type ...
//   for levels l ≥ 1 and -rmtr_coarse_pc_factor_mat_solver_type mumps ... for level 0.
#include <petsc/private/taoimpl.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "mlshell/coarse_level_model.hpp"
#include "mlshell/local_trust_region.hpp"
#include "mlshell/subspace_acceleration.hpp"
#include "mlshell/trust_region.hpp"
#include "tao_objective.hpp"
#include "tao_registration.hpp"

namespace mlshell {

namespace {

enum Projection { kReverse = 0, kLeastSquares = 1, kRestriction = 2 };
const char* const kProjectionNames[] = {"reverse",    "lsq",         "restriction",
                                        "Projection", "PROJECTION_", nullptr};
const char* const kQpNames[] = {"dogleg", "stcg", "RmtrQp", "RMTR_QP_", nullptr};
enum CycleType { kVCycle = 0, kWCycle = 1 };
const char* const kCycleTypeNames[] = {"v", "w", "CycleType", "CYCLE_", nullptr};
enum CoarseModel { kFirstOrder = 0, kGalerkin = 1 };
enum CoarseStart { kProjected = 0, kIterate = 1 };
const char* const kCoarseStartNames[] = {"projection", "iterate", "CoarseStart", "COARSE_START_",
                                         nullptr};
const char* const kCoarseModelNames[] = {"first_order", "galerkin", "CoarseModel", "COARSE_MODEL_",
                                         nullptr};

struct Level {
  Objective* objective = nullptr;           // h^l
  std::unique_ptr<CoarseLevelModel> model;  // l < L
  Mat H = nullptr;                          // owned for l < L
  Mat galerkin = nullptr;                   // l < L, Galerkin models: J_Pᵀ ∇²h^{l+1} J_P
  std::unique_ptr<LocalTrustRegion> tr;
  std::unique_ptr<SubspaceAcceleration> subspace;  // -tao_rmtr_subspace m > 0
  Vec x0 = nullptr, restricted = nullptr;          // l < L: x₀^l and R ∇h^{l+1}
  Vec correction = nullptr, trial = nullptr;       // l > 0: prolongated correction, x + s
  Vec scratch = nullptr;                           // l < L: x − x₀
  Vec shortened = nullptr;        // l < L: a coarse end point pulled back into the fine radius
  Vec anchor = nullptr;           // l < L, -tao_rmtr_coarse_start iterate: the level's own iterate,
  bool anchored = false;          // once it has one
  long objectives = 0;            // coarse-correction trial points
  bool correction_passed = true;  // l > 0: the last coarse correction was accepted
  RmtrLevelStatistics stats;
};

struct RmtrContext {
  MultilevelObjective* hierarchy = nullptr;
  PetscInt requested_levels = 0, mu1 = 1, mu2 = 1, coarse_max_it = -1, stcg_max_it = 10;
  PetscInt projection = kReverse, smoother_qp = 1, coarse_qp = 0, coarse_model = kFirstOrder;
  PetscInt coarse_start = kProjected, cycle_type = kVCycle;
  char smoother_pc[64] = "none";
  PetscInt hessian_lag = 0, fmg_cycles = 1000, subspace = 0, retries = 0;
  PetscInt coarse_redundant = 20000;  // dofs up to which the coarsest Dogleg gathers its level
  PetscReal delta0 = 1.0, eps_delta = 1e-3;
  PetscReal stcg_target = 0.1;   // STCG stops at ‖g + Hs‖ ≤ stcg_target · gatol
  PetscReal newton_rtol = 1e-2;  // Dogleg's inexact Newton point (smoother_pc set): CG's rtol
  StoppingRule stopping;
  bool limiting = false;  // the last solve ended at the limiting accuracy
  Objective* error_source = nullptr;
  PetscBool monitor = PETSC_FALSE, check_consistency = PETSC_FALSE, fmg_always = PETSC_FALSE;
  TrustRegionParameters params;
  std::unique_ptr<TaoObjective> finest;
  std::vector<Level> levels;
  int offset = 0;  // hierarchy level of RMTR level 0
  long cycle_accepted = 0, cycle_rejected = 0;
  RmtrStatistics stats;
};

int finest(const RmtrContext& c) { return static_cast<int>(c.levels.size()) - 1; }

void destroy_levels(RmtrContext& c) {
  for (Level& lv : c.levels) {
    lv.tr.reset();
    if (&lv != &c.levels.back()) MatDestroy(&lv.H);
    MatDestroy(&lv.galerkin);
    VecDestroy(&lv.x0);
    VecDestroy(&lv.restricted);
    VecDestroy(&lv.correction);
    VecDestroy(&lv.trial);
    VecDestroy(&lv.scratch);
    VecDestroy(&lv.anchor);
    VecDestroy(&lv.shortened);
  }
  c.levels.clear();
}

std::unique_ptr<TrustRegionQp> make_qp(MPI_Comm comm, PetscInt kind, const std::string& prefix,
                                       PetscInt stcg_max_it, const char* pc_type,
                                       PetscReal newton_rtol, bool redundant) {
  if (kind == 0)  // with a preconditioner: the inexact Newton point of preconditioned CG
    return std::make_unique<DoglegQp>(
        comm, prefix, InexactNewton{pc_type, static_cast<int>(stcg_max_it), newton_rtol},
        redundant);
  return std::make_unique<SteihaugTointQp>(comm, prefix, static_cast<int>(stcg_max_it), pc_type);
}

PetscErrorCode setup(Tao tao) {
  auto* c = static_cast<RmtrContext*>(tao->data);
  PetscFunctionBeginUser;
  if (!tao->gradient) PetscCall(VecDuplicate(tao->solution, &tao->gradient));
  if (!c->levels.empty()) PetscFunctionReturn(0);
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(tao));
  const int available = c->hierarchy ? c->hierarchy->num_levels() : 1;
  const int n = c->requested_levels > 0 ? static_cast<int>(c->requested_levels) : available;
  PetscCheck(n <= available, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_levels: %d level(s) requested but the hierarchy has %d (raise the scene's "
             "geometry.refine for more)",
             n, available);
  c->offset = available - n;
  const char* prefix = nullptr;
  PetscCall(TaoGetOptionsPrefix(tao, &prefix));
  const std::string p = prefix ? prefix : "";
  c->finest = std::make_unique<TaoObjective>(tao, c->error_source);
  c->levels.resize(n);
  const int L = n - 1;
  for (int l = 0; l <= L; ++l) {
    Level& lv = c->levels[l];
    const int h = c->offset + l;
    Vec like = tao->solution;
    if (l < L) {
      PetscCall(c->hierarchy->create_vector(h, &lv.x0));
      PetscCall(VecDuplicate(lv.x0, &lv.restricted));
      PetscCall(VecDuplicate(lv.x0, &lv.scratch));
      if (c->coarse_start == kIterate) PetscCall(VecDuplicate(lv.x0, &lv.anchor));
      PetscCall(c->hierarchy->create_hessian(h, &lv.H));
      lv.model = std::make_unique<CoarseLevelModel>(c->hierarchy->level_objective(h));
      lv.objective = lv.model.get();
      like = lv.x0;
    } else {
      lv.H = tao->hessian;
      lv.objective = c->finest.get();
    }
    if (l > 0) {
      PetscCall(VecDuplicate(like, &lv.correction));
      PetscCall(VecDuplicate(like, &lv.trial));
    }
    const std::string qp_prefix =
        l == 0 ? p + "rmtr_coarse_" : p + "rmtr_levels_" + std::to_string(l) + "_";
    PetscCall(VecGetSize(like, &lv.stats.dofs));
    LevelNorm norm;
    if (l < L) {
      MultilevelObjective* hierarchy = c->hierarchy;
      norm = [hierarchy, h](Vec v, PetscReal* r) { return hierarchy->composite_norm(h, v, r); };
    }
    lv.tr = std::make_unique<LocalTrustRegion>(
        *lv.objective, like, lv.H,
        make_qp(comm, l == 0 ? c->coarse_qp : c->smoother_qp, qp_prefix, c->stcg_max_it,
                l == 0 ? PCNONE : c->smoother_pc, c->newton_rtol,
                l == 0 && lv.stats.dofs <= c->coarse_redundant),
        std::move(norm));
    lv.tr->set_hessian_lag(static_cast<int>(c->hessian_lag));
    if (c->subspace > 0 && l > 0)
      lv.subspace = std::make_unique<SubspaceAcceleration>(static_cast<int>(c->subspace));
  }
  PetscFunctionReturn(0);
}

/// Alg. 4.3, second half: caps the radius of level l < L so that its iterates stay within the
/// finer level's radius Δ^{l+1}; sets *delta = 0 when no room is left.
PetscErrorCode cap_radius(RmtrContext& c, int l, PetscReal fine_radius, PetscReal* delta) {
  Level& lv = c.levels[l];
  PetscFunctionBeginUser;
  if (l == finest(c)) PetscFunctionReturn(0);
  PetscCall(VecWAXPY(lv.scratch, -1.0, lv.x0, lv.tr->solution()));
  PetscReal d;
  PetscCall(lv.tr->level_norm(lv.scratch, &d));
  *delta = d > (1.0 - c.eps_delta) * fine_radius ? 0.0 : std::min(*delta, fine_radius - d);
  PetscFunctionReturn(0);
}

/// Up to `steps` Local_TR steps on level l, each retried after a rejection up to c.retries times
/// (-tao_rmtr_retries). Returns false in *go_on when the level is done
/// (gradient below ε_g, or no radius left).
PetscErrorCode smooth(Tao tao, RmtrContext& c, int l, int steps, PetscReal fine_radius,
                      PetscReal* delta, std::vector<long>& successful, bool* go_on) {
  Level& lv = c.levels[l];
  PetscFunctionBeginUser;
  const auto done = [&] { return lv.tr->gradient_norm() <= tao->gatol || *delta <= 0.0; };
  for (PetscInt i = 0, tries = 0; i < steps && !done();) {
    TrustRegionIteration it;
    PetscCall(lv.tr->iterate(c.params, delta, &it));
    tao->ksp_its += it.qp.iterations;
    tao->ksp_tot_its += it.qp.iterations;
    if (it.accepted) ++successful[l];
    PetscCall(cap_radius(c, l, fine_radius, delta));
    // A rejected step is retried at once with the shrunk radius, up to -tao_rmtr_retries times,
    // instead of waiting a whole V-cycle for the next smoothing step.
    if (!it.accepted && tries < c.retries) {
      ++tries;
    } else {
      ++i;
      tries = 0;
    }
  }
  *go_on = !done();
  PetscFunctionReturn(0);
}

/// The transfers between RMTR levels l − 1 and l.
const LevelTransfer& transfer(const RmtrContext& c, int l) {
  return c.hierarchy->transfer(c.offset + l - 1);
}

/// x₀^{l−1} = P x^l (eq. 4.6).
PetscErrorCode project(RmtrContext& c, int l, Vec fine, Vec coarse) {
  using P = LevelTransfer::Projection;
  const P kind = c.projection == kReverse        ? P::kNatural
                 : c.projection == kLeastSquares ? P::kLeastSquares
                                                 : P::kScaledRestriction;
  return transfer(c, l).project(fine, coarse, kind);
}

/// Eq. (4.7) for a nonlinear prolongation (the shell prolongation of triangle levels): a coarse
/// step within the coarse radius can prolongate to a correction slightly longer than the fine
/// radius Δ (a linear transfer's composite norm rules that out). The coarse step is shortened
/// along its direction, x₀ + θ(x* − x₀), until its correction fits, and the coarse reduction is
/// measured again at the shortened point, h(x₀) − h(x₀ + θ(x* − x₀)). On return *end is that
/// point (lc.shortened), *norm the correction's norm and *reduction the new reduction (≤ 0:
/// the correction is not tried).
PetscErrorCode pull_into_radius(RmtrContext& c, int l, PetscReal delta, Vec* end, PetscReal* norm,
                                PetscReal* reduction) {
  Level& lv = c.levels[l];
  Level& lc = c.levels[l - 1];
  PetscFunctionBeginUser;
  if (!lc.shortened) PetscCall(VecDuplicate(lc.x0, &lc.shortened));
  PetscReal theta = 1.0;
  for (int k = 0; k < 8 && *norm > delta; ++k) {
    theta *= 0.999 * delta / *norm;
    PetscCall(VecWAXPY(lc.shortened, -1.0, lc.x0, lc.tr->solution()));
    PetscCall(VecAYPX(lc.shortened, theta, lc.x0));
    PetscCall(transfer(c, l).prolong_correction(lc.x0, lc.shortened, lv.correction));
    PetscCall(lv.tr->level_norm(lv.correction, norm));
  }
  ++lv.stats.coarse_shortened;
  PetscReal h0, h;
  PetscCall(lc.model->objective(lc.x0, &h0, nullptr));
  PetscCall(lc.model->objective(lc.shortened, &h, nullptr));
  *reduction = *norm <= delta && std::isfinite(h) ? h0 - h : 0.0;
  *end = lc.shortened;
  PetscFunctionReturn(0);
}

/// One V-cycle from level l down (Alg. 4.2). `fine_radius` is Δ^{l+1} (∞ on the finest level),
/// *delta the level's radius; successful[k] counts accepted steps on level k ≤ l that survive.
PetscErrorCode cycle(Tao tao, RmtrContext& c, int l, PetscReal fine_radius, PetscReal* delta,
                     std::vector<long>& successful) {
  Level& lv = c.levels[l];
  PetscFunctionBeginUser;
  bool go_on;
  const int pre = l == 0 ? static_cast<int>(c.coarse_max_it) : static_cast<int>(c.mu1);
  PetscCall(smooth(tao, c, l, pre, fine_radius, delta, successful, &go_on));
  if (l == 0 || !go_on) PetscFunctionReturn(0);

  // Coarse-level correction.
  Level& lc = c.levels[l - 1];
  if (lc.anchored)
    PetscCall(VecCopy(lc.anchor, lc.x0));
  else
    PetscCall(project(c, l, lv.tr->solution(), lc.x0));
  PetscCall(transfer(c, l).restrict_gradient(lc.x0, lv.tr->gradient(), lc.restricted));
  PetscReal rg, f0;
  PetscCall(VecNorm(lc.restricted, NORM_2, &rg));
  bool attempted = false;
  if (rg > tao->gatol) {
    if (c.coarse_model == kGalerkin) {
      Mat H;  // the level's model Hessian, as its smoother's last subproblem used it
      PetscCall(lv.tr->model_hessian(&H));
      PetscCall(transfer(c, l).coarse_operator(
          lc.x0, H, lc.galerkin ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &lc.galerkin));
      PetscCall(lc.model->initialize_galerkin(lc.x0, lc.restricted, lc.galerkin));
      f0 = 0.0;
    } else {
      PetscCall(lc.model->initialize(lc.x0, lc.restricted, &f0));
      c.stats.max_coarse_start_energy =
          std::max<double>(c.stats.max_coarse_start_energy, std::abs(f0));
    }
    PetscCall(lc.tr->start(lc.x0, &f0, lc.restricted));
    attempted = lc.tr->finite();  // a projected state outside the material's domain: skip
    if (attempted && c.check_consistency) {  // eq. (4.5): ∇h^{l−1}(x₀) = R ∇h^l
      PetscReal h0, error;
      PetscCall(lc.model->objective(lc.x0, &h0, lc.scratch));
      PetscCall(VecAXPY(lc.scratch, -1.0, lc.restricted));
      PetscCall(VecNorm(lc.scratch, NORM_2, &error));
      // Relative to the terms that cancel in ∇h(x₀) = ∇f(x₀) + (R∇h^l − ∇f(x₀)): round-off.
      c.stats.max_consistency_error =
          std::max<double>(c.stats.max_consistency_error, error / (rg + lc.model->coupling_norm()));
      PetscReal xnorm, misfit;
      PetscCall(VecNorm(lv.tr->solution(), NORM_2, &xnorm));
      if (xnorm > 0.0) {
        PetscCall(transfer(c, l).prolong(lc.x0, lv.trial));
        PetscCall(VecAXPY(lv.trial, -1.0, lv.tr->solution()));
        PetscCall(VecNorm(lv.trial, NORM_2, &misfit));
        c.stats.max_projection_misfit =
            std::max<double>(c.stats.max_projection_misfit, misfit / xnorm);
      }
    }
  }
  if (attempted) {
    std::vector<long> coarse_successful(successful.size(), 0);
    PetscReal coarse_delta = *delta;  // Δ_{c,0}^{l−1} = Δ_{c,μ₁}^l
    // A W-cycle minimises a coarse level above the coarsest with two of its cycles, the second
    // from where the first ended (same model, radius and bound), unless the first left it done.
    const int visits = c.cycle_type == kWCycle && l - 1 > 0 ? 2 : 1;
    for (int k = 0; k < visits; ++k) {
      if (k > 0 && (lc.tr->gradient_norm() <= tao->gatol || coarse_delta <= 0.0)) break;
      PetscCall(cycle(tao, c, l - 1, *delta, &coarse_delta, coarse_successful));
    }
    // h(x₀) − h(x*) as the coarse steps measured it: at the round-off floor the difference of
    // the two values has either sign, and a sound correction would be discarded on it.
    PetscReal coarse_reduction = lc.tr->reduction();
    Vec coarse_end = lc.tr->solution();
    PetscReal rho = -PETSC_INFINITY, step_norm = 0.0;
    if (coarse_reduction > 0.0) {
      // s = P(x^{l−1}) − P(x₀^{l−1}) (eq. 4.10)
      PetscCall(transfer(c, l).prolong_correction(lc.x0, coarse_end, lv.correction));
      PetscCall(lv.tr->level_norm(lv.correction, &step_norm));
      if (step_norm > *delta)
        PetscCall(pull_into_radius(c, l, *delta, &coarse_end, &step_norm, &coarse_reduction));
    }
    if (coarse_reduction > 0.0) {
      c.stats.max_correction_ratio =
          std::max<double>(c.stats.max_correction_ratio, step_norm / *delta);
      PetscReal ft;  // with ∇f if the last correction passed: then accepting costs no evaluation
      PetscCall(lv.tr->evaluate_trial(lv.correction, lv.correction_passed, &ft));
      ++lv.objectives;
      if (std::isfinite(ft)) {  // below the noise of f^l, from the gradients (as Local_TR does)
        PetscReal actual;
        bool trapezoidal;
        PetscCall(lv.tr->trial_reduction(coarse_reduction, &actual, &trapezoidal));
        rho = actual / coarse_reduction;
      }
    }
    if (coarse_reduction > 0.0) lv.correction_passed = rho > c.params.eta1;
    if (lc.anchor) {  // the coarse level's iterate: where its accepted correction ended
      PetscCall(VecCopy(rho > c.params.eta1 ? coarse_end : lc.x0, lc.anchor));
      lc.anchored = true;
    }
    if (rho > c.params.eta1) {
      PetscCall(lv.tr->accept_trial());
      ++lv.stats.coarse_accepted;
      ++successful[l];
      for (int k = 0; k < l; ++k) successful[k] += coarse_successful[k];
      if (l == finest(c)) ++c.cycle_accepted;
    } else {
      ++lv.stats.coarse_rejected;
      if (l == finest(c)) ++c.cycle_rejected;
    }
    if (coarse_reduction > 0.0) {
      // γ₁Δ on rejection (used = 1): a short correction is no sign that a radius near its
      // length would give the same one (the coarse radii follow Δ), and shrinking to it
      // would let a stalled coarse level collapse the fine radius.
      *delta = c.params.updated_radius(rho, *delta, 1.0);
      PetscCall(cap_radius(c, l, fine_radius, delta));
    }
  }
  PetscCall(smooth(tao, c, l, static_cast<int>(c.mu2), fine_radius, delta, successful, &go_on));
  PetscFunctionReturn(0);
}

/// After a V-cycle on level l that started at `start`: the subspace step (-tao_rmtr_subspace),
/// if on; `note` (of `size` chars) gets its outcome for the monitor line.
PetscErrorCode accelerate(RmtrContext& c, int l, Vec start, PetscReal delta, char* note,
                          size_t size) {
  Level& lv = c.levels[l];
  PetscFunctionBeginUser;
  note[0] = '\0';
  if (!lv.subspace) PetscFunctionReturn(0);
  SubspaceStep st;
  PetscCall(lv.subspace->step(*lv.tr, start, c.params, delta, &st));
  if (!st.tried) PetscFunctionReturn(0);
  ++(st.accepted ? c.stats.subspace_accepted : c.stats.subspace_rejected);
  PetscCall(PetscSNPrintf(note, size, ", subspace step %s (rho %.2f, correction x %.2f)",
                          st.accepted ? "accepted" : "rejected", (double)st.rho,
                          (double)(1.0 + st.relaxation)));
  PetscFunctionReturn(0);
}

/// Copies `candidate` into `current` if f is finite and lower there; *taken says whether. ∇f at
/// the candidate comes with f into `g` (*fc the value), so that a start from it evaluates nothing.
PetscErrorCode keep_lower(Objective& f, Vec candidate, PetscReal f_current, Vec current,
                          bool* taken, PetscReal* fc, Vec g) {
  PetscFunctionBeginUser;
  PetscCall(f.objective(candidate, fc, g));
  *taken = std::isfinite(*fc) && *fc < f_current;
  if (*taken) PetscCall(VecCopy(candidate, current));
  PetscFunctionReturn(0);
}

/// Up to c.fmg_cycles V-cycles on level l < L's own problem, from its started iterate, until the
/// finest level's tolerances hold for it (‖g^l‖ ≤ max(gatol, gttol‖g^l₀‖)) or its solve ends as
/// the finest one would: radius collapse, stagnation (eq. 7.1) or meandering at the round-off
/// floor, here at any ‖g^l‖: a start needs no accuracy its floor cannot give, and a coarse level
/// that carries the finest level's penalty β = h^−σ can have its floor far above the finest
/// tolerance (the drooping cloth at 795,675 dofs: the 147-dof level at ‖g‖ = 3·10⁻⁵ ran all its
/// 1,000 V-cycles). *cycles: the V-cycles done.
PetscErrorCode fmg_solve_level(Tao tao, RmtrContext& c, int l, std::vector<long>& successful,
                               PetscInt* cycles) {
  Level& lv = c.levels[l];
  PetscReal gatol, grtol, gttol;
  PetscFunctionBeginUser;
  PetscCall(TaoGetTolerances(tao, &gatol, &grtol, &gttol));
  const PetscReal g0 = lv.tr->gradient_norm(), tolerance = std::max(gatol, gttol * g0);
  StoppingRule rule = c.stopping;
  rule.reset();
  rule.limiting_factor = PETSC_INFINITY;  // the floor ends a start's level wherever it lies
  if (lv.subspace) lv.subspace->reset();
  PetscReal delta = c.delta0, xnorm, dx;
  Vec previous;  // not lv.scratch: the cycle uses it
  PetscCall(VecDuplicate(lv.x0, &previous));
  *cycles = 0;
  while (*cycles < c.fmg_cycles && lv.tr->gradient_norm() > tolerance) {
    PetscCall(VecNorm(lv.tr->solution(), NORM_2, &xnorm));
    if (rule.collapsed(delta, xnorm)) break;
    const PetscReal f_old = lv.tr->value();
    PetscCall(VecCopy(lv.tr->solution(), previous));
    PetscCall(cycle(tao, c, l, PETSC_INFINITY, &delta, successful));
    char note[96];
    PetscCall(accelerate(c, l, previous, delta, note, sizeof note));
    ++*cycles;
    const PetscReal f = lv.tr->value();
    PetscCall(VecAXPY(previous, -1.0, lv.tr->solution()));
    PetscCall(VecNorm(previous, NORM_2, &dx));
    PetscCall(VecNorm(lv.tr->solution(), NORM_2, &xnorm));
    if (f < f_old && rule.stagnated(delta, f_old - f, f, dx, xnorm, lv.tr->gradient_norm())) break;
    if (rule.at_floor(tao, f_old - f, lv.objective->evaluation_error(), lv.tr->gradient_norm(), g0))
      break;
  }
  PetscCall(VecDestroy(&previous));
  PetscFunctionReturn(0);
}

/// The full-multigrid start (-tao_rmtr_fmg_cycles k): level by level from the coarsest, the
/// level's own problem h^l = f^l (δg = 0) solved with at most k V-cycles (fmg_solve_level), started
/// from the coarser level's solution prolongated where that is lower in f^l than the projected fine
/// iterate (eq. 4.6); finally the finest iterate becomes the prolongated solution of level L − 1 if
/// that lowers f^L below `f_fine`, its value at the given iterate (*moved says whether; then
/// *f_moved and the finest level's `correction` hold f^L and ∇f^L there). The energy never rises.
PetscErrorCode fmg_start(Tao tao, RmtrContext& c, PetscReal f_fine, bool* moved,
                         PetscReal* f_moved) {
  const int L = finest(c);
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(tao));
  PetscFunctionBeginUser;
  *moved = false;
  for (int l = L; l > 0; --l)
    PetscCall(project(c, l, l == L ? tao->solution : c.levels[l].x0, c.levels[l - 1].x0));
  std::vector<long> successful(c.levels.size(), 0);
  for (int l = 0; l < L; ++l) {
    Level& lv = c.levels[l];
    PetscReal f0;
    bool taken = false;
    if (l > 0) {
      Objective& f = c.hierarchy->level_objective(c.offset + l);
      PetscReal fp;
      PetscCall(f.objective(lv.x0, &f0, nullptr));
      PetscCall(transfer(c, l).prolong(c.levels[l - 1].tr->solution(), lv.trial));
      PetscCall(keep_lower(f, lv.trial, std::isfinite(f0) ? f0 : PETSC_INFINITY, lv.x0, &taken, &fp,
                           lv.restricted));
      if (taken) f0 = fp;
    }
    if (taken)  // f^l and ∇f^l at the new start are in f0 and lv.restricted
      PetscCall(lv.model->set_unmodified(lv.x0));
    else
      PetscCall(lv.model->initialize_unmodified(lv.x0, &f0, lv.restricted));
    PetscCall(lv.tr->start(lv.x0, &f0, lv.restricted));
    if (!lv.tr->finite())
      PetscFunctionReturn(0);  // a projected state outside the material's domain
    PetscInt k = 0;
    PetscCall(fmg_solve_level(tao, c, l, successful, &k));
    if (lv.anchor) {  // the level's own solution is its iterate for the V-cycles above
      PetscCall(VecCopy(lv.tr->solution(), lv.anchor));
      lv.anchored = true;
    }
    c.stats.fmg_cycles += k;
    if (c.monitor)
      PetscCall(PetscPrintf(comm,
                            "  rmtr fmg level %d (%" PetscInt_FMT " dofs): %" PetscInt_FMT
                            " V-cycle(s), f % .12e  |g| %.4e\n",
                            l, lv.stats.dofs, k, (double)lv.tr->value(),
                            (double)lv.tr->gradient_norm()));
  }
  Level& top = c.levels[L];
  PetscCall(transfer(c, L).prolong(c.levels[L - 1].tr->solution(), top.trial));
  PetscCall(
      keep_lower(*top.objective, top.trial, f_fine, tao->solution, moved, f_moved, top.correction));
  if (*moved)  // the coarse steps now live on in the finest iterate
    for (int l = 0; l < L; ++l) c.stats.levels[l].successful += successful[l];
  if (c.monitor)
    PetscCall(PetscPrintf(comm, "  rmtr fmg: the finest level starts from %s\n",
                          *moved ? "the prolongated solution" : "its own iterate (lower energy)"));
  PetscFunctionReturn(0);
}

PetscErrorCode collect_statistics(RmtrContext& c) {
  PetscFunctionBeginUser;
  const int L = finest(c);
  c.stats.assembly_work_units = c.stats.qp_work_units = 0.0;
  c.stats.levels.resize(c.levels.size());
  // W^l / W^L (eq. 7.3) as the product of the transfers' relative costs, finest first.
  std::vector<double> weight(L + 1, 1.0);
  for (int l = L - 1; l >= 0; --l) weight[l] = weight[l + 1] * transfer(c, l + 1).relative_cost();
  for (int l = 0; l <= L; ++l) {
    Level& lv = c.levels[l];
    RmtrLevelStatistics& s = c.stats.levels[l];
    const TrustRegionCounters& t = lv.tr->counters();
    s.dofs = lv.stats.dofs;
    s.assemblies = t.hessians;
    s.qp_solves = t.qp_solves;
    s.factorisations = t.factorisations;
    s.objectives = t.objectives + lv.objectives;
    s.coarse_accepted = lv.stats.coarse_accepted;
    s.coarse_rejected = lv.stats.coarse_rejected;
    s.coarse_shortened = lv.stats.coarse_shortened;
    c.stats.assembly_work_units += weight[l] * s.assemblies;
    c.stats.qp_work_units += weight[l] * s.qp_solves;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode solve(Tao tao) {
  auto* c = static_cast<RmtrContext*>(tao->data);
  PetscFunctionBeginUser;
  const int L = finest(*c);
  Level& top = c->levels[L];
  for (Level& lv : c->levels) {
    lv.tr->set_gradient_target(c->stcg_target * tao->gatol);
    lv.tr->reset_counters();
    lv.objectives = 0;
    lv.stats.coarse_accepted = lv.stats.coarse_rejected = lv.stats.coarse_shortened = 0;
    lv.anchored = false;  // a coarse iterate of the previous solve need not fit this one's start
  }
  c->stats = RmtrStatistics{};
  c->stats.levels.resize(c->levels.size());
  c->limiting = false;
  c->stopping.reset();
  if (top.subspace) top.subspace->reset();
  tao->reason = TAO_CONTINUE_ITERATING;
  // Iteration 0 is the given iterate, also when the full-multigrid start moves it: tolerances
  // relative to ‖g₀‖ and the energy history refer to it.
  PetscReal f_in = 0.0, g0 = 0.0;
  PetscReal x_max;
  PetscCall(VecNorm(tao->solution, NORM_INFINITY, &x_max));
  const bool fmg = c->fmg_cycles > 0 && L > 0 && (c->fmg_always || x_max == 0.0);
  bool moved = false;
  PetscReal f_moved = 0.0;
  if (fmg) {
    PetscCall(top.objective->objective(tao->solution, &f_in, tao->gradient));
    PetscCall(VecNorm(tao->gradient, NORM_2, &g0));
    if (std::isfinite(f_in) && std::isfinite(g0) && g0 > tao->gatol)
      PetscCall(fmg_start(tao, *c, f_in, &moved, &f_moved));
  }
  if (moved)  // f and ∇f at the prolongated solution are known
    PetscCall(top.tr->start(tao->solution, &f_moved, top.correction));
  else if (fmg)  // and at the given iterate
    PetscCall(top.tr->start(tao->solution, &f_in, tao->gradient));
  else
    PetscCall(top.tr->start(tao->solution));
  PetscReal delta = c->delta0;
  if (!fmg) {
    f_in = top.tr->value();
    g0 = top.tr->gradient_norm();
  }
  if (!top.tr->finite()) {  // nothing to iterate on: say so instead of producing NaN
    tao->reason = TAO_DIVERGED_NAN;
    tao->fc = top.tr->value();
    tao->residual = top.tr->gradient_norm();
    PetscCall(collect_statistics(*c));
    PetscFunctionReturn(0);
  }
  PetscCall(TaoLogConvergenceHistory(tao, f_in, g0, 0.0, tao->ksp_its));
  PetscCall(TaoMonitor(tao, tao->niter, f_in, g0, 0.0, delta));
  PetscCall((*tao->ops->convergencetest)(tao, tao->cnvP));
  if (tao->reason != TAO_CONTINUE_ITERATING && moved) {  // stopped at the moved iterate
    PetscCall(VecCopy(top.tr->gradient(), tao->gradient));
    tao->fc = top.tr->value();
    tao->residual = top.tr->gradient_norm();
  }
  Vec previous;
  PetscCall(VecDuplicate(tao->solution, &previous));
  while (tao->reason == TAO_CONTINUE_ITERATING) {
    PetscReal xnorm;
    PetscCall(VecNorm(top.tr->solution(), NORM_2, &xnorm));
    if (c->stopping.collapsed(delta, xnorm)) {
      c->stopping.end_collapsed(tao, top.tr->gradient_norm(), g0, &c->limiting);
      break;
    }
    const PetscReal f_old = top.tr->value();
    PetscCall(VecCopy(top.tr->solution(), previous));
    c->cycle_accepted = c->cycle_rejected = 0;
    std::vector<long> successful(c->levels.size(), 0);
    PetscCall(cycle(tao, *c, L, PETSC_INFINITY, &delta, successful));
    char note[96];
    PetscCall(accelerate(*c, L, previous, delta, note, sizeof note));
    for (int l = 0; l <= L; ++l) c->stats.levels[l].successful += successful[l];
    ++c->stats.cycles;
    ++tao->niter;
    PetscCall(VecCopy(top.tr->solution(), tao->solution));
    PetscCall(VecCopy(top.tr->gradient(), tao->gradient));
    const PetscReal f = top.tr->value(), gnorm = top.tr->gradient_norm();
    if (c->monitor)
      PetscCall(PetscPrintf(PetscObjectComm((PetscObject)tao),
                            "  rmtr cycle %4" PetscInt_FMT "  f % .12e  |g| %.4e  delta %.3e  "
                            "coarse corrections %ld accepted, %ld rejected%s\n",
                            tao->niter, (double)f, (double)gnorm, (double)delta, c->cycle_accepted,
                            c->cycle_rejected, note));
    PetscCall(TaoLogConvergenceHistory(tao, f, gnorm, 0.0, tao->ksp_its));
    PetscCall(TaoMonitor(tao, tao->niter, f, gnorm, 0.0, delta));
    PetscCall((*tao->ops->convergencetest)(tao, tao->cnvP));
    // Eq. (7.1), second part: Newton-like regime and no more progress in floating point.
    if (tao->reason == TAO_CONTINUE_ITERATING && f < f_old) {
      PetscReal dx, xnorm_new;
      PetscCall(VecAXPY(previous, -1.0, top.tr->solution()));
      PetscCall(VecNorm(previous, NORM_2, &dx));
      PetscCall(VecNorm(top.tr->solution(), NORM_2, &xnorm_new));
      if (c->stopping.stagnated(delta, f_old - f, f, dx, xnorm_new, gnorm))
        c->stopping.end_stagnated(tao, gnorm, g0);
    }
    if (tao->reason == TAO_CONTINUE_ITERATING &&
        c->stopping.at_floor(tao, f_old - f, top.objective->evaluation_error(), gnorm, g0))
      c->stopping.end_at_floor(tao, &c->limiting);
  }
  PetscCall(VecDestroy(&previous));
  PetscCall(collect_statistics(*c));
  PetscFunctionReturn(0);
}

PetscErrorCode set_from_options(Tao tao, PetscOptionItems* PetscOptionsObject) {
  auto* c = static_cast<RmtrContext*>(tao->data);
  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Recursive multilevel trust region (paper Alg. 4.2)");
  PetscCall(PetscOptionsInt("-tao_rmtr_levels", "number of levels (0: all)", "",
                            c->requested_levels, &c->requested_levels, nullptr));
  PetscCall(PetscOptionsInt("-tao_rmtr_mu1", "pre-smoothing steps", "", c->mu1, &c->mu1, nullptr));
  PetscCall(PetscOptionsInt("-tao_rmtr_mu2", "post-smoothing steps", "", c->mu2, &c->mu2, nullptr));
  PetscCall(PetscOptionsEnum("-tao_rmtr_cycle_type",
                             "v: one cycle of each coarse level per visit (the paper); w: two", "",
                             kCycleTypeNames, static_cast<PetscEnum>(c->cycle_type),
                             reinterpret_cast<PetscEnum*>(&c->cycle_type), nullptr));
  PetscCall(PetscOptionsInt("-tao_rmtr_coarse_max_it", "steps on the coarsest level (-1: mu1+mu2)",
                            "", c->coarse_max_it, &c->coarse_max_it, nullptr));
  PetscCall(PetscOptionsInt("-tao_rmtr_stcg_max_it",
                            "CG iterations per smoothing step (STCG, or Dogleg's inexact Newton "
                            "point with -tao_rmtr_smoother_pc)",
                            "", c->stcg_max_it, &c->stcg_max_it, nullptr));
  PetscCall(PetscOptionsReal("-tao_rmtr_newton_rtol",
                             "Dogleg smoothing with -tao_rmtr_smoother_pc: relative tolerance of "
                             "the CG solve for its Newton point",
                             "", c->newton_rtol, &c->newton_rtol, nullptr));
  PetscCall(PetscOptionsReal("-tao_rmtr_stcg_target",
                             "STCG stops at a model gradient of this fraction of -tao_gatol", "",
                             c->stcg_target, &c->stcg_target, nullptr));
  PetscCall(PetscOptionsEnum("-tao_rmtr_projection", "projection of iterates to coarser levels", "",
                             kProjectionNames, static_cast<PetscEnum>(c->projection),
                             reinterpret_cast<PetscEnum*>(&c->projection), nullptr));
  PetscCall(PetscOptionsEnum("-tao_rmtr_coarse_start",
                             "x0 of a coarse level: the projection of the fine iterate, or the "
                             "coarse level's own iterate from its last visit",
                             "", kCoarseStartNames, static_cast<PetscEnum>(c->coarse_start),
                             reinterpret_cast<PetscEnum*>(&c->coarse_start), nullptr));
  PetscCall(PetscOptionsEnum("-tao_rmtr_coarse_model",
                             "coarse-level model: first_order (eq. 4.3) or galerkin (J_P^T H J_P)",
                             "", kCoarseModelNames, static_cast<PetscEnum>(c->coarse_model),
                             reinterpret_cast<PetscEnum*>(&c->coarse_model), nullptr));
  PetscCall(
      PetscOptionsString("-tao_rmtr_smoother_pc",
                         "preconditioner of STCG above the coarsest level (none, vpatch, ...); "
                         "with Dogleg, of the CG solve for its Newton point",
                         "", c->smoother_pc, c->smoother_pc, sizeof c->smoother_pc, nullptr));
  PetscCall(PetscOptionsInt("-tao_rmtr_hessian_lag",
                            "accepted steps a level keeps its Hessian before assembling it again",
                            "", c->hessian_lag, &c->hessian_lag, nullptr));
  PetscCall(PetscOptionsEnum("-tao_rmtr_smoother_qp", "QP solver above the coarsest level", "",
                             kQpNames, static_cast<PetscEnum>(c->smoother_qp),
                             reinterpret_cast<PetscEnum*>(&c->smoother_qp), nullptr));
  PetscCall(PetscOptionsEnum("-tao_rmtr_coarse_qp", "QP solver on the coarsest level", "", kQpNames,
                             static_cast<PetscEnum>(c->coarse_qp),
                             reinterpret_cast<PetscEnum*>(&c->coarse_qp), nullptr));
  PetscCall(PetscOptionsInt("-tao_rmtr_coarse_redundant",
                            "Dogleg factorises a coarsest level of at most this many dofs whole on "
                            "every rank, the same in every run (0: distributed MUMPS)",
                            "", c->coarse_redundant, &c->coarse_redundant, nullptr));
  PetscCall(
      PetscOptionsReal("-tao_rmtr_delta0", "initial radius", "", c->delta0, &c->delta0, nullptr));
  PetscCall(trust_region_parameter_options(PetscOptionsObject, "-tao_rmtr_", &c->params));
  PetscCall(PetscOptionsReal("-tao_rmtr_eps_delta", "coarse-correction threshold (Alg. 4.3)", "",
                             c->eps_delta, &c->eps_delta, nullptr));
  PetscCall(c->stopping.options(PetscOptionsObject, "-tao_rmtr_"));
  PetscCall(PetscOptionsInt("-tao_rmtr_fmg_cycles",
                            "full-multigrid start: V-cycles on each coarser level's own problem "
                            "before the finest (0: off)",
                            "", c->fmg_cycles, &c->fmg_cycles, nullptr));
  PetscCall(PetscOptionsInt("-tao_rmtr_retries",
                            "a rejected smoothing step is retried at once with the shrunk radius, "
                            "up to this many times (0: the paper's one iteration per step)",
                            "", c->retries, &c->retries, nullptr));
  PetscCall(PetscOptionsInt("-tao_rmtr_subspace",
                            "after each V-cycle, a trust-region step in the span of its correction "
                            "and this many minus one earlier changes (0: off)",
                            "", c->subspace, &c->subspace, nullptr));
  PetscCall(PetscOptionsBool("-tao_rmtr_fmg_always",
                             "full-multigrid start before every solve, not only from the rest "
                             "state x = 0",
                             "", c->fmg_always, &c->fmg_always, nullptr));
  PetscCall(PetscOptionsBool("-tao_rmtr_monitor", "one line per V-cycle", "", c->monitor,
                             &c->monitor, nullptr));
  PetscCall(PetscOptionsBool("-tao_rmtr_check_consistency",
                             "check eq. (4.5) at every coarse start (one more gradient each)", "",
                             c->check_consistency, &c->check_consistency, nullptr));
  PetscOptionsHeadEnd();
  MPI_Comm comm = PetscObjectComm((PetscObject)tao);
  PetscCall(c->params.validate(comm, "-tao_rmtr_"));
  PetscCheck(c->requested_levels >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_levels: must be >= 1 (or 0 for all levels), got %" PetscInt_FMT,
             c->requested_levels);
  PetscCheck(c->mu1 >= 0 && c->mu2 >= 0 && c->mu1 + c->mu2 > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_mu1/-tao_rmtr_mu2: need non-negative counts with mu1 + mu2 >= 1, got "
             "%" PetscInt_FMT " and %" PetscInt_FMT,
             c->mu1, c->mu2);
  if (c->coarse_max_it < 0) c->coarse_max_it = c->mu1 + c->mu2;
  PetscCheck(c->coarse_max_it >= 1 && c->stcg_max_it >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_coarse_max_it and -tao_rmtr_stcg_max_it must be >= 1");
  PetscCheck(c->stcg_target >= 0 && c->stcg_target < 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_stcg_target: must lie in [0, 1), got %g", (double)c->stcg_target);
  PetscCheck(c->newton_rtol > 0 && c->newton_rtol < 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_newton_rtol: must lie in (0, 1), got %g", (double)c->newton_rtol);
  PetscCheck(c->fmg_cycles >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_fmg_cycles must be >= 0, got %" PetscInt_FMT, c->fmg_cycles);
  PetscCheck(c->coarse_redundant >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_coarse_redundant must be >= 0, got %" PetscInt_FMT, c->coarse_redundant);
  PetscCheck(c->retries >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_retries must be >= 0, got %" PetscInt_FMT, c->retries);
  PetscCheck(c->subspace >= 0 && c->subspace <= 20, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_subspace must lie in [0, 20], got %" PetscInt_FMT, c->subspace);
  PetscCheck(c->hessian_lag >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_hessian_lag must be >= 0, got %" PetscInt_FMT, c->hessian_lag);
  PetscCheck(c->delta0 > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_delta0: must be positive, got %g", (double)c->delta0);
  PetscCheck(c->eps_delta > 0 && c->eps_delta < 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-tao_rmtr_eps_delta: must lie in (0, 1), got %g", (double)c->eps_delta);
  PetscFunctionReturn(0);
}

PetscErrorCode view(Tao tao, PetscViewer viewer) {
  auto* c = static_cast<RmtrContext*>(tao->data);
  PetscFunctionBeginUser;
  const int n = c->levels.empty()
                    ? (c->requested_levels > 0 ? static_cast<int>(c->requested_levels)
                                               : (c->hierarchy ? c->hierarchy->num_levels() : 1))
                    : static_cast<int>(c->levels.size());
  PetscCall(PetscViewerASCIIPrintf(
      viewer,
      "  RMTR (Alg. 4.2): %d level(s)%s, %s-cycle mu1 = %" PetscInt_FMT ", mu2 = %" PetscInt_FMT
      ", coarsest %" PetscInt_FMT " step(s) of %s, smoother %s (%" PetscInt_FMT
      " iterations or a model gradient of %g gatol, PC %s), projection %s, %s coarse models "
      "from the %s\n",
      n, c->hierarchy ? "" : " (no hierarchy attached)", c->cycle_type == kWCycle ? "W" : "V",
      c->mu1, c->mu2, c->coarse_max_it, kQpNames[c->coarse_qp], kQpNames[c->smoother_qp],
      c->stcg_max_it, (double)c->stcg_target, c->smoother_pc, kProjectionNames[c->projection],
      kCoarseModelNames[c->coarse_model],
      c->coarse_start == kIterate ? "coarse iterate" : "projection"));
  PetscCall(PetscViewerASCIIPrintf(
      viewer, "  delta0 %g, eta1 %g, eta2 %g, gamma1 %g, gamma2 %g, eps_delta %g\n",
      (double)c->delta0, (double)c->params.eta1, (double)c->params.eta2, (double)c->params.gamma1,
      (double)c->params.gamma2, (double)c->eps_delta));
  if (c->coarse_qp == 0)
    PetscCall(PetscViewerASCIIPrintf(
        viewer, "  coarsest Dogleg factorised whole on every rank up to %" PetscInt_FMT " dofs\n",
        c->coarse_redundant));
  if (c->fmg_cycles > 0)
    PetscCall(PetscViewerASCIIPrintf(
        viewer,
        "  full-multigrid start (%s): at most %" PetscInt_FMT " V-cycle(s) per coarser level\n",
        c->fmg_always ? "before every solve" : "from the rest state x = 0", c->fmg_cycles));
  if (c->subspace > 0)
    PetscCall(PetscViewerASCIIPrintf(
        viewer,
        "  subspace step after each V-cycle: its correction and %" PetscInt_FMT
        " earlier change(s)\n",
        c->subspace - 1));
  if (c->stats.cycles > 0) {
    PetscCall(PetscViewerASCIIPrintf(
        viewer,
        "  level       dofs  successful  assemblies   QP solves  factorised  objectives  "
        "coarse +/-\n"));
    for (int l = static_cast<int>(c->stats.levels.size()) - 1; l >= 0; --l) {
      const RmtrLevelStatistics& s = c->stats.levels[l];
      PetscCall(PetscViewerASCIIPrintf(
          viewer, "  %5d %10" PetscInt_FMT " %11ld %11ld %11ld %11ld %11ld  %ld/%ld\n", l, s.dofs,
          s.successful, s.assemblies, s.qp_solves, s.factorisations, s.objectives,
          s.coarse_accepted, s.coarse_rejected));
    }
    PetscCall(PetscViewerASCIIPrintf(
        viewer,
        "  %ld V-cycles; work units (eq. 7.3-7.4): assembly %.1f (%.2f per cycle), QP %.1f "
        "(%.2f per cycle)\n",
        c->stats.cycles, c->stats.assembly_work_units,
        c->stats.assembly_work_units / c->stats.cycles, c->stats.qp_work_units,
        c->stats.qp_work_units / c->stats.cycles));
    if (c->stats.fmg_cycles > 0)
      PetscCall(PetscViewerASCIIPrintf(viewer,
                                       "  full-multigrid start: %ld V-cycles on the coarser levels "
                                       "(in the counts above)\n",
                                       c->stats.fmg_cycles));
    if (c->subspace > 0)
      PetscCall(PetscViewerASCIIPrintf(viewer, "  subspace steps: %ld accepted, %ld rejected\n",
                                       c->stats.subspace_accepted, c->stats.subspace_rejected));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode destroy(Tao tao) {
  auto* c = static_cast<RmtrContext*>(tao->data);
  PetscFunctionBeginUser;
  destroy_levels(*c);
  delete c;
  tao->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode create(Tao tao) {
  PetscFunctionBeginUser;
  tao->data = new RmtrContext();
  tao->ops->setup = setup;
  tao->ops->solve = solve;
  tao->ops->setfromoptions = set_from_options;
  tao->ops->view = view;
  tao->ops->destroy = destroy;
  PetscFunctionReturn(0);
}

}  // namespace

RmtrStatistics& RmtrStatistics::operator+=(const RmtrStatistics& o) {
  if (levels.empty()) levels.resize(o.levels.size());
  for (size_t l = 0; l < std::min(levels.size(), o.levels.size()); ++l) {
    RmtrLevelStatistics& a = levels[l];
    const RmtrLevelStatistics& b = o.levels[l];
    a.dofs = b.dofs;
    a.successful += b.successful;
    a.assemblies += b.assemblies;
    a.qp_solves += b.qp_solves;
    a.factorisations += b.factorisations;
    a.objectives += b.objectives;
    a.coarse_accepted += b.coarse_accepted;
    a.coarse_rejected += b.coarse_rejected;
    a.coarse_shortened += b.coarse_shortened;
  }
  cycles += o.cycles;
  fmg_cycles += o.fmg_cycles;
  subspace_accepted += o.subspace_accepted;
  subspace_rejected += o.subspace_rejected;
  max_correction_ratio = std::max(max_correction_ratio, o.max_correction_ratio);
  max_consistency_error = std::max(max_consistency_error, o.max_consistency_error);
  max_projection_misfit = std::max(max_projection_misfit, o.max_projection_misfit);
  max_coarse_start_energy = std::max(max_coarse_start_energy, o.max_coarse_start_energy);
  assembly_work_units += o.assembly_work_units;
  qp_work_units += o.qp_work_units;
  return *this;
}

PetscErrorCode register_rmtr_tao_type() { return TaoRegister("rmtr", create); }

PetscErrorCode rmtr_set_levels(Tao tao, MultilevelObjective* levels) {
  PetscFunctionBeginUser;
  PetscCall(require_tao_type(tao, "rmtr"));
  auto* c = static_cast<RmtrContext*>(tao->data);
  destroy_levels(*c);
  c->hierarchy = levels;
  PetscFunctionReturn(0);
}

bool rmtr_reached_limiting_accuracy(Tao tao) {
  return static_cast<RmtrContext*>(tao->data)->limiting;
}

PetscErrorCode rmtr_set_error_source(Tao tao, Objective* source) {
  PetscFunctionBeginUser;
  PetscCall(require_tao_type(tao, "rmtr"));
  auto* c = static_cast<RmtrContext*>(tao->data);
  c->error_source = source;
  c->finest.reset();
  destroy_levels(*c);
  PetscFunctionReturn(0);
}

PetscErrorCode rmtr_statistics(Tao tao, RmtrStatistics* stats) {
  PetscFunctionBeginUser;
  PetscCall(require_tao_type(tao, "rmtr"));
  *stats = static_cast<RmtrContext*>(tao->data)->stats;
  PetscFunctionReturn(0);
}

}  // namespace mlshell
