// Pressure work on a closed triangle surface (see triangle_effects.hpp).
//
// Each face's share of the enclosed volume is written about a fixed centre c, the centroid of
// the rest points (computed once, over all ranks):
//   V(x) = Σ_t V_t(x − c),   V_t(y) = y₀·(y₁ × y₂)/6   (enclosed_volume.hpp).
// On a closed surface Σ_t n_t = 0 makes the sum independent of c, so the energy, gradient and
// Hessian of the whole term are those of −p (V(x) − V(X)) whatever c is. One face's Hessian is
// not: ∇²V_t has the blocks ±[y_k]×/6, so it grows with the distance of the face from the
// origin and changes when the body is translated. About the body's own centre each block has
// the body's size, and translating the scene (X and x together) leaves every block as it was.
// That makes the per-face projection onto the PSD cone of projected Newton (paper 2 §4.5,
// -mlshell_hessian_psd) meaningful: P(−p∇²V_t(x − c)) does not depend on where the body sits.
// ∇²V_t has zero trace (its diagonal blocks vanish), so it is indefinite unless it is zero;
// its projection adds curvature the exact Hessian lacks, which the line search absorbs.
// Without -mlshell_hessian_psd the exact (indefinite) Hessian is assembled.
#include <mpi.h>

#include <algorithm>

#include "mlshell/psd_projection.hpp"
#include "mlshell/triangle/enclosed_volume.hpp"
#include "mlshell/triangle/triangle_effects.hpp"

namespace mlshell {

double pressure_element(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                        const Eigen::Vector3d& x2, const Eigen::Vector3d& centre, double pressure,
                        bool project, Vector9* grad, Matrix9* hess) {
  const double v = triangle_volume(x0 - centre, x1 - centre, x2 - centre, grad, hess);
  if (grad) *grad *= -pressure;
  if (hess) {
    *hess *= -pressure;
    if (project) project_to_psd(*hess);
  }
  return -pressure * v;
}

PressureTerm::PressureTerm(const TriangleDiscretization& disc, const ParallelLayout& layout,
                           double pressure, double ramp_time)
    : EnergyTerm("pressure"), pressure_(pressure), ramp_time_(ramp_time) {
  for (int v : layout.local_points()) reference_.push_back(disc.points()[v]);
  // c: the mean of the rest points, each counted on its owner rank.
  double sums[4] = {0.0, 0.0, 0.0, static_cast<double>(layout.num_owned_points())};
  for (int i = 0; i < layout.num_owned_points(); ++i)
    for (int k = 0; k < 3; ++k) sums[k] += reference_[i][k];
  MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, layout.comm());
  if (sums[3] > 0.0) centre_ = Eigen::Vector3d(sums[0], sums[1], sums[2]) / sums[3];
  const auto& X = disc.points();
  for (int f : layout.local_elements()) {
    const Triangle& t = disc.mesh().triangles[f];
    elements_.push_back({layout.local_of(t[0]), layout.local_of(t[1]), layout.local_of(t[2])});
    reference_volume_ +=
        triangle_volume(X[t[0]] - centre_, X[t[1]] - centre_, X[t[2]] - centre_, nullptr, nullptr);
  }
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
  Vector9 g;
  Matrix9 H;
  std::vector<PetscInt> nodes(3);
  for (const auto& e : elements_) {
    Eigen::Vector3d x[3];
    for (int k = 0; k < 3; ++k)
      x[k] = reference_[e[k]] + Eigen::Vector3d(u[3 * e[k]], u[3 * e[k] + 1], u[3 * e[k] + 2]);
    energy.add(pressure_element(x[0], x[1], x[2], centre_, p, projects_hessian(),
                                grad ? &g : nullptr, hess ? &H : nullptr));
    nodes.assign(e.begin(), e.end());
    if (grad) add_local_gradient(nodes, g.data(), *grad);
    if (hess) PetscCall(add_local_hessian(hess, nodes, H.data()));
  }
  energy.add(p * reference_volume_);
  PetscFunctionReturn(0);
}

}  // namespace mlshell
