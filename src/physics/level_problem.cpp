// Sum of a scene's energy terms on distributed vectors.
#include "mlshell/level_problem.hpp"

#include <algorithm>
#include <cmath>

#include "mlshell/effects.hpp"
#include "mlshell/element_matrix_assembly.hpp"
#include "mlshell/log_events.hpp"

namespace mlshell {

LevelProblem::LevelProblem(const ParallelLayout& layout) : layout_(layout) {}

void LevelProblem::add_term(std::unique_ptr<EnergyTerm> term) { terms_.push_back(std::move(term)); }

void LevelProblem::set_time(double time) {
  for (auto& t : terms_) t->set_time(time);
}

PetscErrorCode LevelProblem::begin_step(double time, Vec predictor) {
  PetscFunctionBeginUser;
  StepStart start{time, nullptr};
  std::vector<double> local;
  if (predictor) {
    PetscCall(layout_.to_local(predictor, local));
    start.predictor = &local;
  }
  for (auto& t : terms_) t->begin_step(start);
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::prepare_terms(Vec u, Vec du, bool step_limiters_only) {
  PetscFunctionBeginUser;
  for (auto& t : terms_)
    if (t->needs_prepare() && (!step_limiters_only || t->limits_steps())) {
      PetscCall(PetscLogEventBegin(t->log_event(), 0, 0, 0, 0));
      PetscCall(t->prepare(u, du));
      PetscCall(PetscLogEventEnd(t->log_event(), 0, 0, 0, 0));
    }
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::add_nonlocal_gradients(Vec g, const EnergyTerm* excluded) {
  PetscFunctionBeginUser;
  for (const auto& t : terms_)
    if (t->needs_prepare() && t.get() != excluded) PetscCall(t->add_nonlocal_gradient(g));
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::max_step(Vec u, Vec du, PetscReal* alpha) {
  PetscFunctionBeginUser;
  *alpha = 1.0;
  if (std::none_of(terms_.begin(), terms_.end(), [](const auto& t) { return t->limits_steps(); }))
    PetscFunctionReturn(0);
  PetscCall(prepare_terms(u, du, true));
  PetscCall(layout_.to_local(u, u_local_));
  PetscCall(layout_.to_local(du, d_local_));
  double mine = 1.0;
  for (const auto& t : terms_)
    if (t->limits_steps()) {
      PetscCall(PetscLogEventBegin(t->log_event(), 0, 0, 0, 0));
      mine = std::min(mine, t->max_step(u_local_, d_local_));
      PetscCall(PetscLogEventEnd(t->log_event(), 0, 0, 0, 0));
    }
  PetscCallMPI(MPI_Allreduce(&mine, alpha, 1, MPI_DOUBLE, MPI_MIN, layout_.comm()));
  PetscFunctionReturn(0);
}

long LevelProblem::revision() const {
  long r = 0;
  for (const auto& t : terms_) r += t->revision();
  return r;
}

PetscErrorCode LevelProblem::accepted(Vec u) {
  PetscFunctionBeginUser;
  PetscCall(prepare_terms(u, nullptr));
  PetscCall(layout_.to_local(u, u_local_));
  for (auto& t : terms_) t->after_accept(u_local_);
  PetscFunctionReturn(0);
}

namespace {

constexpr const char* kPatternVersionKey = "mlshell_pattern_version";

PetscErrorCode destroy_version(void* p) {
  delete static_cast<long*>(p);
  return 0;
}

/// The sparsity version a matrix was made for (create_matrix); -1 if unknown.
long pattern_version(Mat H) {
  PetscContainer c = nullptr;
  if (PetscObjectQuery((PetscObject)H, kPatternVersionKey, (PetscObject*)&c) || !c) return -1;
  void* p = nullptr;
  if (PetscContainerGetPointer(c, &p) || !p) return -1;
  return *static_cast<long*>(p);
}

PetscErrorCode set_pattern_version(Mat H, long version) {
  PetscFunctionBeginUser;
  PetscContainer c;
  PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)H), &c));
  PetscCall(PetscContainerSetPointer(c, new long(version)));
  PetscCall(PetscContainerSetUserDestroy(c, destroy_version));
  PetscCall(PetscObjectCompose((PetscObject)H, kPatternVersionKey, (PetscObject)c));
  PetscCall(PetscContainerDestroy(&c));
  PetscFunctionReturn(0);
}

}  // namespace

long LevelProblem::sparsity_version() const {
  long version = 0;
  for (const auto& t : terms_) version += t->sparsity_version();
  return version;
}

PetscErrorCode LevelProblem::create_matrix(Mat* H) const {
  PetscFunctionBeginUser;
  std::vector<std::array<int, 2>> pairs = pattern_pairs_;
  for (const auto& t : terms_) t->extend_sparsity(pairs);
  PetscCall(layout_.create_matrix(H, pairs));
  PetscCall(set_pattern_version(*H, sparsity_version()));
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::face_fields(
    Vec u, int num_faces, std::vector<std::pair<std::string, std::vector<double>>>& fields) {
  PetscFunctionBeginUser;
  fields.clear();
  // Every rank has the same terms: all return here, or none.
  if (std::all_of(terms_.begin(), terms_.end(),
                  [](const auto& t) { return t->face_field_names().empty(); }))
    PetscFunctionReturn(0);
  PetscCall(layout_.to_local(u, u_local_));
  const auto& mine = layout_.local_elements();
  int size;
  PetscCallMPI(MPI_Comm_size(layout_.comm(), &size));
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(size), displs(size, 0);
  PetscCallMPI(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, layout_.comm()));
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  const int total = layout_.rank() == 0 ? displs[size - 1] + counts[size - 1] : 0;
  std::vector<int> faces(total);
  PetscCallMPI(MPI_Gatherv(mine.data(), count, MPI_INT, faces.data(), counts.data(), displs.data(),
                           MPI_INT, 0, layout_.comm()));
  for (const auto& t : terms_) {
    const auto names = t->face_field_names();
    if (names.empty()) continue;
    std::vector<std::vector<double>> values;
    t->face_field_values(u_local_, values);
    for (size_t k = 0; k < names.size(); ++k) {
      std::vector<double> gathered(total);
      PetscCallMPI(MPI_Gatherv(values[k].data(), count, MPI_DOUBLE, gathered.data(), counts.data(),
                               displs.data(), MPI_DOUBLE, 0, layout_.comm()));
      if (layout_.rank() != 0) {
        fields.emplace_back(names[k], std::vector<double>());
        continue;
      }
      std::vector<double> natural(num_faces, 0.0);
      for (int i = 0; i < total; ++i) natural[faces[i]] = gathered[i];
      fields.emplace_back(names[k], std::move(natural));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::objective(Vec u, PetscReal* f, Vec g) {
  return evaluate(u, f, g, nullptr);
}

PetscErrorCode LevelProblem::objective_without(const EnergyTerm& excluded, Vec u, PetscReal* f,
                                               Vec g) {
  return evaluate(u, f, g, &excluded);
}

PetscErrorCode LevelProblem::evaluate(Vec u, PetscReal* f, Vec g, const EnergyTerm* excluded) {
  PetscFunctionBeginUser;
  ++objective_evaluations_;
  PetscCall(prepare_terms(u, nullptr));
  PetscCall(layout_.to_local(u, u_local_));
  if (g) g_local_.assign(u_local_.size(), 0.0);
  CompensatedSum local;
  for (const auto& t : terms_) {
    if (t.get() == excluded) continue;
    PetscCall(PetscLogEventBegin(t->log_event(), 0, 0, 0, 0));
    PetscCall(t->add(u_local_, local, g ? &g_local_ : nullptr, nullptr));
    PetscCall(PetscLogEventEnd(t->log_event(), 0, 0, 0, 0));
  }
  // Sum the ranks' compensated partial sums and the magnitudes of their pieces.
  double mine[2] = {local.value(), local.magnitude()}, sums[2] = {0.0, 0.0};
  PetscCallMPI(MPI_Allreduce(mine, sums, 2, MPI_DOUBLE, MPI_SUM, layout_.comm()));
  const double total = sums[0];
  evaluation_error_ = 4.0 * PETSC_MACHINE_EPSILON * sums[1];
  *f = std::isfinite(total) ? total : PETSC_INFINITY;
  if (!std::isfinite(total)) ++inadmissible_evaluations_;
  if (g) {
    PetscCall(VecZeroEntries(g));
    PetscCall(layout_.add_to_global(g_local_, g));
    PetscCall(add_nonlocal_gradients(g, excluded));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::hessian(Vec u, Mat H) {
  PetscFunctionBeginUser;
  ++hessian_evaluations_;
  PetscCall(prepare_terms(u, nullptr));
  // Terms whose pairs come and go (contact) may need a pattern H was not made for: then H is
  // made anew under the same handle, so the solvers holding it see the new pattern.
  for (auto& t : terms_) PetscCall(t->update_sparsity());
  if (const long version = sparsity_version(); version != 0 && pattern_version(H) != version) {
    const LogEventScope event("Hessian:pattern");
    Mat fresh;
    PetscCall(create_matrix(&fresh));
    PetscInt references;
    PetscCall(PetscObjectGetReference((PetscObject)fresh, &references));
    if (references > 1) {  // the layout keeps the first matrix of a pattern: take a copy
      Mat copy;
      PetscCall(create_matrix(&copy));
      PetscCall(MatDestroy(&fresh));
      fresh = copy;
    }
    PetscCall(replace_matrix(H, &fresh));
    PetscCall(set_pattern_version(H, version));
  }
  PetscCall(layout_.to_local(u, u_local_));
  PetscCall(MatZeroEntries(H));
  CompensatedSum ignored;
  for (const auto& t : terms_) {
    PetscCall(PetscLogEventBegin(t->log_event(), 0, 0, 0, 0));
    PetscCall(t->add(u_local_, ignored, nullptr, H));
    PetscCall(PetscLogEventEnd(t->log_event(), 0, 0, 0, 0));
  }
  PetscCall(MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY));
  for (const auto& t : terms_) {
    PetscCall(PetscLogEventBegin(t->log_event(), 0, 0, 0, 0));
    PetscCall(t->add_constant_hessian(H));
    PetscCall(PetscLogEventEnd(t->log_event(), 0, 0, 0, 0));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::reduce_per_term(Vec u, const PerTerm& value, MPI_Op op,
                                             std::vector<double>& out) {
  PetscFunctionBeginUser;
  PetscCall(prepare_terms(u, nullptr));
  PetscCall(layout_.to_local(u, u_local_));
  std::vector<double> mine;
  for (const auto& t : terms_) mine.push_back(value(*t, u_local_));
  out.assign(mine.size(), 0.0);
  PetscCallMPI(MPI_Allreduce(mine.data(), out.data(), static_cast<int>(mine.size()), MPI_DOUBLE, op,
                             layout_.comm()));
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::term_energies(Vec u, std::vector<double>& energies) {
  return reduce_per_term(
      u,
      [](const EnergyTerm& t, const std::vector<double>& ul) {
        CompensatedSum s;
        PetscCallAbort(PETSC_COMM_SELF, t.add(ul, s, nullptr, nullptr));
        return s.value();
      },
      MPI_SUM, energies);
}

PetscErrorCode LevelProblem::external_force_norm(Vec like, PetscReal* norm) {
  PetscFunctionBeginUser;
  const std::vector<double> zero(3 * static_cast<size_t>(layout_.num_local_points()), 0.0);
  std::vector<double> force(zero.size(), 0.0);
  CompensatedSum ignored;
  for (const auto& t : terms_)
    if (dynamic_cast<const LinearLoadTerm*>(t.get()))
      PetscCall(t->add(zero, ignored, &force, nullptr));
  Vec f;
  PetscCall(VecDuplicate(like, &f));
  PetscCall(VecZeroEntries(f));
  PetscCall(layout_.add_to_global(force, f));
  PetscCall(VecNorm(f, NORM_2, norm));
  PetscCall(VecDestroy(&f));
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::constraint_violations(Vec u, std::vector<double>& violations) {
  return reduce_per_term(
      u,
      [](const EnergyTerm& t, const std::vector<double>& ul) {
        return t.constraint_violation(ul);
      },
      MPI_MAX, violations);
}

PetscErrorCode LevelProblem::update_multipliers(Vec u, bool* met) {
  PetscFunctionBeginUser;
  *met = true;
  if (std::none_of(terms_.begin(), terms_.end(),
                   [](const auto& t) { return t->has_multipliers(); }))
    PetscFunctionReturn(0);
  std::vector<double> violations;
  PetscCall(constraint_violations(u, violations));  // leaves u in u_local_
  for (size_t i = 0; i < terms_.size(); ++i) {
    if (!terms_[i]->has_multipliers() || violations[i] <= terms_[i]->constraint_tolerance())
      continue;
    *met = false;
    terms_[i]->update_multipliers(u_local_, violations[i]);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::material_report(Vec u, MaterialReport& report) {
  PetscFunctionBeginUser;
  PetscCall(layout_.to_local(u, u_local_));
  MaterialReport mine;
  if (const auto* elastic = find_term<ShellElasticTerm>()) elastic->inspect(u_local_, mine);
  long counts[4] = {mine.points, mine.beyond_fit, mine.coupling_limited, mine.negative};
  long sums[4];
  PetscCallMPI(MPI_Allreduce(counts, sums, 4, MPI_LONG, MPI_SUM, layout_.comm()));
  double min_psi;
  PetscCallMPI(
      MPI_Allreduce(&mine.min_energy_density, &min_psi, 1, MPI_DOUBLE, MPI_MIN, layout_.comm()));
  report = MaterialReport{sums[0], sums[1], sums[2], sums[3], min_psi};
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::report(Vec u, std::vector<double>& energies, PetscReal* total,
                                    PetscReal* gnorm) {
  PetscFunctionBeginUser;
  // One pass over the terms for their energies and the gradient (the same gradient as
  // objective()'s), not counted among the solvers' evaluations.
  PetscCall(prepare_terms(u, nullptr));
  PetscCall(layout_.to_local(u, u_local_));
  g_local_.assign(u_local_.size(), 0.0);
  std::vector<double> mine;
  for (const auto& t : terms_) {
    CompensatedSum s;
    PetscCall(PetscLogEventBegin(t->log_event(), 0, 0, 0, 0));
    PetscCall(t->add(u_local_, s, &g_local_, nullptr));
    PetscCall(PetscLogEventEnd(t->log_event(), 0, 0, 0, 0));
    mine.push_back(s.value());
  }
  energies.assign(mine.size(), 0.0);
  PetscCallMPI(MPI_Allreduce(mine.data(), energies.data(), static_cast<int>(mine.size()),
                             MPI_DOUBLE, MPI_SUM, layout_.comm()));
  CompensatedSum sum;
  for (double e : energies) sum.add(e);
  *total = std::isfinite(sum.value()) ? sum.value() : PETSC_INFINITY;
  Vec g;
  PetscCall(VecDuplicate(u, &g));
  PetscCall(VecZeroEntries(g));
  PetscCall(layout_.add_to_global(g_local_, g));
  PetscCall(add_nonlocal_gradients(g, nullptr));
  PetscCall(VecNorm(g, NORM_2, gnorm));
  PetscCall(VecDestroy(&g));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
