// Neo-Hookean and St. Venant–Kirchhoff triangle membranes: closed-form gradients and Hessians
// against central differences (random, large and thin-triangle states), zero energy and force
// at rest and after rigid motions, the closed form of a uniform biaxial stretch, PSD of the
// Neo-Hookean Hessian at rest, and +infinity for collapsed triangles.
#include "mlshell/triangle/membrane.hpp"

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
using mlshell::test::stack;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const MembraneParameters kParams{2.3, 5.1, 0.01};

enum class Model { kNeoHookean, kStVK };

double membrane(Model m, const TriangleRest& rest, const Vector9& x, Vector9* g, Matrix9* H) {
  const Eigen::Vector3d x0 = x.segment<3>(0), x1 = x.segment<3>(3), x2 = x.segment<3>(6);
  return m == Model::kNeoHookean ? neo_hookean_membrane(rest, kParams, x0, x1, x2, g, H)
                                 : stvk_membrane(rest, kParams, x0, x1, x2, g, H);
}

const char* name(Model m) { return m == Model::kNeoHookean ? "NH" : "StVK"; }

struct Triangle {
  Eigen::Vector3d X[3];
};

/// Applies x = F X + c to a triangle.
Vector9 deform(const Triangle& t, const Eigen::Matrix3d& F, const Eigen::Vector3d& c) {
  return stack(F * t.X[0] + c, F * t.X[1] + c, F * t.X[2] + c);
}

Triangle random_triangle(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    Triangle t;
    for (auto& X : t.X) X = Eigen::Vector3d(u(rng), u(rng), u(rng));
    const double area = 0.5 * (t.X[1] - t.X[0]).cross(t.X[2] - t.X[0]).norm();
    if (area > 0.1) return t;
  }
}

/// A thin triangle (height/edge = 1e-3) in a random position.
Triangle thin_triangle(std::mt19937& rng) {
  const Eigen::Matrix3d R = random_rotation(rng);
  const Eigen::Vector3d c(0.3, -0.2, 0.1);
  return Triangle{{c, R * Eigen::Vector3d(1, 0, 0) + c, R * Eigen::Vector3d(0.4, 1e-3, 0) + c}};
}

TriangleRest rest_of(const Triangle& t) { return TriangleRest::from(t.X[0], t.X[1], t.X[2]); }

}  // namespace

TEST(TriangleMembrane, GradientAndHessianMatchFiniteDifferencesAtRandomStates) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Model m : {Model::kNeoHookean, Model::kStVK}) {
    for (int trial = 0; trial < 40; ++trial) {
      const Triangle t = random_triangle(rng);
      const TriangleRest rest = rest_of(t);
      // Moderate (±30 %) and large (±80 %, rotations, shears) deformations.
      const double amount = trial % 2 ? 0.3 : 0.8;
      Eigen::Matrix3d F = random_rotation(rng);
      for (int i = 0; i < 9; ++i) F.data()[i] += amount * 0.5 * u(rng);
      Vector9 x = deform(t, F, Eigen::Vector3d(u(rng), u(rng), u(rng)));
      for (int i = 0; i < 9; ++i) x[i] += 0.05 * u(rng);
      if (!std::isfinite(membrane(m, rest, x, nullptr, nullptr))) continue;  // collapsed
      expect_derivatives<9>(
          [&](const Vector9& y, Vector9* g, Matrix9* H) { return membrane(m, rest, y, g, H); }, x,
          1.0, std::string(name(m)) + " trial " + std::to_string(trial));
    }
  }
}

TEST(TriangleMembrane, GradientAndHessianMatchFiniteDifferencesOnThinTriangles) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Model m : {Model::kNeoHookean, Model::kStVK}) {
    for (int trial = 0; trial < 10; ++trial) {
      const Triangle t = thin_triangle(rng);
      const TriangleRest rest = rest_of(t);
      Eigen::Matrix3d F = random_rotation(rng);
      for (int i = 0; i < 9; ++i) F.data()[i] += 0.2 * u(rng);
      Vector9 x = deform(t, F, Eigen::Vector3d::Zero());
      for (int i = 0; i < 9; ++i) x[i] += 1e-4 * u(rng);
      ASSERT_TRUE(std::isfinite(membrane(m, rest, x, nullptr, nullptr)));
      // Steps relative to the smallest dimension (the height 1e-3).
      expect_derivatives<9>(
          [&](const Vector9& y, Vector9* g, Matrix9* H) { return membrane(m, rest, y, g, H); }, x,
          1e-3, std::string(name(m)) + " thin " + std::to_string(trial));
    }
  }
}

TEST(TriangleMembrane, ZeroEnergyAndForceAtRestAndAfterRigidMotions) {
  std::mt19937 rng(7);
  for (Model m : {Model::kNeoHookean, Model::kStVK}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Triangle t = trial % 4 == 3 ? thin_triangle(rng) : random_triangle(rng);
      const TriangleRest rest = rest_of(t);
      // Energy and force scales of a unit strain.
      const double scale = kParams.thickness * rest.area * (kParams.mu + kParams.lambda);
      const double length = (t.X[1] - t.X[0]).norm();
      const Eigen::Matrix3d R = random_rotation(rng);
      const Eigen::Vector3d c(1.5, -2.0, 0.7);
      for (const Vector9& x :
           {deform(t, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), deform(t, R, c)}) {
        Vector9 g;
        const double E = membrane(m, rest, x, &g, nullptr);
        // Thin triangles (smallest angle ≈ 2.5e-3): round-off ε/sin, not ε/sin² ≈ 1e-11.
        const double tol = trial % 4 == 3 ? 1e-12 : 1e-13;
        EXPECT_LE(std::abs(E), tol * scale) << name(m) << " trial " << trial;
        EXPECT_LE(g.norm(), tol * scale / std::min(length, 2 * rest.area / length))
            << name(m) << " trial " << trial;
      }
    }
  }
}

// Stretch by s1, s2 along orthogonal in-plane axes (at angle φ to x), then a rigid motion:
// M has eigenvalues s1², s2², so ψ_NH = μ/2 (s1² + s2² − 2 − 2 ln(s1 s2)) + λ/2 ln²(s1 s2) and
// G = diag((s1² − 1)/2, (s2² − 1)/2) gives ψ_StVK = μ (G11² + G22²) + λ/2 (G11 + G22)².
TEST(TriangleMembrane, UniformBiaxialStretchMatchesClosedForm) {
  std::mt19937 rng(11);
  const Triangle t{
      {Eigen::Vector3d(0.1, 0.2, 0), Eigen::Vector3d(1.3, -0.1, 0), Eigen::Vector3d(0.5, 0.9, 0)}};
  const TriangleRest rest = rest_of(t);
  const double area = 0.5 * std::abs((t.X[1] - t.X[0]).cross(t.X[2] - t.X[0]).z());
  EXPECT_NEAR(rest.area, area, 1e-15);
  const double mu = kParams.mu, lambda = kParams.lambda, tau = kParams.thickness;
  const double stretches[][2] = {{1.0, 1.0}, {1.2, 1.0}, {0.7, 1.4}, {0.5, 0.6}, {2.0, 3.0}};
  for (const auto& s : stretches) {
    for (double phi : {0.0, 0.4, 2.0}) {
      const Eigen::Matrix3d Rz = Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitZ()).matrix();
      const Eigen::Matrix3d F = random_rotation(rng) * Rz *
                                Eigen::Vector3d(s[0], s[1], 1.0).asDiagonal() * Rz.transpose();
      const Vector9 x = deform(t, F, Eigen::Vector3d(0.3, 0.4, -2.0));
      const double J = s[0] * s[1];
      const double nh = tau * area *
                        (0.5 * mu * (s[0] * s[0] + s[1] * s[1] - 2 - 2 * std::log(J)) +
                         0.5 * lambda * std::log(J) * std::log(J));
      const double G11 = 0.5 * (s[0] * s[0] - 1), G22 = 0.5 * (s[1] * s[1] - 1);
      const double svk =
          tau * area * (mu * (G11 * G11 + G22 * G22) + 0.5 * lambda * (G11 + G22) * (G11 + G22));
      EXPECT_NEAR(membrane(Model::kNeoHookean, rest, x, nullptr, nullptr), nh,
                  1e-12 * (std::abs(nh) + tau * area * mu))
          << s[0] << " " << s[1] << " phi " << phi;
      EXPECT_NEAR(membrane(Model::kStVK, rest, x, nullptr, nullptr), svk,
                  1e-12 * (std::abs(svk) + tau * area * mu))
          << s[0] << " " << s[1] << " phi " << phi;
    }
  }
}

TEST(TriangleMembrane, HessiansSymmetricAndPsdAtRest) {
  std::mt19937 rng(13);
  for (Model m : {Model::kNeoHookean, Model::kStVK}) {
    for (int trial = 0; trial < 10; ++trial) {
      const Triangle t = random_triangle(rng);
      const TriangleRest rest = rest_of(t);
      Matrix9 H;
      membrane(m, rest, deform(t, random_rotation(rng), Eigen::Vector3d(1, 2, 3)), nullptr, &H);
      EXPECT_LE((H - H.transpose()).norm(), 1e-14 * H.norm());
      const Eigen::SelfAdjointEigenSolver<Matrix9> eig(H);
      const auto& l = eig.eigenvalues();
      // Six rigid modes and the three out-of-plane displacements have zero stiffness at rest;
      // the three in-plane strain modes are positive.
      EXPECT_GE(l.minCoeff(), -1e-12 * H.norm()) << name(m) << " " << l.transpose();
      for (int i = 0; i < 6; ++i) EXPECT_LE(std::abs(l[i]), 1e-12 * H.norm()) << l.transpose();
      for (int i = 6; i < 9; ++i) EXPECT_GT(l[i], 1e-6 * H.norm()) << l.transpose();
    }
  }
}

TEST(TriangleMembrane, NullPointersGiveTheSameEnergyAndDerivatives) {
  std::mt19937 rng(17);
  const Triangle t = random_triangle(rng);
  const TriangleRest rest = rest_of(t);
  const Vector9 x = deform(t, 1.1 * random_rotation(rng), Eigen::Vector3d::Zero());
  for (Model m : {Model::kNeoHookean, Model::kStVK}) {
    Vector9 g1, g2;
    Matrix9 H1, H2;
    const double E = membrane(m, rest, x, &g1, &H1);
    EXPECT_EQ(membrane(m, rest, x, nullptr, nullptr), E);
    EXPECT_EQ(membrane(m, rest, x, &g2, nullptr), E);
    EXPECT_EQ(membrane(m, rest, x, nullptr, &H2), E);
    EXPECT_EQ(g1, g2);
    EXPECT_EQ(H1, H2);
    EXPECT_GT(E, 0.0);
  }
}

// det A = |d₁ × d₂|² ≥ 0, so for a membrane the only inversion is a collapse (det M = 0):
// Neo-Hookean returns +inf and writes nothing; StVK stays finite and smooth there.
TEST(TriangleMembrane, CollapsedTriangleIsInfiniteForNeoHookean) {
  std::mt19937 rng(19);
  const Triangle t = random_triangle(rng);
  const TriangleRest rest = rest_of(t);
  const Eigen::Vector3d a(0.1, 0.2, 0.3), b(1.1, 2.2, 3.3);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Vector9 collapsed[] = {
      stack(a, b, a + 2.0 * (b - a)),  // collinear (exact: 2 (b − a))
      stack(a, a, b),                  // two vertices coincide
      stack(a, a, a),                  // a point
      stack(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.1, 0.3, 0.7),  // collinear to round-off
            Eigen::Vector3d(0.3, 0.9, 2.1)),
      stack(a, b, Eigen::Vector3d(nan, 0.0, 0.0)),    // not a position
      stack(a, b, Eigen::Vector3d(kInf, 0.0, 0.0))};  // not a position
  for (const Vector9& x : collapsed) {
    Vector9 g = Vector9::Constant(42.0);
    Matrix9 H = Matrix9::Constant(42.0);
    EXPECT_EQ(membrane(Model::kNeoHookean, rest, x, &g, &H), kInf) << x.transpose();
    EXPECT_EQ(g, Vector9::Constant(42.0));
    EXPECT_EQ(H, Matrix9::Constant(42.0));
  }
  for (int i = 0; i < 4; ++i) {
    const double E = membrane(Model::kStVK, rest, collapsed[i], nullptr, nullptr);
    EXPECT_TRUE(std::isfinite(E));
    EXPECT_GT(E, 0.0);
  }
  for (int i = 4; i < 6; ++i)
    EXPECT_EQ(membrane(Model::kStVK, rest, collapsed[i], nullptr, nullptr), kInf);
  expect_derivatives<9>([&](const Vector9& y, Vector9* g,
                            Matrix9* H) { return membrane(Model::kStVK, rest, y, g, H); },
                        collapsed[0], 1.0, "StVK collapsed");
  // Approaching the collapse, the Neo-Hookean energy grows without bound.
  double previous = 0.0;
  for (double h : {1e-1, 1e-3, 1e-6, 1e-9}) {
    const Eigen::Vector3d c = a + 0.5 * (b - a) + h * Eigen::Vector3d(1, -1, 0.2);
    const double E = membrane(Model::kNeoHookean, rest, stack(a, b, c), nullptr, nullptr);
    EXPECT_TRUE(std::isfinite(E));
    EXPECT_GT(E, previous);
    previous = E;
  }
}

// Reflecting x2 across the line x0x1 within the plane turns the triangle over, but in 3D this is
// the rotation by π about that line: the membrane energy stays that of the rigid motion, 0.
TEST(TriangleMembrane, InPlaneFlipIsARigidRotationInThreeD) {
  const Triangle t{
      {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0.3, 0.8, 0)}};
  const TriangleRest rest = rest_of(t);
  const Vector9 flipped = stack(t.X[0], t.X[1], Eigen::Vector3d(0.3, -0.8, 0));
  for (Model m : {Model::kNeoHookean, Model::kStVK})
    EXPECT_LE(std::abs(membrane(m, rest, flipped, nullptr, nullptr)), 1e-16) << name(m);
}

TEST(TriangleMembrane, DegenerateRestTriangleThrows) {
  const Eigen::Vector3d a(0.1, 0.2, 0.3), b(1.1, 2.2, 3.3);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(TriangleRest::from(a, b, a + 2.0 * (b - a)), std::invalid_argument);
  EXPECT_THROW(TriangleRest::from(a, a, b), std::invalid_argument);
  EXPECT_THROW(TriangleRest::from(a, b, b), std::invalid_argument);
  EXPECT_THROW(TriangleRest::from(a, b, Eigen::Vector3d(nan, 0, 0)), std::invalid_argument);
  EXPECT_THROW(TriangleRest::from(a, b, Eigen::Vector3d(kInf, 0, 0)), std::invalid_argument);
  // Collinear to round-off (0.1, 0.3, 0.7 are not exact in binary).
  EXPECT_THROW(TriangleRest::from(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.1, 0.3, 0.7),
                                  Eigen::Vector3d(0.3, 0.9, 2.1)),
               std::invalid_argument);
  // A thin but valid triangle is accepted, with Ā⁻¹ Ā = I.
  const TriangleRest r = TriangleRest::from(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0),
                                            Eigen::Vector3d(0.4, 1e-3, 0));
  EXPECT_NEAR(r.area, 0.5e-3, 1e-18);
  Eigen::Matrix2d A;
  A << 1, 0.4, 0.4, 0.16 + 1e-6;
  EXPECT_LE((r.metric_inverse * A - Eigen::Matrix2d::Identity()).norm(), 1e-9);
}

// A hand-made rest state that no triangle has (zero or negative area, Ā⁻¹ not positive) is
// rejected with +inf rather than evaluated.
TEST(TriangleMembrane, InvalidRestStateGivesInfinity) {
  const Triangle t{
      {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0.3, 0.8, 0)}};
  const Vector9 x = deform(t, 1.1 * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  TriangleRest negative = rest_of(t);
  negative.area = -negative.area;
  TriangleRest indefinite = rest_of(t);
  indefinite.metric_inverse(0, 0) = -1.0;
  for (const TriangleRest& rest : {TriangleRest{}, negative, indefinite})
    for (Model m : {Model::kNeoHookean, Model::kStVK})
      EXPECT_EQ(membrane(m, rest, x, nullptr, nullptr), kInf) << name(m);
}
