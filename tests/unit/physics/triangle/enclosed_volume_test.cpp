// Signed triangle volumes: a closed unit cube (12 triangles) and tetrahedra enclose their
// volumes, the closed total is translation-invariant while one triangle's term is not, and the
// gradient and Hessian match central differences.
#include "mlshell/triangle/enclosed_volume.hpp"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "element_fixtures.hpp"

using namespace mlshell;
using mlshell::test::expect_derivatives;
using mlshell::test::random_rotation;
using mlshell::test::stack;

namespace {

using Face = std::array<Eigen::Vector3d, 3>;

/// The unit cube [0, 1]³ as 12 triangles, counter-clockwise seen from outside: each face quad
/// (a, b, c, d) → (a, b, c), (a, c, d).
std::vector<Face> unit_cube() {
  const int quads[6][4][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}},   // z = 0
                              {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},   // z = 1
                              {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},   // y = 0
                              {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},   // y = 1
                              {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}},   // x = 0
                              {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};  // x = 1
  std::vector<Face> faces;
  for (const auto& q : quads) {
    Eigen::Vector3d v[4];
    for (int i = 0; i < 4; ++i) v[i] = Eigen::Vector3d(q[i][0], q[i][1], q[i][2]);
    faces.push_back({v[0], v[1], v[2]});
    faces.push_back({v[0], v[2], v[3]});
  }
  return faces;
}

/// The outward faces of the tetrahedron (p0, p1, p2, p3) with det(p1 − p0, p2 − p0, p3 − p0) > 0.
std::vector<Face> tetrahedron(const Eigen::Vector3d p[4]) {
  return {{p[0], p[2], p[1]}, {p[0], p[1], p[3]}, {p[1], p[2], p[3]}, {p[0], p[3], p[2]}};
}

double total(const std::vector<Face>& faces, const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity(),
             const Eigen::Vector3d& c = Eigen::Vector3d::Zero()) {
  double V = 0.0;
  for (const Face& f : faces)
    V += triangle_volume(R * f[0] + c, R * f[1] + c, R * f[2] + c, nullptr, nullptr);
  return V;
}

}  // namespace

TEST(EnclosedVolume, ClosedUnitCubeEnclosesOne) {
  const std::vector<Face> cube = unit_cube();
  ASSERT_EQ(cube.size(), 12u);
  EXPECT_NEAR(total(cube), 1.0, 1e-15);
  // Translated, rotated, and scaled by 2 (volume 8).
  std::mt19937 rng(47);
  const Eigen::Matrix3d R = random_rotation(rng);
  EXPECT_NEAR(total(cube, Eigen::Matrix3d::Identity(), Eigen::Vector3d(3, -2, 5)), 1.0, 1e-14);
  EXPECT_NEAR(total(cube, R, Eigen::Vector3d(-10, 7, 0.5)), 1.0, 1e-13);
  EXPECT_NEAR(total(cube, 2.0 * R, Eigen::Vector3d(1, 1, 1)), 8.0, 1e-13);
  // Turning every triangle inside out negates the volume.
  std::vector<Face> inward = cube;
  for (Face& f : inward) std::swap(f[1], f[2]);
  EXPECT_NEAR(total(inward), -1.0, 1e-15);
}

TEST(EnclosedVolume, TetrahedraEncloseTheirVolume) {
  const Eigen::Vector3d corner[4] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                     Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  EXPECT_NEAR(total(tetrahedron(corner)), 1.0 / 6.0, 1e-16);
  std::mt19937 rng(53);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::Vector3d p[4];
    for (auto& x : p) x = Eigen::Vector3d(u(rng), u(rng), u(rng));
    Eigen::Matrix3d D;
    D << p[1] - p[0], p[2] - p[0], p[3] - p[0];
    if (D.determinant() < 0) std::swap(p[1], p[2]);
    const double expected = std::abs(D.determinant()) / 6.0;
    EXPECT_NEAR(total(tetrahedron(p)), expected, 1e-14);
    EXPECT_NEAR(total(tetrahedron(p), Eigen::Matrix3d::Identity(), Eigen::Vector3d(5, 5, -5)),
                expected, 1e-13);
  }
}

// V_t(x + c) = V_t(x) + c·n_t/6 with n_t = (x1 − x0) × (x2 − x0): only closed sums are invariant.
TEST(EnclosedVolume, SingleTriangleTermIsNotTranslationInvariant) {
  const Eigen::Vector3d x0(0.2, 0.1, 0.5), x1(1.0, 0.3, 0.2), x2(0.4, 1.1, 0.7), c(1, -2, 3);
  const Eigen::Vector3d n = (x1 - x0).cross(x2 - x0);
  const double V = triangle_volume(x0, x1, x2, nullptr, nullptr);
  EXPECT_NEAR(V, x0.dot(x1.cross(x2)) / 6.0, 1e-16);
  EXPECT_NEAR(triangle_volume(x0 + c, x1 + c, x2 + c, nullptr, nullptr), V + c.dot(n) / 6.0, 1e-15);
  EXPECT_GT(std::abs(c.dot(n)), 0.1);
}

TEST(EnclosedVolume, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(59);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int trial = 0; trial < 20; ++trial) {
    Vector9 x;
    for (int i = 0; i < 9; ++i) x[i] = u(rng);
    expect_derivatives<9>(
        [](const Vector9& y, Vector9* g, Matrix9* H) {
          return triangle_volume(y.segment<3>(0), y.segment<3>(3), y.segment<3>(6), g, H);
        },
        x, 1.0, "trial " + std::to_string(trial));
    Matrix9 H;
    triangle_volume(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), nullptr, &H);
    for (int b = 0; b < 3; ++b) EXPECT_TRUE((H.block<3, 3>(3 * b, 3 * b).isZero(0.0)));
  }
  // The gradient of the cube's volume moves each face outward: pushing the face x = 1 out by h
  // adds h (its area 1) to the volume, which the summed gradient at its 4 vertices predicts.
  const std::vector<Face> cube = unit_cube();
  double dV = 0.0;
  for (const Face& f : cube) {
    Vector9 g;
    triangle_volume(f[0], f[1], f[2], &g, nullptr);
    for (int i = 0; i < 3; ++i)
      if (f[i].x() == 1.0) dV += g[3 * i];
  }
  EXPECT_NEAR(dV, 1.0, 1e-15);
}
