// Point–segment squared distance by type (see point_edge.hpp).
#include "mlshell/contact/distance/point_edge.hpp"

#include "mlshell/contact/distance/point_line.hpp"
#include "mlshell/contact/distance/point_point.hpp"
#include "vector_products.hpp"

namespace mlshell {

using namespace contact_detail;

PointEdgeDistanceType point_edge_distance_type(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                                               const Eigen::Vector3d& e1) {
  const Eigen::Vector3d e = e1 - e0;
  const double along = (p - e0).dot(e), length2 = e.squaredNorm();
  if (along <= 0.0 || !(length2 > 0.0)) return PointEdgeDistanceType::P_E0;
  if (along >= length2) return PointEdgeDistanceType::P_E1;
  return PointEdgeDistanceType::P_E;
}

double point_edge_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                           const Eigen::Vector3d& e1, PointEdgeDistanceType type, Vector9* grad,
                           Matrix9* hess) {
  if (type == PointEdgeDistanceType::P_E) return point_line_distance(p, e0, e1, grad, hess);
  const bool first = type == PointEdgeDistanceType::P_E0;
  Vector6 g;
  Matrix6 H;
  const double d =
      point_point_distance(p, first ? e0 : e1, grad ? &g : nullptr, hess ? &H : nullptr);
  const int to[2] = {0, first ? 1 : 2};
  scatter<2, 3>(g, H, to, grad, hess);
  return d;
}

double point_edge_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                           const Eigen::Vector3d& e1) {
  return point_edge_distance(p, e0, e1, point_edge_distance_type(p, e0, e1));
}

}  // namespace mlshell
