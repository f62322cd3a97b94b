// The energy terms of triangle-mesh shells (paper 2 §3, footnote 1), one class per effect:
//
//   elastic    Σ_t τ Ā_t ψ(Ā_t⁻¹A_t) + bending                                 membrane + bending
//              ψ neo-Hookean or St. Venant–Kirchhoff (membrane.hpp); bending either
//              Σ_hinges 3k (θ − θ̄)² |ē|²/(Ā₁ + Ā₂), k = Eτ³/(24(1 − ν²)) (hinge_bending.hpp,
//              paper 2) or Σ_t ½ δθᵀ K_t δθ over each triangle's three hinges (midedge_bending.hpp)
//   inertia    1/(2 dt²) (u − û)ᵀ M (u − û), M the consistent P1 mass of the area density ρτ
//              (also the proximal term ½h⁻²‖x − xᵗ‖²_M of quasistatics)
//   pressure   −s(t) p (V(x) − V(X)), V the volume enclosed by a closed surface (its Hessian
//              assembled, and projected, per edge)
//   clamp      hinges between each clamped boundary edge's triangle and a virtual triangle,
//              its rest mirror through the edge midpoint, placed by the clamp's rigid motion φ_t
//              (turned with its rotation, so the clamped slope turns too): the
//              boundary keeps its rest slope (θ̄ = 0) with the shell's own bending stiffness;
//              with midedge bending the clamp instead fixes the midedge normal of each clamped
//              edge: the clamped triangle's element with that edge held minus the same element
//              with it free (the elastic term's), a positive semi-definite difference
// Loads and penalty Dirichlet conditions are the generic LinearLoadTerm and PenaltyTerm.
// Positions are x = X + u for the reference positions X of the mesh.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

#include "mlshell/energy_term.hpp"
#include "mlshell/prescribed_motion.hpp"
#include "mlshell/triangle/hinge_bending.hpp"
#include "mlshell/triangle/membrane.hpp"
#include "mlshell/triangle/midedge_bending.hpp"
#include "mlshell/triangle/triangle_discretization.hpp"

namespace mlshell {

/// Isotropic shell parameters of a triangle mesh.
struct TriangleShellParameters {
  enum class Membrane { kNeoHookean, kStVenantKirchhoff };
  enum class Bending { kHinge, kMidedge };
  Membrane membrane = Membrane::kNeoHookean;
  Bending bending = Bending::kHinge;
  double youngs_modulus = 0.0;  ///< E, Pa
  double poisson_ratio = 0.0;   ///< ν
  double thickness = 0.0;       ///< τ, m
  /// The membrane's Lamé parameters in plane stress: μ = E/(2(1 + ν)), λ = Eν/(1 − ν²), so that
  /// the small-strain limit of either membrane energy is the plane-stress membrane of E and ν.
  MembraneParameters lame() const;
};

/// A triangle's midedge element on the mesh: its vertices x0, x1, x2, then the vertex across
/// each edge i (opposite x_i; −1 on the boundary), the wing kinds (free on the boundary), their
/// local nodes on `layout` (−1 across a free edge) and rest positions (a free edge's wing slot
/// holds its own corner x_i, a finite point the element does not use).
struct MidedgeStencil {
  std::array<int, 6> vertices;
  std::array<EdgeWing, 3> wings;
  std::array<PetscInt, 6> nodes;
  std::array<Eigen::Vector3d, 6> reference;
};
MidedgeStencil midedge_stencil(const TriangleDiscretization& disc, const ParallelLayout& layout,
                               int face);

/// Adds one midedge element at positions x: its energy, and its gradient and Hessian on the
/// slots whose local node is ≥ 0 (−1: a prescribed position, e.g. a clamp's virtual vertex);
/// `project` projects the element Hessian onto the PSD cone first.
PetscErrorCode add_midedge_element(const MidedgeRest& rest, const std::array<Eigen::Vector3d, 6>& x,
                                   const std::array<PetscInt, 6>& nodes, bool project,
                                   CompensatedSum& energy, std::vector<double>* grad, Mat hess);

/// Membrane energy of every triangle and bending energy of every hinge (or of every triangle's
/// midedge element).
class TriangleElasticTerm final : public EnergyTerm {
 public:
  TriangleElasticTerm(const TriangleDiscretization& disc, const ParallelLayout& layout,
                      const TriangleShellParameters& params);
  /// Several bodies on one mesh: face f has the parameters params[body_of_face[f]] (all with the
  /// same bending model). A hinge joins two faces of one body (bodies share no edge).
  TriangleElasticTerm(const TriangleDiscretization& disc, const ParallelLayout& layout,
                      std::vector<TriangleShellParameters> params,
                      const std::vector<int>& body_of_face);
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;
  /// Per element this rank assembles (layout.local_elements() order): the largest principal
  /// Green strain of the membrane and the bending energy (half of each of its hinges', or its
  /// midedge element's).
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
    int body = 0;  ///< index into params_ and lame_
  };
  struct Bend {
    std::array<PetscInt, 4> nodes;
    HingeRest rest;
    std::array<int, 2> elements;  ///< indices into membranes_ (-1: not assembled here)
  };
  struct Plate {
    std::array<PetscInt, 6> nodes;  ///< local nodes; −1 across a free edge
    MidedgeRest rest;
  };
  Eigen::Vector3d position(const std::vector<double>& u, PetscInt node) const;
  double membrane_energy(const Membrane& m, const std::vector<double>& u, Vector9* g,
                         Matrix9* H) const;
  void plate_positions(const Plate& p, const std::vector<double>& u,
                       std::array<Eigen::Vector3d, 6>& x) const;
  std::vector<Membrane> membranes_;
  std::vector<Bend> hinges_;         // assembled here
  std::vector<Bend> shared_hinges_;  // owned by the rank of their first triangle; output only
  std::vector<Plate> plates_;        // midedge bending: one per membrane, in the same order
  std::vector<Point3> reference_;    // X of the local points
  std::vector<TriangleShellParameters> params_;  // per body
  std::vector<MembraneParameters> lame_;         // per body
};

/// 1/(2 dt²) (u − û)ᵀ M (u − û) with the consistent mass M_t = ρτĀ_t/12 (1 + δ_ij) of each
/// triangle; the Hessian M/dt² is assembled once.
class TriangleInertiaTerm final : public EnergyTerm {
 public:
  TriangleInertiaTerm(const TriangleDiscretization& disc, const ParallelLayout& layout,
                      double area_density, double dt, std::string name = "inertia");
  /// Several bodies: face f has the area density ρτ = area_density[f].
  TriangleInertiaTerm(const TriangleDiscretization& disc, const ParallelLayout& layout,
                      const std::vector<double>& area_density, double dt,
                      std::string name = "inertia");
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

/// 6 × 6 matrices: one edge's Hessian block in (x_a, x_b).
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// One interior edge's share of the pressure Hessian −p∇²V, V = Σ_t x₀·(x₁ × x₂)/6
/// (enclosed_volume.hpp). V is linear in each vertex and two vertices are coupled only through
/// the two faces of their edge: for the edge a–b with faces (a, b, c) and (b, a, d),
///   M_e = [[0, S], [Sᵀ, 0]] in (x_a, x_b),   S = ∂²(−pV)/∂x_a∂x_b = (p/6) [x_c − x_d]×,
/// and Σ_e M_e = −p∇²V on a closed surface. If `project`, its projection onto the PSD cone in
/// closed form (pressure_term.cpp): ½ M_e + (|p|/12) blockdiag(P, P), P = |w| I − w wᵀ/|w|,
/// w = x_c − x_d.
Matrix6d pressure_edge_hessian(const Eigen::Vector3d& xc, const Eigen::Vector3d& xd,
                               double pressure, bool project);

/// Pressure work on a closed, outward-oriented surface: −s(t) p (V(X + u) − V(X)) with
/// V(x) = Σ_t x₀·(x₁ × x₂)/6, its energy and gradient summed over the faces this rank
/// assembles, its Hessian over the edges (pressure_edge_hessian) whose first face (Hinge) this
/// rank assembles: exact, or with set_hessian_projection (-mlshell_hessian_psd with
/// -mlshell_pressure_psd) each edge's block projected onto the PSD cone.
class PressureTerm final : public EnergyTerm {
 public:
  PressureTerm(const TriangleDiscretization& disc, const ParallelLayout& layout, double pressure,
               double ramp_time);
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;
  double scale() const;
  /// V(X), summed over the ranks (each face counted once): > 0 for an outward-oriented closed
  /// surface, < 0 for one oriented inwards.
  double enclosed_volume() const { return enclosed_volume_; }

 private:
  std::vector<std::array<PetscInt, 3>> elements_;
  std::vector<std::array<PetscInt, 4>> edges_;  // local (a, b, c, d) of Hinge::v
  std::vector<Point3> reference_;
  double pressure_, ramp_time_;
  double reference_volume_ = 0.0;  // this rank's part of V(X)
  double enclosed_volume_ = 0.0;   // V(X) of all ranks
};

/// The rotation part of a clamp: one hinge per clamped boundary edge with a virtual fourth
/// vertex φ_t(X₀ + X₁ − X₂), the rest mirror placed by the clamp's rigid motion.
class ClampHingeTerm final : public EnergyTerm {
 public:
  /// `edges`: boundary edges (v0 → v1 in their triangle's direction) to clamp.
  ClampHingeTerm(std::string name, const TriangleDiscretization& disc, const ParallelLayout& layout,
                 const std::vector<std::array<int, 2>>& edges, double stiffness,
                 PrescribedMotion motion);
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
  PrescribedMotion motion_;
};

/// The rotation part of a clamp with midedge bending: for each clamped triangle, its midedge
/// element with the clamped edges' normals held by virtual vertices φ_t(X_j + X_k − X_i),
/// minus the elastic term's element of the same triangle with those edges free. Two clamp
/// effects on one corner triangle each add their own difference: both edges are held, but the
/// sum differs from the element with both held by a cross term.
class MidedgeClampTerm final : public EnergyTerm {
 public:
  /// `edges`: boundary edges (v0 → v1 in their triangle's direction) to clamp.
  MidedgeClampTerm(std::string name, const TriangleDiscretization& disc,
                   const ParallelLayout& layout, const std::vector<std::array<int, 2>>& edges,
                   const TriangleShellParameters& params, PrescribedMotion motion);
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;

 private:
  struct Element {
    std::array<PetscInt, 6> nodes;  ///< local nodes; −1 for virtual and free wings
    std::array<Point3, 6> reference;
    std::array<bool, 6> moves;  ///< a virtual vertex, moved with the clamp
    MidedgeRest rest;           ///< held minus free
  };
  std::vector<Element> elements_;
  PrescribedMotion motion_;
};

}  // namespace mlshell
