// Triangle shells on 1 and 2 ranks give the same answer to round-off (run under mpiexec -n 2,
// ctest mpi.two_ranks): energy, gradient and Hessian of every effect (hinge and midedge
// bending; exact and PSD-projected Hessians), the per-face output fields, the pressure's enclosed
// volume (and its refusal of an inward surface), and a quasistatic solve's final
// state, compared in natural order with the same problem built on PETSC_COMM_SELF on each rank.
#include <cmath>

#include "mlshell/contact/contact_term.hpp"
#include "mlshell/triangle/triangle_effects.hpp"
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
    "  - dirichlet: {where: boundary(left), motion: {translate: [0, 0, 0.1], rotate: {axis: "
    "[1, 0, 0], center: [0, 0.5, 0], angle: 0.5}, over: [0, 1]}}\n"
    "  - clamp: {where: boundary(bottom)}\n"
    "time: {dt: 0.5, steps: 2}\n";

}  // namespace

TEST(MpiTriangleShell, EnergyGradientHessianAndFieldsAgreeWithOneRank) {
  int size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  ASSERT_GE(size, 2) << "run under mpiexec -n 2";
  for (const char* yaml :
       {kScene,
        // Midedge bending with clamps on two sides (a corner triangle with two held edges), one
        // of them turning.
        "geometry: {mesh: {generator: rectangle, size: [1, 1], edge_length: 0.1}}\n"
        "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, "
        "thickness: 0.01, volume_density: 500, bending: midedge}\n"
        "effects:\n  - gravity\n  - clamp: {where: boundary(bottom), motion: {translate: "
        "[0, 0, 0.1], over: [0, 1]}}\n  - clamp: {where: boundary(left), motion: {rotate: "
        "{axis: [0, 1, 0.5], center: [0, 0.5, 0], angle: 0.7}, over: [0, 2]}}\n"
        "time: {dt: 0.5, steps: 2}\n",
        "geometry: {mesh: {generator: sphere, radius: 1, subdivisions: 2}}\n"
        "material: {model: st-venant-kirchhoff, youngs_modulus: 1.0e6, poisson_ratio: 0.3, "
        "thickness: 0.01, volume_density: 500}\n"
        "effects:\n  - pressure: {pressure: 100}\n"
        "time: {dt: 1, steps: 1, integrator: quasistatic}\n",
        // Contact: a plane collider within reach of every vertex, and self-contact pairs
        // across the ranks' halo (contact_term.hpp).
        "geometry: {mesh: {generator: rectangle, size: [0.5, 0.5], edge_length: 0.05}}\n"
        "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, "
        "thickness: 0.01, volume_density: 500}\n"
        "effects:\n  - gravity\n  - contact: {thickness: 0.005, gap: 0.06}\n"
        "  - collider: {plane: {point: [0, 0, -0.04], normal: [0, 0, 1], side: 1.0}}\n"
        "time: {dt: 1, steps: 1, integrator: quasistatic}\n"}) {
    const Scene scene = triangle_scene("mpi", yaml);
    TriangleProblem distributed(scene, PETSC_COMM_WORLD), serial(scene, PETSC_COMM_SELF);
    ASSERT_GT(distributed.layout().local_elements().size(), 0u);
    ASSERT_LT(distributed.layout().local_elements().size(), distributed.disc().elements().size());
    // Exact Hessians, and those of projected Newton (-mlshell_hessian_psd).
    for (const bool project : {false, true}) {
      for (TriangleProblem* tp : {&distributed, &serial})
        for (const auto& t : tp->problem->terms()) t->set_hessian_projection(project);
      const Evaluation a = evaluate(distributed), b = evaluate(serial);
      EXPECT_NEAR(a.f, b.f, 1e-12 * std::abs(b.f));
      if (const auto* contact = distributed.problem->find_term<ContactTerm>()) {
        // The same pairs, as global primitives, found with a halo of the other rank's surface.
        ContactStatistics sa, sb;
        contact->statistics(&sa);
        serial.problem->find_term<ContactTerm>()->statistics(&sb);
        EXPECT_EQ(sa.candidates, sb.candidates);
        EXPECT_EQ(sa.active, sb.active);
        EXPECT_GT(sa.active, 1000);
        EXPECT_GT(sa.halo_points, 0);
        EXPECT_EQ(sb.halo_points, 0);
      }
      if (distributed.layout().rank() == 0) {
        EXPECT_LT(relative_difference(a.gradient, b.gradient), 1e-11);
        EXPECT_LT(relative_difference(a.hessian_action, b.hessian_action), 1e-11) << project;
        ASSERT_EQ(a.fields.size(), b.fields.size());
        ASSERT_EQ(a.fields.size(), 2u);
        for (size_t k = 0; k < a.fields.size(); ++k)
          EXPECT_LT(relative_difference(a.fields[k].second, b.fields[k].second), 1e-11)
              << a.fields[k].first;
      }
    }
  }
}

// The pressure's V(X) is a sum over the ranks: the same as on one rank, and an
// inward surface is refused on every rank with the same message.
TEST(MpiTriangleShell, PressureVolumeAndOrientationAgreeWithOneRank) {
  const char* material =
      "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: "
      "0.01, volume_density: 500}\n"
      "effects:\n  - pressure: {pressure: 100}\ntime: {dt: 1, steps: 1}\n";
  for (const bool inward : {false, true}) {
    const auto obj = write_sphere_obj("mpi_sphere", 1.0, 2, Point3(2.0, 1.0, -1.0), inward);
    const Scene scene = triangle_scene(
        "mpi_pressure", "geometry: {mesh: {obj: " + obj.string() + "}}\n" + material);
    std::string messages[2];
    const PressureTerm* terms[2] = {nullptr, nullptr};
    std::unique_ptr<TriangleProblem> problems[2];
    const MPI_Comm comms[2] = {PETSC_COMM_WORLD, PETSC_COMM_SELF};
    for (int k = 0; k < 2; ++k) {
      try {
        problems[k] = std::make_unique<TriangleProblem>(scene, comms[k]);
        terms[k] = dynamic_cast<const PressureTerm*>(problems[k]->problem->terms()[1].get());
      } catch (const SceneError& e) {
        // The scene file's name differs between the ranks: compare what follows it.
        messages[k] = std::string(e.what()).substr(scene.file.string().size());
      }
    }
    std::filesystem::remove(obj);
    if (inward) {
      EXPECT_NE(messages[0].find(": effects[0].pressure: "), std::string::npos) << messages[0];
      EXPECT_NE(messages[0].find("oriented inwards"), std::string::npos) << messages[0];
      EXPECT_EQ(messages[0], messages[1]);
    } else {
      ASSERT_TRUE(terms[0] && terms[1]) << messages[0] << messages[1];
      ASSERT_LT(problems[0]->layout().local_elements().size(),
                static_cast<size_t>(problems[0]->disc().num_faces()));
      EXPECT_GT(terms[0]->enclosed_volume(), 0.0);
      EXPECT_NEAR(terms[0]->enclosed_volume(), terms[1]->enclosed_volume(),
                  1e-13 * terms[1]->enclosed_volume());
    }
  }
}

namespace {

/// The scene `yaml` solved on PETSC_COMM_WORLD ends where each rank's own serial solve ends.
void expect_the_state_of_one_rank(const std::string& name, const std::string& yaml) {
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const auto dir = std::filesystem::temp_directory_path() / ("mlshell_triangle_" + name);
  const Scene scene = triangle_scene(name, yaml);
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

}  // namespace

TEST(MpiTriangleShell, QuasistaticStateAgreesWithOneRank) {
  expect_the_state_of_one_rank(
      "mpi_solve",
      "geometry: {mesh: {generator: dome, radius: 1, opening_angle: 1.0, rings: 6}}\n"
      "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: "
      "0.01, volume_density: 500}\n"
      "effects:\n  - dirichlet: {where: boundary}\n"
      "  - point_load: {where: {at: [0, 0, 1]}, force: [0, 0, -5], ramp: true}\n"
      "time: {dt: 1, steps: 2, integrator: quasistatic}\n");
}

// A strip twisted by a quarter turn of its clamped right end (hinge bending), whose points a
// Dirichlet condition with the same motion holds to 1e-7 m in augmented-Lagrangian mode: the
// same final state on 1 and 2 ranks.
TEST(MpiTriangleShell, TwistedStripAgreesWithOneRank) {
  expect_the_state_of_one_rank(
      "mpi_twist",
      "geometry: {mesh: {generator: rectangle, size: [1, 0.2], faces: [12, 2]}}\n"
      "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: "
      "0.01, volume_density: 500}\n"
      "effects:\n  - clamp: {where: boundary(left)}\n"
      "  - clamp: {where: boundary(right), motion: {rotate: {axis: [1, 0, 0], center: [1, 0.1, "
      "0], angle: 1.5707963267948966}, over: [0, 1]}}\n"
      "  - dirichlet: {where: boundary(right), tolerance: 1e-7, motion: {rotate: {axis: [1, 0, "
      "0], center: [1, 0.1, 0], angle: 1.5707963267948966}, over: [0, 1]}}\n"
      "time: {dt: 1, steps: 1, integrator: quasistatic}\n");
}
