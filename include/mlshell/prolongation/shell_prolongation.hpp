// The shell prolongation of paper 2 (§4.3, eq. 4–9, footnote 2) from a coarse triangle level
// to a finer one (the next level, or directly the finest):
//   P(x)_i = v_i(x) + n_i(x) γ_i + R(F_i(x)) t_i,     v_i = Σ_k w_ik x_{c_k}   (U x)
// where fine vertex i lies in coarse triangle (c_0, c_1, c_2) with barycentric weights w_i,
// n_i is that triangle's unit normal, F_i its 3×2 deformation gradient against the rest
// triangle and R(F) = polar rotation U (I₂ 0)ᵀ Vᵀ of F = U Σ Vᵀ. The rest offsets (γ_i, t_i)
// are the difference between the fine rest position and the intrinsic anchor, written in the
// rest triangle's frame (ē, n̄ × ē, n̄), ē along the triangle's first edge. So P recovers the
// fine rest shape from the coarse one exactly, and moves with the coarse triangle rigidly.
//
// A fine vertex depends on one coarse triangle only: P and its Jacobian are pointwise kernels
// over three coarse vertices (one 3×9 block per fine vertex), which the distributed transfer
// applies over its owned fine vertices.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mlshell/decimation/intrinsic_embedding.hpp"
#include "mlshell/triangle/triangle_mesh.hpp"

namespace mlshell {

/// R(F) of footnote 2 for a 3×2 F: the 3×2 factor with orthonormal columns nearest to F,
/// U (I₂ 0)ᵀ Vᵀ with F = U Σ Vᵀ, in closed form (F + (n × F) Jᵀ)/(σ₁ + σ₂), n the unit normal of
/// F's columns and J the 90° rotation of the plane. For F of rank 1 (σ₂ ≤ 1e-12 σ₁, up to the
/// constant) it is F/‖F‖_F; for F = 0 (‖F‖_F ≤ 1e-12), zero.
Eigen::Matrix<double, 3, 2> polar_rotation(const Eigen::Matrix<double, 3, 2>& F);

class ShellProlongation {
 public:
  using Jacobian = Eigen::Matrix<double, 3, 9>;  ///< ∂P_i/∂(x_{c_0}, x_{c_1}, x_{c_2})

  /// `coarse_rest`: the coarse level's rest mesh; `fine_rest`: the finer level's rest points;
  /// `embedding[i]`: fine vertex i in the coarse mesh (weights summing to 1 within 1e-10).
  /// Throws std::invalid_argument for sizes that do not match, bad triangle indices, weights
  /// that are not a partition of unity or a degenerate rest triangle that carries a point.
  ShellProlongation(const TriangleMesh& coarse_rest, const std::vector<Point3>& fine_rest,
                    std::vector<EmbeddedPoint> embedding);

  int num_fine() const { return static_cast<int>(embedding_.size()); }
  /// The coarse vertices fine vertex i depends on (the columns of its row of U and of J_P).
  const Triangle& columns(int i) const { return columns_[i]; }
  const EmbeddedPoint& embedding(int i) const { return embedding_[i]; }
  /// Rest offsets: γ_i along the normal, t_i in the plane.
  double normal_offset(int i) const { return gamma_[i]; }
  const Eigen::Vector2d& tangent_offset(int i) const { return tangent_[i]; }

  /// P(x)_i from the current positions of columns(i).
  Point3 point(int i, const Point3& x0, const Point3& x1, const Point3& x2) const;
  /// ∂P_i/∂(x0, x1, x2), exact. A deformed triangle of rank 1 (collapsed to a segment) has no
  /// normal: n = 0 there and R = F/|F| (the segment's direction); rank 0 (a point): the
  /// offset is dropped and P_i is the anchor. Never NaN or Inf for finite input.
  Jacobian jacobian(int i, const Point3& x0, const Point3& x1, const Point3& x2) const;

  /// Whole-mesh conveniences (positions of all coarse vertices in, all fine out).
  std::vector<Point3> apply(const std::vector<Point3>& coarse) const;

 private:
  std::vector<EmbeddedPoint> embedding_;
  std::vector<Triangle> columns_;
  std::vector<Eigen::Matrix2d> rest_inverse_;  ///< B̄⁻¹ per fine vertex's triangle
  std::vector<double> gamma_;
  std::vector<Eigen::Vector2d> tangent_;
};

}  // namespace mlshell
