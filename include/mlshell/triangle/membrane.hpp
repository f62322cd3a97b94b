// Membrane energy of one linear (constant-strain) triangle, 9 dofs x = (x0, x1, x2) stacked.
//
// With the edge matrices D̄ = [X1 − X0, X2 − X0] (rest) and D = [x1 − x0, x2 − x0] (deformed),
// both 3×2, the first fundamental forms are Ā = D̄ᵀD̄ and A = DᵀD, and M = Ā⁻¹A (2×2, the right
// Cauchy–Green tensor in the rest basis, mixed components). The energy is τ Ā_t ψ(M) with τ the
// thickness and Ā_t = ½ |(X1 − X0) × (X2 − X0)| = ½ √det Ā the rest area:
//   Neo-Hookean (Progressive Shell Quasistatics, footnote 1; Chen et al. 2018):
//     ψ = μ/2 (tr M − 2 − ln det M) + λ/8 ln²(det M),
//   St. Venant–Kirchhoff, with the Green strain G = ½ (M − I):
//     ψ = μ tr(G²) + λ/2 (tr G)².
// ψ depends on x only through A, so both are invariant under rigid motions of x, including the
// improper ones: a triangle mirrored in 3D has the same A, and since det A = |d₁ × d₂|² ≥ 0 a
// membrane cannot tell "flipped" from "not flipped"; det M = 0 (a collapsed triangle) is the only
// inversion it sees. Orientation is the bending term's business (see hinge_bending.hpp).
#pragma once

#include <Eigen/Core>

#include "mlshell/triangle/element_types.hpp"

namespace mlshell {

/// Rest-state quantities of one triangle. The two must describe the same triangle, as from()
/// builds them: the kernels use det Ā⁻¹ = 1/(2 Ā_t)², accurate where the entries of Ā⁻¹ would
/// cancel (thin triangles).
struct TriangleRest {
  Eigen::Matrix2d metric_inverse;  ///< Ā⁻¹, Ā = D̄ᵀD̄ (symmetric positive definite)
  double area = 0.0;               ///< Ā_t = ½ |(X1 − X0) × (X2 − X0)| = ½ √det Ā
  /// From the rest positions. Throws std::invalid_argument if a position is not finite or the
  /// triangle is degenerate: |(X1 − X0) × (X2 − X0)| ≤ 64 ε |X1 − X0| |X2 − X0|, i.e. zero area
  /// to round-off (ε the machine epsilon), where Ā⁻¹ would be meaningless.
  static TriangleRest from(const Eigen::Vector3d& X0, const Eigen::Vector3d& X1,
                           const Eigen::Vector3d& X2);
};

/// Lamé parameters (as chosen by the caller) and the thickness τ.
struct MembraneParameters {
  double mu = 0.0;
  double lambda = 0.0;
  double thickness = 0.0;
};

/// Neo-Hookean membrane energy τ Ā_t ψ and, where the pointers are not null, its gradient and
/// Hessian in (x0, x1, x2). Returns +infinity, writing neither, when det M ≤ 0 (a collapsed
/// deformed triangle, to round-off: |d₁ × d₂| ≤ 64 ε |d₁| |d₂|, d_k the edges from x0), when a
/// position is not finite or `rest` is not a valid rest state, or when a result would not be finite
/// (never NaN).
double neo_hookean_membrane(const TriangleRest& rest, const MembraneParameters& params,
                            const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                            const Eigen::Vector3d& x2, Vector9* grad, Matrix9* hess);

/// St. Venant–Kirchhoff membrane energy τ Ā_t ψ with optional gradient and Hessian. A polynomial
/// in x, finite for every finite x (collapsed triangles included); +infinity, writing neither,
/// only when a position is not finite or `rest` is not a valid rest state.
double stvk_membrane(const TriangleRest& rest, const MembraneParameters& params,
                     const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                     const Eigen::Vector3d& x2, Vector9* grad, Matrix9* hess);

}  // namespace mlshell
