// Fixed-size Eigen types shared by the per-triangle (9 dofs: x0, x1, x2 stacked) and per-hinge
// (12 dofs: x0, x1, x2, x3 stacked) energy kernels. No equations here.
#pragma once

#include <Eigen/Core>

namespace mlshell {

using Vector9 = Eigen::Matrix<double, 9, 1>;
using Matrix9 = Eigen::Matrix<double, 9, 9>;
using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

}  // namespace mlshell
