// d = ((eb0 − ea0) · n)² / |n|² (see line_line.hpp).
#include "mlshell/contact/distance/line_line.hpp"

#include "vector_products.hpp"

namespace mlshell {

using namespace contact_detail;

double line_line_distance(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                          const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1, Vector12* grad,
                          Matrix12* hess) {
  Vector9 gy;
  Matrix9 hy;
  const double d = squared_normal_component(eb0 - ea0, ea1 - ea0, eb1 - eb0, grad ? &gy : nullptr,
                                            hess ? &hy : nullptr);
  // w = eb0 − ea0, u = ea1 − ea0, v = eb1 − eb0.
  Eigen::Matrix<double, 3, 4> C;
  C << -1, 0, 1, 0, -1, 1, 0, 0, 0, 0, -1, 1;
  const Eigen::Matrix<double, 9, 12> A = difference_map<3, 4>(C);
  if (grad) *grad = A.transpose() * gy;
  if (hess) *hess = A.transpose() * hy * A;
  return d;
}

}  // namespace mlshell
