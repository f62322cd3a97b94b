// Result files of a run (see simulation.hpp): limit-surface frames (HDF5/XDMF written by all
// ranks in parallel; OBJ), checkpoints of converged steps, and summary.json (these by rank 0
// from natural-order data).
#include "simulation_output.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "mlshell/build_info.hpp"
#include "mlshell/effects.hpp"
#include "mlshell/output_files.hpp"
#include "mlshell/simulation.hpp"

#include "mlshell/contact/audit/intersection_audit.hpp"
#include "mlshell/contact/contact_term.hpp"
#include "mlshell/triangle/triangle_bodies.hpp"
#include "mlshell/triangle/triangle_discretization.hpp"
#include "mlshell/unused_options.hpp"

namespace mlshell {

namespace {

/// Whether glibc's malloc was asked for transparent huge pages (the CLI's restart, main.cpp).
bool huge_pages_requested() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  return tunables && std::string(tunables).find("glibc.malloc.hugetlb=1") != std::string::npos;
}

/// The PETSc options database as one "-name value ..." line: the options in effect, mlshell's
/// defaults included (StepSolver sets them wherever no file or command line did), so that a
/// run's configuration can be read and repeated from its summary.
std::string petsc_options_in_effect() {
  char* all = nullptr;
  if (PetscOptionsGetAll(nullptr, &all) || !all) return "";
  std::string text(all);
  PetscFree(all);
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace

PetscErrorCode Simulation::write_frame(int n, double t, bool force, bool converged) {
  PetscFunctionBeginUser;
  const bool frame_due = force || n % scene_.output.every == 0;
  // run() audits the start
  if (frame_due) PetscCall(write_series_frame(output_->frames, u_, n, t, n > first_step_));
  // Only converged states are worth restarting from.
  const bool checkpoint_due = converged && scene_.output.checkpoint_every > 0 && n > 0 &&
                              n % scene_.output.checkpoint_every == 0;
  if (checkpoint_due) {
    std::vector<double> u, v;
    PetscCall(layout_->gather_natural(u_, u));
    PetscCall(layout_->gather_natural(v_, v));
    if (rank_ == 0) {
      char name[64];
      std::snprintf(name, sizeof name, "checkpoint_%06d.bin", n);
      write_checkpoint(output_->dir / name,
                       {n, t, discretization_fingerprint(*disc_), std::move(u), std::move(v)});
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::write_series_frame(FrameSeries& series, Vec u, int n, double t,
                                              bool audit) {
  PetscFunctionBeginUser;
  if (audit && options_.audit_intersections) {
    long pairs;
    PetscCall(audit_frame(series, u, n, t, &pairs, &audit_message_));
  }
  if (collider_motion_ && series.disc == disc_ && rank_ == 0) {  // where the colliders are now
    char name[64];
    std::snprintf(name, sizeof name, "colliders_%06d.obj", n);
    write_colliders(name);
  }
  const auto& formats = scene_.output.formats;
  auto has = [&](const char* f) {
    return std::find(formats.begin(), formats.end(), f) != formats.end();
  };
  if (!has("xdmf") && !has("obj")) PetscFunctionReturn(0);
  // Per-face fields are XDMF cell data; OBJ has none.
  std::vector<std::pair<std::string, std::vector<double>>> fields;
  if (has("xdmf")) PetscCall(series.problem->face_fields(u, series.disc->num_faces(), fields));
  PetscCall(write_frame_files(series, u, n, t, has("xdmf"), has("obj"), fields));
  PetscFunctionReturn(0);
}

// Every rank samples its slice of the surface and formats or writes it: nothing is gathered
// but the OBJ text.
PetscErrorCode Simulation::write_frame_files(
    FrameSeries& series, Vec u, int n, double t, bool xdmf, bool obj,
    const std::vector<std::pair<std::string, std::vector<double>>>& fields) {
  PetscFunctionBeginUser;
  FrameData frame;
  frame.cell_size = series.sampling->cell_size();
  PetscCall(series.sampling->sample(u, &frame.geometry, &frame.displacement));
  PetscCall(series.sampling->topology(&frame.topology));
  // Per-face fields go with samplings that have one cell per face (triangle meshes); they are
  // on rank 0 (LevelProblem::face_fields), which holds the whole dataset.
  if (series.sampling->num_cells() == series.disc->num_faces())
    for (const auto& [name, values] : fields) {
      Vec v;
      PetscCall(VecCreateMPIWithArray(comm_, 1, static_cast<PetscInt>(values.size()),
                                      PETSC_DETERMINE, values.data(), &v));
      PetscCall(PetscObjectSetName((PetscObject)v, ("cell_" + name).c_str()));
      frame.cell_fields.emplace_back(name, v);
    }
  auto destroy = [&] {
    VecDestroy(&frame.geometry);
    VecDestroy(&frame.displacement);
    ISDestroy(&frame.topology);
    for (auto& field : frame.cell_fields) VecDestroy(&field.second);
  };
  try {
    if (xdmf) {
      if (!series.xdmf)
        series.xdmf = std::make_unique<XdmfSeries>(output_->dir, series.stem, comm_);
      series.xdmf->add_frame(n, t, frame);
    }
    if (obj) {
      char name[64];
      std::snprintf(name, sizeof name, "_%06d.obj", n);
      std::ostringstream c;
      c << "mlshell " << series.stem << " step " << n << " time " << t;
      write_obj(comm_, output_->dir / (series.obj_prefix + name), frame, c.str());
    }
  } catch (...) {
    destroy();
    throw;
  }
  destroy();
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::audit_frame(const FrameSeries& series, Vec state, int n, double t,
                                       long* pairs, std::string* message) {
  PetscFunctionBeginUser;
  const auto* triangles = dynamic_cast<const TriangleDiscretization*>(series.disc);
  *pairs = 0;
  message->clear();
  if (!triangles) PetscFunctionReturn(0);  // subdivision surfaces: not audited (yet)
  std::vector<double> u;
  PetscCall(series.layout->gather_natural(state, u));
  std::array<long, 3> found{0, -1, -1};  // pairs, and the first pair's triangles
  if (rank_ == 0) {
    std::vector<Point3> x = triangles->mesh().points;
    for (size_t i = 0; i < x.size(); ++i) x[i] += Point3(u[3 * i], u[3 * i + 1], u[3 * i + 2]);
    const IntersectionReport r = self_intersections(x, triangles->mesh().triangles, 1);
    found = {r.pairs, r.pairs ? r.examples[0][0] : -1, r.pairs ? r.examples[0][1] : -1};
    // Contact scenes: the shell against each collider too (the first hit named as
    // (shell triangle, -1 - collider)).
    if (contact_ && series.disc == disc_)
      for (std::size_t k = 0; k < contact_->obstacles().size(); ++k) {
        const TriangleMesh& o = contact_->obstacles()[k];
        const IntersectionReport c =
            intersections_between(x, triangles->mesh().triangles, o.points, o.triangles, 1);
        if (c.pairs > 0 && found[0] == 0)
          found[1] = c.examples[0][0], found[2] = -1 - static_cast<long>(k);
        found[0] += c.pairs;
      }
  }
  PetscCallMPI(MPI_Bcast(found.data(), 3, MPI_LONG, 0, comm_));
  ++audited_frames_;
  intersecting_pairs_ += found[0];
  *pairs = found[0];
  // With several bodies, each triangle is named with its body.
  const auto triangle = [&](long face) {
    std::string text = "triangle " + std::to_string(face);
    if (!scene_.bodies.empty() && series.disc == disc_) {
      const TriangleBodies bodies = TriangleBodies::of(scene_, triangles->mesh());
      text += " of '" + bodies.names[bodies.of_face[face]] + "'";
    }
    return text;
  };
  if (found[0] > 0)
    *message = std::to_string(found[0]) + " pair(s) of triangles intersect (the first: " +
               triangle(found[1]) + " and " +
               (found[2] >= 0 ? triangle(found[2]) : "collider " + std::to_string(-1 - found[2])) +
               ", at step " + std::to_string(n) + ", t = " + std::to_string(t) + " s)";
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::estimate_condition() {
  PetscFunctionBeginUser;
  Mat H;
  PetscCall(problem_->create_matrix(&H));
  PetscCall(problem_->hessian(u_, H));
  SpectrumEstimate e;
  PetscCall(estimate_spectrum(H, options_.condition_steps, &e));
  PetscCall(MatDestroy(&H));
  spectrum_ = e;
  PetscCall(PetscPrintf(comm_,
                        "mlshell: Hessian at the %s state: |lambda| in [%.6e, %.6e], cond_2 = %.6e "
                        "(Lanczos, %d steps on H and on H^-1%s)\n",
                        options_.evaluate_only ? "initial" : "final", std::abs(e.lambda_min),
                        std::abs(e.lambda_max), e.condition, e.steps,
                        e.converged ? "" : "; NOT settled: raise -mlshell_condition_steps"));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::write_limit_csv() {
  PetscFunctionBeginUser;
  std::vector<double> u;
  PetscCall(layout_->gather_natural(u_, u));
  if (rank_ == 0) {
    const SurfaceSample s = disc_->element_sampling(options_.limit_csv_samples)->sample(u);
    std::string text = "X,Y,Z,ux,uy,uz\n";
    char line[256];
    for (size_t i = 0; i + 2 < s.points.size(); i += 3) {
      const double* x = &s.points[i];
      const double* d = &s.displacement[i];
      std::snprintf(line, sizeof line, "%.15e,%.15e,%.15e,%.15e,%.15e,%.15e\n", x[0] - d[0],
                    x[1] - d[1], x[2] - d[2], d[0], d[1], d[2]);
      text += line;
    }
    write_file_atomic(output_->dir / "limit_surface.csv", text);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::write_summary(const std::string& status, const SolveReport* last) {
  PetscFunctionBeginUser;
  std::vector<double> energies, u;
  PetscReal f, gnorm;
  PetscCall(problem_->report(u_, energies, &f, &gnorm));
  PetscCall(layout_->gather_natural(u_, u));
  // Peak resident memory of each rank so far (Linux: ru_maxrss in KiB): the largest and the sum.
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  const double mine = static_cast<double>(usage.ru_maxrss) / 1024.0;
  double peak_largest = 0.0, peak_sum = 0.0;
  PetscCallMPI(MPI_Reduce(&mine, &peak_largest, 1, MPI_DOUBLE, MPI_MAX, 0, comm_));
  PetscCallMPI(MPI_Reduce(&mine, &peak_sum, 1, MPI_DOUBLE, MPI_SUM, 0, comm_));
  Json progressive, contact;
  if (scene_.time.progressive()) PetscCall(progressive_summary(&progressive));
  PetscCall(contact_summary(&contact));
  if (rank_ == 0) {
    Json::Object energy;
    double total = 0.0;
    for (double e : energies) total += e;
    // One number per effect (several effects of one kind are summed).
    std::vector<std::pair<std::string, double>> sums;
    for (size_t i = 0; i < energies.size(); ++i) {
      auto it = std::find_if(sums.begin(), sums.end(),
                             [&](const auto& p) { return p.first == output_->effect_names[i]; });
      if (it == sums.end())
        sums.emplace_back(output_->effect_names[i], energies[i]);
      else
        it->second += energies[i];
    }
    for (const auto& [k, val] : sums) energy.emplace_back(k, Json(val));
    energy.emplace_back("total", Json(total));
    Json::Object probes;
    for (size_t p = 0; p < probes_.size(); ++p) {
      const Point3& X = probes_[p].reference;
      std::vector<double> d(3, 0.0);
      for (size_t i = 0; i < probes_[p].nodes.size(); ++i)
        for (int c = 0; c < 3; ++c) d[c] += probes_[p].weights[i] * u[3 * probes_[p].nodes[i] + c];
      probes.emplace_back(scene_.probes[p].name,
                          Json(Json::Object{{"reference", Json::array({X[0], X[1], X[2]})},
                                            {"displacement", Json::array(d)}}));
    }
    Json::Object solver{
        {"type", Json(solver_ ? solver_->type() : std::string("none"))},
        {"options_file",
         scene_.solver.options_file ? Json(scene_.solver.options_file->string()) : Json(nullptr)},
        {"iterations", Json(static_cast<long long>(total_iterations_))},
        {"linear_iterations", Json(static_cast<long long>(total_linear_iterations_))},
        {"solves", Json(static_cast<long long>(total_solves_))},
        {"solve_time", Json(solve_time_)},
        {"converged", Json(all_converged_)},
        {"reason", Json(last ? last->reason : std::string("not run"))},
        {"gradient_tolerance", Json(last ? last->gradient_tolerance : 0.0)},
        {"force_scale", Json(last ? last->force_scale : 0.0)},
        {"energy_scale", Json(energy_scale_.total())},
        {"objective_evaluations", Json(problem_->objective_evaluations())},
        {"hessian_evaluations", Json(problem_->hessian_evaluations())},
        {"nonfinite_trial_points", Json(problem_->inadmissible_evaluations())},
        {"petsc_options", Json(petsc_options_in_effect())}};
    if (!rmtr_totals_.levels.empty()) {
      // Work of RMTR summed over the steps (paper eq. 7.2-7.4); level 0 is the coarsest.
      Json::Array levels;
      for (const RmtrLevelStatistics& l : rmtr_totals_.levels)
        levels.push_back(Json(Json::Object{{"dofs", Json(static_cast<long long>(l.dofs))},
                                           {"successful", Json(l.successful)},
                                           {"assemblies", Json(l.assemblies)},
                                           {"qp_solves", Json(l.qp_solves)},
                                           {"factorisations", Json(l.factorisations)},
                                           {"objectives", Json(l.objectives)},
                                           {"coarse_accepted", Json(l.coarse_accepted)},
                                           {"coarse_rejected", Json(l.coarse_rejected)},
                                           {"coarse_shortened", Json(l.coarse_shortened)}}));
      solver.emplace_back(
          "rmtr", Json(Json::Object{{"cycles", Json(rmtr_totals_.cycles)},
                                    {"levels", Json(levels)},
                                    {"assembly_work_units", Json(rmtr_totals_.assembly_work_units)},
                                    {"qp_work_units", Json(rmtr_totals_.qp_work_units)}}));
    }
    // Where the material points lie in the material model: at the last solution, and over all
    // steps (steps whose solution reached the continuation or a negative energy density).
    const MaterialReport& m = material_final_;
    const double min_psi = std::isfinite(min_energy_density_) ? min_energy_density_ : 0.0;
    const Json material(
        Json::Object{{"points", Json(m.points)},
                     {"beyond_fit", Json(m.beyond_fit)},
                     {"coupling_limited", Json(m.coupling_limited)},
                     {"negative_energy", Json(m.negative)},
                     {"min_energy_density",
                      Json(std::isfinite(m.min_energy_density) ? m.min_energy_density : 0.0)},
                     {"steps_beyond_fit", Json(steps_beyond_fit_)},
                     {"steps_with_negative_energy", Json(steps_negative_)},
                     {"min_energy_density_all_steps", Json(min_psi)}});
    // The largest violation of every penalty condition, at the last step and over all steps.
    Json::Array constraints;
    for (size_t i = 0; i < violation_last_.size(); ++i) {
      const auto* p = dynamic_cast<const PenaltyTerm*>(problem_->terms()[i].get());
      if (!p) continue;
      constraints.push_back(
          Json(Json::Object{{"effect", Json(p->name())},
                            {"index", Json(static_cast<long long>(p->effect_index()))},
                            {"max_violation", Json(violation_last_[i])},
                            {"max_violation_all_steps", Json(violation_max_[i])},
                            {"warning_threshold", Json(kConstraintWarning * disc_->mesh_size())}}));
    }
    // The user's options that nothing read (main.cpp prints them as warnings).
    Json::Array unused;
    for (const UnusedOption& o : unused_options(solver_ != nullptr))
      unused.push_back(Json(Json::Object{
          {"name", Json(o.name)},
          {"value", o.value.empty() ? Json(nullptr) : Json(o.value)},
          {"did_you_mean", o.suggestion.empty() ? Json(nullptr) : Json(o.suggestion)}}));
    const BuildInfo& build = build_info();
    Json::Object top{
        {"scene", Json(scene_.name)},
        {"build", Json(Json::Object{{"mlshell", Json(build.version)},
                                    {"commit", Json(build.commit)},
                                    {"petsc", Json(build.petsc)}})},
        {"status", Json(status)},
        {"dofs", Json(disc_->num_dofs())},
        {"discretization", Json(disc_->kind())},
        {"elements", Json(static_cast<long long>(disc_->elements().size()))},
        {"integrator", Json(scene_.time.progressive() ? std::string("progressive")
                            : stepper_                  ? stepper_->name()
                            : std::string(scene_.time.quasistatic() ? "quasistatic"
                                                                    : "implicit_euler"))},
        {"ranks", Json(size_)},
        {"steps", Json(steps_done_)},
        {"time", Json((steps_done_ + first_step_) * scene_.time.dt)},
        {"energy", Json(energy)},
        {"gradient_norm", Json(static_cast<double>(gnorm))},
        {"probes", Json(probes)},
        {"solver", Json(solver)},
        {"unused_options", Json(unused)},
        {"material", material},
        {"constraints", Json(constraints)},
        {"intersection_audit",
         options_.audit_intersections
             ? Json(Json::Object{{"frames", Json(audited_frames_)},
                                 {"intersecting_pairs", Json(intersecting_pairs_)}})
             : Json(nullptr)},
        {"wall_time", Json(MPI_Wtime() - wall_start_)},
        {"memory", Json(Json::Object{{"peak_rss_mib_largest_rank", Json(peak_largest)},
                                     {"peak_rss_mib_all_ranks", Json(peak_sum)},
                                     {"huge_pages", Json(huge_pages_requested())}})}};
    if (scene_.time.progressive()) top.emplace_back("progressive", progressive);
    if (contact_) top.emplace_back("contact", contact);
    // Several bodies: each one's name, size and material in brief.
    if (const auto* triangles = dynamic_cast<const TriangleDiscretization*>(disc_);
        triangles && !scene_.bodies.empty()) {
      const TriangleBodies bodies = TriangleBodies::of(scene_, triangles->mesh());
      Json::Array list;
      for (int b = 0; b < bodies.size(); ++b) {
        const TriangleShellParameters p = bodies.parameters(b);
        list.push_back(Json(Json::Object{
            {"name", Json(bodies.names[b])},
            {"vertices", Json(static_cast<long long>(
                             std::count(bodies.of_point.begin(), bodies.of_point.end(), b)))},
            {"faces", Json(static_cast<long long>(
                          std::count(bodies.of_face.begin(), bodies.of_face.end(), b)))},
            {"youngs_modulus", Json(p.youngs_modulus)},
            {"thickness", Json(p.thickness)},
            {"area_density", Json(bodies.materials[b]->density)}}));
      }
      top.emplace_back("bodies", Json(list));
    }
    if (spectrum_)
      top.emplace_back(
          "hessian",
          Json(Json::Object{
              {"lambda_min", Json(spectrum_->lambda_min)},
              {"lambda_max", Json(spectrum_->lambda_max)},
              {"condition", Json(spectrum_->condition)},
              {"method", Json(std::string("Lanczos with full reorthogonalisation on H and on "
                                          "H^-1 (MUMPS LDL^T), ") +
                              std::to_string(spectrum_->steps) + " steps")},
              {"settled", Json(spectrum_->converged)}}));
    const Json summary(std::move(top));
    write_file_atomic(output_->dir / "summary.json", summary.dump() + "\n");
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
