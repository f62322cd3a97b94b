// What a solver sees of a level: an objective with gradient and Hessian on distributed vectors
// (never a mesh). LevelProblem implements it for a scene's energy; RMTR's coarse-level models
// wrap one.
#pragma once

#include <petscmat.h>

namespace mlshell {

class Objective {
 public:
  virtual ~Objective() = default;
  /// f(x) and, if g is not null, ∇f(x).
  virtual PetscErrorCode objective(Vec x, PetscReal* f, Vec g) = 0;
  /// ∇²f(x) into H.
  virtual PetscErrorCode hessian(Vec x, Mat H) = 0;
  /// An estimate of the absolute rounding error of the last value objective() returned (0 if
  /// unknown). Below it, differences of two values are noise (paper §7.2, limiting accuracy).
  virtual PetscReal evaluation_error() const { return 0.0; }
  /// The largest α ∈ (0, 1] such that x + α d is admissible (e.g. collision-free): solvers
  /// shorten their trial steps to it. 1 for smooth objectives.
  virtual PetscErrorCode max_step(Vec x, Vec d, PetscReal* alpha) {
    *alpha = 1.0;
    return 0;
  }
  /// The solver accepted x as its new iterate (terms may adapt: barrier stiffness, friction).
  virtual PetscErrorCode accepted(Vec x) { return 0; }
  /// Changes whenever the objective itself changes (accepted() doubled contact's κ, moved a
  /// collider): a solver that holds f and ∇f of its iterate evaluates them again.
  virtual long revision() const { return 0; }
  /// A matrix with the pattern of hessian(), for solvers that allocate their own (StepSolver).
  virtual PetscErrorCode create_hessian(Mat* H) const {
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_SUP, "this objective does not create its Hessian");
  }
  /// The force scale of the problem at x (‖f_ext‖₂ for a shell), which makes gradient
  /// tolerances unit-free; 0 if it has none.
  virtual PetscErrorCode force_scale(Vec x, PetscReal* scale) {
    *scale = 0.0;
    return 0;
  }
};

}  // namespace mlshell
