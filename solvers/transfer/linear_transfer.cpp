// The linear adapter of LevelTransfer: prolongation S, restriction R = Sᵀ, projection Q.
#include "mlshell/level_transfer.hpp"

namespace mlshell {

LinearTransfer::LinearTransfer(Mat S, Mat R, Mat Q, double relative_cost, Operation least_squares)
    : S_(S),
      R_(R),
      Q_(Q),
      relative_cost_(relative_cost),
      least_squares_(std::move(least_squares)) {}

LinearTransfer::~LinearTransfer() {
  VecDestroy(&difference_);
  VecDestroy(&inverse_row_sums_);
}

PetscErrorCode LinearTransfer::prolong(Vec coarse, Vec fine) const {
  return MatMult(S_, coarse, fine);
}

PetscErrorCode LinearTransfer::prolong_correction(Vec x0, Vec x, Vec fine_correction) const {
  PetscFunctionBeginUser;
  if (!difference_) PetscCall(VecDuplicate(x, &difference_));
  PetscCall(VecWAXPY(difference_, -1.0, x0, x));
  PetscCall(MatMult(S_, difference_, fine_correction));
  PetscFunctionReturn(0);
}

PetscErrorCode LinearTransfer::prolong_direction(Vec, Vec direction, Vec fine) const {
  return MatMult(S_, direction, fine);
}

PetscErrorCode LinearTransfer::restrict_gradient(Vec, Vec fine_gradient,
                                                 Vec coarse_gradient) const {
  return MatMult(R_, fine_gradient, coarse_gradient);
}

PetscErrorCode LinearTransfer::coarse_operator(Vec, Mat fine, MatReuse reuse, Mat* coarse) const {
  return MatPtAP(fine, S_, reuse, PETSC_DEFAULT, coarse);
}

PetscErrorCode LinearTransfer::project(Vec fine, Vec coarse, Projection kind) const {
  PetscFunctionBeginUser;
  switch (kind) {
    case Projection::kNatural:
      PetscCall(MatMult(Q_, fine, coarse));
      break;
    case Projection::kLeastSquares:
      PetscCheck(static_cast<bool>(least_squares_),
                 PetscObjectComm(reinterpret_cast<PetscObject>(S_)), PETSC_ERR_SUP,
                 "this transfer has no least-squares projection");
      PetscCall(least_squares_(fine, coarse));
      break;
    case Projection::kScaledRestriction:
      if (!inverse_row_sums_) {  // diag(R 1)⁻¹
        Vec ones;
        PetscCall(MatCreateVecs(R_, &ones, nullptr));
        PetscCall(VecSet(ones, 1.0));
        PetscCall(VecDuplicate(coarse, &inverse_row_sums_));
        PetscCall(MatMult(R_, ones, inverse_row_sums_));
        PetscCall(VecReciprocal(inverse_row_sums_));
        PetscCall(VecDestroy(&ones));
      }
      PetscCall(MatMult(R_, fine, coarse));
      PetscCall(VecPointwiseMult(coarse, coarse, inverse_row_sums_));
      break;
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
