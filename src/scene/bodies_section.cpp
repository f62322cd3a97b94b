// The `bodies:` list: further triangle-mesh shells beside geometry.mesh, each with its own mesh,
// placement and material (docs/scene-format.md#bodies).
#include <regex>
#include <set>

#include "scene_sections.hpp"

namespace mlshell::scene_reading {

std::vector<BodySpec> read_bodies(const Field& bodies, const Scene& scene,
                                  const std::filesystem::path& scene_dir) {
  bodies.check(scene.geometry.triangles(),
               "several bodies need triangle meshes; the geometry is a subdivision cage",
               "geometry: {mesh: {...}}");
  bodies.check(!scene.geometry.hierarchy.has_value(),
               "several bodies with a geometry.hierarchy are not supported yet",
               "no geometry.hierarchy (a direct fine simulation)");
  const std::vector<Field> items = bodies.items();
  bodies.check(!items.empty(), "is empty", "a list of {name, mesh, translate, material}");
  const auto& main = std::get<TriangleMaterial>(scene.material.model);
  std::vector<BodySpec> out;
  std::set<std::string> names;
  for (const Field& item : items) {
    item.expect_keys({"name", "mesh", "translate", "material", "self_contact"});
    BodySpec body;
    const Field name = item.require("name", "a name: letters, digits, _ or -");
    body.name = name.string();
    name.check(std::regex_match(body.name, std::regex("[A-Za-z0-9_-]+")),
               "must be letters, digits, _ or -");
    name.check(names.insert(body.name).second, "names another body already");
    body.mesh = read_mesh(item.require("mesh", "{generator: ...} or {obj: path}"), scene_dir);
    if (const auto t = item.find("translate")) {
      const auto v = t->numbers<3>("[x, y, z] in m");
      body.translate = {v[0], v[1], v[2]};
    }
    body.material = scene.material;
    if (const auto m = item.find("material")) {
      body.material = read_material(*m);
      const auto* tri = std::get_if<TriangleMaterial>(&body.material.model);
      m->require("model", "").check(tri != nullptr, "a body needs a triangle-mesh material",
                                    "neo-hookean or st-venant-kirchhoff");
      m->check(tri->midedge_bending == main.midedge_bending,
               "every body bends by the same model as the scene's material",
               main.midedge_bending ? "bending: midedge" : "bending: hinge");
    }
    if (const auto s = item.find("self_contact")) body.self_contact = s->boolean();
    out.push_back(std::move(body));
  }
  return out;
}

}  // namespace mlshell::scene_reading
