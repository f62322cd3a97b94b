// Inspecting a level hierarchy: statistics per level and OBJ files for ParaView.
#include <filesystem>
#include <map>
#include <sstream>

#include "mlshell/subdivision/level_hierarchy.hpp"
#include "mlshell/output_files.hpp"
#include "mlshell/subdivision/surface_sampler.hpp"

namespace mlshell {

namespace {

/// Stored entries per row (global average) and CSR storage (8-byte values, PetscInt column
/// indices and row offsets; summed over ranks, MiB) of a matrix.
void matrix_stats(Mat A, double* nnz_per_row, double* mib) {
  MatInfo info;
  PetscInt rows, cols;
  MatGetInfo(A, MAT_GLOBAL_SUM, &info);
  MatGetSize(A, &rows, &cols);
  *nnz_per_row = info.nz_used / rows;
  *mib = (info.nz_used * (sizeof(PetscScalar) + sizeof(PetscInt)) + rows * sizeof(PetscInt)) /
         (1024.0 * 1024.0);
}

}  // namespace

PetscErrorCode view_hierarchy(const LevelHierarchy& levels, MPI_Comm comm) {
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(comm, "mlshell: level hierarchy (%d levels)\n", levels.num_levels()));
  for (int l = 0; l < levels.num_levels(); ++l) {
    const SubdivisionDiscretization& d = levels.discretization(l);
    const QuadAdjacency adj(d.mesh());
    std::map<int, int> valences;  // extraordinary vertices of the simulated domain
    std::vector<char> domain(d.num_points(), 0);
    for (int f : d.elements())
      for (int v : d.mesh().quads[f]) domain[v] = 1;
    for (int v = 0; v < d.num_points(); ++v)
      if (domain[v] && adj.valence(v) != 4) ++valences[adj.valence(v)];
    std::ostringstream ev;
    for (const auto& [valence, count] : valences) ev << " " << count << "×" << valence;
    PetscCall(PetscPrintf(comm,
                          "  level %d: %7d control points, %8d dofs, %6zu elements, h = %.4g, "
                          "extraordinary vertices:%s\n",
                          l, d.num_points(), d.num_dofs(), d.elements().size(), d.mesh_size(),
                          valences.empty() ? " none" : ev.str().c_str()));
    if (l == levels.finest()) continue;
    const struct {
      const char* name;
      Mat A;
    } ops[] = {{"S (prolongation)", levels.prolongation(l)},
               {"R = S^T (restriction)", levels.restriction(l)},
               {"Q (reverse subdivision)", levels.projection(l)}};
    for (const auto& op : ops) {
      double nnz, mib;
      matrix_stats(op.A, &nnz, &mib);
      PetscCall(PetscPrintf(comm, "      %-24s %d <-> %d: %6.2f entries/row, %8.3f MiB (CSR)\n",
                            op.name, l, l + 1, nnz, mib));
    }
  }
  PetscFunctionReturn(0);
}

void write_hierarchy(const LevelHierarchy& levels, const std::string& dir) {
  if (levels.layout(0).rank() != 0) return;
  for (int l = 0; l < levels.num_levels(); ++l) {
    const SubdivisionDiscretization& d = levels.discretization(l);
    SurfaceSample cage;
    for (const Point3& p : d.mesh().points)
      cage.points.insert(cage.points.end(), {p.x(), p.y(), p.z()});
    for (const Quad& q : d.mesh().quads) cage.cells.insert(cage.cells.end(), q.begin(), q.end());
    const std::filesystem::path base = std::filesystem::path(dir) / ("level_" + std::to_string(l));
    write_obj(base.string() + "_cage.obj", cage,
              "mlshell level " + std::to_string(l) + " control cage");
    write_obj(base.string() + "_surface.obj", sample_limit_surface(d, 4)->sample({}),
              "mlshell level " + std::to_string(l) + " limit surface");
  }
}

}  // namespace mlshell
