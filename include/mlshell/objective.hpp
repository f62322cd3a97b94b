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
};

}  // namespace mlshell
