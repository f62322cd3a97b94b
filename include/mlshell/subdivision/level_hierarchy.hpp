// The levels of the multilevel hierarchy and the transfers between them (paper §4.2, §5.1–5.3),
// as distributed PETSc objects.
//
// Every level is a full discretization with its own layout; the finest level is partitioned
// with METIS, and each coarser face takes the owner of its children, so that transfers stay
// mostly on-rank. Between levels l and l+1:
//   prolongation  I = S_l^{l+1}   (coarse corrections to the fine level),
//   restriction   R = Sᵀ          (fine gradients to the coarse level), formed explicitly,
//   projection    Q_{l+1}^l       (fine iterates to the coarse level, reverse subdivision),
// all MPIAIJ with block size 3 (each scalar weight acts on x, y and z alike).
#pragma once

#include <petscksp.h>

#include <memory>
#include <string>
#include <vector>

#include "mlshell/level_transfer.hpp"
#include "mlshell/levels.hpp"
#include "mlshell/parallel_layout.hpp"
#include "mlshell/subdivision/subdivision_discretization.hpp"
#include "mlshell/subdivision/subdivision_hierarchy.hpp"

namespace mlshell {

class LevelHierarchy final : public Levels {
 public:
  /// Levels `coarsest`..`subdivision.num_levels() − 1` of the subdivision hierarchy; level index
  /// 0 of this object is the coarsest of them.
  LevelHierarchy(MPI_Comm comm, const SubdivisionHierarchy& subdivision, int coarsest, int gauss);
  ~LevelHierarchy();
  LevelHierarchy(const LevelHierarchy&) = delete;
  LevelHierarchy& operator=(const LevelHierarchy&) = delete;

  int num_levels() const override { return static_cast<int>(levels_.size()); }
  const SubdivisionDiscretization& discretization(int l) const override { return *levels_[l].disc; }
  const ParallelLayout& layout(int l) const override { return *levels_[l].layout; }
  /// S_l^{l+1}, R_{l+1}^l = Sᵀ and Q_{l+1}^l for l < finest().
  Mat prolongation(int l) const { return transfers_[l].S; }
  Mat restriction(int l) const { return transfers_[l].R; }
  Mat projection(int l) const { return transfers_[l].Q; }
  /// The three as a LevelTransfer (relative cost 1/4), with the least-squares projection.
  const LevelTransfer& transfer(int l) const override { return *transfers_[l].linear; }

  /// The least-squares projection P = (SᵀS)⁻¹Sᵀ (eq. 5.18) of fine values onto level l: a
  /// solve with the sparse SᵀS (MUMPS Cholesky, set up on first use; P itself is dense and never
  /// formed). For comparison with Q on small and medium problems.
  PetscErrorCode least_squares_projection(int l, Vec fine, Vec coarse) const;

 private:
  struct Level {
    std::unique_ptr<SubdivisionDiscretization> disc;
    std::unique_ptr<ParallelLayout> layout;
  };
  struct Transfer {
    Mat S = nullptr, R = nullptr, Q = nullptr;
    Mat StS = nullptr;  // for P, on first use
    KSP normal = nullptr;
    std::unique_ptr<LinearTransfer> linear;
  };
  std::vector<Level> levels_;
  mutable std::vector<Transfer> transfers_;
};

/// Prints per level: control points, dofs, h, extraordinary vertices by valence, and nonzeros
/// per row and memory of S, R and Q (`-mlshell_hierarchy_view`).
PetscErrorCode view_hierarchy(const LevelHierarchy& levels, MPI_Comm comm);

/// Writes each level's control cage (ghost ring included) and its limit surface as OBJ files
/// `level_<l>_cage.obj` and `level_<l>_surface.obj` in `dir` (rank 0; `-mlshell_hierarchy_write`).
void write_hierarchy(const LevelHierarchy& levels, const std::string& dir);

/// A scalar sparse matrix (rows: points of `rows`, columns: points of `cols`, natural order) as
/// an MPIAIJ matrix with block size 3 in the two layouts' PETSc numbering.
PetscErrorCode create_block_transfer(const SubdivisionMatrix& A, const ParallelLayout& rows,
                                     const ParallelLayout& cols, Mat* M);

}  // namespace mlshell
