// Trust-region subproblems (Dogleg, Steihaug–Toint CG) and Local_TR (TAO type "tr").
#include "mlshell/trust_region.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "mlshell/local_trust_region.hpp"
#include "mlshell/simulation.hpp"
#include "mlshell/step_solver.hpp"
#include "mlshell/trust_region_qp.hpp"
#include "physics_fixtures.hpp"

using namespace mlshell;

namespace {

/// A diagonal matrix and a vector on PETSC_COMM_SELF.
struct SmallModel {
  Mat H;
  Vec g, s;
  SmallModel(std::vector<double> diag, std::vector<double> grad) {
    const PetscInt n = static_cast<PetscInt>(diag.size());
    MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 1, nullptr, &H);
    MatSetOption(H, MAT_SYMMETRIC, PETSC_TRUE);
    for (PetscInt i = 0; i < n; ++i) MatSetValue(H, i, i, diag[i], INSERT_VALUES);
    MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY);
    MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY);
    VecCreateSeq(PETSC_COMM_SELF, n, &g);
    VecDuplicate(g, &s);
    for (PetscInt i = 0; i < n; ++i) VecSetValue(g, i, grad[i], INSERT_VALUES);
    VecAssemblyBegin(g);
    VecAssemblyEnd(g);
  }
  ~SmallModel() {
    MatDestroy(&H);
    VecDestroy(&g);
    VecDestroy(&s);
  }
  /// Sufficient decrease (SDC) with κ = 0.5, the Cauchy point's guarantee.
  bool sufficient_decrease(const QpResult& r, double radius) const {
    PetscReal gnorm, hnorm;
    VecNorm(g, NORM_2, &gnorm);
    MatNorm(H, NORM_FROBENIUS, &hnorm);
    return r.model_decrease >= 0.5 * gnorm * std::min(gnorm / (1.0 + hnorm), radius) - 1e-14;
  }
};

}  // namespace

TEST(TrustRegionQp, DoglegTakesTheNewtonStepInsideTheRegion) {
  SmallModel m({2.0, 4.0, 1.0}, {1.0, -2.0, 0.5});
  DoglegQp qp(PETSC_COMM_SELF, "test_dogleg_newton_");
  qp.set_operator(m.H);
  QpResult r;
  qp.solve(m.g, 10.0, m.s, r);
  EXPECT_STREQ(r.kind, "newton");
  const PetscScalar* s;
  VecGetArrayRead(m.s, &s);
  EXPECT_NEAR(s[0], -0.5, 1e-14);
  EXPECT_NEAR(s[1], 0.5, 1e-14);
  EXPECT_NEAR(s[2], -0.5, 1e-14);
  VecRestoreArrayRead(m.s, &s);
  // Between the Cauchy point (‖p_C‖ = 0.659) and the Newton point (0.866): the dogleg path,
  // on the boundary, with sufficient decrease; inside ‖p_C‖: the Cauchy point on the boundary.
  qp.solve(m.g, 0.75, m.s, r);
  EXPECT_STREQ(r.kind, "dogleg");
  EXPECT_NEAR(r.step_norm, 0.75, 1e-12);
  EXPECT_TRUE(m.sufficient_decrease(r, 0.75));
  qp.solve(m.g, 0.5, m.s, r);
  EXPECT_STREQ(r.kind, "cauchy");
  EXPECT_NEAR(r.step_norm, 0.5, 1e-12);
  EXPECT_TRUE(m.sufficient_decrease(r, 0.5));
}

TEST(TrustRegionQp, DoglegHandlesAnIndefiniteHessian) {
  // Negative curvature along g: steepest descent to the boundary; a finite step, never NaN.
  SmallModel m({1.0, -3.0}, {0.1, 1.0});
  DoglegQp qp(PETSC_COMM_SELF, "test_dogleg_indefinite_");
  qp.set_operator(m.H);
  QpResult r;
  qp.solve(m.g, 0.7, m.s, r);
  EXPECT_STREQ(r.kind, "cauchy");
  EXPECT_TRUE(std::isfinite(r.step_norm));
  EXPECT_NEAR(r.step_norm, 0.7, 1e-12);
  EXPECT_GT(r.model_decrease, 0.0);
  EXPECT_TRUE(m.sufficient_decrease(r, 0.7));
  // Positive curvature along g, and even along the Newton point, but an indefinite H (found by
  // the inertia of the LDLᵀ factor): the Cauchy point is used.
  SmallModel n({1.0, -0.01}, {1.0, 0.01});
  ASSERT_EQ(qp.set_operator(n.H), 0);
  ASSERT_EQ(qp.solve(n.g, 100.0, n.s, r), 0);
  EXPECT_STREQ(r.kind, "cauchy");
  EXPECT_GT(r.model_decrease, 0.0);
}

TEST(TrustRegionQp, DoglegUsesAShiftedNewtonPointWhenItBeatsTheCauchyPoint) {
  // H = diag(1, 4, −0.001), g = (1, 1, 0.001): positive curvature along g, one small negative
  // eigenvalue. Cauchy: m = −0.4. The Newton point of H + λI (λ = 4e-3, the first tenfold shift
  // that is positive definite) gives m ≈ −0.62: taken, inside the region, and finite.
  SmallModel m({1.0, 4.0, -0.001}, {1.0, 1.0, 0.001});
  DoglegQp qp(PETSC_COMM_SELF, "test_dogleg_shift_");
  ASSERT_EQ(qp.set_operator(m.H), 0);
  QpResult r;
  ASSERT_EQ(qp.solve(m.g, 100.0, m.s, r), 0);
  EXPECT_STREQ(r.kind, "shifted");
  EXPECT_TRUE(std::isfinite(r.step_norm));
  EXPECT_GT(r.model_decrease, 0.6);
  PetscReal model;
  quadratic_model(m.H, m.g, m.s, &model);
  EXPECT_NEAR(r.model_decrease, -model, 1e-14);
  EXPECT_TRUE(m.sufficient_decrease(r, 100.0));
  // A small region: the dogleg path of the shifted point, cut at the boundary.
  ASSERT_EQ(qp.solve(m.g, 0.8, m.s, r), 0);
  EXPECT_NEAR(r.step_norm, 0.8, 1e-12);
  EXPECT_TRUE(m.sufficient_decrease(r, 0.8));
}

TEST(TrustRegionQp, DoglegReadsTheInertiaOfARedundantFactorisation) {
  // Under pc_type redundant the factorisation is the inner solver's (each rank's whole copy of
  // H, reproducible from run to run): its inertia must still reveal the negative eigenvalue,
  // so that the step is the shifted Newton point of the test above (λ = 4e-3), not H⁻¹g.
  const char* options[][2] = {
      {"-test_dogleg_redundant_pc_type", "redundant"},
      {"-test_dogleg_redundant_redundant_pc_type", "cholesky"},
      {"-test_dogleg_redundant_redundant_pc_factor_mat_solver_type", "mumps"}};
  for (const auto& o : options) ASSERT_EQ(PetscOptionsSetValue(nullptr, o[0], o[1]), 0);
  SmallModel m({1.0, 4.0, -0.001}, {1.0, 1.0, 0.001});
  DoglegQp qp(PETSC_COMM_SELF, "test_dogleg_redundant_");
  ASSERT_EQ(qp.set_operator(m.H), 0);
  QpResult r;
  ASSERT_EQ(qp.solve(m.g, 100.0, m.s, r), 0);
  for (const auto& o : options) PetscOptionsClearValue(nullptr, o[0]);
  EXPECT_STREQ(r.kind, "shifted");
  const PetscScalar* s;
  VecGetArrayRead(m.s, &s);
  EXPECT_NEAR(-1e-3 / s[2] + 1e-3, 4e-3, 1e-12);  // λ read back from the step's last entry
  EXPECT_NEAR(s[0], -1.0 / (1.0 + 4e-3), 1e-12);
  VecRestoreArrayRead(m.s, &s);
  EXPECT_TRUE(m.sufficient_decrease(r, 100.0));
}

TEST(TrustRegionQp, DoglegShiftsByTheLeastDecadeFromTheLastShift) {
  // ‖H‖∞ = 4. First indefinite Hessian: the grid starts at 1e-10‖H‖∞ = 4e-10 and climbs tenfold
  // to the first definite H + λI. Later ones start a decade below the last λ.
  DoglegQp qp(PETSC_COMM_SELF, "test_dogleg_least_shift_");
  QpResult r;
  const auto shift_of = [&](double negative) {
    SmallModel m({1.0, 4.0, negative}, {1.0, 1.0, 1e-3});
    EXPECT_EQ(qp.set_operator(m.H), 0);
    EXPECT_EQ(qp.solve(m.g, 1e6, m.s, r), 0);
    EXPECT_STREQ(r.kind, "shifted");
    // The step is −(H + λI)⁻¹g; read λ back from its last entry.
    const PetscScalar* s;
    VecGetArrayRead(m.s, &s);
    const double lambda = -1e-3 / s[2] - negative;
    EXPECT_NEAR(s[0], -1.0 / (1.0 + lambda), 1e-12);
    VecRestoreArrayRead(m.s, &s);
    return lambda;
  };
  EXPECT_NEAR(shift_of(-2e-5), 4e-5, 1e-12);  // 4e-10 … 4e-6 are indefinite
  EXPECT_NEAR(shift_of(-2e-3), 4e-3, 1e-12);  // from 4e-6 up
  EXPECT_NEAR(shift_of(-2e-6), 4e-4, 1e-12);  // a decade below 4e-3 is definite already
  EXPECT_NEAR(shift_of(-2e-6), 4e-5, 1e-12);  // and the next Hessian a decade lower still
  EXPECT_NEAR(shift_of(-2e-6), 4e-6, 1e-12);
  EXPECT_NEAR(shift_of(-2e-6), 4e-6, 1e-12);  // 4e-7 is indefinite: the least decade
}

TEST(TrustRegionQp, DoglegWithAnInexactNewtonPointShiftsWhereCgMeetsNegativeCurvature) {
  // The Newton point from CG, preconditioned by |diag H| (SPD, as PC vpatch is for any H):
  // H = diag(1, 4, −0.001), g = (1, 1, 0.001) has positive curvature along g, and CG's second
  // direction has pᵀHp ≈ −0.004. CG starts over on H + λI, λ on the decade grid from
  // 1e-10‖H‖∞ = 4e-10 up, until it gets through: at λ = 4e-3, where H + λI is positive definite
  // (λ = 4e-4 leaves −6e-4 on the diagonal, which CG meets as it met −0.001). The step is that
  // Newton point, the factorisation's too (DoglegUsesAShiftedNewtonPoint...), and it beats the
  // Cauchy point: m ≈ −0.625 against −0.4.
  PetscOptionsSetValue(nullptr, "-test_dogleg_cg_pc_jacobi_abs", "1");
  SmallModel m({1.0, 4.0, -0.001}, {1.0, 1.0, 0.001});
  DoglegQp qp(PETSC_COMM_SELF, "test_dogleg_cg_", InexactNewton{PCJACOBI, 50, 1e-12});
  PetscOptionsClearValue(nullptr, "-test_dogleg_cg_pc_jacobi_abs");
  ASSERT_EQ(qp.set_operator(m.H), 0);
  QpResult r;
  ASSERT_EQ(qp.solve(m.g, 1e6, m.s, r), 0);
  EXPECT_STREQ(r.kind, "shifted");
  EXPECT_EQ(r.iterations, 9);  // H, then the eight λ = 4e-10, 4e-9, ..., 4e-3
  const PetscScalar* s;
  VecGetArrayRead(m.s, &s);
  EXPECT_NEAR(s[0], -1.0 / 1.004, 1e-10);
  EXPECT_NEAR(s[1], -1.0 / 4.004, 1e-10);
  EXPECT_NEAR(s[2], -0.001 / 0.003, 1e-8);
  VecRestoreArrayRead(m.s, &s);
  EXPECT_GT(r.model_decrease, 0.6);
  EXPECT_TRUE(m.sufficient_decrease(r, 1e6));
  // A Hessian with the same pattern starts a decade below the last λ: 4e-4 fails, 4e-3 holds.
  ASSERT_EQ(qp.set_operator(m.H), 0);
  ASSERT_EQ(qp.solve(m.g, 1e6, m.s, r), 0);
  EXPECT_STREQ(r.kind, "shifted");
  EXPECT_EQ(r.iterations, 3);
}

TEST(TrustRegionQp, DoglegGivesMumpsMoreWorkspaceInsteadOfAShift) {
  // A positive definite path with tiny and large diagonal entries in turn and three long-range
  // couplings per row, factorised without scaling (ICNTL(8) = 0): LDLᵀ delays about 1,700
  // pivots, more than the analysis's estimate allows for with MUMPS's default spare workspace
  // (ICNTL(14) = 20), and the factorisation fails with INFOG(1) = -9. That is no sign of an
  // indefinite H: Dogleg factorises again with more workspace and takes the Newton step (a
  // shift after the failure would damp the soft modes).
  const PetscInt n = 2000;
  Mat H;
  MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 12, nullptr, &H);
  const auto couple = [&](PetscInt i, PetscInt j) {
    MatSetValue(H, i, j, 3e-6, INSERT_VALUES);
    MatSetValue(H, j, i, 3e-6, INSERT_VALUES);
  };
  for (PetscInt i = 0; i < n; ++i) {
    MatSetValue(H, i, i, i % 2 ? 1e3 : 1e-12, INSERT_VALUES);
    if (i + 1 < n) couple(i, i + 1);
    for (PetscInt a : {7919, 112648, 217377})
      if (const PetscInt j = (i * a) % n; (i + j) % 2 == 1) couple(i, j);
  }
  MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY);
  MatSetOption(H, MAT_SYMMETRIC, PETSC_TRUE);
  Vec g, s, r;
  MatCreateVecs(H, &g, nullptr);
  VecSet(g, 1e-9);
  VecDuplicate(g, &s);
  VecDuplicate(g, &r);
  PetscOptionsSetValue(nullptr, "-test_dogleg_workspace_mat_mumps_icntl_8", "0");
  {
    DoglegQp qp(PETSC_COMM_SELF, "test_dogleg_workspace_");
    QpResult result;
    ASSERT_EQ(qp.set_operator(H), 0);
    ASSERT_EQ(qp.solve(g, 1e30, s, result), 0);
    EXPECT_STREQ(result.kind, "newton");
    MatMult(H, s, r);  // H s = −g
    VecAXPY(r, 1.0, g);
    PetscReal residual, gnorm;
    VecNorm(r, NORM_2, &residual);
    VecNorm(g, NORM_2, &gnorm);
    EXPECT_LT(residual, 1e-6 * gnorm);
  }
  // The failure happened (the factor read ICNTL(8) under the solver's prefix), and the larger
  // workspace went into the solver's options.
  PetscInt percent = 0;
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetInt(nullptr, nullptr, "-test_dogleg_workspace_mat_mumps_icntl_14", &percent, &set);
  EXPECT_TRUE(set);
  EXPECT_GE(percent, 100);
  PetscOptionsClearValue(nullptr, "-test_dogleg_workspace_mat_mumps_icntl_8");
  PetscOptionsClearValue(nullptr, "-test_dogleg_workspace_mat_mumps_icntl_14");
  MatDestroy(&H);
  VecDestroy(&g);
  VecDestroy(&s);
  VecDestroy(&r);
}

TEST(TrustRegionQp, RadiusNeededIsTheLeastRadiusThatGivesTheSameStep) {
  // Dogleg, H = diag(2, 4, 1): ‖p_C‖ = 0.659, ‖p_N‖ = 0.866.
  SmallModel m({2.0, 4.0, 1.0}, {1.0, -2.0, 0.5});
  DoglegQp dogleg(PETSC_COMM_SELF, "test_dogleg_needed_");
  dogleg.set_operator(m.H);
  QpResult r;
  dogleg.solve(m.g, 10.0, m.s, r);
  EXPECT_NEAR(r.radius_needed, std::sqrt(0.75), 1e-14);  // the Newton point
  dogleg.solve(m.g, 0.75, m.s, r);
  EXPECT_EQ(r.radius_needed, 0.75);  // on the boundary
  // A Cauchy point inside (indefinite H, no usable Newton point): its length.
  SmallModel c({1.0, -0.01}, {1.0, 0.01});
  DoglegQp cauchy(PETSC_COMM_SELF, "test_dogleg_needed_cauchy_");
  cauchy.set_operator(c.H);
  cauchy.solve(c.g, 100.0, c.s, r);
  ASSERT_STREQ(r.kind, "cauchy");
  EXPECT_NEAR(r.radius_needed, r.step_norm, 1e-14);
  EXPECT_LT(r.radius_needed, 100.0);

  // STCG, plain and Jacobi-preconditioned (the radius then bounds ‖s‖_M): an interior step
  // is returned unchanged by any radius above radius_needed and cut by any radius below.
  SmallModel q({1.0, 30.0, 900.0, 3.0}, {1.0, -2.0, 3.0, 0.5});
  for (const char* pc : {"none", "jacobi"}) {
    SteihaugTointQp stcg(PETSC_COMM_SELF, std::string("test_stcg_needed_") + pc + "_", 50, pc);
    stcg.set_operator(q.H);
    stcg.solve(q.g, 1e3, q.s, r);
    ASSERT_STREQ(r.kind, "interior") << pc;
    const double needed = r.radius_needed;
    Vec first;
    VecDuplicate(q.s, &first);
    VecCopy(q.s, first);
    stcg.solve(q.g, needed * (1 + 1e-9), q.s, r);
    EXPECT_STREQ(r.kind, "interior") << pc;
    VecAXPY(first, -1.0, q.s);
    PetscReal diff;
    VecNorm(first, NORM_INFINITY, &diff);
    EXPECT_LT(diff, 1e-12) << pc;
    stcg.solve(q.g, needed * 0.99, q.s, r);
    EXPECT_STREQ(r.kind, "boundary") << pc;
    VecDestroy(&first);
  }
}

TEST(TrustRegionParameters, ARejectionSkipsTheRadiiThatWouldRepeatTheStep) {
  const TrustRegionParameters p;  // η₁ = 0.1, η₂ = 0.75, γ₁ = 0.5, γ₂ = 2
  EXPECT_EQ(p.updated_radius(0.9, 8.0, 0.1), 16.0);    // very successful: γ₂Δ
  EXPECT_EQ(p.updated_radius(0.5, 8.0, 0.1), 8.0);     // successful: Δ
  EXPECT_EQ(p.updated_radius(1e30, 1e30, 1.0), 1e30);  // capped
  // Rejected: γ₁ᵏΔ with the least k ≥ 1 for which γ₁ᵏ < used (the step's share of Δ).
  EXPECT_EQ(p.updated_radius(0.05, 8.0, 1.0), 4.0);  // on the boundary: the paper's γ₁Δ
  EXPECT_EQ(p.updated_radius(0.05, 8.0, 0.6), 4.0);
  EXPECT_EQ(p.updated_radius(-1.0, 8.0, 0.3), 2.0);
  EXPECT_EQ(p.updated_radius(-1.0, 8.0, 0.25), 1.0);  // γ₁²Δ = ‖s‖ would give the same step
  EXPECT_EQ(p.updated_radius(-PETSC_INFINITY, 1e30, 1e-30), std::ldexp(1e30, -100));
}

TEST(TrustRegionQp, SteihaugTointStopsOnNegativeCurvatureAtTheBoundary) {
  SmallModel m({1.0, -2.0, 3.0}, {0.3, 0.5, -0.2});
  SteihaugTointQp qp(PETSC_COMM_SELF, "test_stcg_", 10);
  qp.set_operator(m.H);
  QpResult r;
  qp.solve(m.g, 0.4, m.s, r);
  EXPECT_STREQ(r.kind, "boundary");
  EXPECT_NEAR(r.step_norm, 0.4, 1e-10);
  PetscReal model;
  quadratic_model(m.H, m.g, m.s, &model);
  EXPECT_NEAR(r.model_decrease, -model, 1e-12);  // KSPCGGetObjFcn is the model value
  EXPECT_TRUE(m.sufficient_decrease(r, 0.4));
}

namespace {

/// The energy and the gradient norm after every iteration (and at the start).
struct History {
  std::vector<double> f, gnorm;
  size_t size() const { return f.size(); }
  double operator[](size_t i) const { return f[i]; }
};

PetscErrorCode record_energy(Tao tao, void* ctx) {
  PetscReal f, g;
  PetscFunctionBeginUser;
  PetscCall(TaoGetSolutionStatus(tao, nullptr, &f, &g, nullptr, nullptr, nullptr));
  static_cast<History*>(ctx)->f.push_back(f);
  static_cast<History*>(ctx)->gnorm.push_back(g);
  PetscFunctionReturn(0);
}

/// Solves the first step of a scene (refine 1) from u = 0 with the given TAO type; returns the
/// solution (natural order), the energy after every iteration and whether it converged.
struct TaoRun {
  std::vector<double> u;
  History history;
  double gradient_tolerance = 0;
  bool converged = false;
  int iterations = 0;
  TrustRegionStatistics stats;  // for type "tr"
};

TaoRun run(const char* example, const char* type, MPI_Comm comm) {
  PetscOptionsSetValue(nullptr, "-tao_type", type);
  Scene scene = parse_scene(std::filesystem::path(MLSHELL_SOURCE_DIR) / "examples" / example);
  scene.geometry.refine = 1;
  SubdivisionDiscretization disc(SubdivisionHierarchy(build_cage(scene.geometry), 1).finest(), 3);
  ParallelLayout layout(comm, disc);
  auto problem = build_level_problem(scene, disc, layout, CageFrame::from(scene.geometry));
  problem->set_time(scene.time.dt);
  TaoRun out;
  {
    StepSolver solver(*problem);
    TaoSetMonitor(solver.tao(), record_energy, &out.history, nullptr);
    Vec u;
    layout.create_vector(&u);
    SolveReport report;
    solver.solve(u, report);
    out.converged = report.converged;
    out.iterations = report.iterations;
    out.gradient_tolerance = report.gradient_tolerance;
    if (std::string(type) == "tr") trust_region_statistics(solver.tao(), &out.stats);
    layout.gather_natural(u, out.u);
    VecDestroy(&u);
  }
  PetscOptionsClearValue(nullptr, "-tao_type");
  return out;
}

}  // namespace

TEST(LocalTrustRegion, ConvergesToTheMinimiserOfPetscsTrustRegionWithMonotoneEnergy) {
  for (const char* example : {"plate.yaml", "trampoline.yaml"}) {
    const TaoRun tr = run(example, "tr", PETSC_COMM_SELF);
    const TaoRun bntr = run(example, "bntr", PETSC_COMM_SELF);
    ASSERT_TRUE(tr.converged) << example;
    ASSERT_TRUE(bntr.converged) << example;
    double diff = 0, norm = 0;
    for (size_t i = 0; i < tr.u.size(); ++i) {
      diff = std::max(diff, std::abs(tr.u[i] - bntr.u[i]));
      norm = std::max(norm, std::abs(bntr.u[i]));
    }
    EXPECT_LT(diff, 1e-6 * norm) << example;
    ASSERT_GT(tr.history.size(), 2u) << example;
    // Work counts: one QP and one trial evaluation per iteration; Hessians only where a QP needs
    // one, at the start and after every accepted step but the last (the converged point needs
    // none; a rejected step reuses its Hessian).
    EXPECT_EQ(tr.stats.qp_solves, tr.iterations) << example;
    EXPECT_EQ(tr.stats.objectives, tr.iterations) << example;
    EXPECT_EQ(tr.stats.hessians, tr.stats.accepted) << example;
    EXPECT_LE(tr.stats.accepted, tr.iterations) << example;
    // Monotone up to f's rounding (a step near the limiting accuracy is accepted if f rose by
    // less than 10 times its evaluation error).
    for (size_t i = 1; i < tr.history.size(); ++i)
      EXPECT_LE(tr.history[i], tr.history[i - 1] + 1e-10 * std::abs(tr.history[i - 1]))
          << example << ": energy rose at iteration " << i;
  }
}

TEST(NewtonBaselines, DampedNewtonAndLinearizedEquationBehaveAsSpecified) {
  // Damped Newton with α = 0.3 on the (nearly linear) plate: each iteration takes 0.3 of the
  // Newton step, so the gradient shrinks by 1 − α = 0.7 per iteration until the tolerance is met.
  const TaoRun damped = run("plate.yaml", "dampednewton", PETSC_COMM_SELF);
  ASSERT_TRUE(damped.converged);
  const std::vector<double>& g = damped.history.gnorm;
  ASSERT_GE(g.size(), 20u);
  for (size_t i = 1; i < g.size(); ++i)
    EXPECT_NEAR(g[i] / g[i - 1], 0.7, 0.02)
        << "iteration " << i << ": |g| " << g[i - 1] << " -> " << g[i];
  // As many iterations as the rate needs to bring |g| to the tolerance, and not one more.
  EXPECT_LE(g.back(), damped.gradient_tolerance);
  EXPECT_GT(g[g.size() - 2], damped.gradient_tolerance);
  // The linearized equation: exactly one Newton step, which on the nearly linear plate lands
  // close to the minimiser. It is reported converged exactly when that step meets the tolerance.
  const TaoRun linearized = run("plate.yaml", "linearized", PETSC_COMM_SELF);
  ASSERT_EQ(linearized.history.size(), 2u);  // the initial point and one step
  const double g1 = linearized.history.gnorm[1];
  EXPECT_LT(g1, 0.5 * linearized.history.gnorm[0]);
  EXPECT_EQ(linearized.converged, g1 <= linearized.gradient_tolerance) << "|g| = " << g1;
  double diff = 0, norm = 0;
  for (size_t i = 0; i < damped.u.size(); ++i) {
    diff = std::max(diff, std::abs(linearized.u[i] - damped.u[i]));
    norm = std::max(norm, std::abs(damped.u[i]));
  }
  EXPECT_LT(diff, 1e-3 * norm);
}
