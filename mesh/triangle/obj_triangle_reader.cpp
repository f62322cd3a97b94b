// Reads a triangle mesh, with named vertex groups, from a plain Wavefront OBJ file.
#include <charconv>
#include <fstream>
#include <set>
#include <sstream>

#include "../obj_error.hpp"
#include "mlshell/triangle/triangle_mesh.hpp"

namespace mlshell {

namespace {

/// Parses a whole token as a number; from_chars accepts "nan" and "inf", which validation
/// then reports with the vertex. A leading '+' is allowed, as printf-style writers emit it.
template <class Number>
bool parse_number(const std::string& token, Number& value) {
  const char* first = token.data();
  const char* last = first + token.size();
  if (first != last && *first == '+') ++first;
  if (first == last) return false;
  const auto [end, error] = std::from_chars(first, last, value);
  return error == std::errc() && end == last;
}

/// Parses an `f` entry (`i`, `i/t`, `i//n`, `i/t/n`; negative = counted back from the last
/// vertex so far) to a 0-based vertex index.
int parse_face_index(const std::string& token, int num_points, const std::filesystem::path& path,
                     int line) {
  std::vector<std::string> parts{""};
  for (char c : token)
    if (c == '/')
      parts.emplace_back();
    else
      parts.back().push_back(c);
  long index = 0, unused = 0;
  bool ok = parts.size() <= 3 && parse_number(parts[0], index) && index != 0;
  for (size_t i = 1; ok && i < parts.size(); ++i)
    ok = (i == 1 && parts[i].empty() && parts.size() == 3) || parse_number(parts[i], unused);
  if (!ok)
    obj_error(path, line,
              "bad face entry '" + token + "' (expected a vertex index i, i/t, i//n or i/t/n)");
  const long resolved = index > 0 ? index - 1 : num_points + index;
  if (resolved < 0 || resolved >= num_points)
    obj_error(path, line,
              "face refers to vertex " + parts[0] + " but only " + std::to_string(num_points) +
                  " vertices are defined before it (expected an index from 1 to " +
                  std::to_string(num_points) + ", or from -1 to -" + std::to_string(num_points) +
                  ")");
  return static_cast<int>(resolved);
}

}  // namespace

TriangleMesh read_obj_triangles(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw MeshError(path.string() + ": is a directory, not an OBJ file");
  std::ifstream in(path);
  if (!in) throw MeshError(path.string() + ": cannot open the OBJ file");
  TriangleMesh mesh;
  TriangleSourceLines lines;
  std::map<std::string, std::set<int>> groups;
  std::vector<std::string> current_groups;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    std::istringstream s(text);
    std::string tag;
    if (!(s >> tag) || tag[0] == '#') continue;
    if (tag == "v") {
      Point3 p;
      std::string token;
      for (int k = 0; k < 3; ++k) {
        if (!(s >> token))
          obj_error(path, line, "vertex '" + text + "' has fewer than three coordinates");
        if (!parse_number(token, p[k]))
          obj_error(path, line, "malformed number '" + token + "' in vertex '" + text + "'");
      }
      mesh.points.push_back(p);
      lines.points.push_back(line);
    } else if (tag == "f") {
      std::vector<int> face;
      std::string token;
      while (s >> token) face.push_back(parse_face_index(token, mesh.num_points(), path, line));
      if (face.size() != 3)
        obj_error(
            path, line,
            "face with " + std::to_string(face.size()) +
                " vertices: mlshell's triangle shells need a triangle mesh; triangulate the face "
                "first");
      mesh.triangles.push_back({face[0], face[1], face[2]});
      lines.triangles.push_back(line);
      for (const std::string& g : current_groups) groups[g].insert(face.begin(), face.end());
    } else if (tag == "g") {
      current_groups.clear();
      for (std::string name; s >> name;)
        if (name != "default") current_groups.push_back(name);
    }
  }
  if (in.bad()) throw MeshError(path.string() + ": read error after line " + std::to_string(line));
  for (const auto& [name, vertices] : groups)
    mesh.groups[name] = std::vector<int>(vertices.begin(), vertices.end());
  validate_triangle_mesh(mesh, path.string(), lines);
  return mesh;
}

}  // namespace mlshell
