// Kirchhoff–Love kinematics, closed-form strain derivatives, and through-thickness integration
// (see shell_kinematics.hpp).
#include "mlshell/shell/shell_kinematics.hpp"

#include <Eigen/Dense>

#include "mlshell/cross_matrix.hpp"
#include "mlshell/subdivision/subdivision_discretization.hpp"

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

void ShellSection::inspect(const ShellReference& ref, const Vector6& s,
                           MaterialReport& report) const {
  for (double z : z_) {
    const Strain3 e = ref.T * (s.head<3>() + z * s.tail<3>());
    report.add(material_.status(e), material_.energy_density(e, nullptr, nullptr));
  }
}

// Derivatives in closed form. With c = a₁ × a₂, s = |c|, n = c/s, P = I − n nᵀ:
//   ε11: ∂/∂δ₁ = a₁;  ε12: ∂/∂δ₁ = a₂/2, ∂/∂δ₂ = a₁/2;  ε22: ∂/∂δ₂ = a₂;
//   κ_q = b̄_q − a_q·n:  ∂/∂δ_q = −n,  ∂/∂δ₁ = −a₂ × g_q,  ∂/∂δ₂ = −g_q × a₁,  g_q = P a_q / s.
// For the weighted Hessian Σ_i w_i ∇²s_i the bending part is that of F = v·n with
// v = −Σ_q w_{3+q} a_q, through c(a₁, a₂) = a₁ × a₂ (dc = −[a₂]× da₁ + [a₁]× da₂):
//   ∂²F/∂c² = −[(n·v) P + n (Pv)ᵀ + (Pv) nᵀ]/s²,  ∂²F/∂a_q∂c = −w_{3+q} P/s,
//   ∂²F/∂a₁∂a₂ also holds −[∂F/∂c]×, the second derivative of the bilinear map c.
void shell_strains(const ShellReference& ref, const double delta[15], Vector6& s,
                   Eigen::Matrix<double, 6, 15>* ds, const Vector6* weights, Matrix15* hw) {
  Eigen::Vector3d d[5], a[5];
  for (int q = 0; q < 5; ++q) {
    d[q] = Eigen::Vector3d(delta[3 * q], delta[3 * q + 1], delta[3 * q + 2]);
    a[q] = ref.a[q] + d[q];
  }
  auto membrane = [&](int al, int be) {
    return 0.5 * (ref.a[al].dot(d[be]) + ref.a[be].dot(d[al])) + 0.5 * d[al].dot(d[be]);
  };
  const Eigen::Vector3d c = a[0].cross(a[1]);
  const double norm = c.norm();
  const Eigen::Vector3d n = c / norm;
  s << membrane(0, 0), membrane(0, 1), membrane(1, 1), ref.a[2].dot(ref.normal) - a[2].dot(n),
      ref.a[3].dot(ref.normal) - a[3].dot(n), ref.a[4].dot(ref.normal) - a[4].dot(n);
  if (!ds) return;
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
  ds->setZero();
  ds->block<1, 3>(0, 0) = a[0].transpose();
  ds->block<1, 3>(1, 0) = 0.5 * a[1].transpose();
  ds->block<1, 3>(1, 3) = 0.5 * a[0].transpose();
  ds->block<1, 3>(2, 3) = a[1].transpose();
  for (int q = 0; q < 3; ++q) {
    const Eigen::Vector3d g = P * a[2 + q] / norm;
    ds->block<1, 3>(3 + q, 3 * (2 + q)) = -n.transpose();
    ds->block<1, 3>(3 + q, 0) = -a[1].cross(g).transpose();
    ds->block<1, 3>(3 + q, 3) = -g.cross(a[0]).transpose();
  }
  if (!hw) return;
  const Vector6& w = *weights;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  hw->setZero();
  hw->block<3, 3>(0, 0) = w[0] * I;
  hw->block<3, 3>(0, 3) = 0.5 * w[1] * I;
  hw->block<3, 3>(3, 0) = 0.5 * w[1] * I;
  hw->block<3, 3>(3, 3) = w[2] * I;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int q = 0; q < 3; ++q) v -= w[3 + q] * a[2 + q];
  const Eigen::Vector3d Pv = P * v;
  const Eigen::Matrix3d Hc =
      -(n.dot(v) * P + n * Pv.transpose() + Pv * n.transpose()) / (norm * norm);
  const Eigen::Vector3d gc = Pv / norm;
  const Eigen::Matrix3d J1 = -cross_matrix(a[1]), J2 = cross_matrix(a[0]);  // ∂c/∂a₁, ∂c/∂a₂
  hw->block<3, 3>(0, 0) += J1.transpose() * Hc * J1;
  hw->block<3, 3>(3, 3) += J2.transpose() * Hc * J2;
  const Eigen::Matrix3d mixed = J1.transpose() * Hc * J2 - cross_matrix(gc);
  hw->block<3, 3>(0, 3) += mixed;
  hw->block<3, 3>(3, 0) += mixed.transpose();
  for (int q = 0; q < 3; ++q) {
    const Eigen::Matrix3d Aq = -w[3 + q] * P / norm;  // ∂²F/∂a_q∂c
    const int col = 3 * (2 + q);
    hw->block<3, 3>(col, 0) += Aq * J1;
    hw->block<3, 3>(col, 3) += Aq * J2;
    hw->block<3, 3>(0, col) += (Aq * J1).transpose();
    hw->block<3, 3>(3, col) += (Aq * J2).transpose();
  }
}

double shell_point_energy(const ShellReference& ref, const ShellSection& section,
                          const double delta[15], Vector15* g, Matrix15* H) {
  Vector6 s, gs;
  Eigen::Matrix<double, 6, 15> ds;
  Matrix6 Hs;
  const bool derivatives = g || H;
  shell_strains(ref, delta, s, nullptr, nullptr, nullptr);
  const double W = section.energy(ref, s, derivatives ? &gs : nullptr, H ? &Hs : nullptr);
  if (!derivatives) return ref.area * W;
  Matrix15 hw;
  shell_strains(ref, delta, s, &ds, &gs, H ? &hw : nullptr);
  if (g) *g = ref.area * (ds.transpose() * gs);
  if (H) *H = ref.area * (ds.transpose() * Hs * ds + hw);
  return ref.area * W;
}

}  // namespace mlshell
