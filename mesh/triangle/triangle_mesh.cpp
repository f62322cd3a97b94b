// Topology (edges, neighbours, hinges, vertex fans, boundary loops) and validation of triangle
// meshes.
#include "mlshell/triangle/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

namespace mlshell {

namespace {

/// One side of an edge: local edge `local` of face `face`, with sorted vertices lo < hi.
struct HalfEdge {
  int lo, hi, face, local;
  bool operator<(const HalfEdge& o) const {
    return std::tie(lo, hi, face, local) < std::tie(o.lo, o.hi, o.face, o.local);
  }
};

/// All 3F half-edges sorted so that the sides of each undirected edge are adjacent, in face
/// order. Faces with a repeated vertex give lo == hi; callers reject those first.
std::vector<HalfEdge> sorted_half_edges(const std::vector<Triangle>& triangles) {
  std::vector<HalfEdge> h;
  h.reserve(3 * triangles.size());
  for (int f = 0; f < static_cast<int>(triangles.size()); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[f][k], b = triangles[f][(k + 1) % 3];
      h.push_back({std::min(a, b), std::max(a, b), f, k});
    }
  std::sort(h.begin(), h.end());
  return h;
}

/// Calls visit(first, last) for each run [first, last) of half-edges on the same edge.
template <class Visit>
void for_each_edge(const std::vector<HalfEdge>& h, Visit visit) {
  for (size_t i = 0; i < h.size();) {
    size_t j = i + 1;
    while (j < h.size() && h[j].lo == h[i].lo && h[j].hi == h[i].hi) ++j;
    visit(i, j);
    i = j;
  }
}

/// The directed start vertex of a half-edge in its face.
int tail(const std::vector<Triangle>& triangles, const HalfEdge& e) {
  return triangles[e.face][e.local];
}

}  // namespace

TriangleTopology::TriangleTopology(const TriangleMesh& mesh)
    : num_points_(mesh.num_points()),
      num_triangles_(mesh.num_triangles()),
      triangle_edges_(mesh.triangles.size(), {-1, -1, -1}),
      neighbours_(mesh.triangles.size(), {-1, -1, -1}),
      vertex_triangles_(mesh.points.size()),
      boundary_vertices_(mesh.points.size(), 0) {
  const auto& tris = mesh.triangles;
  for (int f = 0; f < num_triangles_; ++f)
    for (int k = 0; k < 3; ++k)
      if (tris[f][k] < 0 || tris[f][k] >= num_points_ || tris[f][k] == tris[f][(k + 1) % 3])
        throw MeshError("TriangleTopology: face " + std::to_string(f + 1) +
                        " has a missing or repeated vertex (validate the mesh first)");
  const std::vector<HalfEdge> h = sorted_half_edges(tris);
  for_each_edge(h, [&](size_t i, size_t j) {
    const std::string name =
        "TriangleTopology: edge " + std::to_string(h[i].lo + 1) + "-" + std::to_string(h[i].hi + 1);
    if (j - i > 2) throw MeshError(name + " has more than two faces (validate the mesh first)");
    if (j - i == 2 && tail(tris, h[i]) == tail(tris, h[i + 1]))
      throw MeshError(name + " is inconsistently oriented (validate the mesh first)");
    const int e = num_edges();
    TriangleEdge edge;
    edge.v = {tail(tris, h[i]), tris[h[i].face][(h[i].local + 1) % 3]};
    edge.faces = {h[i].face, j - i == 2 ? h[i + 1].face : -1};
    edge.local = {h[i].local, j - i == 2 ? h[i + 1].local : -1};
    edges_.push_back(edge);
    triangle_edges_[edge.faces[0]][edge.local[0]] = e;
    if (edge.on_boundary()) {
      boundary_vertices_[edge.v[0]] = boundary_vertices_[edge.v[1]] = 1;
      return;
    }
    triangle_edges_[edge.faces[1]][edge.local[1]] = e;
    neighbours_[edge.faces[0]][edge.local[0]] = edge.faces[1];
    neighbours_[edge.faces[1]][edge.local[1]] = edge.faces[0];
    const int v2 = tris[edge.faces[0]][(edge.local[0] + 2) % 3];
    const int v3 = tris[edge.faces[1]][(edge.local[1] + 2) % 3];
    hinges_.push_back({{edge.v[0], edge.v[1], v2, v3}, edge.faces});
    hinge_edges_.push_back(e);
  });

  // Fans: from a face with corner k at the vertex, the next face counter-clockwise is across
  // local edge k + 2 (the edge arriving at the vertex). A boundary fan starts at the face whose
  // edge leaving the vertex (local edge k) is on the boundary.
  std::vector<std::vector<int>> incident(num_points_);
  for (int f = 0; f < num_triangles_; ++f)
    for (int k = 0; k < 3; ++k) incident[tris[f][k]].push_back(f);
  auto corner = [&](int f, int v) {
    return static_cast<int>(std::find(tris[f].begin(), tris[f].end(), v) - tris[f].begin());
  };
  for (int v = 0; v < num_points_; ++v) {
    const auto& around = incident[v];
    if (around.empty()) continue;
    int start = around.front();
    for (int f : around)
      if (neighbours_[f][corner(f, v)] < 0) {
        start = f;
        break;
      }
    auto& fan = vertex_triangles_[v];
    for (int f = start; f >= 0 && fan.size() < around.size();) {
      fan.push_back(f);
      f = neighbours_[f][(corner(f, v) + 2) % 3];
      if (f == start) break;
    }
    if (fan.size() != around.size())  // not a single fan: only for an unvalidated mesh
      for (int f : around)
        if (std::find(fan.begin(), fan.end(), f) == fan.end()) fan.push_back(f);
  }

  // Boundary loops: each boundary vertex of a valid mesh has exactly one boundary edge leaving
  // it (in its triangle's direction).
  std::vector<int> next(num_points_, -1);
  for (const TriangleEdge& e : edges_)
    if (e.on_boundary()) next[e.v[0]] = e.v[1];
  std::vector<char> visited(num_points_, 0);
  for (int v = 0; v < num_points_; ++v) {
    if (next[v] < 0 || visited[v]) continue;
    std::vector<int> loop;
    for (int w = v; w >= 0 && !visited[w]; w = next[w]) {
      visited[w] = 1;
      loop.push_back(w);
    }
    boundary_loops_.push_back(std::move(loop));
  }
}

int TriangleTopology::euler_characteristic() const {
  return num_points_ - num_edges() + num_triangles_;
}

namespace {

/// Builds messages "source[:line]: face F ..." / "vertex V ...", numbering 1-based.
class Reporter {
 public:
  Reporter(const std::string& source, const TriangleSourceLines& lines)
      : source_(source), lines_(lines) {}

  [[noreturn]] void face(int f, const std::string& what) const {
    throw MeshError(prefix(lines_.triangles, f) + "face " + std::to_string(f + 1) + " " + what);
  }
  [[noreturn]] void vertex(int v, const std::string& what) const {
    throw MeshError(prefix(lines_.points, v) + "vertex " + std::to_string(v + 1) + " " + what);
  }
  /// "face F (line L)" for mentioning another face inside a message.
  std::string face_name(int f) const {
    std::string s = "face " + std::to_string(f + 1);
    if (f < static_cast<int>(lines_.triangles.size()))
      s += " (line " + std::to_string(lines_.triangles[f]) + ")";
    return s;
  }

 private:
  std::string prefix(const std::vector<int>& lines, int i) const {
    if (i < static_cast<int>(lines.size())) return source_ + ":" + std::to_string(lines[i]) + ": ";
    return source_ + ": ";
  }
  const std::string& source_;
  const TriangleSourceLines& lines_;
};

std::string vertex_list(const Triangle& t) {
  return std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1);
}

}  // namespace

void validate_triangle_mesh(const TriangleMesh& mesh, const std::string& source,
                            const TriangleSourceLines& lines) {
  const Reporter report(source, lines);
  const int nv = mesh.num_points(), nf = mesh.num_triangles();
  const auto& tris = mesh.triangles;
  if (nf == 0) throw MeshError(source + ": the mesh has no triangles (expected at least one)");

  for (int v = 0; v < nv; ++v)
    if (!mesh.points[v].allFinite()) {
      std::ostringstream m;
      m << "has a non-finite coordinate (" << mesh.points[v].x() << ", " << mesh.points[v].y()
        << ", " << mesh.points[v].z() << "); expected finite numbers";
      report.vertex(v, m.str());
    }

  std::map<Triangle, int> by_vertex_set;
  for (int f = 0; f < nf; ++f) {
    const Triangle& t = tris[f];
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= nv)
        report.face(f, "refers to vertex " + std::to_string(t[k] + 1) + " but the mesh has " +
                           std::to_string(nv) + " vertices");
    for (int k = 0; k < 3; ++k)
      if (t[k] == t[(k + 1) % 3])
        report.face(f, "has vertex " + std::to_string(t[k] + 1) +
                           " twice (expected three distinct vertices)");
    const Point3 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &c = mesh.points[t[2]];
    const double twice_area = (b - a).cross(c - a).norm();
    const double longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (!(twice_area > 1e-12 * longest))
      report.face(f, "(vertices " + vertex_list(t) +
                         ") is degenerate: zero area (its vertices are collinear or coincide)");
    Triangle key = t;
    std::sort(key.begin(), key.end());
    const auto [it, inserted] = by_vertex_set.emplace(key, f);
    if (!inserted)
      report.face(f, "repeats " + report.face_name(it->second) + ": same vertices " +
                         vertex_list(t) + " (duplicate face)");
  }

  const std::vector<HalfEdge> h = sorted_half_edges(tris);
  for_each_edge(h, [&](size_t i, size_t j) {
    if (j - i <= 2) return;
    std::string faces;
    for (size_t k = i; k < j; ++k)
      faces += (k == i ? "" : k + 1 == j ? " and " : ", ") + report.face_name(h[k].face);
    report.face(h[j - 1].face, "makes edge " + std::to_string(h[i].lo + 1) + "-" +
                                   std::to_string(h[i].hi + 1) + " non-manifold: it is shared by " +
                                   faces + " (expected at most two faces per edge)");
  });
  // An edge run in the same direction by both its faces: blame the face with more such
  // conflicts (a single flipped face disagrees with all its neighbours), the later one on a tie.
  std::vector<int> conflicts(nf, 0);
  const HalfEdge* first_conflict = nullptr;
  for_each_edge(h, [&](size_t i, size_t j) {
    if (j - i == 2 && tail(tris, h[i]) == tail(tris, h[i + 1])) {
      ++conflicts[h[i].face], ++conflicts[h[i + 1].face];
      if (!first_conflict) first_conflict = &h[i];
    }
  });
  if (first_conflict) {
    const HalfEdge& e = *first_conflict;
    const int f = e.face, g = (&e + 1)->face;
    const auto [flipped, other] = conflicts[f] > conflicts[g] ? std::pair{f, g} : std::pair{g, f};
    const int a = tail(tris, e), b = tris[f][(e.local + 1) % 3];
    report.face(flipped, "is flipped relative to " + report.face_name(other) + ": both run edge " +
                             std::to_string(a + 1) + "->" + std::to_string(b + 1) +
                             " in the same direction (expected consistently oriented faces)");
  }

  for (const auto& [name, vertices] : mesh.groups)
    for (size_t i = 0; i < vertices.size(); ++i) {
      if (vertices[i] < 0 || vertices[i] >= nv)
        throw MeshError(source + ": group '" + name + "' refers to vertex " +
                        std::to_string(vertices[i] + 1) + " but the mesh has " +
                        std::to_string(nv) + " vertices");
      if (i > 0 && vertices[i] <= vertices[i - 1])
        throw MeshError(source + ": group '" + name +
                        "' is not sorted and unique (expected increasing vertex indices)");
    }

  std::vector<std::vector<int>> incident(nv);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) incident[tris[f][k]].push_back(f);
  for (int v = 0; v < nv; ++v)
    if (incident[v].empty()) report.vertex(v, "is not used by any face (expected none unused)");

  // Fans around each vertex: faces connected through the edges that contain the vertex.
  const TriangleTopology topology(mesh);
  std::vector<int> stamp(nf, -1);
  for (int v = 0; v < nv; ++v) {
    int fans = 0;
    for (int start : incident[v]) {
      if (stamp[start] == v) continue;
      ++fans;
      std::vector<int> todo{start};
      stamp[start] = v;
      while (!todo.empty()) {
        const int f = todo.back();
        todo.pop_back();
        const int k =
            static_cast<int>(std::find(tris[f].begin(), tris[f].end(), v) - tris[f].begin());
        for (int g : {topology.neighbour(f, k), topology.neighbour(f, (k + 2) % 3)})
          if (g >= 0 && stamp[g] != v) stamp[g] = v, todo.push_back(g);
      }
    }
    if (fans > 1)
      report.vertex(v, "is non-manifold: its faces form " + std::to_string(fans) +
                           " separate fans (expected one fan of faces around each vertex)");
  }
}

}  // namespace mlshell
