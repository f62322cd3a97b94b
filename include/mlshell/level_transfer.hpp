// Transfers between two neighbouring levels of a hierarchy, as operations (paper 1 §4.2, §5.3;
// paper 2 eq. 4–9). RMTR is written against this interface only, so the same solver runs on
// linear subdivision transfers and on nonlinear shell prolongations:
//   prolong              x_f = P(x_c)
//   prolong_correction   s_f = P(x_c) − P(x₀)        the coarse correction (paper 1 eq. 4.10)
//   prolong_direction    J_P(x₀) d                    level norms (eq. 4.9)
//   restrict_gradient    g_c = J_P(x₀)ᵀ g_f           first-order consistency (eq. 4.4)
//   project              x_c = Π(x_f)                 the coarse start (eq. 4.6)
//   coarse_operator      A_c = J_P(x₀)ᵀ A_f J_P(x₀)   Galerkin coarse Hessians
//   relative_cost        W^l / W^{l+1}                work units (eq. 7.3)
// with x₀ the coarse start of the current coarse-level solve. A linear transfer (LinearTransfer)
// ignores x₀: P(x) = S x, J_P = S, J_Pᵀ = R = Sᵀ.
#pragma once

#include <petscmat.h>

#include <functional>

namespace mlshell {

class LevelTransfer {
 public:
  /// Π of eq. (4.6): the transfer's own projection (reverse subdivision for subdivision levels),
  /// the least-squares projection (Sᵀ S)⁻¹ Sᵀ, or the restriction scaled to preserve constants,
  /// diag(R 1)⁻¹ R (the last two for comparison, on linear transfers).
  enum class Projection { kNatural, kLeastSquares, kScaledRestriction };

  virtual ~LevelTransfer() = default;
  virtual PetscErrorCode prolong(Vec coarse, Vec fine) const = 0;
  virtual PetscErrorCode prolong_correction(Vec x0, Vec x, Vec fine_correction) const = 0;
  virtual PetscErrorCode prolong_direction(Vec x0, Vec direction, Vec fine) const = 0;
  virtual PetscErrorCode restrict_gradient(Vec x0, Vec fine_gradient,
                                           Vec coarse_gradient) const = 0;
  virtual PetscErrorCode project(Vec fine, Vec coarse, Projection kind) const = 0;
  /// J_P(x₀)ᵀ A J_P(x₀) into *coarse: created with MAT_INITIAL_MATRIX, refilled with
  /// MAT_REUSE_MATRIX (then A must keep the pattern it had).
  virtual PetscErrorCode coarse_operator(Vec x0, Mat fine, MatReuse reuse, Mat* coarse) const = 0;
  PetscErrorCode project(Vec fine, Vec coarse) const {
    return project(fine, coarse, Projection::kNatural);
  }
  virtual double relative_cost() const = 0;
};

/// The linear adapter: P(x) = S x with explicit S, R = Sᵀ and a projection matrix Q (all
/// borrowed; they must outlive the adapter), and optionally the least-squares projection as an
/// operation (it is dense as a matrix).
class LinearTransfer final : public LevelTransfer {
 public:
  using Operation = std::function<PetscErrorCode(Vec fine, Vec coarse)>;
  LinearTransfer(Mat S, Mat R, Mat Q, double relative_cost, Operation least_squares = {});
  ~LinearTransfer() override;
  LinearTransfer(const LinearTransfer&) = delete;
  LinearTransfer& operator=(const LinearTransfer&) = delete;

  PetscErrorCode prolong(Vec coarse, Vec fine) const override;
  /// S (x − x₀).
  PetscErrorCode prolong_correction(Vec x0, Vec x, Vec fine_correction) const override;
  PetscErrorCode prolong_direction(Vec x0, Vec direction, Vec fine) const override;
  PetscErrorCode restrict_gradient(Vec x0, Vec fine_gradient, Vec coarse_gradient) const override;
  PetscErrorCode project(Vec fine, Vec coarse, Projection kind) const override;
  using LevelTransfer::project;
  /// Sᵀ A S (MatPtAP).
  PetscErrorCode coarse_operator(Vec x0, Mat fine, MatReuse reuse, Mat* coarse) const override;
  double relative_cost() const override { return relative_cost_; }

 private:
  Mat S_, R_, Q_;
  double relative_cost_;
  Operation least_squares_;
  mutable Vec difference_ = nullptr;        // x − x₀, on first use
  mutable Vec inverse_row_sums_ = nullptr;  // diag(R 1)⁻¹, on first use
};

}  // namespace mlshell
