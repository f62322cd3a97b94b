// The pressure Hessian −p∇²V split over the edges (pressure_edge_hessian): the edges' blocks sum
// to the faces' exact Hessians on a closed surface (so the derived block, its sign included, is
// that of enclosed_volume's finite-difference-tested face Hessians), and the closed-form PSD
// projection of -mlshell_pressure_psd is the eigen-decomposition one (project_to_psd), PSD, and
// the same wherever the edge sits.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "mlshell/psd_projection.hpp"
#include "mlshell/triangle/enclosed_volume.hpp"
#include "mlshell/triangle/triangle_effects.hpp"
#include "mlshell/triangle/triangle_generators.hpp"
#include "mlshell/triangle/triangle_mesh.hpp"

using namespace mlshell;

namespace {

constexpr double kPressure = 2500.0;

Eigen::Vector3d random_point(std::mt19937& rng, double size) {
  std::uniform_real_distribution<double> u(-size, size);
  return Eigen::Vector3d(u(rng), u(rng), u(rng));
}

}  // namespace

// On a jiggled sphere far from the origin: Σ_faces −p∇²V_t (enclosed_volume.cpp) against
// Σ_edges M_e placed on each edge's (a, b) = Hinge::v[0], v[1].
TEST(PressureEdgeHessian, EdgeBlocksSumToTheFacesExactHessian) {
  std::mt19937 rng(61);
  TriangleMesh sphere = make_sphere(0.5, 2);
  const Eigen::Vector3d offset(3.0, -2.0, 1.0);
  for (Point3& x : sphere.points) x += offset + random_point(rng, 0.05);
  const TriangleTopology topology(sphere);
  const int n = 3 * sphere.num_points();
  Eigen::MatrixXd by_faces = Eigen::MatrixXd::Zero(n, n), by_edges = by_faces;
  for (const Triangle& t : sphere.triangles) {
    Matrix9 H;
    triangle_volume(sphere.points[t[0]], sphere.points[t[1]], sphere.points[t[2]], nullptr, &H);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        by_faces.block<3, 3>(3 * t[i], 3 * t[j]) -= kPressure * H.block<3, 3>(3 * i, 3 * j);
  }
  ASSERT_EQ(topology.hinges().size(), 3 * sphere.triangles.size() / 2);  // closed
  for (const Hinge& h : topology.hinges()) {
    const Matrix6d M =
        pressure_edge_hessian(sphere.points[h.v[2]], sphere.points[h.v[3]], kPressure, false);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        by_edges.block<3, 3>(3 * h.v[i], 3 * h.v[j]) += M.block<3, 3>(3 * i, 3 * j);
  }
  ASSERT_GT(by_faces.norm(), 0.0);
  // The faces' blocks grow with the distance from the origin and cancel; the edges' do not.
  EXPECT_LE((by_edges - by_faces).norm(), 1e-13 * offset.norm() * by_faces.norm());
  EXPECT_EQ((by_edges - by_edges.transpose()).norm(), 0.0);
}

TEST(PressureEdgeHessian, ClosedFormProjectionIsTheEigenDecompositionOne) {
  std::mt19937 rng(67);
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Vector3d xc = random_point(rng, 1.0), xd = random_point(rng, 1.0);
    const double p = (trial % 2 ? -1.0 : 1.0) * kPressure;  // suction too
    const Matrix6d exact = pressure_edge_hessian(xc, xd, p, false);
    const Matrix6d projected = pressure_edge_hessian(xc, xd, p, true);
    Eigen::MatrixXd reference = exact;
    project_to_psd(reference);
    const double scale = exact.norm();
    ASSERT_GT(scale, 0.0);
    EXPECT_LE((projected - reference).norm(), 1e-14 * scale) << trial;
    EXPECT_EQ((projected - projected.transpose()).norm(), 0.0);
    const Eigen::SelfAdjointEigenSolver<Matrix6d> of_exact(exact), of_projected(projected);
    EXPECT_GE(of_projected.eigenvalues().minCoeff(), -1e-14 * scale) << trial;
    // M_e = [[0, S], [Sᵀ, 0]] with S = (p/6)[w]×: eigenvalues ±|p||w|/6 (twice) and 0 (twice),
    // so its projection keeps half of the norm squared.
    const double sigma = std::abs(p) * (xc - xd).norm() / 6.0;
    EXPECT_NEAR(of_exact.eigenvalues()[0], -sigma, 1e-13 * scale);
    EXPECT_NEAR(of_exact.eigenvalues()[5], sigma, 1e-13 * scale);
    EXPECT_NEAR(projected.squaredNorm(), 0.5 * exact.squaredNorm(), 1e-13 * scale * scale);
    // Only the difference w = x_c − x_d matters: no centre, whatever the edge's position.
    const Eigen::Vector3d shift = random_point(rng, 100.0);
    EXPECT_LE((pressure_edge_hessian(xc + shift, xd + shift, p, true) - projected).norm(),
              1e-13 * shift.norm() * std::abs(p));
  }
  // A degenerate edge (x_c = x_d) and no pressure (a ramp at t = 0) give zero blocks, no NaN.
  const Eigen::Vector3d x(0.2, 0.1, 0.5);
  for (const bool project : {false, true}) {
    EXPECT_TRUE(pressure_edge_hessian(x, x, kPressure, project).isZero(0.0));
    EXPECT_TRUE(pressure_edge_hessian(x, 2.0 * x, 0.0, project).isZero(0.0));
  }
}
