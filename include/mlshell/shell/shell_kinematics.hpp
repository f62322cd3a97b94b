// Kirchhoff–Love shell kinematics (paper §3, eq. 3.1): r = x + ξ³ a₃ with the Green–Lagrange
// strain through the thickness E(ξ³) = ε + ξ³ κ, where (covariant components, α, β ∈ {1, 2})
//   ε_αβ = ½ (a_α·a_β − ā_α·ā_β)     membrane strain,
//   κ_αβ = ā_αβ·ā₃ − a_αβ·a₃         change of curvature,
// and the quadratic term in ξ³ is dropped as usual for thin shells. The reduced strain in the
// material frame is Ẽ = Oᵀ E O (eq. 3.3): Ẽ_ij = (o_i·Ā^α)(o_j·Ā^β) E_αβ with the contravariant
// reference basis Ā^α. The energy per reference area is ∫ ψ(Ẽ(ξ³)) dξ³ over [−τ/2, τ/2] (Gauss
// points), times the area element J̄ = |ā₁ × ā₂| of the midsurface.
//
// Displacements, not positions, are the unknowns: a_α = ā_α + δ_α, so that ε is computed as
// ā_(α·δ_β) + ½ δ_α·δ_β without the cancellation of a·a − ā·ā at small strains.
#pragma once

#include <Eigen/Core>

#include "mlshell/shell/material.hpp"

namespace mlshell {

/// The 15 local surface quantities: δ_1, δ_2, δ_11, δ_12, δ_22 (3 each), in this order.
constexpr int kSurfaceQuantities = 15;
using Vector15 = Eigen::Matrix<double, 15, 1>;
using Matrix15 = Eigen::Matrix<double, 15, 15>;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// Reference midsurface quantities at one quadrature point.
struct ShellReference {
  Eigen::Vector3d a[5];    ///< ā_1, ā_2, ā_11, ā_12, ā_22
  Eigen::Vector3d normal;  ///< ā_3
  double area = 0.0;       ///< J̄ = |ā_1 × ā_2|
  Eigen::Matrix3d T;       ///< (E11, E12, E22) → (Ẽ11, Ẽ22, Ẽ12)
  /// From the reference derivatives and the warp direction (projected to the tangent plane).
  static ShellReference from(const Eigen::Vector3d a[5], const Eigen::Vector3d& warp);
};

/// Through-thickness integration of a material: W(ε, κ) per unit reference area.
class ShellSection {
 public:
  ShellSection(const Material& material, double thickness, int points);
  /// W and its derivatives in s = (ε11, ε12, ε22, κ11, κ12, κ22).
  double energy(const ShellReference& ref, const Vector6& s, Vector6* g, Matrix6* H) const;
  double thickness() const { return thickness_; }
  /// Adds the status and ψ of every through-thickness point at strains s to the report.
  void inspect(const ShellReference& ref, const Vector6& s, MaterialReport& report) const;

 private:
  const Material& material_;
  double thickness_;
  std::vector<double> z_, w_;  // Gauss points ξ³ and weights (summing to τ)
};

/// Generalised strains s(δ) in the 15 surface quantities; optionally their Jacobian ds and the
/// weighted Hessian hw = Σ_i weights_i ∇²s_i (what the chain rule needs), in closed form.
void shell_strains(const ShellReference& ref, const double delta[15], Vector6& s,
                   Eigen::Matrix<double, 6, 15>* ds, const Vector6* weights, Matrix15* hw);

/// Energy per unit reference area (times J̄) at one point and its derivatives in δ.
double shell_point_energy(const ShellReference& ref, const ShellSection& section,
                          const double delta[15], Vector15* g, Matrix15* H);

}  // namespace mlshell
