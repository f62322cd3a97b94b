// Reverse subdivision Q (paper §5.3.2, Appendices B and C): exact inverse of subdivision on
// subdivided data (Q S = I, eq. 5.16) on every level, including ghost, corner-ghost and notch
// points and extraordinary vertices of valence 3, 5, 6 and 8, interior and near the boundary.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "mlshell/subdivision/selection.hpp"
#include "mlshell/subdivision/subdivision_hierarchy.hpp"
#include "opensubdiv_reference.hpp"
#include "physics_fixtures.hpp"

using namespace mlshell;

namespace {

struct NamedCage {
  std::string name;
  QuadMesh cage;
};

std::vector<NamedCage> cages() {
  std::vector<NamedCage> out{
      {"square", add_ghost_ring(make_rectangle_cage(1, 1, 4, 4, 0, 0))},
      {"l-shape", add_ghost_ring(make_l_shape_cage(1, 1, 10, 10, 0.3, 0.3, 0, 0))}};
  for (int valence : {3, 5, 6, 8}) {
    out.push_back(
        {"interior valence " + std::to_string(valence), add_ghost_ring(fan_cage(valence))});
    out.push_back({"near-boundary valence " + std::to_string(valence),
                   add_ghost_ring(fan_cage(valence, true))});
  }
  return out;
}

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

TEST(ReverseSubdivision, InvertsSubdivisionOnEveryLevel) {
  for (const NamedCage& c : cages()) {
    const int levels = c.name == "l-shape" ? 2 : 3;
    SubdivisionHierarchy h(c.cage, levels);
    for (int l = 0; l < levels; ++l) {
      const Eigen::MatrixXd QS = Eigen::MatrixXd(h.reverse_subdivision(l) * h.subdivision(l));
      const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(QS.rows(), QS.cols());
      EXPECT_LT(max_abs(QS - I), 1e-13) << c.name << ", level " << l;
    }
  }
}

TEST(ReverseSubdivision, IsSparseAndLocal) {
  for (const NamedCage& c : cages()) {
    SubdivisionHierarchy h(c.cage, 2);
    const SubdivisionMatrix& Q = h.reverse_subdivision(1);
    for (int i = 0; i < Q.rows(); ++i) {
      EXPECT_LE(Q.row(i).nonZeros(), 40) << c.name << ", row " << i;
      EXPECT_NEAR(Q.row(i).sum(), 1.0, 1e-12) << c.name << ", row " << i;  // affine
    }
  }
}

TEST(ReverseSubdivision, IsANearOptimalLocalFitOffTheRangeOfS) {
  // On data outside the range of S, Q is not the least-squares fit P (eq. 5.18 vs 5.19) but a
  // local one: its residual ‖x − S Q x‖ is at least P's (P is optimal) and within a small
  // factor of it (white noise, the worst case: 2.5× on the square, 3.2× at valence 3).
  for (int c : {0, 2}) {  // the square, the valence-3 fan
    SubdivisionHierarchy h(cages()[c].cage, 2);
    const SubdivisionMatrix& S = h.subdivision(1);
    std::mt19937 rng(1);
    std::normal_distribution<double> dist;
    Eigen::MatrixXd fine(S.rows(), 1);
    for (int i = 0; i < fine.rows(); ++i) fine(i, 0) = dist(rng);
    const Eigen::MatrixXd q = h.reverse_subdivision(1) * fine;
    const Eigen::MatrixXd p = LeastSquaresProjection(S).apply(fine);
    ASSERT_TRUE(q.allFinite());
    const double rq = (fine - S * q).norm(), rp = (fine - S * p).norm();
    EXPECT_GE(rq, rp * (1 - 1e-12)) << cages()[c].name;
    EXPECT_LE(rq, 4.0 * rp) << cages()[c].name << ": Q's residual " << rq << ", P's " << rp;
    EXPECT_GT((q - p).norm(), 1e-3 * p.norm()) << cages()[c].name << ": Q is P";
  }
}

TEST(LeastSquaresProjection, SatisfiesTheNormalEquationsAndAgreesWithQOnSubdividedData) {
  SubdivisionHierarchy h(cages()[3].cage, 2);  // interior valence 5
  const SubdivisionMatrix& S = h.subdivision(1);
  LeastSquaresProjection P(S);
  std::mt19937 rng(2);
  std::normal_distribution<double> dist;
  Eigen::MatrixXd fine(S.rows(), 3);
  for (int i = 0; i < fine.rows(); ++i)
    for (int c = 0; c < 3; ++c) fine(i, c) = dist(rng);
  const Eigen::MatrixXd q = P.apply(fine);
  ASSERT_TRUE(q.allFinite());
  // Normal equations Sᵀ(S q − q^{l+1}) = 0: q minimises ‖q^{l+1} − S q‖.
  EXPECT_LT(max_abs(S.transpose() * (S * q - fine)), 1e-10 * max_abs(fine));
  // On data in the range of S, P and Q both recover the coarse points.
  Eigen::MatrixXd coarse(S.cols(), 3);
  for (int i = 0; i < coarse.rows(); ++i) coarse.row(i) = h.level(1).points[i].transpose();
  EXPECT_LT(max_abs(P.apply(S * coarse) - coarse), 1e-11);
  EXPECT_LT(max_abs(Eigen::MatrixXd(h.reverse_subdivision(1) * (S * coarse)) - coarse), 1e-13);
}

TEST(SubdivisionHierarchy, LevelsDescribeTheSameLimitSurface) {
  // Nestedness (5.6): N^l q^l = N^{l+1} S q^l. Sample the limit surface of level l inside the
  // domain and find each point on the limit surface of level l+1.
  for (const NamedCage& c : cages()) {
    if (c.name == "l-shape") continue;
    SubdivisionHierarchy h(c.cage, 2);
    SubdivisionDiscretization coarse(h.level(1), 3), fine(h.level(2), 3);
    std::vector<SurfacePoint> samples;
    for (int f : coarse.elements()) samples.push_back({f, 0.3, 0.6});
    const auto basis = coarse.evaluator().evaluate(samples);
    double worst = 0.0;
    for (const PointBasis& b : basis) {
      double d = 0.0;
      nearest_surface_point(fine, b.apply(kValue, coarse.mesh().points), &d);
      worst = std::max(worst, d);
    }
    EXPECT_LT(worst, 1e-12) << c.name;
  }
}

TEST(SubdivisionHierarchy, TrimmedLevelsMatchOpenSubdivOnTheUntrimmedCage) {
  // Independent reference: refine the whole cage (all ghost layers kept) with OpenSubdiv and
  // interpolate positions directly. Every kept point of the trimmed hierarchy (whose levels are
  // S applied to the previous kept level) must coincide with a point of that refinement: the
  // dropped outer ghost ring never influences the kept points.
  for (const NamedCage& c : cages()) {
    const int levels = 2;
    SubdivisionHierarchy h(c.cage, levels);
    const auto reference = opensubdiv_levels(c.cage, levels);
    for (int l = 1; l <= levels; ++l) {
      // Each kept point of level l equals some refined point (nearest within 1e-13).
      const double worst = farthest_from(h.level(l).points, reference[l]);
      EXPECT_LT(worst, 1e-13) << c.name << ", level " << l;
    }
  }
}
