// RMTR (TAO type "rmtr") on decimation hierarchies of triangle shells, beyond both papers: on 2
// and 3 levels, quasistatic and dynamic (implicit Euler), it reaches the single-level trust
// region's minimiser with the theory's invariants
// (4.5) and (4.7), with each coarse model and with vertex-patch smoothers that factorise only on
// the coarsest level; and 1 and 2 ranks agree (MpiTriangleRmtr.*, ctest mpi.two_ranks).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "mlshell/step_solver.hpp"
#include "solvers/solver_test_support.hpp"
#include "triangle/triangle_fixtures.hpp"

using namespace mlshell;

namespace {

const char* kMaterial =
    "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: 0.01, "
    "volume_density: 500}\n";

/// A dome (529 vertices) pressed at its apex over two quasistatic steps: a nonlinear shell.
Scene pressed_dome() {
  return triangle_scene(
      "rmtr_dome",
      std::string("geometry:\n  hierarchy: {levels: 3, ratio: 4}\n"
                  "  mesh: {generator: dome, radius: 1, opening_angle: 1.0, rings: 12}\n") +
          kMaterial +
          "effects:\n  - dirichlet: {where: boundary}\n"
          "  - point_load: {where: {at: [0, 0, 1]}, force: [0, 0, -20], ramp: true}\n"
          "time: {dt: 1, steps: 2, integrator: quasistatic}\n");
}

/// An unstructured, embossed square (about 700 vertices) clamped on its left side and sagging
/// under gravity and a load on its right side: rest-shape detail the coarse levels cannot hold.
Scene embossed_cantilever() {
  return triangle_scene(
      "rmtr_embossed",
      std::string("geometry:\n  hierarchy: {levels: 3, ratio: 4}\n"
                  "  mesh: {generator: rectangle, size: [1, 1], edge_length: 0.045, relief: "
                  "{amplitude: 0.05, bumps: [2, 2]}}\n") +
          kMaterial +
          "effects:\n  - clamp: {where: boundary(left)}\n  - gravity: [0, 0, -9.81]\n"
          "  - line_load: {where: boundary(right), force_per_length: [0, 0, -2]}\n"
          "time: {dt: 1, steps: 1, integrator: quasistatic}\n");
}

/// A sheet hanging from two corners and falling under gravity, by implicit Euler (dynamic).
Scene falling_sheet() {
  return triangle_scene(
      "rmtr_falling",
      std::string("geometry:\n  hierarchy: {levels: 3, ratio: 4}\n"
                  "  mesh: {generator: rectangle, size: [1, 1], edge_length: 0.05}\n") +
          kMaterial +
          "effects:\n  - inertia\n  - gravity: [0, 0, -9.81]\n"
          "  - dirichlet: {where: corner(top-left)}\n  - dirichlet: {where: corner(top-right)}\n"
          "time: {dt: 0.02, steps: 2}\n");
}

struct Outcome {
  int status = -1;
  double energy = 0.0;
  std::vector<double> u;
  RmtrStatistics rmtr;
};

Outcome solve(const Scene& scene, MPI_Comm comm, const std::string& tag) {
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const auto dir = std::filesystem::temp_directory_path() /
                   ("mlshell_triangle_rmtr_" + tag + "_" + std::to_string(rank));
  SolvedScene solved = solve_scene(scene, comm, dir);
  Outcome out;
  out.status = solved.status;
  out.u = solved.displacement;
  out.rmtr = solved.simulation->rmtr_totals();
  solved.simulation->problem().objective(solved.simulation->displacement(), &out.energy, nullptr);
  std::filesystem::remove_all(dir);
  return out;
}

}  // namespace

TEST(TriangleRmtr, TwoAndThreeLevelsReachTheMinimiserOfTheSingleLevelTrustRegion) {
  // mlshell's default RMTR (Dogleg on inexact Newton points from patch-preconditioned CG,
  // Galerkin models, subspace steps), and STCG smoothing on vertex patches with first-order
  // coarse models built from each level's own mesh.
  for (const char* smoother : {"default", "stcg-vpatch-first-order"})
    for (const Scene& scene : {pressed_dome(), embossed_cantilever(), falling_sheet()}) {
      const bool stcg = std::string(smoother) != "default";
      ScopedOptions smoothing(
          stcg ? std::initializer_list<std::pair<const char*, const char*>>{
                     {"-tao_rmtr_smoother_qp", "stcg"},
                     {"-tao_rmtr_smoother_pc", "vpatch"},
                     {"-tao_rmtr_coarse_model", "first_order"},
                     {"-tao_rmtr_subspace", "0"}}
               : std::initializer_list<std::pair<const char*, const char*>>{});
      Outcome tr;
      {
        ScopedOptions o({{"-tao_type", "tr"}});
        tr = solve(scene, PETSC_COMM_SELF, "tr");
      }
      ASSERT_EQ(tr.status, 0) << scene.name;
      for (const char* levels : {"2", "3"}) {
        ScopedOptions o({{"-tao_type", "rmtr"},
                         {"-tao_rmtr_levels", levels},
                         {"-tao_rmtr_check_consistency", "1"}});
        const Outcome rmtr = solve(scene, PETSC_COMM_SELF, std::string("rmtr") + levels);
        const std::string what = std::string(smoother) + " " + scene.name + " " + levels;
        ASSERT_EQ(rmtr.status, 0) << what;
        ASSERT_EQ(rmtr.rmtr.levels.size(), static_cast<size_t>(std::stoi(levels))) << what;
        EXPECT_NEAR(rmtr.energy, tr.energy, 1e-10 * std::abs(tr.energy)) << what;
        EXPECT_LT(max_difference(rmtr.u, tr.u), 1e-6 * max_abs(tr.u)) << what;
        EXPECT_LE(rmtr.rmtr.max_correction_ratio, 1.0 + 1e-12) << what;  // eq. (4.7)
        EXPECT_LT(rmtr.rmtr.max_consistency_error, 1e-8) << what;        // eq. (4.5)
        const auto& done = rmtr.rmtr.levels;
        EXPECT_GT(done.front().factorisations, 0) << what;
        long coarse_accepted = 0;
        for (size_t l = 1; l < done.size(); ++l) {
          EXPECT_EQ(done[l].factorisations, 0) << what << ", level " << l;
          coarse_accepted += done[l].coarse_accepted;
        }
        EXPECT_GT(coarse_accepted, 0) << what << ": no coarse correction was ever accepted";
      }
    }
}

TEST(MpiTriangleRmtr, TwoRanksReachTheStateOfOne) {
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  ScopedOptions o({{"-tao_type", "rmtr"}});
  const Scene scene = pressed_dome();
  const Outcome parallel = solve(scene, PETSC_COMM_WORLD, "parallel");
  const Outcome serial = solve(scene, PETSC_COMM_SELF, "serial");
  EXPECT_EQ(parallel.status, 0);
  EXPECT_EQ(serial.status, 0);
  ASSERT_EQ(parallel.rmtr.levels.size(), 3u);
  for (size_t l = 0; l < 3; ++l)
    EXPECT_EQ(parallel.rmtr.levels[l].dofs, serial.rmtr.levels[l].dofs) << "level " << l;
  EXPECT_NEAR(parallel.energy, serial.energy, 1e-10 * std::abs(serial.energy));
  if (rank == 0) {
    ASSERT_EQ(parallel.u.size(), serial.u.size());
    EXPECT_LT(relative_difference(parallel.u, serial.u), 1e-6);
  }
}
