// The intrinsic prolongation U of a decimation hierarchy (Liu et al. 2021; paper 2 §4.2): every
// vertex of a finer level is tracked through the collapse records, each collapse flattened
// jointly (its one-ring before and after, v_removed → (0,0), v_kept → (1,0)), to barycentric
// coordinates in one triangle of a coarser level. U therefore has at most three nonzeros per
// row. Both vertices of a collapse are anchored in the after chart (paper 2 §4.2), so a vertex
// that the collapse's placement moved is embedded where it was; a vertex that never moves has
// weight 1 on itself. On a flat mesh every point therefore lies exactly at its barycentric
// place, and P = U.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mlshell/decimation/decimation.hpp"

namespace mlshell {

/// A point of a coarser level's surface: barycentric weights (summing to 1, each ≥ −1e-12) in
/// one of its triangles (an index into that level's mesh.triangles).
struct EmbeddedPoint {
  int triangle = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
};

/// How the embedding went: collapses whose joint flattening folded and fell back to a simpler
/// chart, and points found outside every chart triangle and snapped to the nearest one.
struct EmbeddingReport {
  int collapses = 0;
  int fallback_charts = 0;
  int snapped_points = 0;
  double largest_snap = 0.0;  ///< in barycentric units
};

/// For every vertex of hierarchy.levels[fine] (in its own numbering), its place on
/// hierarchy.levels[coarse] (coarse < fine). fine = finest gives the rows of the direct U^l.
std::vector<EmbeddedPoint> intrinsic_embedding(const DecimationHierarchy& hierarchy, int coarse,
                                               int fine, EmbeddingReport* report = nullptr);

}  // namespace mlshell
