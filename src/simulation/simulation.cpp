// A scene run end to end (see simulation.hpp).
#include "mlshell/simulation.hpp"

#include "mlshell/proxy_energy.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "mlshell/effects.hpp"
#include "mlshell/log_events.hpp"
#include "mlshell/output_files.hpp"
#include "mlshell/step_failure.hpp"
#include "mlshell/subdivision/level_hierarchy.hpp"
#include "mlshell/contact/collider_motion.hpp"
#include "mlshell/contact/contact_term.hpp"
#include "mlshell/triangle/triangle_bodies.hpp"
#include "mlshell/triangle/triangle_effect_builder.hpp"
#include "mlshell/triangle/triangle_levels.hpp"
#include "mlshell/triangle/triangle_selection.hpp"
#include "simulation_output.hpp"

namespace mlshell {

namespace fs = std::filesystem;

namespace {

/// The group "mlshell: simulation": what a run does and prints.
PetscErrorCode simulation_options(MPI_Comm comm, SimulationOptions* o) {
  PetscBool evaluate = o->evaluate_only ? PETSC_TRUE : PETSC_FALSE;
  PetscBool quiet = o->quiet ? PETSC_TRUE : PETSC_FALSE;
  PetscInt gauss = o->gauss_points;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "mlshell: simulation", "");
  PetscCall(PetscOptionsBool("-mlshell_evaluate",
                             "energies of every effect and the gradient norm at the initial "
                             "state; writes summary.json and exits (no solve)",
                             "", evaluate, &evaluate, nullptr));
  PetscCall(PetscOptionsBool("-mlshell_quiet", "no per-step progress lines", "", quiet, &quiet,
                             nullptr));
  PetscCall(PetscOptionsInt("-mlshell_gauss_points",
                            "Gauss points per direction per element (2..6)", "", gauss, &gauss,
                            nullptr));
  PetscOptionsEnd();
  o->evaluate_only = evaluate;
  o->quiet = quiet;
  if (gauss < 2 || gauss > 6)
    throw SceneError("-mlshell_gauss_points: must be in 2..6; got '" + std::to_string(gauss) + "'");
  o->gauss_points = static_cast<int>(gauss);
  PetscFunctionReturn(0);
}

/// The group "mlshell: measuring": what the studies measure besides the run itself.
PetscErrorCode measuring_options(MPI_Comm comm, SimulationOptions* o) {
  PetscBool view = o->hierarchy_view ? PETSC_TRUE : PETSC_FALSE;
  PetscBool audit = o->audit_intersections ? PETSC_TRUE : PETSC_FALSE;
  PetscBool condition = o->condition ? PETSC_TRUE : PETSC_FALSE;
  PetscInt steps = o->condition_steps, samples = o->limit_csv_samples;
  PetscBool has_dir = PETSC_FALSE, has_samples = PETSC_FALSE;
  char dir[PETSC_MAX_PATH_LEN] = "";
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "mlshell: measuring", "");
  PetscCall(PetscOptionsBool("-mlshell_condition",
                             "estimate cond_2 of the Hessian at the final state (initial with "
                             "-mlshell_evaluate): Lanczos on H and on H^-1 (MUMPS); into "
                             "summary.json",
                             "", condition, &condition, nullptr));
  PetscCall(PetscOptionsInt("-mlshell_condition_steps", "Lanczos steps of that estimate (2..2000)",
                            "", steps, &steps, nullptr));
  PetscCall(PetscOptionsInt("-mlshell_limit_csv",
                            "write limit_surface.csv: the final limit surface on a (K+1)x(K+1) "
                            "grid per element (reference X,Y,Z; ux,uy,uz), K in 1..64 (0: none)",
                            "", samples, &samples, &has_samples));
  PetscCall(PetscOptionsBool("-mlshell_hierarchy_view",
                             "print the levels: subdivision (control points, dofs, "
                             "extraordinary vertices, nonzeros/row and memory of S, R, Q) or "
                             "triangle (vertices, faces, smallest angle, build time, nonzeros of "
                             "U, rest-shape recovery)",
                             "", view, &view, nullptr));
  PetscCall(PetscOptionsString("-mlshell_hierarchy_write",
                               "write each level as OBJ files into this folder (subdivision: "
                               "cage and limit surface; triangle: rest mesh and its prolongation "
                               "to the finest level)",
                               "", dir, dir, sizeof dir, &has_dir));
  PetscCall(PetscOptionsBool("-mlshell_audit_intersections",
                             "check every written frame of a triangle mesh (and the input) for "
                             "intersecting triangles, exactly (CGAL); a frame with any stops the "
                             "run (exit 5)",
                             "", audit, &audit, nullptr));
  PetscOptionsEnd();
  o->audit_intersections = audit;
  o->condition = condition;
  if (steps < 2 || steps > 2000)
    throw SceneError("-mlshell_condition_steps: must be in 2..2000; got '" +
                     std::to_string(steps) + "'");
  o->condition_steps = static_cast<int>(steps);
  if (has_samples && (samples < 1 || samples > 64))
    throw SceneError("-mlshell_limit_csv: samples per element edge must be in 1..64; got '" +
                     std::to_string(samples) + "'");
  o->limit_csv_samples = static_cast<int>(samples);
  o->hierarchy_view = view;
  if (has_dir) o->hierarchy_write = dir;
  PetscFunctionReturn(0);
}

/// The group "mlshell: progressive": how a progressive run (time.integrator progressive) refines.
PetscErrorCode progressive_options(MPI_Comm comm, SimulationOptions* o) {
  PetscInt stop = o->progressive_stop_level;
  char hessian[16], gradient[16];
  std::snprintf(hessian, sizeof hessian, "%s", o->progressive_own_hessian ? "own" : "galerkin");
  std::snprintf(gradient, sizeof gradient, "%s",
                o->progressive_frozen_gradient ? "frozen" : "exact");
  PetscBool has_stop = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "mlshell: progressive", "");
  PetscCall(PetscOptionsInt("-mlshell_progressive_stop_level",
                            "end a progressive run after this level (0 = the coarsest preview); "
                            "its output is complete and its summary says where it stopped",
                            "", stop, &stop, &has_stop));
  PetscCall(PetscOptionsString("-mlshell_progressive_hessian",
                               "own|galerkin: the proxy steps' Newton matrix, the level mesh's "
                               "own M_l/h^2 + PSD(H_l) or J_P^T PSD(H_fine) J_P",
                               "", hessian, hessian, sizeof hessian, nullptr));
  PetscCall(PetscOptionsString("-mlshell_progressive_gradient",
                               "exact|frozen: the proxy energy's gradient, J_P^T grad Psi or "
                               "U^T grad Psi with the offset frozen (paper 2 eq. 10)",
                               "", gradient, gradient, sizeof gradient, nullptr));
  PetscOptionsEnd();
  if (has_stop && stop < 0)
    throw SceneError("-mlshell_progressive_stop_level: must be a level >= 0; got '" +
                     std::to_string(stop) + "'");
  const std::string h = hessian, g = gradient;
  if (h != "galerkin" && h != "own")
    throw SceneError("-mlshell_progressive_hessian: must be galerkin or own; got '" + h + "'");
  if (g != "exact" && g != "frozen")
    throw SceneError("-mlshell_progressive_gradient: must be exact or frozen; got '" + g + "'");
  o->progressive_stop_level = static_cast<int>(stop);
  o->progressive_own_hessian = h == "own";
  o->progressive_frozen_gradient = g == "frozen";
  PetscFunctionReturn(0);
}

}  // namespace

SimulationOptions SimulationOptions::from_petsc_options() {
  SimulationOptions o;
  PetscCallAbort(PETSC_COMM_WORLD, simulation_options(PETSC_COMM_WORLD, &o));
  PetscCallAbort(PETSC_COMM_WORLD, measuring_options(PETSC_COMM_WORLD, &o));
  PetscCallAbort(PETSC_COMM_WORLD, progressive_options(PETSC_COMM_WORLD, &o));
  o.solver = StepSolverOptions::from_options(PETSC_COMM_WORLD);
  return o;
}

QuadMesh build_cage(const GeometrySpec& geometry) {
  QuadMesh cage;
  if (const auto* r = std::get_if<RectangleCage>(&geometry.cage)) {
    cage = make_rectangle_cage(r->size[0], r->size[1], r->faces[0], r->faces[1], r->origin[0],
                               r->origin[1]);
  } else if (const auto* l = std::get_if<LShapeCage>(&geometry.cage)) {
    cage = make_l_shape_cage(l->size[0], l->size[1], l->faces[0], l->faces[1], l->cut[0], l->cut[1],
                             l->origin[0], l->origin[1]);
  } else {
    cage = read_obj_cage(std::get<ObjCage>(geometry.cage).path);
  }
  return add_ghost_ring(cage);
}

Simulation::Simulation(MPI_Comm comm, Scene scene, SimulationOptions options)
    : comm_(comm), scene_(std::move(scene)), options_(options) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
  wall_start_ = MPI_Wtime();
  PetscCallAbort(comm, PetscLogStageGetId("Setup", &stage_setup_));
  if (stage_setup_ < 0) {
    PetscCallAbort(comm, PetscLogStageRegister("Setup", &stage_setup_));
    PetscCallAbort(comm, PetscLogStageRegister("Solve", &stage_solve_));
    PetscCallAbort(comm, PetscLogStageRegister("Output", &stage_output_));
  } else {
    PetscCallAbort(comm, PetscLogStageGetId("Solve", &stage_solve_));
    PetscCallAbort(comm, PetscLogStageGetId("Output", &stage_output_));
  }
  if (!options_.solver) options_.solver = StepSolverOptions::from_options(comm);
  const LogStageScope setup(stage_setup_);
  frame_ = CageFrame::from(scene_.geometry);
  if (scene_.geometry.triangles())
    setup_triangles();
  else
    setup_subdivision();
  disc_ = &levels_->discretization(levels_->finest());
  layout_ = &levels_->layout(levels_->finest());
  problem_ = &multilevel_->level(levels_->finest());
  for (int l = 0; l < multilevel_->num_levels(); ++l)
    for (const auto& t : multilevel_->level(l).terms())
      t->set_hessian_projection(term_hessian_projection(*options_.solver, t->name()));
  if ((contact_ = problem_->find_term<ContactTerm>())) {
    check_contact_solver();
    options_.audit_intersections = true;  // no contact scene writes an unaudited frame
  }
  PetscCallAbort(comm, layout_->create_vector(&u_));
  PetscCallAbort(comm, VecDuplicate(u_, &v_));
  PetscCallAbort(comm, VecZeroEntries(v_));

  output_ = std::make_unique<Output>();
  output_->dir = scene_.output.dir;
  for (const auto& t : problem_->terms()) output_->effect_names.push_back(t->name());
  // Frames (XDMF, OBJ) sample the surface with one matrix, each rank its slice of the samples.
  const auto& formats = scene_.output.formats;
  if (std::find(formats.begin(), formats.end(), "xdmf") != formats.end() ||
      std::find(formats.begin(), formats.end(), "obj") != formats.end()) {
    const LogEventScope event("Setup:sampling");
    output_->frames.sampling = std::make_unique<DistributedSampling>(
        *disc_->sampling_part(scene_.output.samples_for(scene_.geometry.refine), rank_, size_),
        *layout_);
  }
  output_->frames.stem = scene_.name;
  output_->frames.obj_prefix = "frame";
  output_->frames.disc = disc_;
  output_->frames.layout = layout_;
  output_->frames.problem = problem_;
  create_output_folder(comm, output_->dir);
}

void Simulation::setup_subdivision() {
  try {
    const LogEventScope event("Setup:subdivision");
    hierarchy_ =
        std::make_unique<SubdivisionHierarchy>(build_cage(scene_.geometry), scene_.geometry.refine);
  } catch (const MeshError& e) {
    throw SceneError(scene_.file.string() + ": geometry.cage: " + e.what());
  }
  if (options_.hierarchy_view || !options_.hierarchy_write.empty()) {
    const LevelHierarchy levels(comm_, *hierarchy_, 0, options_.gauss_points);
    if (options_.hierarchy_view) PetscCallAbort(comm_, view_hierarchy(levels, comm_));
    if (!options_.hierarchy_write.empty()) write_hierarchy(levels, options_.hierarchy_write);
  }
  // RMTR needs the scene on every level; other solvers only on the finest.
  const int finest = hierarchy_->num_levels() - 1;
  const int coarsest = options_.solver->type == "rmtr" ? 0 : finest;
  auto levels =
      std::make_unique<LevelHierarchy>(comm_, *hierarchy_, coarsest, options_.gauss_points);
  {
    const LogEventScope event("Setup:problems");
    multilevel_ = std::make_unique<MultilevelProblem>(scene_, *levels, frame_);
  }
  const SubdivisionDiscretization& disc = levels->discretization(levels->finest());
  for (const auto& p : scene_.probes) {
    try {
      const SurfacePoint sp =
          select_point(disc, std::get<PointSelection>(p.where.selection), frame_, p.where.text);
      const PointBasis b = disc.evaluator().evaluate({sp})[0];
      probes_.push_back({b.nodes, b.w[kValue], b.apply(kValue, disc.mesh().points)});
    } catch (const SceneError& e) {
      throw SceneError(scene_.file.string() + ": probes." + p.name + ": " + e.what());
    }
  }
  levels_ = std::move(levels);
}

namespace {

/// The fine vertices the scene's point selections pick (point conditions, point loads, probes):
/// decimation keeps them, so a point means the same vertex on every level.
std::vector<int> selected_points(const Scene& scene, const TriangleDiscretization& fine,
                                 const CageFrame& frame) {
  std::vector<int> points;
  auto add = [&](const Where& where) {
    if (const auto* p = std::get_if<PointSelection>(&where.selection))
      points.push_back(select_vertex(fine, *p, frame, where.text));
  };
  for (const Effect& effect : scene.effects)
    std::visit(
        [&](const auto& e) {
          if constexpr (requires { e.where; }) add(e.where);
        },
        effect);
  for (const auto& probe : scene.probes) add(probe.where);
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

}  // namespace

std::shared_ptr<const DecimationHierarchy> Simulation::decimate_mesh(const TriangleMesh& mesh) {
  const HierarchySpec& spec = *scene_.geometry.hierarchy;
  const std::string where = scene_.file.string() + ": geometry.hierarchy: ";
  DecimationOptions options;
  if (spec.vertices.empty())
    options = DecimationOptions::by_ratio(mesh.num_points(), spec.levels, spec.ratio);
  else
    options.vertices = spec.vertices;
  options.boundary_deviation = spec.boundary_deviation;
  // Each point selection's vertex is a group of its own while decimating: it is never removed.
  TriangleMesh marked = mesh;
  std::vector<int> selected;
  {
    const TriangleDiscretization fine(mesh);
    selected = selected_points(scene_, fine, frame_);
    const std::vector<int>& points = selected;
    for (int v : points) marked.groups[" point " + std::to_string(v)] = {v};
  }
  try {
    options.validate(mesh.num_points());
    const LogEventScope event("Setup:decimation");
    auto hierarchy = std::make_shared<DecimationHierarchy>(decimate(marked, options));
    for (DecimationLevel& level : hierarchy->levels)
      for (int v : selected) level.mesh.groups.erase(" point " + std::to_string(v));
    return hierarchy;
  } catch (const std::invalid_argument& e) {
    std::string what = e.what();
    if (spec.vertices.empty()) {
      char ratio[32];
      std::snprintf(ratio, sizeof ratio, "%g", spec.ratio);
      what = "levels " + std::to_string(spec.levels) + " with ratio " + ratio + " from " +
             std::to_string(mesh.num_points()) + " vertices: " + what +
             " (ask for fewer levels or a smaller ratio)";
    }
    throw SceneError(where + what);
  } catch (const MeshError& e) {
    throw SceneError(where + e.what());
  }
}

void Simulation::setup_triangles() {
  TriangleMesh mesh;
  try {
    mesh = build_scene_mesh(scene_);
  } catch (const MeshError& e) {
    throw SceneError(scene_.file.string() + ": geometry.mesh: " + e.what());
  } catch (const std::invalid_argument& e) {
    throw SceneError(scene_.file.string() + ": geometry.mesh: " + e.what());
  }
  // RMTR needs the scene on every level; other solvers only on the finest.
  const bool hierarchy = scene_.geometry.hierarchy.has_value();
  const bool multilevel =
      hierarchy && (options_.solver->type == "rmtr" || scene_.time.progressive());
  const bool inspect = options_.hierarchy_view || !options_.hierarchy_write.empty();
  std::shared_ptr<const DecimationHierarchy> decimation;
  // Built whenever the scene declares it: a hierarchy the mesh cannot have is bad input, whatever
  // the solver.
  if (hierarchy) decimation = decimate_mesh(mesh);
  if (decimation && inspect) {
    const TriangleLevels all(comm_, decimation);
    if (options_.hierarchy_view) PetscCallAbort(comm_, view_hierarchy(all, comm_));
    if (!options_.hierarchy_write.empty()) write_hierarchy(all, options_.hierarchy_write);
  } else if (inspect && rank_ == 0) {
    std::fprintf(stderr,
                 "mlshell: warning: -mlshell_hierarchy_view/_write: %s has no geometry.hierarchy; "
                 "its triangle mesh is one level\n",
                 scene_.file.c_str());
  }
  std::unique_ptr<TriangleLevels> levels;
  {
    const LogEventScope event("Setup:layout");
    if (multilevel)
      levels = std::make_unique<TriangleLevels>(comm_, decimation);
    else
      levels = std::make_unique<TriangleLevels>(comm_, std::move(mesh));
  }
  const TriangleLevels& t = *levels;
  {
    const LogEventScope event("Setup:problems");
    multilevel_ = std::make_unique<MultilevelProblem>(*levels, scene_.time.dt, [&](int l) {
      auto problem = build_triangle_problem(scene_, t.discretization(l), t.layout(l), frame_,
                                            t.discretization(t.finest()).mesh_size());
      if (l < t.finest()) problem->extend_pattern(t.galerkin_pairs(l));
      return problem;
    });
    if (multilevel && options_.solver->proxy_coarse_energy)
      for (int l = 0; l < t.finest(); ++l) {
        Vec template_vector;
        Mat pattern;
        PetscCallAbort(comm_, t.layout(l).create_vector(&template_vector));
        PetscCallAbort(comm_, multilevel_->level(l).create_matrix(&pattern));
        multilevel_->set_level_objective(
            l, std::make_unique<ProxyEnergy>(multilevel_->level(t.finest()), t.direct_transfer(l),
                                             template_vector, pattern));
        PetscCallAbort(comm_, VecDestroy(&template_vector));
        PetscCallAbort(comm_, MatDestroy(&pattern));
      }
  }
  const TriangleDiscretization& disc = t.discretization(t.finest());
  for (const auto& p : scene_.probes) {
    try {
      const int v =
          select_vertex(disc, std::get<PointSelection>(p.where.selection), frame_, p.where.text);
      probes_.push_back({{v}, {1.0}, disc.points()[v]});
    } catch (const SceneError& e) {
      throw SceneError(scene_.file.string() + ": probes." + p.name + ": " + e.what());
    }
  }
  levels_ = std::move(levels);
}

Simulation::~Simulation() {
  for (ProgressiveLevel& r : progressive_levels_) VecDestroy(&r.preview);
  VecDestroy(&u_);
  VecDestroy(&v_);
  VecDestroy(&u_last_);
  VecDestroy(&v_last_);
}

PetscErrorCode Simulation::natural_displacement(std::vector<double>& u) const {
  return layout_->gather_natural(u_, u);
}

PetscErrorCode Simulation::set_initial_state() {
  PetscFunctionBeginUser;
  const InitialState& init = scene_.initial_state;
  std::vector<double> u, v;
  if (init.checkpoint) {
    // Rank 0 reads; every rank must learn whether that worked, so all of them raise the error.
    Checkpoint c;
    std::string error;
    if (rank_ == 0) {
      try {
        c = read_checkpoint(*init.checkpoint);
        if (c.scene_fingerprint != discretization_fingerprint(*disc_) ||
            c.displacement.size() != static_cast<size_t>(disc_->num_dofs()))
          error = "'" + init.checkpoint->string() +
                  "' was written for a different discretization (cage, refine or ghost ring)";
      } catch (const OutputError& e) {
        error = e.what();
      }
    }
    int length = static_cast<int>(error.size());
    PetscCallMPI(MPI_Bcast(&length, 1, MPI_INT, 0, comm_));
    error.resize(length);
    PetscCallMPI(MPI_Bcast(error.data(), length, MPI_CHAR, 0, comm_));
    if (!error.empty())
      throw SceneError(scene_.file.string() + ": initial_state.checkpoint: " + error);
    PetscCallMPI(MPI_Bcast(&c.step, 1, MPI_INT, 0, comm_));
    first_step_ = c.step;
    u = c.displacement;
    v = c.velocity;
  } else if (rank_ == 0) {
    u.assign(disc_->num_dofs(), 0.0);
    v.assign(disc_->num_dofs(), 0.0);
    if (init.affine) {
      const auto& A = *init.affine;
      for (int i = 0; i < disc_->num_points(); ++i) {
        const Point3& X = disc_->points()[i];
        for (int r = 0; r < 3; ++r)
          u[3 * i + r] =
              A[r][0] * X[0] + A[r][1] * X[1] + A[r][2] * X[2] + init.translate[r] - X[r];
      }
    }
  }
  PetscCall(layout_->scatter_natural(u, u_));
  PetscCall(layout_->scatter_natural(v, v_));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::evaluate(int* status) {
  PetscFunctionBeginUser;
  // The predictor of the first step's inertia is û = u₀ + dt v₀.
  PetscCall(multilevel_->synchronize(first_step_ * scene_.time.dt, u_, v_));
  std::vector<double> energies;
  PetscReal f, gnorm;
  PetscCall(problem_->report(u_, energies, &f, &gnorm));
  PetscCall(PetscPrintf(comm_, "mlshell: %s: %d dofs on %d rank(s), initial state\n",
                        scene_.name.c_str(), disc_->num_dofs(), size_));
  for (size_t i = 0; i < energies.size(); ++i)
    PetscCall(PetscPrintf(comm_, "  energy %-14s % .10e\n", output_->effect_names[i].c_str(),
                          energies[i]));
  PetscCall(PetscPrintf(comm_, "  energy %-14s % .10e\n  gradient norm         %.10e\n", "total",
                        static_cast<double>(f), static_cast<double>(gnorm)));
  if (options_.condition) PetscCall(estimate_condition());
  if (options_.limit_csv_samples > 0) PetscCall(write_limit_csv());
  PetscCall(write_summary("evaluated", nullptr));
  PetscCall(PetscPrintf(comm_, "mlshell: wrote %s\n", (output_->dir / "summary.json").c_str()));
  *status = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::step(int n, SolveReport& report) {
  PetscFunctionBeginUser;
  const LogStageScope solve(stage_solve_);
  PetscCall(stepper_->advance(n * scene_.time.dt, u_, v_, report));
  PetscFunctionReturn(0);
}

void Simulation::count_solve(const SolveReport& report, double wall) {
  total_iterations_ += report.iterations;
  total_linear_iterations_ += report.linear_iterations;
  total_solves_ += report.solves;
  solve_time_ += wall;
  rmtr_totals_ += report.rmtr;
}

PetscErrorCode Simulation::run(int* status) {
  PetscFunctionBeginUser;
  PetscCall(set_initial_state());
  if (options_.evaluate_only) {
    PetscCall(evaluate(status));
    PetscFunctionReturn(0);
  }
  {
    const LogStageScope setup(stage_setup_);
    const LogEventScope event("Setup:solver");
    solver_ = std::make_unique<StepSolver>(*problem_, multilevel_.get(), &*options_.solver);
    if (scene_.time.quasistatic()) {
      stepper_ = std::make_unique<Quasistatic>(*multilevel_, *solver_,
                                               *problem_->find_term("proximal"),
                                               scene_.time.max_proximal_solves);
    } else {
      stepper_ = std::make_unique<ImplicitEuler>(*multilevel_, *solver_, scene_.time.dt);
    }
    energy_scale_ = energy_scale(scene_, reference_area(*disc_), reference_size(*disc_));
    solver_->set_energy_scale(energy_scale_.total());
    PetscCall(VecDuplicate(u_, &u_last_));
    PetscCall(VecDuplicate(v_, &v_last_));
  }
  if (scene_.time.progressive()) {
    PetscCall(run_progressive(status));
    PetscFunctionReturn(0);
  }
  PetscCall(
      PetscPrintf(comm_,
                  "mlshell: %s: %d dofs (%d elements, h = %.4g m) on %d rank(s), %d step(s) of "
                  "dt = %g s, solver %s\n",
                  scene_.name.c_str(), disc_->num_dofs(),
                  static_cast<int>(disc_->elements().size()), disc_->mesh_size(), size_,
                  scene_.time.steps - first_step_, scene_.time.dt, solver_->type().c_str()));
  const bool csv = std::find(scene_.output.formats.begin(), scene_.output.formats.end(), "csv") !=
                   scene_.output.formats.end();
  if (rank_ == 0 && csv) {
    std::vector<std::string> cols{"step", "time"};
    for (const auto& n : output_->effect_names) cols.push_back("energy_" + n);
    for (const char* c : {"energy_total", "iterations", "linear_iterations", "gradient_norm",
                          "converged", "reason", "wall_time"})
      cols.push_back(c);
    if (contact_)
      for (const char* c : {"contact_active_pairs", "contact_min_distance", "contact_stiffness"})
        cols.push_back(c);
    // Effects of one kind may repeat: number the columns so the header stays unique.
    for (size_t i = 0; i < cols.size(); ++i)
      for (size_t j = i + 1; j < cols.size(); ++j)
        if (cols[j] == cols[i]) cols[j] += "_" + std::to_string(j);
    output_->csv = std::make_unique<CsvTable>(output_->dir / "steps.csv", cols);
  }
  if (contact_) start_collider_motion(first_step_ * scene_.time.dt);
  if (options_.audit_intersections) {  // the input first: an intersecting one is bad input
    long pairs;
    std::string message;
    PetscCall(audit_frame(output_->frames, u_, first_step_, first_step_ * scene_.time.dt, &pairs,
                          &message));
    if (pairs > 0)
      throw SceneError(scene_.file.string() + ": geometry.mesh: the " +
                       (first_step_ == 0 ? std::string("input surface")
                                         : "checkpoint's state") +
                       (scene_.bodies.empty() ? " intersects itself" : " intersects itself or a body") +
                       (contact_ && !contact_->obstacles().empty() ? " or a collider: " : ": ") +
                       message);
  }
  if (contact_) PetscCall(start_contact());
  if (first_step_ == 0) PetscCall(write_frame(0, 0.0, true, true));
  SolveReport report;
  bool intersected = false;
  for (int n = first_step_ + 1; n <= scene_.time.steps; ++n) {
    const double t0 = MPI_Wtime();
    PetscCall(VecCopy(u_, u_last_));
    PetscCall(VecCopy(v_, v_last_));
    PetscCall(step(n, report));
    const double wall = MPI_Wtime() - t0;
    count_solve(report, wall);
    if (report.unbounded) {
      all_converged_ = false;
      PetscCall(stop_unbounded(n, report));
      break;
    }
    ++steps_done_;
    std::vector<double> energies;
    PetscCall(problem_->term_energies(u_, energies));
    double total = 0.0;
    for (double e : energies) total += e;
    if (!options_.quiet)
      PetscCall(PetscPrintf(
          comm_, "step %4d/%d  t = %-8.4g  E = % .6e  its = %4d  |g| = %.3e  %s  %.2f s\n", n,
          scene_.time.steps, n * scene_.time.dt, total, report.iterations, report.gradient_norm,
          report.reason.c_str(), wall));
    PetscCall(report_material(n));
    PetscCall(report_constraints(n));
    ContactStatistics contact;
    if (contact_) {
      PetscCall(contact_->prepare(u_, nullptr));
      PetscCall(contact_->statistics(&contact));
      if (!options_.quiet)
        PetscCall(PetscPrintf(comm_,
                              "          contact: %ld active pair(s), smallest distance %.4g m "
                              "(thickness %.4g m), stiffness %.3e\n",
                              contact.active, contact.min_distance,
                              contact_->settings().barrier.thickness, contact.stiffness));
    }
    if (output_->csv) {
      std::vector<std::variant<double, long long, std::string>> row{static_cast<long long>(n),
                                                                    n * scene_.time.dt};
      for (double e : energies) row.emplace_back(e);
      row.emplace_back(total);
      row.emplace_back(static_cast<long long>(report.iterations));
      row.emplace_back(static_cast<long long>(report.linear_iterations));
      row.emplace_back(report.gradient_norm);
      row.emplace_back(static_cast<long long>(report.converged));
      row.emplace_back(report.reason);
      row.emplace_back(wall);
      if (contact_) {
        row.emplace_back(static_cast<long long>(contact.active));
        row.emplace_back(contact.min_distance);  // inf without pairs
        row.emplace_back(contact.stiffness);
      }
      output_->csv->append(row);
    }
    {
      const LogStageScope output(stage_output_);
      PetscCall(write_frame(n, n * scene_.time.dt, n == scene_.time.steps || !report.converged,
                            report.converged));
    }
    if (!audit_message_.empty()) {  // write_frame's audit found intersecting triangles
      PetscCall(PetscPrintf(comm_, "mlshell: frame %d (t = %g s) intersects itself%s: %s; stopping\n",
                            n, n * scene_.time.dt,
                            contact_ && !contact_->obstacles().empty() ? " or a collider" : "",
                            audit_message_.c_str()));
      intersected = true;
      break;
    }
    if (!report.converged && report.reason == "DIVERGED_COLLIDER_MOTION") {
      all_converged_ = false;
      PetscCall(PetscPrintf(comm_,
                            "mlshell: step %d did not converge: a collider could not reach its "
                            "place at t = %g s (DIVERGED_COLLIDER_MOTION after %d solves); "
                            "stopping. The shell is caught between it and something else "
                            "(another collider, a boundary condition, itself), or the step moves "
                            "it too far: try smaller steps (time.dt) or more proximal solves "
                            "(time.max_proximal_solves)\n",
                            n, n * scene_.time.dt, report.solves));
      break;
    }
    if (!report.converged) {
      all_converged_ = false;
      const std::string remedies =
          not_converged_remedies(scene_, solver_->type().rfind("snes", 0) == 0);
      PetscCall(PetscPrintf(comm_,
                            "mlshell: step %d did not converge (%s, |g| = %.3e after %d "
                            "iterations); stopping. Try %s",
                            n, report.reason.c_str(), report.gradient_norm, report.iterations,
                            remedies.c_str()));
      break;
    }
  }
  if (options_.condition) PetscCall(estimate_condition());
  {
    const LogStageScope output(stage_output_);
    if (options_.limit_csv_samples > 0) PetscCall(write_limit_csv());
    PetscCall(write_summary(intersected      ? "intersection"
                            : all_converged_ ? "complete"
                                             : "solver_failed",
                            &report));
  }
  PetscCall(PetscPrintf(
      comm_, "mlshell: results in %s (summary.json%s%s%s)\n", fs::absolute(output_->dir).c_str(),
      csv ? ", steps.csv" : "",
      output_->frames.xdmf
          ? (", " + output_->frames.xdmf->xdmf_path().filename().string()).c_str()
          : "",
      std::find(scene_.output.formats.begin(), scene_.output.formats.end(), "obj") !=
              scene_.output.formats.end()
          ? ", frame_*.obj"
          : ""));
  *status = intersected ? kExitIntersection : all_converged_ ? 0 : kExitSolverFailed;
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::stop_unbounded(int n, SolveReport& report) {
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(
      comm_,
      "mlshell: step %d stopped after %d iterations: the energy fell to %.2e J, below %.2e J = "
      "E0 - B (E0 = %.2e J where the solve began, B = %g x (S + |E0|), S = %.2e J the scene's "
      "energy scale: %s): it has no minimum near this state.\nLikely causes:\n%s",
      n, report.iterations, report.energy, report.energy_start - report.energy_bound,
      report.energy_start, kUnboundedEnergyFactor, energy_scale_.total(),
      energy_scale_.describe().c_str(), unbounded_energy_causes(scene_).c_str()));
  // The results end at the last good step: its state, its frame (written now if `every`
  // skipped it), no row and no frame of the divergent state.
  PetscCall(VecCopy(u_last_, u_));
  PetscCall(VecCopy(v_last_, v_));
  PetscCall(report_material(n - 1));
  PetscCall(report_constraints(n - 1));
  if (n - 1 > first_step_ && (n - 1) % scene_.output.every != 0) {
    const LogStageScope output(stage_output_);
    PetscCall(write_frame(n - 1, (n - 1) * scene_.time.dt, true, false));
  }
  PetscCall(PetscPrintf(comm_, "mlshell: the results end at step %d (t = %g s)\n", n - 1,
                        (n - 1) * scene_.time.dt));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::report_material(int step) {
  PetscFunctionBeginUser;
  MaterialReport& r = material_final_;
  PetscCall(problem_->material_report(u_, r));
  if (r.points == 0) PetscFunctionReturn(0);
  min_energy_density_ = std::min(min_energy_density_, r.min_energy_density);
  const double pct = 100.0 / static_cast<double>(r.points);
  if (r.beyond_fit > 0) {
    ++steps_beyond_fit_;
    PetscCall(PetscPrintf(comm_,
                          "mlshell: step %d: %ld of %ld material points (%.2f %%) have strains "
                          "beyond the fitted range of the material (its continuation, see "
                          "`mlshell --help`)\n",
                          step, r.beyond_fit, r.points, pct * r.beyond_fit));
  }
  if (r.negative > 0) {
    ++steps_negative_;
    PetscCall(PetscPrintf(comm_,
                          "mlshell: step %d: the strain energy density is negative at %ld of %ld "
                          "material points (%.2f %%), min psi = %.4g Pa: the material fit is not "
                          "positive there (preset denim-table1's well; preset denim limits it)\n",
                          step, r.negative, r.points, pct * r.negative, r.min_energy_density));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::report_constraints(int step) {
  PetscFunctionBeginUser;
  PetscCall(problem_->constraint_violations(u_, violation_last_));
  violation_max_.resize(violation_last_.size(), 0.0);
  const double h = disc_->mesh_size();
  const auto& terms = problem_->terms();
  for (size_t i = 0; i < violation_last_.size(); ++i) {
    violation_max_[i] = std::max(violation_max_[i], violation_last_[i]);
    if (violation_last_[i] > kConstraintWarning * h)
      PetscCall(PetscPrintf(comm_,
                            "mlshell: step %d: %s (effects[%d]) is violated by %.3g m, more than "
                            "%g h = %.3g m: its penalty is too soft for this material and size "
                            "(raise sigma or set penalty)\n",
                            step, terms[i]->name().c_str(), terms[i]->effect_index(),
                            violation_last_[i], kConstraintWarning, kConstraintWarning * h));
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
