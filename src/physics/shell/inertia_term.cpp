// Implicit Euler inertia (paper §3.1.1): the kinetic term of the incremental potential,
// ρ/(2 dt²) ∫ |u − û|² dA with û = u_n + dt v_n; its minimiser satisfies the Euler step.
#include "mlshell/effects.hpp"

#include "mlshell/element_matrix_assembly.hpp"

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
  PetscCallAbort(layout.comm(), layout.create_point_matrix(&mass_));
  PetscCallAbort(layout.comm(), assemble_mass(mass_));
}

InertiaTerm::~InertiaTerm() { MatDestroy(&mass_); }

PetscErrorCode InertiaTerm::assemble_mass(Mat M) const {
  PetscFunctionBeginUser;
  std::vector<double> Ms;
  for (const Element& e : elements_) {
    const int n = e.basis.size;
    // The scalar mass Σ_g m_g N Nᵀ: the Hessian's 3 × 3 blocks are its entries times I₃.
    Ms.assign(n * n, 0.0);
    for (size_t g = 0; g < e.area.size(); ++g) {
      const double* N = e.basis.slot(static_cast<int>(g), kValue);
      const double m = coefficient_ * e.area[g];
      for (int i = 0; i < n; ++i) {
        const double mi = m * N[i];
        for (int j = i; j < n; ++j) Ms[i * n + j] += mi * N[j];
      }
    }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < i; ++j) Ms[i * n + j] = Ms[j * n + i];
    PetscCall(MatSetValuesLocal(M, n, e.nodes.data(), n, e.nodes.data(), Ms.data(), ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode InertiaTerm::add_constant_hessian(Mat hess) const {
  PetscFunctionBeginUser;
  // ρ/dt² M ⊗ I₃ into the Hessian, whose pattern the point matrix shares
  // (ParallelLayout::create_matrix and create_point_matrix).
  PetscCall(add_point_matrix(hess, mass_));
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
