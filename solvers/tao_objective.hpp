// The objective a Tao was given (TaoSetObjectiveAndGradient, TaoSetHessian) seen as an
// Objective, so that mlshell's own TAO types run their levels through one interface and TAO's
// evaluation counters stay right.
#pragma once

#include <petsc/private/taoimpl.h>

#include "mlshell/objective.hpp"

namespace mlshell {

class TaoObjective final : public Objective {
 public:
  /// `error_source` (may be null) is the objective behind the Tao's callbacks, asked for the
  /// rounding error of the last value.
  explicit TaoObjective(Tao tao, const Objective* error_source = nullptr)
      : tao_(tao), error_source_(error_source) {}
  PetscReal evaluation_error() const override {
    return error_source_ ? error_source_->evaluation_error() : 0.0;
  }
  PetscErrorCode objective(Vec x, PetscReal* f, Vec g) override {
    return g ? TaoComputeObjectiveAndGradient(tao_, x, f, g) : TaoComputeObjective(tao_, x, f);
  }
  PetscErrorCode hessian(Vec x, Mat H) override {
    return TaoComputeHessian(tao_, x, H,
                             tao_->hessian_pre == tao_->hessian ? H : tao_->hessian_pre);
  }

 private:
  Tao tao_;
  const Objective* error_source_;
};

}  // namespace mlshell
