// What every kind of mesh shares: points in R³, and the error raised for a mesh that cannot be
// simulated (unreadable file, bad index, non-manifold, degenerate, non-finite coordinates).
#pragma once

#include <Eigen/Core>
#include <stdexcept>

namespace mlshell {

/// Raised for an invalid mesh; the message names the file or generator, the line, vertex or
/// face, and what was expected.
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using Point3 = Eigen::Vector3d;

}  // namespace mlshell
