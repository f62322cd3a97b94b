// Sum of a scene's energy terms on distributed vectors.
#include "mlshell/level_problem.hpp"

#include <cmath>

#include "mlshell/effects.hpp"

namespace mlshell {

LevelProblem::LevelProblem(const ParallelLayout& layout) : layout_(layout) {}

void LevelProblem::add_term(std::unique_ptr<EnergyTerm> term) { terms_.push_back(std::move(term)); }

void LevelProblem::set_time(double time) {
  for (auto& t : terms_) t->set_time(time);
}

PetscErrorCode LevelProblem::objective(Vec u, PetscReal* f, Vec g) {
  PetscFunctionBeginUser;
  ++objective_evaluations_;
  PetscCall(layout_.to_local(u, u_local_));
  if (g) g_local_.assign(u_local_.size(), 0.0);
  CompensatedSum local;
  for (const auto& t : terms_) {
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
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LevelProblem::hessian(Vec u, Mat H) {
  PetscFunctionBeginUser;
  ++hessian_evaluations_;
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
        const auto* p = dynamic_cast<const PenaltyTerm*>(&t);
        return p ? p->max_violation(ul) : 0.0;
      },
      MPI_MAX, violations);
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
  PetscCall(term_energies(u, energies));
  Vec g;
  PetscCall(VecDuplicate(u, &g));
  PetscCall(objective(u, total, g));
  PetscCall(VecNorm(g, NORM_2, gnorm));
  PetscCall(VecDestroy(&g));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
