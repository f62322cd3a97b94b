// One proxy step of a progressive level: Algorithm 1 of paper 2 (Appendix B, §4.5).
//
//   i ← 0
//   while i < max_iter:
//     H ← Newton matrix at x          (Galerkin J_Pᵀ PSD(∇²Ψ) J_P, or the level's own
//                                       M_l/h² + PSD(∇²E_l): the caller's choice)
//     g ← ∇F(x)                         (the proxy's gradient: exact, or eq. 10's frozen offset)
//     d ← −H⁻¹ g
//     if ‖d‖₂ < tolerance: stop          (√n_l h ε of the paper)
//     α ← line search on F from min(1, F.max_step(x, d))   (backtracking, Armijo)
//     if α < γ: stop
//     x ← x + α d,  i ← i + 1
//   in equilibrium if no iteration was taken
//
// The objective's max_step is the step-size filter (contact's CCD joins there); its accepted()
// hears of every new iterate. The linear solver is a KSP with the options prefix
// `mlshell_preview_` (default: a direct MUMPS factorisation, -mlshell_preview_ksp_type preonly
// -mlshell_preview_pc_type lu).
#pragma once

#include <petscksp.h>

#include <functional>
#include <string>

#include "mlshell/objective.hpp"

namespace mlshell {

struct ProxyStepSettings {
  int max_iterations = 5;  ///< max_iter
  double tolerance = 0.0;  ///< on ‖d‖₂, absolute (m)
  double min_step = 1e-3;  ///< γ
};

struct ProxyStepReport {
  int iterations = 0;
  int linear_iterations = 0;
  double energy = 0.0;         ///< F at the step's end
  double gradient_norm = 0.0;  ///< ‖∇F‖₂ at the step's end
  double step_norm = 0.0;      ///< ‖d‖₂ of the last direction
  double alpha = 0.0;          ///< the last line search's step (0 where none ran)
  /// Stopped before the first iteration (Alg. 1 line 21): on a short Newton step, or on a line
  /// search that found no step α ≥ γ from there.
  bool equilibrium = false;
  /// STEP_NORM (‖d‖ < tolerance), LINE_SEARCH (α < γ), MAX_ITERATIONS, LINEAR_SOLVE_FAILED (no
  /// factorisation, or no descent) or NONFINITE (F or ∇F not finite at the start or after an
  /// accepted step).
  std::string stop;
};

class ProxyNewton {
 public:
  /// Fills the Newton matrix at x into H.
  using NewtonMatrix = std::function<PetscErrorCode(Vec x, Mat H)>;
  /// `objective`: F; `H`: a matrix newton_matrix fills (borrowed, it must outlive this);
  /// `like`: a vector of the level. Collective.
  ProxyNewton(Objective& objective, Mat H, NewtonMatrix newton_matrix, Vec like);
  ~ProxyNewton();
  ProxyNewton(const ProxyNewton&) = delete;
  ProxyNewton& operator=(const ProxyNewton&) = delete;

  /// Algorithm 1 from x, in place.
  PetscErrorCode step(Vec x, const ProxyStepSettings& settings, ProxyStepReport* report);

 private:
  Objective& objective_;
  Mat H_;
  NewtonMatrix newton_matrix_;
  KSP ksp_ = nullptr;
  Vec g_ = nullptr, d_ = nullptr, trial_ = nullptr;
};

}  // namespace mlshell
