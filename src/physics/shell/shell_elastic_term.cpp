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

PetscErrorCode ShellElasticTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                     std::vector<double>* grad, Mat hess) const {
  PetscFunctionBeginUser;
  const int ng = disc_.num_quadrature_points();
  std::vector<double> ge, He;
  Vector15 g15;
  Matrix15 H15;
  Eigen::Matrix<double, 3, 15> A;
  for (const Element& e : elements_) {
    const int n = e.basis.size;
    if (grad) ge.assign(3 * n, 0.0);
    if (hess) He.assign(9 * n * n, 0.0);
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
      if (hess) {
        // He(i,j) = Σ_pq B_p,i B_q,j H15(p,q): first A_i = Σ_p B_p,i H15(p, :).
        for (int i = 0; i < n; ++i) {
          A.setZero();
          for (int p = 0; p < 5; ++p) A += e.basis.slot(g, kDu + p)[i] * H15.middleRows<3>(3 * p);
          A *= qw;
          for (int j = i; j < n; ++j) {  // upper blocks; the lower ones by symmetry below
            Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
            for (int q = 0; q < 5; ++q)
              block += e.basis.slot(g, kDu + q)[j] * A.middleCols<3>(3 * q);
            for (int c = 0; c < 3; ++c)
              for (int d = 0; d < 3; ++d) He[(3 * i + c) * 3 * n + 3 * j + d] += block(c, d);
          }
        }
      }
    }
    if (hess) {
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < i; ++j)
          for (int c = 0; c < 3; ++c)
            for (int d = 0; d < 3; ++d)
              He[(3 * i + c) * 3 * n + 3 * j + d] = He[(3 * j + d) * 3 * n + 3 * i + c];
    }
    if (grad) add_local_gradient(e.nodes, ge.data(), *grad);
    if (hess) {
      if (projects_hessian()) project_to_psd(Eigen::Map<Eigen::MatrixXd>(He.data(), 3 * n, 3 * n));
      PetscCall(add_local_hessian(hess, e.nodes, He.data()));
    }
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
