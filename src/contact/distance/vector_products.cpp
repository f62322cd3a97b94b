// g = |u × v|² and f = w · (u × v) with their derivatives (see vector_products.hpp).
#include "vector_products.hpp"

#include <Eigen/Geometry>
#include <stdexcept>

namespace mlshell::contact_detail {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

double cross_squared_norm(const Eigen::Vector3d& u, const Eigen::Vector3d& v, Vector6* grad,
                          Matrix6* hess) {
  const Eigen::Vector3d n = u.cross(v);
  if (grad) *grad << 2.0 * v.cross(n), 2.0 * n.cross(u);
  if (hess) {
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d uv =
        4.0 * u * v.transpose() - 2.0 * v * u.transpose() - 2.0 * u.dot(v) * I;
    hess->block<3, 3>(0, 0) = 2.0 * (v.squaredNorm() * I - v * v.transpose());
    hess->block<3, 3>(3, 3) = 2.0 * (u.squaredNorm() * I - u * u.transpose());
    hess->block<3, 3>(0, 3) = uv;
    hess->block<3, 3>(3, 0) = uv.transpose();
  }
  return n.squaredNorm();
}

double triple_product(const Eigen::Vector3d& w, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                      Vector9* grad, Matrix9* hess) {
  const Eigen::Vector3d n = u.cross(v);
  if (grad) *grad << n, v.cross(w), w.cross(u);
  if (hess) {
    hess->setZero();
    const Eigen::Matrix3d wu = -cross_matrix(v), wv = cross_matrix(u), uv = -cross_matrix(w);
    hess->block<3, 3>(0, 3) = wu;
    hess->block<3, 3>(3, 0) = wu.transpose();
    hess->block<3, 3>(0, 6) = wv;
    hess->block<3, 3>(6, 0) = wv.transpose();
    hess->block<3, 3>(3, 6) = uv;
    hess->block<3, 3>(6, 3) = uv.transpose();
  }
  return w.dot(n);
}

double squared_normal_component(const Eigen::Vector3d& w, const Eigen::Vector3d& u,
                                const Eigen::Vector3d& v, Vector9* grad, Matrix9* hess) {
  const bool derivatives = grad || hess;
  Vector9 gf;
  Matrix9 hf;
  const double f = triple_product(w, u, v, derivatives ? &gf : nullptr, hess ? &hf : nullptr);
  Vector6 gg6;
  Matrix6 hg6;
  const double g = cross_squared_norm(u, v, derivatives ? &gg6 : nullptr, hess ? &hg6 : nullptr);
  if (!(g > 0.0)) throw std::domain_error("squared_normal_component: u × v = 0, no plane");
  if (!derivatives) return f * f / g;
  // N = f², D = g (which does not depend on w), both in (w, u, v).
  Vector9 gN = 2.0 * f * gf, gD = Vector9::Zero();
  gD.tail<6>() = gg6;
  Matrix9 hN = Matrix9::Zero(), hD = Matrix9::Zero();
  if (hess) {
    hN = 2.0 * gf * gf.transpose() + 2.0 * f * hf;
    hD.bottomRightCorner<6, 6>() = hg6;
  }
  return quotient<9>(f * f, gN, hN, g, gD, hD, grad, hess);
}

}  // namespace mlshell::contact_detail
