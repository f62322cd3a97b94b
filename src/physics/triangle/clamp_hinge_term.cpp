// The rotation part of a clamp on a triangle mesh (see triangle_effects.hpp).
#include "mlshell/psd_projection.hpp"
#include "mlshell/triangle/triangle_effects.hpp"

namespace mlshell {

ClampHingeTerm::ClampHingeTerm(std::string name, const TriangleDiscretization& disc,
                               const ParallelLayout& layout,
                               const std::vector<std::array<int, 2>>& edges, double stiffness,
                               PrescribedMotion motion)
    : EnergyTerm(std::move(name)), motion_(std::move(motion)) {
  const auto& X = disc.points();
  const TriangleTopology& topo = disc.topology();
  for (const auto& [a, b] : edges) {
    // The boundary edge a → b runs along its triangle (a, b, c).
    for (int f : topo.vertex_triangles(a)) {
      const Triangle& t = disc.mesh().triangles[f];
      int k = 0;
      while (t[k] != a) ++k;
      if (t[(k + 1) % 3] != b || layout.face_owner(f) != layout.rank()) continue;
      const int c = t[(k + 2) % 3];
      Hinge h;
      h.nodes = {layout.local_of(a), layout.local_of(b), layout.local_of(c)};
      h.reference = {X[a], X[b], X[c]};
      h.virtual_vertex = X[a] + X[b] - X[c];  // point mirror of c through the edge midpoint
      h.rest = HingeRest::from(X[a], X[b], X[c], h.virtual_vertex, stiffness);
      hinges_.push_back(h);
    }
  }
}

PetscErrorCode ClampHingeTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                   std::vector<double>* grad, Mat hess) const {
  PetscFunctionBeginUser;
  const RigidPlacement placement = motion_ ? motion_(time_) : RigidPlacement{};
  Vector12 g;
  Matrix12 H;
  std::vector<PetscInt> nodes(3);
  for (const Hinge& h : hinges_) {
    Eigen::Vector3d x[3];
    for (int k = 0; k < 3; ++k)
      x[k] = h.reference[k] +
             Eigen::Vector3d(u[3 * h.nodes[k]], u[3 * h.nodes[k] + 1], u[3 * h.nodes[k] + 2]);
    const double e = hinge_bending(h.rest, x[0], x[1], x[2], placement.position(h.virtual_vertex),
                                   grad ? &g : nullptr, hess ? &H : nullptr);
    energy.add(e);
    if (!std::isfinite(e)) continue;
    nodes.assign(h.nodes.begin(), h.nodes.end());
    // The virtual vertex is prescribed: only the first nine dofs are unknowns.
    if (grad) add_local_gradient(nodes, g.data(), *grad);
    if (hess) {
      Matrix9 H9 = H.topLeftCorner<9, 9>();
      if (projects_hessian()) project_to_psd(H9);
      PetscCall(add_local_hessian(hess, nodes, H9.data()));
    }
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
