// Boundary sides, boxes, corners and nearest points on the reference limit surface.
#include "mlshell/subdivision/selection.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

namespace mlshell {

CageFrame CageFrame::from(const GeometrySpec& geometry) {
  CageFrame f;
  if (geometry.mesh) {
    const TriangleMeshSpec& m = *geometry.mesh;
    if (m.generator == TriangleMeshSpec::Generator::kRectangle)
      f = {true, m.origin[0], m.origin[1], m.size[0], m.size[1], 0.0, 0.0};
    return f;
  }
  if (const auto* r = std::get_if<RectangleCage>(&geometry.cage)) {
    f = {true, r->origin[0], r->origin[1], r->size[0], r->size[1], 0.0, 0.0};
  } else if (const auto* l = std::get_if<LShapeCage>(&geometry.cage)) {
    f = {true, l->origin[0], l->origin[1], l->size[0], l->size[1], l->cut[0], l->cut[1]};
  }
  return f;
}

namespace {

[[noreturn]] void empty_selection(const std::string& where, const std::string& why) {
  throw SceneError("where '" + where + "': " + why);
}

/// Limit positions of the two ends and the midpoint of every boundary edge.
std::vector<std::array<Point3, 3>> edge_geometry(const SubdivisionDiscretization& disc) {
  std::vector<SurfacePoint> pts;
  for (const BoundaryEdge& e : disc.boundary_edges())
    for (double s : {0.0, 1.0, 0.5}) pts.push_back(disc.edge_point(e, s));
  const auto basis = disc.evaluator().evaluate(pts);
  std::vector<std::array<Point3, 3>> out(disc.boundary_edges().size());
  for (size_t e = 0; e < out.size(); ++e)
    for (int k = 0; k < 3; ++k) out[e][k] = basis[3 * e + k].apply(kValue, disc.mesh().points);
  return out;
}

}  // namespace

std::vector<BoundaryEdge> select_curve(const SubdivisionDiscretization& disc,
                                       const CurveSelection& sel, const CageFrame& frame,
                                       const std::string& where) {
  const auto& edges = disc.boundary_edges();
  if (sel.kind == CurveSelection::Kind::All) return edges;
  const auto geo = edge_geometry(disc);
  const double tol = 1e-9 * std::max({1.0, frame.width, frame.height});
  std::vector<BoundaryEdge> out;
  for (size_t e = 0; e < edges.size(); ++e) {
    bool take = false;
    if (sel.kind == CurveSelection::Kind::Box) {
      const Point3& m = geo[e][2];
      take = true;
      for (int c = 0; c < 3; ++c)
        take = take && m[c] >= sel.box_min[c] - tol && m[c] <= sel.box_max[c] + tol;
    } else {
      if (!frame.generated)
        empty_selection(where, "named sides exist only for generated cages; use {box: ...}");
      auto on = [&](int c, double value) {
        return std::abs(geo[e][0][c] - value) < tol && std::abs(geo[e][1][c] - value) < tol;
      };
      const double x1 = frame.x0 + frame.width, y1 = frame.y0 + frame.height;
      const double nx = x1 - frame.cut_x, ny = y1 - frame.cut_y;
      if (sel.side == "left")
        take = on(0, frame.x0);
      else if (sel.side == "right")
        take = on(0, x1);
      else if (sel.side == "bottom")
        take = on(1, frame.y0);
      else if (sel.side == "top")
        take = on(1, y1);
      else if (sel.side == "re-entrant")
        take = (on(0, nx) && geo[e][2][1] > ny - tol) || (on(1, ny) && geo[e][2][0] > nx - tol);
      else
        empty_selection(where, "unknown side '" + sel.side + "'");
    }
    if (take) out.push_back(edges[e]);
  }
  if (out.empty()) empty_selection(where, "selects no part of the boundary");
  return out;
}

SurfacePoint nearest_surface_point(const SubdivisionDiscretization& disc, const Point3& target,
                                   double* distance) {
  const QuadMesh& mesh = disc.mesh();
  const auto& elements = disc.elements();
  // Candidate faces: nearest control-point centroids.
  std::vector<std::pair<double, int>> by_centroid;
  for (int f : elements) {
    Point3 c = Point3::Zero();
    for (int v : mesh.quads[f]) c += 0.25 * mesh.points[v];
    by_centroid.emplace_back((c - target).squaredNorm(), f);
  }
  const size_t candidates = std::min<size_t>(8, by_centroid.size());
  std::partial_sort(by_centroid.begin(), by_centroid.begin() + candidates, by_centroid.end());
  SurfacePoint best;
  double best_d2 = INFINITY;
  for (size_t k = 0; k < candidates; ++k) {
    const int f = by_centroid[k].second;
    // Start from the best of a 5×5 sample, then clamped Newton on |x(u,v) − target|².
    std::vector<SurfacePoint> grid;
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i) grid.push_back({f, 0.25 * i, 0.25 * j});
    const auto gb = disc.evaluator().evaluate(grid);
    SurfacePoint p = grid[0];
    double d2 = INFINITY;
    for (size_t s = 0; s < grid.size(); ++s) {
      const double e = (gb[s].apply(kValue, mesh.points) - target).squaredNorm();
      if (e < d2) d2 = e, p = grid[s];
    }
    for (int it = 0; it < 20; ++it) {
      const PointBasis b = disc.evaluator().evaluate({p})[0];
      const Point3 r = b.apply(kValue, mesh.points) - target;
      const Point3 xu = b.apply(kDu, mesh.points), xv = b.apply(kDv, mesh.points);
      Eigen::Matrix2d H;
      H << xu.dot(xu) + r.dot(b.apply(kDuu, mesh.points)),
          xu.dot(xv) + r.dot(b.apply(kDuv, mesh.points)),
          xu.dot(xv) + r.dot(b.apply(kDuv, mesh.points)),
          xv.dot(xv) + r.dot(b.apply(kDvv, mesh.points));
      const Eigen::Vector2d g(xu.dot(r), xv.dot(r));
      Eigen::Vector2d step = -H.ldlt().solve(g);
      if (!step.allFinite() || H.determinant() <= 0)
        step = -g / std::max(xu.squaredNorm(), xv.squaredNorm());
      const double u = std::clamp(p.u + step[0], 0.0, 1.0), v = std::clamp(p.v + step[1], 0.0, 1.0);
      if (std::abs(u - p.u) + std::abs(v - p.v) < 1e-15) break;
      p.u = u, p.v = v;
    }
    const double e =
        (disc.evaluator().evaluate({p})[0].apply(kValue, mesh.points) - target).squaredNorm();
    if (e < best_d2) best_d2 = e, best = p;
  }
  if (distance) *distance = std::sqrt(best_d2);
  return best;
}

SurfacePoint select_point(const SubdivisionDiscretization& disc, const PointSelection& sel,
                          const CageFrame& frame, const std::string& where) {
  Point3 target(sel.at[0], sel.at[1], sel.at[2]);
  bool must_hit = false;
  if (sel.kind != PointSelection::Kind::At) {
    if (!frame.generated)
      empty_selection(
          where, "corners and point(u, v) exist only for generated cages; use {at: [x, y, z]}");
    must_hit = true;
    if (sel.kind == PointSelection::Kind::Param) {
      target = {frame.x0 + sel.param[0] * frame.width, frame.y0 + sel.param[1] * frame.height, 0.0};
    } else {
      const bool right = sel.corner.find("right") != std::string::npos;
      const bool top = sel.corner.find("top") != std::string::npos;
      target = {frame.x0 + (right ? frame.width : 0.0), frame.y0 + (top ? frame.height : 0.0), 0.0};
    }
  }
  double distance = 0.0;
  const SurfacePoint p = nearest_surface_point(disc, target, &distance);
  if (must_hit && distance > 1e-8 * std::max({1.0, frame.width, frame.height})) {
    std::ostringstream m;
    m << "the point (" << target.x() << ", " << target.y() << ", " << target.z()
      << ") is not on this cage (nearest surface point is " << distance << " away)";
    empty_selection(where, m.str());
  }
  return p;
}

}  // namespace mlshell
