// d = |p − q|² (see point_point.hpp).
#include "mlshell/contact/distance/point_point.hpp"

namespace mlshell {

double point_point_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& q, Vector6* grad,
                            Matrix6* hess) {
  const Eigen::Vector3d r = p - q;
  if (grad) *grad << 2.0 * r, -2.0 * r;
  if (hess) {
    const Eigen::Matrix3d I2 = 2.0 * Eigen::Matrix3d::Identity();
    *hess << I2, -I2, -I2, I2;
  }
  return r.squaredNorm();
}

}  // namespace mlshell
