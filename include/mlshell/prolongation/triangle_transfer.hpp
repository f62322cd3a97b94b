// The shell prolongation of paper 2 (eq. 4–9) as a distributed LevelTransfer between two
// triangle levels: each rank prolongs its owned fine vertices with the pointwise kernel
// ShellProlongation, from the coarse vertices of their columns gathered by one VecScatter.
//
// State vectors are displacements from the rest shape, as every triangle level's objective
// takes them (x = X̄ + u, TriangleElasticTerm::position). The transfer acts on positions:
//   prolong(u_c) = P(X̄_c + u_c) − P(X̄_c),
// where P(X̄_c) is the fine rest shape X̄_f to round-off (rest recovery), so u_c = 0 prolongs
// to exactly 0. The other operations follow (they do not depend on the offset X̄):
//   prolong_correction(u₀, u) = P(X̄_c + u) − P(X̄_c + u₀),
//   prolong_direction(u₀, d)  = J_P(X̄_c + u₀) d,   restrict_gradient(u₀, g) = J_P(X̄_c + u₀)ᵀ g,
//   coarse_operator(u₀, A)    = J_Pᵀ A J_P  (J_P an MPIAIJ matrix, 9 entries per row, MatPtAP).
// A null u₀ means the rest state u₀ = 0 (Levels::composite_norm's linearisation).
// The Jacobian blocks are evaluated at every call (a 3×9 block per owned fine vertex: cheap next
// to an energy evaluation).
//
// Natural projection Π (paper 1 eq. 4.6) for a decimation hierarchy, where every coarse vertex
// k is a surviving fine vertex m(k) (`coarse_to_fine`): the coarse vertex takes the survivor's
// displacement, Π(u_f)_k = u_f(m(k)), i.e. in positions x_c(k) = x_f(m(k)) − (X̄_f(m(k)) −
// X̄_c(k)): the survivor's rest move is undone by translation. So Π(prolong(0)) = 0 exactly (rest
// states are recovered); for a deformed coarse state the misfit Π(prolong(u_c)) − u_c at k is
// (n γ + R t)(x_c) − (n̄ γ + R̄ t) of the survivor's offset, i.e. the rest move rotated by the
// local deformation minus itself: zero where the survivor kept its rest place, small where it
// moved a little. The least-squares and scaled-restriction projections are not offered here
// (PETSC_ERR_SUP): they belong to linear transfers.
//
// The same class serves the direct prolongation P^l to the finest level (eq. 9): it is another
// ShellProlongation, from level l's rest mesh to the finest rest points.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "mlshell/level_transfer.hpp"
#include "mlshell/parallel_layout.hpp"
#include "mlshell/prolongation/shell_prolongation.hpp"

namespace mlshell {

class ShellTransfer final : public LevelTransfer {
 public:
  /// `coarse`, `fine`: the two levels' layouts (borrowed; they must outlive the transfer), their
  /// natural numbering that of `prolongation`'s coarse mesh and fine points. `coarse_to_fine`:
  /// for every coarse vertex (natural), the fine vertex (natural) it survives as, for the
  /// natural projection; empty: project() answers PETSC_ERR_SUP. Throws std::invalid_argument
  /// (on every rank) for sizes or indices that do not match. Collective.
  ShellTransfer(const ParallelLayout& coarse, const ParallelLayout& fine,
                std::shared_ptr<const ShellProlongation> prolongation, double relative_cost,
                std::vector<int> coarse_to_fine = {});
  ~ShellTransfer() override;
  ShellTransfer(const ShellTransfer&) = delete;
  ShellTransfer& operator=(const ShellTransfer&) = delete;

  PetscErrorCode prolong(Vec coarse, Vec fine) const override;
  PetscErrorCode prolong_correction(Vec x0, Vec x, Vec fine_correction) const override;
  PetscErrorCode prolong_direction(Vec x0, Vec direction, Vec fine) const override;
  PetscErrorCode restrict_gradient(Vec x0, Vec fine_gradient, Vec coarse_gradient) const override;
  PetscErrorCode project(Vec fine, Vec coarse, Projection kind) const override;
  using LevelTransfer::project;
  PetscErrorCode coarse_operator(Vec x0, Mat fine, MatReuse reuse, Mat* coarse) const override;
  double relative_cost() const override { return relative_cost_; }

  /// Uᵀ g: the restriction with the intrinsic part alone, the offsets' Jacobian dropped (paper 2
  /// eq. 10: the gradient with the offset frozen at the current state). Not J_Pᵀ g wherever the
  /// offsets turn with the coarse triangles.
  PetscErrorCode restrict_intrinsic(Vec fine_gradient, Vec coarse_gradient) const;
  /// J_P(X̄_c + u₀) assembled (fine rows, coarse columns, block size 3), owned by the transfer:
  /// valid until the next call. For tests and diagnostics.
  PetscErrorCode jacobian_matrix(Vec x0, Mat* J) const;
  const ShellProlongation& prolongation() const { return *prolongation_; }

 private:
  const ParallelLayout& coarse_;
  const ParallelLayout& fine_;
  std::shared_ptr<const ShellProlongation> prolongation_;
  double relative_cost_;
  /// Owned fine vertices (PETSc order): natural index and the slots of their columns in the
  /// gathered coarse values.
  std::vector<int> fine_natural_;
  std::vector<std::array<int, 3>> slots_;
  std::vector<Point3> rest_gathered_;  ///< X̄_c at the gathered coarse vertices
  std::vector<Point3> rest_image_;     ///< P(X̄_c) at the owned fine vertices
  Vec gathered_ = nullptr;             ///< sequential: the coarse values this rank reads
  VecScatter gather_ = nullptr;        ///< coarse global → gathered_
  VecScatter survivors_ = nullptr;     ///< fine global → coarse global (Π), if given
  mutable Mat J_ = nullptr;
  mutable std::vector<ShellProlongation::Jacobian> jacobians_;
  mutable std::vector<ShellProlongation::Jacobian> rest_jacobians_;  ///< at u₀ = 0, on first use

  /// X̄_c + u (with_rest) or u at the gathered coarse vertices.
  PetscErrorCode gather(Vec u, bool with_rest, std::vector<Point3>& values) const;
  /// Σ_j blockᵀ-products of the owned fine vertices' gradients, added into their columns.
  PetscErrorCode restrict_blocks(
      Vec fine_gradient, Vec coarse_gradient,
      const std::function<Eigen::Matrix<double, 9, 1>(size_t, const Eigen::Vector3d&)>& block)
      const;
  /// The Jacobian blocks of the owned fine vertices at X̄_c + u₀ into jacobians_.
  PetscErrorCode update_jacobians(Vec x0) const;
};

}  // namespace mlshell
