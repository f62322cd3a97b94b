// Shared pieces of all energy terms: their log events, local assembly.
#include "mlshell/energy_term.hpp"

#include "mlshell/element_matrix_assembly.hpp"
#include "mlshell/log_events.hpp"

#include <stdexcept>

namespace mlshell {

EnergyTerm::EnergyTerm(std::string name)
    : name_(std::move(name)), event_(mlshell::log_event("Effect:" + name_)) {}

std::vector<PetscInt> to_local_nodes(const ParallelLayout& layout, const int* nodes, int n) {
  std::vector<PetscInt> local(n);
  for (int i = 0; i < n; ++i) {
    local[i] = layout.local_of(nodes[i]);
    if (local[i] < 0) throw std::logic_error("element node is not local to its rank");
  }
  return local;
}

void add_local_gradient(const std::vector<PetscInt>& nodes, const double* g,
                        std::vector<double>& grad) {
  for (size_t i = 0; i < nodes.size(); ++i)
    for (int c = 0; c < 3; ++c) grad[3 * nodes[i] + c] += g[3 * i + c];
}

PetscErrorCode add_local_hessian(Mat H, const std::vector<PetscInt>& nodes, const double* values) {
  PetscFunctionBeginUser;
  PetscCall(add_element_matrix(H, static_cast<PetscInt>(nodes.size()), nodes.data(), values));
  PetscFunctionReturn(0);
}

double reference_area(const ElementBasis& b, int g, const std::vector<Point3>& X) {
  Point3 xu = Point3::Zero(), xv = Point3::Zero();
  const double* du = b.slot(g, kDu);
  const double* dv = b.slot(g, kDv);
  for (int i = 0; i < b.size; ++i) {
    xu += du[i] * X[b.nodes[i]];
    xv += dv[i] * X[b.nodes[i]];
  }
  return xu.cross(xv).norm();
}

}  // namespace mlshell
