// The energy terms of mlshell's effects (paper §3, eq. 3.2 and 3.6), one class per effect.
//
//   elastic       ∫ J̄ ∫ ψ(Ẽ(ξ³)) dξ³ dω                   membrane + bending, eq. (3.3)
//   inertia       ρ/(2 dt²) ∫ |u − û|² dA,  û = u_n + dt v_n  implicit Euler
//   loads         −s(t) f·u   (gravity ρg, surface, line and point forces; s ramps 0 → 1)
//   penalties     β/2 ∫ |P(u − d(X, t))|² ds  (+ β_r/2 ∫ |∂_ν u − (R(t) − I) ∂_ν X|² ds for
//                 clamps), β = h^-σ, d(X, t) = φ_t(X) − X of the rigid motion
//                 φ_t(X) = R(t)(X − c) + c + T(t)
//
// Energies are measured from the reference configuration (u = 0), where loads do no work.
#pragma once

#include <array>
#include <functional>
#include <memory>

#include "mlshell/energy_term.hpp"
#include "mlshell/prescribed_motion.hpp"
#include "mlshell/shell/material.hpp"
#include "mlshell/shell/shell_kinematics.hpp"

namespace mlshell {

/// Membrane and bending energy of the shell material (always present).
class ShellElasticTerm final : public EnergyTerm {
 public:
  ShellElasticTerm(const SubdivisionDiscretization& disc, const ParallelLayout& layout,
                   const MaterialSpec& material);
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;
  /// Where this rank's material points lie in the material model at displacement u (local).
  void inspect(const std::vector<double>& u, MaterialReport& report) const;

 private:
  struct Element {
    std::vector<PetscInt> nodes;
    ElementBasis basis;
    int first_reference;
  };
  /// δ_p = Σ_i B_p,i u_i at quadrature point g, for p = 1, 2, 11, 12, 22.
  void surface_quantities(const Element& e, int g, const std::vector<double>& u,
                          double delta[15]) const;
  const SubdivisionDiscretization& disc_;
  std::vector<Element> elements_;
  std::vector<ShellReference> references_;  // per element and quadrature point
  std::unique_ptr<Material> material_;
  ShellSection section_;
  double rounding_;  // Material::rounding_factor, for the energy's error estimate
};

/// Implicit Euler inertia ρ/(2 dt²) ∫ |u − û|² dA with the predictor û = u_n + dt v_n.
/// Its Hessian, the mass matrix over dt², is assembled once and added by add_constant_hessian.
class InertiaTerm final : public EnergyTerm {
 public:
  /// `name`: "inertia", or "proximal" for the proximal term of quasistatics (dt = h).
  InertiaTerm(const SubdivisionDiscretization& disc, const ParallelLayout& layout,
              double area_density, double dt, std::string name = "inertia");
  ~InertiaTerm() override;
  PetscErrorCode add_constant_hessian(Mat hess) const override;
  /// Sets û from local predictor values (3 per local point).
  void set_predictor(std::vector<double> local_predictor) {
    predictor_ = std::move(local_predictor);
  }
  /// Takes the step's predictor (StepStart::predictor, if given).
  void begin_step(const StepStart& start) override {
    EnergyTerm::begin_step(start);
    if (start.predictor) predictor_ = *start.predictor;
  }
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;

 private:
  struct Element {
    std::vector<PetscInt> nodes;
    ElementBasis basis;
    std::vector<double> area;  // w_g J̄_g
  };
  PetscErrorCode assemble_mass(Mat M) const;
  std::vector<Element> elements_;
  double coefficient_;  // ρ / dt²
  std::vector<double> predictor_;
  Mat mass_ = nullptr;  // ρ/dt² M, assembled in the constructor
};

/// A constant force field, linear in u: −s(t) f·u with s(t) = min(1, t / t_ramp) if ramped.
class LinearLoadTerm final : public EnergyTerm {
 public:
  /// `local_force`: this rank's contributions, 3 per local point.
  LinearLoadTerm(std::string name, std::vector<double> local_force, double ramp_time);
  double scale() const;
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;

 private:
  std::vector<double> force_;
  double ramp_time_;  // 0: no ramp
};

/// One penalty sample: a point of a boundary curve (with its quadrature weight) or a single
/// selected point, with its basis on local nodes.
struct PenaltySample {
  std::vector<PetscInt> nodes;
  std::vector<double> value;     ///< N_i at the point
  std::vector<double> conormal;  ///< ∂_ν N_i (clamp rotation), empty otherwise
  double weight = 0.0;           ///< β × quadrature weight × arc length (β for single points)
  double rotation_weight = 0.0;
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();  ///< X(ξ), where the motion is taken
  /// ∂_ν X(ξ), the reference slope across the boundary (clamps): the motion turns it by R.
  Eigen::Vector3d reference_conormal = Eigen::Vector3d::Zero();
};

/// Penalty boundary conditions (eq. 3.6) that follow a prescribed rigid motion φ_t:
///   β/2 Σ w |P(u(ξ) − d(ξ, t))|² + β_r/2 Σ w |∂_ν u(ξ) − (R(t) − I) ∂_ν X(ξ)|²,
/// d(ξ, t) = φ_t(X(ξ)) − X(ξ): the point goes where the motion takes it, and a clamp's slope
/// across the boundary, ∂_ν x = ∂_ν X + ∂_ν u, turns with the motion's rotation R to R ∂_ν X.
class PenaltyTerm final : public EnergyTerm {
 public:
  PenaltyTerm(std::string name, std::vector<PenaltySample> samples, std::array<bool, 3> components,
              PrescribedMotion motion);
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;
  /// max over this rank's samples of |P(u(ξ) − d(ξ, t))| (m): how far the penalty lets go.
  double max_violation(const std::vector<double>& u) const;
  double constraint_violation(const std::vector<double>& u) const override {
    return max_violation(u);
  }
  /// Augmented-Lagrangian mode (method of multipliers): the energy becomes
  /// Σ (s w/2 |P c|² − λ·P c) with c = u(ξ) − d(ξ, t), w = β × weight, multipliers λ per sample and
  /// a penalty factor s (1 at first), updated after each solve until max |P c| ≤ tolerance (m):
  /// λ ← λ − s w P c, and s ← 10 s when the violation fell by less than 4× since the last update.
  void enable_augmented_lagrangian(double tolerance) {
    tolerance_ = tolerance;
    multipliers_.assign(samples_.size(), Eigen::Vector3d::Zero());
  }
  bool has_multipliers() const override { return tolerance_ > 0.0; }
  double constraint_tolerance() const override { return tolerance_; }
  void update_multipliers(const std::vector<double>& u, double violation) override;

 private:
  /// P(u(ξ_s) − d(ξ_s, t)) of sample s at the placement φ_t.
  Eigen::Vector3d residual(const PenaltySample& s, const std::vector<double>& u,
                           const RigidPlacement& placement) const;
  double tolerance_ = 0.0;
  std::vector<Eigen::Vector3d> multipliers_;  // λ_s, augmented-Lagrangian mode
  double scale_ = 1.0;                        // s
  double last_violation_ = INFINITY;          // at the last update
  std::vector<PenaltySample> samples_;
  std::array<bool, 3> components_;
  PrescribedMotion motion_;
};

}  // namespace mlshell
