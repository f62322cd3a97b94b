// The bodies of a triangle-mesh scene: geometry.mesh (body 0) and the scene's `bodies:` (body k
// is bodies[k − 1]), merged into one mesh and one discretization. Each body keeps its material:
// the elastic, inertia and gravity terms read it per face, and contact switches self-contact per
// body (docs/contact.md#several-bodies).
#pragma once

#include <string>
#include <vector>

#include "mlshell/scene.hpp"
#include "mlshell/triangle/triangle_effects.hpp"
#include "mlshell/triangle/triangle_mesh.hpp"

namespace mlshell {

/// The scene's mesh: geometry.mesh, then each body's mesh moved by its `translate`. A body's
/// vertices form group(name), its mesh's own groups group(name/group). Throws MeshError for a bad
/// mesh and SceneError for a body whose name is a group of geometry.mesh already.
TriangleMesh build_scene_mesh(const Scene& scene);

struct TriangleBodies {
  std::vector<std::string> names;               ///< per body; body 0 is the scene's name
  std::vector<const MaterialSpec*> materials;   ///< per body
  std::vector<int> of_point, of_face;           ///< the body of each mesh point and face

  /// The bodies of `mesh` (build_scene_mesh's, or a discretization's mesh with its groups).
  static TriangleBodies of(const Scene& scene, const TriangleMesh& mesh);
  int size() const { return static_cast<int>(materials.size()); }
  TriangleShellParameters parameters(int body) const;
  /// ρτ of each face.
  std::vector<double> face_area_density() const;
  /// The largest over the bodies of τ, of ρτ, and of the membrane stiffness Yτ.
  double max_thickness() const;
  double max_area_density() const;
  double max_membrane_stiffness() const;
};

}  // namespace mlshell
