// The shell prolongation of paper 2 (§4.3, eq. 4–9, footnote 2), pointwise:
//   P_i(x) = Σ_k w_k x_k + n(x) γ + R(F(x)) t,   F = (x₁ − x₀, x₂ − x₀) B̄⁻¹.
//
// The polar factor in closed form. Write F = Q G with Q = (q₁, q₂) an orthonormal basis of F's
// column space, q₁ × q₂ = n = f₁ × f₂ / |f₁ × f₂|, so det G = σ₁σ₂ = δ = |f₁ × f₂| > 0. For a 2×2
// G with positive determinant the polar rotation is (G + cof G)/(σ₁ + σ₂), cof G = J G Jᵀ with
// J the 90° rotation; and Q J Qᵀ is n × · on the plane, so
//   R(F) = (F + (n × F) Jᵀ)/τ = (f₁ − n × f₂, f₂ + n × f₁)/τ,   τ = σ₁ + σ₂ = √(‖F‖²_F + 2δ).
// This is U (I₂ 0)ᵀ Vᵀ of footnote 2 (= F (FᵀF)^{-1/2}) without an SVD, and polynomial in
// (F, n) over τ, so its derivative is a few lines. At rest F = (ē, n̄ × ē) and R = F.
//
// Degenerate deformed triangles (the thresholds are scale-free: F is a stretch against the rest
// triangle): rank 1, δ ≤ 1e-12 ‖F‖²_F (σ₂/σ₁ ≲ 1e-12): the normal is undefined, n = 0, and
// the same formula gives R = F/‖F‖_F — the in-plane offset follows the segment the triangle
// collapsed to, and keeps its length where the segment kept its rest length; rank 0,
// ‖F‖_F ≤ 1e-12: the offset is dropped and P_i is the anchor. The Jacobian is that of the
// branch taken, so it is finite wherever P is.
#include "mlshell/prolongation/shell_prolongation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mlshell {

namespace {

using Matrix32 = Eigen::Matrix<double, 3, 2>;

constexpr double kRankOne = 1e-12;   // δ / ‖F‖²_F below: a segment
constexpr double kRankZero = 1e-24;  // ‖F‖²_F below: a point

/// [a]× b = a × b.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

/// The deformed triangle's normal and polar factor, with what their derivatives need.
struct DeformedFrame {
  int rank = 2;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  double delta = 0.0;  // |f₁ × f₂|
  double tau = 0.0;    // √(‖F‖² + 2δ)
  Matrix32 R = Matrix32::Zero();
};

DeformedFrame deformed_frame(const Matrix32& F) {
  DeformedFrame d;
  const Eigen::Vector3d f1 = F.col(0), f2 = F.col(1);
  const double frobenius2 = F.squaredNorm();
  if (!(frobenius2 > kRankZero)) {
    d.rank = 0;
    return d;
  }
  const Eigen::Vector3d m = f1.cross(f2);
  d.delta = m.norm();
  if (d.delta > kRankOne * frobenius2) {
    d.n = m / d.delta;
    d.tau = std::sqrt(frobenius2 + 2.0 * d.delta);
    d.R.col(0) = (f1 - d.n.cross(f2)) / d.tau;
    d.R.col(1) = (f2 + d.n.cross(f1)) / d.tau;
  } else {
    d.rank = 1;
    d.delta = 0.0;
    d.tau = std::sqrt(frobenius2);
    d.R = F / d.tau;
  }
  return d;
}

std::string vertex_message(int i, const std::string& what) {
  std::ostringstream s;
  s << "ShellProlongation: fine vertex " << i << ": " << what;
  return s.str();
}

}  // namespace

Matrix32 polar_rotation(const Matrix32& F) { return deformed_frame(F).R; }

ShellProlongation::ShellProlongation(const TriangleMesh& coarse_rest,
                                     const std::vector<Point3>& fine_rest,
                                     std::vector<EmbeddedPoint> embedding)
    : embedding_(std::move(embedding)) {
  const int n = num_fine();
  if (fine_rest.size() != embedding_.size()) {
    std::ostringstream s;
    s << "ShellProlongation: " << fine_rest.size() << " fine rest points but " << embedding_.size()
      << " embedded points (one per fine vertex expected)";
    throw std::invalid_argument(s.str());
  }
  columns_.resize(n);
  rest_inverse_.resize(n);
  gamma_.resize(n);
  tangent_.resize(n);
  const int nc = coarse_rest.num_points();
  for (int i = 0; i < n; ++i) {
    const EmbeddedPoint& e = embedding_[i];
    if (e.triangle < 0 || e.triangle >= coarse_rest.num_triangles()) {
      std::ostringstream s;
      s << "triangle index " << e.triangle << " outside the coarse mesh's "
        << coarse_rest.num_triangles() << " triangles";
      throw std::invalid_argument(vertex_message(i, s.str()));
    }
    if (!e.weights.allFinite() || std::abs(e.weights.sum() - 1.0) > 1e-10) {
      std::ostringstream s;
      s << "barycentric weights (" << e.weights.transpose() << ") in coarse triangle " << e.triangle
        << " sum to " << e.weights.sum() << ", not 1 (within 1e-10)";
      throw std::invalid_argument(vertex_message(i, s.str()));
    }
    const Triangle& t = coarse_rest.triangles[e.triangle];
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= nc) {
        std::ostringstream s;
        s << "coarse triangle " << e.triangle << " names vertex " << t[k] << " of " << nc;
        throw std::invalid_argument(vertex_message(i, s.str()));
      }
    if (!fine_rest[i].allFinite())
      throw std::invalid_argument(vertex_message(i, "rest position is not finite"));
    columns_[i] = t;
    const Point3 &x0 = coarse_rest.points[t[0]], &x1 = coarse_rest.points[t[1]],
                 &x2 = coarse_rest.points[t[2]];
    const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0, cross = e1.cross(e2);
    const double longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (x2 - x1).squaredNorm()});
    // validate_triangle_mesh's test: twice the area ≤ 1e-12 × the longest edge squared.
    if (!(cross.norm() > 1e-12 * longest2)) {
      std::ostringstream s;
      s << "its coarse rest triangle " << e.triangle << " (vertices " << t[0] << ", " << t[1]
        << ", " << t[2] << ") is degenerate (twice its area " << cross.norm()
        << ", longest edge squared " << longest2 << ")";
      throw std::invalid_argument(vertex_message(i, s.str()));
    }
    const double l1 = e1.norm(), twice_area = cross.norm();
    Eigen::Matrix2d B;  // footnote 2: the rest edges in the frame (ē, n̄ × ē)
    B << l1, e1.dot(e2) / l1, 0.0, twice_area / l1;
    rest_inverse_[i] = B.inverse();
    const Eigen::Vector3d normal = cross / twice_area, edge = e1 / l1;
    const Eigen::Vector3d anchor = e.weights[0] * x0 + e.weights[1] * x1 + e.weights[2] * x2;
    const Eigen::Vector3d d = fine_rest[i] - anchor;
    gamma_[i] = normal.dot(d);
    tangent_[i] = Eigen::Vector2d(edge.dot(d), normal.cross(edge).dot(d));
  }
}

Point3 ShellProlongation::point(int i, const Point3& x0, const Point3& x1, const Point3& x2) const {
  const Eigen::Vector3d& w = embedding_[i].weights;
  Matrix32 E;
  E << x1 - x0, x2 - x0;
  const DeformedFrame d = deformed_frame(E * rest_inverse_[i]);
  return w[0] * x0 + w[1] * x1 + w[2] * x2 + d.n * gamma_[i] + d.R * tangent_[i];
}

// With a = τ R t = t₁(f₁ − n × f₂) + t₂(f₂ + n × f₁) and M = f₁ × f₂ (n = M/δ, δ = |M|):
//   ∂M/∂f₁ = −[f₂]×, ∂M/∂f₂ = [f₁]×,  ∂n/∂f_j = (I − n nᵀ) ∂M/∂f_j / δ,  ∂δ/∂f_j = nᵀ ∂M/∂f_j,
//   ∂τ/∂f_j = (f_jᵀ + ∂δ/∂f_j)/τ,
//   ∂a/∂f₁ = t₁ I + t₂ [n]× + K ∂n/∂f₁,  ∂a/∂f₂ = t₂ I − t₁ [n]× + K ∂n/∂f₂,
//   K = t₁ [f₂]× − t₂ [f₁]×,   ∂(R t)/∂f_j = ∂a/∂f_j / τ − a ∂τ/∂f_j / τ².
// Rank 1 (n = 0, δ = 0, τ = ‖F‖): ∂(R t)/∂f_j = t_j I/τ − (F t) f_jᵀ/τ³. Then the chain rule
// through F = (x₁ − x₀, x₂ − x₀) B̄⁻¹: ∂f_j/∂x₁ = B̄⁻¹(0, j) I, ∂f_j/∂x₂ = B̄⁻¹(1, j) I and
// ∂f_j/∂x₀ = −(both).
ShellProlongation::Jacobian ShellProlongation::jacobian(int i, const Point3& x0, const Point3& x1,
                                                        const Point3& x2) const {
  const Eigen::Vector3d& w = embedding_[i].weights;
  const Eigen::Matrix2d& Binv = rest_inverse_[i];
  const double gamma = gamma_[i];
  const Eigen::Vector2d& t = tangent_[i];
  Matrix32 E;
  E << x1 - x0, x2 - x0;
  const Matrix32 F = E * Binv;
  const Eigen::Vector3d f1 = F.col(0), f2 = F.col(1);
  const DeformedFrame d = deformed_frame(F);

  std::array<Eigen::Matrix3d, 2> D;  // ∂(n γ + R t)/∂f_j
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  if (d.rank == 2) {
    const std::array<Eigen::Matrix3d, 2> dM = {-cross_matrix(f2), cross_matrix(f1)};
    const Eigen::Matrix3d tangential = (I - d.n * d.n.transpose()) / d.delta;
    const Eigen::Vector3d a = d.tau * (d.R * t);
    const Eigen::Matrix3d K = t[0] * cross_matrix(f2) - t[1] * cross_matrix(f1);
    const Eigen::Matrix3d N = cross_matrix(d.n);
    const std::array<Eigen::Matrix3d, 2> a_direct = {t[0] * I + t[1] * N, t[1] * I - t[0] * N};
    for (int j = 0; j < 2; ++j) {
      const Eigen::Matrix3d dn = tangential * dM[j];
      const Eigen::RowVector3d ddelta = d.n.transpose() * dM[j];
      const Eigen::RowVector3d dtau = (F.col(j).transpose() + ddelta) / d.tau;
      const Eigen::Matrix3d da = a_direct[j] + K * dn;
      D[j] = gamma * dn + da / d.tau - a * dtau / (d.tau * d.tau);
    }
  } else if (d.rank == 1) {
    const Eigen::Vector3d Ft = F * t;
    const double tau3 = d.tau * d.tau * d.tau;
    for (int j = 0; j < 2; ++j) D[j] = t[j] * I / d.tau - Ft * F.col(j).transpose() / tau3;
  } else {
    D = {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
  }

  Jacobian J;
  const Eigen::Matrix3d d1 = Binv(0, 0) * D[0] + Binv(0, 1) * D[1];
  const Eigen::Matrix3d d2 = Binv(1, 0) * D[0] + Binv(1, 1) * D[1];
  J.block<3, 3>(0, 0) = w[0] * I - d1 - d2;
  J.block<3, 3>(0, 3) = w[1] * I + d1;
  J.block<3, 3>(0, 6) = w[2] * I + d2;
  return J;
}

std::vector<Point3> ShellProlongation::apply(const std::vector<Point3>& coarse) const {
  std::vector<Point3> fine(num_fine());
  for (int i = 0; i < num_fine(); ++i) {
    const Triangle& c = columns_[i];
    fine[i] = point(i, coarse.at(c[0]), coarse.at(c[1]), coarse.at(c[2]));
  }
  return fine;
}

}  // namespace mlshell
