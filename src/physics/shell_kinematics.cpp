// Kirchhoff–Love kinematics and through-thickness integration (see shell_kinematics.hpp).
#include "mlshell/shell_kinematics.hpp"

#include <Eigen/Dense>

#include "mlshell/discretization.hpp"
#include "mlshell/jet.hpp"

namespace mlshell {

ShellReference ShellReference::from(const Eigen::Vector3d a[5], const Eigen::Vector3d& warp) {
  ShellReference r;
  for (int i = 0; i < 5; ++i) r.a[i] = a[i];
  const Eigen::Vector3d c = a[0].cross(a[1]);
  r.area = c.norm();
  r.normal = c / r.area;
  // Material frame: o1 = warp projected onto the tangent plane (a_1 if the warp is normal).
  Eigen::Vector3d o1 = warp - warp.dot(r.normal) * r.normal;
  if (o1.norm() < 1e-8 * warp.norm()) o1 = a[0];
  o1.normalize();
  const Eigen::Vector3d o2 = r.normal.cross(o1);
  // Contravariant basis Ā^α = ā^{αβ} ā_β.
  Eigen::Matrix2d metric;
  metric << a[0].dot(a[0]), a[0].dot(a[1]), a[1].dot(a[0]), a[1].dot(a[1]);
  const Eigen::Matrix2d inv = metric.inverse();
  const Eigen::Vector3d A1 = inv(0, 0) * a[0] + inv(0, 1) * a[1];
  const Eigen::Vector3d A2 = inv(1, 0) * a[0] + inv(1, 1) * a[1];
  const double t[2][2] = {{o1.dot(A1), o1.dot(A2)}, {o2.dot(A1), o2.dot(A2)}};
  // Ẽ_ij = t_iα t_jβ E_αβ with E_12 = E_21; columns: E11, E12, E22.
  auto row = [&](int i, int j) {
    return Eigen::RowVector3d(t[i][0] * t[j][0], t[i][0] * t[j][1] + t[i][1] * t[j][0],
                              t[i][1] * t[j][1]);
  };
  r.T.row(0) = row(0, 0);
  r.T.row(1) = row(1, 1);
  r.T.row(2) = row(0, 1);
  return r;
}

ShellSection::ShellSection(const Material& material, double thickness, int points)
    : material_(material), thickness_(thickness) {
  const GaussRule rule(points);
  for (int k = 0; k < points; ++k) {
    z_.push_back((rule.points[k] - 0.5) * thickness);
    w_.push_back(rule.weights[k] * thickness);
  }
}

double ShellSection::energy(const ShellReference& ref, const Vector6& s, Vector6* g,
                            Matrix6* H) const {
  double W = 0.0;
  if (g) g->setZero();
  if (H) H->setZero();
  Eigen::Vector3d dpsi;
  Eigen::Matrix3d ddpsi;
  for (size_t k = 0; k < z_.size(); ++k) {
    const Eigen::Vector3d E = s.head<3>() + z_[k] * s.tail<3>();
    const Strain3 e = ref.T * E;
    W += w_[k] * material_.energy_density(e, g ? &dpsi : nullptr, H ? &ddpsi : nullptr);
    if (g) {
      const Eigen::Vector3d gE = w_[k] * (ref.T.transpose() * dpsi);
      g->head<3>() += gE;
      g->tail<3>() += z_[k] * gE;
    }
    if (H) {
      const Eigen::Matrix3d HE = w_[k] * (ref.T.transpose() * ddpsi * ref.T);
      H->topLeftCorner<3, 3>() += HE;
      H->topRightCorner<3, 3>() += z_[k] * HE;
      H->bottomLeftCorner<3, 3>() += z_[k] * HE;
      H->bottomRightCorner<3, 3>() += z_[k] * z_[k] * HE;
    }
  }
  return W;
}

namespace {

/// s(δ) with jets J (first or second order).
template <class J>
void strains_with_jets(const ShellReference& ref, const double delta[15], Vector6& s,
                       Eigen::Matrix<double, 6, 15>* ds, Eigen::Matrix<double, 15, 15>* dds) {
  // Deformed quantities a = ā + δ as jets.
  J a[5][3];
  for (int q = 0; q < 5; ++q)
    for (int c = 0; c < 3; ++c) a[q][c] = J::variable(delta[3 * q + c], 3 * q + c) + ref.a[q][c];
  // Membrane: ε_αβ = ā_(α·δ_β) + ½ δ_α·δ_β, from jets of δ only (no cancellation).
  J d[2][3];
  for (int q = 0; q < 2; ++q)
    for (int c = 0; c < 3; ++c) d[q][c] = J::variable(delta[3 * q + c], 3 * q + c);
  auto membrane = [&](int al, int be) {
    J e = J::constant(0.0);
    for (int c = 0; c < 3; ++c)
      e = e + 0.5 * (ref.a[al][c] * d[be][c] + ref.a[be][c] * d[al][c]) + 0.5 * (d[al][c] * d[be][c]);
    return e;
  };
  // Bending: κ_αβ = ā_αβ·ā₃ − a_αβ·(a₁ × a₂)/|a₁ × a₂|.
  J cr[3] = {a[0][1] * a[1][2] - a[0][2] * a[1][1], a[0][2] * a[1][0] - a[0][0] * a[1][2],
             a[0][0] * a[1][1] - a[0][1] * a[1][0]};
  const J inv_norm = inverse(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]));
  auto bending = [&](int q) {
    const J p = a[q][0] * cr[0] + a[q][1] * cr[1] + a[q][2] * cr[2];
    return (-1.0 * (p * inv_norm)) + ref.a[q].dot(ref.normal);
  };
  const J strains[6] = {membrane(0, 0), membrane(0, 1), membrane(1, 1),
                        bending(2),     bending(3),     bending(4)};
  for (int i = 0; i < 6; ++i) {
    s[i] = strains[i].v;
    if (ds)
      for (int k = 0; k < 15; ++k) (*ds)(i, k) = strains[i].g[k];
  }
  if constexpr (J::kSecond)
    if (dds)
      for (int i = 0; i < 6; ++i)
        for (int k = 0; k < 15 * 15; ++k) dds[i].data()[k] = strains[i].h[k];
}

/// s(δ) in plain arithmetic, for energy-only evaluations.
void strain_values(const ShellReference& ref, const double delta[15], Vector6& s) {
  Eigen::Vector3d d[5], a[5];
  for (int q = 0; q < 5; ++q) {
    d[q] = Eigen::Vector3d(delta[3 * q], delta[3 * q + 1], delta[3 * q + 2]);
    a[q] = ref.a[q] + d[q];
  }
  auto membrane = [&](int al, int be) {
    return 0.5 * (ref.a[al].dot(d[be]) + ref.a[be].dot(d[al])) + 0.5 * d[al].dot(d[be]);
  };
  const Eigen::Vector3d n = a[0].cross(a[1]).normalized();
  s << membrane(0, 0), membrane(0, 1), membrane(1, 1), ref.a[2].dot(ref.normal) - a[2].dot(n),
      ref.a[3].dot(ref.normal) - a[3].dot(n), ref.a[4].dot(ref.normal) - a[4].dot(n);
}

}  // namespace

void shell_strains(const ShellReference& ref, const double delta[15], Vector6& s,
                   Eigen::Matrix<double, 6, 15>* ds, Eigen::Matrix<double, 15, 15>* dds) {
  if (dds) strains_with_jets<Jet<15, true>>(ref, delta, s, ds, dds);
  else if (ds) strains_with_jets<Jet<15, false>>(ref, delta, s, ds, nullptr);
  else strain_values(ref, delta, s);
}



double shell_point_energy(const ShellReference& ref, const ShellSection& section,
                          const double delta[15], Vector15* g, Matrix15* H) {
  Vector6 s;
  Eigen::Matrix<double, 6, 15> ds;
  Eigen::Matrix<double, 15, 15> dds[6];
  const bool derivatives = g || H;
  shell_strains(ref, delta, s, derivatives ? &ds : nullptr, H ? dds : nullptr);
  Vector6 gs;
  Matrix6 Hs;
  const double W = section.energy(ref, s, derivatives ? &gs : nullptr, H ? &Hs : nullptr);
  if (g) *g = ref.area * (ds.transpose() * gs);
  if (H) {
    *H = ds.transpose() * Hs * ds;
    for (int i = 0; i < 6; ++i) *H += gs[i] * dds[i];
    *H *= ref.area;
  }
  return ref.area * W;
}

}  // namespace mlshell
