// Algorithm 1 of paper 2 (ProxyNewton): each of its stops made to trigger on a separable convex
// objective f(x) = Σ ½ a_i x_i² + ¼ x_i⁴ − b_i x_i, whose Newton matrix the test may distort:
//   STEP_NORM       ‖d‖ below the tolerance (and a following step is in equilibrium);
//   MAX_ITERATIONS  the iteration budget spent far from the minimum;
//   LINE_SEARCH     a Newton matrix 1000× too soft: its steps overshoot, α < γ;
//   LINEAR_SOLVE_FAILED  a negative definite matrix: d ascends, the step refuses it.
#include "mlshell/proxy_step.hpp"
#include "separable_quartic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace mlshell;

namespace {

/// a_i = 1 + i, b_i = 2 − i/2 over six unknowns.
class Quartic final : public SeparableQuartic {
 public:
  explicit Quartic(double matrix_scale)
      : SeparableQuartic({1, 2, 3, 4, 5, 6}, {2.0, 1.5, 1.0, 0.5, 0.0, -0.5}, matrix_scale) {}
  static constexpr int kN = 6;
};

struct StepRun {
  ProxyStepReport report;
  double gradient_norm = 0.0;  // at the step's end
};

StepRun run(double matrix_scale, double start, const ProxyStepSettings& settings,
            ProxyStepReport* second = nullptr) {
  Quartic f(matrix_scale);
  Vec x, g;
  Mat H;
  VecCreateSeq(PETSC_COMM_SELF, Quartic::kN, &x);
  VecDuplicate(x, &g);
  MatCreateSeqAIJ(PETSC_COMM_SELF, Quartic::kN, Quartic::kN, 1, nullptr, &H);
  VecSet(x, start);
  StepRun r;
  {
    ProxyNewton newton(
        f, H, [&](Vec y, Mat A) { return f.hessian(y, A); }, x);
    PetscCallAbort(PETSC_COMM_SELF, newton.step(x, settings, &r.report));
    if (second) PetscCallAbort(PETSC_COMM_SELF, newton.step(x, settings, second));
  }
  PetscReal value;
  f.objective(x, &value, g);
  VecNorm(g, NORM_2, &r.gradient_norm);
  VecDestroy(&x);
  VecDestroy(&g);
  MatDestroy(&H);
  return r;
}

}  // namespace

TEST(ProxyNewton, StopsWhenTheNewtonStepIsBelowTheTolerance) {
  ProxyStepReport again;
  const StepRun r = run(1.0, 3.0, {50, 1e-10, 1e-3}, &again);
  EXPECT_EQ(r.report.stop, "STEP_NORM");
  EXPECT_GT(r.report.iterations, 2);
  EXPECT_FALSE(r.report.equilibrium);
  EXPECT_LT(r.gradient_norm, 1e-8);
  // From the minimiser the next proxy step takes no iteration: Alg. 1's equilibrium.
  EXPECT_EQ(again.stop, "STEP_NORM");
  EXPECT_EQ(again.iterations, 0);
  EXPECT_TRUE(again.equilibrium);
}

TEST(ProxyNewton, StopsAfterItsIterationBudget) {
  const StepRun r = run(1.0, 3.0, {2, 1e-10, 1e-3});
  EXPECT_EQ(r.report.stop, "MAX_ITERATIONS");
  EXPECT_EQ(r.report.iterations, 2);
  EXPECT_FALSE(r.report.equilibrium);
  EXPECT_GT(r.gradient_norm, 1e-3);
}

TEST(ProxyNewton, StopsWhenTheLineSearchStepFallsBelowGamma) {
  // Steps 1000 times too long: halving from α = 1 passes below γ = 0.01 before it fits.
  const StepRun r = run(1e-3, 3.0, {50, 1e-10, 1e-2});
  EXPECT_EQ(r.report.stop, "LINE_SEARCH");
  EXPECT_LT(r.report.alpha, 1e-2);
  EXPECT_EQ(r.report.iterations, 0);
  EXPECT_TRUE(r.report.equilibrium);  // Alg. 1: no iteration taken
  // With γ small enough the same steps are taken, shortened, and the objective falls.
  const StepRun patient = run(1e-3, 3.0, {3, 1e-10, 1e-6});
  EXPECT_EQ(patient.report.iterations, 3);
  EXPECT_GT(patient.report.alpha, 0.0);
}

TEST(ProxyNewton, RefusesADirectionThatDoesNotDescend) {
  const StepRun r = run(-1.0, 3.0, {50, 1e-10, 1e-3});
  EXPECT_EQ(r.report.stop, "LINEAR_SOLVE_FAILED");
  EXPECT_EQ(r.report.iterations, 0);
  EXPECT_FALSE(r.report.equilibrium);
}
