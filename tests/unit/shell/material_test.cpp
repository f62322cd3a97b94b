// The woven-cloth material (paper eq. 3.3-3.4) of both presets: derivatives against finite
// differences in every regime (fitted, continued, coupling-limited), C² across the switches,
// positivity of `denim` against the negative well of `denim-table1`, and Table 1's responses
// against an independent long-double evaluation of the table.
#include "mlshell/shell/material.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace mlshell;

namespace {

// Table 1 typed again (not read from the preset), with mu_j1 from sum_i mu_ji = 1.
constexpr long double kK[4] = {4.79e6L, 4.52e6L, 9.03e6L, 2.44e6L};
const std::vector<std::vector<long double>> kMu = {{-1482.1L, 276.43L, 2407.67L, 3416.79L},
                                                   {},
                                                   {0.658L, -185.7L, -45.82L, 146.98L},
                                                   {0.79L, 11.08L}};
const std::vector<std::vector<long double>> kAlpha = {{-7.80L, 10.80L, 18.95L, -12.89L, 1.61L},
                                                      {1.0L},
                                                      {12.71L, -12802.0L, 17.91L, 30.07L, 24.68L},
                                                      {2.95L, -2823.9L, 4.29L}};

/// φ_j(u) of Table 1 in long double with powl (no expm1 tricks).
long double table1_phi(int j, long double u) {
  std::vector<long double> mu = kMu[j];
  long double rest = 0.0L;
  for (long double m : mu) rest += m;
  mu.insert(mu.begin(), 1.0L - rest);
  long double f = 0.0L;
  for (size_t i = 0; i < mu.size(); ++i)
    f += mu[i] / kAlpha[j][i] * (powl(1.0L + u, kAlpha[j][i]) - 1.0L);
  return f;
}

ClydeOrthotropicMaterial denim() { return ClydeOrthotropicMaterial(denim_preset()); }
ClydeOrthotropicMaterial table1() { return ClydeOrthotropicMaterial(denim_table1_preset()); }

/// Central differences of ψ and ∇ψ against the analytic gradient and Hessian. The step and the
/// tolerance scale with the strain and with this point's own derivatives.
void expect_derivatives(const Material& m, const Strain3& e, const char* where) {
  Eigen::Vector3d g;
  Eigen::Matrix3d H;
  m.energy_density(e, &g, &H);
  const double h = 1e-6 * std::max(1e-2, e.norm());
  for (int i = 0; i < 3; ++i) {
    Strain3 ep = e, em = e;
    ep[i] += h;
    em[i] -= h;
    Eigen::Vector3d gp, gm;
    const double fd =
        (m.energy_density(ep, &gp, nullptr) - m.energy_density(em, &gm, nullptr)) / (2 * h);
    EXPECT_NEAR(g[i], fd, 1e-6 * g.norm() + 1e-8 * H.norm() * h)
        << where << " e = " << e.transpose();
    const Eigen::Vector3d col = (gp - gm) / (2 * h);
    EXPECT_LT((H.col(i) - col).norm(), 1e-5 * H.norm()) << where << " e = " << e.transpose();
  }
  EXPECT_LT((H - H.transpose()).norm(), 1e-12 * H.norm());
}

}  // namespace

TEST(Material, BothPresetsMatchFiniteDifferencesInEveryRegime) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> small(-0.05, 0.05), large(-0.6, 0.6);
  const ClydeOrthotropicMaterial presets[] = {denim(), table1()};
  for (const auto& m : presets) {
    for (int t = 0; t < 20; ++t) {
      expect_derivatives(m, Strain3(small(rng), small(rng), small(rng)), "fitted");
      expect_derivatives(m, Strain3(large(rng), large(rng), large(rng)), "large");
    }
    // The weft continuation (|Ẽ22| > 0.279), the strain-100 % caps, and mixed strains where
    // the coupling limit acts, including the lines Ẽ11 = 0 and Ẽ22 = 0 and tiny strains.
    for (const Strain3& e :
         {Strain3(0.0, 0.35, 0.0), Strain3(0.01, -0.4, 0.02), Strain3(1.3, 0.0, 0.0),
          Strain3(0.0, 0.0, 1.2), Strain3(0.115, -0.11, 0.0), Strain3(-0.2, 0.15, 0.01),
          Strain3(1e-6, 0.1, 0.0), Strain3(0.1, 1e-7, 0.0), Strain3(2e-5, -3e-5, 1e-5),
          Strain3(0.0, 0.07, 0.0)})
      expect_derivatives(m, e, "regime");
  }
}

TEST(Material, DenimIsPositiveForEveryNonzeroStrainAndTable1HasItsWell) {
  const ClydeOrthotropicMaterial d = denim(), t = table1();
  double min_ratio = INFINITY, min_table1 = INFINITY;
  Strain3 at = Strain3::Zero();
  const int n = 40;  // grid of (2n+1)³ points on [-0.5, 0.5]³
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; k += 4) {
        const Strain3 e(0.5 * i / n, 0.5 * j / n, 0.5 * k / n);
        if (e.isZero()) continue;
        const double psi = d.energy_density(e, nullptr, nullptr);
        // ψ ≥ (1 − θ_b)(A + B) + k4 φ4: the limit's guarantee, with A, B from the φ used.
        const double A = 0.5 * 4.79e6 * d.phi(0)(e[0] * e[0]).f,
                     B = 0.5 * 9.03e6 * d.phi(2)(e[1] * e[1]).f,
                     D = 2.44e6 * d.phi(3)(e[2] * e[2]).f;
        ASSERT_GT(psi, 0.0) << e.transpose();
        ASSERT_GE(psi, (1 - 0.9) * (A + B) + D - 1e-12 * psi) << e.transpose();
        min_ratio = std::min(min_ratio, psi / (A + B + D));
        const double pt = t.energy_density(e, nullptr, nullptr);
        if (pt < min_table1) {
          min_table1 = pt;
          at = e;
        }
      }
  EXPECT_GT(min_ratio, 0.1);
  // Table 1 as printed: ψ_min ≈ −0.0205 MPa near Ẽ = (0.115, −0.11, 0) (or its mirror).
  EXPECT_LT(min_table1, -0.018e6);
  EXPECT_GT(min_table1, -0.022e6);
  EXPECT_NEAR(std::abs(at[0]), 0.11, 0.02);
  EXPECT_NEAR(std::abs(at[1]), 0.11, 0.02);
  EXPECT_LT(at[0] * at[1], 0.0);
}

TEST(Material, BothPresetsKeepTable1sTangentAndUniaxialResponses) {
  const ClydeOrthotropicMaterial presets[] = {denim(), table1()};
  for (const auto& m : presets) {
    Eigen::Vector3d g;
    Eigen::Matrix3d H;
    EXPECT_EQ(m.energy_density(Strain3::Zero(), &g, &H), 0.0);
    EXPECT_EQ(g.norm(), 0.0);
    EXPECT_NEAR(H(0, 0), 4.79e6, 1e-3);
    EXPECT_NEAR(H(0, 1), 4.52e6, 1e-3);
    EXPECT_NEAR(H(1, 1), 9.03e6, 1e-3);
    EXPECT_NEAR(H(2, 2), 2 * 2.44e6, 1e-3);
    EXPECT_EQ(H(0, 2), 0.0);
    // Uniaxial warp (to 60 %), weft (to 27 %, where φ3' peaks) and shear (to 60 %): k/2 φ(Ẽ²)
    // and k4 φ4(Ẽ12²) of the table, to the accuracy of the fit's own cancellation.
    for (double s = -0.6; s <= 0.6; s += 0.01) {
      const long double warp = 0.5L * kK[0] * table1_phi(0, (long double)s * s);
      const long double shear = kK[3] * table1_phi(3, (long double)s * s);
      EXPECT_NEAR(m.energy_density(Strain3(s, 0, 0), nullptr, nullptr), (double)warp,
                  1e-10 * std::abs((double)warp) + 1e-3)
          << s;
      EXPECT_NEAR(m.energy_density(Strain3(0, 0, s), nullptr, nullptr), (double)shear,
                  1e-10 * std::abs((double)shear) + 1e-3)
          << s;
      if (std::abs(s) <= 0.27) {
        const long double weft = 0.5L * kK[2] * table1_phi(2, (long double)s * s);
        EXPECT_NEAR(m.energy_density(Strain3(0, s, 0), nullptr, nullptr), (double)weft,
                    1e-10 * std::abs((double)weft) + 1e-3)
            << s;
      }
    }
  }
}

TEST(Material, Table1PresetIsEquation33WithTheTableOnBiaxialAndShearedStrains) {
  // ψ = k1/2 φ1(Ẽ11²) + k2 φ2(Ẽ11 Ẽ22) + k3/2 φ3(Ẽ22²) + k4 φ4(Ẽ12²) inside the fitted range,
  // every term from the table typed above: a wrong k, μ or α of any row shows here.
  const ClydeOrthotropicMaterial m = table1();
  for (double a : {-0.2, -0.05, 0.03, 0.15})
    for (double b : {-0.12, -0.02, 0.04, 0.09})
      for (double c : {-0.3, 0.1}) {
        const long double psi = 0.5L * kK[0] * table1_phi(0, (long double)a * a) +
                                kK[1] * table1_phi(1, (long double)a * b) +
                                0.5L * kK[2] * table1_phi(2, (long double)b * b) +
                                kK[3] * table1_phi(3, (long double)c * c);
        const double scale = 0.5 * 4.79e6 * a * a + 0.5 * 9.03e6 * b * b + 2.44e6 * c * c;
        EXPECT_NEAR(m.energy_density(Strain3(a, b, c), nullptr, nullptr), (double)psi, 1e-9 * scale)
            << a << " " << b << " " << c;
      }
}

TEST(Material, WeftIsContinuedFromItsPeakStiffnessAndStaysIncreasing) {
  const ClydeOrthotropicMaterial m = denim();
  const ResponseFunction& phi3 = m.phi(2);
  // φ3' peaks at u ≈ 0.078 and falls to zero at u ≈ 0.10 (the fit turns down there).
  EXPECT_NEAR(phi3.upper_limit(), 0.0779, 5e-4);
  EXPECT_NEAR(phi3.fitted(phi3.upper_limit()).ddf, 0.0, 1e-6 * phi3.fitted(0.05).ddf);
  EXPECT_LT(phi3.fitted(0.105).df, 0.0);
  for (double u = 1e-6; u < 1e4; u *= 1.1) {
    ASSERT_GT(phi3(u).df, 0.0) << u;
    ASSERT_GT(m.phi(0)(u).df, 0.0) << u;
    ASSERT_GT(m.phi(3)(u).df, 0.0) << u;
  }
  // C² at the switch: value, slope and curvature continuous.
  const double us = phi3.upper_limit(), d = 1e-9;
  const PhiValue below = phi3(us - d), above = phi3(us + d);
  EXPECT_NEAR(below.f, above.f, 1e-7 * std::abs(below.f));
  EXPECT_NEAR(below.df, above.df, 1e-6 * std::abs(below.df));
  EXPECT_NEAR(below.ddf, above.ddf, 1e-5 * std::abs(phi3(0.05).ddf));
  EXPECT_FALSE(phi3.continued(us - d));
  EXPECT_TRUE(phi3.continued(us + d));
  // Finite for any strain a solver can try; the status reports the continuation.
  EXPECT_TRUE(std::isfinite(m.energy_density(Strain3(1e3, -1e3, 1e3), nullptr, nullptr)));
  EXPECT_TRUE(m.status(Strain3(0.0, 0.3, 0.0)).beyond_fit);
  EXPECT_FALSE(m.status(Strain3(0.0, 0.25, 0.0)).beyond_fit);
}

TEST(Material, CouplingLimitIsSmoothAtItsOnsetAndNearTheAxes) {
  const ClydeOrthotropicMaterial m = denim();
  // Along the ray Ẽ = t (1, −1, 0) the limit switches on at some t₀: find it by bisection.
  double lo = 1e-4, hi = 0.1;
  ASSERT_FALSE(m.status(Strain3(lo, -lo, 0)).coupling_limited);
  ASSERT_TRUE(m.status(Strain3(hi, -hi, 0)).coupling_limited);
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (m.status(Strain3(mid, -mid, 0)).coupling_limited ? hi : lo) = mid;
  }
  Eigen::Vector3d g0, g1;
  Eigen::Matrix3d H0, H1;
  const double d = 1e-9;
  const double p0 = m.energy_density(Strain3(lo - d, -(lo - d), 0), &g0, &H0);
  const double p1 = m.energy_density(Strain3(hi + d, -(hi + d), 0), &g1, &H1);
  EXPECT_NEAR(p0, p1, 1e-6 * p0);
  EXPECT_LT((g0 - g1).norm(), 1e-6 * g0.norm());
  EXPECT_LT((H0 - H1).norm(), 1e-5 * H0.norm());
  // At Ẽ11 = 0 the coupling and its Ẽ22-derivatives vanish; the Ẽ11-slope is k2 s Ẽ22.
  Eigen::Vector3d g;
  Eigen::Matrix3d H;
  const double psi = m.energy_density(Strain3(0.0, 0.07, 0.0), &g, &H);
  EXPECT_EQ(psi, m.energy_density(Strain3(0.0, 0.07, 0.0), nullptr, nullptr));
  EXPECT_TRUE(std::isfinite(H.norm()));
  EXPECT_TRUE(m.status(Strain3(0.0, 0.07, 0.0)).coupling_limited);
  EXPECT_GT(g[0], 0.0);
  EXPECT_LT(g[0], 4.52e6 * 0.07);
}

TEST(Material, RejectsResponseFunctionsThatCannotBeContinued) {
  ClydeMaterial bad = denim_table1_preset();
  bad.mu[0][0] -= 2.0;  // φ1'(0) = −1
  EXPECT_THROW(ClydeOrthotropicMaterial{bad}, std::invalid_argument);
  ClydeMaterial falling = denim_table1_preset();
  falling.mu[3] = {2.0, -1.0};  // φ4' = 2 − (1+u)^9: falls from 1 to 0 without rising
  falling.alpha[3] = {1.0, 10.0};
  EXPECT_THROW(ClydeOrthotropicMaterial{falling}, std::invalid_argument);
}
