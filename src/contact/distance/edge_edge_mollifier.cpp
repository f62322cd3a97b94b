// The edge–edge mollifier m(c) (see edge_edge_mollifier.hpp).
#include "mlshell/contact/distance/edge_edge_mollifier.hpp"

#include <Eigen/Geometry>

#include "vector_products.hpp"

namespace mlshell {

using namespace contact_detail;

double edge_edge_mollifier_threshold(const Eigen::Vector3d& rest_ea0,
                                     const Eigen::Vector3d& rest_ea1,
                                     const Eigen::Vector3d& rest_eb0,
                                     const Eigen::Vector3d& rest_eb1) {
  return 1e-3 * (rest_ea1 - rest_ea0).squaredNorm() * (rest_eb1 - rest_eb0).squaredNorm();
}

double edge_edge_cross_squared_norm(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                    const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1,
                                    Vector12* grad, Matrix12* hess) {
  Vector6 gy;
  Matrix6 hy;
  const double c =
      cross_squared_norm(ea1 - ea0, eb1 - eb0, grad ? &gy : nullptr, hess ? &hy : nullptr);
  // u = ea1 − ea0, v = eb1 − eb0.
  Eigen::Matrix<double, 2, 4> C;
  C << -1, 1, 0, 0, 0, 0, -1, 1;
  const Eigen::Matrix<double, 6, 12> A = difference_map<2, 4>(C);
  if (grad) *grad = A.transpose() * gy;
  if (hess) *hess = A.transpose() * hy * A;
  return c;
}

bool edge_edge_mollifier_active(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1,
                                double eps_x) {
  return edge_edge_cross_squared_norm(ea0, ea1, eb0, eb1) < eps_x;
}

double edge_edge_mollifier(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                           const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1, double eps_x,
                           Vector12* grad, Matrix12* hess) {
  Vector12 gc;
  Matrix12 hc;
  const double c = edge_edge_cross_squared_norm(ea0, ea1, eb0, eb1, grad || hess ? &gc : nullptr,
                                                hess ? &hc : nullptr);
  if (!(c < eps_x)) {
    if (grad) grad->setZero();
    if (hess) hess->setZero();
    return 1.0;
  }
  const double r = c / eps_x;
  const double dm = 2.0 * (1.0 - r) / eps_x, d2m = -2.0 / (eps_x * eps_x);
  if (grad) *grad = dm * gc;
  if (hess) *hess = d2m * gc * gc.transpose() + dm * hc;
  return (2.0 - r) * r;
}

}  // namespace mlshell
