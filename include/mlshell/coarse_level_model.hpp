// The coarse-level model of RMTR (paper eq. 4.3–4.4):
//   h(x) = f(x) + ⟨δg, x − x₀⟩,   δg = R ∇h_fine(x_fine) − ∇f(x₀),
// where f is the level's own objective and x₀ the projected fine iterate. It makes the first
// coarse gradient the restricted fine gradient, ∇h(x₀) = R ∇h_fine (first-order consistency,
// eq. 4.5), so the coarse minimisation starts downhill for the fine problem. ∇²h = ∇²f.
#pragma once

#include "mlshell/objective.hpp"

namespace mlshell {

class CoarseLevelModel final : public Objective {
 public:
  explicit CoarseLevelModel(Objective& level);
  ~CoarseLevelModel() override;
  CoarseLevelModel(const CoarseLevelModel&) = delete;
  CoarseLevelModel& operator=(const CoarseLevelModel&) = delete;

  /// Starts a coarse cycle at x₀ with the restricted fine gradient R ∇h_fine; returns
  /// f(x₀) = h(x₀) in *f0 if not null.
  PetscErrorCode initialize(Vec x0, Vec restricted_gradient, PetscReal* f0 = nullptr);
  /// Starts the level's own problem at x₀, h = f (δg = 0: RMTR's full-multigrid start solves
  /// the coarse levels' problems before the finest); f(x₀) and ∇f(x₀) into *f0 and g0.
  PetscErrorCode initialize_unmodified(Vec x0, PetscReal* f0, Vec g0);
  /// As initialize_unmodified, for a caller that knows f(x₀) and ∇f(x₀) already.
  PetscErrorCode set_unmodified(Vec x0);
  PetscErrorCode objective(Vec x, PetscReal* h, Vec g) override;
  PetscErrorCode hessian(Vec x, Mat H) override { return level_.hessian(x, H); }
  /// The level's error plus that of ⟨δg, x − x₀⟩ at the last point, 8 ε ‖δg‖ ‖x − x₀‖.
  PetscReal evaluation_error() const override;
  /// ‖δg‖ = ‖R∇h_fine − ∇f(x₀)‖ of the last initialize(): with ‖R∇h_fine‖, the size of the terms
  /// that cancel in ∇h(x₀), and so the scale of its round-off.
  PetscReal coupling_norm() const { return delta_g_norm_; }
  /// The linear term is smooth: the level's own step limit and acceptance hooks.
  PetscErrorCode max_step(Vec x, Vec d, PetscReal* alpha) override {
    return level_.max_step(x, d, alpha);
  }
  PetscErrorCode accepted(Vec x) override { return level_.accepted(x); }

 private:
  PetscErrorCode set_start(Vec x0);  // allocates on first use, copies x0
  Objective& level_;
  Vec x0_ = nullptr, delta_g_ = nullptr, work_ = nullptr;
  PetscReal delta_g_norm_ = 0.0;
};

}  // namespace mlshell
