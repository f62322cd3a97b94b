// Midedge-normal bending of one triangle: Kirchhoff's plate energy of every constant-curvature
// state on a parallelogram patch (any triangle shape, ν = 0 and 0.3, cylinders, spheres and
// saddles), the elimination of a free edge (the minimum over that edge's wing), gradients and
// Hessians against central differences (every wing kind, nearly flat, nearly folded, curved
// rest), zero energy at rest after rigid motions, and the failures.
#include "mlshell/triangle/midedge_bending.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "element_fixtures.hpp"

using namespace mlshell;
using mlshell::test::expect_derivatives;
using mlshell::test::random_rotation;

namespace {

using Points = std::array<Eigen::Vector3d, 6>;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr EdgeWing kN = EdgeWing::kNeighbour;

/// The triangle p0, p0 + a, p0 + b with the wings of a parallelogram grid: the mirror of each
/// vertex through the midpoint of the opposite edge.
Points parallelogram_patch(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d q[3] = {Eigen::Vector2d::Zero(), a, b};
  Points X;
  for (int i = 0; i < 3; ++i) {
    X[i] << q[i], 0.0;
    X[3 + i] << q[(i + 1) % 3] + q[(i + 2) % 3] - q[i], 0.0;
  }
  return X;
}

/// The points lifted onto the height field z = ½ (k11 x² + 2 k12 xy + k22 y²).
Points lifted(Points X, const Eigen::Matrix2d& k) {
  for (auto& p : X) p.z() = 0.5 * p.head<2>().dot(k * p.head<2>());
  return X;
}

Eigen::Matrix<double, 18, 1> stack(const Points& x) {
  Eigen::Matrix<double, 18, 1> y;
  for (int k = 0; k < 6; ++k) y.segment<3>(3 * k) = x[k];
  return y;
}

Points unstack(const Eigen::Matrix<double, 18, 1>& y) {
  Points x;
  for (int k = 0; k < 6; ++k) x[k] = y.segment<3>(3 * k);
  return x;
}

double area(const Points& X) { return 0.5 * (X[1] - X[0]).cross(X[2] - X[0]).norm(); }

void expect_element_derivatives(const MidedgeRest& rest, const Points& x, double length,
                                const std::string& where) {
  expect_derivatives<18>([&](const Vector18& y, Vector18* g,
                             Matrix18* H) { return midedge_bending(rest, unstack(y), g, H); },
                         stack(x), length, where);
}

}  // namespace

TEST(MidedgeBending, PlateStiffness) {
  EXPECT_DOUBLE_EQ(plate_stiffness(2e6, 0.5, 0.1), 2e6 * 1e-3 / (12.0 * 0.75));
}

// A parallelogram patch on a quadratic height field: the dihedral angles are the field's
// second differences, so the element holds Kirchhoff's D/2 [ν tr(κ)² + (1 − ν) tr(κ²)] per
// area to O((κh)²). κh = 1e-4 here.
TEST(MidedgeBending, KirchhoffEnergyOfConstantCurvatureOnParallelogramPatches) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double D = 3.0, kappa = 1e-4;
  for (double nu : {0.0, 0.3}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Vector2d a(1.0 + 0.3 * u(rng), 0.3 * u(rng));
      const Eigen::Vector2d b(0.4 * u(rng), 0.8 + 0.3 * u(rng));
      const Points X = parallelogram_patch(a, b);
      const MidedgeRest rest = MidedgeRest::from(X, {kN, kN, kN}, D, nu);
      Eigen::Matrix2d k;
      if (trial == 0)
        k << kappa, 0, 0, 0;  // cylinder along x
      else if (trial == 1)
        k << 0, 0, 0, kappa;  // cylinder along y
      else if (trial == 2)
        k << kappa, 0, 0, kappa;  // sphere
      else if (trial == 3)
        k << 0, kappa, kappa, 0;  // saddle (pure twist)
      else {
        const double k11 = kappa * u(rng), k12 = kappa * u(rng), k22 = kappa * u(rng);
        k << k11, k12, k12, k22;
      }
      const double expected =
          area(X) * D / 2 * (nu * k.trace() * k.trace() + (1 - nu) * (k * k).trace());
      // Rigidly moved as well: the energy is frame-invariant.
      Points x = lifted(X, k);
      const Eigen::Matrix3d R = random_rotation(rng);
      for (auto& p : x) p = R * p + Eigen::Vector3d(1, -2, 3);
      EXPECT_NEAR(midedge_bending(rest, x, nullptr, nullptr), expected, 1e-6 * std::abs(expected))
          << "nu " << nu << " trial " << trial << "\n"
          << k;
    }
  }
}

// Eliminating a free edge's tilt is the minimum over what lies across it: with a neighbour
// there instead, turning the neighbour about the edge reaches every θ of that hinge, and the
// energy is quadratic in it, so three turns find the minimum exactly.
TEST(MidedgeBending, FreeEdgeIsTheMinimumOverItsWing) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Points X = parallelogram_patch({1.0, 0.1}, {0.3, 0.9});
  for (int free_edge = 0; free_edge < 3; ++free_edge) {
    std::array<EdgeWing, 3> wings = {kN, kN, kN};
    wings[free_edge] = EdgeWing::kFree;
    const MidedgeRest free = MidedgeRest::from(X, wings, 2.0, 0.3);
    const MidedgeRest held = MidedgeRest::from(X, {kN, kN, kN}, 2.0, 0.3);
    Points x = X;
    for (auto& p : x) p += 0.05 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    // Turn the wing of the free edge about that edge by φ.
    const Eigen::Vector3d e0 = x[(free_edge + 1) % 3], e1 = x[(free_edge + 2) % 3];
    const Eigen::Vector3d axis = (e1 - e0).normalized();
    auto energy_at = [&](double phi) {
      Points y = x;
      y[3 + free_edge] = e0 + Eigen::AngleAxisd(phi, axis) * (x[3 + free_edge] - e0);
      return midedge_bending(held, y, nullptr, nullptr);
    };
    const double h = 0.01, em = energy_at(-h), e0v = energy_at(0), ep = energy_at(h);
    const double curvature = (ep - 2 * e0v + em) / (h * h), slope = (ep - em) / (2 * h);
    const double minimum = e0v - 0.5 * slope * slope / curvature;
    const double eliminated = midedge_bending(free, x, nullptr, nullptr);
    EXPECT_NEAR(eliminated, minimum, 1e-7 * e0v) << "free edge " << free_edge;
    EXPECT_LT(eliminated, e0v) << "free edge " << free_edge;
  }
}

TEST(MidedgeBending, StiffnessIsSymmetricPositiveSemiDefiniteAndZeroOnFreeEdges) {
  const Points X = parallelogram_patch({1.0, 0.0}, {0.2, 0.7});
  for (const auto& wings : {std::array<EdgeWing, 3>{kN, kN, kN},
                            std::array<EdgeWing, 3>{EdgeWing::kFree, kN, EdgeWing::kClamp},
                            std::array<EdgeWing, 3>{EdgeWing::kFree, EdgeWing::kFree, kN}}) {
    const MidedgeRest rest = MidedgeRest::from(X, wings, 1.0, 0.3);
    EXPECT_EQ(rest.stiffness, rest.stiffness.transpose());
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(rest.stiffness);
    EXPECT_GE(es.eigenvalues().minCoeff(), -1e-14 * es.eigenvalues().maxCoeff());
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(rest.active[i], wings[i] != EdgeWing::kFree);
      if (!rest.active[i]) EXPECT_EQ(rest.stiffness.row(i).norm(), 0.0);
    }
  }
}

// A clamped edge's normal is held by the virtual vertex: the hinge to it turns by the whole
// angle, c = 1, where a neighbour's averaged normal turns by half, c = ½ (the file comment).
TEST(MidedgeBending, ClampedEdgeCountsTheWholeAngle) {
  const Points X = parallelogram_patch({1.0, 0.0}, {0.0, 1.0});
  const MidedgeRest neighbour = MidedgeRest::from(X, {kN, EdgeWing::kFree, EdgeWing::kFree}, 1, 0);
  const MidedgeRest clamp =
      MidedgeRest::from(X, {EdgeWing::kClamp, EdgeWing::kFree, EdgeWing::kFree}, 1, 0);
  Points x = X;
  x[3].z() = 0.01;  // turn the wing of edge 0
  EXPECT_NEAR(midedge_bending(clamp, x, nullptr, nullptr),
              4.0 * midedge_bending(neighbour, x, nullptr, nullptr),
              1e-12 * midedge_bending(clamp, x, nullptr, nullptr));
}

TEST(MidedgeBending, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::array<std::array<EdgeWing, 3>, 4> cases = {
      std::array<EdgeWing, 3>{kN, kN, kN},
      {EdgeWing::kFree, kN, kN},
      {kN, EdgeWing::kClamp, EdgeWing::kFree},
      {EdgeWing::kClamp, EdgeWing::kFree, EdgeWing::kFree}};
  for (size_t c = 0; c < cases.size(); ++c) {
    // A curved rest patch, then a random large deformation.
    Points X = parallelogram_patch({1.0, 0.2}, {0.3, 0.9});
    for (auto& p : X) p.z() = 0.2 * u(rng);
    const MidedgeRest rest = MidedgeRest::from(X, cases[c], 2.0, 0.3);
    for (int trial = 0; trial < 3; ++trial) {
      Points x = X;
      for (auto& p : x) p += 0.2 * Eigen::Vector3d(u(rng), u(rng), u(rng));
      expect_element_derivatives(rest, x, 1.0, "case " + std::to_string(c));
    }
  }
}

// θ ≈ 0 everywhere (a flat rest patch barely bent) and a hinge folded to θ ≈ ±π.
TEST(MidedgeBending, GradientAndHessianAccurateWhenNearlyFlatOrFolded) {
  const Points X = parallelogram_patch({1.0, 0.0}, {0.4, 0.8});
  const MidedgeRest rest = MidedgeRest::from(X, {kN, kN, kN}, 1.0, 0.3);
  Points flat = lifted(X, (Eigen::Matrix2d() << 1e-3, 2e-4, 2e-4, -5e-4).finished());
  expect_element_derivatives(rest, flat, 1.0, "nearly flat");
  Points folded = X;
  // Fold the wing of edge 2 (x0–x1, along x) almost onto the triangle.
  const double angle = 3.1;
  folded[5] = Eigen::Vector3d(folded[5].x(), -folded[5].y() * std::cos(angle),
                              -folded[5].y() * std::sin(angle));
  expect_element_derivatives(rest, folded, 1.0, "nearly folded");
}

TEST(MidedgeBending, ZeroAtCurvedRestAfterRigidMotion) {
  std::mt19937 rng(17);
  Points X = lifted(parallelogram_patch({1.0, 0.1}, {0.2, 1.1}),
                    (Eigen::Matrix2d() << 0.5, 0.2, 0.2, -0.3).finished());
  const MidedgeRest rest = MidedgeRest::from(X, {kN, EdgeWing::kFree, kN}, 1.0, 0.3);
  const Eigen::Matrix3d R = random_rotation(rng);
  Points x;
  for (int k = 0; k < 6; ++k) x[k] = R * X[k] + Eigen::Vector3d(3, 2, 1);
  Vector18 g;
  Matrix18 H;
  EXPECT_NEAR(midedge_bending(rest, x, &g, &H), 0.0, 1e-28);
  EXPECT_LT(g.norm(), 1e-14 * H.norm());
  EXPECT_GT(H.norm(), 0.0);
}

TEST(MidedgeBending, DegenerateStatesAreInfiniteAndRestThrows) {
  const Points X = parallelogram_patch({1.0, 0.0}, {0.0, 1.0});
  const MidedgeRest rest = MidedgeRest::from(X, {kN, kN, kN}, 1.0, 0.3);
  Points collapsed = X;
  collapsed[2] = 0.5 * (X[0] + X[1]);  // the triangle has no normal
  EXPECT_EQ(midedge_bending(rest, collapsed, nullptr, nullptr), kInf);
  Points nan = X;
  nan[4].x() = std::nan("");
  EXPECT_EQ(midedge_bending(rest, nan, nullptr, nullptr), kInf);
  // A free edge's wing slot is not used: NaN there is harmless.
  const MidedgeRest free = MidedgeRest::from(X, {kN, EdgeWing::kFree, kN}, 1.0, 0.3);
  EXPECT_EQ(midedge_bending(free, nan, nullptr, nullptr), 0.0);
  EXPECT_THROW(MidedgeRest::from(collapsed, {kN, kN, kN}, 1.0, 0.3), std::invalid_argument);
  Points bad_wing = X;
  bad_wing[3] = 0.5 * (X[1] + X[2]);  // the wing lies on its edge: no normal
  EXPECT_THROW(MidedgeRest::from(bad_wing, {kN, kN, kN}, 1.0, 0.3), std::invalid_argument);
  EXPECT_NO_THROW(MidedgeRest::from(bad_wing, {EdgeWing::kFree, kN, kN}, 1.0, 0.3));
}
