// What the solver tests share: PETSc options set for a scope, and the distances between two
// results in natural order.
#pragma once

#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace mlshell {

/// Sets PETSc options for the lifetime of the object.
struct ScopedOptions {
  std::vector<std::string> names;
  explicit ScopedOptions(std::initializer_list<std::pair<const char*, const char*>> options) {
    for (const auto& [name, value] : options) {
      PetscOptionsSetValue(nullptr, name, value);
      names.emplace_back(name);
    }
  }
  ~ScopedOptions() {
    for (const auto& n : names) PetscOptionsClearValue(nullptr, n.c_str());
  }
};

/// max |a − b|.
inline double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

/// max |a|.
inline double max_abs(const std::vector<double>& a) {
  double m = 0.0;
  for (double x : a) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace mlshell
