// Edge–edge squared distance by type (see edge_edge.hpp).
#include "mlshell/contact/distance/edge_edge.hpp"

#include <Eigen/Geometry>

#include "mlshell/contact/distance/line_line.hpp"
#include "mlshell/contact/distance/point_edge.hpp"
#include "mlshell/contact/distance/point_line.hpp"
#include "mlshell/contact/distance/point_point.hpp"
#include "vector_products.hpp"

namespace mlshell {

using namespace contact_detail;
using Type = EdgeEdgeDistanceType;

namespace {

/// The stencil of each non-line–line type: the local function's vertices (point first) as
/// vertices of (ea0, ea1, eb0, eb1).
struct Stencil {
  int size;  // 2: point–point, 3: point–line
  int to[3];
};

Stencil stencil_of(Type type) {
  switch (type) {
    case Type::EA0_EB0:
      return {2, {0, 2, -1}};
    case Type::EA0_EB1:
      return {2, {0, 3, -1}};
    case Type::EA1_EB0:
      return {2, {1, 2, -1}};
    case Type::EA1_EB1:
      return {2, {1, 3, -1}};
    case Type::EA_EB0:
      return {3, {2, 0, 1}};
    case Type::EA_EB1:
      return {3, {3, 0, 1}};
    case Type::EA0_EB:
      return {3, {0, 2, 3}};
    case Type::EA1_EB:
      return {3, {1, 2, 3}};
    case Type::EA_EB:
      break;
  }
  return {4, {-1, -1, -1}};
}

}  // namespace

EdgeEdgeDistanceType edge_edge_distance_type(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                             const Eigen::Vector3d& eb0,
                                             const Eigen::Vector3d& eb1) {
  const Eigen::Vector3d u = ea1 - ea0, v = eb1 - eb0, w = ea0 - eb0;
  const double uu = u.squaredNorm(), vv = v.squaredNorm(), uv = u.dot(v);
  const double D = u.cross(v).squaredNorm();
  if (D > kEdgeEdgeParallelThreshold * uu * vv) {
    const double uw = u.dot(w), vw = v.dot(w);
    const double s = (uv * vw - vv * uw) / D, t = (uu * vw - uv * uw) / D;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) return Type::EA_EB;
  }
  // The minimum is on the boundary of [0, 1]²: an endpoint against the other edge.
  using PE = PointEdgeDistanceType;
  struct Candidate {
    const Eigen::Vector3d &p, &e0, &e1;
    Type at_e0, at_e1, inside;
  };
  const Candidate candidates[4] = {{ea0, eb0, eb1, Type::EA0_EB0, Type::EA0_EB1, Type::EA0_EB},
                                   {ea1, eb0, eb1, Type::EA1_EB0, Type::EA1_EB1, Type::EA1_EB},
                                   {eb0, ea0, ea1, Type::EA0_EB0, Type::EA1_EB0, Type::EA_EB0},
                                   {eb1, ea0, ea1, Type::EA0_EB1, Type::EA1_EB1, Type::EA_EB1}};
  double best = 0.0;
  Type type = Type::EA0_EB0;
  for (int i = 0; i < 4; ++i) {
    const Candidate& c = candidates[i];
    const PE on = point_edge_distance_type(c.p, c.e0, c.e1);
    const double d = point_edge_distance(c.p, c.e0, c.e1, on);
    if (i > 0 && !(d < best)) continue;
    best = d;
    type = on == PE::P_E0 ? c.at_e0 : on == PE::P_E1 ? c.at_e1 : c.inside;
  }
  return type;
}

double edge_edge_distance(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                          const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1,
                          EdgeEdgeDistanceType type, Vector12* grad, Matrix12* hess) {
  const Stencil s = stencil_of(type);
  if (s.size == 4) return line_line_distance(ea0, ea1, eb0, eb1, grad, hess);
  const Eigen::Vector3d* x[4] = {&ea0, &ea1, &eb0, &eb1};
  if (s.size == 2) {
    Vector6 g;
    Matrix6 H;
    const double d =
        point_point_distance(*x[s.to[0]], *x[s.to[1]], grad ? &g : nullptr, hess ? &H : nullptr);
    const int to[2] = {s.to[0], s.to[1]};
    scatter<2, 4>(g, H, to, grad, hess);
    return d;
  }
  Vector9 g;
  Matrix9 H;
  const double d = point_line_distance(*x[s.to[0]], *x[s.to[1]], *x[s.to[2]], grad ? &g : nullptr,
                                       hess ? &H : nullptr);
  scatter<3, 4>(g, H, s.to, grad, hess);
  return d;
}

double edge_edge_distance(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                          const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1) {
  return edge_edge_distance(ea0, ea1, eb0, eb1, edge_edge_distance_type(ea0, ea1, eb0, eb1));
}

}  // namespace mlshell
