// Collider surfaces (collider_meshes.hpp).
#include "mlshell/contact/collider_meshes.hpp"

#include <algorithm>
#include <cmath>

#include "mlshell/triangle/triangle_generators.hpp"

namespace mlshell {

namespace {

Point3 point(const Vec3& v) { return {v[0], v[1], v[2]}; }

/// A parallelogram o + s a + t b, s, t ∈ [0, 1], as an n_a × n_b grid of triangle pairs whose
/// normals point along a × b, appended to `mesh`.
void add_patch(TriangleMesh& mesh, const Point3& o, const Point3& a, const Point3& b, int na,
               int nb) {
  const int first = mesh.num_points();
  for (int j = 0; j <= nb; ++j)
    for (int i = 0; i <= na; ++i)
      mesh.points.push_back(o + a * (double(i) / na) + b * (double(j) / nb));
  auto id = [&](int i, int j) { return first + j * (na + 1) + i; };
  for (int j = 0; j < nb; ++j)
    for (int i = 0; i < na; ++i) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

int cells(double length, double edge_length, int most) {
  return std::clamp(static_cast<int>(std::ceil(length / (4.0 * edge_length))), 1, most);
}

}  // namespace

TriangleMesh make_collider_mesh(const ColliderEffect& c, const Point3& shell_lo,
                                const Point3& shell_hi, double edge_length) {
  using Shape = ColliderEffect::Shape;
  TriangleMesh mesh;
  switch (c.shape) {
    case Shape::kSphere:
      mesh = make_sphere(c.radius, c.subdivisions);
      for (Point3& p : mesh.points) p += point(c.center);
      break;
    case Shape::kPlane: {
      const Point3 n = point(c.normal).normalized();
      // Tangents: the axis least aligned with n, made orthogonal.
      Eigen::Index axis;
      n.cwiseAbs().minCoeff(&axis);
      const Point3 t1 = n.cross(Point3::Unit(axis)).normalized(), t2 = n.cross(t1);
      const double side = c.side ? *c.side : 4.0 * (shell_hi - shell_lo).norm();
      const Point3 centre = 0.5 * (shell_lo + shell_hi);
      const Point3 foot = centre - n * n.dot(centre - point(c.center));
      const int k = cells(side, edge_length, 64);
      add_patch(mesh, foot - 0.5 * side * (t1 + t2), side * t1, side * t2, k, k);
      break;
    }
    case Shape::kBox: {
      const Point3 h = 0.5 * point(c.size), o = point(c.center);
      const int most = 32;
      for (int axis = 0; axis < 3; ++axis) {
        const int p = (axis + 1) % 3, q = (axis + 2) % 3;
        const Point3 a = 2.0 * h[p] * Point3::Unit(p), b = 2.0 * h[q] * Point3::Unit(q);
        const int na = cells(a.norm(), edge_length, most), nb = cells(b.norm(), edge_length, most);
        const Point3 low = o - h;  // the corner (−, −, −)
        // The face at +axis, normal a × b = +e_axis; the one at −axis with the axes swapped.
        add_patch(mesh, low + 2.0 * h[axis] * Point3::Unit(axis), a, b, na, nb);
        add_patch(mesh, low, b, a, nb, na);
      }
      break;
    }
    case Shape::kObj:
      mesh = read_obj_triangles(c.obj);
      break;
  }
  mesh.groups.clear();
  return mesh;
}

}  // namespace mlshell
