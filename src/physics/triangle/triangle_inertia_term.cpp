// Consistent-mass inertia (or proximal) term of a triangle mesh (see triangle_effects.hpp).
#include "mlshell/triangle/triangle_effects.hpp"

namespace mlshell {

TriangleInertiaTerm::TriangleInertiaTerm(const TriangleDiscretization& disc,
                                         const ParallelLayout& layout, double area_density,
                                         double dt, std::string name)
    : TriangleInertiaTerm(disc, layout, std::vector<double>(disc.num_faces(), area_density), dt,
                          std::move(name)) {}

TriangleInertiaTerm::TriangleInertiaTerm(const TriangleDiscretization& disc,
                                         const ParallelLayout& layout,
                                         const std::vector<double>& area_density, double dt,
                                         std::string name)
    : EnergyTerm(std::move(name)), predictor_(3 * layout.num_local_points(), 0.0) {
  const auto& X = disc.points();
  for (int f : layout.local_elements()) {
    const Triangle& t = disc.mesh().triangles[f];
    const double area = 0.5 * (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]).norm();
    Element e;
    for (int k = 0; k < 3; ++k) e.nodes[k] = layout.local_of(t[k]);
    e.mass = area_density.at(f) * area / 12.0 / (dt * dt);
    elements_.push_back(e);
  }
  PetscCallAbort(layout.comm(), layout.create_matrix(&mass_));
  std::vector<PetscInt> nodes(3);
  std::vector<double> block(81);
  for (const Element& e : elements_) {
    nodes.assign(e.nodes.begin(), e.nodes.end());
    std::fill(block.begin(), block.end(), 0.0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int c = 0; c < 3; ++c) block[(3 * i + c) * 9 + 3 * j + c] = e.mass * (i == j ? 2 : 1);
    PetscCallAbort(layout.comm(), add_local_hessian(mass_, nodes, block.data()));
  }
  PetscCallAbort(layout.comm(), MatAssemblyBegin(mass_, MAT_FINAL_ASSEMBLY));
  PetscCallAbort(layout.comm(), MatAssemblyEnd(mass_, MAT_FINAL_ASSEMBLY));
}

TriangleInertiaTerm::~TriangleInertiaTerm() { MatDestroy(&mass_); }

void TriangleInertiaTerm::begin_step(const StepStart& start) {
  EnergyTerm::begin_step(start);
  if (start.predictor) predictor_ = *start.predictor;
}

PetscErrorCode TriangleInertiaTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                        std::vector<double>* grad, Mat) const {
  PetscFunctionBeginUser;
  for (const Element& e : elements_) {
    double r[3][3];
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) r[i][c] = u[3 * e.nodes[i] + c] - predictor_[3 * e.nodes[i] + c];
    // ½ rᵀ M r with M_ij = m (1 + δ_ij): ½ m (Σ_i |r_i|² + |Σ_i r_i|²)
    double sum[3] = {0, 0, 0}, squares = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) {
        sum[c] += r[i][c];
        squares += r[i][c] * r[i][c];
      }
    energy.add(0.5 * e.mass * (squares + sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]));
    if (grad)
      for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c) (*grad)[3 * e.nodes[i] + c] += e.mass * (r[i][c] + sum[c]);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TriangleInertiaTerm::add_constant_hessian(Mat hess) const {
  return MatAXPY(hess, 1.0, mass_, SUBSET_NONZERO_PATTERN);
}

}  // namespace mlshell
