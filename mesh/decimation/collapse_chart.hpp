// The joint flattening of one edge collapse (Liu et al. 2021, "Surface multigrid via intrinsic
// prolongation", §4; paper 2 §4.2): the one-ring of the edge before the collapse and the one-ring
// of the kept vertex after it, laid out in one plane so that a point of the surface known by its
// barycentric coordinates in a `before` triangle can be found in an `after` triangle.
//
// The before chart is the least-squares conformal map (LSCM, Lévy et al. 2002) of the `before`
// triangles with v_removed → (0,0) and v_kept → (1,0). The after chart keeps every link vertex
// where the before chart put it and places the kept vertex by the LSCM of the `after` triangles
// with the link fixed (a 2 × 2 least-squares problem). Where that folds an after triangle the
// kept vertex goes to the centroid of the kernel of its link (the points from which the link is
// seen counter-clockwise); where the kernel is empty and the link is closed, the whole chart is
// Tutte's (link on a circle, uniform weights). A planar patch whose placement lies inside its
// link is laid out by one similarity of the plane, so the chart then reproduces it exactly.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mlshell/decimation/decimation.hpp"

namespace mlshell {

class CollapseChart {
 public:
  /// The chart of `record`; `position(v)` is the current (before the collapse) position of a
  /// link vertex v (finest-mesh index). The removed and kept vertices' positions come from the
  /// record (removed_at, kept_from, placement).
  template <class Position>
  CollapseChart(const CollapseRecord& record, const Position& position) : record_(&record) {
    collect_vertices();
    before_3d_.resize(vertices_.size());
    for (size_t k = 0; k < vertices_.size(); ++k) {
      const int v = vertices_[k];
      before_3d_[k] = v == record.removed ? record.removed_at
                      : v == record.kept  ? record.kept_from
                                          : Point3(position(v));
    }
    build();
  }

  /// True where the LSCM after chart folded and a simpler chart was used instead.
  bool fell_back() const { return fell_back_; }

  /// The before-chart position of a point with barycentric `weights` in the `before` triangle
  /// `corners` (finest-mesh indices, in any corner order matching `weights`).
  Eigen::Vector2d before_position(const Triangle& corners, const Eigen::Vector3d& weights) const;
  Eigen::Vector2d removed_position() const { return before_[removed_local_]; }
  /// The kept vertex's before-chart position (where it was before the collapse moved it).
  Eigen::Vector2d kept_position() const { return before_[kept_local_]; }

  /// The after triangle (an index into record.after) containing chart point p, with p's
  /// barycentric coordinates in it (in that triangle's corner order). A point outside every
  /// after triangle (round-off, or a boundary that moved) goes to the triangle it is least
  /// outside of, its coordinates clamped to ≥ 0 and renormalised; *snap is how far outside it
  /// was (the most negative coordinate's magnitude, 0 inside).
  int locate(const Eigen::Vector2d& p, Eigen::Vector3d* weights, double* snap) const;

 private:
  void collect_vertices();
  int local(int v) const;
  void build();
  void lscm_before();
  bool place_kept_lscm();
  bool after_valid() const;
  bool place_kept_in_kernel();
  bool tutte_chart();

  const CollapseRecord* record_;
  std::vector<int> vertices_;  // finest-mesh indices of the before patch
  std::vector<Point3> before_3d_;
  int removed_local_ = -1;
  int kept_local_ = -1;
  std::vector<Eigen::Vector2d> before_;  // before-chart position of each vertex of the patch
  Eigen::Vector2d kept_after_ = Eigen::Vector2d::Zero();
  bool fell_back_ = false;
};

}  // namespace mlshell
