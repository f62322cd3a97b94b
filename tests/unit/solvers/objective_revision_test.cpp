// An objective that changes when an iterate is accepted (contact's adaptive κ doubles as the
// gap closes): projected Newton and the trust region evaluate f and ∇f at the iterate again
// (Objective::revision), so a solve ends at a minimiser of the final objective, not of the one
// its last gradient was computed for.
#include <gtest/gtest.h>
#include <petscmat.h>

#include <cmath>

#include "mlshell/objective.hpp"
#include "mlshell/step_solver.hpp"
#include "solver_test_support.hpp"

using namespace mlshell;

namespace {

/// f(x) = Σ ½ c x_i² + ¼ x_i⁴ − b_i x_i. Each time an accepted iterate is nearly stationary
/// (‖∇f‖ < 10⁻⁴), c doubles (at most three times), as IPC's κ does when the gap stops shrinking.
class Stiffening final : public Objective {
 public:
  PetscErrorCode objective(Vec x, PetscReal* f, Vec g) override {
    const PetscScalar* a;
    PetscCall(VecGetArrayRead(x, &a));
    PetscScalar* ga = nullptr;
    if (g) PetscCall(VecGetArray(g, &ga));
    double sum = 0.0;
    for (int i = 0; i < kN; ++i) {
      sum += 0.5 * c_ * a[i] * a[i] + 0.25 * std::pow(a[i], 4) - load(i) * a[i];
      if (g) ga[i] = c_ * a[i] + std::pow(a[i], 3) - load(i);
    }
    if (g) PetscCall(VecRestoreArray(g, &ga));
    PetscCall(VecRestoreArrayRead(x, &a));
    *f = sum;
    return 0;
  }
  PetscErrorCode hessian(Vec x, Mat H) override {
    const PetscScalar* a;
    PetscCall(VecGetArrayRead(x, &a));
    for (PetscInt i = 0; i < kN; ++i)
      PetscCall(MatSetValue(H, i, i, c_ + 3 * a[i] * a[i], INSERT_VALUES));
    PetscCall(VecRestoreArrayRead(x, &a));
    PetscCall(MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY));
    return 0;
  }
  PetscErrorCode create_hessian(Mat* H) const override {
    PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, kN, kN, 1, nullptr, H));
    for (PetscInt i = 0; i < kN; ++i) PetscCall(MatSetValue(*H, i, i, 0.0, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(*H, MAT_FINAL_ASSEMBLY));
    return MatAssemblyEnd(*H, MAT_FINAL_ASSEMBLY);
  }
  PetscErrorCode accepted(Vec x) override {
    Vec g;
    PetscCall(VecDuplicate(x, &g));
    PetscReal f, gnorm;
    PetscCall(objective(x, &f, g));
    PetscCall(VecNorm(g, NORM_2, &gnorm));
    PetscCall(VecDestroy(&g));
    if (gnorm < 1e-4 && doublings_ < 3) c_ *= 2, ++doublings_;
    return 0;
  }
  long revision() const override { return doublings_; }
  int doublings() const { return doublings_; }
  static constexpr int kN = 4;

 private:
  static double load(int i) { return 1.0 + 0.5 * i; }
  double c_ = 1.0;
  int doublings_ = 0;
};

}  // namespace

TEST(ObjectiveRevision, SolversEndAtAMinimiserOfTheFinalObjective) {
  for (const char* type : {"pnewton", "tr"}) {
    const ScopedOptions options{{"-tao_type", type}, {"-mlshell_hessian_psd", "false"}};
    Stiffening f;
    Vec x, g;
    VecCreateSeq(PETSC_COMM_SELF, Stiffening::kN, &x);
    VecDuplicate(x, &g);
    VecZeroEntries(x);
    {
      StepSolver solver(f);
      SolveReport report;
      ASSERT_EQ(solver.solve(x, report), 0);
      EXPECT_TRUE(report.converged) << type << ": " << report.reason;
    }
    EXPECT_EQ(f.doublings(), 3) << type;
    PetscReal value, gnorm;
    f.objective(x, &value, g);
    VecNorm(g, NORM_2, &gnorm);
    EXPECT_LT(gnorm, 1e-6) << type << ": the gradient of the objective as it ended";
    VecDestroy(&x);
    VecDestroy(&g);
  }
}
