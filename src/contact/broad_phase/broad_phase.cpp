// The broad phase's entry points (broad_phase.hpp): input checks, the primitives' boxes, and
// the chosen method.
#include "mlshell/contact/broad_phase/broad_phase.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "primitive_boxes.hpp"

namespace mlshell {

namespace {

void check_positions(const ContactSurface& surface, std::span<const Eigen::Vector3d> x,
                     const char* name) {
  if (static_cast<long>(x.size()) != surface.num_vertices)
    throw std::invalid_argument(std::string("contact broad phase: ") + name + " has " +
                                std::to_string(x.size()) + " points for a surface of " +
                                std::to_string(surface.num_vertices) + " vertices");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!x[i].allFinite())
      throw std::invalid_argument(std::string("contact broad phase: ") + name + " of vertex " +
                                  std::to_string(i) + " is not finite");
}

ContactCandidates candidates(const ContactSurface& surface, std::span<const Eigen::Vector3d> x0,
                             std::span<const Eigen::Vector3d> x1, double distance,
                             BroadPhaseMethod method) {
  if (!(std::isfinite(distance) && distance >= 0.0))
    throw std::invalid_argument("contact broad phase: the distance must be finite and ≥ 0, got " +
                                std::to_string(distance));
  const auto boxes = contact_detail::primitive_boxes(surface, x0, x1, distance);
  return method == BroadPhaseMethod::kSpatialHash
             ? contact_detail::spatial_hash_candidates(surface, boxes)
             : contact_detail::bvh_candidates(surface, boxes);
}

}  // namespace

ContactCandidates find_proximity_candidates(const ContactSurface& surface,
                                            std::span<const Eigen::Vector3d> x, double distance,
                                            BroadPhaseMethod method) {
  check_positions(surface, x, "the positions");
  return candidates(surface, x, x, distance, method);
}

ContactCandidates find_swept_candidates(const ContactSurface& surface,
                                        std::span<const Eigen::Vector3d> x0,
                                        std::span<const Eigen::Vector3d> x1, double distance,
                                        BroadPhaseMethod method) {
  check_positions(surface, x0, "x0");
  check_positions(surface, x1, "x1");
  return candidates(surface, x0, x1, distance, method);
}

}  // namespace mlshell
