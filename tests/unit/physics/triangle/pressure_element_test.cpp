// One face's pressure work about a fixed centre, −p V_t(x − c): its gradient and exact Hessian
// against central differences (tolerances on this element's own scale), the same element
// wherever face and centre are translated together, and the projected Hessian of
// -mlshell_hessian_psd: positive semi-definite, the nearest such matrix to the exact one (the
// exact block minus its negative part), and the exact block itself where that is PSD.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "element_fixtures.hpp"
#include "mlshell/psd_projection.hpp"
#include "mlshell/triangle/triangle_effects.hpp"

using namespace mlshell;
using mlshell::test::expect_derivatives;

namespace {

constexpr double kPressure = 2500.0;

Eigen::Vector3d random_point(std::mt19937& rng, double size) {
  std::uniform_real_distribution<double> u(-size, size);
  return Eigen::Vector3d(u(rng), u(rng), u(rng));
}

}  // namespace

TEST(PressureElement, GradientAndExactHessianMatchFiniteDifferencesAboutACentre) {
  std::mt19937 rng(61);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d c = random_point(rng, 5.0);
    Vector9 x;
    for (int k = 0; k < 3; ++k) x.segment<3>(3 * k) = c + random_point(rng, 0.3);
    expect_derivatives<9>(
        [&](const Vector9& y, Vector9* g, Matrix9* H) {
          return pressure_element(y.segment<3>(0), y.segment<3>(3), y.segment<3>(6), c, kPressure,
                                  false, g, H);
        },
        x, 0.3, "trial " + std::to_string(trial));
  }
}

TEST(PressureElement, IsTheSameWhereverFaceAndCentreAreTranslatedTogether) {
  std::mt19937 rng(67);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Vector3d x0 = random_point(rng, 1.0), x1 = random_point(rng, 1.0),
                          x2 = random_point(rng, 1.0), c = random_point(rng, 0.5),
                          shift = random_point(rng, 100.0);
    for (const bool project : {false, true}) {
      Vector9 g, gs;
      Matrix9 H, Hs;
      const double e = pressure_element(x0, x1, x2, c, kPressure, project, &g, &H);
      const double es = pressure_element(x0 + shift, x1 + shift, x2 + shift, c + shift, kPressure,
                                         project, &gs, &Hs);
      const double scale = kPressure * 1e-13 * shift.norm();
      EXPECT_NEAR(es, e, scale) << trial;
      EXPECT_LE((gs - g).norm(), scale) << trial;
      EXPECT_LE((Hs - H).norm(), scale) << trial;
    }
  }
}

TEST(PressureElement, ProjectedHessianIsTheNearestPsdBlock) {
  std::mt19937 rng(71);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d c = random_point(rng, 1.0);
    const Eigen::Vector3d x0 = random_point(rng, 1.0), x1 = random_point(rng, 1.0),
                          x2 = random_point(rng, 1.0);
    Vector9 g, gp;
    Matrix9 exact, projected;
    const double e = pressure_element(x0, x1, x2, c, kPressure, false, &g, &exact);
    const double ep = pressure_element(x0, x1, x2, c, kPressure, true, &gp, &projected);
    // The projection changes the Hessian only.
    EXPECT_EQ(ep, e);
    EXPECT_EQ(gp, g);
    // ∇²V_t has zero diagonal blocks, so zero trace: a non-zero block is indefinite.
    const Eigen::SelfAdjointEigenSolver<Matrix9> of_exact(exact), of_projected(projected);
    const double scale = exact.norm();
    ASSERT_GT(scale, 0.0);
    EXPECT_NEAR(exact.trace(), 0.0, 1e-14 * scale);
    EXPECT_LT(of_exact.eigenvalues().minCoeff(), -1e-3 * scale);
    // PSD, symmetric, and exact − projected is the negative part: NSD, with the Frobenius norm
    // sqrt(Σ_{λ<0} λ²) of the nearest PSD matrix.
    EXPECT_GE(of_projected.eigenvalues().minCoeff(), -1e-12 * scale) << trial;
    EXPECT_LE((projected - projected.transpose()).norm(), 1e-14 * scale);
    const Eigen::SelfAdjointEigenSolver<Matrix9> of_difference(exact - projected);
    EXPECT_LE(of_difference.eigenvalues().maxCoeff(), 1e-12 * scale) << trial;
    double negative2 = 0.0;
    for (int i = 0; i < 9; ++i) negative2 += std::pow(std::min(of_exact.eigenvalues()[i], 0.0), 2);
    EXPECT_NEAR((exact - projected).norm(), std::sqrt(negative2), 1e-12 * scale) << trial;
  }
  // Where the exact block is PSD it is kept exactly: with no pressure (a ramp at t = 0), and for
  // a face through the centre whose corners all sit at c (V_t and its Hessian vanish).
  const Eigen::Vector3d x0(0.2, 0.1, 0.5), x1(1.0, 0.3, 0.2), x2(0.4, 1.1, 0.7);
  for (const auto& [p, y0, y1, y2] :
       {std::tuple{0.0, x0, x1, x2}, std::tuple{kPressure, x0, x0, x0}}) {
    Matrix9 exact, projected;
    pressure_element(y0, y1, y2, x0, p, false, nullptr, &exact);
    pressure_element(y0, y1, y2, x0, p, true, nullptr, &projected);
    EXPECT_EQ(projected, exact);
    EXPECT_TRUE(exact.isZero(0.0));
  }
}
