// A broad-phase test scene (contact tests and tests/benchmarks/broad_phase_benchmark.cpp):
// `layers` unit squares of n × n cells (two triangles each) stacked `gap` apart in z, each
// rippled by amplitude·sin(2π(3x + k/3))·sin(2π·2y) with its own phase, so neighbouring layers
// come within gap − 2·amplitude of each other in places. One surface, layer k's vertices at
// k·(n + 1)².
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "mlshell/contact/broad_phase/contact_candidates.hpp"
#include "mlshell/triangle/triangle_generators.hpp"

namespace mlshell::test {

struct SheetScene {
  ContactSurface surface;
  std::vector<Eigen::Vector3d> x;
};

inline SheetScene stacked_sheets(int layers, int n, double gap, double amplitude) {
  const TriangleMesh sheet = make_triangle_rectangle(1.0, 1.0, n, n);
  SheetScene scene;
  std::vector<std::array<int, 3>> faces;
  const double two_pi = 2.0 * std::numbers::pi;
  for (int k = 0; k < layers; ++k) {
    const int offset = static_cast<int>(scene.x.size());
    for (const auto& p : sheet.points)
      scene.x.emplace_back(p.x(), p.y(),
                           k * gap + amplitude * std::sin(two_pi * (3.0 * p.x() + k / 3.0)) *
                                         std::sin(two_pi * 2.0 * p.y()));
    for (const auto& t : sheet.triangles)
      faces.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  scene.surface = ContactSurface::from_faces(static_cast<int>(scene.x.size()), std::move(faces));
  return scene;
}

}  // namespace mlshell::test
