// The triangle surfaces of a scene's colliders (static obstacles for contact; scene.hpp's
// ColliderEffect): generated spheres, planes and boxes, or an OBJ surface. Planes are squares
// and boxes' faces grids of triangles a few of the shell's edges across, so that the contact
// broad phase's cells (about an edge's size) stay small.
#pragma once

#include "mlshell/scene.hpp"
#include "mlshell/triangle/triangle_mesh.hpp"

namespace mlshell {

/// The collider's surface, oriented with its normals outwards (towards the shell for a
/// plane). `shell_lo`, `shell_hi` bound the shell's reference positions (a plane's square is
/// centred below the shell's centre, 4 diagonals wide by default); `edge_length` is the shell's
/// mean edge length. Throws MeshError for an unreadable OBJ.
TriangleMesh make_collider_mesh(const ColliderEffect& collider, const Point3& shell_lo,
                                const Point3& shell_hi, double edge_length);

}  // namespace mlshell
