// d = ((p − t0) · n)² / |n|² (see point_plane.hpp).
#include "mlshell/contact/distance/point_plane.hpp"

#include "vector_products.hpp"

namespace mlshell {

using namespace contact_detail;

double point_plane_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                            const Eigen::Vector3d& t1, const Eigen::Vector3d& t2, Vector12* grad,
                            Matrix12* hess) {
  Vector9 gy;
  Matrix9 hy;
  const double d = squared_normal_component(p - t0, t1 - t0, t2 - t0, grad ? &gy : nullptr,
                                            hess ? &hy : nullptr);
  // w = p − t0, u = t1 − t0, v = t2 − t0.
  Eigen::Matrix<double, 3, 4> C;
  C << 1, -1, 0, 0, 0, -1, 1, 0, 0, -1, 0, 1;
  const Eigen::Matrix<double, 9, 12> A = difference_map<3, 4>(C);
  if (grad) *grad = A.transpose() * gy;
  if (hess) *hess = A.transpose() * hy * A;
  return d;
}

}  // namespace mlshell
