// A scene's energy re-discretised on every level of a hierarchy (paper §4.2, §6, Fig. 7): each
// level assembles all of the scene's effects on its own discretization, with its own penalty
// β_l = h_l^-σ and its own boundary conditions, and all levels describe the same moment in time.
#pragma once

#include <memory>
#include <vector>

#include "mlshell/level_hierarchy.hpp"
#include "mlshell/level_problem.hpp"
#include "mlshell/scene.hpp"
#include "mlshell/selection.hpp"

namespace mlshell {

class MultilevelProblem {
 public:
  MultilevelProblem(const Scene& scene, const LevelHierarchy& levels, const CageFrame& frame);
  ~MultilevelProblem();
  MultilevelProblem(const MultilevelProblem&) = delete;
  MultilevelProblem& operator=(const MultilevelProblem&) = delete;

  int num_levels() const { return static_cast<int>(problems_.size()); }
  LevelProblem& level(int l) { return *problems_[l]; }
  const LevelHierarchy& hierarchy() const { return levels_; }
  /// Displacement and velocity of level l after the last synchronize().
  Vec state(int l) const { return u_[l]; }
  Vec velocity(int l) const { return v_[l]; }

  /// Moves every level to time t (boundary motion, load ramps) and refreshes the coarse levels
  /// from the finest state by the projection Q: u_l = Q u_{l+1}, v_l = Q v_{l+1}; each level's
  /// inertia predictor becomes û_l = u_l + dt v_l. Call after each time step.
  PetscErrorCode synchronize(double time, Vec u_finest, Vec v_finest);

 private:
  const LevelHierarchy& levels_;
  double dt_;
  std::vector<std::unique_ptr<LevelProblem>> problems_;
  std::vector<Vec> u_, v_;
};

}  // namespace mlshell
