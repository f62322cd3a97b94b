// The contact term on a scene (contact_term.hpp): its gradient and Hessian against finite
// differences of the term alone, CCD as max_step, the barrier's domain, and the Hessian's
// pattern growing under the same matrix handle.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "mlshell/contact/barrier/adaptive_stiffness.hpp"
#include "mlshell/contact/contact_term.hpp"
#include "../triangle/triangle_fixtures.hpp"

using namespace mlshell;

namespace {

// A sheet 5 cm above a plane collider, the barrier reaching 10 cm beyond a 1 cm thickness: every
// vertex sees the plane, and with self-contact the sheet's non-adjacent primitives (≥ 8.7 cm
// apart) see each other.
std::string contact_scene(bool self) {
  return std::string(
             "geometry: {mesh: {generator: rectangle, size: [0.5, 0.5], edge_length: 0.1}}\n"
             "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, "
             "thickness: 0.01, volume_density: 500}\n"
             "effects:\n"
             "  - contact: {thickness: 0.01, gap: 0.1, stiffness: 10, self: ") +
         (self ? "true" : "false") +
         "}\n"
         "  - collider: {plane: {point: [0, 0, -0.05], normal: [0, 0, 1], side: 1.0}}\n"
         "time: {dt: 1, steps: 1, integrator: quasistatic}\n";
}

/// The scene's contact term alone in a problem of its own, on `tp`'s layout.
std::unique_ptr<LevelProblem> contact_only(const TriangleProblem& tp) {
  const auto* term = tp.problem->find_term<ContactTerm>();
  EXPECT_NE(term, nullptr);
  auto problem = std::make_unique<LevelProblem>(tp.layout());
  problem->add_term(std::make_unique<ContactTerm>("contact", tp.disc().mesh(), tp.layout(),
                                                  term->obstacles(), term->settings()));
  return problem;
}

void fill(Vec v, double scale, double phase) {
  PetscInt lo, hi;
  VecGetOwnershipRange(v, &lo, &hi);
  for (PetscInt i = lo; i < hi; ++i)
    VecSetValue(v, i, scale * std::sin(0.9 * i + phase), INSERT_VALUES);
  VecAssemblyBegin(v);
  VecAssemblyEnd(v);
}

}  // namespace

TEST(ContactTerm, GradientAndHessianMatchFiniteDifferences) {
  long active[2] = {0, 0};  // without and with self-contact
  for (const bool self : {false, true}) {
    const Scene scene = triangle_scene("contact_fd", contact_scene(self));
    TriangleProblem tp(scene, PETSC_COMM_SELF);
    auto problem = contact_only(tp);
    Vec u, d, g, gp, gm, Hd;
    tp.layout().create_vector(&u);
    for (Vec* v : {&d, &g, &gp, &gm, &Hd}) VecDuplicate(u, v);
    fill(u, 5e-3, 0.3);
    fill(d, 1.0, 1.1);
    double f, fp, fm;
    problem->objective(u, &f, g);
    ASSERT_TRUE(std::isfinite(f));
    ASSERT_GT(f, 0.0);
    ContactStatistics stats;
    problem->find_term<ContactTerm>()->statistics(&stats);
    EXPECT_GT(stats.active, 50);
    active[self] = stats.active;
    const double h = 1e-6;
    VecAXPY(u, h, d);
    problem->objective(u, &fp, gp);
    VecAXPY(u, -2 * h, d);
    problem->objective(u, &fm, gm);
    VecAXPY(u, h, d);
    double gd, gnorm, dnorm;
    VecDot(g, d, &gd);
    VecNorm(g, NORM_2, &gnorm);
    VecNorm(d, NORM_2, &dnorm);
    // Scaled to the term: its own gradient's size along d.
    EXPECT_NEAR((fp - fm) / (2 * h), gd, 1e-6 * gnorm * dnorm) << "self " << self;
    Mat H;
    double err, hd_norm;
    hessian_difference(*problem, u, d, gp, gm, Hd, h, &H, &err, &hd_norm);
    EXPECT_LT(err, 1e-5 * hd_norm) << "self " << self;
    MatDestroy(&H);
    for (Vec* v : {&u, &d, &g, &gp, &gm, &Hd}) VecDestroy(v);
  }
  EXPECT_GT(active[1], active[0] + 50) << "self-contact adds the sheet's own pairs";
}

namespace {

/// Every component c of v set to value[c].
void fill_uniform(Vec v, const std::array<double, 3>& value) {
  PetscInt lo, hi;
  VecGetOwnershipRange(v, &lo, &hi);
  for (PetscInt i = lo; i < hi; ++i) VecSetValue(v, i, value[i % 3], INSERT_VALUES);
  VecAssemblyBegin(v);
  VecAssemblyEnd(v);
}

}  // namespace

// CCD as the step limit: the sheet moved 10 cm straight down onto a plane 5 cm below stops
// before its mid-surface comes within the thickness (1 cm) of the plane, and a step away from the
// plane is not limited. Inside the thickness the energy is +∞ (never NaN).
TEST(ContactTerm, MaxStepStopsBeforeTheThicknessAndTheBarrierEndsThere) {
  const Scene scene = triangle_scene("contact_ccd", contact_scene(false));
  TriangleProblem tp(scene, PETSC_COMM_SELF);
  LevelProblem& problem = *tp.problem;
  Vec u, du;
  tp.layout().create_vector(&u);
  VecDuplicate(u, &du);
  VecZeroEntries(u);
  fill_uniform(du, {0.0, 0.0, -0.1});
  double alpha;
  problem.max_step(u, du, &alpha);
  // The gap closes from 4 cm to 0 at α = 0.4; CCD stops short of it, leaving a gap.
  EXPECT_GT(alpha, 0.05);
  EXPECT_LT(alpha, 0.4);
  VecAXPY(u, alpha, du);
  double f;
  problem.objective(u, &f, nullptr);
  EXPECT_TRUE(std::isfinite(f));
  double d;
  problem.find_term<ContactTerm>()->min_squared_distance(&d);
  EXPECT_GT(std::sqrt(d), 0.01);
  // Away from the plane: no limit.
  VecZeroEntries(u);
  fill_uniform(du, {0.0, 0.0, 0.1});
  problem.max_step(u, du, &alpha);
  EXPECT_EQ(alpha, 1.0);
  // 4.5 cm down: 5 mm from the plane, inside the 1 cm thickness.
  fill_uniform(u, {0.0, 0.0, -0.045});
  problem.objective(u, &f, nullptr);
  EXPECT_EQ(f, PETSC_INFINITY);
  VecDestroy(&u);
  VecDestroy(&du);
}

// `self: false` leaves out every pair of the shell with itself: without a collider there is
// none, and with `self: true` the same sheet has both point–triangle and edge–edge pairs.
TEST(ContactTerm, SelfContactOffLeavesNoShellPairs) {
  for (const bool self : {false, true}) {
    std::string yaml = contact_scene(self);
    yaml.erase(yaml.find("  - collider"), yaml.find("time:") - yaml.find("  - collider"));
    const Scene scene = triangle_scene("contact_self", yaml);
    TriangleProblem tp(scene, PETSC_COMM_SELF);
    Vec u;
    tp.layout().create_vector(&u);
    fill(u, 5e-3, 0.3);
    double f;
    tp.problem->objective(u, &f, nullptr);
    ContactStatistics stats;
    tp.problem->find_term<ContactTerm>()->statistics(&stats);
    if (self) {
      EXPECT_GT(stats.active, 100);
    } else {
      EXPECT_EQ(stats.candidates, 0);
    }
    VecDestroy(&u);
  }
}

// Moving obstacles (collider_motion.hpp's pieces): the plane 5 cm below the sheet raised 10 cm
// through it is cut by CCD short of the thickness; the carry step pushes the sheet ahead of it
// (the plane's vertical motion, by the fraction 1 − t/2 of a time of impact t ≤ 0.4, so at
// least 80 % of it), and the joint move is then safe; a plane lowered away pushes nothing; and
// the moved plane is where the energy sees it.
TEST(ContactTerm, ObstaclesMoveOnlyAsFarAsCcdAllowsAndPushTheShellAhead) {
  const Scene scene = triangle_scene("contact_moving", contact_scene(false));
  TriangleProblem tp(scene, PETSC_COMM_SELF);
  auto* contact = tp.problem->find_term<ContactTerm>();
  Vec u, du;
  tp.layout().create_vector(&u);
  VecDuplicate(u, &du);
  VecZeroEntries(u);
  VecZeroEntries(du);
  auto shifted = [&](double dz) {
    std::vector<std::vector<Point3>> points;
    for (const TriangleMesh& o : contact->obstacles()) {
      points.push_back(o.points);
      for (Point3& p : points.back()) p[2] += dz;
    }
    return points;
  };
  const auto up = shifted(0.1);
  double alpha;
  contact->obstacle_step_limit(u, du, up, &alpha);
  EXPECT_GT(alpha, 0.05);  // the gap closes to the thickness at α = 0.4
  EXPECT_LT(alpha, 0.4);
  const std::vector<char> moving{1};
  const auto rise = [](double dz) {
    return [dz](int, const Point3& x) { return Point3(x + Point3(0, 0, dz)); };
  };
  contact->carry(u, up, moving, rise(0.1), du);
  PetscInt n;
  VecGetLocalSize(du, &n);
  const PetscScalar* d;
  VecGetArrayRead(du, &d);
  for (PetscInt i = 0; i < n; i += 3) {  // every vertex is over the plane
    EXPECT_EQ(d[i], 0.0);
    EXPECT_EQ(d[i + 1], 0.0);
    EXPECT_GE(d[i + 2], 0.08 - 1e-12);
    EXPECT_LE(d[i + 2], 0.1);
  }
  VecRestoreArrayRead(du, &d);
  contact->obstacle_step_limit(u, du, up, &alpha);
  EXPECT_EQ(alpha, 1.0);
  // Lowered away: nothing to push.
  contact->carry(u, shifted(-0.1), moving, rise(-0.1), du);
  PetscReal norm;
  VecNorm(du, NORM_INFINITY, &norm);
  EXPECT_EQ(norm, 0.0);
  // Moved 4.5 cm up, the plane is 5 mm below the sheet: inside the thickness, +∞ energy.
  contact->move_obstacles(shifted(0.045));
  double f;
  tp.problem->objective(u, &f, nullptr);
  EXPECT_EQ(f, PETSC_INFINITY);
  contact->move_obstacles(shifted(0.0));
  tp.problem->objective(u, &f, nullptr);
  EXPECT_EQ(f, PETSC_INFINITY) << "still there";
  contact->move_obstacles(shifted(-0.045));
  tp.problem->objective(u, &f, nullptr);
  EXPECT_TRUE(std::isfinite(f));
  VecDestroy(&u);
  VecDestroy(&du);
}

// Adaptive κ (contact_term.hpp): the sheet lowered towards the plane within 10⁻² ĝ of the
// thickness, a little closer after each accepted iterate, doubles κ up to its cap and no
// further: 100 κ₀ (IPC's) when nothing presses harder than the force f a vertex holds, and the κ
// at which one pair at half the gap holds f_max when the shell's own pull may press harder.
TEST(ContactTerm, AdaptiveStiffnessDoublesUpToTheForceAVertexCanBePressedWith) {
  std::string yaml = contact_scene(false);
  yaml.replace(yaml.find("stiffness: 10, "), 15, "");
  const Scene scene = triangle_scene("contact_adaptive", yaml);
  TriangleProblem tp(scene, PETSC_COMM_SELF);
  const auto* term = tp.problem->find_term<ContactTerm>();
  ContactSettings settings = term->settings();
  ASSERT_EQ(settings.stiffness, 0.0);
  const double half = settings.barrier.thickness + 0.5 * settings.barrier.gap;
  const double holding = std::abs(settings.barrier.first_derivative(half * half)) * 2.0 * half;
  for (const double pull : {1.0, 1e4}) {
    settings.vertex_force = 1.0;
    settings.max_vertex_force = pull;
    LevelProblem problem(tp.layout());
    problem.add_term(std::make_unique<ContactTerm>("contact", tp.disc().mesh(), tp.layout(),
                                                   term->obstacles(), settings));
    const auto* contact = problem.find_term<ContactTerm>();
    const double kappa0 = contact->stiffness();
    EXPECT_DOUBLE_EQ(kappa0, std::max(1.0 / holding, min_barrier_stiffness(
                                                         settings.barrier, settings.bbox_diagonal,
                                                         settings.average_mass)));
    const double cap = std::max(100.0 * kappa0, pull / holding);
    Vec u;
    tp.layout().create_vector(&u);
    // The plane is 5 cm below; the gap to the thickness shrinks from 9e-4 by 1e-5 per iterate.
    for (int k = 0; k < 40; ++k) {
      VecSet(u, 0.0);
      for (PetscInt i = 2; i < 3 * tp.disc().mesh().num_points(); i += 3)
        VecSetValue(u, i, -0.04 + 9e-4 - 1e-5 * k, INSERT_VALUES);
      VecAssemblyBegin(u);
      VecAssemblyEnd(u);
      double f;
      problem.objective(u, &f, nullptr);
      problem.accepted(u);
    }
    EXPECT_DOUBLE_EQ(contact->stiffness(), cap) << "f_max = " << pull;
    EXPECT_GT(cap, (pull > 1.0 ? 1000.0 : 99.0) * kappa0);
    VecDestroy(&u);
  }
}
