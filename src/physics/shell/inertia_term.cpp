// Implicit Euler inertia (paper §3.1.1): the kinetic term of the incremental potential,
// ρ/(2 dt²) ∫ |u − û|² dA with û = u_n + dt v_n; its minimiser satisfies the Euler step.
#include "mlshell/effects.hpp"

namespace mlshell {

InertiaTerm::InertiaTerm(const SubdivisionDiscretization& disc, const ParallelLayout& layout,
                         double area_density, double dt, std::string name)
    : EnergyTerm(std::move(name)),
      coefficient_(area_density / (dt * dt)),
      predictor_(3 * layout.num_local_points(), 0.0) {
  const int ng = disc.num_quadrature_points();
  for (int f : layout.local_elements()) {
    const ElementBasis b = disc.element_basis(f);
    Element e{to_local_nodes(layout, b.nodes, b.size), b, {}};
    for (int g = 0; g < ng; ++g)
      e.area.push_back(disc.quadrature_weight(g) * reference_area(b, g, disc.mesh().points));
    elements_.push_back(std::move(e));
  }
  PetscCallAbort(layout.comm(), layout.create_matrix(&mass_));
  PetscCallAbort(layout.comm(), assemble_mass(mass_));
}

InertiaTerm::~InertiaTerm() { MatDestroy(&mass_); }

PetscErrorCode InertiaTerm::assemble_mass(Mat M) const {
  PetscFunctionBeginUser;
  std::vector<double> Ms, He;
  for (const Element& e : elements_) {
    const int n = e.basis.size;
    // The scalar mass Σ_g m_g N Nᵀ (its upper triangle), then one copy per component.
    Ms.assign(n * n, 0.0);
    for (size_t g = 0; g < e.area.size(); ++g) {
      const double* N = e.basis.slot(static_cast<int>(g), kValue);
      const double m = coefficient_ * e.area[g];
      for (int i = 0; i < n; ++i) {
        const double mi = m * N[i];
        for (int j = i; j < n; ++j) Ms[i * n + j] += mi * N[j];
      }
    }
    He.assign(9 * n * n, 0.0);
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j)
        for (int c = 0; c < 3; ++c)
          He[(3 * i + c) * 3 * n + 3 * j + c] = He[(3 * j + c) * 3 * n + 3 * i + c] = Ms[i * n + j];
    PetscCall(add_local_hessian(M, e.nodes, He.data()));
  }
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode InertiaTerm::add_constant_hessian(Mat hess) const {
  PetscFunctionBeginUser;
  // Same element-stencil pattern as every level Hessian (ParallelLayout::create_matrix).
  PetscCall(MatAXPY(hess, 1.0, mass_, SAME_NONZERO_PATTERN));
  PetscFunctionReturn(0);
}

PetscErrorCode InertiaTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                std::vector<double>* grad, Mat) const {
  PetscFunctionBeginUser;
  std::vector<double> ge;
  for (const Element& e : elements_) {
    const int n = e.basis.size;
    if (grad) ge.assign(3 * n, 0.0);
    for (size_t g = 0; g < e.area.size(); ++g) {
      const double* N = e.basis.slot(static_cast<int>(g), kValue);
      double r[3] = {0, 0, 0};
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
          r[c] += N[i] * (u[3 * e.nodes[i] + c] - predictor_[3 * e.nodes[i] + c]);
      const double m = coefficient_ * e.area[g];
      energy.add(0.5 * m * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]));
      if (grad)
        for (int i = 0; i < n; ++i)
          for (int c = 0; c < 3; ++c) ge[3 * i + c] += m * N[i] * r[c];
    }
    if (grad) add_local_gradient(e.nodes, ge.data(), *grad);
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
