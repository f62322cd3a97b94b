// d = |(e0 − p) × (e1 − p)|² / |e1 − e0|² (see point_line.hpp).
#include "mlshell/contact/distance/point_line.hpp"

#include <Eigen/Geometry>
#include <stdexcept>

#include "vector_products.hpp"

namespace mlshell {

using namespace contact_detail;

double point_line_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                           const Eigen::Vector3d& e1, Vector9* grad, Matrix9* hess) {
  const Eigen::Vector3d u = e0 - p, v = e1 - p, e = v - u;
  const double D = e.squaredNorm();
  if (!(D > 0.0)) throw std::domain_error("point_line_distance: e0 = e1, no line");
  if (!grad && !hess) return u.cross(v).squaredNorm() / D;
  // In y = (u, v): N = g(u, v), D = |v − u|².
  Vector6 gN, gD;
  Matrix6 hN, hD = Matrix6::Zero();
  const double N = cross_squared_norm(u, v, &gN, hess ? &hN : nullptr);
  gD << -2.0 * e, 2.0 * e;
  if (hess) {
    const Eigen::Matrix3d I2 = 2.0 * Eigen::Matrix3d::Identity();
    hD << I2, -I2, -I2, I2;
  }
  Vector6 gy;
  Matrix6 hy;
  const double d = quotient<6>(N, gN, hN, D, gD, hD, &gy, hess ? &hy : nullptr);
  // u = e0 − p, v = e1 − p.
  Eigen::Matrix<double, 2, 3> C;
  C << -1, 1, 0, -1, 0, 1;
  const Eigen::Matrix<double, 6, 9> A = difference_map<2, 3>(C);
  if (grad) *grad = A.transpose() * gy;
  if (hess) *hess = A.transpose() * hy * A;
  return d;
}

}  // namespace mlshell
