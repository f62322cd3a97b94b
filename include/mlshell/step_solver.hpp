// Solves one step's minimisation problem with a PETSc TAO solver (options prefix `-tao_`).
//
// Defaults (all overridable from the command line or an options file, which win):
//   -tao_type bntr -tao_gatol 1e-7 (paper eq. 7.1) -tao_gttol 1e-10 -tao_grtol 0 -tao_max_it 1000
// and, for the KSP of whichever Newton-type TAO solver is chosen (prefix tao_bnk_ for
// bntr/bnls/bqnkls..., tao_nls_ for nls, ...): ksp_type stcg, pc_type lu,
// pc_factor_mat_solver_type mumps.
// i.e. a Newton trust-region method whose subproblem is solved with a sparse direct
// factorisation (the recursive multilevel trust region arrives with its own TAO type).
#pragma once

#include <petsctao.h>

#include <string>

#include "mlshell/level_problem.hpp"

namespace mlshell {

struct SolveReport {
  bool converged = false;
  std::string reason;  ///< TAO's converged reason, e.g. CONVERGED_GATOL
  int iterations = 0;
  int linear_iterations = 0;
  double energy = 0.0;
  double gradient_norm = 0.0;
};

class StepSolver {
 public:
  explicit StepSolver(LevelProblem& problem);
  ~StepSolver();
  StepSolver(const StepSolver&) = delete;
  StepSolver& operator=(const StepSolver&) = delete;

  /// Minimises from the displacement in `u`, leaving the result there.
  PetscErrorCode solve(Vec u, SolveReport& report);
  Tao tao() const { return tao_; }
  std::string type() const;

 private:
  LevelProblem& problem_;
  Tao tao_ = nullptr;
  Mat H_ = nullptr;
};

}  // namespace mlshell
