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
};

}  // namespace mlshell
