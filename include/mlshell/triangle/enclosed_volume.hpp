// Signed volume contribution of one triangle of a closed, outward-oriented triangle surface,
// 9 dofs x = (x0, x1, x2) stacked:
//   V_t = x0·(x1 × x2) / 6,
// the signed volume of the tetrahedron (0, x0, x1, x2). By the divergence theorem Σ_t V_t is the
// volume enclosed by the surface (positive for counter-clockwise triangles seen from outside).
// A single V_t depends on the origin: translating by c gives V_t + c·n_t/6 with
// n_t = (x1 − x0) × (x2 − x0). Only the sum over a closed surface, where Σ_t n_t = 0, is
// translation-invariant; the total of an open surface is not a volume.
#pragma once

#include <Eigen/Core>

#include "mlshell/triangle/element_types.hpp"

namespace mlshell {

/// V_t and, where the pointers are not null, its gradient
///   ∂V_t/∂x0 = x1 × x2 / 6,  ∂V_t/∂x1 = x2 × x0 / 6,  ∂V_t/∂x2 = x0 × x1 / 6
/// and its (constant-coefficient, indefinite, zero-diagonal) Hessian.
double triangle_volume(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                       const Eigen::Vector3d& x2, Vector9* grad, Matrix9* hess);

}  // namespace mlshell
