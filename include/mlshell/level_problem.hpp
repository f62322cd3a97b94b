// The objective of one level: the sum of the energy terms a scene enables, evaluated on
// distributed PETSc vectors of displacements. This is what a solver sees — value, gradient and
// Hessian — never a mesh.
#pragma once

#include <petscmat.h>

#include <functional>
#include <memory>
#include <string>
#include <array>
#include <string_view>
#include <vector>

#include "mlshell/energy_term.hpp"
#include "mlshell/objective.hpp"
#include "mlshell/shell/material.hpp"

namespace mlshell {

class LevelProblem final : public Objective {
 public:
  explicit LevelProblem(const ParallelLayout& layout);
  void add_term(std::unique_ptr<EnergyTerm> term);
  const std::vector<std::unique_ptr<EnergyTerm>>& terms() const { return terms_; }
  template <class T>
  T* find_term() const {
    for (const auto& t : terms_)
      if (auto* p = dynamic_cast<T*>(t.get())) return p;
    return nullptr;
  }
  /// The term called `name` (EnergyTerm::name(), e.g. "proximal"), or null.
  const EnergyTerm* find_term(std::string_view name) const {
    for (const auto& t : terms_)
      if (t->name() == name) return t.get();
    return nullptr;
  }
  const ParallelLayout& layout() const { return layout_; }

  void set_time(double time);
  /// A step begins at `time`: every term's begin_step, with the predictor (a global vector of
  /// this level, or null) as local values.
  PetscErrorCode begin_step(double time, Vec predictor);
  /// min over the terms that limit steps (EnergyTerm::limits_steps) and the ranks; 1 without
  /// communication when none does.
  PetscErrorCode max_step(Vec u, Vec du, PetscReal* alpha) override;
  /// Every term's after_accept.
  PetscErrorCode accepted(Vec u) override;
  /// The sum of the terms' revisions.
  long revision() const override;
  /// f(u) and, if g is not null, ∇f(u). A non-finite energy (a trial point outside the
  /// material's domain) is reported as +inf so that trust-region and line-search methods reject
  /// the step instead of propagating NaN.
  PetscErrorCode objective(Vec u, PetscReal* f, Vec g) override;
  /// f(u) and ∇f(u) without one of the terms (the proximal term of quasistatics: ∇E).
  PetscErrorCode objective_without(const EnergyTerm& excluded, Vec u, PetscReal* f, Vec g);
  /// 4 ε Σ_pieces w |e| over every element, sample and node of the last objective(), with w
  /// the material's rounding factor for elastic pieces (1 otherwise).
  PetscReal evaluation_error() const override { return evaluation_error_; }
  /// ∇²f(u), assembled into H (created by create_matrix).
  PetscErrorCode hessian(Vec u, Mat H) override;
  /// A matrix for the Hessian: the element-stencil pattern plus the pairs the terms add
  /// (EnergyTerm::extend_sparsity).
  PetscErrorCode create_matrix(Mat* H) const;
  /// Point pairs (natural indices) every matrix of this level must hold beyond the element
  /// stencils, e.g. the pattern of Galerkin coarse Hessians J_Pᵀ H J_P on a decimated level.
  void extend_pattern(std::vector<std::array<int, 2>> pairs) { pattern_pairs_ = std::move(pairs); }
  PetscErrorCode create_hessian(Mat* H) const override { return create_matrix(H); }
  /// The sum of the terms' sparsity versions (EnergyTerm::sparsity_version): hessian() remakes
  /// a matrix made for another one.
  long sparsity_version() const;
  PetscErrorCode force_scale(Vec u, PetscReal* scale) override {
    return external_force_norm(u, scale);
  }
  /// Global energy of each term at u, in the order of terms().
  PetscErrorCode term_energies(Vec u, std::vector<double>& energies);
  /// ‖f_ext‖₂: the norm of the external forces (gravity and loads, at the current time), the
  /// force scale of the problem's stopping tolerance. `like` gives the vector layout.
  PetscErrorCode external_force_norm(Vec like, PetscReal* norm);
  /// The largest violation |P(u − d(t))| (m) of each penalty term at u, in the order of terms()
  /// (0 for terms that are not penalties), over all ranks.
  PetscErrorCode constraint_violations(Vec u, std::vector<double>& violations);
  /// Augmented-Lagrangian outer step at u: *met is whether every term with multipliers has its
  /// violation within its tolerance (all ranks); the multipliers of those that do not are
  /// updated. *met is true when no term has multipliers.
  PetscErrorCode update_multipliers(Vec u, bool* met);
  /// Where the material points of the elastic term lie in the material model at u (all ranks).
  PetscErrorCode material_report(Vec u, MaterialReport& report);
  /// Energy of each term, their sum f(u) and ‖∇f(u)‖₂ at u, in one pass (for reports; not
  /// counted in objective_evaluations()).
  PetscErrorCode report(Vec u, std::vector<double>& energies, PetscReal* total, PetscReal* gnorm);

  /// Every term's per-element output fields at u, in natural face order, on rank 0 (on the
  /// other ranks the same names with no values; faces that are not elements hold 0).
  PetscErrorCode face_fields(Vec u, int num_faces,
                             std::vector<std::pair<std::string, std::vector<double>>>& fields);

  long objective_evaluations() const { return objective_evaluations_; }
  /// Evaluations whose energy was not finite: trial points outside a material's valid domain.
  long inadmissible_evaluations() const { return inadmissible_evaluations_; }
  long hessian_evaluations() const { return hessian_evaluations_; }

 private:
  PetscErrorCode evaluate(Vec u, PetscReal* f, Vec g, const EnergyTerm* excluded);
  /// Every term's prepare(u, du) that needs one (only the step limiters' if asked).
  PetscErrorCode prepare_terms(Vec u, Vec du, bool step_limiters_only = false);
  PetscErrorCode add_nonlocal_gradients(Vec g, const EnergyTerm* excluded);
  using PerTerm = std::function<double(const EnergyTerm&, const std::vector<double>&)>;
  /// One number per term from this rank's local values, reduced over the ranks with `op`.
  PetscErrorCode reduce_per_term(Vec u, const PerTerm& value, MPI_Op op, std::vector<double>& out);
  const ParallelLayout& layout_;
  std::vector<std::unique_ptr<EnergyTerm>> terms_;
  std::vector<std::array<int, 2>> pattern_pairs_;
  std::vector<double> u_local_, g_local_, d_local_;
  long objective_evaluations_ = 0, hessian_evaluations_ = 0, inadmissible_evaluations_ = 0;
  PetscReal evaluation_error_ = 0.0;
};

}  // namespace mlshell
