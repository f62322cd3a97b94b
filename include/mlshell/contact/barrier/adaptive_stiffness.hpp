// Adaptive barrier stiffness κ (IPC, Li et al. 2020 and its supplement; the IPC Toolkit's
// initial_barrier_stiffness and update_barrier_stiffness, whose formulas these follow), for the
// offset barrier b_ξ of barrier.hpp. All distances d below are squared distances.
//
// Lower bound, from the barrier's curvature at a tiny distance and the lumped masses: with the
// probe d₀ = (ξ + 10⁻⁸ L)² (L the diagonal of the scene's bounding box; the IPC Toolkit's
// d₀ = (10⁻⁸ L + d_min)²), and 4 d₀ b_ξ''(d₀) the barrier's curvature in the distance √d there
// (∂²b/∂(√d)² = 4 d b'' + 2 b', the second term dropped as IPC does),
//   κ_min = s m̄ / (4 d₀ b_ξ''(d₀)),   s = 10¹¹,   m̄ the average lumped nodal mass,
//   κ_max = 100 κ_min.
// Where the probe lies outside the barrier's range (10⁻⁸ L ≥ ĝ) it is put at half the gap,
// d₀ = (ξ + ĝ/2)² (mlshell's choice; the IPC Toolkit marks its own fallback untested).
// Initial κ: the value that best balances the barrier's gradient g_b against the elastic
// (incremental potential's) gradient g_e in the least-squares sense,
//   κ = −⟨g_b, g_e⟩ / |g_b|²   (κ = 1 where g_b = 0),   clamped to [κ_min, κ_max].
// Update after each Newton iteration: while the minimum distance stays within ε L of contact,
// the gap below ε L and shrinking, κ doubles up to κ_max:
//   d_prev < (ξ + εL)²  and  d < (ξ + εL)²  and  d < d_prev   ⟹   κ ← min(κ_max, 2κ),
// ε = 10⁻⁹ (IPC's default). With ξ = 0 these are the IPC Toolkit's formulas.
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/barrier/barrier.hpp"

namespace mlshell {

/// κ_min = s m̄ / (4 d₀ b_ξ''(d₀)) of the file comment (κ_max = 100 κ_min). Throws
/// std::invalid_argument unless bbox_diagonal, average_mass and scale are finite and positive.
double min_barrier_stiffness(const ContactBarrier& barrier, double bbox_diagonal,
                             double average_mass, double scale = 1e11);

/// The initial κ of the file comment from the two scalars ⟨g_b, g_e⟩ and |g_b|² (summed over
/// ranks by the caller); writes κ_max = 100 κ_min to *max_stiffness.
double initial_barrier_stiffness(const ContactBarrier& barrier, double bbox_diagonal,
                                 double average_mass, double barrier_dot_energy_gradient,
                                 double barrier_gradient_squared_norm, double* max_stiffness,
                                 double scale = 1e11);

/// The same from the two gradients.
double initial_barrier_stiffness(const ContactBarrier& barrier, double bbox_diagonal,
                                 double average_mass,
                                 const Eigen::Ref<const Eigen::VectorXd>& grad_energy,
                                 const Eigen::Ref<const Eigen::VectorXd>& grad_barrier,
                                 double* max_stiffness, double scale = 1e11);

/// κ after an iteration whose minimum squared distance went from prev_min_distance to
/// min_distance: doubled (capped at max_stiffness) while both are below (ξ + ε L)² and it
/// shrinks, else unchanged.
double update_barrier_stiffness(double prev_min_distance, double min_distance, double max_stiffness,
                                double stiffness, double bbox_diagonal, double thickness = 0.0,
                                double epsilon = 1e-9);

}  // namespace mlshell
