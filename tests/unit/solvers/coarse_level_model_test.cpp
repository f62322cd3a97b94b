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

TEST(CoarseLevelModel, GalerkinModelIsTheFineQuadraticOnTheCoarseSpace) {
  // h(x₀ + w) = ⟨R∇f, w⟩ + ½ wᵀ SᵀHS w is the fine quadratic model ∇fᵀs + ½ sᵀHs along s = S w,
  // computed here from fine-level products only; its gradient and Hessian are those of that
  // quadratic, and the Galerkin operator fits the coarse Hessian's pattern.
  TwoLevels t;
  Vec u1 = t.random(1, 1e-3, 11), g1, x0 = t.random(0, 1e-3, 12), rg, w = t.random(0, 1e-3, 13), x,
      gh, s, hs, v;
  VecDuplicate(u1, &g1);
  VecDuplicate(u1, &s);
  VecDuplicate(u1, &hs);
  VecDuplicate(x0, &rg);
  VecDuplicate(x0, &x);
  VecDuplicate(x0, &gh);
  VecDuplicate(x0, &v);
  PetscReal f1;
  t.problem.level(1).objective(u1, &f1, g1);
  MatMult(t.levels.restriction(0), g1, rg);
  Mat H1, G = nullptr, Hc;
  t.problem.level(1).create_hessian(&H1);
  t.problem.level(1).hessian(u1, H1);
  ASSERT_EQ(t.levels.transfer(0).coarse_operator(x0, H1, MAT_INITIAL_MATRIX, &G), 0);
  CoarseLevelModel model(t.problem.level(0));
  model.initialize_galerkin(x0, rg, G);
  PetscReal h, err, ref;
  model.objective(x0, &h, gh);
  EXPECT_EQ(h, 0.0);
  VecAXPY(gh, -1.0, rg);
  VecNorm(gh, NORM_INFINITY, &err);
  EXPECT_EQ(err, 0.0);  // eq. (4.5), exactly
  // The value and gradient at x₀ + w against the fine quadratic along s = S w.
  VecWAXPY(x, 1.0, x0, w);
  model.objective(x, &h, gh);
  MatMult(t.levels.prolongation(0), w, s);
  MatMult(H1, s, hs);
  PetscReal gs, shs;
  VecDot(g1, s, &gs);
  VecDot(s, hs, &shs);
  const double expected = gs + 0.5 * shs;
  EXPECT_NEAR(h, expected, 1e-10 * (std::abs(gs) + std::abs(shs)));
  MatMult(t.levels.restriction(0), hs, v);  // R H S w + R∇f
  VecAXPY(v, 1.0, rg);
  VecNorm(v, NORM_INFINITY, &ref);
  VecAXPY(gh, -1.0, v);
  VecNorm(gh, NORM_INFINITY, &err);
  EXPECT_LT(err, 1e-10 * ref);
  // The Hessian: G copied into the coarse level's own matrix without new allocations, over the
  // level's own Hessian left there before (the full-multigrid start assembles it); a central
  // difference of the gradient along d agrees with H d to round-off (the model is quadratic).
  t.problem.level(0).create_hessian(&Hc);
  t.problem.level(0).hessian(x0, Hc);
  ASSERT_EQ(model.hessian(x, Hc), 0);
  MatInfo info;
  MatGetInfo(Hc, MAT_LOCAL, &info);
  EXPECT_EQ(info.mallocs, 0.0);
  Vec d = t.random(0, 1.0, 14), hd, gp, gm;
  VecDuplicate(d, &hd);
  VecDuplicate(d, &gp);
  VecDuplicate(d, &gm);
  MatMult(Hc, d, hd);
  const double eps = 1e-4;
  PetscReal unused;
  VecAXPY(x, eps, d);
  model.objective(x, &unused, gp);
  VecAXPY(x, -2 * eps, d);
  model.objective(x, &unused, gm);
  VecAXPY(gp, -1.0, gm);
  VecScale(gp, 1.0 / (2 * eps));
  VecNorm(hd, NORM_INFINITY, &ref);
  VecAXPY(gp, -1.0, hd);
  VecNorm(gp, NORM_INFINITY, &err);
  EXPECT_LT(err, 1e-6 * ref);
  // The Galerkin operator against R H S applied to d.
  MatMult(t.levels.prolongation(0), d, s);
  MatMult(H1, s, hs);
  MatMult(t.levels.restriction(0), hs, v);
  MatMult(G, d, hd);
  VecNorm(v, NORM_INFINITY, &ref);
  VecAXPY(hd, -1.0, v);
  VecNorm(hd, NORM_INFINITY, &err);
  EXPECT_LT(err, 1e-12 * ref);
  MatDestroy(&H1);
  MatDestroy(&G);
  MatDestroy(&Hc);
  for (Vec* p : {&u1, &g1, &x0, &rg, &w, &x, &gh, &s, &hs, &v, &d, &hd, &gp, &gm}) VecDestroy(p);
}
