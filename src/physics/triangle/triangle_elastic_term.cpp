// Membrane and bending (hinge or midedge) energy of a triangle mesh (see triangle_effects.hpp).
#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

#include "mlshell/psd_projection.hpp"
#include "mlshell/triangle/triangle_effects.hpp"

namespace mlshell {

MembraneParameters TriangleShellParameters::lame() const {
  const double E = youngs_modulus, nu = poisson_ratio;
  return {E / (2.0 * (1.0 + nu)), E * nu / (1.0 - nu * nu), thickness};
}

TriangleElasticTerm::TriangleElasticTerm(const TriangleDiscretization& disc,
                                         const ParallelLayout& layout,
                                         const TriangleShellParameters& params)
    : TriangleElasticTerm(disc, layout, std::vector{params},
                          std::vector<int>(disc.num_faces(), 0)) {}

TriangleElasticTerm::TriangleElasticTerm(const TriangleDiscretization& disc,
                                         const ParallelLayout& layout,
                                         std::vector<TriangleShellParameters> params,
                                         const std::vector<int>& body_of_face)
    : EnergyTerm("elastic"), params_(std::move(params)) {
  if (params_.empty() || body_of_face.size() != static_cast<std::size_t>(disc.num_faces()))
    throw std::invalid_argument("TriangleElasticTerm: one body per face and parameters per body");
  for (const TriangleShellParameters& p : params_) {
    if (p.bending != params_[0].bending)
      throw std::invalid_argument("TriangleElasticTerm: every body bends by the same model");
    lame_.push_back(p.lame());
  }
  for (int v : layout.local_points()) reference_.push_back(disc.points()[v]);
  const auto& X = disc.points();
  std::vector<int> element_index(disc.num_faces(), -1);
  for (int f : layout.local_elements()) {
    const Triangle& t = disc.mesh().triangles[f];
    Membrane m;
    for (int k = 0; k < 3; ++k) m.nodes[k] = layout.local_of(t[k]);
    m.rest = TriangleRest::from(X[t[0]], X[t[1]], X[t[2]]);
    m.body = body_of_face[f];
    element_index[f] = static_cast<int>(membranes_.size());
    membranes_.push_back(m);
  }
  if (params_[0].bending == TriangleShellParameters::Bending::kMidedge) {
    // One element per owned triangle: its stencil holds the three wing vertices.
    for (int f : layout.local_elements()) {
      const TriangleShellParameters& p = params_[body_of_face[f]];
      const double D = plate_stiffness(p.youngs_modulus, p.poisson_ratio, p.thickness);
      const MidedgeStencil s = midedge_stencil(disc, layout, f);
      plates_.push_back({s.nodes, MidedgeRest::from(s.reference, s.wings, D, p.poisson_ratio)});
    }
    return;
  }
  // A hinge belongs to the rank of its first triangle, whose stencil holds all four vertices.
  // Hinges whose second triangle only is here are kept for face_fields (its stencil holds the
  // four vertices too).
  for (const Hinge& h : disc.topology().hinges()) {
    const bool owned = layout.face_owner(h.faces[0]) == layout.rank();
    if (!owned && layout.face_owner(h.faces[1]) != layout.rank()) continue;
    const TriangleShellParameters& p = params_[body_of_face[h.faces[0]]];
    const double k = hinge_stiffness(p.youngs_modulus, p.poisson_ratio, p.thickness);
    Bend b;
    for (int i = 0; i < 4; ++i) b.nodes[i] = layout.local_of(h.v[i]);
    b.rest = HingeRest::from(X[h.v[0]], X[h.v[1]], X[h.v[2]], X[h.v[3]], k);
    b.elements = {element_index[h.faces[0]], element_index[h.faces[1]]};
    (owned ? hinges_ : shared_hinges_).push_back(b);
  }
}

// A free edge's wing slot holds any finite point (it is not used): its own corner.
void TriangleElasticTerm::plate_positions(const Plate& p, const std::vector<double>& u,
                                          std::array<Eigen::Vector3d, 6>& x) const {
  for (int i = 0; i < 3; ++i) {
    x[i] = position(u, p.nodes[i]);
    x[3 + i] = position(u, p.nodes[3 + i] >= 0 ? p.nodes[3 + i] : p.nodes[i]);
  }
}

Eigen::Vector3d TriangleElasticTerm::position(const std::vector<double>& u, PetscInt node) const {
  return reference_[node] + Eigen::Vector3d(u[3 * node], u[3 * node + 1], u[3 * node + 2]);
}

double TriangleElasticTerm::membrane_energy(const Membrane& m, const std::vector<double>& u,
                                            Vector9* g, Matrix9* H) const {
  const Eigen::Vector3d x0 = position(u, m.nodes[0]), x1 = position(u, m.nodes[1]),
                        x2 = position(u, m.nodes[2]);
  const MembraneParameters& lame = lame_[m.body];
  return params_[m.body].membrane == TriangleShellParameters::Membrane::kNeoHookean
             ? neo_hookean_membrane(m.rest, lame, x0, x1, x2, g, H)
             : stvk_membrane(m.rest, lame, x0, x1, x2, g, H);
}

PetscErrorCode TriangleElasticTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                        std::vector<double>* grad, Mat hess) const {
  PetscFunctionBeginUser;
  Vector9 g9;
  Matrix9 H9;
  std::vector<PetscInt> nodes(3);
  // The energy near rest cancels pieces of size ~ 2μτĀ (tr M − 2 − ln det M): its rounding
  // error is that of those pieces, not of the small result.
  std::vector<double> piece;
  for (const MembraneParameters& l : lame_)
    piece.push_back(2.0 * (l.mu + std::abs(l.lambda)) * l.thickness);
  for (const Membrane& m : membranes_) {
    const double e = membrane_energy(m, u, grad ? &g9 : nullptr, hess ? &H9 : nullptr);
    energy.add_with_magnitude(e, std::abs(e) + piece[m.body] * m.rest.area);
    if (!std::isfinite(e)) continue;  // the sum is +inf: the solver rejects the point
    nodes.assign(m.nodes.begin(), m.nodes.end());
    if (grad) add_local_gradient(nodes, g9.data(), *grad);
    if (hess) {
      if (projects_hessian()) project_stencil_hessian_to_psd(H9);
      PetscCall(add_local_hessian(hess, nodes, H9.data()));  // symmetric: row = column major
    }
  }
  std::array<Eigen::Vector3d, 6> x;
  for (const Plate& p : plates_) {
    plate_positions(p, u, x);
    PetscCall(add_midedge_element(p.rest, x, p.nodes, projects_hessian(), energy, grad, hess));
  }
  Vector12 g12;
  Matrix12 H12;
  nodes.resize(4);
  for (const Bend& b : hinges_) {
    const double e = hinge_bending(b.rest, position(u, b.nodes[0]), position(u, b.nodes[1]),
                                   position(u, b.nodes[2]), position(u, b.nodes[3]),
                                   grad ? &g12 : nullptr, hess ? &H12 : nullptr);
    energy.add(e);
    if (!std::isfinite(e)) continue;
    nodes.assign(b.nodes.begin(), b.nodes.end());
    if (grad) add_local_gradient(nodes, g12.data(), *grad);
    if (hess) {
      if (projects_hessian()) project_stencil_hessian_to_psd(H12);
      PetscCall(add_local_hessian(hess, nodes, H12.data()));
    }
  }
  PetscFunctionReturn(0);
}

void TriangleElasticTerm::face_fields(const std::vector<double>& u, std::vector<double>& strain,
                                      std::vector<double>& bending) const {
  strain.assign(membranes_.size(), 0.0);
  bending.assign(membranes_.size(), 0.0);
  for (size_t i = 0; i < membranes_.size(); ++i) {
    const Membrane& m = membranes_[i];
    const Eigen::Vector3d x0 = position(u, m.nodes[0]);
    Eigen::Matrix<double, 3, 2> D;
    D.col(0) = position(u, m.nodes[1]) - x0;
    D.col(1) = position(u, m.nodes[2]) - x0;
    // Green strain G = ½(Ā⁻¹A − I); its eigenvalues are the principal strains.
    const Eigen::Matrix2d G =
        0.5 * (m.rest.metric_inverse * (D.transpose() * D) - Eigen::Matrix2d::Identity());
    const Eigen::Vector2cd ev = G.eigenvalues();
    strain[i] = std::max(ev[0].real(), ev[1].real());
  }
  std::array<Eigen::Vector3d, 6> x;
  for (size_t i = 0; i < plates_.size(); ++i) {
    plate_positions(plates_[i], u, x);
    bending[i] = midedge_bending(plates_[i].rest, x, nullptr, nullptr);
  }
  for (const auto* list : {&hinges_, &shared_hinges_})
    for (const Bend& b : *list) {
      const double e =
          hinge_bending(b.rest, position(u, b.nodes[0]), position(u, b.nodes[1]),
                        position(u, b.nodes[2]), position(u, b.nodes[3]), nullptr, nullptr);
      for (int k : b.elements)
        if (k >= 0) bending[k] += 0.5 * e;
    }
}

}  // namespace mlshell
