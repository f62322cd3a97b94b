// ContactSurface::from_faces: the edges of a face list (contact_candidates.hpp).
#include "mlshell/contact/broad_phase/contact_candidates.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace mlshell {

ContactSurface ContactSurface::from_faces(int num_vertices, std::vector<std::array<int, 3>> faces) {
  ContactSurface s;
  s.num_vertices = num_vertices;
  s.edges.reserve(3 * faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& t = faces[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= num_vertices)
        throw std::invalid_argument("contact surface: face " + std::to_string(f) + " has vertex " +
                                    std::to_string(t[k]) + " outside [0, " +
                                    std::to_string(num_vertices) + ")");
      if (t[k] == t[(k + 1) % 3])
        throw std::invalid_argument("contact surface: face " + std::to_string(f) +
                                    " repeats vertex " + std::to_string(t[k]));
      s.edges.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
    }
  }
  std::sort(s.edges.begin(), s.edges.end());
  s.edges.erase(std::unique(s.edges.begin(), s.edges.end()), s.edges.end());
  s.faces = std::move(faces);
  return s;
}

}  // namespace mlshell
