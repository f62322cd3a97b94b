// Per-level problems and their synchronisation in time (see multilevel_problem.hpp).
#include "mlshell/multilevel_problem.hpp"

#include "mlshell/effect_builder.hpp"
#include "mlshell/effects.hpp"

namespace mlshell {

MultilevelProblem::MultilevelProblem(const Scene& scene, const LevelHierarchy& levels,
                                     const CageFrame& frame)
    : MultilevelProblem(levels, scene.time.dt,
                        [&, scale = PenaltyScale::of(scene.material,
                                                     levels.discretization(levels.finest()),
                                                     levels.layout(levels.finest()))](int l) {
                          return build_level_problem(
                              scene, levels.discretization(l), levels.layout(l), frame,
                              levels.discretization(levels.finest()).mesh_size(), &scale);
                        }) {}

MultilevelProblem::MultilevelProblem(const Levels& levels, double dt, const LevelBuilder& build)
    : levels_(levels), dt_(dt) {
  for (int l = 0; l < levels.num_levels(); ++l) {
    problems_.push_back(build(l));
    Vec u, v;
    PetscCallAbort(levels.layout(l).comm(), levels.layout(l).create_vector(&u));
    PetscCallAbort(levels.layout(l).comm(), levels.layout(l).create_vector(&v));
    u_.push_back(u);
    v_.push_back(v);
  }
  replaced_.resize(problems_.size());
}

void MultilevelProblem::set_level_objective(int l, std::unique_ptr<Objective> objective) {
  if (l < 0 || l >= levels_.finest())
    throw std::logic_error("MultilevelProblem: level " + std::to_string(l) +
                           " is not a coarse level");
  replaced_[l] = std::move(objective);
}

MultilevelProblem::~MultilevelProblem() {
  for (Vec& u : u_) VecDestroy(&u);
  for (Vec& v : v_) VecDestroy(&v);
}

PetscErrorCode MultilevelProblem::synchronize(double time, Vec u_finest, Vec v_finest) {
  PetscFunctionBeginUser;
  const int top = levels_.finest();
  PetscCall(VecCopy(u_finest, u_[top]));
  PetscCall(VecCopy(v_finest, v_[top]));
  PetscCall(levels_.project_down(u_[top], u_));
  PetscCall(levels_.project_down(v_[top], v_));
  for (int l = 0; l <= top; ++l) {
    Vec predictor;
    PetscCall(VecDuplicate(u_[l], &predictor));
    PetscCall(VecWAXPY(predictor, dt_, v_[l], u_[l]));
    PetscCall(problems_[l]->begin_step(time, predictor));
    PetscCall(VecDestroy(&predictor));
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
