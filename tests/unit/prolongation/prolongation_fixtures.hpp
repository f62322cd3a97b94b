// Coarse/fine triangle-mesh pairs for the shell prolongation's tests, without decimation: the
// fine mesh splits every coarse triangle into four at its edge midpoints, so the embedding is
// exact (a midpoint has weights ½, ½, 0 in a triangle of its edge; a coarse vertex survives as
// the fine vertex of the same index, weight 1 on itself). The fine rest points are then moved
// off the coarse surface by `place` (e.g. midpoints pushed onto a sphere), so the offsets
// (γ, t) are not zero.
#pragma once

#include <algorithm>
#include <functional>
#include <map>
#include <utility>
#include <vector>

#include "mlshell/prolongation/shell_prolongation.hpp"
#include "mlshell/triangle/triangle_generators.hpp"

namespace mlshell {

struct RefinedPair {
  TriangleMesh coarse, fine;
  std::vector<EmbeddedPoint> embedding;  ///< per fine vertex, in the coarse mesh
  std::vector<int> coarse_to_fine;       ///< coarse vertex k survives as fine vertex k
};

/// `place(i, p, is_midpoint)`: the fine rest point of fine vertex i, given its place p on the
/// coarse surface (the coarse vertex or the edge's midpoint).
inline RefinedPair split_one_to_four(
    const TriangleMesh& coarse, const std::function<Point3(int, const Point3&, bool)>& place = {}) {
  RefinedPair pair;
  pair.coarse = coarse;
  const int nc = coarse.num_points();
  std::vector<Point3> points(coarse.points);
  pair.embedding.resize(nc);
  for (int t = 0; t < coarse.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      EmbeddedPoint& e = pair.embedding[coarse.triangles[t][k]];
      if (e.triangle >= 0) continue;
      e.triangle = t;
      e.weights = Eigen::Vector3d::Zero();
      e.weights[k] = 1.0;
    }
  std::map<std::pair<int, int>, int> midpoint;
  auto middle = [&](int t, int k) {
    const int a = coarse.triangles[t][k], b = coarse.triangles[t][(k + 1) % 3];
    const auto key = std::minmax(a, b);
    auto [it, added] = midpoint.emplace(key, static_cast<int>(points.size()));
    if (added) {
      points.push_back(0.5 * (coarse.points[a] + coarse.points[b]));
      EmbeddedPoint e;
      e.triangle = t;
      e.weights[k] = 0.5;
      e.weights[(k + 1) % 3] = 0.5;
      pair.embedding.push_back(e);
    }
    return it->second;
  };
  for (int t = 0; t < coarse.num_triangles(); ++t) {
    const Triangle& c = coarse.triangles[t];
    const int m01 = middle(t, 0), m12 = middle(t, 1), m20 = middle(t, 2);
    pair.fine.triangles.push_back({c[0], m01, m20});
    pair.fine.triangles.push_back({m01, c[1], m12});
    pair.fine.triangles.push_back({m20, m12, c[2]});
    pair.fine.triangles.push_back({m01, m12, m20});
  }
  if (place)
    for (int i = 0; i < static_cast<int>(points.size()); ++i)
      points[i] = place(i, points[i], i >= nc);
  pair.fine.points = std::move(points);
  pair.coarse_to_fine.resize(nc);
  for (int k = 0; k < nc; ++k) pair.coarse_to_fine[k] = k;
  return pair;
}

/// The same pair with the fine vertices numbered backwards, so that a survivor's fine index is
/// not its coarse one.
inline RefinedPair with_fine_numbering_reversed(RefinedPair pair) {
  const int nf = pair.fine.num_points();
  auto flip = [nf](int i) { return nf - 1 - i; };
  std::reverse(pair.fine.points.begin(), pair.fine.points.end());
  std::reverse(pair.embedding.begin(), pair.embedding.end());
  for (Triangle& t : pair.fine.triangles)
    for (int& v : t) v = flip(v);
  for (int& m : pair.coarse_to_fine) m = flip(m);
  return pair;
}

inline double bounding_box_diagonal(const std::vector<Point3>& points) {
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const Point3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

/// An icosphere of radius 1 split once more, the midpoints pushed onto the sphere; survivors
/// stay (`move_survivors`: they move outwards by 2 % of the radius, a rest place that moved).
inline RefinedPair sphere_pair(int subdivisions, bool move_survivors = false) {
  return split_one_to_four(make_sphere(1.0, subdivisions),
                           [move_survivors](int, const Point3& p, bool mid) -> Point3 {
                             if (mid) return p.normalized();
                             return move_survivors ? Point3(1.02 * p) : p;
                           });
}

/// A dome (spherical cap of radius 1, opening 1 rad), midpoints onto the sphere.
inline RefinedPair dome_pair() {
  return split_one_to_four(make_spherical_cap(1.0, 1.0, 4),
                           [](int, const Point3& p, bool mid) { return mid ? p.normalized() : p; });
}

/// An unstructured unit square, its interior vertices perturbed in the plane, then split; the
/// midpoints get a wave out of the plane and a shift in it.
inline RefinedPair wavy_plate_pair(double edge_length = 0.25) {
  TriangleMesh coarse = make_unstructured_rectangle(1.0, 1.0, edge_length);
  for (Point3& p : coarse.points)
    if (p.x() > 1e-9 && p.x() < 1.0 - 1e-9 && p.y() > 1e-9 && p.y() < 1.0 - 1e-9)
      p += 0.15 * edge_length * Point3(std::sin(17.0 * p.y()), std::cos(13.0 * p.x()), 0.0);
  return split_one_to_four(coarse, [](int, const Point3& p, bool mid) -> Point3 {
    if (!mid) return p;
    return p + Point3(0.01 * std::sin(9.0 * p.y()), 0.01 * std::cos(7.0 * p.x()),
                      0.05 * std::sin(5.0 * p.x()) * std::cos(4.0 * p.y()));
  });
}

inline ShellProlongation make_prolongation(const RefinedPair& pair) {
  return ShellProlongation(pair.coarse, pair.fine.points, pair.embedding);
}

}  // namespace mlshell
