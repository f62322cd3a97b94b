// A triangle-mesh shell as a hierarchy of levels (paper 2 §4.1–4.3): the user's mesh on the
// finest level and, when the scene asks for a hierarchy, coarser levels decimated from it
// (decimation.hpp), with the shell prolongation P_{l+1}^l between neighbouring levels
// (shell_prolongation.hpp, behind LevelTransfer) and the direct prolongation P^l of each level
// to the finest (for proxy energies and the rest-shape check).
//
// The decimation runs on every rank identically (it is deterministic; the constructor checks
// the fingerprints agree). The finest level is partitioned with METIS; every coarser level
// takes its owners from the next finer one: a coarse triangle goes to the rank that owns most
// of the finer vertices it carries (its own corners and the vertices embedded in it), so the
// transfers move little data between ranks.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "mlshell/decimation/decimation.hpp"
#include "mlshell/levels.hpp"
#include "mlshell/prolongation/shell_prolongation.hpp"
#include "mlshell/triangle/triangle_discretization.hpp"

namespace mlshell {

class TriangleLevels final : public Levels {
 public:
  /// One level: `mesh`, partitioned with METIS over the ranks of `comm`.
  TriangleLevels(MPI_Comm comm, TriangleMesh mesh);
  /// The levels of `hierarchy` (decimate()) from `coarsest` (an index into hierarchy.levels) up
  /// to the finest; coarsest = hierarchy.num_levels() − 1 keeps only the fine mesh.
  TriangleLevels(MPI_Comm comm, std::shared_ptr<const DecimationHierarchy> hierarchy,
                 int coarsest = 0);
  ~TriangleLevels() override;

  int num_levels() const override { return static_cast<int>(discs_.size()); }
  const TriangleDiscretization& discretization(int l) const override { return *discs_[l]; }
  const ParallelLayout& layout(int l) const override { return *layouts_[l]; }
  /// Between levels l and l + 1; throws std::logic_error on a single level.
  const LevelTransfer& transfer(int l) const override;

  /// The decimation this hierarchy came from (null for a single level built from a mesh).
  const DecimationHierarchy* decimation() const { return hierarchy_.get(); }
  /// P_{l+1}^l as a serial kernel (the transfer applies it on distributed vectors).
  const ShellProlongation& prolongation(int l) const { return *prolongations_[l]; }
  /// The direct P^l from level l to the finest (built on first use; P^L is not defined).
  const ShellProlongation& direct_prolongation(int l) const;
  /// P^l on distributed vectors, level l → the finest (built on first use; collective): the
  /// transfer of the proxy energies Ψ(P^l(x_l)) (proxy_energy.hpp).
  const LevelTransfer& direct_transfer(int l) const;
  /// Point pairs of level l (l < finest) that the Galerkin product J_Pᵀ H J_P couples beyond
  /// level l's element stencils, H with level l + 1's pattern (its own such pairs included): a
  /// fine vertex depends on the three corners of its coarse triangle, so two coarse triangles
  /// couple wherever fine vertices in them do. LevelProblem::extend_pattern takes them.
  const std::vector<std::array<int, 2>>& galerkin_pairs(int l) const { return galerkin_pairs_[l]; }

 private:
  std::shared_ptr<const DecimationHierarchy> hierarchy_;
  int first_ = 0;  // hierarchy_->levels[first_ + l] is level l
  std::vector<std::unique_ptr<TriangleDiscretization>> discs_;
  std::vector<std::unique_ptr<ParallelLayout>> layouts_;
  std::vector<std::shared_ptr<const ShellProlongation>> prolongations_;
  std::vector<std::unique_ptr<LevelTransfer>> transfers_;
  mutable std::vector<std::shared_ptr<const ShellProlongation>> direct_;
  mutable std::vector<std::unique_ptr<LevelTransfer>> direct_transfers_;
  std::vector<std::vector<std::array<int, 2>>> galerkin_pairs_;
  void find_galerkin_pairs();
};

/// The rank that owns each point of `layout` (natural order), on every rank.
std::vector<int> point_owners(const ParallelLayout& layout);

/// Owners for the faces of `coarse` inheriting from the finer level: face t goes to the rank
/// that owns most of the finer vertices it carries (`embedding`: finer vertex → coarse
/// triangle; `corner_of`: coarse vertex → its finer vertex), ties to the lowest rank.
std::vector<int> inherited_face_owners(const TriangleMesh& coarse,
                                       const std::vector<EmbeddedPoint>& embedding,
                                       const std::vector<int>& corner_of,
                                       const std::vector<int>& finer_point_owner, int num_ranks);

}  // namespace mlshell

namespace mlshell {

/// -mlshell_hierarchy_view: per level its vertices, dofs, faces, smallest angle, build time, the
/// nonzeros of U to the next level and the rest-shape recovery of P_{l+1}^l and of the direct
/// P^l (the largest |P(x̄_l) − x̄|, relative to the bounding-box diagonal).
PetscErrorCode view_hierarchy(const TriangleLevels& levels, MPI_Comm comm);
/// -mlshell_hierarchy_write DIR (rank 0): level_<l>.obj, each level's rest mesh, and
/// level_<l>_to_finest.obj, P^l of that rest mesh on the finest topology.
void write_hierarchy(const TriangleLevels& levels, const std::string& dir);

/// The largest |P(x̄_coarse)_i − x̄_i| over the fine points, relative to their bounding-box
/// diagonal: 0 up to round-off (rest-shape recovery).
double rest_shape_error(const ShellProlongation& p, const std::vector<Point3>& coarse_rest,
                        const std::vector<Point3>& fine_rest);
/// The smallest interior angle of any triangle of the mesh, in degrees.
double smallest_angle_degrees(const TriangleMesh& mesh);

}  // namespace mlshell
