// Scripted colliders (collider_motion.hpp): a collider moves towards its place only as far as
// is safe, pushing the shell ahead of it, never into it, also when it turns (a rotation's chord
// is not its arc); it stops where the shell is caught against another collider; one that moves
// away arrives at once, exactly at φ(X, t).
#include "mlshell/contact/collider_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../triangle/triangle_fixtures.hpp"
#include "mlshell/effect_builder.hpp"

using namespace mlshell;

namespace {

// A 0.5 m sheet 5 cm above a 1 m square plane; contact keeps 1 cm, the barrier reaching 1 cm
// beyond that.
const char* kScene =
    "geometry: {mesh: {generator: rectangle, size: [0.5, 0.5], edge_length: 0.1}}\n"
    "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, "
    "thickness: 0.01, volume_density: 500}\n"
    "effects:\n"
    "  - contact: {thickness: 0.01, gap: 0.01, stiffness: 10, self: false}\n"
    "  - collider: {plane: {point: [0, 0, -0.05], normal: [0, 0, 1], side: 1.0}}\n"
    "time: {dt: 1, steps: 1, integrator: quasistatic}\n";

/// The plane turned by `angle` about the x axis through (0, y, -0.05), over [0, 1].
PrescribedMotion turn(double y, double angle) {
  Motion m;
  m.over = {0.0, 1.0};
  m.rotate = Rotation{{1, 0, 0}, {0, y, -0.05}, angle};
  return motion_function(m);
}

/// A scene's problem, its contact term and a zero displacement u.
struct Sheet {
  Sheet(const char* name, const std::string& yaml)
      : scene(triangle_scene(name, yaml)), tp(scene, PETSC_COMM_SELF) {
    contact = tp.problem->find_term<ContactTerm>();
    tp.layout().create_vector(&u);
    VecZeroEntries(u);
  }
  ~Sheet() { VecDestroy(&u); }
  /// The largest displacement of any vertex component.
  double pushed() const {
    PetscReal norm;
    VecNorm(u, NORM_INFINITY, &norm);
    return norm;
  }
  Scene scene;
  TriangleProblem tp;
  ContactTerm* contact = nullptr;
  Vec u = nullptr;
};

}  // namespace

// The plane's far half swings up through the sheet (a quarter turn about an axis beyond the
// sheet's edge): after every advance the sheet is still farther than the thickness from it, and
// where the plane has moved, it is at a rigid place of its motion.
TEST(ColliderMotion, ATurningPlaneNeverComesWithinTheThickness) {
  Sheet sheet("collider_turn", kScene);
  ContactTerm* contact = sheet.contact;
  Vec u = sheet.u;
  const std::vector<Point3> rest = contact->obstacles()[0].points;
  const PrescribedMotion motion = turn(0.75, -M_PI / 2);
  ColliderMotion driver(*contact, {motion}, u);
  bool reached = false;
  int advances = 0;
  for (; advances < 40 && !reached; ++advances) {
    ASSERT_EQ(driver.advance(1.0, u, &reached), 0);
    contact->prepare(u, nullptr);
    double d;
    contact->min_squared_distance(&d);
    ASSERT_GT(std::sqrt(d), 0.01) << "advance " << advances;
    const RigidPlacement phi = motion(driver.time());
    for (std::size_t i = 0; i < rest.size(); ++i)
      ASSERT_LT((contact->obstacles()[0].points[i] - phi.position(rest[i])).norm(), 1e-12);
  }
  EXPECT_TRUE(reached);
  EXPECT_GT(driver.moves(), 0);
  EXPECT_GT(sheet.pushed(), 0.05);  // the sheet was carried up with the plane
}

// Turned the other way the plane swings down, away from the sheet: one move, nothing pushed.
TEST(ColliderMotion, APlaneTurningAwayArrivesInOneMoveAndPushesNothing) {
  Sheet sheet("collider_away", kScene);
  Vec u = sheet.u;
  ColliderMotion driver(*sheet.contact, {turn(0.75, M_PI / 2)}, u);
  bool reached = false;
  ASSERT_EQ(driver.advance(1.0, u, &reached), 0);
  EXPECT_TRUE(reached);
  EXPECT_EQ(driver.moves(), 1);
  EXPECT_EQ(driver.cut_moves(), 0);
  EXPECT_EQ(sheet.pushed(), 0.0);
}

// With a ceiling 5 cm above the sheet, the turning plane pushes the sheet into it: CCD cuts the
// moves short, the plane stops where the sheet is caught, and no state comes within the
// thickness of either plane.
TEST(ColliderMotion, ATurningPlaneStopsWhereTheSheetIsCaughtUnderACeiling) {
  std::string yaml = kScene;
  yaml.insert(yaml.find("time:"),
              "  - collider: {plane: {point: [0, 0, 0.05], normal: [0, 0, -1], side: 1.0}}\n");
  Sheet sheet("collider_caught", yaml);
  ContactTerm* contact = sheet.contact;
  Vec u = sheet.u;
  ASSERT_EQ(contact->obstacles().size(), 2u);
  ColliderMotion driver(*contact, {turn(0.75, -M_PI / 2), PrescribedMotion()}, u);
  bool reached = false;
  for (int advances = 0; advances < 40 && !reached; ++advances) {
    ASSERT_EQ(driver.advance(1.0, u, &reached), 0);
    contact->prepare(u, nullptr);
    double d;
    contact->min_squared_distance(&d);
    ASSERT_GT(std::sqrt(d), 0.01) << "advance " << advances;
  }
  EXPECT_FALSE(reached);
  EXPECT_GT(driver.cut_moves(), 0);
  EXPECT_LT(driver.time(), 1.0);
}
