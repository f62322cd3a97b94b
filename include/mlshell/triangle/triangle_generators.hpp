// Generated triangle meshes: flat rectangles (structured and unstructured), an open cylinder,
// a spherical cap and a closed sphere.
//
// Every generator returns a mesh that passes validate_triangle_mesh, with its triangles
// oriented to the +z side (flat meshes) or outwards (curved ones), and throws
// std::invalid_argument naming the parameter and its value for nonsensical parameters
// (non-positive or non-finite sizes, too few divisions, more elements than int indices allow).
#pragma once

#include "mlshell/triangle/triangle_mesh.hpp"

namespace mlshell {

/// [x0, x0 + width] × [y0, y0 + height] in the z = 0 plane, normal +z: an nx × ny grid of
/// squares, each split into two triangles along alternating diagonals (criss-cross: the
/// diagonal of cell (i, j) runs from its bottom-left corner when i + j is even, from its
/// bottom-right corner otherwise), so the mesh has no preferred direction. Vertex (i, j), at
/// (x0 + i·width/nx, y0 + j·height/ny), has index j·(nx + 1) + i. Groups "left", "right",
/// "bottom" and "top" hold the vertices on each side (corners are in two groups). With
/// `uniform_diagonals` every diagonal runs from its cell's bottom-left corner instead, so the two
/// triangles at every edge form a parallelogram.
TriangleMesh make_triangle_rectangle(double width, double height, int nx, int ny, double x0 = 0.0,
                                     double y0 = 0.0, bool uniform_diagonals = false);

/// The same rectangle as an unstructured Delaunay triangulation with edges of about
/// edge_length, from CGAL's 2D constrained Delaunay mesher (minimum angle ≈ 20.7°). The sides
/// are split evenly into segments of the length nearest edge_length, which the mesher leaves
/// as they are unless longer than its size bound; inside, edges average edge_length and range
/// from about 0.7 to 1.45 × edge_length (the size bound given to CGAL, which caps each
/// triangle's longest edge, is 1.45 × edge_length). The output depends only on the arguments:
/// vertices are sorted by (y, x), each triangle starts at its smallest vertex, triangles are
/// sorted. Normal +z; groups as make_triangle_rectangle's.
TriangleMesh make_unstructured_rectangle(double width, double height, double edge_length,
                                         double x0 = 0.0, double y0 = 0.0);

/// Open cylinder of the given radius around the z axis, z ∈ [0, length], outward normals:
/// n_along rings of n_around vertices each (ring j at z = j·length/n_along, vertex i at angle
/// 2πi/n_around, index j·n_around + i), quads split along alternating diagonals (for odd
/// n_around two neighbouring columns around angle 0 share a diagonal direction). Two boundary
/// loops; groups "bottom" (z = 0) and "top" (z = length).
TriangleMesh make_cylinder(double radius, double length, int n_around, int n_along);

/// Spherical cap (dome) of the sphere of the given radius centred at the origin: the points at
/// polar angle ≤ opening_angle ∈ (0, π) from the +z axis, outward normals. Vertex 0 is the
/// apex (0, 0, radius); rings k = 1..n_rings at polar angle k·opening_angle/n_rings follow,
/// each with about as many vertices as make its edges as long as the ring spacing (at least
/// 3), so triangles are roughly uniform. Groups "apex" ({0}) and "boundary" (the last ring).
TriangleMesh make_spherical_cap(double radius, double opening_angle, int n_rings);

/// Closed icosphere: an icosahedron whose triangles are split into four `subdivisions` times,
/// the new vertices projected onto the sphere of the given radius centred at the origin.
/// 10·4^s + 2 vertices, 20·4^s triangles, outward normals.
TriangleMesh make_sphere(double radius, int subdivisions);

}  // namespace mlshell
