// Discrete hinge bending: the signed dihedral angle of known configurations (sign convention,
// range (−π, π], mirror and relabelling symmetry), the weight and stiffness formulas, closed-form
// gradients and Hessians against central differences at random, nearly flat, nearly folded,
// rest-angle-near-π and thin-triangle states, zero energy at (curved) rest after rigid motions,
// and +infinity for degenerate deformed hinges.
#include "mlshell/triangle/hinge_bending.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include "element_fixtures.hpp"

using namespace mlshell;
using mlshell::test::expect_derivatives;
using mlshell::test::random_rotation;
using mlshell::test::stack;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Hinge {
  Eigen::Vector3d x[4];
  Vector12 stacked() const { return stack(x[0], x[1], x[2], x[3]); }
  Hinge moved(const Eigen::Matrix3d& R, const Eigen::Vector3d& c) const {
    return Hinge{{R * x[0] + c, R * x[1] + c, R * x[2] + c, R * x[3] + c}};
  }
};

/// A hinge along x of length l with dihedral angle θ: wing 1 in the xy plane (n₁ = +z) with x2 at
/// (a2, r2, 0), wing 2 at distance r3 from the edge turned by θ (x3 below the plane for θ > 0).
Hinge hinge_at(double theta, double a2 = 0.4, double r2 = 0.9, double a3 = 0.6, double r3 = 0.8,
               double l = 1.0) {
  return Hinge{{Eigen::Vector3d::Zero(), Eigen::Vector3d(l, 0, 0), Eigen::Vector3d(a2, r2, 0),
                Eigen::Vector3d(a3, -r3 * std::cos(theta), -r3 * std::sin(theta))}};
}

double theta_of(const Hinge& h) { return dihedral_angle(h.x[0], h.x[1], h.x[2], h.x[3]); }

double energy(const HingeRest& rest, const Vector12& y, Vector12* g, Matrix12* H) {
  return hinge_bending(rest, y.segment<3>(0), y.segment<3>(3), y.segment<3>(6), y.segment<3>(9), g,
                       H);
}

void expect_hinge_derivatives(const HingeRest& rest, const Hinge& h, double length,
                              const std::string& where) {
  expect_derivatives<12>(
      [&](const Vector12& y, Vector12* g, Matrix12* H) { return energy(rest, y, g, H); },
      h.stacked(), length, where);
}

}  // namespace

TEST(HingeBending, DihedralAngleOfKnownConfigurations) {
  const Eigen::Vector3d x0(0, 0, 0), x1(1, 0, 0), x2(0.5, 1, 0);
  EXPECT_EQ(dihedral_angle(x0, x1, x2, Eigen::Vector3d(0.5, -1, 0)), 0.0);
  // Folded by exactly 90°: x3 below the plane (away from n₁ = +z) is convex, θ = +π/2.
  EXPECT_NEAR(dihedral_angle(x0, x1, x2, Eigen::Vector3d(0.5, 0, -1)), kPi / 2, 1e-15);
  EXPECT_NEAR(dihedral_angle(x0, x1, x2, Eigen::Vector3d(0.5, 0, 1)), -kPi / 2, 1e-15);
  // Completely folded: +π, never −π.
  EXPECT_EQ(dihedral_angle(x0, x1, x2, Eigen::Vector3d(0.2, 0.7, 0)), kPi);
  EXPECT_EQ(dihedral_angle(x0, x1, Eigen::Vector3d(0.5, -1, 0), Eigen::Vector3d(0.2, -0.7, 0)),
            kPi);
  EXPECT_EQ(dihedral_angle(x1, x0, Eigen::Vector3d(0.2, 0.7, 0), x2), kPi);
  // One where atan2 itself returns −π (its y is −0).
  EXPECT_EQ(dihedral_angle(Eigen::Vector3d(-2, 0, -2), Eigen::Vector3d(-2, 0, -3),
                           Eigen::Vector3d(2, 2, -3), Eigen::Vector3d(0, 1, -1)),
            kPi);
  // An edge of a convex closed surface with outward normals: the tetrahedron (0, e1, e2, e3)
  // has the outward faces (0, e1, e3) and (e1, 0, e2) on the hinge 0–e1, normals −y and −z:
  // convex, θ = +π/2, whichever face is named first.
  const Eigen::Vector3d o = Eigen::Vector3d::Zero(), e1 = Eigen::Vector3d::UnitX(),
                        e2 = Eigen::Vector3d::UnitY(), e3 = Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(dihedral_angle(o, e1, e3, e2), kPi / 2, 1e-15);
  EXPECT_NEAR(dihedral_angle(e1, o, e2, e3), kPi / 2, 1e-15);
  // A sweep after a rigid motion, including the nearly flat and nearly folded angles.
  std::mt19937 rng(23);
  for (double theta : {1e-6, -1e-6, 0.3, -1.2, 2.5, kPi - 1e-3, -(kPi - 1e-3), kPi - 1e-9}) {
    const Hinge h = hinge_at(theta).moved(random_rotation(rng), Eigen::Vector3d(1, -2, 3));
    EXPECT_NEAR(theta_of(h), theta, 1e-14) << theta;
    // The mirror image negates θ; naming the same hinge from the other triangle keeps it.
    const Eigen::Matrix3d mirror = Eigen::Vector3d(1, 1, -1).asDiagonal();
    EXPECT_NEAR(theta_of(h.moved(mirror, Eigen::Vector3d::Zero())), -theta, 1e-14) << theta;
    EXPECT_NEAR(dihedral_angle(h.x[1], h.x[0], h.x[3], h.x[2]), theta, 1e-14) << theta;
  }
}

TEST(HingeBending, WeightAndStiffnessFormulas) {
  const double k = hinge_stiffness(2e6, 0.3, 0.01);
  EXPECT_NEAR(k, 2e6 * 1e-6 / (24 * (1 - 0.09)), 1e-15);
  // |ē|² = 4, Ā₁ = 1, Ā₂ = 3: w = 3·4/4 k.
  const HingeRest rest = HingeRest::from(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 0, 0),
                                         Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, -3, 0), k);
  EXPECT_NEAR(rest.weight, 3 * k, 1e-15);
  EXPECT_EQ(rest.angle, 0.0);
  // The energy of a 90° fold from flat is w (π/2)².
  EXPECT_NEAR(hinge_bending(rest, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 0, 0),
                            Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 0, -3), nullptr, nullptr),
              3 * k * kPi * kPi / 4, 1e-14);
}

TEST(HingeBending, GradientAndHessianMatchFiniteDifferencesAtRandomStates) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0), angle(-kPi + 0.05, kPi - 0.05);
  std::uniform_real_distribution<double> along(-0.5, 1.5), away(0.3, 1.5);
  for (int trial = 0; trial < 40; ++trial) {
    Hinge h = hinge_at(angle(rng), along(rng), away(rng), along(rng), away(rng))
                  .moved(random_rotation(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)));
    for (auto& x : h.x) x += 0.05 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    const HingeRest rest{angle(rng), 1.3};
    expect_hinge_derivatives(rest, h, 1.0, "trial " + std::to_string(trial));
  }
}

// Nearly flat and nearly folded hinges, each with rest angles at Δ = θ − θ̄ ≈ 0 (where the
// Hessian is 2w ∇θ∇θᵀ) and at |Δ| = 1 (where Δ ∇²θ matters as much), flat and curved.
TEST(HingeBending, GradientAndHessianAccurateWhenNearlyFlatOrFolded) {
  std::mt19937 rng(31);
  for (double theta : {1e-6, -1e-6, 0.0, kPi - 1e-3, -(kPi - 1e-3)}) {
    const Hinge h = hinge_at(theta, 0.3, 0.7, 0.8, 1.1)
                        .moved(random_rotation(rng), Eigen::Vector3d(0.5, 0.5, -1));
    EXPECT_NEAR(theta_of(h), theta, 1e-14);
    const double inward = theta > 0 ? -1.0 : 1.0;
    for (double rest_angle : {theta, 0.0, 0.7, theta + inward}) {
      const HingeRest rest{rest_angle, 0.8};
      expect_hinge_derivatives(
          rest, h, 1.0, "theta " + std::to_string(theta) + " rest " + std::to_string(rest_angle));
    }
  }
}

// θ̄ near π: a hinge that closes past π (θ jumps to ≈ −π) sees a small wrapped Δ, no 2π jump,
// and the derivatives stay exact across the cut.
TEST(HingeBending, RestAngleNearPiWrapsAcrossTheCut) {
  std::mt19937 rng(37);
  const double rest_angle = kPi - 1e-4;
  const HingeRest rest{rest_angle, 2.0};
  const Eigen::Matrix3d R = random_rotation(rng);
  const Eigen::Vector3d c(0.1, 0.2, 0.3);
  const struct {
    double theta, delta;
  } cases[] = {{kPi - 1e-4, 0.0},
               {kPi, 1e-4},
               {-kPi + 1e-4, 2e-4},
               {-kPi + 0.1, 0.1 + 1e-4},
               {kPi - 0.1, -0.1 + 1e-4}};
  for (const auto& k : cases) {
    const Hinge h = hinge_at(k.theta).moved(R, c);
    const double E = energy(rest, h.stacked(), nullptr, nullptr);
    EXPECT_NEAR(E, rest.weight * k.delta * k.delta, 1e-13 * rest.weight) << k.theta;
    if (k.delta != 0.0) {
      EXPECT_NEAR(E / (rest.weight * k.delta * k.delta), 1.0, 1e-9) << k.theta;
    }
    expect_hinge_derivatives(rest, h, 1.0, "theta " + std::to_string(k.theta));
  }
  // The same for θ̄ near −π.
  const HingeRest mirrored{-rest_angle, 2.0};
  const Hinge h = hinge_at(kPi - 1e-4).moved(R, c);
  EXPECT_NEAR(energy(mirrored, h.stacked(), nullptr, nullptr), 2.0 * 4e-8, 1e-16);
  expect_hinge_derivatives(mirrored, h, 1.0, "rest near -pi");
}

// Δ is wrapped into (−π, π]: at Δ = ±π exactly (θ̄ = π, flat hinge) Δ = +π, so the gradient is
// +2wπ ∇θ; rest angles outside (−π, π] act like their wrapped values.
TEST(HingeBending, WrappedDifferenceIsInHalfOpenInterval) {
  std::mt19937 rng(39);
  const Hinge h = hinge_at(0.0).moved(random_rotation(rng), Eigen::Vector3d(1, 2, 3));
  Vector12 g_unit, g_pi;
  energy(HingeRest{-1.0, 1.0}, h.stacked(), &g_unit, nullptr);  // Δ = 1: g = 2∇θ
  const double E = energy(HingeRest{kPi, 1.0}, h.stacked(), &g_pi, nullptr);
  EXPECT_NEAR(E, kPi * kPi, 1e-14);
  EXPECT_LE((g_pi - kPi * g_unit).norm(), 1e-14 * g_pi.norm());
  const Hinge bent = hinge_at(0.4).moved(random_rotation(rng), Eigen::Vector3d(0, 0, 0));
  const double E1 = energy(HingeRest{0.3, 1.0}, bent.stacked(), nullptr, nullptr);
  EXPECT_NEAR(E1, 0.01, 1e-14);
  EXPECT_NEAR(energy(HingeRest{0.3 + 2 * kPi, 1.0}, bent.stacked(), nullptr, nullptr), E1, 1e-14);
  EXPECT_NEAR(energy(HingeRest{0.3 - 4 * kPi, 1.0}, bent.stacked(), nullptr, nullptr), E1, 1e-14);
}

// Aspect ratio 1e-3: wings of height 1e-3 over a unit edge, and a hinge edge of length 1e-3
// under unit-height wings. Steps are relative to the smallest dimension.
TEST(HingeBending, GradientAndHessianMatchFiniteDifferencesOnThinTriangles) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double theta : {0.4, -2.0, kPi - 1e-3, 1e-6}) {
    const Hinge flat_wings = hinge_at(theta, 0.3, 1e-3, 0.7, 2e-3);
    const Hinge short_edge = hinge_at(theta, 4e-4, 1.0, 7e-4, 0.9, 1e-3);
    for (const Hinge& base : {flat_wings, short_edge}) {
      const Hinge h = base.moved(random_rotation(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)));
      for (double rest_angle : {theta, theta > 0 ? theta - 1.0 : theta + 1.0}) {
        expect_hinge_derivatives(HingeRest{rest_angle, 1.0}, h, 1e-3,
                                 "thin theta " + std::to_string(theta));
      }
    }
  }
}

TEST(HingeBending, ZeroAtRestIncludingCurvedRestAfterRigidMotion) {
  std::mt19937 rng(43);
  for (double rest_theta : {0.0, 0.7, -0.7, 3.0}) {
    const Hinge X = hinge_at(rest_theta, 0.2, 0.6, 0.9, 1.3)
                        .moved(random_rotation(rng), Eigen::Vector3d(2, 0, -1));
    const HingeRest rest = HingeRest::from(X.x[0], X.x[1], X.x[2], X.x[3], 0.5);
    EXPECT_NEAR(rest.angle, rest_theta, 1e-14);
    const Hinge moved = X.moved(random_rotation(rng), Eigen::Vector3d(-3, 1, 4));
    for (const Hinge& h : {X, moved}) {
      Vector12 g;
      const double E = energy(rest, h.stacked(), &g, nullptr);
      EXPECT_LE(E, 1e-26 * rest.weight) << rest_theta;
      EXPECT_LE(g.norm(), 1e-12 * rest.weight) << rest_theta;
    }
    // Rigid motions leave the energy of a deformed state unchanged.
    Hinge bent = X;
    bent.x[3] += Eigen::Vector3d(0.1, -0.2, 0.3);
    const double E = energy(rest, bent.stacked(), nullptr, nullptr);
    EXPECT_GT(E, 0.0);
    EXPECT_NEAR(energy(rest, bent.moved(random_rotation(rng), Eigen::Vector3d(1, 1, 1)).stacked(),
                       nullptr, nullptr),
                E, 1e-12 * E);
  }
}

TEST(HingeBending, DegenerateHingeIsInfiniteAndRestThrows) {
  const Eigen::Vector3d x0(0.1, 0.2, 0.3), x1(1.1, 2.2, 3.3), x2(0, 1, 0), x3(1, 0, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const HingeRest rest{0.3, 1.0};
  const Hinge degenerate[] = {{{x0, x0, x2, x3}},                    // zero edge
                              {{x0, x1, x0 + 2.0 * (x1 - x0), x3}},  // wing 1 collinear (exactly)
                              {{x0, x1, x2, x1}},                    // wing 2 collapsed onto x1
                              {{x0, x1, x2, Eigen::Vector3d(nan, 0, 0)}},    // not a position
                              {{x0, x1, Eigen::Vector3d(kInf, 0, 0), x3}}};  // not a position
  for (const Hinge& h : degenerate) {
    Vector12 g = Vector12::Constant(42.0);
    Matrix12 H = Matrix12::Constant(42.0);
    EXPECT_EQ(energy(rest, h.stacked(), &g, &H), kInf);
    EXPECT_EQ(energy(rest, h.stacked(), nullptr, nullptr), kInf);
    EXPECT_EQ(g, Vector12::Constant(42.0));
    EXPECT_EQ(H, Matrix12::Constant(42.0));
  }
  for (int i = 0; i < 3; ++i)
    EXPECT_THROW(HingeRest::from(degenerate[i].x[0], degenerate[i].x[1], degenerate[i].x[2],
                                 degenerate[i].x[3], 1.0),
                 std::invalid_argument);
  EXPECT_THROW(HingeRest::from(x0, x1, x2, Eigen::Vector3d(nan, 0, 0), 1.0), std::invalid_argument);
}
