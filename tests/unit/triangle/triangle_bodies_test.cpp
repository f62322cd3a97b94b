// Several bodies in one scene (triangle_bodies.hpp): each body's mesh in place with its groups,
// its own material in the elastic energy and in gravity, clamps of one body only, and
// self-contact switched per body while pairs between bodies always count.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mlshell/contact/contact_term.hpp"
#include "mlshell/effects.hpp"
#include "triangle_fixtures.hpp"

using namespace mlshell;

namespace {

// A 2 m × 1 m sheet (E = 1 MPa, τ = 1 cm, 500 kg/m³) and a body "upper", the same rectangle
// 1 m above with E = 3 MPa, τ = 2 cm, 800 kg/m³.
std::string two_sheets(const std::string& effects) {
  return "geometry: {mesh: {generator: rectangle, size: [2, 1], edge_length: 0.25}}\n"
         "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, "
         "thickness: 0.01, volume_density: 500}\n"
         "bodies:\n"
         "  - name: upper\n"
         "    mesh: {generator: rectangle, size: [2, 1], faces: [6, 3]}\n"
         "    translate: [0, 0, 1]\n"
         "    material: {model: neo-hookean, youngs_modulus: 3.0e6, poisson_ratio: 0.3, "
         "thickness: 0.02, volume_density: 800}\n" +
         effects + "time: {dt: 1, steps: 1, integrator: quasistatic}\n";
}

}  // namespace

TEST(TriangleBodies, EachBodyIsInPlaceWithItsGroups) {
  const Scene scene = triangle_scene("bodies_groups", two_sheets(""));
  const TriangleMesh mesh = build_scene_mesh(scene);
  const TriangleMesh first = build_triangle_mesh(*scene.geometry.mesh);
  ASSERT_EQ(mesh.groups.at("upper").size(), 28u);  // 7 × 4 vertices
  EXPECT_EQ(mesh.num_points(), first.num_points() + 28);
  EXPECT_EQ(mesh.num_triangles(), first.num_triangles() + 36);
  for (int v : mesh.groups.at("upper")) EXPECT_EQ(mesh.points[v].z(), 1.0);
  EXPECT_EQ(mesh.groups.at("upper/left").size(), 4u);
  EXPECT_EQ(mesh.groups.at("left"), first.groups.at("left"));  // the first body's, unprefixed
  for (int v : mesh.groups.at("upper/left")) EXPECT_EQ(mesh.points[v].x(), 0.0);
  const TriangleBodies bodies = TriangleBodies::of(scene, mesh);
  EXPECT_EQ(bodies.size(), 2);
  EXPECT_EQ(bodies.of_face.back(), 1);
  EXPECT_EQ(bodies.of_face.front(), 0);
}

// The membrane energy of a uniform stretch (s1, s2) is τ A ψ per body, each with its own E and τ;
// gravity pulls each body with its own ρτ A g.
TEST(TriangleBodies, EachBodyHasItsOwnMaterial) {
  const Scene scene = triangle_scene("bodies_material", two_sheets("effects: [gravity]\n"));
  TriangleProblem tp(scene, PETSC_COMM_SELF);
  const double s1 = 1.2, s2 = 0.9;
  const int n = tp.disc().num_points();
  std::vector<double> u(3 * n, 0.0);
  for (int i = 0; i < n; ++i) {
    u[3 * i] = (s1 - 1.0) * tp.disc().points()[i][0];
    u[3 * i + 1] = (s2 - 1.0) * tp.disc().points()[i][1];
  }
  const double nu = 0.3, J = s1 * s2, area = 2.0;
  const auto psi = [&](double E) {
    const double mu = E / (2 * (1 + nu)), lambda = E * nu / (1 - nu * nu);  // plane stress
    return mu / 2 * (s1 * s1 + s2 * s2 - 2 - 2 * std::log(J)) +
           lambda / 2 * std::log(J) * std::log(J);
  };
  const double expected = 0.01 * area * psi(1.0e6) + 0.02 * area * psi(3.0e6);
  CompensatedSum e;
  PetscCallAbort(PETSC_COMM_SELF, tp.problem->terms()[0]->add(u, e, nullptr, nullptr));
  EXPECT_NEAR(e.value(), expected, 1e-10 * expected);
  // Gravity: −∇E = f, Σ f_z = −g (ρ₁τ₁ + ρ₂τ₂) A.
  const EnergyTerm* gravity = tp.problem->find_term("gravity");
  ASSERT_NE(gravity, nullptr);
  std::vector<double> g(3 * n, 0.0);
  CompensatedSum ignored;
  PetscCallAbort(PETSC_COMM_SELF, gravity->add(std::vector<double>(3 * n, 0.0), ignored, &g, nullptr));
  double fz = 0.0;
  for (int i = 0; i < n; ++i) fz -= g[3 * i + 2];
  const double weight = -9.81 * (500 * 0.01 + 800 * 0.02) * area;
  EXPECT_NEAR(fz, weight, 1e-12 * std::abs(weight));
}

TEST(TriangleBodies, AClampHoldsOneBodyAndNamesClashAreRefused) {
  const Scene spans =
      triangle_scene("bodies_clamp", two_sheets("effects:\n  - clamp: {where: {box: {min: [-1, -1, "
                                                "-1], max: [0.01, 2, 2]}}}\n"));
  try {
    TriangleProblem tp(spans, PETSC_COMM_SELF);
    ADD_FAILURE() << "a clamp over two bodies was accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("a clamp holds the edges of one body"), std::string::npos) << what;
    EXPECT_NE(what.find("'upper'"), std::string::npos) << what;
  }
  std::string clash = two_sheets("");
  clash.replace(clash.find("name: upper"), 11, "name: left");  // a side group of the first mesh
  const Scene named = triangle_scene("bodies_clash", clash);
  try {
    build_scene_mesh(named);
    ADD_FAILURE() << "a body named like a group of geometry.mesh was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("bodies[0].name: 'left' is a group of geometry.mesh"),
              std::string::npos)
        << e.what();
  }
}

// Self-contact per body at rest: the barrier reaches 1.1 m, so each sheet's own non-adjacent
// primitives and the two sheets 1 m apart all interact. With S a sheet's pairs with itself and
// B the pairs between the sheets: both off gives B, the first on B + S₁, both on B + S₁ + S₂.
TEST(TriangleBodies, SelfContactIsPerBodyAndPairsBetweenBodiesAlwaysCount) {
  const auto active = [](const std::string& self, const std::string& upper_self) {
    std::string yaml = two_sheets("effects:\n  - contact: {thickness: 0.01, gap: 1.1, stiffness: "
                                  "10, self: " + self + "}\n");
    if (!upper_self.empty())
      yaml.replace(yaml.find("    translate"), 0, "    self_contact: " + upper_self + "\n");
    const Scene scene = triangle_scene("bodies_self", yaml);
    TriangleProblem tp(scene, PETSC_COMM_SELF);
    Vec u;
    tp.layout().create_vector(&u);
    double f;
    tp.problem->objective(u, &f, nullptr);
    ContactStatistics stats;
    tp.problem->find_term<ContactTerm>()->statistics(&stats);
    VecDestroy(&u);
    return stats.active;
  };
  const long between = active("false", "");
  const long first_self = active("true", "false") - between;
  const long upper_self = active("false", "true") - between;
  EXPECT_GT(between, 100);
  EXPECT_GT(first_self, 100);
  EXPECT_GT(upper_self, 10);
  EXPECT_EQ(active("true", ""), between + first_self + upper_self);
}
