// A triangle's midedge bending element on the mesh, and its assembly (see triangle_effects.hpp).
#include <Eigen/Dense>
#include <cmath>

#include "mlshell/psd_projection.hpp"
#include "mlshell/triangle/triangle_effects.hpp"

namespace mlshell {

// Edge i of the element runs from x_{i+1} to x_{i+2}: the mesh's local edge i + 1 (local edge k
// leaves corner k).
MidedgeStencil midedge_stencil(const TriangleDiscretization& disc, const ParallelLayout& layout,
                               int face) {
  const Triangle& t = disc.mesh().triangles[face];
  const auto& X = disc.points();
  MidedgeStencil s;
  for (int i = 0; i < 3; ++i) {
    s.vertices[i] = t[i];
    const int g = disc.topology().neighbour(face, (i + 1) % 3);
    s.vertices[3 + i] = -1;
    s.wings[i] = EdgeWing::kFree;
    if (g >= 0) {
      for (int v : disc.mesh().triangles[g])
        if (v != t[(i + 1) % 3] && v != t[(i + 2) % 3]) s.vertices[3 + i] = v;
      s.wings[i] = EdgeWing::kNeighbour;
    }
  }
  for (int k = 0; k < 6; ++k) {
    const int v = s.vertices[k];
    s.nodes[k] = v >= 0 ? layout.local_of(v) : -1;
    s.reference[k] = X[v >= 0 ? v : s.vertices[k - 3]];
  }
  return s;
}

PetscErrorCode add_midedge_element(const MidedgeRest& rest, const std::array<Eigen::Vector3d, 6>& x,
                                   const std::array<PetscInt, 6>& nodes, bool project,
                                   CompensatedSum& energy, std::vector<double>* grad, Mat hess) {
  PetscFunctionBeginUser;
  Vector18 g;
  Matrix18 H;
  const double e = midedge_bending(rest, x, grad ? &g : nullptr, hess ? &H : nullptr);
  energy.add(e);
  if (!std::isfinite(e) || (!grad && !hess)) PetscFunctionReturn(0);
  // Keep the slots that are unknowns (all six inside the mesh: no copy).
  int slots[6], n = 0;
  for (int k = 0; k < 6; ++k)
    if (nodes[k] >= 0) slots[n++] = k;
  std::vector<PetscInt> dofs(n);
  for (int a = 0; a < n; ++a) dofs[a] = nodes[slots[a]];
  if (n == 6) {
    if (grad) add_local_gradient(dofs, g.data(), *grad);
    if (hess) {
      if (project) project_stencil_hessian_to_psd(H);
      PetscCall(add_local_hessian(hess, dofs, H.data()));  // symmetric: row = column major
    }
    PetscFunctionReturn(0);
  }
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 18, 1> gc(3 * n);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 18, 18> Hc(3 * n, 3 * n);
  for (int a = 0; a < n; ++a) {
    if (grad) gc.segment<3>(3 * a) = g.segment<3>(3 * slots[a]);
    if (hess)
      for (int b = 0; b < n; ++b)
        Hc.block<3, 3>(3 * a, 3 * b) = H.block<3, 3>(3 * slots[a], 3 * slots[b]);
  }
  if (grad) add_local_gradient(dofs, gc.data(), *grad);
  if (hess) {
    if (project) project_to_psd(Hc);
    PetscCall(add_local_hessian(hess, dofs, Hc.data()));  // symmetric: row = column major
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
