// A coarse level's proxy of the finest energy (paper 2 eq. 2, §4.5): F_l(x_l) = Ψ(P^l(x_l)),
// the finest level's energy (elastics, loads, pressure, boundary penalties, the step's proximal
// or inertia term) evaluated at the direct prolongation of the coarse state, with the exact
// gradient J_{P^l}(x_l)ᵀ ∇Ψ and the Galerkin Hessian J_Pᵀ ∇²Ψ J_P (PSD wherever ∇²Ψ is: the
// finest problem's -mlshell_hessian_psd projects it per element). Contact barriers of the
// coarse level's own mesh (C_l of eq. 2) join it later.
//
// It is an Objective on level l's displacements, so RMTR's first-order coarse models can take
// it in place of the coarse mesh's own energy (-mlshell_coarse_energy proxy), and the
// progressive driver steps on it.
#pragma once

#include <petscmat.h>

#include "mlshell/level_transfer.hpp"
#include "mlshell/objective.hpp"

namespace mlshell {

class ProxyEnergy final : public Objective {
 public:
  /// The gradient objective() returns: the exact J_P(u)ᵀ∇Ψ, or paper 2's eq. (10), Uᵀ∇Ψ with the
  /// prolongation's offset frozen at u (the intrinsic part's transpose alone; the same as the
  /// exact one for a linear transfer or where the offsets are zero).
  enum class Gradient { kExact, kFrozenOffset };
  /// `finest`: the finest level's problem (it must outlive this); `direct`: P^l from this level
  /// to the finest; `pattern`: a matrix of this level whose pattern the Hessian must also hold
  /// (the coarse problem's own, so RMTR's Galerkin models fit too; may be null). Collective.
  ProxyEnergy(Objective& finest, const LevelTransfer& direct, Vec coarse_template, Mat pattern);
  ~ProxyEnergy() override;
  ProxyEnergy(const ProxyEnergy&) = delete;
  ProxyEnergy& operator=(const ProxyEnergy&) = delete;

  /// Ψ(P^l(x̄_l + u) − x̄) and J_P(u)ᵀ∇Ψ (u: displacements of level l).
  PetscErrorCode objective(Vec u, PetscReal* f, Vec g) override;
  /// J_P(u)ᵀ ∇²Ψ J_P(u) into H (a matrix from create_hessian()).
  PetscErrorCode hessian(Vec u, Mat H) override;
  PetscReal evaluation_error() const override { return finest_.evaluation_error(); }
  PetscErrorCode create_hessian(Mat* H) const override;
  PetscErrorCode force_scale(Vec u, PetscReal* scale) override;
  void set_gradient(Gradient gradient) { gradient_ = gradient; }
  Gradient gradient() const { return gradient_; }

 private:
  Objective& finest_;
  const LevelTransfer& direct_;
  Mat pattern_ = nullptr;  // a reference to the caller's `pattern`
  Vec fine_u_ = nullptr, fine_g_ = nullptr, rest_ = nullptr;
  Mat fine_h_ = nullptr;            // the finest problem's Hessian
  mutable Mat galerkin_ = nullptr;  // J_Pᵀ ∇²Ψ J_P, on first use
  mutable Mat template_ = nullptr;  // the union of the Galerkin pattern and `pattern`, zero
  PetscErrorCode build_galerkin() const;
  Gradient gradient_ = Gradient::kExact;
};

}  // namespace mlshell
