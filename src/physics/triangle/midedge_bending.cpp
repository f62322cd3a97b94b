// Midedge-normal bending of one triangle (see midedge_bending.hpp).
//
// Derivatives. With the hinge of edge i on the element slots (i+1, i+2, i, 3+i) and J the 3×18
// matrix whose row i is ∇θ_i there (zero for free edges),
//   ∇W = Jᵀ K δθ,   ∇²W = Jᵀ K J + Σ_i (K δθ)_i ∇²θ_i,
// with ∇θ_i and ∇²θ_i the closed forms of hinge_bending.cpp. The result is symmetric up to the
// round-off of the second sum, which is symmetrised away.
#include "mlshell/triangle/midedge_bending.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "mlshell/triangle/hinge_bending.hpp"
#include "mlshell/triangle/membrane.hpp"

namespace mlshell {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// The element slots of the hinge of edge i, in dihedral_angle's order (x0, x1, x2, x3).
std::array<int, 4> hinge_slots(int i) { return {(i + 1) % 3, (i + 2) % 3, i, 3 + i}; }

/// The hinge of edge i: the edge from x_{i+1} to x_{i+2}, x_i and the wing.
void hinge_of(const std::array<Eigen::Vector3d, 6>& x, int i, Eigen::Vector3d h[4]) {
  const auto s = hinge_slots(i);
  for (int k = 0; k < 4; ++k) h[k] = x[s[k]];
}

}  // namespace

double plate_stiffness(double E, double nu, double thickness) {
  return E * thickness * thickness * thickness / (12.0 * (1.0 - nu * nu));
}

MidedgeRest MidedgeRest::from(const std::array<Eigen::Vector3d, 6>& X,
                              const std::array<EdgeWing, 3>& wings, double plate_stiffness,
                              double poisson_ratio) {
  for (int v = 0; v < 6; ++v)
    if ((v < 3 || wings[v - 3] != EdgeWing::kFree) && !X[v].allFinite())
      throw std::invalid_argument("MidedgeRest: rest position is not finite");
  const TriangleRest tri = TriangleRest::from(X[0], X[1], X[2]);  // throws if degenerate
  MidedgeRest rest;
  // K in the tilts, then scaled to the angles: δt_i = −c_i h̄_i δθ_i (the sign is common to all
  // edges and drops out of the quadratic form).
  const Eigen::Matrix2d G[3] = {(Eigen::Matrix2d() << 2, 2, 2, 2).finished(),
                                (Eigen::Matrix2d() << 2, 0, 0, 0).finished(),
                                (Eigen::Matrix2d() << 0, 0, 0, 2).finished()};
  Eigen::Matrix2d M[3];
  for (int i = 0; i < 3; ++i) M[i] = tri.metric_inverse * G[i];
  const double nu = poisson_ratio;
  Eigen::Matrix3d K;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      K(i, j) = tri.area * plate_stiffness *
                (nu * M[i].trace() * M[j].trace() + (1.0 - nu) * (M[i] * M[j]).trace());
  Eigen::Vector3d scale;
  for (int i = 0; i < 3; ++i) {
    const double height = 2.0 * tri.area / (X[(i + 2) % 3] - X[(i + 1) % 3]).norm();
    scale[i] = (wings[i] == EdgeWing::kClamp ? 1.0 : 0.5) * height;
  }
  K = scale.asDiagonal() * K * scale.asDiagonal();
  // Eliminate the free edges' tilts: the Schur complement on the edges with a wing.
  int free_edges[3], wing_edges[3], nf = 0, nw = 0;
  for (int i = 0; i < 3; ++i) {
    rest.active[i] = wings[i] != EdgeWing::kFree;
    (rest.active[i] ? wing_edges[nw++] : free_edges[nf++]) = i;
  }
  Eigen::MatrixXd Kww(nw, nw), Kwf(nw, nf), Kff(nf, nf);
  for (int a = 0; a < nw; ++a) {
    for (int b = 0; b < nw; ++b) Kww(a, b) = K(wing_edges[a], wing_edges[b]);
    for (int b = 0; b < nf; ++b) Kwf(a, b) = K(wing_edges[a], free_edges[b]);
  }
  for (int a = 0; a < nf; ++a)
    for (int b = 0; b < nf; ++b) Kff(a, b) = K(free_edges[a], free_edges[b]);
  if (nf > 0 && nw > 0) Kww -= Kwf * Kff.llt().solve(Kwf.transpose());
  for (int a = 0; a < nw; ++a)
    for (int b = 0; b < nw; ++b)
      rest.stiffness(wing_edges[a], wing_edges[b]) = 0.5 * (Kww(a, b) + Kww(b, a));
  for (int i = 0; i < 3; ++i) {
    if (!rest.active[i]) continue;
    Eigen::Vector3d h[4];
    hinge_of(X, i, h);
    if (!dihedral_angle_derivatives(h, rest.angles[i], nullptr, nullptr))
      throw std::invalid_argument("MidedgeRest: degenerate rest hinge (zero edge or normal)");
  }
  return rest;
}

double midedge_bending(const MidedgeRest& rest, const std::array<Eigen::Vector3d, 6>& x,
                       Vector18* grad, Matrix18* hess) {
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 18> J = Eigen::Matrix<double, 3, 18>::Zero();
  Matrix12 ddtheta[3];
  const bool derivatives = grad || hess;
  for (int i = 0; i < 3; ++i) {
    if (!rest.active[i]) continue;
    Eigen::Vector3d h[4];
    hinge_of(x, i, h);
    for (const auto& p : h)
      if (!p.allFinite()) return kInfinity;
    double theta = 0.0;
    Vector12 dtheta;
    if (!dihedral_angle_derivatives(h, theta, derivatives ? &dtheta : nullptr,
                                    hess ? &ddtheta[i] : nullptr))
      return kInfinity;
    delta[i] = wrap_angle(theta - rest.angles[i]);
    if (!derivatives) continue;
    const auto s = hinge_slots(i);
    for (int k = 0; k < 4; ++k) J.block<1, 3>(i, 3 * s[k]) = dtheta.segment<3>(3 * k).transpose();
  }
  const Eigen::Vector3d moment = rest.stiffness * delta;  // K δθ
  const double energy = 0.5 * delta.dot(moment);
  if (!std::isfinite(energy)) return kInfinity;
  if (!derivatives) return energy;
  const Vector18 g = J.transpose() * moment;
  Matrix18 H;
  if (hess) {
    H = J.transpose() * rest.stiffness * J;
    for (int i = 0; i < 3; ++i) {
      if (!rest.active[i] || moment[i] == 0.0) continue;
      const auto s = hinge_slots(i);
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          H.block<3, 3>(3 * s[a], 3 * s[b]) += moment[i] * ddtheta[i].block<3, 3>(3 * a, 3 * b);
    }
    H = 0.5 * (H + H.transpose()).eval();
  }
  if ((grad && !g.allFinite()) || (hess && !H.allFinite())) return kInfinity;
  if (grad) *grad = g;
  if (hess) *hess = H;
  return energy;
}

}  // namespace mlshell
