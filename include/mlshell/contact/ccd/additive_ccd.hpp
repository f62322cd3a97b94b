// Additive continuous collision detection (ACCD; Li, Kaufman, Jiang 2021, "Codimensional
// Incremental Potential Contact", §5 and its Algorithm 1; the IPC Toolkit's additive_ccd.cpp
// writes the same loop with the rescaling η below). A stencil moves along the straight
// trajectory x(t) = x₀ + t Δx, t ∈ [0, t_max] (the positions of its 2, 3 or 4 vertices stacked
// as contact_types.hpp says); its primitives must stay apart by a thickness ξ ≥ 0 (a distance,
// as the barrier's ContactBarrier::thickness). With d the squared distance of distance/*.hpp and
// D = √d, the gap is
//   g(d) = D − ξ = (d − ξ²) / (D + ξ)            (the right form avoids cancelling √d − ξ).
//
// 1. Subtract the mean displacement from every vertex's Δx_i (a rigid translation moves no
//    distance) and bound the speed at which the gap can close:
//      point–triangle  l_p = |Δp| + max_k |Δt_k|,       edge–edge   l_p = max|Δa_i| + max|Δb_j|,
//      point–edge      l_p = |Δp| + max_k |Δe_k|,       point–point l_p = |Δp| + |Δq|.
//    Every point of a primitive is a convex combination of its vertices, so the relative
//    displacement of any two points, one on each primitive, is at most l_p per unit t, and
//    D(t + τ) ≥ D(t) − τ l_p. l_p = 0 means a rigid translation: no collision.
// 2. From t = 0 advance by the step that the bound proves safe, a fraction η of it,
//      t_l = η g(d) / l_p,        so that    g(d(t + t_l)) ≥ (1 − η) g(d(t)) > 0,
//    re-evaluating d at each new t, until the gap has closed to a fraction of its start,
//      g(d(t + t_l)) < (1 − η) g(d₀)     (never at the first step, so toi > 0 when g(d₀) > 0),
//    which reports a possible collision at toi = t: every configuration in [0, toi + t_l] is
//    separated by more than ξ, the one at toi by at least (1 − η) g(d₀). If t + t_l reaches
//    t_max first, [0, t_max] is safe: no collision.
// η = 0.9 is the IPC Toolkit's default "conservative rescaling"; in C-IPC's and PSQ's terms the
// stopping fraction is s = r = 1 − η = 0.1.
//
// Iteration cap. Where the primitives slide past each other at a small gap the gap hardly
// closes and each step is ≈ η g/l_p, so reaching t_max takes ≈ l_p t_max / (η g) iterations
// (10⁸ for a point gliding 1 over a triangle at 10⁻⁸). At `max_iterations` the loop stops
// and reports a possible collision at the t reached so far, which the steps proved safe; each
// step before the stop is at least η (1 − η) g(d₀) / l_p, so the capped toi is at least
// max_iterations · η (1 − η) g(d₀) / l_p. The default 10⁶ (the IPC Toolkit's default iteration
// limit for its CCD) costs about 0.1 s for one capped pair and needs a gap below 10⁻⁶ of the
// relative displacement, which the barrier keeps well away from.
//
// Floating point: a step's bound holds in exact arithmetic; should a re-evaluated gap come out
// ≤ 0 anyway, the loop stops and reports a possible collision at the last t it proved safe.
// Like the IPC Toolkit's, this CCD is not provably conservative in floating point, but its
// (1 − η) g(d₀) margin absorbs the rounding of the distance kernels.
// Inputs must be finite (x₀ + t_max Δx included); the functions throw std::invalid_argument
// otherwise, so no NaN or ∞ leaves them.
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/contact_types.hpp"

namespace mlshell {

/// The parameters of the loop of the file comment.
struct AdditiveCcdOptions {
  double conservative_rescaling = 0.9;  ///< η ∈ (0, 1); PSQ's and C-IPC's s = 1 − η
  long max_iterations = 1'000'000;      ///< the cap, ≥ 1

  /// Throws std::invalid_argument unless 0 < η < 1 and max_iterations ≥ 1.
  void validate() const;
};

/// What additive CCD found along x₀ + t Δx, t ∈ [0, t_max].
struct CcdResult {
  /// False: no configuration in [0, t_max] comes within ξ. True: one may (a false positive is
  /// possible, a false negative is not meant to be).
  bool may_collide = false;
  /// The largest t the loop proved safe: t_max without a collision; otherwise a time in
  /// [0, t_max) whose configuration is apart by more than ξ (0 if d₀ ≤ ξ² already).
  double toi = 0.0;
  long iterations = 0;  ///< distance evaluations after the first
  bool capped = false;  ///< stopped by max_iterations (may_collide is then true)
};

/// Point–point (p, q): x = (p, q), Δx their displacements.
CcdResult point_point_ccd(const Vector6& x0, const Vector6& dx, double thickness, double t_max,
                          const AdditiveCcdOptions& options = {});
/// Point–edge (p, e0, e1).
CcdResult point_edge_ccd(const Vector9& x0, const Vector9& dx, double thickness, double t_max,
                         const AdditiveCcdOptions& options = {});
/// Point–triangle (p, t0, t1, t2).
CcdResult point_triangle_ccd(const Vector12& x0, const Vector12& dx, double thickness, double t_max,
                             const AdditiveCcdOptions& options = {});
/// Edge–edge (ea0, ea1, eb0, eb1).
CcdResult edge_edge_ccd(const Vector12& x0, const Vector12& dx, double thickness, double t_max,
                        const AdditiveCcdOptions& options = {});

}  // namespace mlshell
