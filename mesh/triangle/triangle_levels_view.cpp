// Inspecting a triangle-level hierarchy: statistics per level and OBJ files for ParaView.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "mlshell/output_files.hpp"
#include "mlshell/triangle/triangle_levels.hpp"

namespace mlshell {

double rest_shape_error(const ShellProlongation& p, const std::vector<Point3>& coarse_rest,
                        const std::vector<Point3>& fine_rest) {
  const std::vector<Point3> prolonged = p.apply(coarse_rest);
  Point3 lo = Point3::Constant(INFINITY), hi = Point3::Constant(-INFINITY);
  double error = 0.0;
  for (size_t i = 0; i < fine_rest.size(); ++i) {
    lo = lo.cwiseMin(fine_rest[i]);
    hi = hi.cwiseMax(fine_rest[i]);
    error = std::max(error, (prolonged[i] - fine_rest[i]).norm());
  }
  return error / (hi - lo).norm();
}

double smallest_angle_degrees(const TriangleMesh& mesh) {
  double smallest = 180.0;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const Point3 a = mesh.points[t[(k + 1) % 3]] - mesh.points[t[k]];
      const Point3 b = mesh.points[t[(k + 2) % 3]] - mesh.points[t[k]];
      smallest = std::min(smallest, std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / std::numbers::pi);
    }
  return smallest;
}

PetscErrorCode view_hierarchy(const TriangleLevels& levels, MPI_Comm comm) {
  PetscFunctionBeginUser;
  const DecimationHierarchy* h = levels.decimation();
  PetscCall(PetscPrintf(comm, "mlshell: triangle hierarchy (%d levels%s%s)\n", levels.num_levels(),
                        h ? ", fingerprint " : "", h ? h->fingerprint().c_str() : ""));
  const int top = levels.finest();
  const auto& finest_rest = levels.discretization(top).points();
  for (int l = 0; l <= top; ++l) {
    const TriangleMesh& mesh = levels.discretization(l).mesh();
    const int index = h ? h->num_levels() - 1 - (top - l) : 0;
    PetscCall(PetscPrintf(comm,
                          "  level %d: %8d vertices, %9d dofs, %8d faces, smallest angle %5.2f deg, "
                          "built in %.3f s\n",
                          l, mesh.num_points(), 3 * mesh.num_points(), mesh.num_triangles(),
                          smallest_angle_degrees(mesh), h ? h->build_seconds[index] : 0.0));
    if (l == top) continue;
    const ShellProlongation& p = levels.prolongation(l);
    long nonzeros = 0;
    for (int i = 0; i < p.num_fine(); ++i)
      nonzeros += (p.embedding(i).weights.array() != 0.0).count();
    const auto& next_rest = levels.discretization(l + 1).points();
    PetscCall(PetscPrintf(comm,
                          "      U %d -> %d: %ld nonzeros (%.2f per row); rest shape: "
                          "P_%d^%d %.1e, direct P^%d %.1e (of the bounding-box diagonal)\n",
                          l, l + 1, nonzeros, static_cast<double>(nonzeros) / p.num_fine(), l + 1,
                          l, rest_shape_error(p, mesh.points, next_rest), l,
                          rest_shape_error(levels.direct_prolongation(l), mesh.points,
                                           finest_rest)));
  }
  PetscFunctionReturn(0);
}

void write_hierarchy(const TriangleLevels& levels, const std::string& dir) {
  if (levels.layout(0).rank() != 0) return;
  std::filesystem::create_directories(dir);
  const TriangleMesh& finest = levels.discretization(levels.finest()).mesh();
  auto sample = [](const std::vector<Point3>& points, const std::vector<Triangle>& triangles) {
    SurfaceSample s;
    s.cell_size = 3;
    for (const Point3& p : points) s.points.insert(s.points.end(), {p.x(), p.y(), p.z()});
    for (const Triangle& t : triangles) s.cells.insert(s.cells.end(), t.begin(), t.end());
    return s;
  };
  for (int l = 0; l <= levels.finest(); ++l) {
    const TriangleMesh& mesh = levels.discretization(l).mesh();
    const std::filesystem::path base = std::filesystem::path(dir) / ("level_" + std::to_string(l));
    write_obj(base.string() + ".obj", sample(mesh.points, mesh.triangles),
              "mlshell level " + std::to_string(l) + " rest mesh");
    if (l == levels.finest()) continue;
    write_obj(base.string() + "_to_finest.obj",
              sample(levels.direct_prolongation(l).apply(mesh.points), finest.triangles),
              "mlshell level " + std::to_string(l) + " prolonged to the finest level (P^" +
                  std::to_string(l) + ")");
  }
}

}  // namespace mlshell
