// What a run does for a scene with contact (the `contact` effect, contact_term.hpp): the solvers
// it accepts, the check of the start, the colliders' surface as output and the summary's
// contact section. The audit of every frame against the colliders is in audit_frame.
#include <cmath>
#include <iomanip>
#include <sstream>

#include "mlshell/contact/collider_motion.hpp"
#include "mlshell/contact/contact_term.hpp"
#include "mlshell/simulation.hpp"
#include "simulation_output.hpp"

namespace mlshell {

namespace {

std::string contact_key(const Scene& scene, const ContactTerm& contact) {
  return scene.file.string() + ": effects[" + std::to_string(contact.effect_index()) + "].contact";
}

}  // namespace

void Simulation::check_contact_solver() const {
  // Projected Newton's line search, the trust region's trial points and SNES newtonls's line
  // search (a pre-check) are cut to CCD's max_step; TAO's own solvers and RMTR's coarse
  // corrections are not (yet).
  const std::string& type = options_.solver->type;
  if (type == "pnewton" || type == "tr") return;
  if (type == "snes") {  // newtonls's line search starts within CCD's step (step_solver.cpp)
    char snes_type[64] = "newtonls", line_search[64] = "bt";
    PetscReal damping = 1.0;
    PetscCallAbort(comm_, PetscOptionsGetString(nullptr, nullptr, "-snes_type", snes_type,
                                                sizeof snes_type, nullptr));
    PetscCallAbort(comm_, PetscOptionsGetString(nullptr, nullptr, "-snes_linesearch_type",
                                                line_search, sizeof line_search, nullptr));
    PetscCallAbort(comm_, PetscOptionsGetReal(nullptr, nullptr, "-snes_linesearch_damping",
                                              &damping, nullptr));
    const std::string t = snes_type, ls = line_search;
    // Backtracking and the plain step never go beyond λ = 1 (with damping ≤ 1); the others
    // may extrapolate past the direction CCD cut.
    if (t == "newtonls" && (ls == "bt" || ls == "basic") && damping <= 1.0) return;
    throw SceneError(contact_key(scene_, *contact_) + ": -snes_type " + t +
                     " with -snes_linesearch_type " + ls + " (damping " +
                     std::to_string(damping) +
                     ") may step beyond continuous collision detection's limit; contact scenes "
                     "run SNES as newtonls with the bt or basic line search, damping <= 1");
  }
  throw SceneError(contact_key(scene_, *contact_) + ": the solver '" + type +
                   "' does not keep its steps within continuous collision detection's limit, so "
                   "it could step through a contact; use -tao_type pnewton (e.g. solver: "
                   "{options_file: petsc-options/projected-newton.yaml}), -tao_type tr or "
                   "-mlshell_step_solver snes");
}

PetscErrorCode Simulation::start_contact() {
  PetscFunctionBeginUser;
  PetscCall(contact_->prepare(u_, nullptr));
  double d;
  PetscCall(contact_->min_squared_distance(&d));
  const double xi = contact_->settings().barrier.thickness;
  if (!(d > xi * xi)) {
    std::ostringstream message;
    message << contact_key(scene_, *contact_) << ": the shell starts " << std::setprecision(6)
            << std::sqrt(std::max(d, 0.0)) << " m from itself or a collider, within the contact "
            << "thickness " << xi << " m: move it (or the collider) apart, or give a smaller "
            << "`thickness`";
    throw SceneError(message.str());
  }
  const double reach = xi + contact_->settings().barrier.gap;
  if (d < reach * reach)  // a mesh finer than ξ + ĝ (self-contact) or a collider close by
    PetscCall(PetscPrintf(comm_,
                          "mlshell: warning: the contact barrier acts at the start: pairs %g m "
                          "apart are within thickness + gap = %g m, so the shell is pushed "
                          "even at rest; a smaller gap or thickness (or self: false) avoids it\n",
                          std::sqrt(d), reach));
  if (rank_ == 0 && !contact_->obstacles().empty()) write_colliders("colliders.obj");
  PetscFunctionReturn(0);
}

void Simulation::start_collider_motion(double time) {
  std::vector<PrescribedMotion> motions;
  bool any = false;
  for (const Effect& e : scene_.effects)
    if (const auto* c = std::get_if<ColliderEffect>(&e)) {
      motions.push_back(c->motion ? motion_function(c->motion) : PrescribedMotion());
      any = any || c->motion.has_value();
    }
  if (!any) return;
  collider_motion_ = std::make_unique<ColliderMotion>(*contact_, std::move(motions), u_);
  collider_motion_->place_at(time);
  stepper_->set_kinematics(collider_motion_.get());
}

void Simulation::write_colliders(const std::string& file) const {
  std::ostringstream obj;
  obj << "# mlshell colliders of " << scene_.name << ", one object per collider\n"
      << std::setprecision(17);
  int offset = 1;
  for (std::size_t k = 0; k < contact_->obstacles().size(); ++k) {
    const TriangleMesh& m = contact_->obstacles()[k];
    obj << "o collider_" << k << '\n';
    for (const Point3& p : m.points) obj << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    for (const Triangle& t : m.triangles)
      obj << "f " << t[0] + offset << ' ' << t[1] + offset << ' ' << t[2] + offset << '\n';
    offset += m.num_points();
  }
  write_file_atomic(output_->dir / file, obj.str());
}

PetscErrorCode Simulation::contact_summary(Json* out) const {
  PetscFunctionBeginUser;
  *out = Json(nullptr);
  if (!contact_) PetscFunctionReturn(0);
  PetscCall(contact_->prepare(u_, nullptr));
  ContactStatistics s;
  PetscCall(contact_->statistics(&s));
  const ContactSettings& c = contact_->settings();
  *out = Json(Json::Object{
      {"thickness", Json(c.barrier.thickness)},
      {"gap", Json(c.barrier.gap)},
      {"self", Json(c.self_contact)},
      {"colliders", Json(static_cast<long long>(contact_->obstacles().size()))},
      {"stiffness", Json(s.stiffness)},
      {"stiffness_fixed", Json(c.stiffness > 0.0)},
      {"candidate_pairs", Json(static_cast<long long>(s.candidates))},
      {"active_pairs", Json(static_cast<long long>(s.active))},
      {"min_distance", std::isfinite(s.min_distance) ? Json(s.min_distance) : Json(nullptr)},
      {"halo_points", Json(static_cast<long long>(s.halo_points))},
      {"pattern_rebuilds", Json(static_cast<long long>(s.pattern_rebuilds))},
      {"broad_phase_builds", Json(static_cast<long long>(s.list_builds))}});
  if (collider_motion_) {  // scripted colliders: their moves, and those CCD cut short
    out->set("collider_moves", Json(static_cast<long long>(collider_motion_->moves())));
    out->set("collider_moves_cut", Json(static_cast<long long>(collider_motion_->cut_moves())));
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
