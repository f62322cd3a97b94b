// What RMTR sees of a level hierarchy (paper §4.2): per level an objective f^l with its Hessian,
// and the transfers between neighbouring levels — all on distributed vectors, never a mesh.
// Level 0 is the coarsest. MultilevelProblem implements it for a scene.
#pragma once

#include <petscmat.h>

#include "mlshell/level_transfer.hpp"
#include "mlshell/objective.hpp"

namespace mlshell {

class MultilevelObjective {
 public:
  virtual ~MultilevelObjective() = default;
  virtual int num_levels() const = 0;
  /// f^l, the problem re-discretised on level l (the finest is the problem being solved).
  virtual Objective& level_objective(int l) = 0;
  virtual PetscErrorCode create_vector(int l, Vec* v) const = 0;
  virtual PetscErrorCode create_hessian(int l, Mat* H) const = 0;
  /// The transfers between levels l and l + 1, for l + 1 < num_levels().
  virtual const LevelTransfer& transfer(int l) const = 0;
  /// ‖I_{L−1}^L ⋯ I_l^{l+1} x‖₂, the level norm of eq. (4.9) (for nonlinear transfers, the
  /// prolongations linearised at the current coarse starts).
  virtual PetscErrorCode composite_norm(int l, Vec x, PetscReal* norm) const = 0;
};

}  // namespace mlshell
