// mlshell's own TAO solvers. After registration, `-tao_type tr` selects Local_TR (paper
// Alg. 4.1; solvers/tao_trust_region.cpp lists its options), and `-tao_type dampednewton` and
// `-tao_type linearized` the baselines of §7.4.1 (solvers/tao_newton_baselines.cpp).
#pragma once

#include <petsctao.h>

namespace mlshell {

/// Work counts of the last solve of a `tr` solver.
struct TrustRegionStatistics {
  long accepted = 0;    ///< successful iterations
  long qp_solves = 0;   ///< subproblem solves
  long objectives = 0;  ///< trial-point evaluations
  long hessians = 0;    ///< Hessian assemblies
};

/// Registers the TAO type "tr" (idempotent).
PetscErrorCode register_trust_region_tao_types();

/// Registers the TAO types "dampednewton" and "linearized" (idempotent).
PetscErrorCode register_newton_baseline_tao_types();

/// Statistics of the last solve of a Tao of type "tr".
PetscErrorCode trust_region_statistics(Tao tao, TrustRegionStatistics* stats);

}  // namespace mlshell
