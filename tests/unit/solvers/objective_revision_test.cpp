// An objective that changes when an iterate is accepted (contact's adaptive κ doubles as the
// gap closes): projected Newton and the trust region evaluate f and ∇f at the iterate again
// (Objective::revision), so a solve ends at a minimiser of the final objective, not of the one
// its last gradient was computed for.
#include <gtest/gtest.h>
#include <petscmat.h>

#include <cmath>

#include "mlshell/step_solver.hpp"
#include "separable_quartic.hpp"
#include "solver_test_support.hpp"

using namespace mlshell;

namespace {

/// f(x) = Σ ½ c x_i² + ¼ x_i⁴ − b_i x_i. Each time an accepted iterate is nearly stationary
/// (‖∇f‖ < 10⁻⁴), c doubles (at most three times), as IPC's κ does when the gap stops shrinking.
class Stiffening final : public SeparableQuartic {
 public:
  Stiffening() : SeparableQuartic({1, 1, 1, 1}, {1.0, 1.5, 2.0, 2.5}) {}
  PetscErrorCode accepted(Vec x) override {
    Vec g;
    PetscCall(VecDuplicate(x, &g));
    PetscReal f, gnorm;
    PetscCall(objective(x, &f, g));
    PetscCall(VecNorm(g, NORM_2, &gnorm));
    PetscCall(VecDestroy(&g));
    if (gnorm < 1e-4 && doublings_ < 3) {
      for (double& a : a_) a *= 2;
      ++doublings_;
    }
    return 0;
  }
  long revision() const override { return doublings_; }
  int doublings() const { return doublings_; }
  static constexpr int kN = 4;

 private:
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
