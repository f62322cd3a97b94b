// Fixed-size Eigen types of the contact kernels: a stencil of 2, 3 or 4 vertices has 6, 9 or 12
// dofs, its vertices' positions stacked in the order the function's arguments name them
// (point–point (p, q); point–edge (p, e0, e1); point–triangle (p, t0, t1, t2); edge–edge
// (ea0, ea1, eb0, eb1)). No equations here.
#pragma once

#include <Eigen/Core>

#include "mlshell/triangle/element_types.hpp"

namespace mlshell {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

}  // namespace mlshell
