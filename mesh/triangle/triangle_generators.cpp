// Generated triangle meshes. The unstructured rectangle uses CGAL's 2D constrained Delaunay
// mesher; CGAL stays in this translation unit (it is slow to compile).
#include "mlshell/triangle/triangle_generators.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace mlshell {

namespace {

constexpr double kPi = std::numbers::pi;

template <class T>
[[noreturn]] void bad_argument(const char* generator, const char* name, T value,
                               const char* expected) {
  std::ostringstream m;
  m << generator << ": " << name << " = " << value << " (expected " << expected << ")";
  throw std::invalid_argument(m.str());
}

void require_positive(const char* generator, const char* name, double value) {
  if (!(std::isfinite(value) && value > 0.0))
    bad_argument(generator, name, value, "a positive finite number");
}

void require_finite(const char* generator, const char* name, double value) {
  if (!std::isfinite(value)) bad_argument(generator, name, value, "a finite number");
}

void require_at_least(const char* generator, const char* name, int value, int least) {
  if (value < least) {
    const std::string expected = "an integer >= " + std::to_string(least);
    bad_argument(generator, name, value, expected.c_str());
  }
}

/// Rejects grids whose vertex or triangle count would overflow int indices.
void require_fits(const char* generator, const char* name, int value, double vertices,
                  double triangles) {
  if (std::max(vertices, triangles) > static_cast<double>(INT_MAX))
    bad_argument(generator, name, value, "a mesh small enough for int vertex indices");
}

/// Coordinate i of n equal steps from x0 to x0 + length, exactly x0 + length at i = n.
double grid(double x0, double length, int i, int n) {
  return i == n ? x0 + length : x0 + length * i / n;
}

/// The two triangles of quad (a, b, c, d) (counter-clockwise), split along a–c or b–d.
void add_quad(TriangleMesh& mesh, int a, int b, int c, int d, bool diagonal_ac) {
  if (diagonal_ac) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
  } else {
    mesh.triangles.push_back({a, b, d});
    mesh.triangles.push_back({b, c, d});
  }
}

/// Groups "left", "right", "bottom", "top": vertices within a tiny tolerance of each side.
void add_side_groups(TriangleMesh& mesh, double width, double height, double x0, double y0) {
  const double tol = 1e-9 * std::max(width, height);
  for (int v = 0; v < mesh.num_points(); ++v) {
    const Point3& p = mesh.points[v];
    if (std::abs(p.x() - x0) <= tol) mesh.groups["left"].push_back(v);
    if (std::abs(p.x() - (x0 + width)) <= tol) mesh.groups["right"].push_back(v);
    if (std::abs(p.y() - y0) <= tol) mesh.groups["bottom"].push_back(v);
    if (std::abs(p.y() - (y0 + height)) <= tol) mesh.groups["top"].push_back(v);
  }
}

}  // namespace

TriangleMesh make_triangle_rectangle(double width, double height, int nx, int ny, double x0,
                                     double y0, bool uniform_diagonals) {
  const char* name = "make_triangle_rectangle";
  require_positive(name, "width", width);
  require_positive(name, "height", height);
  require_at_least(name, "nx", nx, 1);
  require_at_least(name, "ny", ny, 1);
  require_fits(name, "nx", nx, (nx + 1.0) * (ny + 1.0), 2.0 * nx * ny);
  require_finite(name, "x0", x0);
  require_finite(name, "y0", y0);
  TriangleMesh mesh;
  mesh.points.reserve((nx + 1) * (ny + 1));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      mesh.points.emplace_back(grid(x0, width, i, nx), grid(y0, height, j, ny), 0.0);
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      add_quad(mesh, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1),
               uniform_diagonals || (i + j) % 2 == 0);
  add_side_groups(mesh, width, height, x0, y0);
  validate_triangle_mesh(mesh, name);
  return mesh;
}

TriangleMesh make_unstructured_rectangle(double width, double height, double edge_length, double x0,
                                         double y0) {
  const char* name = "make_unstructured_rectangle";
  require_positive(name, "width", width);
  require_positive(name, "height", height);
  require_positive(name, "edge_length", edge_length);
  require_finite(name, "x0", x0);
  require_finite(name, "y0", y0);
  // About 2.3·(width/edge)·(height/edge) triangles at the size bound, several times more in
  // practice: refuse what would take hours or overflow int indices.
  if ((width / edge_length) * (height / edge_length) > 1e8)
    bad_argument(name, "edge_length", edge_length,
                 "at most 1e8 squares of that size in the rectangle");

  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Delaunay_mesh_vertex_base_2<Kernel>;
  using Fb = CGAL::Delaunay_mesh_face_base_2<Kernel>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
  using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds>;
  using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;

  // Boundary vertices evenly along the sides, counter-clockwise, joined by constraints, at the
  // spacing nearest edge_length. CGAL's size bound caps the longest edge of each triangle; the
  // refined triangles' edges then average 0.69 × the bound. A bound of kSizeBound × edge_length
  // makes edge_length the mean edge length and leaves the boundary segments unsplit (with the
  // bound at edge_length, Ruppert's encroachment rule splits most of them and the mean edge
  // drops to 0.69 × edge_length).
  constexpr double kSizeBound = 1.45;
  const auto divisions = [&](double side) {
    return std::max(1, static_cast<int>(std::lround(side / edge_length)));
  };
  const int nx = divisions(width), ny = divisions(height);
  std::vector<Kernel::Point_2> boundary;
  for (int i = 0; i < nx; ++i) boundary.emplace_back(grid(x0, width, i, nx), y0);
  for (int j = 0; j < ny; ++j) boundary.emplace_back(x0 + width, grid(y0, height, j, ny));
  for (int i = nx; i > 0; --i) boundary.emplace_back(grid(x0, width, i, nx), y0 + height);
  for (int j = ny; j > 0; --j) boundary.emplace_back(x0, grid(y0, height, j, ny));
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles;
  for (const auto& p : boundary) handles.push_back(cdt.insert(p));
  for (size_t i = 0; i < handles.size(); ++i)
    cdt.insert_constraint(handles[i], handles[(i + 1) % handles.size()]);
  CGAL::refine_Delaunay_mesh_2(cdt, Criteria(0.125, kSizeBound * edge_length));

  // Canonical output: vertices sorted by (y, x), triangles rotated to start at their smallest
  // vertex and sorted.
  std::vector<Cdt::Vertex_handle> vertices;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
    vertices.push_back(v);
  const auto by_yx = [](const Cdt::Vertex_handle& a, const Cdt::Vertex_handle& b) {
    return std::make_pair(a->point().y(), a->point().x()) <
           std::make_pair(b->point().y(), b->point().x());
  };
  std::sort(vertices.begin(), vertices.end(), by_yx);
  std::map<Cdt::Vertex_handle, int> index;
  TriangleMesh mesh;
  for (const auto& v : vertices) {
    index[v] = mesh.num_points();
    mesh.points.emplace_back(v->point().x(), v->point().y(), 0.0);
  }
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    Triangle t{index.at(f->vertex(0)), index.at(f->vertex(1)), index.at(f->vertex(2))};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    mesh.triangles.push_back(t);
  }
  std::sort(mesh.triangles.begin(), mesh.triangles.end());
  add_side_groups(mesh, width, height, x0, y0);
  validate_triangle_mesh(mesh, name);
  return mesh;
}

TriangleMesh make_cylinder(double radius, double length, int n_around, int n_along) {
  const char* name = "make_cylinder";
  require_positive(name, "radius", radius);
  require_positive(name, "length", length);
  require_at_least(name, "n_around", n_around, 3);
  require_at_least(name, "n_along", n_along, 1);
  require_fits(name, "n_along", n_along, n_around * (n_along + 1.0), 2.0 * n_around * n_along);
  TriangleMesh mesh;
  for (int j = 0; j <= n_along; ++j)
    for (int i = 0; i < n_around; ++i) {
      const double angle = 2.0 * kPi * i / n_around;
      mesh.points.emplace_back(radius * std::cos(angle), radius * std::sin(angle),
                               grid(0.0, length, j, n_along));
    }
  auto id = [&](int i, int j) { return j * n_around + i % n_around; };
  // Counter-clockwise seen from outside: around (increasing angle), then up.
  for (int j = 0; j < n_along; ++j)
    for (int i = 0; i < n_around; ++i)
      add_quad(mesh, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 0);
  for (int i = 0; i < n_around; ++i) {
    mesh.groups["bottom"].push_back(id(i, 0));
    mesh.groups["top"].push_back(id(i, n_along));
  }
  validate_triangle_mesh(mesh, name);
  return mesh;
}

TriangleMesh make_spherical_cap(double radius, double opening_angle, int n_rings) {
  const char* name = "make_spherical_cap";
  require_positive(name, "radius", radius);
  if (!(opening_angle > 0.0 && opening_angle < kPi))
    bad_argument(name, "opening_angle", opening_angle, "an angle in (0, pi) radians");
  require_at_least(name, "n_rings", n_rings, 1);
  // Ring k at polar angle k·h with about 2π·sin(k·h)/h vertices: edges along the ring about
  // as long as the spacing between rings (6k vertices near a flat apex).
  const double h = opening_angle / n_rings;
  std::vector<int> count(n_rings + 1, 1), first(n_rings + 1, 0);
  double total = 1.0;
  for (int k = 1; k <= n_rings; ++k) {
    const double c = std::max(3.0, std::round(2.0 * kPi * std::sin(k * h) / h));
    total += c;
    require_fits(name, "n_rings", n_rings, total, 2.0 * total);
    count[k] = static_cast<int>(c);
    first[k] = first[k - 1] + count[k - 1];
  }
  TriangleMesh mesh;
  mesh.points.emplace_back(0.0, 0.0, radius);
  for (int k = 1; k <= n_rings; ++k) {
    const double polar = k == n_rings ? opening_angle : k * h;
    for (int i = 0; i < count[k]; ++i) {
      const double angle = 2.0 * kPi * i / count[k];
      mesh.points.emplace_back(radius * std::sin(polar) * std::cos(angle),
                               radius * std::sin(polar) * std::sin(angle),
                               radius * std::cos(polar));
    }
  }
  // Counter-clockwise seen from outside = increasing angle with the apex side "up". The apex
  // is a fan; between two rings walk around both, always advancing the ring whose next vertex
  // comes first in angle (the zipper gives count[k-1] + count[k] triangles).
  for (int i = 0; i < count[1]; ++i)
    mesh.triangles.push_back({0, first[1] + i, first[1] + (i + 1) % count[1]});
  for (int k = 2; k <= n_rings; ++k) {
    const int m_in = count[k - 1], m_out = count[k];
    auto in = [&](int i) { return first[k - 1] + i % m_in; };
    auto out = [&](int i) { return first[k] + i % m_out; };
    for (int a = 0, b = 0; a < m_in || b < m_out;) {
      // Compare angles a+1 / m_in and b+1 / m_out exactly, in integers.
      const bool advance_in = b == m_out || (a < m_in && static_cast<long>(a + 1) * m_out <
                                                             static_cast<long>(b + 1) * m_in);
      if (advance_in) {
        mesh.triangles.push_back({in(a), out(b), in(a + 1)});
        ++a;
      } else {
        mesh.triangles.push_back({in(a), out(b), out(b + 1)});
        ++b;
      }
    }
  }
  mesh.groups["apex"] = {0};
  for (int i = 0; i < count[n_rings]; ++i) mesh.groups["boundary"].push_back(first[n_rings] + i);
  validate_triangle_mesh(mesh, name);
  return mesh;
}

TriangleMesh make_sphere(double radius, int subdivisions) {
  const char* name = "make_sphere";
  require_positive(name, "radius", radius);
  require_at_least(name, "subdivisions", subdivisions, 0);
  if (subdivisions > 13)  // 20·4^14 triangles overflow int
    bad_argument(name, "subdivisions", subdivisions, "at most 13");
  // The icosahedron with vertices at the cyclic permutations of (0, ±1, ±φ): its edges are the
  // vertex pairs at distance 2; faces are the mutually adjacent triples, turned outwards.
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh mesh;
  for (int axis = 0; axis < 3; ++axis)
    for (double s : {-1.0, 1.0})
      for (double t : {-phi, phi}) {
        Point3 p;
        p[axis] = 0.0;
        p[(axis + 1) % 3] = s;
        p[(axis + 2) % 3] = t;
        mesh.points.push_back(p);
      }
  auto adjacent = [&](int a, int b) {
    return std::abs((mesh.points[a] - mesh.points[b]).norm() - 2.0) < 1e-9;
  };
  for (int a = 0; a < 12; ++a)
    for (int b = a + 1; b < 12; ++b)
      for (int c = b + 1; c < 12; ++c)
        if (adjacent(a, b) && adjacent(b, c) && adjacent(a, c)) {
          const Point3& pa = mesh.points[a];
          const bool outward = (mesh.points[b] - pa)
                                   .cross(mesh.points[c] - pa)
                                   .dot(pa + mesh.points[b] + mesh.points[c]) > 0.0;
          mesh.triangles.push_back(outward ? Triangle{a, b, c} : Triangle{a, c, b});
        }
  for (Point3& p : mesh.points) p = radius * p.normalized();
  // Split each triangle into four at its edge midpoints, shared through a map per level.
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto [it, inserted] =
          midpoint.emplace(std::minmax(a, b), static_cast<int>(mesh.points.size()));
      if (inserted) mesh.points.push_back(radius * (mesh.points[a] + mesh.points[b]).normalized());
      return it->second;
    };
    std::vector<Triangle> refined;
    refined.reserve(4 * mesh.triangles.size());
    for (const auto& [a, b, c] : mesh.triangles) {
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      refined.push_back({a, ab, ca});
      refined.push_back({ab, b, bc});
      refined.push_back({ca, bc, c});
      refined.push_back({ab, bc, ca});
    }
    mesh.triangles = std::move(refined);
  }
  validate_triangle_mesh(mesh, name);
  return mesh;
}

}  // namespace mlshell
