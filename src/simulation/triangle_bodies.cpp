// Several triangle-mesh bodies on one mesh (see triangle_bodies.hpp).
#include "mlshell/triangle/triangle_bodies.hpp"

#include <algorithm>

#include "mlshell/effect_builder.hpp"
#include "mlshell/mesh_error.hpp"
#include "mlshell/triangle/triangle_effect_builder.hpp"

namespace mlshell {

TriangleMesh build_scene_mesh(const Scene& scene) {
  TriangleMesh mesh = build_triangle_mesh(*scene.geometry.mesh);
  for (std::size_t k = 0; k < scene.bodies.size(); ++k) {
    const BodySpec& body = scene.bodies[k];
    const std::string where = scene.file.string() + ": bodies[" + std::to_string(k) + "]";
    TriangleMesh part;
    try {
      part = build_triangle_mesh(body.mesh);
    } catch (const MeshError& e) {
      throw SceneError(where + ".mesh: " + e.what());
    } catch (const std::invalid_argument& e) {
      throw SceneError(where + ".mesh: " + e.what());
    }
    if (mesh.groups.count(body.name))
      throw SceneError(where + ".name: '" + body.name +
                       "' is a group of geometry.mesh already; name the body otherwise");
    const int offset = mesh.num_points();
    const Point3 shift(body.translate[0], body.translate[1], body.translate[2]);
    for (const Point3& X : part.points) mesh.points.push_back(X + shift);
    for (Triangle t : part.triangles) {
      for (int& v : t) v += offset;
      mesh.triangles.push_back(t);
    }
    std::vector<int>& all = mesh.groups[body.name];
    for (int v = 0; v < part.num_points(); ++v) all.push_back(offset + v);
    for (auto& [name, vertices] : part.groups) {
      std::vector<int>& group = mesh.groups[body.name + "/" + name];
      for (int v : vertices) group.push_back(offset + v);
    }
  }
  return mesh;
}

TriangleBodies TriangleBodies::of(const Scene& scene, const TriangleMesh& mesh) {
  TriangleBodies b;
  b.names.push_back(scene.name);
  b.materials.push_back(&scene.material);
  b.of_point.assign(mesh.num_points(), 0);
  for (std::size_t k = 0; k < scene.bodies.size(); ++k) {
    b.names.push_back(scene.bodies[k].name);
    b.materials.push_back(&scene.bodies[k].material);
    const auto it = mesh.groups.find(scene.bodies[k].name);
    if (it == mesh.groups.end()) throw std::logic_error("bodies: a body's group is missing");
    for (int v : it->second) b.of_point[v] = static_cast<int>(k) + 1;
  }
  for (const Triangle& t : mesh.triangles) b.of_face.push_back(b.of_point[t[0]]);
  return b;
}

TriangleShellParameters TriangleBodies::parameters(int body) const {
  const MaterialSpec& m = *materials.at(body);
  const auto& material = std::get<TriangleMaterial>(m.model);
  TriangleShellParameters params;
  params.membrane = material.neo_hookean ? TriangleShellParameters::Membrane::kNeoHookean
                                         : TriangleShellParameters::Membrane::kStVenantKirchhoff;
  params.bending = material.midedge_bending ? TriangleShellParameters::Bending::kMidedge
                                            : TriangleShellParameters::Bending::kHinge;
  params.youngs_modulus = material.youngs_modulus;
  params.poisson_ratio = material.poisson_ratio;
  params.thickness = m.thickness;
  return params;
}

std::vector<double> TriangleBodies::face_area_density() const {
  std::vector<double> rho;
  for (int body : of_face) rho.push_back(materials[body]->density);
  return rho;
}

double TriangleBodies::max_thickness() const {
  double out = 0.0;
  for (const MaterialSpec* m : materials) out = std::max(out, m->thickness);
  return out;
}

double TriangleBodies::max_area_density() const {
  double out = 0.0;
  for (const MaterialSpec* m : materials) out = std::max(out, m->density);
  return out;
}

double TriangleBodies::max_membrane_stiffness() const {
  double out = 0.0;
  for (const MaterialSpec* m : materials)
    out = std::max(out, PenaltyScale::membrane_stiffness_of(*m));
  return out;
}

}  // namespace mlshell
