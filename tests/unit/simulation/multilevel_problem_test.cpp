// The scene re-discretised on every level, and the synchronisation of the levels in time.
#include "mlshell/multilevel_problem.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "mlshell/effects.hpp"

using namespace mlshell;

namespace {

Scene trampoline() {
  Scene s = parse_scene(std::filesystem::path(MLSHELL_SOURCE_DIR) / "examples/trampoline.yaml");
  s.time.dt = 0.5;
  return s;
}

/// Natural-order values of level 0 prolongated to level `l` by the scalar subdivision matrices.
std::vector<double> prolongate(const SubdivisionHierarchy& sub, std::vector<double> x, int l) {
  for (int k = 0; k < l; ++k) {
    Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> X(x.data(),
                                                                                  x.size() / 3, 3);
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> Y = sub.subdivision(k) * X;
    x.assign(Y.data(), Y.data() + Y.size());
  }
  return x;
}

}  // namespace

TEST(MultilevelProblem, EveryLevelAssemblesEveryEffectWithTheFinestLevelsPenalty) {
  const Scene scene = trampoline();
  SubdivisionHierarchy sub(add_ghost_ring(make_rectangle_cage(1, 1, 4, 4, 0, 0)), 2);
  LevelHierarchy levels(PETSC_COMM_SELF, sub, 0, 3);
  MultilevelProblem problem(scene, levels, CageFrame::from(scene.geometry));
  ASSERT_EQ(problem.num_levels(), 3);
  for (int l = 0; l < 3; ++l) {
    const auto& terms = problem.level(l).terms();
    ASSERT_EQ(terms.size(), 4u);  // elastic, inertia, gravity, dirichlet
    EXPECT_NE(problem.level(l).find_term<InertiaTerm>(), nullptr);
    EXPECT_NE(problem.level(l).find_term<PenaltyTerm>(), nullptr);
    // A uniform sag u_z = −0.01 everywhere: the boundary penalty is β/2 · 0.01² · perimeter on
    // every level, with β = h^-5 of the finest level: all levels discretise one functional.
    Vec u;
    levels.layout(l).create_vector(&u);
    std::vector<double> nat(levels.discretization(l).num_dofs(), 0.0);
    for (size_t i = 2; i < nat.size(); i += 3) nat[i] = -0.01;
    levels.layout(l).scatter_natural(nat, u);
    std::vector<double> energies;
    problem.level(l).term_energies(u, energies);
    const double beta = std::pow(levels.discretization(2).mesh_size(), -5.0);
    EXPECT_NEAR(energies[3], 0.5 * beta * 1e-4 * 4.0, 1e-9 * beta) << "level " << l;
    VecDestroy(&u);
  }
}

TEST(MultilevelProblem, SynchronizeProjectsStatesAndPredictorsToEveryLevel) {
  const Scene scene = trampoline();
  SubdivisionHierarchy sub(add_ghost_ring(make_rectangle_cage(1, 1, 4, 4, 0, 0)), 2);
  LevelHierarchy levels(PETSC_COMM_SELF, sub, 0, 3);
  MultilevelProblem problem(scene, levels, CageFrame::from(scene.geometry));
  // A state of the coarsest level, subdivided to the finest: projection must recover it exactly.
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> d(-0.01, 0.01);
  std::vector<double> u0(levels.discretization(0).num_dofs()), v0(u0.size());
  for (double& x : u0) x = d(rng);
  for (double& x : v0) x = d(rng);
  Vec uf, vf;
  levels.layout(2).create_vector(&uf);
  levels.layout(2).create_vector(&vf);
  levels.layout(2).scatter_natural(prolongate(sub, u0, 2), uf);
  levels.layout(2).scatter_natural(prolongate(sub, v0, 2), vf);
  problem.synchronize(1.5, uf, vf);
  for (int l = 0; l < 2; ++l) {
    std::vector<double> u, v;
    levels.layout(l).gather_natural(problem.state(l), u);
    levels.layout(l).gather_natural(problem.velocity(l), v);
    const auto ue = prolongate(sub, u0, l), ve = prolongate(sub, v0, l);
    for (size_t i = 0; i < u.size(); ++i) {
      ASSERT_NEAR(u[i], ue[i], 1e-14) << "level " << l;
      ASSERT_NEAR(v[i], ve[i], 1e-14) << "level " << l;
    }
    // Inertia vanishes at the predictor û_l = u_l + dt v_l of the level.
    Vec p;
    VecDuplicate(problem.state(l), &p);
    VecWAXPY(p, scene.time.dt, problem.velocity(l), problem.state(l));
    std::vector<double> energies;
    problem.level(l).term_energies(p, energies);
    EXPECT_NEAR(energies[1], 0.0, 1e-20) << "level " << l;
    VecDestroy(&p);
  }
  VecDestroy(&uf);
  VecDestroy(&vf);
}
