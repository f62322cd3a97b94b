// Prescribed rigid motions (scene.hpp's Motion, made placements by motion_function): a quarter
// turn of a point about an axis through a centre before, at, midway through and after its
// interval, a point of the axis that stays, the right-hand rule, rotation before translation,
// and the reach that bounds the displacements. The terms that follow the placements are tested
// with their effects (term_test.cpp, triangle_shell_test.cpp, rotating_support_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mlshell/effect_builder.hpp"
#include "mlshell/scene.hpp"

namespace mlshell {
namespace {

/// φ_t(X) of the motion's placement at time t.
Vec3 placed(const Motion& motion, const Vec3& X, double t) {
  const Eigen::Vector3d x = motion_function(motion)(t).position(Eigen::Vector3d(X.data()));
  return {x[0], x[1], x[2]};
}

/// φ_t(X) − X.
Vec3 displacement(const Motion& motion, const Vec3& X, double t) {
  const Eigen::Vector3d d = motion_function(motion)(t).displacement(Eigen::Vector3d(X.data()));
  return {d[0], d[1], d[2]};
}

void expect_near_vec3(const Vec3& actual, const Vec3& expected, double tolerance = 1e-14) {
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(actual[i], expected[i], tolerance) << "component " << i;
}

TEST(Motion, AQuarterTurnAboutAnAxisThroughACentre) {
  // About the vertical line through (1, 2, 0), counter-clockwise seen from +z; the axis's length
  // does not matter.
  Motion motion;
  motion.over = {1.0, 3.0};
  motion.rotate = Rotation{{0, 0, 5}, {1, 2, 0}, std::numbers::pi / 2};
  const Vec3 X{2, 2, 0.7};                      // 1 m along +x from the axis
  expect_near_vec3(placed(motion, X, 0.0), X);  // before t0
  expect_near_vec3(placed(motion, X, 1.0), X);  // at t0
  // Midway: an eighth of a turn.
  const double r = std::sqrt(0.5);
  expect_near_vec3(placed(motion, X, 2.0), {1 + r, 2 + r, 0.7});
  expect_near_vec3(placed(motion, X, 3.0), {1, 3, 0.7});   // at t1: +x turned to +y
  expect_near_vec3(placed(motion, X, 50.0), {1, 3, 0.7});  // and stays there
  // A point of the axis stays at every time.
  for (const double t : {0.0, 1.5, 2.0, 3.0, 10.0})
    expect_near_vec3(displacement(motion, {1, 2, -4}, t), {0, 0, 0});
  // The rotation at t1 turns directions: R e_x = e_y, R e_z = e_z.
  const Mat3 R = motion.rotation(3.0);
  expect_near_vec3({R[0][0], R[1][0], R[2][0]}, {0, 1, 0});
  expect_near_vec3({R[0][2], R[1][2], R[2][2]}, {0, 0, 1});
  // The right-hand rule about an axis along −z turns the other way.
  motion.rotate->axis = {0, 0, -1};
  expect_near_vec3(placed(motion, X, 3.0), {1, 1, 0.7});
}

TEST(Motion, RotatesFirstThenTranslates) {
  // A half turn about the x axis through the origin, then a translation by (0, 0, 1):
  // (0, 1, 0) → (0, −1, 0) → (0, −1, 1). Translating first would give (0, −1, −1).
  const Motion motion{{0, 0, 1}, {0.0, 2.0}, Rotation{{1, 0, 0}, {0, 0, 0}, std::numbers::pi}};
  expect_near_vec3(placed(motion, {0, 1, 0}, 2.0), {0, -1, 1});
  // Midway: a quarter turn, half the translation: (0, 1, 0) → (0, 0, 1) → (0, 0, 1.5).
  expect_near_vec3(placed(motion, {0, 1, 0}, 1.0), {0, 0, 1.5});
  // The reach bounds every displacement of points within the radius of the centre.
  EXPECT_DOUBLE_EQ(motion.reach(1.0), 1.0 + 2.0);
  const Motion translation{{3, 4, 0}, {0, 1}};
  EXPECT_DOUBLE_EQ(translation.reach(10.0), 5.0);
}

}  // namespace
}  // namespace mlshell
