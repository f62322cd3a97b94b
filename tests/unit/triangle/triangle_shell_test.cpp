// Triangle shells assembled from scenes (paper 2 §3): every effect's gradient and Hessian
// against finite differences of the assembled energy, zero energy at rest for flat and curved
// rest shapes, a uniform stretch against the closed-form neo-Hookean energy, and the
// quasistatic integrator's equilibrium.
#include <Eigen/Eigenvalues>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "mlshell/effects.hpp"
#include "mlshell/step_solver.hpp"
#include "mlshell/triangle/triangle_effects.hpp"
#include "mlshell/triangle/triangle_selection.hpp"
#include "triangle_fixtures.hpp"

using namespace mlshell;

namespace {

const char* kMaterial =
    "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: 0.01, "
    "volume_density: 500}\n";

/// f, ∇f and H·d of one term (alone) at u, on one rank.
struct TermCheck {
  double f;
  std::vector<double> g, Hd;
};

/// The Hessian of one term (alone) at u, on one rank.
Mat term_hessian(TriangleProblem& tp, const EnergyTerm& term, const std::vector<double>& u) {
  Mat H;
  PetscCallAbort(PETSC_COMM_SELF, tp.problem->create_matrix(&H));
  // The pattern the whole problem's Hessian has (the elastic term fills the element stencils),
  // into which constant Hessians are added; then only this term's values.
  Vec uv;
  PetscCallAbort(PETSC_COMM_SELF, MatCreateVecs(H, &uv, nullptr));
  PetscCallAbort(PETSC_COMM_SELF, tp.problem->hessian(uv, H));
  PetscCallAbort(PETSC_COMM_SELF, VecDestroy(&uv));
  PetscCallAbort(PETSC_COMM_SELF, MatZeroEntries(H));
  CompensatedSum ignored;
  PetscCallAbort(PETSC_COMM_SELF, term.add(u, ignored, nullptr, H));
  PetscCallAbort(PETSC_COMM_SELF, MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY));
  PetscCallAbort(PETSC_COMM_SELF, MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY));
  PetscCallAbort(PETSC_COMM_SELF, term.add_constant_hessian(H));
  return H;
}

TermCheck evaluate_term(TriangleProblem& tp, const EnergyTerm& term, const std::vector<double>& u,
                        const std::vector<double>& d) {
  TermCheck out;
  CompensatedSum e;
  out.g.assign(u.size(), 0.0);
  PetscCallAbort(PETSC_COMM_SELF, term.add(u, e, &out.g, nullptr));
  out.f = e.value();
  Mat H = term_hessian(tp, term, u);
  Vec dv, hd;
  PetscCallAbort(PETSC_COMM_SELF, MatCreateVecs(H, &dv, &hd));
  PetscScalar* a;
  VecGetArray(dv, &a);
  std::copy(d.begin(), d.end(), a);
  VecRestoreArray(dv, &a);
  MatMult(H, dv, hd);
  const PetscScalar* r;
  VecGetArrayRead(hd, &r);
  out.Hd.assign(r, r + d.size());
  VecRestoreArrayRead(hd, &r);
  VecDestroy(&dv);
  VecDestroy(&hd);
  MatDestroy(&H);
  return out;
}

double norm(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

/// Central differences of f along d (gradient) and of ∇f along d (Hessian), each compared
/// with the term's own scale.
void expect_derivatives(TriangleProblem& tp, const EnergyTerm& term, const std::vector<double>& u,
                        double step, const std::string& what) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  std::vector<double> d(u.size());
  for (double& x : d) x = r(rng);
  const TermCheck at = evaluate_term(tp, term, u, d);
  std::vector<double> up(u), um(u);
  for (size_t i = 0; i < u.size(); ++i) up[i] += step * d[i], um[i] -= step * d[i];
  const TermCheck p = evaluate_term(tp, term, up, d), m = evaluate_term(tp, term, um, d);
  double gd = 0;
  for (size_t i = 0; i < u.size(); ++i) gd += at.g[i] * d[i];
  const double fd = (p.f - m.f) / (2 * step);
  EXPECT_NEAR(fd, gd, 1e-6 * (std::abs(gd) + norm(at.g) * norm(d)) + 1e-300) << what;
  std::vector<double> hd_fd(u.size()), diff(u.size());
  for (size_t i = 0; i < u.size(); ++i) {
    hd_fd[i] = (p.g[i] - m.g[i]) / (2 * step);
    diff[i] = hd_fd[i] - at.Hd[i];
  }
  EXPECT_LE(norm(diff), 1e-5 * norm(at.Hd) + 1e-300) << what << ": |H d| = " << norm(at.Hd);
  EXPECT_GT(norm(at.Hd) + std::abs(gd), 0.0) << what << ": the check must see the term";
}

std::vector<double> random_displacement(size_t n, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> r(-amplitude, amplitude);
  std::vector<double> u(n);
  for (double& x : u) x = r(rng);
  return u;
}

}  // namespace

TEST(TriangleShell, EveryEffectMatchesFiniteDifferencesOnItsOwnScale) {
  // Hinge bending; midedge bending with a second clamp, so that the corner triangle at the
  // bottom right has two held edges.
  for (const std::string bending : {"hinge", "midedge"}) {
    std::string material = kMaterial;
    material.insert(material.rfind('}'), ", bending: " + bending);
    const Scene scene = triangle_scene(
        "fd",
        std::string("geometry: {mesh: {generator: rectangle, size: [1, 0.5], faces: [4, 3]}}\n") +
            material +
            (bending == "midedge" ? "effects:\n  - clamp: {where: boundary(right)}\n"
                                  : "effects:\n") +
            "  - inertia\n"
            "  - gravity: [0, 0, -9.81]\n"
            "  - surface_load: {force_per_area: [0, 1, 2]}\n"
            "  - line_load: {where: boundary(right), force_per_length: [0, 0, 1]}\n"
            "  - point_load: {where: corner(top-right), force: [1, 0, 0]}\n"
            "  - dirichlet: {where: boundary(left), motion: {translate: [0, 0, 0.1], "
            "over: [0, 1]}}\n"
            "  - clamp: {where: boundary(bottom), motion: {translate: [0, 0.05, 0.02], "
            "over: [0, 1]}}\n"
            "time: {dt: 0.5, steps: 2}\n");
    TriangleProblem tp(scene, PETSC_COMM_SELF);
    std::vector<double> pred = random_displacement(3 * tp.disc().num_points(), 0.02, 5);
    StepStart start{0.5, &pred};
    for (const auto& t : tp.problem->terms()) t->begin_step(start);
    const auto u = random_displacement(3 * tp.disc().num_points(), 0.05, 3);
    for (const auto& t : tp.problem->terms())
      expect_derivatives(tp, *t, u, 1e-6, bending + " " + t->name());
  }
}

TEST(TriangleShell, StVenantKirchhoffMembraneMatchesFiniteDifferences) {
  const Scene scene = triangle_scene(
      "fd_svk",
      "geometry: {mesh: {generator: dome, radius: 1, opening_angle: 1.2, rings: 4}}\n"
      "material: {model: st-venant-kirchhoff, youngs_modulus: 1.0e6, poisson_ratio: 0.3, "
      "thickness: 0.01, volume_density: 500}\n"
      "time: {dt: 1, steps: 1}\n");
  TriangleProblem tp(scene, PETSC_COMM_SELF);
  const auto u = random_displacement(3 * tp.disc().num_points(), 0.05, 9);
  expect_derivatives(tp, *tp.problem->terms()[0], u, 1e-6, "elastic (svk)");
}

TEST(TriangleShell, PressureMatchesFiniteDifferencesAndTheEnclosedVolume) {
  const Scene scene = triangle_scene(
      "fd_pressure",
      std::string("geometry: {mesh: {generator: sphere, radius: 0.5, subdivisions: 2}}\n") +
          kMaterial + "effects:\n  - pressure: {pressure: 1000}\ntime: {dt: 1, steps: 1}\n");
  TriangleProblem tp(scene, PETSC_COMM_SELF);
  const EnergyTerm& pressure = *tp.problem->terms()[1];
  ASSERT_EQ(pressure.name(), "pressure");
  const auto u = random_displacement(3 * tp.disc().num_points(), 0.02, 4);
  expect_derivatives(tp, pressure, u, 1e-6, "pressure");
  // A uniform scaling x = s X changes the volume by (s³ − 1) V: the energy is −p (s³ − 1) V.
  std::vector<double> scale(3 * tp.disc().num_points());
  for (int i = 0; i < tp.disc().num_points(); ++i)
    for (int c = 0; c < 3; ++c) scale[3 * i + c] = 0.1 * tp.disc().points()[i][c];
  CompensatedSum e;
  PetscCallAbort(PETSC_COMM_SELF, pressure.add(scale, e, nullptr, nullptr));
  double volume = 0.0;  // of the inscribed polyhedron
  for (const Triangle& t : tp.disc().mesh().triangles) {
    const auto& X = tp.disc().points();
    volume += X[t[0]].dot(X[t[1]].cross(X[t[2]])) / 6.0;
  }
  EXPECT_NEAR(e.value(), -1000.0 * (1.1 * 1.1 * 1.1 - 1.0) * volume, 1e-10 * 1000.0 * volume);
}

namespace {

/// The dense matrix of H (one rank).
Eigen::MatrixXd dense(Mat H) {
  Mat D;
  PetscCallAbort(PETSC_COMM_SELF, MatConvert(H, MATSEQDENSE, MAT_INITIAL_MATRIX, &D));
  PetscInt m, n;
  PetscCallAbort(PETSC_COMM_SELF, MatGetSize(D, &m, &n));
  const PetscScalar* a;
  PetscCallAbort(PETSC_COMM_SELF, MatDenseGetArrayRead(D, &a));
  Eigen::MatrixXd out = Eigen::Map<const Eigen::MatrixXd>(a, m, n);  // column-major, lda = m
  PetscCallAbort(PETSC_COMM_SELF, MatDenseRestoreArrayRead(D, &a));
  PetscCallAbort(PETSC_COMM_SELF, MatDestroy(&D));
  return out;
}

std::string pressure_scene(const std::string& geometry, double pressure) {
  return geometry + kMaterial + "effects:\n  - pressure: {pressure: " + std::to_string(pressure) +
         "}\ntime: {dt: 1, steps: 1}\n";
}

}  // namespace

// The balloon's sphere (examples/triangle/balloon.yaml), at the origin and far from it, inflated
// by a displacement: the assembled exact Hessian (Σ_e M_e) is indefinite, the projected one
// (-mlshell_pressure_psd, each M_e projected) is PSD, and both are the same wherever the body
// sits (no centre). V(X) is the volume about the origin.
TEST(TriangleShell, PressureHessianPerEdgeIsPsdWhenProjected) {
  const Point3 offset(3.0, -2.0, 1.0);
  const auto obj = write_sphere_obj("offset_sphere", 0.1, 3, offset, false);
  const Scene far = triangle_scene(
      "offset_pressure", pressure_scene("geometry: {mesh: {obj: " + obj.string() + "}}\n", 200));
  const Scene near = triangle_scene(
      "origin_pressure",
      pressure_scene("geometry: {mesh: {generator: sphere, radius: 0.1, subdivisions: 3}}\n", 200));
  TriangleProblem tp(far, PETSC_COMM_SELF), at_origin(near, PETSC_COMM_SELF);
  std::filesystem::remove(obj);
  const auto* pressure = dynamic_cast<const PressureTerm*>(tp.problem->terms()[1].get());
  const auto* pressure0 = dynamic_cast<const PressureTerm*>(at_origin.problem->terms()[1].get());
  ASSERT_TRUE(pressure && pressure0);
  const auto& X = tp.disc().points();
  double volume = 0.0;  // about the origin
  for (const Triangle& t : tp.disc().mesh().triangles)
    volume += X[t[0]].dot(X[t[1]].cross(X[t[2]])) / 6.0;
  EXPECT_GT(pressure->enclosed_volume(), 0.0);
  EXPECT_NEAR(pressure->enclosed_volume(), volume, 1e-12 * volume);
  EXPECT_NEAR(pressure->enclosed_volume(), pressure0->enclosed_volume(), 1e-11 * volume);

  // Inflated by 10 % and jiggled by 1 mm.
  auto u = random_displacement(3 * tp.disc().num_points(), 1e-3, 4);
  for (int i = 0; i < tp.disc().num_points(); ++i)
    for (int c = 0; c < 3; ++c) u[3 * i + c] += 0.1 * (X[i][c] - offset[c]);
  for (const bool project : {false, true}) {
    tp.problem->terms()[1]->set_hessian_projection(project);
    at_origin.problem->terms()[1]->set_hessian_projection(project);
    Mat H = term_hessian(tp, *pressure, u), H0 = term_hessian(at_origin, *pressure0, u);
    const Eigen::MatrixXd A = dense(H), A0 = dense(H0);
    MatDestroy(&H);
    MatDestroy(&H0);
    ASSERT_GT(A.norm(), 0.0);
    EXPECT_LE((A - A0).norm(), 1e-12 * A.norm()) << "projected: " << project;
    EXPECT_EQ((A - A.transpose()).norm(), 0.0);
    const double lowest =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly).eigenvalues()[0];
    if (project)
      EXPECT_GE(lowest, -1e-13 * A.norm());
    else  // −p ∇²V: indefinite
      EXPECT_LT(lowest, -1e-3 * A.norm());
  }
}

// Pressure needs a closed surface oriented outwards: faces turned inwards enclose a negative
// volume (a positive pressure would deflate the surface), and an open surface encloses none.
TEST(TriangleShell, PressureRefusesAnInwardOrAnOpenSurface) {
  const auto obj = write_sphere_obj("inward_sphere", 0.5, 2, Point3(1.0, 0.0, 0.0), true);
  const Scene inward = triangle_scene(
      "inward_pressure", pressure_scene("geometry: {mesh: {obj: " + obj.string() + "}}\n", 1000));
  try {
    TriangleProblem tp(inward, PETSC_COMM_SELF);
    ADD_FAILURE() << "an inward surface under pressure was accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    for (const std::string part :
         {inward.file.string() + ": effects[0].pressure: ", std::string("V(X) = -0.505881 m^3"),
          std::string("oriented inwards"), std::string("flip the orientation of every face")})
      EXPECT_NE(what.find(part), std::string::npos) << part << " not in: " << what;
  }
  std::filesystem::remove(obj);
  const Scene open = triangle_scene(
      "open_pressure",
      pressure_scene("geometry: {mesh: {generator: rectangle, size: [1, 1], faces: [4, 4]}}\n",
                     100));
  try {
    TriangleProblem tp(open, PETSC_COMM_SELF);
    ADD_FAILURE() << "an open surface under pressure was accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("effects[0].pressure: pressure needs a closed surface"), std::string::npos)
        << what;
  }
}

TEST(TriangleShell, RestShapesAreStressFree) {
  for (const std::string geometry :
       {"{generator: rectangle, size: [1, 1], faces: [5, 5]}",
        "{generator: rectangle, size: [1, 1], edge_length: 0.2}",
        "{generator: dome, radius: 1, opening_angle: 1.5, rings: 6}",
        "{generator: cylinder, radius: 0.3, length: 1, faces: [12, 4]}",
        "{generator: cylinder, radius: 0.3, length: 1, faces: [12, 4], imperfection: "
        "[{amplitude: 0.01}, {amplitude: 0.02, waves: [3, 2], phase: 0.5}]}",
        "{generator: sphere, radius: 1, subdivisions: 2}"}) {
    const Scene scene = triangle_scene(
        "rest", "geometry: {mesh: " + geometry + "}\n" + kMaterial + "time: {dt: 1, steps: 1}\n");
    TriangleProblem tp(scene, PETSC_COMM_SELF);
    const std::vector<double> zero(3 * tp.disc().num_points(), 0.0);
    // A rigid rotation and translation of the rest shape is stress-free too.
    std::vector<double> rigid(zero.size());
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
    for (int i = 0; i < tp.disc().num_points(); ++i) {
      const Point3& X = tp.disc().points()[i];
      const Eigen::Vector3d x = R * X + Eigen::Vector3d(0.3, -0.2, 0.5);
      for (int c = 0; c < 3; ++c) rigid[3 * i + c] = x[c] - X[c];
    }
    for (const std::vector<double>* u : {&zero, const_cast<const std::vector<double>*>(&rigid)}) {
      CompensatedSum e;
      std::vector<double> g(zero.size(), 0.0);
      PetscCallAbort(PETSC_COMM_SELF, tp.problem->terms()[0]->add(*u, e, &g, nullptr));
      // Scale: the membrane energy of a 1 % stretch of the whole surface.
      EXPECT_LE(std::abs(e.value()), 1e-9 * 1e6 * 0.01 * 1e-4) << geometry;
      EXPECT_LE(norm(g), 1e-6 * 1e6 * 0.01 * 1e-2) << geometry;
    }
  }
}

TEST(TriangleShell, UniformStretchGivesTheClosedFormNeoHookeanEnergy) {
  const Scene scene = triangle_scene(
      "stretch",
      std::string("geometry: {mesh: {generator: rectangle, size: [2, 1], edge_length: 0.25}}\n") +
          kMaterial + "time: {dt: 1, steps: 1}\n");
  TriangleProblem tp(scene, PETSC_COMM_SELF);
  const double s1 = 1.2, s2 = 0.9;
  std::vector<double> u(3 * tp.disc().num_points(), 0.0);
  for (int i = 0; i < tp.disc().num_points(); ++i) {
    u[3 * i] = (s1 - 1.0) * tp.disc().points()[i][0];
    u[3 * i + 1] = (s2 - 1.0) * tp.disc().points()[i][1];
  }
  CompensatedSum e;
  PetscCallAbort(PETSC_COMM_SELF, tp.problem->terms()[0]->add(u, e, nullptr, nullptr));
  const double E = 1e6, nu = 0.3, tau = 0.01, area = 2.0;
  const double mu = E / (2 * (1 + nu)), lambda = E * nu / (1 - nu * nu);  // plane stress
  const double J = s1 * s2;
  const double psi =
      mu / 2 * (s1 * s1 + s2 * s2 - 2 - 2 * std::log(J)) + lambda / 2 * std::log(J) * std::log(J);
  EXPECT_NEAR(e.value(), tau * area * psi, 1e-10 * tau * area * psi);
}

TEST(TriangleShell, AugmentedLagrangianTermMatchesFiniteDifferences) {
  const Scene scene = triangle_scene(
      "fd_al",
      std::string("geometry: {mesh: {generator: rectangle, size: [1, 1], faces: [3, 3]}}\n") +
          kMaterial +
          "effects:\n  - dirichlet: {where: boundary(left), tolerance: 1e-9, "
          "motion: {translate: [0, 0, 0.1], over: [0, 1]}}\ntime: {dt: 1, steps: 1}\n");
  TriangleProblem tp(scene, PETSC_COMM_SELF);
  EnergyTerm& dirichlet = *tp.problem->terms()[1];
  ASSERT_TRUE(dirichlet.has_multipliers());
  const auto u = random_displacement(3 * tp.disc().num_points(), 0.05, 13);
  // Nonzero multipliers: one update at a violated state.
  CompensatedSum before;
  PetscCallAbort(PETSC_COMM_SELF, dirichlet.add(u, before, nullptr, nullptr));
  dirichlet.update_multipliers(u, 1.0);
  CompensatedSum after;
  PetscCallAbort(PETSC_COMM_SELF, dirichlet.add(u, after, nullptr, nullptr));
  EXPECT_GT(after.value(), before.value());  // −λ·c with λ = −β w c adds β w |c|²
  expect_derivatives(tp, dirichlet, u, 1e-6, "dirichlet (augmented Lagrangian)");
}

TEST(TriangleShell, AugmentedLagrangianDrivesTheViolationBelowItsTolerance) {
  // A soft explicit penalty lets a loaded dome's rim move by about f / β; the multipliers
  // bring it below the tolerance.
  for (const char* mode : {"", ", tolerance: 1e-9"}) {
    const Scene scene = triangle_scene(
        "al", std::string("geometry: {mesh: {generator: dome, radius: 1, opening_angle: 1.0, "
                          "rings: 5}}\n") +
                  kMaterial + "effects:\n  - dirichlet: {where: boundary, penalty: 1e4" + mode +
                  "}\n  - point_load: {where: {at: [0, 0, 1]}, force: [0, 0, -20]}\n"
                  "time: {dt: 1, steps: 1, integrator: quasistatic}\n");
    const SolvedScene solved = solve_scene(
        scene, PETSC_COMM_SELF, (std::filesystem::temp_directory_path() / "mlshell_al").string());
    ASSERT_EQ(solved.status, 0) << mode;
    std::vector<double> violations;
    PetscCallAbort(PETSC_COMM_SELF, solved.simulation->problem().constraint_violations(
                                        solved.simulation->displacement(), violations));
    double worst = 0.0;
    for (double v : violations) worst = std::max(worst, v);
    if (*mode)
      EXPECT_LE(worst, 1e-9);
    else
      EXPECT_GT(worst, 1e-5);  // the penalty alone lets go
  }
}

TEST(TriangleShell, SelectionsResolveToVertices) {
  const Scene scene = triangle_scene(
      "select",
      std::string("geometry: {mesh: {generator: rectangle, size: [2, 1], faces: [4, 2]}}\n") +
          kMaterial + "time: {dt: 1, steps: 1}\n");
  TriangleProblem tp(scene, PETSC_COMM_SELF);
  const CageFrame frame = CageFrame::from(scene.geometry);
  const auto& X = tp.disc().points();
  CurveSelection all;
  EXPECT_EQ(select_vertices(tp.disc(), all, frame, "boundary").size(), 12u);  // 5×3 grid, 3 inside
  CurveSelection left;
  left.kind = CurveSelection::Kind::Side;
  left.side = "left";
  const auto l = select_vertices(tp.disc(), left, frame, "boundary(left)");
  ASSERT_EQ(l.size(), 3u);
  for (int v : l) EXPECT_EQ(X[v][0], 0.0);
  CurveSelection group;
  group.kind = CurveSelection::Kind::Group;
  group.group = "left";
  EXPECT_EQ(select_vertices(tp.disc(), group, frame, "group(left)"), l);
  CurveSelection loop;
  loop.kind = CurveSelection::Kind::Loop;
  EXPECT_EQ(select_vertices(tp.disc(), loop, frame, "boundary(loop 0)").size(), 12u);
  loop.loop = 1;
  EXPECT_THROW(select_vertices(tp.disc(), loop, frame, "boundary(loop 1)"), SceneError);
  CurveSelection box;
  box.kind = CurveSelection::Kind::Box;
  box.box_min = {0.9, 0.4, -1};
  box.box_max = {1.1, 0.6, 1};
  const auto b = select_vertices(tp.disc(), box, frame, "box");
  ASSERT_EQ(b.size(), 1u);  // the interior vertex (1, 0.5)
  EXPECT_EQ(X[b[0]], Point3(1.0, 0.5, 0.0));
  PointSelection corner;
  corner.kind = PointSelection::Kind::Corner;
  corner.corner = "top-right";
  EXPECT_EQ(X[select_vertex(tp.disc(), corner, frame, "corner")], Point3(2, 1, 0));
  PointSelection at;
  at.at = {0.45, 0.3, 0.2};
  EXPECT_EQ(X[select_vertex(tp.disc(), at, frame, "at")], Point3(0.5, 0.5, 0));
  // The boundary edges among the left side's vertices: two, along the side.
  EXPECT_EQ(selected_boundary_edges(tp.disc(), l).size(), 2u);
}

TEST(TriangleShell, ClampMovesWithItsMotionAndResistsRotationWithTheBendingStiffness) {
  // 2 × 1 rectangle of 4 × 2 squares, clamped on the left (two boundary edges of length 0.5,
  // right triangles of area 1/8): a rigid rotation by φ about the clamped edge turns each clamp
  // hinge by exactly φ, so the rotation energy is 2 · 3k|e|²/(Ā + Ā) φ² = 6kφ².
  const Scene scene = triangle_scene(
      "clamp",
      std::string("geometry: {mesh: {generator: rectangle, size: [2, 1], faces: [4, 2]}}\n") +
          kMaterial +
          "effects:\n  - clamp: {where: boundary(left), motion: {translate: [0.1, 0.2, "
          "0.3], over: [0, 1]}}\ntime: {dt: 1, steps: 1}\n");
  TriangleProblem tp(scene, PETSC_COMM_SELF);  // at t = 1: the motion is complete
  const EnergyTerm& penalty = *tp.problem->terms()[1];
  const EnergyTerm& rotation = *tp.problem->terms()[2];
  ASSERT_EQ(rotation.name(), "clamp_rotation");
  const int n = tp.disc().num_points();
  auto energy = [&](const EnergyTerm& t, const std::vector<double>& u) {
    CompensatedSum e;
    PetscCallAbort(PETSC_COMM_SELF, t.add(u, e, nullptr, nullptr));
    return e.value();
  };
  // Following the motion rigidly costs nothing.
  std::vector<double> moved(3 * n);
  for (int i = 0; i < n; ++i) moved[3 * i] = 0.1, moved[3 * i + 1] = 0.2, moved[3 * i + 2] = 0.3;
  EXPECT_NEAR(energy(penalty, moved), 0.0, 1e-20);
  EXPECT_NEAR(energy(rotation, moved), 0.0, 1e-20);
  // A rotation about the clamped edge (the y axis), after the motion.
  const double phi = 0.3, k = 1e6 * 1e-6 / (24.0 * (1.0 - 0.09));
  std::vector<double> rotated(moved);
  for (int i = 0; i < n; ++i) {
    const Point3& X = tp.disc().points()[i];
    rotated[3 * i] += X[0] * (std::cos(phi) - 1.0);
    rotated[3 * i + 2] += X[0] * std::sin(phi);
  }
  EXPECT_NEAR(energy(penalty, rotated), 0.0, 1e-20);  // the clamped edge stays in place
  EXPECT_NEAR(energy(rotation, rotated), 6.0 * k * phi * phi, 1e-12 * k);
}

/// u of the rigid motion X ↦ R_x(φ)(X − c) + c: a turn by φ about the line through c along x.
std::vector<double> turned_about_x(const TriangleDiscretization& disc, double phi,
                                   const Point3& c) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  std::vector<double> u(3 * disc.num_points());
  for (int i = 0; i < disc.num_points(); ++i) {
    const Point3& X = disc.points()[i];
    const Point3 d = R * (X - c) + c - X;
    for (int k = 0; k < 3; ++k) u[3 * i + k] = d[k];
  }
  return u;
}

TEST(TriangleShell, ClampTurnsItsFrameWithARotatingMotion) {
  // A 2 × 1 rectangle clamped on the left, whose motion turns it by π/2 about the line through
  // (0, 0.5, 0) along x. Following the motion rigidly costs nothing, with hinge and midedge
  // bending: the clamp's virtual vertices turn with the motion, so the clamped slope does too.
  // Held at its rest slope instead (the same translation and no rotation), the rotation terms
  // would cost the full quarter turn of every clamped hinge.
  for (const char* bending : {"hinge", "midedge"}) {
    SCOPED_TRACE(bending);
    const Scene scene = triangle_scene(
        "clamp_rotate",
        std::string("geometry: {mesh: {generator: rectangle, size: [2, 1], faces: [4, 2]}}\n") +
            "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, "
            "thickness: 0.01, volume_density: 500, bending: " +
            bending + "}\n" +
            "effects:\n  - clamp: {where: boundary(left), motion: {rotate: {axis: [1, 0, 0], "
            "center: [0, 0.5, 0], angle: 1.5707963267948966}, over: [0, 1]}}\n"
            "time: {dt: 1, steps: 1}\n");
    TriangleProblem tp(scene, PETSC_COMM_SELF);  // at t = 1: the quarter turn is complete
    const EnergyTerm& penalty = *tp.problem->terms()[1];
    const EnergyTerm& rotation = *tp.problem->terms()[2];
    ASSERT_EQ(rotation.name(), "clamp_rotation");
    auto energy = [&](const EnergyTerm& t, const std::vector<double>& u) {
      CompensatedSum e;
      PetscCallAbort(PETSC_COMM_SELF, t.add(u, e, nullptr, nullptr));
      return e.value();
    };
    const std::vector<double> turned =
        turned_about_x(tp.disc(), std::numbers::pi / 2, Point3(0, 0.5, 0));
    EXPECT_NEAR(energy(penalty, turned), 0.0, 1e-20);
    EXPECT_NEAR(energy(rotation, turned), 0.0, 1e-18);
    // Not turned: the penalty and the rotation both resist.
    const std::vector<double> rest(turned.size(), 0.0);
    EXPECT_GT(energy(penalty, rest), 1.0);
    EXPECT_GT(energy(rotation, rest), 1e-3);
    expect_derivatives(tp, rotation, random_displacement(turned.size(), 0.05, 7), 1e-6,
                       "clamp rotation, turned");
  }
}

TEST(TriangleShell, AStripTwistedByItsClampedEndEndsAtTheRotatedPositions) {
  // A 1 × 0.2 strip clamped at both ends; the right end turns by π/2 about the strip's long
  // axis in one quasistatic step. The right end's vertices end where the rotation takes them,
  // to the penalty's accuracy (the default β lets the ends go by 0.8 mm under the twisting
  // moment; β = 1e9, about 1e4 times the default, by 0.1 µm), and the left end stays.
  const Scene scene = triangle_scene(
      "twist",
      std::string("geometry: {mesh: {generator: rectangle, size: [1, 0.2], faces: [10, 2]}}\n") +
          kMaterial +
          "effects:\n  - clamp: {where: boundary(left), penalty: 1e9}\n"
          "  - clamp: {where: boundary(right), penalty: 1e9, motion: {rotate: {axis: [1, 0, 0], "
          "center: [1, 0.1, 0], angle: 1.5707963267948966}, over: [0, 1]}}\n"
          "time: {dt: 1, steps: 1, integrator: quasistatic}\n");
  const SolvedScene solved = solve_scene(
      scene, PETSC_COMM_SELF, (std::filesystem::temp_directory_path() / "mlshell_twist").string());
  ASSERT_EQ(solved.status, 0);
  const auto& disc =
      static_cast<const TriangleDiscretization&>(solved.simulation->discretization());
  const std::vector<double> turned = turned_about_x(disc, std::numbers::pi / 2, Point3(1, 0.1, 0));
  int right = 0, left = 0;
  for (int i = 0; i < disc.num_points(); ++i) {
    const Point3& X = disc.points()[i];
    const Point3 u(solved.displacement[3 * i], solved.displacement[3 * i + 1],
                   solved.displacement[3 * i + 2]);
    if (X[0] == 1.0) {
      ++right;
      const Point3 expected(turned[3 * i], turned[3 * i + 1], turned[3 * i + 2]);
      EXPECT_LT((u - expected).norm(), 1e-6) << "vertex " << i << " at " << X.transpose();
    } else if (X[0] == 0.0) {
      ++left;
      EXPECT_LT(u.norm(), 1e-6) << "vertex " << i;
    }
  }
  EXPECT_EQ(right, 3);
  EXPECT_EQ(left, 3);
}

TEST(TriangleShell, ProjectedNewtonAssemblesAPositiveSemiDefiniteHessian) {
  // A compressed sheet: its membranes are in compression, whose neo-Hookean Hessian is
  // indefinite; projected Newton (the default with pnewton) assembles a PSD Hessian.
  const Scene scene = triangle_scene(
      "psd",
      std::string("geometry: {mesh: {generator: rectangle, size: [1, 1], faces: [3, 3]}}\n") +
          kMaterial + "time: {dt: 1, steps: 1}\n");
  TriangleProblem tp(scene, PETSC_COMM_SELF);
  const int n = tp.disc().num_points();
  Vec u;
  PetscCallAbort(PETSC_COMM_SELF, tp.layout().create_vector(&u));
  PetscScalar* a;
  VecGetArray(u, &a);
  for (int i = 0; i < n; ++i) {
    a[3 * i] = -0.2 * tp.disc().points()[i][0];
    a[3 * i + 2] = 0.01 * std::sin(7.0 * i);
  }
  VecRestoreArray(u, &a);
  auto min_eigenvalue = [&](bool project) {
    for (const auto& t : tp.problem->terms()) t->set_hessian_projection(project);
    Mat H, D;
    PetscCallAbort(PETSC_COMM_SELF, tp.problem->create_matrix(&H));
    PetscCallAbort(PETSC_COMM_SELF, tp.problem->hessian(u, H));
    PetscCallAbort(PETSC_COMM_SELF, MatConvert(H, MATDENSE, MAT_INITIAL_MATRIX, &D));
    const PetscScalar* d;
    MatDenseGetArrayRead(D, &d);
    const Eigen::MatrixXd M = Eigen::Map<const Eigen::MatrixXd>(d, 3 * n, 3 * n);
    MatDenseRestoreArrayRead(D, &d);
    MatDestroy(&D);
    MatDestroy(&H);
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
    return std::make_pair(ev.minCoeff(), ev.maxCoeff());
  };
  const auto [raw_min, raw_max] = min_eigenvalue(false);
  EXPECT_LT(raw_min, -1e-6 * raw_max) << "the state must make the Hessian indefinite";
  const auto [psd_min, psd_max] = min_eigenvalue(hessian_projection_default("pnewton"));
  EXPECT_GE(psd_min, -1e-10 * psd_max);
  EXPECT_FALSE(hessian_projection_default("rmtr"));
  VecDestroy(&u);
}

// -mlshell_hessian_psd projects every term but the pressure, whose Hessian is projected only
// with -mlshell_pressure_psd too (off by default).
TEST(TriangleShell, PressureHessianIsProjectedOnlyWhenAsked) {
  for (const bool given : {false, true}) {
    PetscOptionsSetValue(nullptr, "-mlshell_hessian_psd", "true");
    if (given) PetscOptionsSetValue(nullptr, "-mlshell_pressure_psd", "true");
    const StepSolverOptions read = StepSolverOptions::from_options(PETSC_COMM_SELF);
    PetscOptionsClearValue(nullptr, "-mlshell_hessian_psd");
    PetscOptionsClearValue(nullptr, "-mlshell_pressure_psd");
    EXPECT_TRUE(read.hessian_psd);
    EXPECT_EQ(read.pressure_psd, given);
  }
  for (const bool psd : {false, true})
    for (const bool pressure_psd : {false, true}) {
      StepSolverOptions o;
      o.hessian_psd = psd;
      o.pressure_psd = pressure_psd;
      for (const std::string term : {"elastic", "clamp", "inertia"})
        EXPECT_EQ(term_hessian_projection(o, term), psd) << term;
      EXPECT_EQ(term_hessian_projection(o, "pressure"), psd && pressure_psd);
    }
}

// An imperfect cylinder's wall: the radius r + Σ a cos(k θ + φ) sin(m π z / L) at every vertex,
// the ends round, and two modes leave it without the mirror symmetry x ↔ y that one cos(4θ)
// mode keeps (round-off picked between such mirror images of a crushed can on 1 and 2 ranks).
TEST(TriangleShell, ImperfectCylinderHasItsWavesAndRoundEnds) {
  const auto make = [](const std::string& imperfection) {
    return triangle_scene("can", "geometry: {mesh: {generator: cylinder, radius: 0.3, length: 1, "
                                 "faces: [16, 6], imperfection: " +
                                     imperfection + "}}\n" + kMaterial +
                                     "time: {dt: 1, steps: 1}\n");
  };
  const double pi = std::numbers::pi;
  {
    TriangleProblem tp(make("[{amplitude: 0.01}, {amplitude: 0.02, waves: [3, 2], phase: 0.5}]"),
                       PETSC_COMM_SELF);
    for (const Point3& X : tp.disc().points()) {
      const double theta = std::atan2(X.y(), X.x()), s = X.z() / 1.0;
      const double r = 0.3 + 0.01 * std::cos(4 * theta) * std::sin(pi * s) +
                       0.02 * std::cos(3 * theta + 0.5) * std::sin(2 * pi * s);
      EXPECT_NEAR(std::hypot(X.x(), X.y()), r, 1e-15) << X.transpose();
      if (X.z() == 0.0 || X.z() == 1.0) EXPECT_NEAR(std::hypot(X.x(), X.y()), 0.3, 1e-15);
    }
  }
  // Mirrored across x = y, the one-mode wall is itself; the two-mode wall is not.
  const auto mirror_gap = [&](const std::string& imperfection) {
    TriangleProblem tp(make(imperfection), PETSC_COMM_SELF);
    const auto& P = tp.disc().points();
    double worst = 0.0;
    for (const Point3& X : P) {
      const Point3 m(X.y(), X.x(), X.z());
      double nearest = INFINITY;
      for (const Point3& Y : P) nearest = std::min(nearest, (Y - m).norm());
      worst = std::max(worst, nearest);
    }
    return worst;
  };
  EXPECT_LE(mirror_gap("{amplitude: 0.01}"), 1e-12);
  EXPECT_GE(mirror_gap("[{amplitude: 0.01}, {amplitude: 0.005, waves: [3, 2], phase: 0.5}]"),
            1e-3);
}
