// The coarse-level model of RMTR (paper eq. 4.3–4.4):
//   h(x) = f(x) + ⟨δg, x − x₀⟩,   δg = R ∇h_fine(x_fine) − ∇f(x₀),
// where f is the level's own objective and x₀ the projected fine iterate. It makes the first
// coarse gradient the restricted fine gradient, ∇h(x₀) = R ∇h_fine (first-order consistency,
// eq. 4.5), so the coarse minimisation starts downhill for the fine problem. ∇²h = ∇²f.
//
// The second-order (Galerkin) model replaces f by the fine model's quadratic on the coarse
// space:
//   h(x) = ⟨R ∇h_fine, x − x₀⟩ + ½ (x − x₀)ᵀ G (x − x₀),   G = J_Pᵀ ∇²h_fine J_P,
// consistent to first and second order at x₀ whatever x₀ is. It serves where the projected
// fine iterate is no state the coarse discretisation can represent: the projections of the
// free-hanging drooping cloth have rediscretised coarse values up to 10²¹ (docs/CHANGELOG.md).
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
  /// Starts a coarse cycle at x₀ with the Galerkin model of the restricted gradient and
  /// G = `galerkin` (borrowed until the next initialize); h(x₀) = 0.
  PetscErrorCode initialize_galerkin(Vec x0, Vec restricted_gradient, Mat galerkin);
  /// Starts the level's own problem at x₀, h = f (δg = 0: RMTR's full-multigrid start solves
  /// the coarse levels' problems before the finest); f(x₀) and ∇f(x₀) into *f0 and g0.
  PetscErrorCode initialize_unmodified(Vec x0, PetscReal* f0, Vec g0);
  /// As initialize_unmodified, for a caller that knows f(x₀) and ∇f(x₀) already.
  PetscErrorCode set_unmodified(Vec x0);
  PetscErrorCode objective(Vec x, PetscReal* h, Vec g) override;
  /// ∇²f(x), or G (copied into H, whose pattern holds G's) for the Galerkin model.
  PetscErrorCode hessian(Vec x, Mat H) override;
  /// The level's error plus that of ⟨δg, x − x₀⟩ at the last point, 8 ε ‖δg‖ ‖x − x₀‖; for the
  /// Galerkin model 8 ε (‖r‖ + ‖G(x − x₀)‖) ‖x − x₀‖.
  PetscReal evaluation_error() const override;
  /// ‖δg‖ = ‖R∇h_fine − ∇f(x₀)‖ of the last initialize(): with ‖R∇h_fine‖, the size of the terms
  /// that cancel in ∇h(x₀), and so the scale of its round-off.
  PetscReal coupling_norm() const { return delta_g_norm_; }
  /// The linear term is smooth: the level's own step limit and acceptance hooks (none for the
  /// Galerkin model, which never evaluates the level).
  PetscErrorCode max_step(Vec x, Vec d, PetscReal* alpha) override {
    if (galerkin_) {
      *alpha = 1.0;
      return 0;
    }
    return level_.max_step(x, d, alpha);
  }
  PetscErrorCode accepted(Vec x) override { return galerkin_ ? 0 : level_.accepted(x); }
  long revision() const override { return galerkin_ ? 0 : level_.revision(); }

 private:
  PetscErrorCode set_start(Vec x0);  // allocates on first use, copies x0
  Objective& level_;
  Vec x0_ = nullptr, delta_g_ = nullptr, work_ = nullptr, product_ = nullptr;
  Mat galerkin_ = nullptr;  // G of the Galerkin model (borrowed); null: h = f + ⟨δg, x − x₀⟩
  PetscReal delta_g_norm_ = 0.0, product_norm_ = 0.0;  // ‖δg‖ (‖r‖ for Galerkin), ‖G(x − x₀)‖
};

}  // namespace mlshell
