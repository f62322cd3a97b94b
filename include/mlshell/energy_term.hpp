// One physical effect of a scene as an energy with gradient and Hessian on one level
// ("simulate only the effects a scene calls for": a term exists only if the scene lists it).
//
// Terms work on local arrays: `u` holds the displacements of the rank's local control points
// (ParallelLayout::local_points, 3 per point); a term adds the energy of the elements (or
// boundary/point pieces) this rank owns, adds its gradient into a local array that the caller
// sums into the global vector, and adds element Hessians with local block indices.
#pragma once

#include <petscmat.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "mlshell/parallel_layout.hpp"
#include "mlshell/subdivision/subdivision_discretization.hpp"

namespace mlshell {

/// Neumaier's compensated summation: energies are sums of many terms of both signs whose
/// differences the trust-region ratio needs accurately. It also sums the pieces' magnitudes,
/// weighted by how many roundings of their own size each piece carries (`error_weight`): the
/// rounding error of the total is about ε times magnitude() (Objective::evaluation_error).
class CompensatedSum {
 public:
  /// Adds x whose rounding error is that of pieces of total size `magnitude` (≥ |x| when the
  /// computation of x cancels, e.g. a strain energy near its rest state).
  void add_with_magnitude(double x, double magnitude) {
    add(x, 0.0);
    magnitude_ += magnitude;
  }
  void add(double x, double error_weight = 1.0) {
    const double t = sum_ + x;
    comp_ += std::abs(sum_) >= std::abs(x) ? (sum_ - t) + x : (x - t) + sum_;
    sum_ = t;
    magnitude_ += error_weight * std::abs(x);
  }
  double value() const { return sum_ + comp_; }
  double magnitude() const { return magnitude_; }

 private:
  double sum_ = 0.0, comp_ = 0.0, magnitude_ = 0.0;
};

/// What every term learns when a time (or load) step begins: the time of the state being solved
/// for and, for the terms that need it, the step's predictor.
struct StepStart {
  double time = 0.0;
  /// Local values (3 per local point) of the inertia predictor û = u_n + dt v_n (implicit Euler)
  /// or of the last state xᵗ (the proximal term of quasistatics); may be null.
  const std::vector<double>* predictor = nullptr;
};

class EnergyTerm {
 public:
  explicit EnergyTerm(std::string name);
  virtual ~EnergyTerm() = default;
  const std::string& name() const { return name_; }
  PetscLogEvent log_event() const { return event_; }
  /// Index of the scene's `effects:` entry the term was built for; -1 for the terms every
  /// scene has (elastic) or its integrator adds (proximal).
  int effect_index() const { return effect_index_; }
  void set_effect_index(int index) { effect_index_ = index; }

  /// Time of the state being solved for (moves boundary conditions, ramps loads).
  virtual void set_time(double time) { time_ = time; }

  // Hooks of the solve (DESIGN.md, "EnergyTerm hooks"). The defaults are those of a smooth term
  // whose Hessian lives on the element stencils.

  /// A step begins: moves the term to `start.time` (set_time) and takes the per-step data it
  /// needs (the inertia term its predictor; later, lagged friction bases).
  virtual void begin_step(const StepStart& start) { set_time(start.time); }
  /// Whether max_step can return less than 1 (then solvers ask it before every trial point).
  virtual bool limits_steps() const { return false; }
  /// The largest α ∈ (0, 1] such that u + α du stays admissible for this term (a collision-free
  /// step for contact, by continuous collision detection); local arrays as in add().
  virtual double max_step(const std::vector<double>& u, const std::vector<double>& du) const {
    return 1.0;
  }
  /// The solver accepted the iterate u (local array): adaptive barrier stiffness, friction
  /// lagging.
  virtual void after_accept(const std::vector<double>& u) {}
  /// Changes whenever after_accept (or a constraint update) changes the term's energy function.
  virtual long revision() const { return 0; }
  /// Point pairs (natural indices) that the term's Hessian couples beyond the element stencils
  /// (contact pairs); the level's Hessian is preallocated for them.
  virtual void extend_sparsity(std::vector<std::array<int, 2>>& pairs) const {}
  /// Changes whenever extend_sparsity's pairs do: LevelProblem rebuilds a Hessian made for an
  /// older version.
  virtual long sparsity_version() const { return 0; }
  /// Before a Hessian at the prepared state: adapts extend_sparsity's pairs to it (collective).
  virtual PetscErrorCode update_sparsity() { return 0; }

  /// Terms whose stencils reach beyond the layout's local points (contact with another rank's
  /// surface) read the global vectors in prepare(u, du) before add (du null), max_step and
  /// after_accept (collective: LevelProblem calls it on every rank with the same vectors whose
  /// local values those hooks then get), and add the gradient at points that are not local in
  /// add_nonlocal_gradient, after add.
  virtual bool needs_prepare() const { return false; }
  virtual PetscErrorCode prepare(Vec u, Vec du) { return 0; }
  virtual PetscErrorCode add_nonlocal_gradient(Vec g) const { return 0; }
  /// Constraints solved by an augmented Lagrangian (an outer loop around the solve): whether the
  /// term has one, its violation at u (local; the same measure as its tolerance) and its
  /// tolerance, and the first-order multiplier update λ ← λ − β c(u) given the violation over
  /// all ranks.
  virtual bool has_multipliers() const { return false; }
  /// The violation of the constraint at u (local), in the units of constraint_tolerance; 0 for
  /// terms without one.
  virtual double constraint_violation(const std::vector<double>& u) const { return 0.0; }
  virtual double constraint_tolerance() const { return 0.0; }
  virtual void update_multipliers(const std::vector<double>& u, double violation) {}
  /// Per-element output fields (e.g. a triangle's membrane strain): their names, and their
  /// values on this rank's elements (ParallelLayout::local_elements() order) at u (local).
  virtual std::vector<std::string> face_field_names() const { return {}; }
  virtual void face_field_values(const std::vector<double>& u,
                                 std::vector<std::vector<double>>& values) const {}
  /// Projected Newton (paper 2 §4.5, -mlshell_hessian_psd): terms with non-convex element
  /// energies add each element Hessian projected onto the positive semi-definite cone.
  void set_hessian_projection(bool on) { project_hessian_ = on; }
  bool projects_hessian() const { return project_hessian_; }
  /// Adds this rank's part of the energy, gradient (if `grad`) and Hessian (if `hess`).
  virtual PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                             std::vector<double>* grad, Mat hess) const = 0;
  /// Terms whose Hessian does not depend on u may keep it assembled and add it here, after the
  /// element Hessians are assembled (H has the element-stencil pattern): cheaper than inserting
  /// the same element matrices again at every Newton step.
  virtual PetscErrorCode add_constant_hessian(Mat hess) const { return 0; }

 protected:
  double time_ = 0.0;
  bool project_hessian_ = false;

 private:
  std::string name_;
  PetscLogEvent event_;
  int effect_index_ = -1;
};

/// Maps natural node indices to local ones (all must be local on this rank).
std::vector<PetscInt> to_local_nodes(const ParallelLayout& layout, const int* nodes, int n);

/// grad[3 node + c] += g[3 i + c]
void add_local_gradient(const std::vector<PetscInt>& nodes, const double* g,
                        std::vector<double>& grad);

/// Adds a dense (3n × 3n, row-major) block to the matrix with local block indices.
PetscErrorCode add_local_hessian(Mat H, const std::vector<PetscInt>& nodes, const double* values);

/// Reference area element J̄ = |X_u × X_v| at quadrature point g of an element.
double reference_area(const ElementBasis& b, int g, const std::vector<Point3>& X);

}  // namespace mlshell
