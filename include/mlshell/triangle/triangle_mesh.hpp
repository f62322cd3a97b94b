// Triangle meshes of thin shells: the mesh itself, its edge/face/vertex topology (with the
// interior edges as bending hinges), validation, and a reader for Wavefront OBJ files.
//
// Conventions: triangles are counter-clockwise seen from the normal side; local edge k of a
// triangle runs from its corner k to corner (k + 1) % 3. Messages name vertices and faces
// 1-based, as an OBJ file does.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "mlshell/mesh_error.hpp"

namespace mlshell {

using Triangle = std::array<int, 3>;

struct TriangleMesh {
  std::vector<Point3> points;       ///< #V vertices
  std::vector<Triangle> triangles;  ///< #F faces, counter-clockwise seen from the normal side
  /// Named vertex groups (e.g. for boundary conditions or loads): sorted, unique vertex indices.
  std::map<std::string, std::vector<int>> groups;

  int num_points() const { return static_cast<int>(points.size()); }
  int num_triangles() const { return static_cast<int>(triangles.size()); }
};

/// An undirected edge. v[0] → v[1] is its direction in faces[0], the lower-numbered of its
/// faces; local[i] is the edge's local index in faces[i]. On the boundary faces[1] and local[1]
/// are -1 (and v[0] → v[1] then follows the boundary in the triangles' direction).
struct TriangleEdge {
  std::array<int, 2> v;
  std::array<int, 2> faces;
  std::array<int, 2> local;
  bool on_boundary() const { return faces[1] < 0; }
};

/// An interior edge with its two triangles: v[0]–v[1] is the shared edge, oriented so that
/// faces[0] = (v[0], v[1], v[2]) and faces[1] = (v[1], v[0], v[3]) in their counter-clockwise
/// order (up to a cyclic shift of each triangle's corners). Bending kernels rely on this.
struct Hinge {
  std::array<int, 4> v;
  std::array<int, 2> faces;
};

/// Edges, neighbours, hinges, vertex fans and boundary loops of a mesh that passes
/// validate_triangle_mesh (the constructor assumes it does; it throws MeshError only for what it
/// cannot represent: missing or repeated face vertices, an edge with more than two faces or run
/// twice in the same direction). Edges are numbered in lexicographic order of their sorted
/// vertex pair, hinges in edge order, boundary loops by their smallest vertex (each loop starts
/// there), so the numbering depends only on the mesh.
class TriangleTopology {
 public:
  explicit TriangleTopology(const TriangleMesh& mesh);

  int num_edges() const { return static_cast<int>(edges_.size()); }
  const std::vector<TriangleEdge>& edges() const { return edges_; }
  const TriangleEdge& edge(int e) const { return edges_[e]; }

  /// Edge ids of a triangle's local edges 0, 1, 2.
  const std::array<int, 3>& triangle_edges(int t) const { return triangle_edges_[t]; }
  /// The triangle across local edge k of triangle t, or -1 on the boundary.
  int neighbour(int t, int k) const { return neighbours_[t][k]; }
  const std::array<int, 3>& neighbours(int t) const { return neighbours_[t]; }

  /// One hinge per interior edge, in edge order; hinge_edges()[h] is the edge of hinge h.
  const std::vector<Hinge>& hinges() const { return hinges_; }
  const std::vector<int>& hinge_edges() const { return hinge_edges_; }

  /// Triangles around a vertex in counter-clockwise order seen from the normal side; at a
  /// boundary vertex the first one is the triangle whose edge leaving the vertex is on the
  /// boundary.
  const std::vector<int>& vertex_triangles(int v) const { return vertex_triangles_[v]; }

  /// Boundary loops as ordered vertex lists, each following its boundary edges in their
  /// triangle's direction (so a loop runs counter-clockwise around the surface seen from the
  /// normal side; the last vertex connects back to the first).
  const std::vector<std::vector<int>>& boundary_loops() const { return boundary_loops_; }
  bool closed() const { return boundary_loops_.empty(); }
  /// #V: 1 for a vertex on the boundary.
  const std::vector<char>& boundary_vertices() const { return boundary_vertices_; }
  bool on_boundary(int v) const { return boundary_vertices_[v] != 0; }

  /// V − E + F.
  int euler_characteristic() const;

 private:
  int num_points_ = 0;
  int num_triangles_ = 0;
  std::vector<TriangleEdge> edges_;
  std::vector<std::array<int, 3>> triangle_edges_;
  std::vector<std::array<int, 3>> neighbours_;
  std::vector<Hinge> hinges_;
  std::vector<int> hinge_edges_;
  std::vector<std::vector<int>> vertex_triangles_;
  std::vector<std::vector<int>> boundary_loops_;
  std::vector<char> boundary_vertices_;
};

/// Where the points and triangles of a mesh were read from: 1-based line numbers in the file
/// named by validate_triangle_mesh's `source`. Either vector may be empty (no line known).
struct TriangleSourceLines {
  std::vector<int> points;
  std::vector<int> triangles;
};

/// Checks that the mesh can be simulated, throwing MeshError otherwise. In order: the mesh has
/// faces; every face refers to existing, distinct vertices with finite coordinates and has
/// non-zero area (degenerate: twice its area ≤ 1e-12 × its longest edge squared, i.e. its
/// vertices are collinear to within 1e-12 of its size — a scale- and translation-free test that
/// does not penalise graded meshes); no two faces have the same vertex set; every edge has at
/// most two faces, which run it in opposite directions (consistent orientation); every vertex
/// is used; the faces around each vertex form a single fan; groups hold sorted, unique, existing
/// vertices. Messages start with `source`
/// (then ":line" where `lines` knows it) and name the face or vertex, 1-based.
void validate_triangle_mesh(const TriangleMesh& mesh, const std::string& source,
                            const TriangleSourceLines& lines = {});

/// Reads a triangle mesh from a Wavefront OBJ file: `v x y z` vertices (a fourth, weight,
/// coordinate is ignored) and `f` faces of exactly three entries `i`, `i/t`, `i//n` or `i/t/n`
/// (negative indices count back from the last vertex defined so far; an index must refer to a
/// vertex defined before the face). A `g name...` line starts a group: the vertices of the faces
/// that follow, up to the next `g` line, join groups[name] for each name on the line except
/// `default`; a bare `g` ends the group. All other lines are ignored. Errors (MeshError) name
/// the file and line; the mesh is then checked with validate_triangle_mesh.
TriangleMesh read_obj_triangles(const std::filesystem::path& path);

}  // namespace mlshell
