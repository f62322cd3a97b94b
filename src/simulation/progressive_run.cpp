// A progressive run (paper 2 §3, §4.5, Algorithm 1): the whole loading as proxy steps on the
// coarsest level of the scene's decimation hierarchy, then refinement level by level, each level
// stepped on its proxy energy F_l(x_l) = Ψ(P^l(x_l)) until it is in equilibrium, and the finest
// level solved as quasistatic to the solver's full tolerance (eq. 1).
//
// Output: one frame series per level (<scene>_level<l>.xdmf, level<l>_frame_*.obj; frame k is
// the level's k-th proxy step, frame 0 its start), one steps.csv row per proxy step and level,
// and summary.json with a `progressive` section (per level: time, iterations, energy, boundary
// violation, and at the end each preview's distance to the fine result). summary.json is
// rewritten after every level, so a run that is killed leaves a summary that says how far it
// got; during the previews SIGINT or SIGTERM end the run after the current proxy step (exit
// 130), and -mlshell_progressive_stop_level k after level k (exit 0), both with the status
// saying so. During the finest level's solve a signal ends the run at once (its summary.json is
// the one written after the last preview, status "running").
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "mlshell/effects.hpp"
#include "mlshell/log_events.hpp"
#include "mlshell/output_files.hpp"
#include "mlshell/proxy_energy.hpp"
#include "mlshell/proxy_step.hpp"
#include "mlshell/simulation.hpp"
#include "mlshell/triangle/triangle_levels.hpp"
#include "simulation_output.hpp"

namespace mlshell {

namespace fs = std::filesystem;

namespace {

volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void note_interrupt(int) { g_interrupted = 1; }

/// SIGINT and SIGTERM set a flag for the lifetime of the object (mpirun turns a SIGINT into a
/// SIGTERM of every rank); the old handlers come back after.
class InterruptScope {
 public:
  InterruptScope() {
    g_interrupted = 0;
    old_int_ = std::signal(SIGINT, note_interrupt);
    old_term_ = std::signal(SIGTERM, note_interrupt);
  }
  ~InterruptScope() {
    std::signal(SIGINT, old_int_);
    std::signal(SIGTERM, old_term_);
  }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
  /// Whether any rank was interrupted (collective).
  static bool any(MPI_Comm comm) {
    int mine = g_interrupted, any = 0;
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm);
    return any != 0;
  }

 private:
  void (*old_int_)(int) = SIG_DFL;
  void (*old_term_)(int) = SIG_DFL;
};

}  // namespace

PetscErrorCode Simulation::write_progress_row(int level, int step, double time,
                                              const ProxyStepReport& r, double wall) {
  PetscFunctionBeginUser;
  if (!options_.quiet)
    PetscCall(PetscPrintf(comm_,
                          "level %d/%d  step %4d  t = %-8.4g  F = % .6e  its = %2d  |d| = %.3e  "
                          "alpha = %-6.3g %s  %.2f s\n",
                          level, levels_->finest(), step, time, r.energy, r.iterations, r.step_norm,
                          r.alpha, r.stop.c_str(), wall));
  if (output_->csv)
    output_->csv->append({static_cast<long long>(level), static_cast<long long>(step), time,
                          r.energy, static_cast<long long>(r.iterations),
                          static_cast<long long>(r.linear_iterations), r.gradient_norm, r.step_norm,
                          r.alpha, static_cast<long long>(r.equilibrium), r.stop, wall});
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::preview_level(int l, Vec x, double solve_start, bool* interrupted) {
  PetscFunctionBeginUser;
  const auto& levels = static_cast<const TriangleLevels&>(*levels_);
  const double level_start = MPI_Wtime();
  const int T = scene_.time.steps;
  const double dt = scene_.time.dt;
  LevelProblem& own = multilevel_->level(l);
  const EnergyTerm& proximal = *problem_->find_term("proximal");  // ½h⁻²‖x − xᵗ‖²_M
  // The proxy F_l = Ψ ∘ P^l (the finest problem, its proximal term included) and its Newton
  // matrix; both exist while the level is stepped.
  Vec like, fine_x;
  Mat pattern;
  PetscCall(levels.layout(l).create_vector(&like));
  PetscCall(VecDuplicate(u_, &fine_x));
  PetscCall(own.create_matrix(&pattern));
  ProxyEnergy proxy(*problem_, levels.direct_transfer(l), like, pattern);
  proxy.set_gradient(options_.progressive_frozen_gradient ? ProxyEnergy::Gradient::kFrozenOffset
                                                          : ProxyEnergy::Gradient::kExact);
  Mat H;
  if (options_.progressive_own_hessian)
    PetscCall(own.create_matrix(&H));
  else
    PetscCall(proxy.create_hessian(&H));
  ProxyNewton newton(
      proxy, H,
      [&](Vec xl, Mat A) {
        return options_.progressive_own_hessian ? own.hessian(xl, A) : proxy.hessian(xl, A);
      },
      like);
  const ProxyStepSettings settings{
      scene_.time.preview.max_iterations,
      std::sqrt(static_cast<double>(levels.discretization(l).num_points())) *
          scene_.time.preview.tolerance * disc_->mesh_size(),
      scene_.time.preview.min_step};

  ProgressiveLevel record;
  record.level = l;
  record.vertices = levels.discretization(l).num_points();
  FrameSeries& series = output_->level_frames[l];
  PetscCall(write_series_frame(series, x, 0, 0.0, l > 0));
  const double floor_scale = energy_scale_.total();
  double floor = NAN;
  ProxyStepReport r;
  bool done = false;  // in equilibrium at the final load
  // Level 0 carries the loading (steps 1..T); every level then steps at the final load until a
  // proxy step takes no iteration (Alg. 1's equilibrium), at most max_steps times.
  const int loading = l == 0 ? T : 0;
  for (int k = 1; k <= loading + scene_.time.preview.max_steps; ++k) {
    const double t = (l == 0 ? std::min(k, T) : T) * dt;
    const double t0 = MPI_Wtime();
    // The step's proximal centre: this level's state, prolonged (Ψ's ½h⁻²‖P(x) − P(xᵗ)‖²_M).
    PetscCall(levels.direct_transfer(l).prolong(x, fine_x));
    PetscCall(problem_->begin_step(t, fine_x));
    PetscCall(own.begin_step(t, x));
    PetscCall(newton.step(x, settings, &r));
    // The energy floor of the step solvers (step_solver.hpp), from the level's first step.
    if (std::isnan(floor))
      floor = r.energy - kUnboundedEnergyFactor * (floor_scale + std::abs(r.energy));
    ++record.proxy_steps;
    record.iterations += r.iterations;
    record.linear_iterations += r.linear_iterations;
    PetscCall(write_progress_row(l, k, t, r, MPI_Wtime() - t0));
    done = k >= loading && r.equilibrium;
    const bool last =
        done || r.stop == "LINEAR_SOLVE_FAILED" || r.stop == "NONFINITE" || r.energy < floor;
    *interrupted = InterruptScope::any(comm_);
    if (last || *interrupted || k % scene_.output.every == 0 ||
        k == loading + scene_.time.preview.max_steps)
      PetscCall(write_series_frame(series, x, k, k, true));
    if (!audit_message_.empty()) break;
    if (r.energy < floor) {
      r.stop = "ENERGY_UNBOUNDED";
      PetscCall(PetscPrintf(comm_,
                            "mlshell: level %d, step %d: the proxy energy fell to %.3e J, more "
                            "than %g x (S + |F|) below where the level began (S = %.3e J): it "
                            "has no minimum near this state; stopping\n",
                            l, k, r.energy, kUnboundedEnergyFactor, floor_scale));
    }
    if (last || *interrupted) break;
  }
  // Why the level ended: an intersecting frame or a failed step first, then equilibrium (the
  // last proxy step's own stop), an interrupt, or its max_steps spent.
  const bool failed =
      r.stop == "LINEAR_SOLVE_FAILED" || r.stop == "NONFINITE" || r.stop == "ENERGY_UNBOUNDED";
  record.equilibrium = done && !failed && audit_message_.empty();
  record.stop = !audit_message_.empty() ? "INTERSECTION"
                : failed || done        ? r.stop
                : *interrupted          ? "INTERRUPTED"
                                        : "MAX_STEPS";
  // The level's result on the finest mesh: energy, boundary conditions, the preview itself.
  PetscCall(VecDuplicate(u_, &record.preview));
  PetscCall(levels.direct_transfer(l).prolong(x, record.preview));
  PetscReal energy;
  PetscCall(problem_->objective_without(proximal, record.preview, &energy, nullptr));
  record.energy = energy;
  std::vector<double> violations;
  PetscCall(problem_->constraint_violations(record.preview, violations));
  for (double v : violations) record.max_violation = std::max(record.max_violation, v);
  record.wall_time = MPI_Wtime() - level_start;
  record.time_to_level = MPI_Wtime() - solve_start;
  if (!options_.quiet)
    PetscCall(PetscPrintf(comm_,
                          "mlshell: level %d/%d: %d vertices, %d proxy steps, %ld Newton "
                          "iterations, %s (%s) after %.2f s, %.2f s since the start\n",
                          l, levels_->finest(), record.vertices, record.proxy_steps,
                          record.iterations,
                          record.equilibrium ? "in equilibrium" : "NOT in equilibrium",
                          record.stop.c_str(), record.wall_time, record.time_to_level));
  progressive_levels_.push_back(record);
  PetscCall(VecDestroy(&like));
  PetscCall(VecDestroy(&fine_x));
  PetscCall(MatDestroy(&pattern));
  PetscCall(MatDestroy(&H));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::refine(int l, Vec coarse, Vec fine) {
  PetscFunctionBeginUser;
  PetscCall(levels_->transfer(l).prolong(coarse, fine));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::run_progressive(int* status) {
  PetscFunctionBeginUser;
  const auto& levels = static_cast<const TriangleLevels&>(*levels_);
  const int finest = levels.finest();
  const int stop_level =
      options_.progressive_stop_level < 0 ? finest : options_.progressive_stop_level;
  if (stop_level > finest)
    throw SceneError("-mlshell_progressive_stop_level: must be in 0.." + std::to_string(finest) +
                     " (the levels of " + scene_.file.string() + "'s geometry.hierarchy); got '" +
                     std::to_string(stop_level) + "'");
  std::optional<InterruptScope> interrupts(std::in_place);
  const double T = scene_.time.steps * scene_.time.dt;
  PetscCall(PetscPrintf(comm_,
                        "mlshell: %s: progressive, levels 0..%d (%d..%d dofs) on %d rank(s), %d "
                        "load step(s) of dt = %g s on level 0, then refinement; finest solver %s\n",
                        scene_.name.c_str(), finest, levels.discretization(0).num_dofs(),
                        disc_->num_dofs(), size_, scene_.time.steps, scene_.time.dt,
                        solver_->type().c_str()));
  // Frame series per level.
  const bool frames = std::any_of(scene_.output.formats.begin(), scene_.output.formats.end(),
                                  [](const std::string& f) { return f == "xdmf" || f == "obj"; });
  output_->level_frames.resize(finest + 1);
  // An earlier run's series of a level this run may not reach must not pass for this run's.
  if (rank_ == 0)
    for (int l = 0; l <= finest; ++l) {
      std::error_code ignored;
      fs::remove(output_->dir / (scene_.name + "_level" + std::to_string(l) + ".xdmf"), ignored);
    }
  for (int l = 0; l <= finest; ++l) {
    FrameSeries& s = output_->level_frames[l];
    s.stem = scene_.name + "_level" + std::to_string(l);
    s.obj_prefix = "level" + std::to_string(l) + "_frame";
    s.disc = &levels.discretization(l);
    s.layout = &levels.layout(l);
    s.problem = &multilevel_->level(l);
    if (frames)
      s.sampling =
          std::make_unique<DistributedSampling>(*s.disc->sampling_part(1, rank_, size_), *s.layout);
  }
  if (rank_ == 0 && std::find(scene_.output.formats.begin(), scene_.output.formats.end(), "csv") !=
                        scene_.output.formats.end())
    output_->csv = std::make_unique<CsvTable>(
        output_->dir / "steps.csv",
        std::vector<std::string>{"level", "step", "time", "energy", "iterations",
                                 "linear_iterations", "gradient_norm", "step_norm", "alpha",
                                 "equilibrium", "stop", "wall_time"});
  if (options_.audit_intersections) {  // the input first: an intersecting one is bad input
    long pairs;
    std::string message;
    PetscCall(audit_frame(output_->frames, u_, 0, 0.0, &pairs, &message));
    if (pairs > 0)
      throw SceneError(scene_.file.string() +
                       ": geometry.mesh: the input surface intersects itself: " + message);
  }
  // Previews: every term's Hessian projected (Alg. 1's PSD), the finest's and the levels' own.
  for (int l = 0; l <= finest; ++l)
    for (const auto& t : multilevel_->level(l).terms()) t->set_hessian_projection(true);
  const double solve_start = MPI_Wtime();
  all_converged_ = false;  // until the finest level converges: no summary before says so
  std::string outcome = "complete";
  SolveReport report;
  report.reason = "not run";
  // Level 0 starts from the initial state projected onto it.
  PetscCall(multilevel_->synchronize(0.0, u_, v_));
  Vec x;
  PetscCall(VecDuplicate(multilevel_->state(0), &x));
  PetscCall(VecCopy(multilevel_->state(0), x));
  bool interrupted = false;
  int l = 0;
  for (; l < finest; ++l) {
    PetscCall(preview_level(l, x, solve_start, &interrupted));
    const ProgressiveLevel& done = progressive_levels_.back();
    PetscCall(VecCopy(done.preview, u_));  // the summary's state: this preview, on the finest
    // The load steps level 0 has taken (all of them, unless it was interrupted during them).
    if (l == 0) steps_done_ = std::min(done.proxy_steps, scene_.time.steps);
    const bool failed = !done.equilibrium && done.stop != "INTERRUPTED" && done.stop != "MAX_STEPS";
    if (failed || interrupted || l == stop_level) {
      outcome = !audit_message_.empty() ? "intersection"
                : failed                ? "solver_failed"
                : interrupted           ? "interrupted"
                                        : "preview";
      break;
    }
    PetscCall(write_summary("running", &report));
    Vec finer;
    PetscCall(levels.layout(l + 1).create_vector(&finer));
    PetscCall(refine(l, x, finer));
    PetscCall(VecDestroy(&x));
    x = finer;
  }
  if (l == finest) {
    // The finest level: eq. (1) to the solver's tolerance, from the last preview refined.
    for (const auto& t : problem_->terms())
      t->set_hessian_projection(term_hessian_projection(*options_.solver, t->name()));
    for (int c = 0; c < finest; ++c)
      for (const auto& t : multilevel_->level(c).terms())
        t->set_hessian_projection(term_hessian_projection(*options_.solver, t->name()));
    PetscCall(VecCopy(x, u_));
    FrameSeries& series = output_->level_frames[finest];
    PetscCall(write_series_frame(series, u_, 0, 0.0, true));
    std::string start_intersects = audit_message_;  // the next audit clears it
    // The finest solve cannot stop half-way with a valid result: a signal now ends the run at
    // once, and summary.json stays the one written after the last preview ("running").
    interrupts.reset();
    const double t0 = MPI_Wtime();
    PetscCall(step(scene_.time.steps, report));  // eq. (1) at the final load
    const double wall = MPI_Wtime() - t0;
    count_solve(report, wall);
    steps_done_ = scene_.time.steps;
    ProxyStepReport row;
    row.energy = report.energy;
    row.iterations = report.iterations;
    row.linear_iterations = report.linear_iterations;
    row.gradient_norm = report.gradient_norm;
    row.equilibrium = report.converged;
    row.stop = report.reason;
    PetscCall(write_progress_row(finest, 1, T, row, wall));
    PetscCall(report_material(scene_.time.steps));
    PetscCall(report_constraints(scene_.time.steps));
    PetscCall(write_series_frame(series, u_, 1, 1.0, true));
    ProgressiveLevel record;
    record.level = finest;
    record.vertices = disc_->num_points();
    record.proxy_steps = report.solves;
    record.iterations = report.iterations;
    record.linear_iterations = report.linear_iterations;
    record.energy = report.energy;
    for (double v : violation_last_) record.max_violation = std::max(record.max_violation, v);
    record.equilibrium = report.converged;
    record.stop = report.reason;
    record.wall_time = wall;
    record.time_to_level = MPI_Wtime() - solve_start;
    progressive_levels_.push_back(record);
    if (audit_message_.empty()) audit_message_ = start_intersects;
    all_converged_ = report.converged && audit_message_.empty();
    outcome = !audit_message_.empty() ? "intersection"
              : report.converged      ? "complete"
                                      : "solver_failed";
    if (!options_.quiet)
      PetscCall(PetscPrintf(comm_,
                            "mlshell: level %d/%d (finest): %d dofs, %s (%s, |g| = %.3e after %d "
                            "iterations) after %.2f s, %.2f s since the start\n",
                            finest, finest, disc_->num_dofs(),
                            report.converged ? "converged" : "NOT converged", report.reason.c_str(),
                            report.gradient_norm, report.iterations, wall, record.time_to_level));
  } else {
    all_converged_ = false;
    report.reason = outcome;
  }
  PetscCall(VecDestroy(&x));
  if (!audit_message_.empty())
    PetscCall(PetscPrintf(comm_, "mlshell: a frame intersects itself: %s; stopping\n",
                          audit_message_.c_str()));
  progressive_outcome_ = outcome;
  {
    const LogStageScope output(stage_output_);
    PetscCall(write_summary(outcome, &report));
  }
  std::string files;
  for (int c = 0; c < static_cast<int>(progressive_levels_.size()); ++c)
    if (output_->level_frames[c].xdmf)
      files += ", " + output_->level_frames[c].xdmf->xdmf_path().filename().string();
  if (outcome == "preview" || outcome == "interrupted")
    PetscCall(PetscPrintf(
        comm_,
        "mlshell: %s after level %d of %d: the results are previews, not the "
        "converged fine solution\n",
        outcome == "preview" ? "stopped (-mlshell_progressive_stop_level)" : "interrupted",
        static_cast<int>(progressive_levels_.size()) - 1, finest));
  PetscCall(PetscPrintf(comm_, "mlshell: results in %s (summary.json%s%s)\n",
                        fs::absolute(output_->dir).c_str(), output_->csv ? ", steps.csv" : "",
                        files.c_str()));
  *status = outcome == "complete" || outcome == "preview" ? 0
            : outcome == "interrupted"                    ? kExitInterrupted
            : outcome == "intersection"                   ? kExitIntersection
                                                          : kExitSolverFailed;
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::progressive_summary(Json* section) {
  PetscFunctionBeginUser;
  // Each preview's distance to the final fine result (only once the finest level converged).
  const bool final_result = progressive_outcome_ == "complete";
  std::vector<double> fine;
  if (final_result) PetscCall(layout_->gather_natural(u_, fine));
  double fine_rms = 0.0;  // the final displacement's RMS over the vertices: the errors' scale
  for (size_t i = 0; i < fine.size(); ++i) fine_rms += fine[i] * fine[i];
  if (!fine.empty()) fine_rms = std::sqrt(fine_rms / (fine.size() / 3));
  Json::Array levels;
  for (const ProgressiveLevel& r : progressive_levels_) {
    Json::Object level{{"level", Json(r.level)},
                       {"vertices", Json(r.vertices)},
                       {"dofs", Json(3 * r.vertices)},
                       {"wall_time", Json(r.wall_time)},
                       {"time_to_level", Json(r.time_to_level)},
                       {"proxy_steps", Json(r.proxy_steps)},
                       {"iterations", Json(r.iterations)},
                       {"linear_iterations", Json(r.linear_iterations)},
                       {"energy", Json(r.energy)},
                       {"max_boundary_violation", Json(r.max_violation)},
                       {"equilibrium", Json(r.equilibrium)},
                       {"stop", Json(r.stop)}};
    std::vector<double> preview;
    if (r.preview) PetscCall(layout_->gather_natural(r.preview, preview));
    if (rank_ == 0 && r.preview) {
      Json::Object probes;
      for (size_t p = 0; p < probes_.size(); ++p) {
        const int v = probes_[p].nodes[0];
        std::vector<double> d{preview[3 * v], preview[3 * v + 1], preview[3 * v + 2]};
        double e2 = 0.0;
        if (final_result)
          for (int c = 0; c < 3; ++c) e2 += std::pow(d[c] - fine[3 * v + c], 2);
        probes.emplace_back(
            scene_.probes[p].name,
            Json(Json::Object{{"displacement", Json::array(d)},
                              {"error", final_result ? Json(std::sqrt(e2)) : Json(nullptr)}}));
      }
      level.emplace_back("probes", Json(probes));
      if (final_result) {
        double largest = 0.0, sum = 0.0;
        const size_t n = fine.size() / 3;
        for (size_t i = 0; i < n; ++i) {
          double e2 = 0.0;
          for (int c = 0; c < 3; ++c) e2 += std::pow(preview[3 * i + c] - fine[3 * i + c], 2);
          largest = std::max(largest, std::sqrt(e2));
          sum += e2;
        }
        level.emplace_back("preview_error",
                           Json(Json::Object{{"max_distance", Json(largest)},
                                             {"rms_distance", Json(std::sqrt(sum / n))}}));
      }
    }
    levels.push_back(Json(level));
  }
  const int finest = levels_->finest();
  const int last = progressive_levels_.empty() ? -1 : progressive_levels_.back().level;
  *section = Json(Json::Object{
      {"levels", Json(levels)},
      {"finest_level", Json(finest)},
      {"last_level", Json(last)},
      {"stopped_early", Json(last < finest || progressive_outcome_ != "complete")},
      {"final_rms_displacement", final_result ? Json(fine_rms) : Json(nullptr)},
      {"preview",
       Json(Json::Object{
           {"max_iterations", Json(scene_.time.preview.max_iterations)},
           {"tolerance", Json(scene_.time.preview.tolerance)},
           {"min_step", Json(scene_.time.preview.min_step)},
           {"max_steps", Json(scene_.time.preview.max_steps)},
           {"newton_matrix", Json(options_.progressive_own_hessian ? "own" : "galerkin")},
           {"gradient", Json(options_.progressive_frozen_gradient ? "frozen" : "exact")}})}});
  PetscFunctionReturn(0);
}

}  // namespace mlshell
