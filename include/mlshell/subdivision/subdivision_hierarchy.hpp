// Uniform Catmull–Clark refinement of a cage with ghost ring, trimmed to one ghost ring per level
// (paper §5.1, §5.2.1, Fig. 5), and the subdivision matrices between neighbouring levels.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "mlshell/subdivision/quad_mesh.hpp"

namespace mlshell {

/// Scalar subdivision matrix: row i of level l+1 holds the weights of level-l control points
/// (q^{l+1} = S q^l, eq. 5.11, applied to each coordinate).
using SubdivisionMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// The least-squares projection P = (SᵀS)⁻¹Sᵀ of eq. (5.18), applied through a sparse Cholesky
/// factorisation of SᵀS and never formed (it is dense). For comparison with Q on small and
/// medium problems.
class LeastSquaresProjection {
 public:
  explicit LeastSquaresProjection(const SubdivisionMatrix& S);
  ~LeastSquaresProjection();
  /// q^l = argmin ‖q^{l+1} − S q‖, column by column (one column per coordinate).
  Eigen::MatrixXd apply(const Eigen::MatrixXd& fine) const;

 private:
  struct Factor;
  const SubdivisionMatrix& S_;
  std::unique_ptr<Factor> factor_;
};

class SubdivisionHierarchy {
 public:
  /// `cage` must carry its ghost ring (add_ghost_ring). Builds levels 0..refinements.
  SubdivisionHierarchy(const QuadMesh& cage, int refinements);

  int num_levels() const { return static_cast<int>(levels_.size()); }
  /// Level l: its interior faces and one ring of ghost faces, control points at their
  /// subdivided positions.
  const QuadMesh& level(int l) const { return levels_[l]; }
  const QuadMesh& finest() const { return levels_.back(); }
  /// S_l^{l+1} between the kept control points of levels l and l+1.
  const SubdivisionMatrix& subdivision(int l) const { return subdivision_[l]; }
  /// Q_{l+1}^l, the reverse subdivision projection from level l+1 onto level l (paper eq. 5.19
  /// with 5.21, Appendices B and C): sparse, local, and Q S = I.
  const SubdivisionMatrix& reverse_subdivision(int l) const { return reverse_[l]; }
  /// For each face of level l+1, its parent face on level l.
  const std::vector<int>& parent_faces(int l) const { return parent_face_[l]; }

 private:
  std::vector<QuadMesh> levels_;
  std::vector<SubdivisionMatrix> subdivision_, reverse_;
  std::vector<std::vector<int>> parent_face_;
};

}  // namespace mlshell
