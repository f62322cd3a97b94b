// RMTR's coarse-level model (eq. 4.3–4.4) on a real two-level hierarchy: first-order
// consistency (eq. 4.5) and derivatives.
#include "mlshell/coarse_level_model.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "mlshell/multilevel_problem.hpp"

using namespace mlshell;

namespace {

struct TwoLevels {
  Scene scene;
  SubdivisionHierarchy sub;
  LevelHierarchy levels;
  MultilevelProblem problem;
  TwoLevels()
      : scene(parse_scene(std::filesystem::path(MLSHELL_SOURCE_DIR) / "examples/trampoline.yaml")),
        sub(add_ghost_ring(make_rectangle_cage(1, 1, 4, 4, 0, 0)), 1),
        levels(PETSC_COMM_SELF, sub, 0, 3),
        problem(scene, levels, CageFrame::from(scene.geometry)) {
    for (int l = 0; l < 2; ++l) problem.level(l).set_time(scene.time.dt);
  }
  Vec random(int l, double scale, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> d(-scale, scale);
    std::vector<double> nat(levels.discretization(l).num_dofs());
    for (double& x : nat) x = d(rng);
    Vec v;
    levels.layout(l).create_vector(&v);
    levels.layout(l).scatter_natural(nat, v);
    return v;
  }
};

}  // namespace

TEST(CoarseLevelModel, FirstCoarseGradientIsTheRestrictedFineGradient) {
  TwoLevels t;
  Vec u1 = t.random(1, 1e-3, 1), g1, x0, rg, g0;
  VecDuplicate(u1, &g1);
  PetscReal f1;
  t.problem.level(1).objective(u1, &f1, g1);
  t.levels.layout(0).create_vector(&x0);
  VecDuplicate(x0, &rg);
  VecDuplicate(x0, &g0);
  MatMult(t.levels.projection(0), u1, x0);   // x₀ = Q x_fine
  MatMult(t.levels.restriction(0), g1, rg);  // R ∇f_fine
  CoarseLevelModel model(t.problem.level(0));
  model.initialize(x0, rg);
  PetscReal h, f0, err, ref;
  model.objective(x0, &h, g0);
  t.problem.level(0).objective(x0, &f0, nullptr);
  EXPECT_EQ(h, f0);  // the coupling term vanishes at x₀
  VecAXPY(g0, -1.0, rg);
  VecNorm(g0, NORM_INFINITY, &err);
  VecNorm(rg, NORM_INFINITY, &ref);
  EXPECT_LT(err, 1e-12 * ref);  // eq. (4.5)
  for (Vec* v : {&u1, &g1, &x0, &rg, &g0}) VecDestroy(v);
}

TEST(CoarseLevelModel, IsTheCoarseObjectivePlusTheFirstOrderCoupling) {
  // Eq. (4.3) against the coarse objective assembled on its own: at any x,
  // h(x) − f₀(x) = ⟨R∇f − ∇f₀(x₀), x − x₀⟩ + const and ∇h(x) = ∇f₀(x) + R∇f − ∇f₀(x₀), with
  // ∇f₀(x₀) assembled independently at the projected point (not taken from the model).
  TwoLevels t;
  Vec x0 = t.random(0, 1e-3, 6), rg = t.random(0, 1.0, 7), g00, x, gx, gh, expected;
  VecDuplicate(x0, &g00);
  VecDuplicate(x0, &gx);
  VecDuplicate(x0, &gh);
  VecDuplicate(x0, &expected);
  PetscReal f00, h0;
  t.problem.level(0).objective(x0, &f00, g00);
  CoarseLevelModel model(t.problem.level(0));
  model.initialize(x0, rg);
  model.objective(x0, &h0, nullptr);
  for (unsigned seed : {8u, 9u}) {
    x = t.random(0, 1e-3, seed);
    PetscReal fx, hx;
    t.problem.level(0).objective(x, &fx, gx);
    model.objective(x, &hx, gh);
    // expected gradient ∇f₀(x) + R∇f − ∇f₀(x₀)
    VecWAXPY(expected, -1.0, g00, rg);
    VecAXPY(expected, 1.0, gx);
    PetscReal err, ref, coupling;
    VecAXPY(gh, -1.0, expected);
    VecNorm(gh, NORM_INFINITY, &err);
    VecNorm(expected, NORM_INFINITY, &ref);
    EXPECT_LT(err, 1e-12 * ref) << "seed " << seed;
    // value: (h(x) − h(x₀)) − (f₀(x) − f₀(x₀)) = ⟨R∇f − ∇f₀(x₀), x − x₀⟩
    Vec dx, v;
    VecDuplicate(x, &dx);
    VecDuplicate(x, &v);
    VecWAXPY(dx, -1.0, x0, x);
    VecWAXPY(v, -1.0, g00, rg);
    VecDot(v, dx, &coupling);
    EXPECT_NEAR((hx - h0) - (fx - f00), coupling, 1e-9 * (std::abs(coupling) + std::abs(fx)))
        << "seed " << seed;
    VecDestroy(&dx);
    VecDestroy(&v);
    VecDestroy(&x);
  }
  for (Vec* v : {&x0, &rg, &g00, &gx, &gh, &expected}) VecDestroy(v);
}

TEST(CoarseLevelModel, GradientMatchesFiniteDifferences) {
  TwoLevels t;
  Vec x0 = t.random(0, 1e-3, 2), rg = t.random(0, 1.0, 3), x = t.random(0, 1e-3, 4),
      d = t.random(0, 1.0, 5), g;
  VecDuplicate(x, &g);
  CoarseLevelModel model(t.problem.level(0));
  model.initialize(x0, rg);
  PetscReal h, hp, hm, gd;
  model.objective(x, &h, g);
  VecDot(g, d, &gd);
  const double eps = 1e-6;
  VecAXPY(x, eps, d);
  model.objective(x, &hp, nullptr);
  VecAXPY(x, -2 * eps, d);
  model.objective(x, &hm, nullptr);
  EXPECT_NEAR(gd, (hp - hm) / (2 * eps), 1e-6 * std::abs(gd));
  for (Vec* v : {&x0, &rg, &x, &d, &g}) VecDestroy(v);
}
