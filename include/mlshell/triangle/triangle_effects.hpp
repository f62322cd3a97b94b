// The energy terms of triangle-mesh shells (paper 2 §3, footnote 1), one class per effect:
//
//   elastic    Σ_t τ Ā_t ψ(Ā_t⁻¹A_t) + Σ_hinges 3k (θ − θ̄)² |ē|²/(Ā₁ + Ā₂)   membrane + bending
//              ψ neo-Hookean or St. Venant–Kirchhoff (membrane.hpp), k = Eτ³/(24(1 − ν²))
//   inertia    1/(2 dt²) (u − û)ᵀ M (u − û), M the consistent P1 mass of the area density ρτ
//              (also the proximal term ½h⁻²‖x − xᵗ‖²_M of quasistatics)
//   pressure   −s(t) p (V(x) − V(X)), V the volume enclosed by a closed surface
//   clamp      hinges between each clamped boundary edge's triangle and a virtual triangle,
//              its rest mirror through the edge midpoint, moved with the clamp's motion: the
//              boundary keeps its rest slope (θ̄ = 0) with the shell's own bending stiffness
// Loads and penalty Dirichlet conditions are the generic LinearLoadTerm and PenaltyTerm.
// Positions are x = X + u for the reference positions X of the mesh.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

#include "mlshell/energy_term.hpp"
#include "mlshell/triangle/hinge_bending.hpp"
#include "mlshell/triangle/membrane.hpp"
#include "mlshell/triangle/triangle_discretization.hpp"

namespace mlshell {

/// Isotropic shell parameters of a triangle mesh.
struct TriangleShellParameters {
  enum class Membrane { kNeoHookean, kStVenantKirchhoff };
  Membrane membrane = Membrane::kNeoHookean;
  double youngs_modulus = 0.0;  ///< E, Pa
  double poisson_ratio = 0.0;   ///< ν
  double thickness = 0.0;       ///< τ, m
  /// The membrane's Lamé parameters in plane stress: μ = E/(2(1 + ν)), λ = Eν/(1 − ν²), so that
  /// the small-strain limit of either membrane energy is the plane-stress membrane of E and ν.
  MembraneParameters lame() const;
};

/// Membrane energy of every triangle and bending energy of every hinge.
class TriangleElasticTerm final : public EnergyTerm {
 public:
  TriangleElasticTerm(const TriangleDiscretization& disc, const ParallelLayout& layout,
                      const TriangleShellParameters& params);
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;
  /// Per element this rank assembles (layout.local_elements() order): the largest principal
  /// Green strain of the membrane and the bending energy (half of each of its hinges').
  void face_fields(const std::vector<double>& u, std::vector<double>& strain,
                   std::vector<double>& bending) const;
  std::vector<std::string> face_field_names() const override {
    return {"membrane_strain", "bending_energy"};
  }
  void face_field_values(const std::vector<double>& u,
                         std::vector<std::vector<double>>& values) const override {
    values.resize(2);
    face_fields(u, values[0], values[1]);
  }

 private:
  struct Membrane {
    std::array<PetscInt, 3> nodes;
    TriangleRest rest;
  };
  struct Bend {
    std::array<PetscInt, 4> nodes;
    HingeRest rest;
    std::array<int, 2> elements;  ///< indices into membranes_ (-1: not assembled here)
  };
  Eigen::Vector3d position(const std::vector<double>& u, PetscInt node) const;
  double membrane_energy(const Membrane& m, const std::vector<double>& u, Vector9* g,
                         Matrix9* H) const;
  std::vector<Membrane> membranes_;
  std::vector<Bend> hinges_;         // assembled here
  std::vector<Bend> shared_hinges_;  // owned by the rank of their first triangle; output only
  std::vector<Point3> reference_;    // X of the local points
  TriangleShellParameters params_;
  MembraneParameters lame_;
};

/// 1/(2 dt²) (u − û)ᵀ M (u − û) with the consistent mass M_t = ρτĀ_t/12 (1 + δ_ij) of each
/// triangle; the Hessian M/dt² is assembled once.
class TriangleInertiaTerm final : public EnergyTerm {
 public:
  TriangleInertiaTerm(const TriangleDiscretization& disc, const ParallelLayout& layout,
                      double area_density, double dt, std::string name = "inertia");
  ~TriangleInertiaTerm() override;
  void begin_step(const StepStart& start) override;
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;
  PetscErrorCode add_constant_hessian(Mat hess) const override;

 private:
  struct Element {
    std::array<PetscInt, 3> nodes;
    double mass;  ///< ρτĀ_t/12 / dt²
  };
  std::vector<Element> elements_;
  std::vector<double> predictor_;
  Mat mass_ = nullptr;
};

/// Pressure work on a closed surface: −s(t) p (V(X + u) − V(X)), V = Σ_t x₀·(x₁ × x₂)/6.
class PressureTerm final : public EnergyTerm {
 public:
  PressureTerm(const TriangleDiscretization& disc, const ParallelLayout& layout, double pressure,
               double ramp_time);
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;
  double scale() const;

 private:
  std::vector<std::array<PetscInt, 3>> elements_;
  std::vector<Point3> reference_;
  double pressure_, ramp_time_, reference_volume_ = 0.0;  // this rank's part of V(X)
};

/// The rotation part of a clamp: one hinge per clamped boundary edge with a virtual fourth
/// vertex X₀ + X₁ − X₂ + d(t).
class ClampHingeTerm final : public EnergyTerm {
 public:
  /// `edges`: boundary edges (v0 → v1 in their triangle's direction) to clamp.
  ClampHingeTerm(std::string name, const TriangleDiscretization& disc, const ParallelLayout& layout,
                 const std::vector<std::array<int, 2>>& edges, double stiffness,
                 std::function<Eigen::Vector3d(double)> motion);
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;

 private:
  struct Hinge {
    std::array<PetscInt, 3> nodes;
    std::array<Point3, 3> reference;
    Point3 virtual_vertex;  ///< rest position of the fourth vertex
    HingeRest rest;
  };
  std::vector<Hinge> hinges_;
  std::function<Eigen::Vector3d(double)> motion_;
};

}  // namespace mlshell
