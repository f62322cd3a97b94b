// mlshell's own TAO solvers. After registration, `-tao_type rmtr` selects the recursive
// multilevel trust region (paper Alg. 4.2/4.3; solvers/tao_rmtr.cpp lists its options),
// `-tao_type tr` Local_TR (Alg. 4.1; solvers/tao_trust_region.cpp), and `-tao_type dampednewton`
// and `-tao_type linearized` the baselines of §7.4.1 (solvers/tao_newton_baselines.cpp).
#pragma once

#include <petsctao.h>

#include <string>
#include <vector>

#include "mlshell/multilevel_objective.hpp"

namespace mlshell {

/// Work counts of the last solve of a `tr` solver.
struct TrustRegionStatistics {
  long accepted = 0;    ///< successful iterations
  long qp_solves = 0;   ///< subproblem solves
  long objectives = 0;  ///< trial-point evaluations
  long hessians = 0;    ///< Hessian assemblies
};

/// Work of one level of the last RMTR solve (level 0 the coarsest used).
struct RmtrLevelStatistics {
  PetscInt dofs = 0;
  long successful = 0;  ///< π^l of eq. (7.2): accepted steps that survived to the finest level
  long assemblies = 0;  ///< Hessian assemblies (Q^l of eq. 7.3; only where a QP needed one)
  long qp_solves = 0;
  long factorisations = 0;   ///< sparse direct factorisations (Dogleg's Newton points)
  long objectives = 0;       ///< trial-point evaluations
  long coarse_accepted = 0;  ///< prolongated coarse corrections accepted on this level
  long coarse_rejected = 0;  ///< ... rejected by the multilevel ratio (4.11)
  /// ... shortened first, to fit the radius (eq. 4.7; only a nonlinear prolongation needs it)
  long coarse_shortened = 0;
};

/// Statistics of the last solve of a Tao of type "rmtr".
struct RmtrStatistics {
  std::vector<RmtrLevelStatistics> levels;
  long cycles = 0;
  /// V-cycles of the full-multigrid start on the coarser levels (-tao_rmtr_fmg_cycles).
  long fmg_cycles = 0;
  /// Subspace steps after V-cycles (-tao_rmtr_subspace), on every level: accepted, rejected.
  long subspace_accepted = 0, subspace_rejected = 0;
  /// W of eq. (7.3): Σ_l 2^{−2(L−l)} Q^l, for assemblies and for QP solves.
  double assembly_work_units = 0.0, qp_work_units = 0.0;
  /// Checks of the theory, over all coarse-level corrections: max ‖I s‖_l / Δ^l (eq. 4.7, must
  /// not exceed 1), and with -tao_rmtr_check_consistency max ‖∇h^{l−1}(x₀) − R∇h^l‖ /
  /// (‖R∇h^l‖ + ‖R∇h^l − ∇f^{l−1}(x₀)‖) at the start of every coarse solve (eq. 4.5: round-off
  /// relative to the terms that cancel).
  double max_correction_ratio = 0.0, max_consistency_error = 0.0;
  /// With -tao_rmtr_check_consistency, also the largest relative misfit of the coarse starts,
  /// ‖S x₀^{l−1} − x^l‖ / ‖x^l‖ (eq. 4.6): which projection ran shows here (least squares is the
  /// smallest; a start that is not a projection of the fine iterate is of order 1).
  double max_projection_misfit = 0.0;
  /// The largest |f^{l−1}(x₀^{l−1})| over the coarse starts of first-order models, the value of
  /// the coarse energy where each coarse solve began: far above the solve's own energies when
  /// a projected start distorts the coarse surface (-tao_rmtr_coarse_start).
  double max_coarse_start_energy = 0.0;
  /// Sums the counts of another solve on the same levels (for totals over time steps).
  RmtrStatistics& operator+=(const RmtrStatistics& other);
};

/// Registers the TAO types "tr" and "rmtr" (idempotent).
PetscErrorCode register_trust_region_tao_types();

/// Gives a Tao of type "rmtr" the levels to work on; the finest must be the problem set on the
/// Tao. Without it, RMTR runs on the Tao's problem alone (one level: Local_TR with Dogleg). The
/// object must outlive the solves.
PetscErrorCode rmtr_set_levels(Tao tao, MultilevelObjective* levels);

/// Statistics of the last solve of a Tao of type "rmtr".
PetscErrorCode rmtr_statistics(Tao tao, RmtrStatistics* stats);

/// Registers the TAO types "dampednewton" and "linearized" (idempotent).
PetscErrorCode register_newton_baseline_tao_types();
/// Registers "pnewton", projected Newton with a backtracking line search (paper 2 §4.5;
/// tao_projected_newton.cpp).
PetscErrorCode register_projected_newton_tao_type();

/// Why the last solve of `tao` stopped: TAO's reason, or CONVERGED_LIMITING_ACCURACY when a
/// "tr" or "rmtr" solve ended at the round-off floor, or DIVERGED_STAGNATION when one stagnated
/// far above its tolerance (StoppingRule, local_trust_region.hpp).
std::string trust_region_converged_reason(Tao tao);

/// Tells a "tr" or "rmtr" solver which objective its callbacks evaluate, so that it can ask
/// for the rounding error of f and for step limits (Objective::max_step), and report accepted
/// iterates (no effect on other types). Call before TaoSetUp.
PetscErrorCode trust_region_set_error_source(Tao tao, Objective* source);

/// Statistics of the last solve of a Tao of type "tr".
PetscErrorCode trust_region_statistics(Tao tao, TrustRegionStatistics* stats);

}  // namespace mlshell
