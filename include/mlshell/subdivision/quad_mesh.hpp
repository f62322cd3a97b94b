// Quad control cages of Catmull–Clark subdivision surfaces.
//
// A cage is an all-quad, manifold, consistently oriented mesh. The simulated surface is
// parametrised over the *interior* faces only; one ring of *ghost* faces around the boundary
// carries the control points that the interior faces' one-rings need (paper §5.2.1, Fig. 4c).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "mlshell/mesh_error.hpp"

namespace mlshell {

using Quad = std::array<int, 4>;

struct QuadMesh {
  std::vector<Point3> points;  ///< #V control points
  std::vector<Quad> quads;     ///< #F faces, counter-clockwise seen from the normal side
  std::vector<char> ghost;     ///< #F: 1 for a ghost face (not part of the simulated domain)

  int num_points() const { return static_cast<int>(points.size()); }
  int num_faces() const { return static_cast<int>(quads.size()); }
  bool is_ghost(int f) const { return ghost[f] != 0; }
};

/// Edge/face adjacency of a quad mesh: for a directed edge a→b of face f, `across(f, k)` is the
/// face on the other side of edge k (from corner k to corner k+1) or -1 on the mesh boundary.
class QuadAdjacency {
 public:
  explicit QuadAdjacency(const QuadMesh& mesh);
  int across(int face, int edge) const { return across_[4 * face + edge]; }
  /// Valence (number of incident edges) of each vertex.
  int valence(int v) const { return valence_[v]; }
  bool on_boundary(int v) const { return boundary_vertex_[v] != 0; }
  /// Faces incident to a vertex.
  const std::vector<int>& vertex_faces(int v) const { return vertex_faces_[v]; }

 private:
  std::vector<int> across_;
  std::vector<int> valence_;
  std::vector<char> boundary_vertex_;
  std::vector<std::vector<int>> vertex_faces_;
};

/// Checks that the mesh is a usable cage: valid indices, no repeated vertex in a face, no face of
/// zero area, every edge shared by at most two faces with opposite orientations, every vertex
/// used and with a single fan of faces. `source` names the mesh in messages (a file or generator).
void validate_quad_mesh(const QuadMesh& mesh, const std::string& source);

/// nx × ny rectangle in the z = 0 plane, origin at its bottom-left corner; all faces interior.
QuadMesh make_rectangle_cage(double width, double height, int nx, int ny, double x0, double y0);

/// The rectangle minus its top-right cut_x × cut_y block (a re-entrant corner).
QuadMesh make_l_shape_cage(double width, double height, int nx, int ny, double cut_x, double cut_y,
                           double x0, double y0);

/// Reads a plain OBJ (v and f lines; f entries may be `i`, `i/t`, `i//n`, `i/t/n`, negative
/// indices allowed; other lines ignored). Faces that are not quads are rejected: OpenSubdiv 3.5
/// scales derivatives wrongly on sub-faces of non-quad faces (DESIGN.md). Faces whose name group
/// (`g ghost`) is `ghost` are marked as ghost faces; otherwise all faces are interior.
QuadMesh read_obj_cage(const std::filesystem::path& path);

/// Adds one ring of ghost faces around the boundary of the interior faces by extrapolation
/// (ghost = 2·boundary − inner). Boundary vertices with one incident face (convex corner) get a
/// corner ghost face, with three (re-entrant corner) a single face filling the notch. A mesh
/// that already has ghost faces is returned unchanged.
QuadMesh add_ghost_ring(const QuadMesh& interior);

}  // namespace mlshell
