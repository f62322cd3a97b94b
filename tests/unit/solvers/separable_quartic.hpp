// A separable convex objective for solver tests, f(x) = Σ ½ a_i x_i² + ¼ x_i⁴ − b_i x_i, whose
// Newton matrix a test may scale (s (a_i + 3 x_i²) on the diagonal) to distort it.
#pragma once

#include <petscmat.h>

#include <cmath>
#include <utility>
#include <vector>

#include "mlshell/objective.hpp"

namespace mlshell {

class SeparableQuartic : public Objective {
 public:
  SeparableQuartic(std::vector<double> a, std::vector<double> b, double matrix_scale = 1.0)
      : a_(std::move(a)), b_(std::move(b)), scale_(matrix_scale) {}
  int size() const { return static_cast<int>(a_.size()); }
  PetscErrorCode objective(Vec x, PetscReal* f, Vec g) override {
    const PetscScalar* v;
    PetscCall(VecGetArrayRead(x, &v));
    PetscScalar* gv = nullptr;
    if (g) PetscCall(VecGetArray(g, &gv));
    double sum = 0.0;
    for (int i = 0; i < size(); ++i) {
      sum += 0.5 * a_[i] * v[i] * v[i] + 0.25 * std::pow(v[i], 4) - b_[i] * v[i];
      if (g) gv[i] = a_[i] * v[i] + std::pow(v[i], 3) - b_[i];
    }
    if (g) PetscCall(VecRestoreArray(g, &gv));
    PetscCall(VecRestoreArrayRead(x, &v));
    *f = sum;
    return 0;
  }
  PetscErrorCode hessian(Vec x, Mat H) override {
    const PetscScalar* v;
    PetscCall(VecGetArrayRead(x, &v));
    for (PetscInt i = 0; i < size(); ++i)
      PetscCall(MatSetValue(H, i, i, scale_ * (a_[i] + 3 * v[i] * v[i]), INSERT_VALUES));
    PetscCall(VecRestoreArrayRead(x, &v));
    PetscCall(MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY));
    return 0;
  }
  PetscErrorCode create_hessian(Mat* H) const override {
    PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, size(), size(), 1, nullptr, H));
    for (PetscInt i = 0; i < size(); ++i) PetscCall(MatSetValue(*H, i, i, 0.0, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(*H, MAT_FINAL_ASSEMBLY));
    return MatAssemblyEnd(*H, MAT_FINAL_ASSEMBLY);
  }

 protected:
  std::vector<double> a_, b_;
  double scale_;
};

}  // namespace mlshell
