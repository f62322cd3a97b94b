// Membrane and bending energy of the shell: quadrature of shell_point_energy over the elements.
#include <Eigen/Dense>
#include <algorithm>

#include "mlshell/effects.hpp"
#include "mlshell/psd_projection.hpp"

namespace mlshell {

ShellElasticTerm::ShellElasticTerm(const SubdivisionDiscretization& disc,
                                   const ParallelLayout& layout, const MaterialSpec& material)
    : EnergyTerm("elastic"),
      disc_(disc),
      material_(make_material(material)),
      section_(*material_, material.thickness, material.thickness_points),
      rounding_(material_->rounding_factor()) {
  const Eigen::Vector3d warp(material.warp[0], material.warp[1], material.warp[2]);
  const auto& X = disc.mesh().points;
  const int ng = disc.num_quadrature_points();
  for (int f : layout.local_elements()) {
    const ElementBasis b = disc.element_basis(f);
    elements_.push_back(
        {to_local_nodes(layout, b.nodes, b.size), b, static_cast<int>(references_.size())});
    for (int g = 0; g < ng; ++g) {
      Eigen::Vector3d a[5];
      for (int p = 0; p < 5; ++p) {
        a[p].setZero();
        const double* w = b.slot(g, kDu + p);
        for (int i = 0; i < b.size; ++i) a[p] += w[i] * X[b.nodes[i]];
      }
      references_.push_back(ShellReference::from(a, warp));
    }
  }
}

void ShellElasticTerm::surface_quantities(const Element& e, int g, const std::vector<double>& u,
                                          double delta[15]) const {
  std::fill(delta, delta + 15, 0.0);
  for (int p = 0; p < 5; ++p) {
    const double* w = e.basis.slot(g, kDu + p);
    for (int i = 0; i < e.basis.size; ++i)
      for (int c = 0; c < 3; ++c) delta[3 * p + c] += w[i] * u[3 * e.nodes[i] + c];
  }
}

void ShellElasticTerm::inspect(const std::vector<double>& u, MaterialReport& report) const {
  const int ng = disc_.num_quadrature_points();
  for (const Element& e : elements_)
    for (int g = 0; g < ng; ++g) {
      double delta[15];
      surface_quantities(e, g, u, delta);
      Vector6 s;
      const ShellReference& ref = references_[e.first_reference + g];
      shell_strains(ref, delta, s, nullptr, nullptr, nullptr);
      section_.inspect(ref, s, report);
    }
}

namespace {

// The element Hessian Σ_g qw_g B_gᵀ H_g B_g, where B_g = W_g ⊗ I₃ maps the element's 3n dofs to
// the 15 surface quantities (W_g: the 5 × n weights of δ_1, δ_2, δ_11, δ_12, δ_22 at point g),
// as one dense product: with 𝕎 the 5ng × n stack of the W_g and, for each pair of components
// (c, d), T_cd the 5ng × n stack of Σ_q qw_g H_g(3p + c, 3q + d) W_g(q, ·), its (c, d)
// components are He_cd = 𝕎ᵀ T_cd. He is symmetric, so only the six pairs c ≤ d are formed.
class ElementHessian {
 public:
  static constexpr int kPairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};

  void start(const ElementBasis& b, int ng) {
    n_ = b.size;
    W_.resize(5 * ng, n_);
    for (int g = 0; g < ng; ++g)
      for (int p = 0; p < 5; ++p)
        W_.row(5 * g + p) = Eigen::Map<const Eigen::RowVectorXd>(b.slot(g, kDu + p), n_);
    T_.resize(5 * ng, 6 * n_);
  }

  void add_point(int g, const Matrix15& H, double qw) {
    const auto Wg = W_.middleRows(5 * g, 5);
    for (int k = 0; k < 6; ++k) {
      const int c = kPairs[k][0], d = kPairs[k][1];
      Eigen::Matrix<double, 5, 5> Hcd;
      for (int p = 0; p < 5; ++p)
        for (int q = 0; q < 5; ++q) Hcd(p, q) = qw * H(3 * p + c, 3 * q + d);
      T_.block(5 * g, k * n_, 5, n_).noalias() = Hcd * Wg;
    }
  }

  /// The 3n × 3n row-major element Hessian into He.
  void finish(std::vector<double>& He) {
    P_.noalias() = W_.transpose() * T_;
    const int w = 3 * n_;
    for (int k = 0; k < 6; ++k) {
      const int c = kPairs[k][0], d = kPairs[k][1];
      for (int j = 0; j < n_; ++j)
        for (int i = 0; i < n_; ++i) {
          const double v = P_(i, k * n_ + j);
          He[(3 * i + c) * w + 3 * j + d] = v;
          He[(3 * j + d) * w + 3 * i + c] = v;
        }
    }
  }

 private:
  int n_ = 0;
  Eigen::MatrixXd W_, T_, P_;
};

}  // namespace

PetscErrorCode ShellElasticTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                     std::vector<double>* grad, Mat hess) const {
  PetscFunctionBeginUser;
  const int ng = disc_.num_quadrature_points();
  std::vector<double> ge, He;
  Vector15 g15;
  Matrix15 H15;
  ElementHessian element_hessian;
  for (const Element& e : elements_) {
    const int n = e.basis.size;
    if (grad) ge.assign(3 * n, 0.0);
    if (hess) {
      He.resize(9 * n * n);
      element_hessian.start(e.basis, ng);
    }
    for (int g = 0; g < ng; ++g) {
      double delta[15];
      surface_quantities(e, g, u, delta);
      const double qw = disc_.quadrature_weight(g);
      const double W = shell_point_energy(references_[e.first_reference + g], section_, delta,
                                          grad ? &g15 : nullptr, hess ? &H15 : nullptr);
      energy.add(qw * W, rounding_);
      if (grad)
        for (int p = 0; p < 5; ++p) {
          const double* w = e.basis.slot(g, kDu + p);
          for (int i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) ge[3 * i + c] += qw * w[i] * g15[3 * p + c];
        }
      if (hess) element_hessian.add_point(g, H15, qw);
    }
    if (grad) add_local_gradient(e.nodes, ge.data(), *grad);
    if (hess) {
      element_hessian.finish(He);
      if (projects_hessian()) project_to_psd(Eigen::Map<Eigen::MatrixXd>(He.data(), 3 * n, 3 * n));
      PetscCall(add_local_hessian(hess, e.nodes, He.data()));
    }
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
