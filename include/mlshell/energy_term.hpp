// One physical effect of a scene as an energy with gradient and Hessian on one level
// ("simulate only the effects a scene calls for": a term exists only if the scene lists it).
//
// Terms work on local arrays: `u` holds the displacements of the rank's local control points
// (ParallelLayout::local_points, 3 per point); a term adds the energy of the elements (or
// boundary/point pieces) this rank owns, adds its gradient into a local array that the caller
// sums into the global vector, and adds element Hessians with local block indices.
#pragma once

#include <petscmat.h>

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

class EnergyTerm {
 public:
  explicit EnergyTerm(std::string name);
  virtual ~EnergyTerm() = default;
  const std::string& name() const { return name_; }
  PetscLogEvent log_event() const { return event_; }

  /// Time of the state being solved for (moves boundary conditions, ramps loads).
  virtual void set_time(double time) { time_ = time; }
  /// Adds this rank's part of the energy, gradient (if `grad`) and Hessian (if `hess`).
  virtual PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                             std::vector<double>* grad, Mat hess) const = 0;
  /// Terms whose Hessian does not depend on u may keep it assembled and add it here, after the
  /// element Hessians are assembled (H has the element-stencil pattern): cheaper than inserting
  /// the same element matrices again at every Newton step.
  virtual PetscErrorCode add_constant_hessian(Mat hess) const { return 0; }

 protected:
  double time_ = 0.0;

 private:
  std::string name_;
  PetscLogEvent event_;
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
