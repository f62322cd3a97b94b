// Basis functions of the Catmull–Clark limit surface and their first and second derivatives
// (paper §5.2): x(u, v) = Σ_I N_I(u, v) q_I over the control points of one face's one-ring.
//
// Regular faces (four valence-4 corners) are bicubic B-spline patches on their 4×4 one-ring
// (Fig. 4a); all of them share one table per parameter point. Faces touching an extraordinary
// vertex are evaluated with OpenSubdiv limit stencils after feature-adaptive refinement to
// isolation level 4, so that every point used for quadrature (|u|,|v| > 1/16 away from the
// extraordinary corner) lies on a regular sub-patch: exact values and derivatives, no Gregory
// approximations (DESIGN.md). Evaluating exactly at an extraordinary vertex gives the exact limit
// position and first derivatives but approximate second derivatives.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "mlshell/subdivision/quad_mesh.hpp"

namespace mlshell {

/// A point of the limit surface: face index and (u, v) ∈ [0,1]² in that face, u along the
/// face's first edge (corner 0 → 1) and v along its last edge (corner 0 → 3).
struct SurfacePoint {
  int face = -1;
  double u = 0.0, v = 0.0;
};

/// Derivative slots of PointBasis::w.
enum BasisDerivative { kValue = 0, kDu = 1, kDv = 2, kDuu = 3, kDuv = 4, kDvv = 5 };

/// Which derivative slots LimitEvaluator::evaluate fills: all six, or the values alone (output
/// sampling and bounding boxes need no derivatives, and skipping them skips five allocations
/// and the derivative stencils per point).
enum class BasisSlots { kAll, kValueOnly };

/// Basis functions at one point: Σ_i w[d][i] q_{nodes[i]} is the d-th derivative of x (slots
/// left empty when evaluated with BasisSlots::kValueOnly).
struct PointBasis {
  std::vector<int> nodes;
  std::array<std::vector<double>, 6> w;
  int size() const { return static_cast<int>(nodes.size()); }
  /// Σ_i w[d][i] q_{nodes[i]} for points q.
  Point3 apply(int d, const std::vector<Point3>& q) const;
};

/// Cubic B-spline basis on the 4×4 grid of a regular face, node index i + 4 j (i along u):
/// writes w[d][16] for the six derivative slots.
void bicubic_bspline_basis(double u, double v, std::array<std::array<double, 16>, 6>& w);

class LimitEvaluator {
 public:
  /// `mesh` is one level of the hierarchy (interior faces + ghost ring).
  explicit LimitEvaluator(const QuadMesh& mesh);
  ~LimitEvaluator();
  LimitEvaluator(const LimitEvaluator&) = delete;
  LimitEvaluator& operator=(const LimitEvaluator&) = delete;

  /// True if the face is a bicubic B-spline patch.
  bool is_regular(int face) const { return regular_[face] != 0; }
  /// The 16 control points of a regular face in B-spline order (node i + 4 j).
  const std::array<int, 16>& regular_nodes(int face) const { return grid_[face]; }
  /// Basis at many points at once (faces touching extraordinary vertices are batched into one
  /// OpenSubdiv call). Only interior faces may be evaluated.
  std::vector<PointBasis> evaluate(const std::vector<SurfacePoint>& points,
                                   BasisSlots slots = BasisSlots::kAll) const;
  /// Number of interior faces touching an extraordinary vertex.
  int num_irregular_faces() const;

 private:
  struct OpenSubdivState;
  const QuadMesh& mesh_;
  std::vector<char> regular_;
  std::vector<std::array<int, 16>> grid_;
  mutable std::unique_ptr<OpenSubdivState> osd_;  // built on first irregular evaluation
};

}  // namespace mlshell
