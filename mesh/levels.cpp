// Operations every hierarchy shares (see levels.hpp).
#include "mlshell/levels.hpp"

namespace mlshell {

Levels::~Levels() {
  for (Vec& v : fine_work_) VecDestroy(&v);
}

PetscErrorCode Levels::composite_norm(int l, Vec x, PetscReal* norm) const {
  PetscFunctionBeginUser;
  if (fine_work_.empty()) {
    fine_work_.assign(finest(), nullptr);
    for (int k = 0; k < finest(); ++k) PetscCall(layout(k + 1).create_vector(&fine_work_[k]));
  }
  Vec current = x;  // on the finest level: ‖x‖ itself
  for (int k = l; k < finest(); ++k) {
    PetscCall(transfer(k).prolong_direction(nullptr, current, fine_work_[k]));
    current = fine_work_[k];
  }
  PetscCall(VecNorm(current, NORM_2, norm));
  PetscFunctionReturn(0);
}

PetscErrorCode Levels::project_down(Vec fine, const std::vector<Vec>& coarse) const {
  PetscFunctionBeginUser;
  Vec from = fine;
  for (int l = finest() - 1; l >= 0; --l) {
    PetscCall(transfer(l).project(from, coarse[l]));
    from = coarse[l];
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
