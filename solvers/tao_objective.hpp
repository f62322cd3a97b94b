// The objective a Tao was given (TaoSetObjectiveAndGradient, TaoSetHessian) seen as an
// Objective, so that mlshell's own TAO types run their levels through one interface and TAO's
// evaluation counters stay right.
#pragma once

#include <petsc/private/taoimpl.h>

#include "mlshell/objective.hpp"

namespace mlshell {

class TaoObjective final : public Objective {
 public:
  /// `source` (may be null) is the objective behind the Tao's callbacks, asked for the
  /// rounding error of the last value, for step limits and told of accepted iterates.
  explicit TaoObjective(Tao tao, Objective* source = nullptr) : tao_(tao), source_(source) {}
  PetscReal evaluation_error() const override {
    return source_ ? source_->evaluation_error() : 0.0;
  }
  PetscErrorCode max_step(Vec x, Vec d, PetscReal* alpha) override {
    return source_ ? source_->max_step(x, d, alpha) : Objective::max_step(x, d, alpha);
  }
  PetscErrorCode accepted(Vec x) override { return source_ ? source_->accepted(x) : 0; }
  long revision() const override { return source_ ? source_->revision() : 0; }
  PetscErrorCode objective(Vec x, PetscReal* f, Vec g) override {
    return g ? TaoComputeObjectiveAndGradient(tao_, x, f, g) : TaoComputeObjective(tao_, x, f);
  }
  PetscErrorCode hessian(Vec x, Mat H) override {
    return TaoComputeHessian(tao_, x, H,
                             tao_->hessian_pre == tao_->hessian ? H : tao_->hessian_pre);
  }

 private:
  Tao tao_;
  Objective* source_;
};

}  // namespace mlshell
