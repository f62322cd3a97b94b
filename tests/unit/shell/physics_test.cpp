// Energies, gradients and Hessians: finite-difference checks of every effect (pointwise and
// assembled), closed-form states, and the clamped plate against Kirchhoff plate theory.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "mlshell/effect_builder.hpp"
#include "mlshell/effects.hpp"
#include "physics_fixtures.hpp"

using namespace mlshell;

namespace {

MaterialSpec denim() {
  MaterialSpec m;
  m.model = denim_preset();
  m.thickness = 0.66e-3;
  m.density = 0.4;
  return m;
}

MaterialSpec svk(double E = 1e7, double nu = 0.3, double t = 1e-3) {
  MaterialSpec m;
  m.model = SvkMaterial{E, nu};
  m.thickness = t;
  m.density = 1.0;
  return m;
}

}  // namespace

TEST(Material, DensityGradientAndHessianMatchFiniteDifferences) {
  const MaterialSpec specs[] = {denim(), svk()};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> strain(-0.05, 0.05);
  for (const MaterialSpec& spec : specs) {
    auto material = make_material(spec);
    for (int trial = 0; trial < 5; ++trial) {
      const Strain3 e(strain(rng), strain(rng), strain(rng));
      Eigen::Vector3d g;
      Eigen::Matrix3d H;
      material->energy_density(e, &g, &H);
      const double h = 1e-7;
      for (int i = 0; i < 3; ++i) {
        Strain3 ep = e, em = e;
        ep[i] += h;
        em[i] -= h;
        Eigen::Vector3d gp, gm;
        const double fd = (material->energy_density(ep, &gp, nullptr) -
                           material->energy_density(em, &gm, nullptr)) /
                          (2 * h);
        EXPECT_NEAR(g[i], fd, 1e-6 * (1 + std::abs(fd)));
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(H(k, i), (gp[k] - gm[k]) / (2 * h), 1e-5 * (1 + H.norm()));
      }
    }
  }
}

TEST(Material, DenimSmallStrainStiffnessIsK) {
  // φ_j'(0) = 1 (Σ_i μ_ji = 1): at zero strain ∂²ψ/∂Ẽ11² = k1, ∂²ψ/∂Ẽ11∂Ẽ22 = k2, ...
  auto m = make_material(denim());
  Eigen::Vector3d g;
  Eigen::Matrix3d H;
  EXPECT_EQ(m->energy_density(Strain3::Zero(), &g, &H), 0.0);
  EXPECT_NEAR(H(0, 0), 4.79e6, 1e-3);
  EXPECT_NEAR(H(0, 1), 4.52e6, 1e-3);
  EXPECT_NEAR(H(1, 1), 9.03e6, 1e-3);
  EXPECT_NEAR(H(2, 2), 2 * 2.44e6, 1e-3);
}

TEST(ShellKinematics, PointEnergyDerivativesMatchFiniteDifferences) {
  // A curved, sheared reference point and a random deformation.
  Eigen::Vector3d a[5] = {
      {1.0, 0.1, 0.05}, {0.2, 0.9, -0.1}, {0.0, 0.1, 0.4}, {0.05, 0.0, -0.2}, {0.1, -0.05, 0.3}};
  const ShellReference ref = ShellReference::from(a, Eigen::Vector3d(1, 0, 0));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> dist(-0.02, 0.02);
  for (const MaterialSpec& spec : {denim(), svk(1e7, 0.3, 0.05)}) {
    auto material = make_material(spec);
    ShellSection section(*material, spec.thickness, 3);
    double delta[15];
    for (double& d : delta) d = dist(rng);
    Vector15 g;
    Matrix15 H;
    shell_point_energy(ref, section, delta, &g, &H);
    Vector15 g_only;
    EXPECT_NEAR(shell_point_energy(ref, section, delta, &g_only, nullptr),
                shell_point_energy(ref, section, delta, nullptr, nullptr), 1e-12);
    EXPECT_LT((g_only - g).norm(), 1e-10 * (1 + g.norm()));
    const double h = 1e-6;
    for (int i = 0; i < 15; ++i) {
      double dp[15], dm[15];
      std::copy(delta, delta + 15, dp);
      std::copy(delta, delta + 15, dm);
      dp[i] += h;
      dm[i] -= h;
      Vector15 gp, gm;
      const double fd = (shell_point_energy(ref, section, dp, &gp, nullptr) -
                         shell_point_energy(ref, section, dm, &gm, nullptr)) /
                        (2 * h);
      EXPECT_NEAR(g[i], fd, 1e-6 * (1 + g.norm())) << "component " << i;
      const Vector15 col = (gp - gm) / (2 * h);
      EXPECT_LT((H.col(i) - col).norm(), 1e-5 * (1 + H.norm())) << "column " << i;
    }
    EXPECT_LT((H - H.transpose()).norm(), 1e-9 * H.norm());
  }
}

// Assembled checks, one scene per effect family so that a wrong term cannot hide behind another.
class AssembledDerivatives : public ::testing::TestWithParam<const char*> {};

TEST_P(AssembledDerivatives, GradientAndHessianMatchFiniteDifferences) {
  TestProblem tp(GetParam(), PETSC_COMM_SELF);
  Vec u, d, g, gp, gm, Hd;
  PetscCallAbort(PETSC_COMM_SELF, tp.layout->create_vector(&u));
  VecDuplicate(u, &d);
  VecDuplicate(u, &g);
  VecDuplicate(u, &gp);
  VecDuplicate(u, &gm);
  VecDuplicate(u, &Hd);
  tp.random_state(u, 1e-3, 11);
  tp.random_state(d, 1.0, 12);
  PetscReal f, fp, fm;
  tp.problem->objective(u, &f, g);
  // Directional derivative gᵀd against central differences of f.
  const double h = 1e-6;
  VecAXPY(u, h, d);
  tp.problem->objective(u, &fp, gp);
  VecAXPY(u, -2 * h, d);
  tp.problem->objective(u, &fm, gm);
  VecAXPY(u, h, d);
  PetscReal gd;
  VecDot(g, d, &gd);
  EXPECT_NEAR(gd, (fp - fm) / (2 * h), 1e-6 * (std::abs(gd) + 1e-8)) << GetParam();
  // H d against central differences of g.
  Mat H;
  double err, ref;
  hessian_difference(*tp.problem, u, d, gp, gm, Hd, h, &H, &err, &ref);
  EXPECT_LT(err, 1e-5 * ref + 1e-12) << GetParam();
  PetscBool symmetric;
  MatIsSymmetric(H, 1e-8 * ref, &symmetric);
  EXPECT_TRUE(symmetric) << GetParam();
  MatDestroy(&H);
  for (Vec* v : {&u, &d, &g, &gp, &gm, &Hd}) VecDestroy(v);
}

INSTANTIATE_TEST_SUITE_P(Effects, AssembledDerivatives,
                         ::testing::Values("elastic_denim", "elastic_svk", "inertia", "loads",
                                           "dirichlet", "clamp", "extraordinary"));

// The report (summary.json, -mlshell_evaluate) makes one pass of its own: its energies are
// those of each term, their sum the objective, its gradient norm the objective's.
void expect_report_matches_objective(MPI_Comm comm) {
  TestProblem tp("all", comm);
  Vec u, g;
  tp.layout->create_vector(&u);
  VecDuplicate(u, &g);
  tp.random_state(u, 2e-2, 5);
  PetscReal f, gnorm, total, reported_gnorm;
  tp.problem->objective(u, &f, g);
  VecNorm(g, NORM_2, &gnorm);
  std::vector<double> energies, separate;
  const long evaluations = tp.problem->objective_evaluations();
  ASSERT_EQ(tp.problem->report(u, energies, &total, &reported_gnorm), 0);
  EXPECT_EQ(tp.problem->objective_evaluations(), evaluations);
  ASSERT_EQ(tp.problem->term_energies(u, separate), 0);
  ASSERT_EQ(energies.size(), separate.size());
  double magnitude = 0.0;
  for (double e : separate) magnitude += std::abs(e);
  for (size_t i = 0; i < energies.size(); ++i)
    EXPECT_NEAR(energies[i], separate[i], 1e-14 * magnitude) << "term " << i;
  EXPECT_GT(gnorm, 0.0);
  EXPECT_NEAR(total, f, 1e-13 * magnitude);
  EXPECT_NEAR(reported_gnorm, gnorm, 1e-13 * gnorm);
  VecDestroy(&u);
  VecDestroy(&g);
}

TEST(Report, EnergiesSumToTheObjectiveAndTheGradientIsItsGradient) {
  expect_report_matches_objective(PETSC_COMM_SELF);
}

TEST(MpiReport, EnergiesSumToTheObjectiveAndTheGradientIsItsGradient) {
  expect_report_matches_objective(PETSC_COMM_WORLD);
}

TEST(ClosedForm, FlatSheetAtRestHasZeroEnergyAndGradient) {
  TestProblem tp("elastic_denim", PETSC_COMM_SELF);
  Vec u, g;
  tp.layout->create_vector(&u);
  VecDuplicate(u, &g);
  PetscReal f, gnorm;
  tp.problem->objective(u, &f, g);
  VecNorm(g, NORM_2, &gnorm);
  EXPECT_EQ(f, 0.0);
  EXPECT_EQ(gnorm, 0.0);
  VecDestroy(&u);
  VecDestroy(&g);
}

TEST(ClosedForm, UniformStretchGivesEnergyOfEquation33TimesArea) {
  // Catmull–Clark is affine invariant: stretching every control point by λ in x stretches the
  // limit surface uniformly, so Ẽ11 = (λ² − 1)/2, Ẽ22 = Ẽ12 = 0 and κ = 0 everywhere:
  // energy = τ · k1/2 φ1(Ẽ11²) · area, area = 1.
  TestProblem tp("elastic_denim", PETSC_COMM_SELF);
  const double lambda = 1.02, E11 = 0.5 * (lambda * lambda - 1.0);
  ClydeOrthotropicMaterial m(denim_preset());
  const double expected = 0.66e-3 * 0.5 * 4.79e6 * m.phi(0)(E11 * E11).f;
  Vec u;
  tp.layout->create_vector(&u);
  std::vector<double> nat(tp.disc->num_dofs(), 0.0);
  for (int i = 0; i < tp.disc->num_points(); ++i)
    nat[3 * i] = (lambda - 1.0) * tp.disc->mesh().points[i].x();
  tp.layout->scatter_natural(nat, u);
  PetscReal f;
  tp.problem->objective(u, &f, nullptr);
  EXPECT_NEAR(f, expected, 1e-12 * expected);
  VecDestroy(&u);
}

namespace {

/// Centre deflection of the clamped plate example at a given refinement.
double plate_deflection(int refine) {
  Scene scene = parse_scene(std::filesystem::path(MLSHELL_SOURCE_DIR) / "examples/plate.yaml");
  scene.geometry.refine = refine;
  const auto dir =
      std::filesystem::temp_directory_path() / ("mlshell_plate_" + std::to_string(refine));
  const SolvedScene solved = solve_scene(scene, PETSC_COMM_SELF, dir);
  EXPECT_EQ(solved.status, 0);
  const auto& disc =
      dynamic_cast<const SubdivisionDiscretization&>(solved.simulation->discretization());
  const std::vector<double>& u = solved.displacement;
  const SurfacePoint c = nearest_surface_point(disc, Point3(0.5, 0.5, 0.0));
  const PointBasis b = disc.evaluator().evaluate({c})[0];
  double w = 0.0;
  for (int i = 0; i < b.size(); ++i) w += b.w[kValue][i] * u[3 * b.nodes[i] + 2];
  std::filesystem::remove_all(dir);
  return -w;
}

}  // namespace

TEST(Plate, ClampedSquarePlateMatchesKirchhoffTheory) {
  // w = α q a⁴ / D with α = 0.00126 (Timoshenko & Woinowsky-Krieger: 0.00126532).
  const double D = 1e7 * 1e-6 / (12 * (1 - 0.09)), q = 0.1;
  const double w_paper = 0.00126 * q / D, w_exact = 0.00126532 * q / D;
  const double w1 = plate_deflection(1), w2 = plate_deflection(2), w3 = plate_deflection(3);
  EXPECT_NEAR(w3, w_paper, 0.02 * w_paper);
  // Within 0.05 % of Timoshenko's value: the geometrically nonlinear plate is stiffer by about
  // (w/t)² = 2e-4, so the limit lies just below the linear theory.
  EXPECT_NEAR(w3, w_exact, 5e-4 * w_exact);
  // Converging under refinement: the changes contract (5 times at least).
  EXPECT_LT(std::abs(w3 - w2), 0.2 * std::abs(w2 - w1));
  RecordProperty("deflection_refine2", std::to_string(w2));
  RecordProperty("deflection_refine3", std::to_string(w3));
}

TEST(PenaltyParameter, IsThePapersForItsDenimAndScalesWithStiffnessAndSize) {
  // The paper's 1 m denim: beta = h^-5 exactly.
  const PenaltyScale paper{kPaperMembraneStiffness, 1.0};
  EXPECT_DOUBLE_EQ(penalty_parameter(std::nullopt, 5.0, 0.0625, paper), std::pow(0.0625, -5.0));
  EXPECT_EQ(penalty_parameter(2.5, 5.0, 0.0625, paper), 2.5);  // an explicit penalty wins
  // A problem scaled by lambda in size and kappa in stiffness: beta h / (Y tau), the penalty's
  // weight against the membrane stiffness, is unchanged.
  const double lambda = 37.0, kappa = 1e4, h = 0.0625;
  const PenaltyScale scaled{kappa * kPaperMembraneStiffness, lambda};
  const double ratio =
      penalty_parameter(std::nullopt, 5.0, h, paper) * h / paper.membrane_stiffness;
  const double scaled_ratio = penalty_parameter(std::nullopt, 5.0, lambda * h, scaled) * lambda *
                              h / scaled.membrane_stiffness;
  EXPECT_NEAR(scaled_ratio, ratio, 1e-12 * ratio);
}

TEST(PenaltyParameter, ScaleIsReadFromTheMaterialAndTheSurface) {
  TestProblem tp("elastic_denim", PETSC_COMM_SELF);
  MaterialSpec m = denim();
  const PenaltyScale s = PenaltyScale::of(m, *tp.disc, *tp.layout);
  EXPECT_NEAR(s.membrane_stiffness, 9.03e6 * 0.66e-3, 1e-9);
  EXPECT_NEAR(s.length, 1.0, 1e-12);  // the unit square's limit surface, ghosts excluded
  const PenaltyScale v = PenaltyScale::of(svk(2e7, 0.5 * 0.6, 0.01), *tp.disc, *tp.layout);
  EXPECT_NEAR(v.membrane_stiffness, 2e7 / (1 - 0.09) * 0.01, 1e-6);
}

// Each rank evaluates the corners of its own elements: the size is still the whole surface's.
TEST(MpiPenaltyParameter, ScaleIsTheWholeSurfacesOnEveryRank) {
  TestProblem tp("elastic_denim", PETSC_COMM_WORLD);
  EXPECT_NEAR(PenaltyScale::of(denim(), *tp.disc, *tp.layout).length, 1.0, 1e-12);
}
