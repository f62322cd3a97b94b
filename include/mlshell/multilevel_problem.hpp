// A scene's energy re-discretised on every level of a hierarchy (paper §4.2, §6, Fig. 7): each
// level assembles all of the scene's effects on its own discretization, with its own boundary
// selections, and all levels describe the same moment in time. They discretise one functional:
// the penalty β = h^-σ takes the finest level's h on every level (see build_level_problem).
// It is what RMTR works on (MultilevelObjective).
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "mlshell/level_problem.hpp"
#include "mlshell/multilevel_objective.hpp"
#include "mlshell/scene.hpp"
#include "mlshell/subdivision/level_hierarchy.hpp"
#include "mlshell/subdivision/selection.hpp"

namespace mlshell {

class MultilevelProblem final : public MultilevelObjective {
 public:
  /// Builds the problem of level l of any hierarchy.
  using LevelBuilder = std::function<std::unique_ptr<LevelProblem>(int level)>;
  /// `dt`: the step of the inertia predictor û = u + dt v.
  MultilevelProblem(const Levels& levels, double dt, const LevelBuilder& build);
  /// The scene on every subdivision level (build_level_problem).
  MultilevelProblem(const Scene& scene, const LevelHierarchy& levels, const CageFrame& frame);
  ~MultilevelProblem();
  MultilevelProblem(const MultilevelProblem&) = delete;
  MultilevelProblem& operator=(const MultilevelProblem&) = delete;

  int num_levels() const override { return static_cast<int>(problems_.size()); }
  LevelProblem& level(int l) { return *problems_[l]; }
  const Levels& hierarchy() const { return levels_; }
  /// Replaces what RMTR minimises on level l < finest (its first-order coarse models' f^l) by
  /// `objective`, e.g. a ProxyEnergy; the level's problem still follows the steps
  /// (synchronize). create_hessian(l) then takes the objective's pattern.
  void set_level_objective(int l, std::unique_ptr<Objective> objective);
  // MultilevelObjective
  Objective& level_objective(int l) override {
    return replaced_[l] ? *replaced_[l] : *problems_[l];
  }
  PetscErrorCode create_vector(int l, Vec* v) const override {
    return levels_.layout(l).create_vector(v);
  }
  PetscErrorCode create_hessian(int l, Mat* H) const override {
    return replaced_[l] ? replaced_[l]->create_hessian(H) : problems_[l]->create_matrix(H);
  }
  const LevelTransfer& transfer(int l) const override { return levels_.transfer(l); }
  PetscErrorCode composite_norm(int l, Vec x, PetscReal* norm) const override {
    return levels_.composite_norm(l, x, norm);
  }

  /// Displacement and velocity of level l after the last synchronize().
  Vec state(int l) const { return u_[l]; }
  Vec velocity(int l) const { return v_[l]; }

  /// Moves every level to time t (boundary motion, load ramps) and refreshes the coarse levels
  /// from the finest state by the projection Q: u_l = Q u_{l+1}, v_l = Q v_{l+1}; each level's
  /// inertia predictor becomes û_l = u_l + dt v_l. Call after each time step.
  PetscErrorCode synchronize(double time, Vec u_finest, Vec v_finest);

 private:
  const Levels& levels_;
  double dt_;
  std::vector<std::unique_ptr<LevelProblem>> problems_;
  std::vector<std::unique_ptr<Objective>> replaced_;  // by level, null where not replaced
  std::vector<Vec> u_, v_;
};

}  // namespace mlshell
