// One ring of ghost faces around the boundary of a cage (paper §5.2.1, Fig. 4c).
//
// Each boundary edge a→b of an interior face gets the ghost face (b, a, G(a), G(b)), where the
// ghost vertex G(v) extrapolates across the boundary, G(v) = 2v − w, w being v's interior
// neighbour(s). The rule depends on the number k of interior faces at v:
//   k = 1 (convex corner):    G(v) = 2v − (v's other boundary neighbour), per edge, plus the
//                             corner face (v, G_prev, 2v − diagonal, G_next);
//   k = 2 (regular boundary): one ghost vertex 2v − (its one interior neighbour);
//   k = 3 (re-entrant corner):the two boundary edges share one ghost face (v, u, G(u), w) that
//                             fills the notch; G(u) and G(w) become one vertex;
//   k ≥ 4 (extraordinary):    2v − (mean of its interior neighbours).
#include <algorithm>
#include <map>
#include <set>

#include "mlshell/subdivision/quad_mesh.hpp"

namespace mlshell {

namespace {

struct BoundaryLoopInfo {
  std::vector<int> next, prev;  ///< boundary successor/predecessor of each boundary vertex
  std::vector<int> faces;       ///< number of incident faces per vertex
};

BoundaryLoopInfo boundary_info(const QuadMesh& mesh, const QuadAdjacency& adj) {
  BoundaryLoopInfo info{std::vector<int>(mesh.num_points(), -1),
                        std::vector<int>(mesh.num_points(), -1),
                        std::vector<int>(mesh.num_points(), 0)};
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 4; ++k) {
      ++info.faces[mesh.quads[f][k]];
      if (adj.across(f, k) < 0) {
        const int a = mesh.quads[f][k], b = mesh.quads[f][(k + 1) % 4];
        info.next[a] = b;
        info.prev[b] = a;
      }
    }
  return info;
}

/// Interior (non-boundary-edge) neighbours of a boundary vertex.
std::vector<int> interior_neighbours(const QuadMesh& mesh, const QuadAdjacency& adj,
                                     const BoundaryLoopInfo& info, int v) {
  std::set<int> nbrs;
  for (int f : adj.vertex_faces(v)) {
    const Quad& q = mesh.quads[f];
    const int k = static_cast<int>(std::find(q.begin(), q.end(), v) - q.begin());
    nbrs.insert(q[(k + 1) % 4]);
    nbrs.insert(q[(k + 3) % 4]);
  }
  nbrs.erase(info.next[v]);
  nbrs.erase(info.prev[v]);
  return {nbrs.begin(), nbrs.end()};
}

}  // namespace

QuadMesh add_ghost_ring(const QuadMesh& interior) {
  if (std::any_of(interior.ghost.begin(), interior.ghost.end(), [](char g) { return g != 0; }))
    return interior;
  const QuadAdjacency adj(interior);
  const BoundaryLoopInfo info = boundary_info(interior, adj);
  QuadMesh mesh = interior;
  auto add_point = [&](const Point3& p) {
    mesh.points.push_back(p);
    return mesh.num_points() - 1;
  };
  const int nv = interior.num_points();
  const auto& X = interior.points;

  // Ghost vertex of every regular or extraordinary boundary vertex.
  std::vector<int> ghost_of(nv, -1);
  for (int v = 0; v < nv; ++v) {
    if (info.next[v] < 0 || info.faces[v] == 1 || info.faces[v] == 3) continue;
    const auto inner = interior_neighbours(interior, adj, info, v);
    Point3 mean = Point3::Zero();
    for (int w : inner) mean += X[w];
    mean /= static_cast<double>(inner.size());
    ghost_of[v] = add_point(2.0 * X[v] - mean);
  }
  // Re-entrant corners: the ghosts of both boundary neighbours merge into one vertex.
  for (int v = 0; v < nv; ++v) {
    if (info.next[v] < 0 || info.faces[v] != 3) continue;
    const int u = info.prev[v], w = info.next[v];
    if (ghost_of[u] < 0 || ghost_of[w] < 0)
      throw MeshError(
          "cannot add a ghost ring: re-entrant corner next to another corner at vertex " +
          std::to_string(v + 1) + "; refine the cage once");
    const int merged = ghost_of[u];
    mesh.points[merged] = 0.5 * (mesh.points[ghost_of[u]] + mesh.points[ghost_of[w]]);
    // The replaced vertex stays as an unused point; drop it below.
    ghost_of[w] = merged;
  }
  // Convex corners: one ghost per incident boundary edge plus the diagonal.
  std::map<std::pair<int, int>, int> corner_ghost;  // (corner, boundary neighbour) → ghost
  for (int v = 0; v < nv; ++v) {
    if (info.next[v] < 0 || info.faces[v] != 1) continue;
    const int p = info.next[v], q = info.prev[v];
    corner_ghost[{v, p}] = add_point(2.0 * X[v] - X[q]);
    corner_ghost[{v, q}] = add_point(2.0 * X[v] - X[p]);
  }
  auto ghost_for_edge = [&](int v, int other) {
    if (info.faces[v] == 1) return corner_ghost.at({v, other});
    if (info.faces[v] == 3) return other == info.prev[v] ? info.next[v] : info.prev[v];
    return ghost_of[v];
  };
  std::set<std::vector<int>> seen;  // dedupe the notch face (added from both of its edges)
  auto add_face = [&](Quad q) {
    std::vector<int> key(q.begin(), q.end());
    std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
    if (!seen.insert(key).second) return;
    mesh.quads.push_back(q);
    mesh.ghost.push_back(1);
  };
  for (int a = 0; a < nv; ++a) {
    if (info.next[a] < 0) continue;
    const int b = info.next[a];
    add_face({b, a, ghost_for_edge(a, b), ghost_for_edge(b, a)});
  }
  for (int v = 0; v < nv; ++v) {
    if (info.next[v] < 0 || info.faces[v] != 1) continue;
    const int f = adj.vertex_faces(v).front();
    const Quad& q = interior.quads[f];
    const int k = static_cast<int>(std::find(q.begin(), q.end(), v) - q.begin());
    const int diag = add_point(2.0 * X[v] - X[q[(k + 2) % 4]]);
    add_face({v, corner_ghost.at({v, info.prev[v]}), diag, corner_ghost.at({v, info.next[v]})});
  }
  // Remove points no face uses (merged re-entrant ghosts) and renumber.
  std::vector<int> remap(mesh.num_points(), -1);
  for (const Quad& q : mesh.quads)
    for (int v : q) remap[v] = 0;
  QuadMesh out;
  for (int v = 0; v < mesh.num_points(); ++v)
    if (remap[v] == 0) {
      remap[v] = out.num_points();
      out.points.push_back(mesh.points[v]);
    }
  for (size_t f = 0; f < mesh.quads.size(); ++f) {
    Quad q = mesh.quads[f];
    for (int& v : q) v = remap[v];
    out.quads.push_back(q);
    out.ghost.push_back(mesh.ghost[f]);
  }
  validate_quad_mesh(out, "cage with ghost ring");
  return out;
}

}  // namespace mlshell
