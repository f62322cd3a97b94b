// The cross-product matrix [x]×, with [x]× y = x × y: the derivative of a cross product,
// d(a × b) = [a]× db − [b]× da, used by the closed-form Hessians of shells and triangles.
#pragma once

#include <Eigen/Core>

namespace mlshell {

inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& x) {
  Eigen::Matrix3d m;
  m << 0, -x.z(), x.y(), x.z(), 0, -x.x(), -x.y(), x.x(), 0;
  return m;
}

}  // namespace mlshell
