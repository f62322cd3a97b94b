// Pressure work on a closed triangle surface (see triangle_effects.hpp).
//
// The energy −p (V(x) − V(X)) and its gradient are summed over the faces,
// V = Σ_t x₀·(x₁ × x₂)/6 (enclosed_volume.hpp). The Hessian is summed over the edges: V is
// linear in each vertex, so the diagonal blocks of ∇²V vanish, and two vertices a, b are
// coupled only through the two faces of their edge, (a, b, c) and (b, a, d) (Hinge's order).
// From the face blocks of enclosed_volume.cpp ((0, 1) = ∂²V_t/∂x₀∂x₁ = −[x₂]×/6):
// ∂²V_{abc}/∂x_a∂x_b = −[x_c]×/6 and ∂²V_{bad}/∂x_a∂x_b = (−[x_d]×/6)ᵀ = [x_d]×/6, so
//   ∂²V/∂x_a∂x_b = −[w]×/6,   w = x_c − x_d,
// so −p∇²V = Σ_e M_e, M_e = [[0, S], [Sᵀ, 0]] on (x_a, x_b) with S = (p/6)[w]×. Unlike a single
// face's block (±[x_k]×/6, which grows with the distance from the origin), M_e depends on a
// difference of positions only: it has the size p·h of the mesh and no centre is needed.
//
// When asked (set_hessian_projection: -mlshell_hessian_psd with -mlshell_pressure_psd,
// term_hessian_projection in step_solver.hpp) each M_e is projected onto the PSD cone in closed
// form. With S = UΣVᵀ, M_e has the eigenpairs ±σ_i, (u_i; ±v_i)/√2, so
//   P(M_e) = ½ [[(SSᵀ)^½, S], [Sᵀ, (SᵀS)^½]] = ½ M_e + ½ blockdiag((SSᵀ)^½, (SᵀS)^½),
// and for S = s[w]×: SSᵀ = SᵀS = s²(|w|² I − w wᵀ), whose square root is |s| |w| (I − ŵŵᵀ)
// (I − ŵŵᵀ is a projector). The added curvature, (|p|/12)(|w| I − w wᵀ/|w|) on each of a and b,
// is of order p·h per edge, where projecting a whole face's 9 × 9 block (zero trace, so always
// indefinite) adds p·R for a body of size R. Either makes Newton linear on a stable balloon,
// whose exact Hessian the membrane keeps positive definite, so by default the exact Hessian is
// assembled also under projected Newton (docs/solvers.md has the counts).
// Each edge is assembled once, by the rank of its first face (Hinge::faces[0]), whose stencil
// holds all four vertices, as the elastic term's hinges are.
#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "mlshell/cross_matrix.hpp"
#include "mlshell/triangle/enclosed_volume.hpp"
#include "mlshell/triangle/triangle_effects.hpp"

namespace mlshell {

Matrix6d pressure_edge_hessian(const Eigen::Vector3d& xc, const Eigen::Vector3d& xd,
                               double pressure, bool project) {
  const Eigen::Vector3d w = xc - xd;
  const Eigen::Matrix3d S = (pressure / 6.0) * cross_matrix(w);
  Matrix6d M;
  M << Eigen::Matrix3d::Zero(), S, S.transpose(), Eigen::Matrix3d::Zero();
  if (!project) return M;
  M *= 0.5;
  const double length = w.norm();
  if (length > 0.0) {
    const Eigen::Matrix3d P = (std::abs(pressure) / 12.0) *
                              (length * Eigen::Matrix3d::Identity() - w * w.transpose() / length);
    M.block<3, 3>(0, 0) = P;
    M.block<3, 3>(3, 3) = P;
  }
  return M;
}

PressureTerm::PressureTerm(const TriangleDiscretization& disc, const ParallelLayout& layout,
                           double pressure, double ramp_time)
    : EnergyTerm("pressure"), pressure_(pressure), ramp_time_(ramp_time) {
  for (int v : layout.local_points()) reference_.push_back(disc.points()[v]);
  const auto& X = disc.points();
  for (int f : layout.local_elements()) {
    const Triangle& t = disc.mesh().triangles[f];
    elements_.push_back({layout.local_of(t[0]), layout.local_of(t[1]), layout.local_of(t[2])});
    reference_volume_ += triangle_volume(X[t[0]], X[t[1]], X[t[2]], nullptr, nullptr);
  }
  for (const Hinge& h : disc.topology().hinges())
    if (layout.face_owner(h.faces[0]) == layout.rank())
      edges_.push_back({layout.local_of(h.v[0]), layout.local_of(h.v[1]), layout.local_of(h.v[2]),
                        layout.local_of(h.v[3])});
  // Each face is assembled on one rank (its owner): the sum is V(X), each face counted once.
  enclosed_volume_ = reference_volume_;
  MPI_Allreduce(MPI_IN_PLACE, &enclosed_volume_, 1, MPI_DOUBLE, MPI_SUM, layout.comm());
}

double PressureTerm::scale() const {
  return ramp_time_ > 0.0 ? std::clamp(time_ / ramp_time_, 0.0, 1.0) : 1.0;
}

PetscErrorCode PressureTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                 std::vector<double>* grad, Mat hess) const {
  PetscFunctionBeginUser;
  const double p = scale() * pressure_;
  auto position = [&](PetscInt node) -> Eigen::Vector3d {
    return reference_[node] + Eigen::Vector3d(u[3 * node], u[3 * node + 1], u[3 * node + 2]);
  };
  Vector9 g;
  std::vector<PetscInt> nodes(3);
  for (const auto& e : elements_) {
    const double v = triangle_volume(position(e[0]), position(e[1]), position(e[2]),
                                     grad ? &g : nullptr, nullptr);
    energy.add(-p * v);
    if (grad) {
      g *= -p;
      nodes.assign(e.begin(), e.end());
      add_local_gradient(nodes, g.data(), *grad);
    }
  }
  energy.add(p * reference_volume_);
  if (hess) {
    nodes.resize(2);
    for (const auto& e : edges_) {
      const Matrix6d M =
          pressure_edge_hessian(position(e[2]), position(e[3]), p, projects_hessian());
      nodes = {e[0], e[1]};
      PetscCall(add_local_hessian(hess, nodes, M.data()));  // symmetric: row = column major
    }
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
