// Triangle shells against closed-form solutions (paper 2 §3 physics):
//   the hinge energy of a structured mesh of squares of side a (two right triangles each) bent
//   onto a cylinder of curvature κ: a triangle inscribed in the cylinder tilts with the
//   midpoint of its chord across the axis, so the hinges across the bending direction carry
//   θ = κa and the diagonals none: 3kκ²a² per square, three times the Kirchhoff plate's
//   D/2 κ² = kκ² (D = 2k) — the discrete hinge model's mesh-dependent bending stiffness;
//   a cantilever strip (ν = 0) under a small end load P, reported against Euler–Bernoulli
//   δ = P L³ / (3 E I) and checked to converge under refinement;
//   a closed sphere under a small pressure p: ΔR / R = p R (1 − ν) / (2 E τ).
#include <cmath>
#include <cstdio>

#include "triangle_fixtures.hpp"

using namespace mlshell;

namespace {

/// Tip deflection of a 1 m × 0.1 m strip, 1 cm thick, E = 1e7 Pa, clamped on the left, under
/// an end load P = 2.5e-4 N spread along the right side (Euler–Bernoulli: 1e-3 m).
double cantilever_tip(int nx, int ny, double* expected) {
  const double E = 1e7, b = 0.1, tau = 0.01, L = 1.0, P = 2.5e-4;
  const double I = b * tau * tau * tau / 12.0;
  *expected = P * L * L * L / (3.0 * E * I);
  char yaml[1024];
  std::snprintf(yaml, sizeof yaml,
                "geometry: {mesh: {generator: rectangle, size: [1, 0.1], faces: [%d, %d]}}\n"
                "material: {model: neo-hookean, youngs_modulus: %g, poisson_ratio: 0, "
                "thickness: %g, volume_density: 0}\n"
                "effects:\n"
                "  - clamp: {where: boundary(left)}\n"
                "  - line_load: {where: boundary(right), force_per_length: [0, 0, %.17g]}\n"
                "time: {dt: 1, steps: 1}\n",
                nx, ny, E, tau, -P / b);
  const Scene scene = triangle_scene("cantilever", yaml);
  const SolvedScene solved = solve_scene(
      scene, PETSC_COMM_SELF,
      (std::filesystem::temp_directory_path() / ("mlshell_cantilever_" + std::to_string(nx)))
          .string());
  EXPECT_EQ(solved.status, 0);
  const auto& disc = solved.simulation->discretization();
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < disc.num_points(); ++i)
    if (std::abs(disc.points()[i][0] - L) < 1e-12) {
      sum += solved.displacement[3 * i + 2];
      ++count;
    }
  return -sum / count;
}

}  // namespace

TEST(TriangleValidation, HingeEnergyOfABentStructuredMeshIsThreeTimesKirchhoffs) {
  const Scene scene = triangle_scene(
      "cylinder_bend",
      "geometry: {mesh: {generator: rectangle, size: [1, 1], faces: [40, 40]}}\n"
      "material: {model: neo-hookean, youngs_modulus: 1e6, poisson_ratio: 0, thickness: 0.01, "
      "volume_density: 0}\ntime: {dt: 1, steps: 1}\n");
  TriangleProblem tp(scene, PETSC_COMM_SELF);
  const double k = 1e6 * 1e-6 / 24.0, kappa = 0.05;
  for (int axis = 0; axis < 2; ++axis) {
    // Isometric: x along the bending direction is wrapped onto the cylinder of radius 1/κ.
    std::vector<double> u(3 * tp.disc().num_points(), 0.0);
    for (int i = 0; i < tp.disc().num_points(); ++i) {
      const double s = tp.disc().points()[i][axis];
      u[3 * i + axis] = std::sin(kappa * s) / kappa - s;
      u[3 * i + 2] = (1.0 - std::cos(kappa * s)) / kappa;
    }
    CompensatedSum e;
    PetscCallAbort(PETSC_COMM_SELF, tp.problem->terms()[0]->add(u, e, nullptr, nullptr));
    // The hinges at the mesh's boundary squares are missing: (1 − a) of the ideal total.
    const double a = 1.0 / 40.0;
    EXPECT_NEAR(e.value(), 3.0 * k * kappa * kappa * (1.0 - a), 0.003 * 3.0 * k * kappa * kappa)
        << "bending along axis " << axis;
  }
}

TEST(TriangleValidation, CantileverConvergesUnderRefinement) {
  double expected = 0.0;
  const double coarse = cantilever_tip(20, 2, &expected);
  const double medium = cantilever_tip(40, 4, &expected);
  const double fine = cantilever_tip(80, 8, &expected);
  std::printf(
      "cantilever tip: %.6e (20x2), %.6e (40x4), %.6e (80x8); Euler-Bernoulli %.6e; ratio %.4f "
      "(the hinge model on this mesh is three times as stiff in cylindrical bending)\n",
      coarse, medium, fine, expected, fine / expected);
  EXPECT_LT(std::abs(fine - medium), std::abs(medium - coarse));
  EXPECT_LT(std::abs(fine - medium), 0.05 * fine);
  // Between the hinge model's stiffening of cylindrical bending on this mesh (3, see above; the
  // free strip also bends anticlastically) and the plate's.
  EXPECT_GT(fine / expected, 1.0 / 3.0);
  EXPECT_LT(fine / expected, 0.6);
}

TEST(TriangleValidation, SphereUnderSmallPressureGrowsAsTheThinSphereSolution) {
  const double E = 1e6, nu = 0.3, tau = 0.01, R = 1.0;
  const double growth = 1e-4;  // ΔR / R
  const double p = growth * 2.0 * E * tau / (R * (1.0 - nu));
  char yaml[1024];
  std::snprintf(yaml, sizeof yaml,
                "geometry: {mesh: {generator: sphere, radius: 1, subdivisions: 3}}\n"
                "material: {model: neo-hookean, youngs_modulus: %g, poisson_ratio: %g, "
                "thickness: %g, volume_density: 1000}\n"
                "effects:\n  - pressure: {pressure: %.17g}\n"
                "time: {dt: 1, steps: 1, integrator: quasistatic}\n",
                E, nu, tau, p);
  const Scene scene = triangle_scene("sphere", yaml);
  const SolvedScene solved =
      solve_scene(scene, PETSC_COMM_SELF,
                  (std::filesystem::temp_directory_path() / "mlshell_sphere_pressure").string());
  ASSERT_EQ(solved.status, 0);
  const auto& disc = solved.simulation->discretization();
  double before = 0.0, after = 0.0;
  for (int i = 0; i < disc.num_points(); ++i) {
    const Point3& X = disc.points()[i];
    const Point3 x = X + Point3(solved.displacement[3 * i], solved.displacement[3 * i + 1],
                                solved.displacement[3 * i + 2]);
    before += X.norm();
    after += x.norm();
  }
  const double measured = after / before - 1.0;
  std::printf("sphere: dR/R = %.6e, thin-sphere membrane solution %.6e\n", measured, growth);
  EXPECT_NEAR(measured, growth, 0.02 * growth);
}
