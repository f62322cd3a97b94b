// Reads a quad cage from a plain Wavefront OBJ file.
#include <cmath>
#include <fstream>
#include <sstream>

#include "../obj_error.hpp"
#include "mlshell/subdivision/quad_mesh.hpp"

namespace mlshell {

namespace {

/// Parses the vertex index of an `f` entry (`i`, `i/t`, `i//n`, `i/t/n`; negative = relative).
int parse_face_index(const std::string& token, int num_points, const std::filesystem::path& path,
                     int line) {
  const std::string head = token.substr(0, token.find('/'));
  size_t used = 0;
  long index = 0;
  try {
    index = std::stol(head, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != head.size() || head.empty() || index == 0)
    obj_error(path, line, "bad face entry '" + token + "' (expected a vertex index)");
  const long resolved = index > 0 ? index - 1 : num_points + index;
  if (resolved < 0 || resolved >= num_points)
    obj_error(path, line, "face refers to vertex " + head + " which is not defined before it");
  return static_cast<int>(resolved);
}

}  // namespace

QuadMesh read_obj_cage(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw MeshError(path.string() + ": cannot open the OBJ file");
  QuadMesh mesh;
  bool in_ghost_group = false;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    std::istringstream s(text);
    std::string tag;
    if (!(s >> tag) || tag[0] == '#') continue;
    if (tag == "v") {
      Point3 p;
      if (!(s >> p.x() >> p.y() >> p.z()) || !p.allFinite())
        obj_error(path, line, "bad vertex '" + text + "' (expected three finite numbers)");
      mesh.points.push_back(p);
    } else if (tag == "f") {
      std::vector<int> face;
      std::string token;
      while (s >> token) face.push_back(parse_face_index(token, mesh.num_points(), path, line));
      if (face.size() != 4) {
        std::ostringstream m;
        m << "face with " << face.size()
          << " vertices: mlshell needs an all-quad cage (Catmull–Clark on non-quad faces is not "
             "supported; subdivide the mesh once in a modeller to make it all-quad)";
        obj_error(path, line, m.str());
      }
      mesh.quads.push_back({face[0], face[1], face[2], face[3]});
      mesh.ghost.push_back(in_ghost_group ? 1 : 0);
    } else if (tag == "g" || tag == "o") {
      std::string name;
      s >> name;
      in_ghost_group = tag == "g" && name == "ghost";
    }
  }
  validate_quad_mesh(mesh, path.string());
  return mesh;
}

}  // namespace mlshell
