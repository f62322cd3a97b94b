// The rotation part of a clamp with midedge bending (see triangle_effects.hpp).
#include <map>

#include "mlshell/triangle/triangle_effects.hpp"

namespace mlshell {

MidedgeClampTerm::MidedgeClampTerm(std::string name, const TriangleDiscretization& disc,
                                   const ParallelLayout& layout,
                                   const std::vector<std::array<int, 2>>& edges,
                                   const TriangleShellParameters& params, PrescribedMotion motion)
    : EnergyTerm(std::move(name)), motion_(std::move(motion)) {
  const auto& X = disc.points();
  const TriangleTopology& topo = disc.topology();
  // The clamped edges of each owned triangle, as element edge numbers (opposite corner i).
  std::map<int, std::array<bool, 3>> clamped;
  for (const auto& [a, b] : edges)
    for (int f : topo.vertex_triangles(a)) {
      const Triangle& t = disc.mesh().triangles[f];
      int k = 0;
      while (t[k] != a) ++k;
      if (t[(k + 1) % 3] != b || layout.face_owner(f) != layout.rank()) continue;
      clamped[f][(k + 2) % 3] = true;  // the edge a → b is opposite corner k + 2
    }
  const double D = plate_stiffness(params.youngs_modulus, params.poisson_ratio, params.thickness);
  for (const auto& [f, held] : clamped) {
    const MidedgeStencil s = midedge_stencil(disc, layout, f);
    Element e;
    e.nodes = s.nodes;
    e.reference = s.reference;
    std::array<EdgeWing, 3> wings = s.wings;
    e.moves.fill(false);
    for (int i = 0; i < 3; ++i) {
      if (!held[i]) continue;
      // The rest mirror of x_i through the midpoint of edge i.
      e.reference[3 + i] =
          X[s.vertices[(i + 1) % 3]] + X[s.vertices[(i + 2) % 3]] - X[s.vertices[i]];
      e.moves[3 + i] = true;
      wings[i] = EdgeWing::kClamp;
    }
    const double nu = params.poisson_ratio;
    const MidedgeRest with = MidedgeRest::from(e.reference, wings, D, nu);
    const MidedgeRest without = MidedgeRest::from(e.reference, s.wings, D, nu);
    e.rest = with;
    e.rest.stiffness = with.stiffness - without.stiffness;
    elements_.push_back(e);
  }
}

PetscErrorCode MidedgeClampTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                     std::vector<double>* grad, Mat hess) const {
  PetscFunctionBeginUser;
  const RigidPlacement placement = motion_ ? motion_(time_) : RigidPlacement{};
  std::array<Eigen::Vector3d, 6> x;
  for (const Element& e : elements_) {
    for (int k = 0; k < 6; ++k) {
      x[k] = e.reference[k];
      if (e.nodes[k] >= 0)
        x[k] += Eigen::Vector3d(u[3 * e.nodes[k]], u[3 * e.nodes[k] + 1], u[3 * e.nodes[k] + 2]);
      else if (e.moves[k])  // the virtual vertex follows the motion rigidly
        x[k] = placement.position(e.reference[k]);
    }
    PetscCall(add_midedge_element(e.rest, x, e.nodes, projects_hessian(), energy, grad, hess));
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
