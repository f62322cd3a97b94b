// Squared distance between two points (IPC, Li et al. 2020; the point–point type of the
// point–triangle and edge–edge distances), 6 dofs x = (p, q):
//   d = |p − q|²,   ∇d = 2 (p − q, q − p),   ∇²d = 2 [[I, −I], [−I, I]].
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/contact_types.hpp"

namespace mlshell {

/// d = |p − q|² and, where the pointers are not null, its gradient and Hessian in (p, q).
double point_point_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                            Vector6* grad = nullptr, Matrix6* hess = nullptr);

}  // namespace mlshell
