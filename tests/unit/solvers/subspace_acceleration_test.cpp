// The small trust-region subproblem of the subspace step after a V-cycle
// (subspace_acceleration.hpp): its solution is the global minimiser of the model in the ball,
// checked against the optimality conditions (Moré and Sorensen: (A + μI)a = −b, A + μI positive
// semidefinite, μ ≥ 0, μ(radius − ‖a‖) = 0) and against a dense sample of the ball; and the
// step itself after stand-in V-cycles: it reaches a quadratic's minimiser where the cycles
// contract slowly, and it is not taken where the energy rejects it.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "mlshell/subspace_acceleration.hpp"

using namespace mlshell;

namespace {

double model(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::VectorXd& a) {
  return b.dot(a) + 0.5 * a.dot(A * a);
}

/// The least model value over random points of the ball (on its boundary and inside).
double sampled_minimum(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, double radius) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  double best = 0.0;
  for (int k = 0; k < 20000; ++k) {
    Eigen::VectorXd a(b.size());
    for (Eigen::Index i = 0; i < a.size(); ++i) a(i) = normal(rng);
    a *= radius * (k % 2 ? 1.0 : std::cbrt(uniform(rng))) / a.norm();
    best = std::min(best, model(A, b, a));
  }
  return best;
}

/// The multiplier μ of a boundary solution, from (A + μI)a = −b along a, and the residual of
/// that equation relative to ‖b‖.
std::pair<double, double> multiplier(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                     const Eigen::VectorXd& a) {
  const double mu = -(b + A * a).dot(a) / a.squaredNorm();
  const double residual = (A * a + mu * a + b).norm() / b.norm();
  return {mu, residual};
}

Eigen::MatrixXd spd(int n, double shift) {
  Eigen::MatrixXd M(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) M(i, j) = std::sin(1.0 + i + 3.0 * j);
  return M * M.transpose() + shift * Eigen::MatrixXd::Identity(n, n);
}

}  // namespace

TEST(SmallTrustRegion, InsideTheBallItIsTheNewtonPoint) {
  const Eigen::MatrixXd A = spd(3, 1.0);
  const Eigen::VectorXd b = Eigen::Vector3d(0.3, -0.2, 0.1);
  const Eigen::VectorXd newton = -A.ldlt().solve(b);
  const SmallTrustRegionStep s = solve_small_trust_region(A, b, 10.0 * newton.norm());
  EXPECT_FALSE(s.boundary);
  EXPECT_LT((s.a - newton).norm(), 1e-12 * newton.norm());
  EXPECT_NEAR(s.model, model(A, b, newton), 1e-14);
}

TEST(SmallTrustRegion, OnTheBoundaryItMeetsTheOptimalityConditions) {
  // Positive definite with a radius below the Newton step, then indefinite (negative curvature
  // forces the boundary whatever the radius).
  for (const double shift : {1.0, -4.0}) {
    const Eigen::MatrixXd A = spd(4, shift);
    const double lambda_min = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues()(0);
    ASSERT_EQ(lambda_min < 0.0, shift < 0.0);
    const Eigen::VectorXd b = Eigen::Vector4d(1.0, -2.0, 0.5, 0.25);
    const double radius = 0.05;
    const SmallTrustRegionStep s = solve_small_trust_region(A, b, radius);
    EXPECT_TRUE(s.boundary) << shift;
    EXPECT_NEAR(s.a.norm(), radius, 1e-12 * radius) << shift;
    const auto [mu, residual] = multiplier(A, b, s.a);
    EXPECT_GE(mu, std::max(0.0, -lambda_min) - 1e-10) << shift;
    EXPECT_LT(residual, 1e-10) << shift;
    EXPECT_NEAR(s.model, model(A, b, s.a), 1e-14);
    EXPECT_LE(s.model, sampled_minimum(A, b, radius)) << shift;
  }
}

TEST(SmallTrustRegion, TheHardCaseGoesAlongTheLowestEigenvector) {
  // b has no component along the eigenvector of the negative eigenvalue: −(A + μI)⁻¹b stays
  // inside at μ = −λ_min, and the minimiser reaches the boundary along that eigenvector.
  Eigen::MatrixXd A = Eigen::Vector3d(-1.0, 2.0, 3.0).asDiagonal();
  const Eigen::VectorXd b = Eigen::Vector3d(0.0, 0.3, -0.3);
  const double radius = 1.0;
  const SmallTrustRegionStep s = solve_small_trust_region(A, b, radius);
  EXPECT_TRUE(s.boundary);
  EXPECT_NEAR(s.a.norm(), radius, 1e-12);
  EXPECT_GT(std::abs(s.a(0)), 0.5);  // mostly along e₀
  EXPECT_NEAR(s.a(1), -0.3 / 3.0, 1e-12);  // (A − λ_min I) a = −b on the other components
  EXPECT_NEAR(s.a(2), 0.3 / 4.0, 1e-12);
  EXPECT_LE(s.model, sampled_minimum(A, b, radius));
}

TEST(SmallTrustRegion, NoDescentGivesNoStep) {
  const Eigen::MatrixXd A = spd(2, 1.0);
  const SmallTrustRegionStep s = solve_small_trust_region(A, Eigen::Vector2d::Zero(), 1.0);
  EXPECT_EQ(s.a.norm(), 0.0);
  EXPECT_EQ(s.model, 0.0);
  EXPECT_FALSE(s.boundary);
}

namespace {

/// f(x) = Σ ½ d_i (x_i − m_i)² + k (x_0)⁴ on n entries: a quadratic (k = 0), or one whose
/// quadratic model at 0 is good only near 0 (k > 0, like a membrane stretched by a rotation).
struct QuarticBowl final : Objective {
  std::vector<double> d, m;
  double k = 0.0;
  PetscErrorCode objective(Vec x, PetscReal* f, Vec g) override {
    const PetscScalar* a;
    PetscFunctionBeginUser;
    PetscCall(VecGetArrayRead(x, &a));
    *f = k * std::pow(a[0], 4);
    for (size_t i = 0; i < d.size(); ++i) *f += 0.5 * d[i] * (a[i] - m[i]) * (a[i] - m[i]);
    if (g) {
      PetscScalar* ga;
      PetscCall(VecGetArray(g, &ga));
      for (size_t i = 0; i < d.size(); ++i) ga[i] = d[i] * (a[i] - m[i]);
      ga[0] += 4.0 * k * std::pow(a[0], 3);
      PetscCall(VecRestoreArray(g, &ga));
    }
    PetscCall(VecRestoreArrayRead(x, &a));
    PetscFunctionReturn(0);
  }
  PetscErrorCode hessian(Vec x, Mat H) override {
    const PetscScalar* a;
    PetscFunctionBeginUser;
    PetscCall(VecGetArrayRead(x, &a));
    for (size_t i = 0; i < d.size(); ++i)
      PetscCall(MatSetValue(H, i, i, d[i] + (i == 0 ? 12.0 * k * a[0] * a[0] : 0.0),
                            INSERT_VALUES));
    PetscCall(VecRestoreArrayRead(x, &a));
    PetscCall(MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY));
    PetscFunctionReturn(0);
  }
};

/// A level's trust region on `f` (n entries) and the vectors a test moves it with.
struct Level {
  Vec y = nullptr, s = nullptr;
  Mat H = nullptr;
  std::unique_ptr<LocalTrustRegion> tr;
  Level(QuarticBowl& f, PetscInt n) {
    VecCreateSeq(PETSC_COMM_SELF, n, &y);
    VecDuplicate(y, &s);
    MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 1, nullptr, &H);
    tr = std::make_unique<LocalTrustRegion>(
        f, y, H, std::make_unique<SteihaugTointQp>(PETSC_COMM_SELF, "subspace_test_", 10));
  }
  ~Level() {
    tr.reset();
    VecDestroy(&y);
    VecDestroy(&s);
    MatDestroy(&H);
  }
  /// A stand-in for a V-cycle: from the current iterate y, the step `fraction` of the way to
  /// `target`, accepted.
  void cycle(Vec target, double fraction) {
    VecCopy(tr->solution(), y);
    VecWAXPY(s, -1.0, y, target);
    VecScale(s, fraction);
    PetscReal ft;
    tr->evaluate_trial(s, true, &ft);
    tr->accept_trial();
  }
};

}  // namespace

TEST(SubspaceAcceleration, ExtendsASlowCorrectionToTheMinimiserOfAQuadratic) {
  // Each "V-cycle" removes a tenth of the error along the error itself (contraction 0.9), the
  // slow tail of a V-cycle with one poorly corrected mode. The subspace step extends the
  // correction, within a reach that doubles after each good step on its boundary (1, 2, 4, 8
  // times the correction), and reaches the minimiser within five cycles; the cycles alone
  // would leave 0.9⁵ = 59 % of the error.
  QuarticBowl f;
  f.d = {1.0, 10.0, 100.0};
  f.m = {1.0, -2.0, 0.5};
  Level lv(f, 3);
  Vec minimiser;
  VecDuplicate(lv.y, &minimiser);
  for (PetscInt i = 0; i < 3; ++i) VecSetValue(minimiser, i, f.m[i], INSERT_VALUES);
  VecSet(lv.y, 0.0);
  lv.tr->start(lv.y);
  SubspaceAcceleration subspace(2);
  TrustRegionParameters p;
  const PetscReal delta = 1e10;
  PetscReal error0, error;
  VecNorm(minimiser, NORM_2, &error0);
  int accepted = 0;
  for (int k = 0; k < 5; ++k) {
    lv.cycle(minimiser, 0.1);
    SubspaceStep st;
    ASSERT_EQ(subspace.step(*lv.tr, lv.y, p, delta, &st), 0);
    accepted += st.accepted;
  }
  VecAXPY(minimiser, -1.0, lv.tr->solution());
  VecNorm(minimiser, NORM_2, &error);
  EXPECT_EQ(accepted, 5);
  EXPECT_LT(error, 1e-10 * error0);
  VecDestroy(&minimiser);
}

TEST(SubspaceAcceleration, AStepTheEnergyRejectsIsNotTaken) {
  // f = ½ (x − 1)² + 20 x⁴ after a cycle from −2 to 0: the quadratic model at 0 (curvature 1)
  // puts the minimiser at 1, where f = 20 > f(0) = 0.5 (ρ = −39). The step is rejected, the
  // iterate stays, and the reach shrinks: the next step is shorter.
  QuarticBowl f;
  f.d = {1.0};
  f.m = {1.0};
  f.k = 20.0;
  Level lv(f, 1);
  Vec zero;
  VecDuplicate(lv.y, &zero);
  VecSet(zero, 0.0);
  VecSet(lv.y, -2.0);
  lv.tr->start(lv.y);
  lv.cycle(zero, 1.0);
  ASSERT_NEAR(lv.tr->value(), 0.5, 1e-15);
  SubspaceAcceleration subspace(1);
  TrustRegionParameters p;
  const PetscReal delta = 1e10;
  SubspaceStep st;
  ASSERT_EQ(subspace.step(*lv.tr, lv.y, p, delta, &st), 0);
  EXPECT_TRUE(st.tried);
  EXPECT_FALSE(st.accepted);
  EXPECT_NEAR(st.rho, -39.0, 1e-9);
  EXPECT_NEAR(lv.tr->value(), 0.5, 1e-15);
  PetscReal x;
  VecNorm(lv.tr->solution(), NORM_INFINITY, &x);
  EXPECT_EQ(x, 0.0);
  // The rejected step was 1, half the correction (2): the reach shrinks to γ₁ · ½ = ¼ of it.
  // The same step again is on that boundary, d = 0.5 (relaxation ¼), where f = 1.375:
  // ρ = (0.5 − 1.375) / 0.375 = −7/3, rejected; with the reach kept it would repeat ρ = −39.
  SubspaceStep again;
  ASSERT_EQ(subspace.step(*lv.tr, lv.y, p, delta, &again), 0);
  EXPECT_TRUE(again.tried);
  EXPECT_FALSE(again.accepted);
  EXPECT_NEAR(again.relaxation, 0.25, 1e-14);
  EXPECT_NEAR(again.rho, -7.0 / 3.0, 1e-9);
  VecDestroy(&zero);
}
