// Prescribed rigid motions as the energy terms see them: at each time a placement
//   φ(X) = R (X − c) + c + T
// of the reference points X, whose displacement φ(X) − X is the target of a Dirichlet sample,
// whose rotation R turns a clamp's reference frame (its conormal slope, its virtual vertices
// move with φ), and which a scripted obstacle can apply to its vertices. The scene's Motion
// (scene.hpp) says how R, c and T grow with time; motion_function (effect_builder.hpp) turns it
// into a PrescribedMotion.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace mlshell {

/// The rigid placement φ(X) = R (X − c) + c + T at one time.
struct RigidPlacement {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< R
  Eigen::Vector3d center = Eigen::Vector3d::Zero();        ///< c, on the axis of R
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();   ///< T

  /// φ(X).
  Eigen::Vector3d position(const Eigen::Vector3d& X) const {
    return rotation * (X - center) + center + translation;
  }
  /// φ(X) − X, the prescribed displacement of X.
  Eigen::Vector3d displacement(const Eigen::Vector3d& X) const { return position(X) - X; }
  /// (R − I) v: how a reference direction v (a conormal slope) changes.
  Eigen::Vector3d turn(const Eigen::Vector3d& v) const { return rotation * v - v; }
};

/// The placement at time t; the identity for a selection that does not move.
using PrescribedMotion = std::function<RigidPlacement(double t)>;

}  // namespace mlshell
