// Supports that turn (motion: rotate) on a subdivision shell: a strip whose right end a Dirichlet
// condition turns by a quarter turn about the strip's long axis in one quasistatic step ends with
// that end where the rotation takes it. The condition holds the limit surface at the boundary's
// Gauss points (and at a corner point) in augmented-Lagrangian mode, so the check is to the
// scene's tolerance: the corner's limit point, evaluated here from the final control points, and
// the largest violation over the boundary's samples.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "mlshell/subdivision/selection.hpp"
#include "physics_fixtures.hpp"

using namespace mlshell;

TEST(RotatingSupport, SubdivisionStripTwistedByADirichletEndEndsAtTheRotatedPositions) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("mlshell_rotating_support_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / "twist.yaml";
  std::ofstream(file)
      << "geometry: {cage: {generator: rectangle, size: [1, 0.25], faces: [8, 2]}, refine: 1}\n"
         "material: {model: isotropic-svk, youngs_modulus: 1e6, poisson_ratio: 0.3, "
         "thickness: 0.01, density: 500}\n"
         "effects:\n"
         "  - clamp: {where: boundary(left)}\n"
         "  - dirichlet: {where: boundary(right), tolerance: 1e-6, motion: {rotate: {axis: [1, 0, "
         "0], center: [1, 0.125, 0], angle: 1.5707963267948966}, over: [0, 1]}}\n"
         "  - dirichlet: {where: corner(top-right), tolerance: 1e-6, motion: {rotate: {axis: [1, "
         "0, 0], center: [1, 0.125, 0], angle: 1.5707963267948966}, over: [0, 1]}}\n"
         "time: {dt: 1, steps: 1, integrator: quasistatic}\n";
  const Scene scene = parse_scene(file);
  const SolvedScene solved = solve_scene(scene, PETSC_COMM_SELF, (dir / "out").string());
  ASSERT_EQ(solved.status, 0);

  // Every boundary sample of the turning conditions is within the tolerance of its target.
  std::vector<double> violations;
  PetscCallAbort(PETSC_COMM_SELF, solved.simulation->problem().constraint_violations(
                                      solved.simulation->displacement(), violations));
  const auto& terms = solved.simulation->problem().terms();
  ASSERT_EQ(violations.size(), terms.size());
  int held = 0;
  for (size_t k = 0; k < terms.size(); ++k)
    if (terms[k]->has_multipliers()) {
      ++held;
      EXPECT_LE(violations[k], 1e-6) << terms[k]->name();
    }
  EXPECT_EQ(held, 2);

  // The corner's limit point, from the final control points, is the turned reference point.
  const auto& disc =
      static_cast<const SubdivisionDiscretization&>(solved.simulation->discretization());
  PointSelection corner;
  corner.kind = PointSelection::Kind::Corner;
  corner.corner = "top-right";
  const SurfacePoint p =
      select_point(disc, corner, CageFrame::from(scene.geometry), "corner(top-right)");
  const PointBasis b = disc.evaluator().evaluate({p})[0];
  Point3 X = Point3::Zero(), u = Point3::Zero();
  for (int i = 0; i < b.size(); ++i) {
    X += b.w[kValue][i] * disc.mesh().points[b.nodes[i]];
    for (int c = 0; c < 3; ++c) u[c] += b.w[kValue][i] * solved.displacement[3 * b.nodes[i] + c];
  }
  const Point3 c(1, 0.125, 0);
  const Point3 turned =
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()) * (X - c) + c;
  EXPECT_GT((turned - X).norm(), 0.1);  // the corner moved far
  EXPECT_LT((X + u - turned).norm(), 1e-5) << "X = " << X.transpose();
  std::filesystem::remove_all(dir);
}
