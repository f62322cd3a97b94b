// Adjacency and validation of quad cages.
#include "mlshell/subdivision/quad_mesh.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <utility>

namespace mlshell {

namespace {

using DirectedEdge = std::pair<int, int>;

}  // namespace

QuadAdjacency::QuadAdjacency(const QuadMesh& mesh)
    : across_(4 * mesh.num_faces(), -1),
      valence_(mesh.num_points(), 0),
      boundary_vertex_(mesh.num_points(), 0),
      vertex_faces_(mesh.num_points()) {
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 4; ++k) vertex_faces_[mesh.quads[f][k]].push_back(f);
  // The face across edge a → b of f owns b → a, and has b as a corner: search b's few faces
  // (a map of all directed edges costs more than the rest of the set-up of a fine level).
  const auto edge_owner = [&](int b, int a) {
    for (int g : vertex_faces_[b])
      for (int k = 0; k < 4; ++k)
        if (mesh.quads[g][k] == b && mesh.quads[g][(k + 1) % 4] == a) return g;
    return -1;
  };
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 4; ++k) {
      const int a = mesh.quads[f][k], b = mesh.quads[f][(k + 1) % 4];
      const int g = edge_owner(b, a);
      if (g >= 0) {
        across_[4 * f + k] = g;
        if (a < b) ++valence_[a], ++valence_[b];  // count each interior edge once
      } else {
        ++valence_[a], ++valence_[b];
        boundary_vertex_[a] = boundary_vertex_[b] = 1;
      }
    }
  }
}

void validate_quad_mesh(const QuadMesh& mesh, const std::string& source) {
  const int nv = mesh.num_points();
  if (mesh.num_faces() == 0) throw MeshError(source + ": the cage has no faces");
  if (mesh.ghost.size() != mesh.quads.size())
    throw MeshError(source + ": internal error: ghost flags do not match the faces");
  std::vector<int> used(nv, 0);
  std::map<DirectedEdge, int> owner;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Quad& q = mesh.quads[f];
    for (int k = 0; k < 4; ++k) {
      if (q[k] < 0 || q[k] >= nv) {
        std::ostringstream m;
        m << source << ": face " << f + 1 << " refers to vertex " << q[k] + 1
          << " but the cage has " << nv << " vertices";
        throw MeshError(m.str());
      }
    }
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        if (q[a] == q[b]) {
          std::ostringstream m;
          m << source << ": face " << f + 1 << " is degenerate: vertex " << q[a] + 1
            << " appears twice";
          throw MeshError(m.str());
        }
    const Point3 area =
        (mesh.points[q[2]] - mesh.points[q[0]]).cross(mesh.points[q[3]] - mesh.points[q[1]]);
    double scale = 0.0;
    for (int k = 0; k < 4; ++k)
      scale = std::max(scale, (mesh.points[q[(k + 1) % 4]] - mesh.points[q[k]]).squaredNorm());
    if (!(area.norm() > 1e-12 * scale)) {
      std::ostringstream m;
      m << source << ": face " << f + 1 << " is degenerate (zero area)";
      throw MeshError(m.str());
    }
    for (int k = 0; k < 4; ++k) {
      ++used[q[k]];
      DirectedEdge e{q[k], q[(k + 1) % 4]};
      auto [it, inserted] = owner.emplace(e, f);
      if (!inserted) {
        std::ostringstream m;
        m << source << ": edge " << e.first + 1 << "-" << e.second + 1 << " is used by faces "
          << it->second + 1 << " and " << f + 1
          << " in the same direction: the cage is non-manifold or inconsistently oriented";
        throw MeshError(m.str());
      }
    }
  }
  for (int v = 0; v < nv; ++v)
    if (!used[v]) {
      std::ostringstream m;
      m << source << ": vertex " << v + 1 << " is not used by any face";
      throw MeshError(m.str());
    }
  // Each vertex must have a single fan of faces: on the boundary exactly one outgoing and one
  // incoming boundary edge, in the interior none.
  std::vector<int> out_boundary(nv, 0), in_boundary(nv, 0);
  for (const auto& [e, f] : owner)
    if (!owner.count({e.second, e.first})) ++out_boundary[e.first], ++in_boundary[e.second];
  for (int v = 0; v < nv; ++v)
    if (out_boundary[v] > 1 || in_boundary[v] > 1) {
      std::ostringstream m;
      m << source << ": vertex " << v + 1 << " is non-manifold (its faces form more than one fan)";
      throw MeshError(m.str());
    }
  // A vertex whose faces form several fans meeting only at it, with no boundary edges, is not
  // caught above; count faces reachable around the vertex instead.
  QuadAdjacency adj(mesh);
  for (int v = 0; v < nv; ++v) {
    const auto& faces = adj.vertex_faces(v);
    std::vector<int> seen{faces.front()};
    for (size_t i = 0; i < seen.size(); ++i) {
      const int f = seen[i];
      const Quad& q = mesh.quads[f];
      const int k = static_cast<int>(std::find(q.begin(), q.end(), v) - q.begin());
      for (int edge : {k, (k + 3) % 4}) {
        const int g = adj.across(f, edge);
        if (g >= 0 && std::find(seen.begin(), seen.end(), g) == seen.end()) seen.push_back(g);
      }
    }
    if (seen.size() != faces.size()) {
      std::ostringstream m;
      m << source << ": vertex " << v + 1 << " is non-manifold (its faces form more than one fan)";
      throw MeshError(m.str());
    }
  }
}

}  // namespace mlshell
