// The shell prolongation's kernel (paper 2 eq. 4–9): rest-shape recovery, linearity on flat
// pairs, rigid motions, the polar factor against an SVD, the Jacobian against central finite
// differences (also on nearly collinear and inverted triangles), degenerate triangles, bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <random>
#include <stdexcept>

#include "prolongation/prolongation_fixtures.hpp"

using namespace mlshell;

namespace {

double max_distance(const std::vector<Point3>& a, const std::vector<Point3>& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

std::vector<Point3> deformed(const std::vector<Point3>& points, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Point3> x = points;
  for (Point3& p : x) p += amplitude * Point3(u(rng), u(rng), u(rng));
  return x;
}

/// max |J − J_fd| / max |J| over fine vertex i, with central differences of step h.
double jacobian_error(const ShellProlongation& P, int i, std::array<Point3, 3> x, double h) {
  const ShellProlongation::Jacobian J = P.jacobian(i, x[0], x[1], x[2]);
  EXPECT_TRUE(J.allFinite());
  ShellProlongation::Jacobian fd;
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) {
      std::array<Point3, 3> plus = x, minus = x;
      plus[k][c] += h;
      minus[k][c] -= h;
      fd.col(3 * k + c) =
          (P.point(i, plus[0], plus[1], plus[2]) - P.point(i, minus[0], minus[1], minus[2])) /
          (2.0 * h);
    }
  return (J - fd).cwiseAbs().maxCoeff() / J.cwiseAbs().maxCoeff();
}

/// One coarse rest triangle (right-angled, legs 1 and 0.7, tilted out of the xy plane) with
/// fine points above, below and beside it, so γ and t are not zero.
struct OneTriangle {
  TriangleMesh coarse;
  std::vector<Point3> fine;
  std::vector<EmbeddedPoint> embedding;
  OneTriangle() {
    coarse.points = {Point3(0.1, 0.2, 0.0), Point3(1.1, 0.2, 0.3), Point3(0.0, 0.9, 0.1)};
    coarse.triangles = {{0, 1, 2}};
    const std::vector<Eigen::Vector3d> weights = {
        {1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.6, 0.3, 0.1}, {0.0, 0.5, 0.5}, {1.0, 0.0, 0.0}};
    const std::vector<Point3> offsets = {Point3(0.05, -0.02, 0.1), Point3(-0.1, 0.05, -0.07),
                                         Point3(0.02, 0.08, 0.0), Point3(0.0, 0.0, 0.04)};
    for (size_t k = 0; k < weights.size(); ++k) {
      EmbeddedPoint e;
      e.triangle = 0;
      e.weights = weights[k];
      embedding.push_back(e);
      fine.push_back(weights[k][0] * coarse.points[0] + weights[k][1] * coarse.points[1] +
                     weights[k][2] * coarse.points[2] + offsets[k]);
    }
  }
  ShellProlongation prolongation() const { return {coarse, fine, embedding}; }
};

}  // namespace

TEST(ShellProlongation, RecoversTheFineRestShape) {
  struct Case {
    const char* name;
    RefinedPair pair;
  };
  for (const Case& c :
       {Case{"sphere", sphere_pair(1)}, Case{"sphere, survivors moved", sphere_pair(1, true)},
        Case{"dome", dome_pair()}, Case{"wavy plate", wavy_plate_pair()}}) {
    const ShellProlongation P = make_prolongation(c.pair);
    double largest_offset = 0.0;
    for (int i = 0; i < P.num_fine(); ++i)
      largest_offset =
          std::max(largest_offset, std::abs(P.normal_offset(i)) + P.tangent_offset(i).norm());
    EXPECT_GT(largest_offset, 1e-3) << c.name << ": the offsets must matter";
    const double scale = bounding_box_diagonal(c.pair.fine.points);
    EXPECT_LT(max_distance(P.apply(c.pair.coarse.points), c.pair.fine.points), 1e-12 * scale)
        << c.name;
  }
}

TEST(ShellProlongation, FlatPairIsTheIntrinsicProlongation) {
  // Fine points on the coarse plane at their anchors: γ = 0, t = 0, so P(x) = U x for any x.
  const RefinedPair pair = split_one_to_four(make_unstructured_rectangle(1.0, 1.0, 0.25));
  const ShellProlongation P = make_prolongation(pair);
  for (int i = 0; i < P.num_fine(); ++i) {
    EXPECT_EQ(P.normal_offset(i), 0.0);
    EXPECT_EQ(P.tangent_offset(i).norm(), 0.0);
    EXPECT_NEAR(P.embedding(i).weights.sum(), 1.0, 1e-15);  // U is a partition of unity
  }
  const std::vector<Point3> x = deformed(pair.coarse.points, 0.2, 3);
  const std::vector<Point3> fine = P.apply(x);
  for (int i = 0; i < P.num_fine(); ++i) {
    const Triangle& c = P.columns(i);
    const Eigen::Vector3d& w = P.embedding(i).weights;
    const Point3 Ux = w[0] * x[c[0]] + w[1] * x[c[1]] + w[2] * x[c[2]];
    EXPECT_LT((fine[i] - Ux).norm(), 1e-15) << "fine vertex " << i;
    ShellProlongation::Jacobian U;
    U << w[0] * Eigen::Matrix3d::Identity(), w[1] * Eigen::Matrix3d::Identity(),
        w[2] * Eigen::Matrix3d::Identity();
    EXPECT_LT((P.jacobian(i, x[c[0]], x[c[1]], x[c[2]]) - U).cwiseAbs().maxCoeff(), 1e-15);
  }
}

TEST(ShellProlongation, InPlaneOffsetsStayInThePlane) {
  // Fine points shifted in the coarse plane only: γ = 0, and an in-plane deformation (no fold)
  // keeps every prolonged point in the plane.
  TriangleMesh coarse = make_unstructured_rectangle(1.0, 1.0, 0.25);
  const RefinedPair pair = split_one_to_four(coarse, [](int, const Point3& p, bool mid) -> Point3 {
    return mid ? Point3(p + Point3(0.02 * std::sin(9.0 * p.y()), 0.02 * std::cos(7.0 * p.x()), 0.0))
               : p;
  });
  const ShellProlongation P = make_prolongation(pair);
  double largest_t = 0.0;
  for (int i = 0; i < P.num_fine(); ++i) {
    EXPECT_EQ(P.normal_offset(i), 0.0);
    largest_t = std::max(largest_t, P.tangent_offset(i).norm());
  }
  EXPECT_GT(largest_t, 1e-3);
  std::vector<Point3> x = pair.coarse.points;
  for (Point3& p : x) p = Point3(1.3 * p.x() + 0.2 * p.y(), 0.9 * p.y() + 0.1 * p.x() * p.x(), 0.0);
  for (const Point3& p : P.apply(x)) EXPECT_LT(std::abs(p.z()), 1e-15);
}

TEST(ShellProlongation, FollowsRigidMotions) {
  const Eigen::Matrix3d Q =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  const Point3 shift(0.4, -1.2, 2.5);
  for (const RefinedPair& pair : {sphere_pair(1, true), wavy_plate_pair(), dome_pair()}) {
    const ShellProlongation P = make_prolongation(pair);
    std::vector<Point3> x = pair.coarse.points, expected = pair.fine.points;
    for (Point3& p : x) p = Q * p + shift;
    for (Point3& p : expected) p = Q * p + shift;
    EXPECT_LT(max_distance(P.apply(x), expected), 1e-12 * bounding_box_diagonal(expected));
  }
}

TEST(ShellProlongation, PolarRotationIsTheSvdsRotation) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Matrix<double, 3, 2> F;
    for (int k = 0; k < 6; ++k) F.data()[k] = u(rng);
    if (trial % 3 == 0) F.col(1) = 0.01 * F.col(1) + F.col(0);  // badly conditioned
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(F),
                                                Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::MatrixXd expected = svd.matrixU() * svd.matrixV().transpose();
    const Eigen::Matrix<double, 3, 2> R = polar_rotation(F);
    EXPECT_LT((R - expected).cwiseAbs().maxCoeff(), 1e-12) << "trial " << trial;
    EXPECT_LT((R.transpose() * R - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff(), 1e-13);
  }
  // Rank 1: the segment's direction; rank 0: nothing.
  Eigen::Matrix<double, 3, 2> F;
  F << 2.0, 4.0, 0.0, 0.0, 0.0, 0.0;
  EXPECT_LT((polar_rotation(F) - F / F.norm()).norm(), 1e-15);
  EXPECT_EQ(polar_rotation(Eigen::Matrix<double, 3, 2>::Zero()).norm(), 0.0);
}

TEST(ShellProlongation, JacobianMatchesFiniteDifferences) {
  const RefinedPair pair = sphere_pair(1, true);
  const ShellProlongation P = make_prolongation(pair);
  const std::vector<Point3> x = deformed(pair.coarse.points, 0.1, 11);
  double worst = 0.0;
  for (int i = 0; i < P.num_fine(); ++i) {
    const Triangle& c = P.columns(i);
    worst = std::max(worst, jacobian_error(P, i, {x[c[0]], x[c[1]], x[c[2]]}, 1e-6));
  }
  EXPECT_LT(worst, 1e-8);
}

TEST(ShellProlongation, JacobianMatchesFiniteDifferencesOnHardTriangles) {
  const OneTriangle t;
  const ShellProlongation P = t.prolongation();
  const Point3 &a = t.coarse.points[0], &b = t.coarse.points[1], &c = t.coarse.points[2];
  struct Case {
    const char* name;
    std::array<Point3, 3> x;
    double h;
  };
  const Point3 lift(0.01, -0.02, 0.03);
  const std::vector<Case> cases = {
      {"stretched and bent",
       {a, Point3(b + Point3(0.3, 0.1, -0.2)), Point3(c + Point3(-0.1, 0.2, 0.4))},
       1e-6},
      // x₂ within 1e-3 of the line through x₀, x₁.
      {"nearly collinear", {a, b, Point3(0.5 * (a + b) + 1e-3 * Point3(0.0, 0.0, 1.0))}, 1e-9},
      // x₂ reflected through the edge x₀x₁: the triangle turned over.
      {"inverted",
       {a, b,
        Point3(a + (b - a) * (b - a).dot(c - a) / (b - a).squaredNorm() * 2.0 - (c - a) + lift)},
       1e-6},
      {"shrunk tenfold",
       {a, Point3(a + 0.1 * (b - a)), Point3(a + 0.1 * (c - a) + 0.1 * lift)},
       1e-8}};
  for (const Case& k : cases)
    for (int i = 0; i < P.num_fine(); ++i)
      EXPECT_LT(jacobian_error(P, i, k.x, k.h), 2e-6) << k.name << ", fine point " << i;
  // The inverted triangle's normal is the rest normal turned over: γ moves to the other side.
  const Point3 anchor = (a + b + c) / 3.0;
  const Point3 up = P.point(0, a, b, c) - anchor;
  const Point3 down = P.point(0, cases[2].x[0], cases[2].x[1], cases[2].x[2]) -
                      (cases[2].x[0] + cases[2].x[1] + cases[2].x[2]) / 3.0;
  const Point3 rest_normal = (b - a).cross(c - a).normalized();
  EXPECT_GT(up.dot(rest_normal), 0.0);
  EXPECT_LT(down.dot(rest_normal), 0.0);
}

TEST(ShellProlongation, DegenerateTrianglesStayFinite) {
  const OneTriangle t;
  const ShellProlongation P = t.prolongation();
  const Point3 &a = t.coarse.points[0], &b = t.coarse.points[1];
  const std::array<Point3, 3> segment = {a, b, Point3(0.25 * a + 0.75 * b)};  // rank 1
  const std::array<Point3, 3> point = {a, a, a};                              // rank 0
  const std::array<Point3, 3> nearly_point = {a, Point3(a + Point3(1e-14, 0, 0)), a};
  for (int i = 0; i < P.num_fine(); ++i) {
    const Eigen::Vector3d& w = P.embedding(i).weights;
    for (const auto& x : {segment, point, nearly_point}) {
      const Point3 p = P.point(i, x[0], x[1], x[2]);
      EXPECT_TRUE(p.allFinite());
      EXPECT_TRUE(P.jacobian(i, x[0], x[1], x[2]).allFinite());
      const Point3 anchor = w[0] * x[0] + w[1] * x[1] + w[2] * x[2];
      // Rank 1: n = 0 and R = F/‖F‖, so only the in-plane offset remains, along the segment.
      EXPECT_LE((p - anchor).norm(), P.tangent_offset(i).norm() + 1e-15);
      EXPECT_LT((p - anchor).cross(b - a).norm(), 1e-14);
    }
    EXPECT_LT((P.point(i, a, a, a) - a).norm(), 1e-15);  // rank 0: the anchor
  }
  // Rank 1's Jacobian is that of the branch: check it against differences along the segment.
  for (int i = 0; i < P.num_fine(); ++i) {
    const ShellProlongation::Jacobian J = P.jacobian(i, segment[0], segment[1], segment[2]);
    Eigen::Matrix<double, 9, 1> d;  // a direction that keeps the triangle a segment
    d << 0.1, 0.2, -0.1, 0.3, -0.2, 0.1, 0.0, 0.0, 0.0;
    Eigen::Matrix<double, 9, 1> dir;
    dir << d.head<6>(), 0.25 * d.head<3>() + 0.75 * d.segment<3>(3);
    const double h = 1e-6;
    std::array<Point3, 3> plus = segment, minus = segment;
    for (int k = 0; k < 3; ++k) {
      plus[k] += h * dir.segment<3>(3 * k);
      minus[k] -= h * dir.segment<3>(3 * k);
    }
    const Point3 fd =
        (P.point(i, plus[0], plus[1], plus[2]) - P.point(i, minus[0], minus[1], minus[2])) /
        (2 * h);
    EXPECT_LT((J * dir - fd).norm(), 1e-8 * (1.0 + fd.norm())) << "fine point " << i;
  }
}

TEST(ShellProlongation, RejectsBadInput) {
  const OneTriangle t;
  std::vector<Point3> fine = t.fine;
  std::vector<EmbeddedPoint> embedding = t.embedding;
  EXPECT_THROW(
      ShellProlongation(t.coarse, std::vector<Point3>(fine.begin(), fine.end() - 1), embedding),
      std::invalid_argument);
  embedding[1].triangle = 1;
  EXPECT_THROW(ShellProlongation(t.coarse, fine, embedding), std::invalid_argument);
  embedding[1].triangle = -1;
  EXPECT_THROW(ShellProlongation(t.coarse, fine, embedding), std::invalid_argument);
  embedding = t.embedding;
  embedding[2].weights = Eigen::Vector3d(0.3, 0.3, 0.3);
  EXPECT_THROW(ShellProlongation(t.coarse, fine, embedding), std::invalid_argument);
  embedding[2].weights = Eigen::Vector3d(0.5, 0.5, std::nan(""));
  EXPECT_THROW(ShellProlongation(t.coarse, fine, embedding), std::invalid_argument);
  embedding[2].weights = Eigen::Vector3d(0.5, 0.5 - 1e-11, 1e-11 + 1e-12);  // within 1e-10
  EXPECT_NO_THROW(ShellProlongation(t.coarse, fine, embedding));
  TriangleMesh flat = t.coarse;  // a degenerate rest triangle that carries points
  flat.points[2] = 0.5 * (flat.points[0] + flat.points[1]);
  try {
    ShellProlongation(flat, fine, t.embedding);
    ADD_FAILURE() << "a degenerate rest triangle was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("degenerate"), std::string::npos) << e.what();
  }
  TriangleMesh bad_index = t.coarse;
  bad_index.triangles[0][2] = 7;
  EXPECT_THROW(ShellProlongation(bad_index, fine, t.embedding), std::invalid_argument);
}
