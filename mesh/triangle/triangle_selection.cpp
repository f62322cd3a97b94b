// Selections on triangle meshes (see triangle_selection.hpp).
#include "mlshell/triangle/triangle_selection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mlshell {

namespace {

[[noreturn]] void empty_selection(const std::string& where, const std::string& why) {
  throw SceneError("where '" + where + "': " + why);
}

bool on_side(const Point3& X, const std::string& side, const CageFrame& f) {
  const double tol = 1e-9 * std::max(f.width, f.height);
  if (side == "left") return std::abs(X[0] - f.x0) <= tol;
  if (side == "right") return std::abs(X[0] - (f.x0 + f.width)) <= tol;
  if (side == "bottom") return std::abs(X[1] - f.y0) <= tol;
  return side == "top" && std::abs(X[1] - (f.y0 + f.height)) <= tol;
}

}  // namespace

std::vector<int> select_vertices(const TriangleDiscretization& disc, const CurveSelection& sel,
                                 const CageFrame& frame, const std::string& where) {
  const TriangleTopology& topo = disc.topology();
  const auto& X = disc.points();
  std::vector<int> out;
  using K = CurveSelection::Kind;
  switch (sel.kind) {
    case K::All:
      for (int v = 0; v < disc.num_points(); ++v)
        if (topo.on_boundary(v)) out.push_back(v);
      if (out.empty()) empty_selection(where, "the surface is closed: it has no boundary");
      break;
    case K::Loop: {
      const auto& loops = topo.boundary_loops();
      if (sel.loop >= static_cast<int>(loops.size()))
        empty_selection(where, "the mesh has " + std::to_string(loops.size()) +
                                   " boundary loop(s), numbered from 0 by their smallest vertex");
      out = loops[sel.loop];
      break;
    }
    case K::Side:
      for (int v = 0; v < disc.num_points(); ++v)
        if (topo.on_boundary(v) && on_side(X[v], sel.side, frame)) out.push_back(v);
      break;
    case K::Box:
      for (int v = 0; v < disc.num_points(); ++v) {
        bool inside = true;
        for (int c = 0; c < 3; ++c)
          inside = inside && X[v][c] >= sel.box_min[c] && X[v][c] <= sel.box_max[c];
        if (inside) out.push_back(v);
      }
      if (out.empty()) empty_selection(where, "no vertex of the mesh lies in the box");
      break;
    case K::Group: {
      const auto it = disc.mesh().groups.find(sel.group);
      if (it == disc.mesh().groups.end()) {
        std::string names;
        for (const auto& [name, vertices] : disc.mesh().groups)
          names += (names.empty() ? "" : ", ") + name;
        empty_selection(where, "the mesh has no group '" + sel.group +
                                   "' (its groups: " + (names.empty() ? "none" : names) + ")");
      }
      out = it->second;
      break;
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (out.empty()) empty_selection(where, "selects no vertex of the mesh");
  return out;
}

int select_vertex(const TriangleDiscretization& disc, const PointSelection& sel,
                  const CageFrame& frame, const std::string& where) {
  Point3 target;
  switch (sel.kind) {
    case PointSelection::Kind::At:
      target = {sel.at[0], sel.at[1], sel.at[2]};
      break;
    case PointSelection::Kind::Corner: {
      const bool right = sel.corner.find("right") != std::string::npos;
      const bool top = sel.corner.find("top") != std::string::npos;
      target = {frame.x0 + (right ? frame.width : 0.0), frame.y0 + (top ? frame.height : 0.0), 0.0};
      break;
    }
    default:
      target = {frame.x0 + sel.param[0] * frame.width, frame.y0 + sel.param[1] * frame.height, 0.0};
  }
  int best = -1;
  double distance = std::numeric_limits<double>::infinity();
  for (int v = 0; v < disc.num_points(); ++v) {
    const double d = (disc.points()[v] - target).squaredNorm();
    if (d < distance) distance = d, best = v;
  }
  if (best < 0) empty_selection(where, "the mesh has no vertices");
  return best;
}

std::vector<std::array<int, 2>> selected_boundary_edges(const TriangleDiscretization& disc,
                                                        const std::vector<int>& vertices) {
  std::vector<char> in(disc.num_points(), 0);
  for (int v : vertices) in[v] = 1;
  std::vector<std::array<int, 2>> out;
  for (const TriangleEdge& e : disc.topology().edges())
    if (e.on_boundary() && in[e.v[0]] && in[e.v[1]]) out.push_back(e.v);
  return out;
}

}  // namespace mlshell
