// Fine-to-coarse hierarchies of a triangle mesh by quadric-error edge collapse (paper 2 §4.1):
// CGAL's Surface_mesh_simplification with probabilistic plane quadrics (Garland–Heckbert), with
// every collapse recorded. The records are the single source of everything built on the
// hierarchy: the intrinsic prolongation U (intrinsic_embedding.hpp), the shell offsets (γ, t),
// the projection and the replay test (DESIGN.md, "Paper 2's second half").
//
// Vertex numbering: a record names vertices by their index in the finest mesh (a vertex keeps
// its index while it survives). A level's own mesh numbers its vertices 0..n−1 in increasing
// order of their finest-mesh index (DecimationLevel::finest_vertex).
#pragma once

#include <string>
#include <vector>

#include "mlshell/triangle/triangle_mesh.hpp"

namespace mlshell {

struct DecimationOptions {
  /// Vertex counts of the coarse levels, finest-but-one first, strictly decreasing, each
  /// smaller than the fine mesh's. The hierarchy has vertices.size() + 1 levels.
  std::vector<int> vertices;
  /// A collapse is refused if a triangle around it would get an angle below this (degrees)...
  double min_angle_degrees = 10.0;
  /// ...or if a triangle's normal would turn by more than this (degrees).
  double max_normal_change_degrees = 60.0;
  /// A boundary vertex goes only if the new boundary edge, between its two boundary
  /// neighbours, stays within this fraction of the edge's length of every fine boundary vertex
  /// it replaces (each projecting inside the edge). Straight sides stay exact and corners stay
  /// (a right angle deviates by 0.5); the default lets a curved rim coarsen into chords of up to
  /// about 20° of a circle (4.4 %), so a dome's rim decimates with its surface.
  double boundary_deviation = 0.05;

  /// `levels` levels in all (≥ 2), each coarse level with about 1/ratio of the next finer
  /// level's vertices (ratio > 1): vertices[k] = round(vertices[k − 1] / ratio). Throws
  /// std::invalid_argument for levels < 2 or ratio ≤ 1 ("hierarchy: ratio 1 must be > 1").
  static DecimationOptions by_ratio(int fine_vertices, int levels, double ratio);
  /// Throws std::invalid_argument naming the field and value for nonsense: no coarse level,
  /// counts not strictly decreasing, not below fine_vertices or below 4, angles out of range
  /// ("hierarchy: vertices[1] = 50 must be < vertices[0] = 50 (strictly decreasing)").
  void validate(int fine_vertices) const;
};

/// One edge collapse: `removed` merges into `kept`, which moves from `kept_from` to
/// `placement`. `before` are the triangles around the edge before the collapse (the union of
/// both vertices' one-rings), `after` the triangles that replace them (`removed` replaced by
/// `kept`, the two triangles on the edge gone), all with finest-mesh vertex indices and their
/// orientation.
struct CollapseRecord {
  int removed = -1;
  int kept = -1;
  Point3 removed_at = Point3::Zero();  ///< `removed`'s position before the collapse
  Point3 kept_from = Point3::Zero();
  Point3 placement = Point3::Zero();
  std::vector<Triangle> before;
  std::vector<Triangle> after;
};

struct DecimationLevel {
  /// The level's rest mesh, vertices renumbered 0..n−1; the fine mesh's groups keep the
  /// surviving vertices (a group never loses all of them: its vertices are not removed).
  TriangleMesh mesh;
  /// Level vertex → its index in the finest mesh (increasing).
  std::vector<int> finest_vertex;
  /// records[0, num_records) turn the finest mesh into this level.
  int num_records = 0;
};

struct DecimationHierarchy {
  /// All collapses in the order they happened.
  std::vector<CollapseRecord> records;
  /// Coarsest first; the last level is the fine mesh itself (num_records = 0).
  std::vector<DecimationLevel> levels;
  /// Seconds spent building each level (the same order as `levels`; 0 for the finest).
  std::vector<double> build_seconds;

  int num_levels() const { return static_cast<int>(levels.size()); }
  /// A hash of the topology and rest positions of every level and of the records (equal on
  /// any number of ranks, for tests and the hierarchy view): 16 hex digits of a 64-bit FNV-1a
  /// hash over the bit patterns of the positions and the indices.
  std::string fingerprint() const;
};

/// Decimates `fine` (which must pass validate_triangle_mesh) level by level. Collapses are
/// refused if they would flip or degenerate a triangle (min angle, normal change), change the
/// topology (the link condition; boundary loops are never closed or merged), move the boundary
/// off the fine boundary's shape, or remove a vertex of a group. Deterministic: the same input
/// gives the same hierarchy bit for bit. Throws MeshError naming the level and the counts when
/// a target cannot be reached under these rules.
DecimationHierarchy decimate(const TriangleMesh& fine, const DecimationOptions& options);

}  // namespace mlshell
