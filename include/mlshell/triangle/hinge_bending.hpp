// Discrete hinge bending (Grinspun et al. 2003, "Discrete Shells"; Tamstorf & Grinspun 2013),
// 12 dofs x = (x0, x1, x2, x3) stacked.
//
// A hinge is the edge x0–x1 shared by the triangles (x0, x1, x2) and (x1, x0, x3), both
// counter-clockwise seen from the normal side (consistently oriented); x2, x3 are the opposite
// vertices. With e = x1 − x0, ê = e/|e| and the unnormalised normals
//   n₁ = (x1 − x0) × (x2 − x0),   n₂ = (x3 − x0) × (x1 − x0),
// the dihedral angle is the rotation about ê that takes n₁ to n₂:
//   θ = atan2((n₁ × n₂)·ê, n₁·n₂) ∈ (−π, π],   θ = 0 for a flat hinge.
// Sign convention: θ > 0 where the hinge is convex seen from the normal side (a "mountain": the
// wings bend away from the normals, as at every edge of a convex closed surface with outward
// normals); θ < 0 for a "valley", where the wings fold toward the normal side. E.g. with
// x0 = 0, x1 = (1, 0, 0), x2 = (0.5, 1, 0) (n₁ = +z): x3 = (0.5, 0, −1) gives θ = +π/2 and
// x3 = (0.5, 0, 1) gives θ = −π/2; θ → ±π as the wings close onto each other.
//
// The energy is w (θ − θ̄)², with θ − θ̄ wrapped into (−π, π], and the weight
//   w = 3 |ē|² / (Ā₁ + Ā₂) · k,   k = E τ³ / (24 (1 − ν²)),
// from the rest edge length |ē| and rest triangle areas Ā₁, Ā₂.
#pragma once

#include <Eigen/Core>

#include "mlshell/triangle/element_types.hpp"

namespace mlshell {

/// The signed dihedral angle θ of the file comment. For a zero edge or a zero normal the angle
/// is undefined and atan2's value at the origin, 0, is returned (hinge_bending detects this).
double dihedral_angle(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                      const Eigen::Vector3d& x2, const Eigen::Vector3d& x3);

/// θ of the file comment for x = (x0, x1, x2, x3) and, where the pointers are not null, its
/// gradient and Hessian in the stacked positions (closed form, valid at θ ≈ 0 and θ ≈ ±π).
/// False, writing nothing, for a zero edge or a zero normal.
bool dihedral_angle_derivatives(const Eigen::Vector3d x[4], double& theta, Vector12* grad,
                                Matrix12* hess);

/// d wrapped into (−π, π] (the angle deviation θ − θ̄ of a hinge).
double wrap_angle(double d);

/// The bending stiffness k = E τ³ / (24 (1 − ν²)).
double hinge_stiffness(double E, double nu, double thickness);

/// Rest-state quantities of one hinge.
struct HingeRest {
  double angle = 0.0;   ///< θ̄
  double weight = 0.0;  ///< w = 3 |ē|² / (Ā₁ + Ā₂) · k
  /// From the rest positions and k (hinge_stiffness). Throws std::invalid_argument if a position
  /// is not finite, the rest edge has zero length, or a rest triangle has zero area (to
  /// round-off, the criterion of TriangleRest::from).
  static HingeRest from(const Eigen::Vector3d& X0, const Eigen::Vector3d& X1,
                        const Eigen::Vector3d& X2, const Eigen::Vector3d& X3, double stiffness);
};

/// w (θ − θ̄)² with θ − θ̄ wrapped into (−π, π], and where the pointers are not null its gradient
/// and Hessian in (x0, x1, x2, x3). Returns +infinity, writing neither, when the deformed edge or
/// a deformed normal has zero length, a position is not finite, or a result would not be finite.
/// At θ − θ̄ = ±π (the hinge turned inside out relative to its rest state) the energy is
/// continuous but its gradient jumps sign.
double hinge_bending(const HingeRest& rest, const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                     const Eigen::Vector3d& x2, const Eigen::Vector3d& x3, Vector12* grad,
                     Matrix12* hess);

}  // namespace mlshell
