// Triangle shells on 1 and 2 ranks give the same answer to round-off (run under mpiexec -n 2,
// ctest mpi.two_ranks): energy, gradient and Hessian of every effect (hinge and midedge
// bending), the per-face output
// fields, and a quasistatic solve's final state, compared in natural order with the same problem
// built on PETSC_COMM_SELF on each rank.
#include <cmath>

#include "triangle_fixtures.hpp"

using namespace mlshell;

namespace {

struct Evaluation {
  double f = 0.0;
  std::vector<double> gradient, hessian_action;  // natural order, on rank 0
  std::vector<std::pair<std::string, std::vector<double>>> fields;
};

Evaluation evaluate(TriangleProblem& tp) {
  const ParallelLayout& layout = tp.layout();
  const int n = 3 * tp.disc().num_points();
  std::vector<double> un(n), dn(n);  // the same natural-order vectors on every rank count
  for (int i = 0; i < n; ++i) {
    un[i] = 1e-2 * std::sin(0.7 * i + 0.3);
    dn[i] = std::cos(1.3 * i);
  }
  Vec u, g, d, Hd;
  layout.create_vector(&u);
  VecDuplicate(u, &g);
  VecDuplicate(u, &d);
  VecDuplicate(u, &Hd);
  layout.scatter_natural(layout.rank() == 0 ? un : std::vector<double>{}, u);
  layout.scatter_natural(layout.rank() == 0 ? dn : std::vector<double>{}, d);
  Evaluation e;
  tp.problem->objective(u, &e.f, g);
  Mat H;
  tp.problem->create_matrix(&H);
  tp.problem->hessian(u, H);
  MatMult(H, d, Hd);
  layout.gather_natural(g, e.gradient);
  layout.gather_natural(Hd, e.hessian_action);
  tp.problem->face_fields(u, tp.disc().num_faces(), e.fields);
  MatDestroy(&H);
  for (Vec* v : {&u, &g, &d, &Hd}) VecDestroy(v);
  return e;
}

const char* kScene =
    "geometry: {mesh: {generator: rectangle, size: [1, 1], edge_length: 0.1}}\n"
    "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: 0.01, "
    "volume_density: 500}\n"
    "effects:\n"
    "  - inertia\n"
    "  - gravity\n"
    "  - line_load: {where: boundary(right), force_per_length: [0, 0, 1]}\n"
    "  - point_load: {where: corner(top-right), force: [1, 0, 0]}\n"
    "  - dirichlet: {where: boundary(left), motion: {translate: [0, 0, 0.1], over: [0, 1]}}\n"
    "  - clamp: {where: boundary(bottom)}\n"
    "time: {dt: 0.5, steps: 2}\n";

}  // namespace

TEST(MpiTriangleShell, EnergyGradientHessianAndFieldsAgreeWithOneRank) {
  int size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  ASSERT_GE(size, 2) << "run under mpiexec -n 2";
  for (const char* yaml :
       {kScene,
        // Midedge bending with clamps on two sides (a corner triangle with two held edges).
        "geometry: {mesh: {generator: rectangle, size: [1, 1], edge_length: 0.1}}\n"
        "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, "
        "thickness: 0.01, volume_density: 500, bending: midedge}\n"
        "effects:\n  - gravity\n  - clamp: {where: boundary(bottom), motion: {translate: "
        "[0, 0, 0.1], over: [0, 1]}}\n  - clamp: {where: boundary(left)}\n"
        "time: {dt: 0.5, steps: 2}\n",
        "geometry: {mesh: {generator: sphere, radius: 1, subdivisions: 2}}\n"
        "material: {model: st-venant-kirchhoff, youngs_modulus: 1.0e6, poisson_ratio: 0.3, "
        "thickness: 0.01, volume_density: 500}\n"
        "effects:\n  - pressure: {pressure: 100}\n"
        "time: {dt: 1, steps: 1, integrator: quasistatic}\n"}) {
    const Scene scene = triangle_scene("mpi", yaml);
    TriangleProblem distributed(scene, PETSC_COMM_WORLD), serial(scene, PETSC_COMM_SELF);
    ASSERT_GT(distributed.layout().local_elements().size(), 0u);
    ASSERT_LT(distributed.layout().local_elements().size(), distributed.disc().elements().size());
    const Evaluation a = evaluate(distributed), b = evaluate(serial);
    EXPECT_NEAR(a.f, b.f, 1e-12 * std::abs(b.f));
    if (distributed.layout().rank() == 0) {
      EXPECT_LT(relative_difference(a.gradient, b.gradient), 1e-11);
      EXPECT_LT(relative_difference(a.hessian_action, b.hessian_action), 1e-11);
      ASSERT_EQ(a.fields.size(), b.fields.size());
      ASSERT_EQ(a.fields.size(), 2u);
      for (size_t k = 0; k < a.fields.size(); ++k)
        EXPECT_LT(relative_difference(a.fields[k].second, b.fields[k].second), 1e-11)
            << a.fields[k].first;
    }
  }
}

TEST(MpiTriangleShell, QuasistaticStateAgreesWithOneRank) {
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const auto dir = std::filesystem::temp_directory_path() / "mlshell_triangle_mpi";
  const Scene scene = triangle_scene(
      "mpi_solve",
      "geometry: {mesh: {generator: dome, radius: 1, opening_angle: 1.0, rings: 6}}\n"
      "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: "
      "0.01, volume_density: 500}\n"
      "effects:\n  - dirichlet: {where: boundary}\n"
      "  - point_load: {where: {at: [0, 0, 1]}, force: [0, 0, -5], ramp: true}\n"
      "time: {dt: 1, steps: 2, integrator: quasistatic}\n");
  const SolvedScene parallel = solve_scene(scene, PETSC_COMM_WORLD, (dir / "parallel").string());
  const SolvedScene serial =
      solve_scene(scene, PETSC_COMM_SELF, (dir / ("serial" + std::to_string(rank))).string());
  if (rank == 0) {
    EXPECT_EQ(parallel.status, 0);
    EXPECT_EQ(serial.status, 0);
    ASSERT_EQ(parallel.displacement.size(), serial.displacement.size());
    EXPECT_LT(relative_difference(parallel.displacement, serial.displacement), 1e-6);
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  if (rank == 0) std::filesystem::remove_all(dir);
}
