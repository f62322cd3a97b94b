// Triangle-shell scenes for tests: a scene file written from YAML text, parsed, and run or
// assembled on the finest (only) level.
#pragma once

#include <gtest/gtest.h>
#include <petscsys.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "mlshell/scene.hpp"
#include "mlshell/triangle/triangle_bodies.hpp"
#include "mlshell/triangle/triangle_effect_builder.hpp"
#include "mlshell/triangle/triangle_generators.hpp"
#include "mlshell/triangle/triangle_levels.hpp"
#include "physics_fixtures.hpp"

namespace mlshell {

/// Parses a scene from YAML text (written to a temporary file named after `name` and the
/// process, so that the ranks of an MPI test do not share it).
inline Scene triangle_scene(const std::string& name, const std::string& yaml) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("mlshell_" + name + "_" + std::to_string(getpid()) + ".yaml");
  std::ofstream(file) << yaml;
  Scene scene = parse_scene(file);
  std::filesystem::remove(file);
  return scene;
}

/// Writes make_sphere(radius, subdivisions) moved by `offset` as an OBJ file (its faces turned
/// inside out if `inward`) under the temporary folder, named after `name` and the process.
inline std::filesystem::path write_sphere_obj(const std::string& name, double radius,
                                              int subdivisions, const Point3& offset, bool inward) {
  const TriangleMesh sphere = make_sphere(radius, subdivisions);
  const auto file = std::filesystem::temp_directory_path() /
                    ("mlshell_" + name + "_" + std::to_string(getpid()) + ".obj");
  std::ofstream out(file);
  out.precision(17);
  for (const Point3& x : sphere.points) {
    const Point3 y = x + offset;
    out << "v " << y[0] << ' ' << y[1] << ' ' << y[2] << '\n';
  }
  for (const Triangle& t : sphere.triangles)
    out << "f " << t[0] + 1 << ' ' << (inward ? t[2] : t[1]) + 1 << ' '
        << (inward ? t[1] : t[2]) + 1 << '\n';
  return file;
}

/// The scene's problem on its triangle mesh, on `comm`.
struct TriangleProblem {
  std::unique_ptr<TriangleLevels> levels;
  std::unique_ptr<LevelProblem> problem;
  TriangleProblem(const Scene& scene, MPI_Comm comm) {
    levels = std::make_unique<TriangleLevels>(comm, build_scene_mesh(scene));
    problem = build_triangle_problem(scene, levels->discretization(0), levels->layout(0),
                                     CageFrame::from(scene.geometry));
    problem->begin_step(scene.time.dt, nullptr);
  }
  const TriangleDiscretization& disc() const { return levels->discretization(0); }
  const ParallelLayout& layout() const { return levels->layout(0); }
};

}  // namespace mlshell
