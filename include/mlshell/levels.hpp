// A hierarchy of discretizations of one shell, coarsest first, with the transfers between
// neighbouring levels (DESIGN.md, "Two kinds of level behind one set of interfaces"): what the
// per-level problems, RMTR and the time stepper need, whatever the kind of level.
// Implementations: LevelHierarchy (Catmull–Clark levels, linear transfers) and TriangleLevels
// (triangle meshes; one level until decimation hierarchies exist).
#pragma once

#include <petscvec.h>

#include <vector>

#include "mlshell/discretization.hpp"
#include "mlshell/level_transfer.hpp"
#include "mlshell/parallel_layout.hpp"

namespace mlshell {

class Levels {
 public:
  virtual ~Levels();
  virtual int num_levels() const = 0;
  int finest() const { return num_levels() - 1; }
  virtual const Discretization& discretization(int l) const = 0;
  virtual const ParallelLayout& layout(int l) const = 0;
  /// Between levels l and l + 1, for l < finest().
  virtual const LevelTransfer& transfer(int l) const = 0;

  /// ‖I_{L−1}^L ⋯ I_l^{l+1} x‖₂ (eq. 4.9): the prolongations applied one after the other
  /// (LevelTransfer::prolong_direction, linearised at x₀ = 0 for nonlinear transfers).
  PetscErrorCode composite_norm(int l, Vec x, PetscReal* norm) const;
  /// Fills `coarse[l]` (vectors of layout(l)) with the projections of the finest-level vector
  /// `fine` down the hierarchy: the state of every level after a time step.
  PetscErrorCode project_down(Vec fine, const std::vector<Vec>& coarse) const;

 private:
  mutable std::vector<Vec> fine_work_;  // per level l < finest(): a vector of level l + 1
};

}  // namespace mlshell
