// Local_TR (paper Alg. 4.1) on one Objective: the iteration shared by the TAO type "tr" and by
// every level of RMTR (pre-/post-smoothing and the coarsest-level solve).
//
// One iteration solves the subproblem (4.1) with the level's QP solver, evaluates the trial
// point, accepts it when ρ = (f(x) − f(x+s)) / (m(0) − m(s)) > η₁ (eq. 4.2), and updates the
// radius (Table 2; a rejected step inside the region skips the radii that would return it
// again, TrustRegionParameters::updated_radius). The trial point's gradient is evaluated with
// its value when the previous step was accepted (one pass over the elements for the likely next
// iterate; a gradient wasted on a rejection), otherwise after acceptance. The Hessian is
// assembled only when the next subproblem needs it (a point left at once by RMTR's coarse
// correction, or the converged one, costs none), so a rejected step reuses the Hessian (and a
// Dogleg factorisation).
//
// The radius may be measured in a level norm other than ℓ₂ (RMTR's ‖·‖_l, eq. 4.9): the QP is
// then given the ℓ₂ radius Δ·‖g‖₂/‖g‖_l, and a step still longer than Δ in the level norm is
// shortened along its own direction (which keeps m(s) < 0), so ‖s‖_l ≤ Δ always holds.
//
// Near the round-off floor the actual reduction f(x) − f(x+s) is the difference of two values
// each carrying an error of Objective::evaluation_error(); once the predicted reduction is below
// 1000 times that error, the actual reduction is taken as −½ (∇f(x) + ∇f(x+s))ᵀ s instead (the
// trapezoidal rule: exact for a quadratic, error O(‖s‖³), and its rounding is that of the
// gradients, far smaller), so ρ stays meaningful down to the limiting accuracy. A trial point
// where f rose by more than 10 times its error is still rejected: wrong gradients cannot pass.
#pragma once

#include <petsctao.h>

#include <functional>
#include <memory>
#include <string>

#include "mlshell/objective.hpp"
#include "mlshell/trust_region_qp.hpp"

namespace mlshell {

/// η₁, η₂, γ₁, γ₂ of Table 2, and the radius update they define.
struct TrustRegionParameters {
  PetscReal eta1 = 0.1, eta2 = 0.75, gamma1 = 0.5, gamma2 = 2.0;
  /// The radius after a step with ratio ρ that needed the share `used` ∈ (0, 1] of Δ (every
  /// radius ≥ used·Δ gives the same step): expand to γ₂Δ (at most 1e30) when ρ > η₂, keep Δ
  /// when η₁ < ρ ≤ η₂ (the standard half of Alg. 4.3), and when ρ ≤ η₁ shrink to γ₁ᵏΔ with the
  /// least k ≥ 1 for which γ₁ᵏ < used. The radii γ₁Δ, …, γ₁ᵏ⁻¹Δ that Alg. 4.1 would try next
  /// give the same step, rejected again: k = 1 for a step on the boundary (the paper's γ₁Δ),
  /// and an interior step skips those null iterations (a radius of 1e30 after a run of good
  /// Newton steps would otherwise take 100 rejections to reach a step's length).
  PetscReal updated_radius(PetscReal rho, PetscReal delta, PetscReal used) const;
  /// Raises PETSC_ERR_ARG_OUTOFRANGE unless 0 < η₁ < η₂ < 1 and 0 < γ₁ < 1 < γ₂.
  /// Refuses out-of-range values, naming the options (`prefix`: "-tao_rmtr_", "-tao_tr_").
  PetscErrorCode validate(MPI_Comm comm, const char* prefix) const;
};

/// How a trust-region solve (TR, or RMTR on its finest level) ends besides TAO's tolerances
/// (paper eq. 7.1 and §7.2).
///   - Stagnation, the second part of (7.1): once Δ > 1e15 (Newton's regime), an accepted
///     iteration with |Δf| ≤ s·|f| or ‖Δx‖ ≤ s·‖x‖, unless ‖g‖ is still falling: some iteration
///     among the last `stagnation_window` took it below 0.9 times its lowest value before. The
///     paper's absolute 1e-12 is relative here, so that it holds for any units and size. A
///     large radius is no proof of Newton's regime: an iteration that converges linearly (RMTR's
///     V-cycles, a poor Hessian) inflates Δ by every success while |Δf| ~ ‖g‖²/λ falls below
///     s·|f| long before ‖g‖ reaches its floor. So stagnation is convergence only with ‖g‖
///     within `limiting_factor` of the tolerance, as for a radius collapse; else a failure.
///   - Radius collapse, Δ < r·max(1, ‖x‖): no step lowers f in floating point. If ‖g‖ is within
///     `limiting_factor` of the gradient tolerance, the solve has reached the limiting accuracy
///     of f (its round-off floor) and converged; otherwise it failed (DIVERGED_TR_REDUCTION).
///   - Meandering at the floor: `floor_iterations` iterations in a row whose decrease of f is
///     within 10 times its evaluation error, with ‖g‖ within `limiting_factor` of the tolerance
///     and not halving: the gradient itself is noise there (limiting accuracy).
struct StoppingRule {
  PetscReal stagnation = 1e-12, min_radius = 1e-14, limiting_factor = 100.0;
  PetscInt floor_iterations = 20, stagnation_window = 3;
  /// Feeds one outer iteration (decrease df of f, its evaluation error, ‖g‖, ‖g₀‖); true when
  /// the solve has meandered at the floor long enough (then call end_at_floor).
  bool at_floor(Tao tao, PetscReal df, PetscReal f_error, PetscReal gnorm, PetscReal g0);
  void end_at_floor(Tao tao, bool* limiting) const;
  void reset_floor() {
    floor_count_ = 0;
    floor_decrease_ = 0.0;
  }
  /// Forgets the solve before: call at the start of each.
  void reset() {
    reset_floor();
    best_gnorm_ = PETSC_INFINITY;
    since_best_ = 0;
  }
  /// Feeds one accepted iteration (‖g‖ = `gnorm` after it). While ‖g‖ still falls it has not
  /// stagnated: below the resolution of f the gradient shows the progress (V-cycles that
  /// contract ‖g‖ by 0.5 lower f by less than 1e-12·|f| there, and one of them may raise ‖g‖
  /// a little), so the test looks at the lowest ‖g‖ over a window, not at one iteration.
  bool stagnated(PetscReal delta, PetscReal df, PetscReal f, PetscReal dx, PetscReal xnorm,
                 PetscReal gnorm);
  /// Sets tao->reason after stagnation at gradient norm `gnorm` (‖g₀‖ = `g0` at the start):
  /// TAO_CONVERGED_STEPTOL if ‖g‖ is within `limiting_factor` of the tolerance, else
  /// TAO_DIVERGED_USER (reported as DIVERGED_STAGNATION).
  void end_stagnated(Tao tao, PetscReal gnorm, PetscReal g0) const;
  bool collapsed(PetscReal delta, PetscReal xnorm) const;
  /// Sets tao->reason after a collapse at gradient norm `gnorm` (‖g₀‖ = `g0` at the start):
  /// TAO_CONVERGED_USER (reported as CONVERGED_LIMITING_ACCURACY, *limiting = true) or
  /// TAO_DIVERGED_TR_REDUCTION.
  void end_collapsed(Tao tao, PetscReal gnorm, PetscReal g0, bool* limiting) const;
  /// Reads `<prefix>stagnation`, `min_radius`, `limiting_factor`, `floor_iterations`.
  PetscErrorCode options(PetscOptionItems* PetscOptionsObject, const std::string& prefix);

 private:
  PetscReal tolerance(Tao tao, PetscReal g0) const;
  PetscInt floor_count_ = 0;
  PetscReal floor_gnorm_ = 0.0;            // ‖g‖ when the count started
  PetscReal floor_decrease_ = 0.0;         // decrease of f since the count started
  PetscReal best_gnorm_ = PETSC_INFINITY;  // the last ‖g‖ below 0.9 × the lowest before it
  PetscInt since_best_ = 0;                // accepted iterations since
};

/// Reads `<prefix>eta1`, `eta2`, `gamma1`, `gamma2` inside a PetscOptionsBegin/End block.
PetscErrorCode trust_region_parameter_options(PetscOptionItems* PetscOptionsObject,
                                              const std::string& prefix, TrustRegionParameters* p);

/// Work done by one Local_TR (or one level of RMTR).
struct TrustRegionCounters {
  long accepted = 0;        ///< successful iterations
  long qp_solves = 0;       ///< subproblem solves
  long objectives = 0;      ///< trial-point evaluations
  long hessians = 0;        ///< Hessian assemblies (each where a subproblem needed one)
  long factorisations = 0;  ///< sparse direct factorisations by the subproblem solver
  TrustRegionCounters& operator+=(const TrustRegionCounters& o) {
    accepted += o.accepted;
    qp_solves += o.qp_solves;
    objectives += o.objectives;
    hessians += o.hessians;
    factorisations += o.factorisations;
    return *this;
  }
};

/// The outcome of one iteration.
struct TrustRegionIteration {
  bool accepted = false;
  PetscReal rho = 0.0;          ///< eq. (4.2); −inf when the trial point was not evaluated
  PetscReal step_norm = 0.0;    ///< ‖s‖ in the level norm
  PetscReal radius_used = 1.0;  ///< the least radius giving the same step, over Δ (≤ 1)
  PetscReal decrease = 0.0;     ///< f(x) − f(x+s) if accepted, else 0
  bool trapezoidal = false;     ///< the actual reduction came from the gradients
  QpResult qp;
};

/// ‖v‖ in the norm the radius is measured in.
using LevelNorm = std::function<PetscErrorCode(Vec, PetscReal*)>;

class LocalTrustRegion {
 public:
  /// `H` holds ∇²f (filled here); `norm` is the level norm (empty: ℓ₂).
  LocalTrustRegion(Objective& f, Vec like, Mat H, std::unique_ptr<TrustRegionQp> qp,
                   LevelNorm norm = {});
  ~LocalTrustRegion();
  LocalTrustRegion(const LocalTrustRegion&) = delete;
  LocalTrustRegion& operator=(const LocalTrustRegion&) = delete;

  /// Moves to x and evaluates f and ∇f there (∇²f before the next iteration). A value and
  /// gradient already known at x can be passed to skip their evaluation. If f or ∇f is not
  /// finite there, finite() turns false and no iteration may follow.
  PetscErrorCode start(Vec x, const PetscReal* f = nullptr, Vec g = nullptr);
  /// One iteration of Alg. 4.1 with radius *delta (updated with `p`).
  PetscErrorCode iterate(const TrustRegionParameters& p, PetscReal* delta,
                         TrustRegionIteration* it);
  /// f at the trial point x + s of a step found elsewhere (RMTR's coarse correction), and ∇f
  /// with it if `with_gradient` (one pass over the elements instead of two if the point is
  /// accepted, a gradient wasted if not).
  PetscErrorCode evaluate_trial(Vec s, bool with_gradient, PetscReal* ft);
  /// f(x) − f(x + s) at the last trial point (finite f there), for a step that predicted the
  /// reduction `predicted`: below the noise of f the trapezoidal rule −½ (∇f(x) + ∇f(x+s))ᵀ s
  /// (evaluating ∇f at x + s if needed; *trapezoidal says so), see the file comment.
  PetscErrorCode trial_reduction(PetscReal predicted, PetscReal* actual, bool* trapezoidal);
  /// Moves to the last trial point and takes its value and gradient (evaluating ∇f if
  /// evaluate_trial did not); the Hessian follows before the next iteration, as the lag allows.
  /// The step's reduction, as trial_reduction measured it (f(x) − f(x + s) if it was not
  /// called), adds to reduction().
  PetscErrorCode accept_trial();
  /// ‖v‖ in the level norm.
  PetscErrorCode level_norm(Vec v, PetscReal* norm) const;
  /// The Hessian of the level's current quadratic model: the one its last subproblem used (at
  /// most the lag's accepted steps old), or ∇²f at x assembled now if there was none since
  /// start(). RMTR's Galerkin coarse models are built from it.
  PetscErrorCode model_hessian(Mat* H);

  Objective& objective() { return f_; }
  Vec solution() const { return x_; }
  Vec gradient() const { return g_; }
  PetscReal value() const { return fx_; }
  /// f(x₀) − f(x) since start(x₀): the sum of the accepted steps' reductions, each as
  /// trial_reduction measured it. Below the noise of f the difference of the two values is
  /// round-off of either sign; this sum is what the steps achieved (RMTR's coarse reduction).
  PetscReal reduction() const { return reduction_; }
  PetscReal gradient_norm() const { return gnorm_; }
  bool finite() const { return finite_; }
  const TrustRegionCounters& counters() const { return counters_; }
  void reset_counters() { counters_ = {}; }
  /// Keeps the Hessian for up to `lag` accepted steps before assembling it again (0, the
  /// default: after every accepted step; start() always assembles). A lagged Hessian is still a
  /// bounded model Hessian, which is all the trust-region theory asks for; ρ measures how good it
  /// is and the radius adapts.
  void set_hessian_lag(int lag) { hessian_lag_ = lag; }
  /// The subproblem solver may stop once its model gradient is at most `target`
  /// (TrustRegionQp::set_gradient_target).
  void set_gradient_target(PetscReal target) { qp_->set_gradient_target(target); }

 private:
  /// ‖∇f‖ and finiteness at x_; marks the Hessian due if `force` or it has been kept
  /// `hessian_lag_` times.
  PetscErrorCode assemble_derivatives(bool force);
  /// Assembles a due Hessian at x_ (and hands it to the QP): only when a subproblem needs it, so
  /// that a point left by a coarse correction or at convergence costs no Hessian.
  PetscErrorCode ensure_hessian();
  /// Counts an accepted step at the new x_, f and ∇f, and marks its Hessian due.
  PetscErrorCode accepted();
  Objective& f_;
  Mat H_;
  std::unique_ptr<TrustRegionQp> qp_;
  LevelNorm norm_;
  Vec x_ = nullptr, g_ = nullptr, s_ = nullptr, trial_ = nullptr, g_trial_ = nullptr;
  PetscReal fx_ = 0.0, gnorm_ = 0.0, f_trial_ = 0.0;
  PetscReal trial_measured_ = 0.0;  // f(x) − f(x + s) of the last trial, as last measured
  PetscReal reduction_ = 0.0;       // reduction(): accepted steps since start()
  bool finite_ = false;
  Vec trial_step_ = nullptr;        // s of the last trial point trial_ = x_ + s (not owned)
  bool trial_gradient_ = false;     // g_trial_ holds ∇f at trial_
  bool last_accepted_ = true;       // the last iterate() accepted its step: expect the next to pass
  int hessian_lag_ = 0, kept_ = 0;  // accepted steps the current Hessian has been kept
  bool hessian_due_ = false;        // x_ moved past the Hessian's point: assemble before a QP
  bool hessian_since_start_ = false;  // H_ was assembled after the last start()
  TrustRegionCounters counters_;
};

}  // namespace mlshell
