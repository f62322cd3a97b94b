// Generated cages: rectangle and L-shape (the paper's §7 scenes).
#include <cmath>

#include "mlshell/subdivision/quad_mesh.hpp"

namespace mlshell {

QuadMesh make_l_shape_cage(double width, double height, int nx, int ny, double cut_x, double cut_y,
                           double x0, double y0) {
  const double hx = width / nx, hy = height / ny;
  // Faces with index i >= keep_x and j >= keep_y are cut away.
  const int keep_x = nx - static_cast<int>(std::lround(cut_x / hx));
  const int keep_y = ny - static_cast<int>(std::lround(cut_y / hy));
  auto kept = [&](int i, int j) { return i < keep_x || j < keep_y; };
  QuadMesh mesh;
  std::vector<int> id((nx + 1) * (ny + 1), -1);
  auto vid = [&](int i, int j) -> int {
    int& v = id[j * (nx + 1) + i];
    if (v < 0) {
      v = mesh.num_points();
      mesh.points.emplace_back(x0 + i * hx, y0 + j * hy, 0.0);
    }
    return v;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (kept(i, j)) {
        mesh.quads.push_back({vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)});
        mesh.ghost.push_back(0);
      }
  return mesh;
}

QuadMesh make_rectangle_cage(double width, double height, int nx, int ny, double x0, double y0) {
  return make_l_shape_cage(width, height, nx, ny, 0.0, 0.0, x0, y0);
}

}  // namespace mlshell
