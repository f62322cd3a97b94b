// The grown boxes of a surface's primitives (broad_phase.hpp's file comment).
#include "primitive_boxes.hpp"

#include <cmath>
#include <limits>

namespace mlshell::contact_detail {

namespace {

/// The box of the given vertices at x0 and x1, grown by r and rounded outwards.
template <std::size_t N>
Box box_of(const std::array<int, N>& v, std::span<const Eigen::Vector3d> x0,
           std::span<const Eigen::Vector3d> x1, double r) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box b;
  for (int k = 0; k < 3; ++k) {
    double lo = inf, hi = -inf;
    for (const int i : v) {
      lo = std::min({lo, x0[i][k], x1[i][k]});
      hi = std::max({hi, x0[i][k], x1[i][k]});
    }
    b.lo[k] = std::nextafter(lo - r, -inf);
    b.hi[k] = std::nextafter(hi + r, inf);
  }
  return b;
}

}  // namespace

PrimitiveBoxes primitive_boxes(const ContactSurface& surface, std::span<const Eigen::Vector3d> x0,
                               std::span<const Eigen::Vector3d> x1, double distance) {
  const double r = 0.5 * distance;
  PrimitiveBoxes boxes;
  boxes.vertices.resize(surface.num_vertices);
  for (int v = 0; v < surface.num_vertices; ++v)
    boxes.vertices[v] = box_of(std::array<int, 1>{v}, x0, x1, r);
  boxes.edges.resize(surface.edges.size());
  for (std::size_t e = 0; e < surface.edges.size(); ++e)
    boxes.edges[e] = box_of(surface.edges[e], x0, x1, r);
  boxes.faces.resize(surface.faces.size());
  for (std::size_t f = 0; f < surface.faces.size(); ++f)
    boxes.faces[f] = box_of(surface.faces[f], x0, x1, r);
  return boxes;
}

}  // namespace mlshell::contact_detail
