// Scripted colliders (collider_motion.hpp).
#include "mlshell/contact/collider_motion.hpp"

#include <petscsys.h>

namespace mlshell {

namespace {
/// Shorter targets tried per advance before the colliders wait for the next solve.
constexpr int kMaxCuts = 8;
}  // namespace

ColliderMotion::ColliderMotion(ContactTerm& contact, std::vector<PrescribedMotion> motions,
                               Vec like)
    : contact_(contact), motions_(std::move(motions)) {
  if (motions_.size() != contact_.obstacles().size())
    throw std::logic_error("collider motion: one motion per obstacle");
  for (const TriangleMesh& o : contact_.obstacles()) reference_.push_back(o.points);
  PetscCallAbort(PetscObjectComm(reinterpret_cast<PetscObject>(like)), VecDuplicate(like, &du_));
}

ColliderMotion::~ColliderMotion() { VecDestroy(&du_); }

std::vector<std::vector<Point3>> ColliderMotion::places(double time) const {
  std::vector<std::vector<Point3>> out = reference_;
  for (std::size_t k = 0; k < out.size(); ++k)
    if (motions_[k]) {
      const RigidPlacement phi = motions_[k](time);
      for (Point3& x : out[k]) x = phi.position(x);
    }
  return out;
}

void ColliderMotion::place_at(double time) {
  contact_.move_obstacles(places(time));
  time_ = time;
}

PetscErrorCode ColliderMotion::advance(double time, Vec u, bool* reached) {
  PetscFunctionBeginUser;
  *reached = time == time_;
  if (*reached) PetscFunctionReturn(0);
  double target = time;
  for (int cut = 0; cut <= kMaxCuts; ++cut) {
    // The rigid motion from the colliders' place now to that at the target, and who moves.
    std::vector<RigidPlacement> from(motions_.size()), to(motions_.size());
    std::vector<char> moving(motions_.size(), 0);
    for (std::size_t k = 0; k < motions_.size(); ++k)
      if (motions_[k]) {
        from[k] = motions_[k](time_), to[k] = motions_[k](target);
        moving[k] = from[k].rotation != to[k].rotation || from[k].translation != to[k].translation;
      }
    const auto place = [&](int k, const Point3& x) -> Point3 {
      const RigidPlacement &a = from[k], &b = to[k];
      return b.position(a.rotation.transpose() * (x - a.center - a.translation) + a.center);
    };
    const std::vector<std::vector<Point3>> points = places(target);
    PetscCall(contact_.carry(u, points, moving, place, du_));
    double alpha;
    PetscCall(contact_.obstacle_step_limit(u, du_, points, &alpha));
    if (alpha >= 1.0) {
      PetscCall(VecAXPY(u, 1.0, du_));
      contact_.move_obstacles(points);
      ++moves_;
      if (target != time) ++cut_moves_;
      time_ = target;
      *reached = target == time;
      PetscFunctionReturn(0);
    }
    if (!(alpha > 0.0)) break;  // blocked now: the next solve lets the barrier push
    target = time_ + alpha * (target - time_);
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
