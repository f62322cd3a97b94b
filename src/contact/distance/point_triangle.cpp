// Point–triangle squared distance by type (see point_triangle.hpp).
#include "mlshell/contact/distance/point_triangle.hpp"

#include <Eigen/Geometry>

#include "mlshell/contact/distance/point_edge.hpp"
#include "mlshell/contact/distance/point_line.hpp"
#include "mlshell/contact/distance/point_plane.hpp"
#include "mlshell/contact/distance/point_point.hpp"
#include "vector_products.hpp"

namespace mlshell {

using namespace contact_detail;
using Type = PointTriangleDistanceType;

PointTriangleDistanceType point_triangle_distance_type(const Eigen::Vector3d& p,
                                                       const Eigen::Vector3d& t0,
                                                       const Eigen::Vector3d& t1,
                                                       const Eigen::Vector3d& t2) {
  const Eigen::Vector3d t[3] = {t0, t1, t2};
  const Eigen::Vector3d n = (t1 - t0).cross(t2 - t0);
  if (n.squaredNorm() > 0.0) {
    bool inside = true;
    for (int i = 0; i < 3 && inside; ++i)
      inside = (t[(i + 1) % 3] - t[i]).cross(p - t[i]).dot(n) >= 0.0;
    if (inside) return Type::P_T;
  }
  // The closest point is on the boundary: the nearest edge, and where on it.
  double best = 0.0;
  Type type = Type::P_T0;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d &a = t[i], &b = t[(i + 1) % 3];
    const PointEdgeDistanceType on = point_edge_distance_type(p, a, b);
    const double d = point_edge_distance(p, a, b, on);
    if (i > 0 && !(d < best)) continue;
    best = d;
    if (on == PointEdgeDistanceType::P_E)
      type = static_cast<Type>(static_cast<int>(Type::P_E0) + i);
    else
      type = static_cast<Type>(on == PointEdgeDistanceType::P_E0 ? i : (i + 1) % 3);
  }
  return type;
}

double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                               const Eigen::Vector3d& t1, const Eigen::Vector3d& t2,
                               PointTriangleDistanceType type, Vector12* grad, Matrix12* hess) {
  const Eigen::Vector3d* t[3] = {&t0, &t1, &t2};
  switch (type) {
    case Type::P_T0:
    case Type::P_T1:
    case Type::P_T2: {
      const int i = static_cast<int>(type) - static_cast<int>(Type::P_T0);
      Vector6 g;
      Matrix6 H;
      const double d = point_point_distance(p, *t[i], grad ? &g : nullptr, hess ? &H : nullptr);
      const int to[2] = {0, 1 + i};
      scatter<2, 4>(g, H, to, grad, hess);
      return d;
    }
    case Type::P_E0:
    case Type::P_E1:
    case Type::P_E2: {
      const int i = static_cast<int>(type) - static_cast<int>(Type::P_E0), j = (i + 1) % 3;
      Vector9 g;
      Matrix9 H;
      const double d =
          point_line_distance(p, *t[i], *t[j], grad ? &g : nullptr, hess ? &H : nullptr);
      const int to[3] = {0, 1 + i, 1 + j};
      scatter<3, 4>(g, H, to, grad, hess);
      return d;
    }
    case Type::P_T:
      break;
  }
  return point_plane_distance(p, t0, t1, t2, grad, hess);
}

double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                               const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) {
  return point_triangle_distance(p, t0, t1, t2, point_triangle_distance_type(p, t0, t1, t2));
}

}  // namespace mlshell
