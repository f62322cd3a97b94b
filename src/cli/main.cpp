// mlshell — Kirchhoff–Love thin shells and cloth on Catmull–Clark subdivision elements, solved
// on distributed PETSc vectors.
//
//   mpirun -n 2 build/mlshell examples/drape.yaml -tao_monitor -log_view
//   build/mlshell examples/plate.yaml -mlshell_evaluate
//
// Exit status: 0 success, 1 usage, 2 invalid input (scene, mesh, options), 3 a solver did not
// converge (results up to that step are written and summary.json says so), 4 output failure,
// 5 a written frame intersects itself, 130 interrupted (SIGINT, SIGTERM).
#include <petscsys.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <regex>
#include <string>

#include "mlshell/build_info.hpp"
#include "mlshell/output_files.hpp"
#include "mlshell/scene.hpp"
#include "mlshell/simulation.hpp"
#include "mlshell/step_solver.hpp"
#include "mlshell/unused_options.hpp"

namespace {

const char* kUsage =
    "usage: mlshell SCENE.yaml [PETSc options]\n"
    "       mpirun -n 2 mlshell SCENE.yaml -tao_monitor -log_view\n"
    "       mlshell -help      (every mlshell option and the default solver's, each with its\n"
    "                           default and a line of description; exits 0)\n"
    "       mlshell --help     (this text and the scene format)\n"
    "       mlshell --version  (mlshell's version, source commit and PETSc version)\n"
    "\n"
    "Simulates the thin shell or cloth described by SCENE.yaml and writes its results to the\n"
    "scene's output folder (summary.json, steps.csv, <name>.xdmf + HDF5 frames, frame_*.obj).\n"
    "\n"
    "mlshell options (mlshell -help lists them with their defaults):\n"
    "  -mlshell_evaluate           energies of every effect and the gradient norm at the initial\n"
    "                              state; writes summary.json and exits\n"
    "  -mlshell_gauss_points N     Gauss points per direction per element (default 3, 2..6)\n"
    "  -mlshell_quiet              no per-step progress lines\n"
    "  -mlshell_material_csv FILE  write the scene's material as tables (uniaxial curves, the\n"
    "                              (E11, E22) plane) to FILE and exit; see\n"
    "                              examples/material/plot_material.py\n"
    "  -mlshell_hierarchy_view     print the levels: subdivision (0..refine): control points,\n"
    "                              dofs, extraordinary vertices, nonzeros/row and memory of S, R,\n"
    "                              Q; triangle (geometry.hierarchy): vertices, faces, smallest\n"
    "                              angle, build time, nonzeros of U, rest-shape recovery\n"
    "  -mlshell_hierarchy_write DIR  each level as OBJ files in DIR: subdivision cage and limit\n"
    "                              surface; triangle rest mesh and its prolongation to the finest\n"
    "  -mlshell_dt DT, -mlshell_steps N, -mlshell_output_dir DIR, -mlshell_refine N\n"
    "                              override the scene's time.dt, time.steps, output.dir,\n"
    "                              geometry.refine\n"
    "  -mlshell_condition          estimate cond_2 of the Hessian at the final state (initial\n"
    "                              with -mlshell_evaluate): Lanczos on H and on H^-1 (MUMPS),\n"
    "                              -mlshell_condition_steps N (default 60); into summary.json\n"
    "  -mlshell_limit_csv K        write limit_surface.csv: the final limit surface on a\n"
    "                              (K+1)x(K+1) grid per element (reference X,Y,Z; ux,uy,uz)\n"
    "  -mlshell_step_solver snes   solve grad f = 0 with PETSc SNES (default newtonls, MUMPS LU;\n"
    "                              -snes_*, -ksp_*, -pc_* options) instead of TAO\n"
    "  -mlshell_hessian_psd        project non-convex element Hessians onto the PSD cone\n"
    "                              (default: on for -tao_type pnewton)\n"
    "  -mlshell_coarse_energy proxy RMTR on a triangle hierarchy: coarse levels minimise the\n"
    "                              finest energy at their prolongation (paper 2 eq. 2; default\n"
    "                              own: each coarse mesh's own energy)\n"
    "  -mlshell_pressure_psd       with it, project the pressure's Hessian too (per edge;\n"
    "                              default off: exact, Newton stays quadratic on a balloon)\n"
    "  -mlshell_progressive_stop_level K  time.integrator progressive: end after level K (0 =\n"
    "                              the coarsest preview); -mlshell_progressive_hessian\n"
    "                              own|galerkin (the proxy steps' Newton matrix),\n"
    "                              -mlshell_progressive_gradient exact|frozen (eq. 10),\n"
    "                              -mlshell_preview_ksp_*/-mlshell_preview_pc_* (default MUMPS LU)\n"
    "  -options_file FILE          PETSc options from FILE (plain or .yaml); the scene may name\n"
    "                              its default one (solver.options_file), which FILE replaces;\n"
    "                              the command line's own options win over both\n"
    "  -mlshell_scene_solver false ignore the scene's solver.options_file (mlshell's built-in\n"
    "                              defaults and the command line only)\n"
    "  -mlshell_options_left false no warnings about options nothing read. By default, after a\n"
    "                              run, each option given (command line, options files) that\n"
    "                              nothing read is named, with the nearest known name:\n"
    "                              'mlshell: warning: option -tao_rmtr_smoothr_qp (value stcg)\n"
    "                              was never used; did you mean -tao_rmtr_smoother_qp?'; the\n"
    "                              list is in summary.json (unused_options) either way\n"
    "\n"
    "Solver options (TAO, prefix -tao_): default -tao_type rmtr, the recursive multilevel trust\n"
    "  region on all levels 0..geometry.refine (petsc-options/rmtr-patch-dogleg.yaml): Dogleg\n"
    "  smoothing whose Newton point comes from vertex-patch-preconditioned CG (no factorisation\n"
    "  above the coarsest level), Galerkin coarse models, subspace steps, retried smoothing\n"
    "  steps, the coarsest level factorised whole on every rank (MUMPS LDL^T, up to\n"
    "  -tao_rmtr_coarse_redundant 20000 dofs), after a full-multigrid start from the rest state\n"
    "  (each coarser level solved first, -tao_rmtr_fmg_cycles 1000 at most, 0: off;\n"
    "  -tao_rmtr_fmg_always before every solve; petsc-options/rmtr.yaml: factorised Dogleg on\n"
    "  every level, the default before 2026-12-05),\n"
    "  -tao_gatol 1e-7 -tao_gttol 1e-10 -tao_max_it 1000; the gradient tolerance of a step is\n"
    "  max(gatol, -mlshell_force_rtol (1e-8) x |external forces|). A solve whose radius collapses\n"
    "  at the round-off floor with |g| within -tao_rmtr_limiting_factor (100) of the tolerance\n"
    "  stops as CONVERGED_LIMITING_ACCURACY; far above it, as DIVERGED_TR_REDUCTION. The\n"
    "  stagnation test of the paper's (7.1) (radius > 1e15, |df| or |dx| < 1e-12 relative,\n"
    "  no new low of |g| below 0.9 x the lowest in -tao_rmtr_stagnation_window (6) iterations)\n"
    "  stops as CONVERGED_STEPTOL within that factor, and as DIVERGED_STAGNATION above it.\n"
    "  RMTR: -tao_rmtr_levels N,\n"
    "  -tao_rmtr_mu1/-tao_rmtr_mu2 (1), -tao_rmtr_smoother_qp dogleg|stcg,\n"
    "  -tao_rmtr_stcg_max_it 60, -tao_rmtr_smoother_pc vpatch|none (with Dogleg smoothing: its\n"
    "  Newton point by CG with that PC, -tao_rmtr_newton_rtol 1e-2; none: a factorisation),\n"
    "  -tao_rmtr_projection reverse|lsq|restriction, -tao_rmtr_coarse_model galerkin|first_order,\n"
    "  -tao_rmtr_coarse_start projection|iterate (coarse solves from the projection of the fine\n"
    "  iterate, or from the coarse level's own iterate of its last visit),\n"
    "  -tao_rmtr_subspace M (5; after each V-cycle a trust-region step in the span of its\n"
    "  correction and M-1 earlier changes; 0: off), -tao_rmtr_retries K (3; a rejected\n"
    "  smoothing step is retried at once with the shrunk radius, up to K times; 0: off),\n"
    "  -tao_rmtr_monitor (one line per V-cycle), -tao_view (per-level work, work units);\n"
    "  per level -rmtr_levels_<l>_ksp_..., coarsest -rmtr_coarse_pc_factor_mat_solver_type.\n"
    "  Others: -tao_type tr (Local_TR), dampednewton, linearized, bntr|bnls|nls|lmvm;\n"
    "  ready-made files in petsc-options/. Useful: -tao_monitor, -log_view (one event per\n"
    "  effect: Effect:elastic, Effect:gravity, ...; the set-up's phases: Setup:subdivision, ...).\n"
    "\n"
    "Environment: MLSHELL_HUGE_PAGES=0 keeps glibc's malloc off transparent huge pages (by\n"
    "default mlshell restarts itself once with GLIBC_TUNABLES=glibc.malloc.hugetlb=1).\n"
    "\n"
    "Exit status: 0 success (also -help, --help, --version; unused options are warnings),\n"
    "  1 usage (no scene), 2 invalid input (scene, mesh, option values), 3 a step did not\n"
    "  converge (results up to that step are written, summary.json says so), 4 output failure\n"
    "  (the output folder or a result file cannot be written), 5 a frame intersects itself\n"
    "  (-mlshell_audit_intersections), 130 interrupted (SIGINT/SIGTERM; a progressive run\n"
    "  ends after its current proxy step, with complete output of the levels done).\n"
    "\n";

/// `--help` or `-h`: the usage and the scene format, without PETSc.
bool wants_help(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) return true;
  return false;
}

bool wants_version(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--version")) return true;
  return false;
}

/// `-help` (PETSc's): with a scene, a run whose options PETSc lists as it reads them; without
/// one, the list alone (print_options_help).
bool wants_petsc_help(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "-help")) return true;
  return false;
}

/// The scene is the first argument that is not an option (nor an option's value).
const char* scene_argument(int argc, char** argv) {
  if (argc >= 2 && argv[1][0] != '-') return argv[1];
  return nullptr;
}

/// Turns PETSc errors raised by a solver option's value into invalid input (exit 2, one line):
/// an argument-class error whose message names an option, e.g. "-tao_rmtr_eta1" or
/// "-tao_rmtr_projection". Option values are checked identically on every rank, so every rank
/// raises it and the run ends like bad scene input. Any other error keeps PETSc's traceback.
struct OptionErrors {
  std::string message;
  static bool from_an_option(PetscErrorCode n, const char* mess) {
    static const std::regex option(R"((^|[^A-Za-z0-9_])-[a-z]+_[a-z0-9_]+)");
    const bool argument = n == PETSC_ERR_ARG_WRONG || n == PETSC_ERR_ARG_OUTOFRANGE ||
                          n == PETSC_ERR_ARG_INCOMP || n == PETSC_ERR_ARG_UNKNOWN_TYPE ||
                          n == PETSC_ERR_USER || n == PETSC_ERR_USER_INPUT;
    return argument && mess && std::regex_search(mess, option);
  }
  static PetscErrorCode handler(MPI_Comm comm, int line, const char* fun, const char* file,
                                PetscErrorCode n, PetscErrorType p, const char* mess, void* ctx) {
    auto* self = static_cast<OptionErrors*>(ctx);
    if (p == PETSC_ERROR_INITIAL && self->message.empty() && from_an_option(n, mess)) {
      self->message = mess;
      return n;
    }
    if (!self->message.empty()) return n;  // that error on its way up
    return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, nullptr);
  }
  /// The handler for the lifetime of a scope, popped however the scope is left (an exception
  /// from the solve included).
  struct Scope {
    explicit Scope(OptionErrors& errors) { PetscPushErrorHandler(handler, &errors); }
    ~Scope() { PetscPopErrorHandler(); }
  };
};

/// The options file given on the command line (-options_file FILE), or nullptr.
const char* command_line_options_file(int argc, char** argv) {
  for (int i = 1; i + 1 < argc; ++i)
    if (!std::strcmp(argv[i], "-options_file")) return argv[i + 1];
  return nullptr;
}

/// The command line's options of mlshell: the scene's overrides, its solver file, the report of
/// unused options.
struct CommandLineOptions {
  PetscBool scene_solver = PETSC_TRUE;
  std::optional<std::string> output_dir;
  PetscInt steps = 1, refine = 0;
  PetscReal dt = 1.0;
  std::optional<std::string> material_csv;
  PetscBool options_left = PETSC_TRUE;
};

/// The group "mlshell: command line": read once the scene is parsed (its values are the
/// defaults) and before its solver.options_file is (which therefore cannot set these). Invalid
/// values throw SceneError naming the option and the value.
PetscErrorCode command_line_options(const mlshell::Scene& scene, CommandLineOptions* o) {
  char dir[PETSC_MAX_PATH_LEN], table[PETSC_MAX_PATH_LEN] = "";
  PetscBool has_dir = PETSC_FALSE, has_table = PETSC_FALSE;
  PetscFunctionBeginUser;
  std::snprintf(dir, sizeof dir, "%s", scene.output.dir.c_str());
  o->steps = scene.time.steps;
  o->dt = scene.time.dt;
  o->refine = scene.geometry.refine;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "mlshell: command line (scene overrides)", "");
  PetscCall(PetscOptionsBool("-mlshell_scene_solver",
                             "read the scene's solver.options_file (false: mlshell's built-in "
                             "solver defaults and the command line only)",
                             "", o->scene_solver, &o->scene_solver, nullptr));
  PetscCall(PetscOptionsString("-mlshell_output_dir", "output folder (overrides output.dir)", "",
                               dir, dir, sizeof dir, &has_dir));
  PetscCall(PetscOptionsInt("-mlshell_steps", "time steps, >= 1 (overrides time.steps)", "",
                            o->steps, &o->steps, nullptr));
  PetscCall(PetscOptionsReal("-mlshell_dt", "time step, > 0 (overrides time.dt)", "", o->dt,
                             &o->dt, nullptr));
  PetscCall(PetscOptionsInt("-mlshell_refine",
                            "subdivision refinements 0..8 (overrides geometry.refine)", "",
                            o->refine, &o->refine, nullptr));
  PetscCall(PetscOptionsString("-mlshell_material_csv",
                               "write the scene's material as tables to this file and exit (no "
                               "mesh, no solve)",
                               "", table, table, sizeof table, &has_table));
  PetscCall(PetscOptionsBool("-mlshell_options_left",
                             "after the run, warn about every option given that nothing read "
                             "(with a did-you-mean)",
                             "", o->options_left, &o->options_left, nullptr));
  PetscOptionsEnd();
  if (has_dir) o->output_dir = dir;
  if (has_table) o->material_csv = table;
  if (o->steps < 1)
    throw mlshell::SceneError("-mlshell_steps: must be >= 1; got '" + std::to_string(o->steps) +
                              "'");
  if (!(o->dt > 0.0) || !std::isfinite(o->dt))
    throw mlshell::SceneError("-mlshell_dt: must be a positive number; got '" +
                              std::to_string(o->dt) + "'");
  if (o->refine < 0 || o->refine > 8)
    throw mlshell::SceneError("-mlshell_refine: must be in 0..8; got '" +
                              std::to_string(o->refine) + "'");
  PetscFunctionReturn(0);
}

/// The scene with the command line's overrides.
void apply_overrides(const CommandLineOptions& o, mlshell::Scene& scene) {
  if (o.output_dir) scene.output.dir = *o.output_dir;
  scene.time.steps = static_cast<int>(o.steps);
  scene.time.dt = o.dt;
  scene.geometry.refine = static_cast<int>(o.refine);
}

/// The scene's solver.options_file sets the scene's default solver. It is read unless the
/// command line names its own options file (which replaces it, so that two configurations are
/// never mixed) or says -mlshell_scene_solver false; the command line is inserted again after
/// it so that its options win. Afterwards scene.solver.options_file names the file whose
/// options are in effect (for summary.json).
void apply_scene_solver_file(mlshell::Scene& scene, PetscBool use_scene, int argc, char** argv) {
  if (const char* file = command_line_options_file(argc, argv)) {
    scene.solver.options_file = std::filesystem::path(file);
    return;
  }
  if (!use_scene) scene.solver.options_file.reset();
  if (!scene.solver.options_file) return;
  PetscCallAbort(PETSC_COMM_WORLD,
                 PetscOptionsInsertFile(PETSC_COMM_WORLD, nullptr,
                                        scene.solver.options_file->c_str(), PETSC_TRUE));
  PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsInsert(nullptr, &argc, &argv, nullptr));
}

/// Rank 0 warns about each option given that nothing read (unused_options.hpp), and says
/// where those not on the command line came from when an options file is in effect.
void report_unused_options(int rank, bool solver_built,
                           const std::optional<std::filesystem::path>& options_file) {
  if (rank != 0) return;
  int from_file = 0;
  for (const mlshell::UnusedOption& o : mlshell::unused_options(solver_built)) {
    std::cerr << "mlshell: warning: " << mlshell::describe(o) << std::endl;
    from_file += !o.on_command_line;
  }
  if (from_file > 0 && options_file)
    std::cerr << "mlshell: note: " << from_file << " of these options come from the options "
              << "file in effect, '" << options_file->string()
              << "' (or PETSC_OPTIONS); -mlshell_options_left false silences these warnings"
              << std::endl;
}

/// `mlshell -help` without a scene: the usage, then every option group as a run reads them
/// (PETSc's help prints each option with its default and description as it is read): the
/// command line's, the simulation's, the step solver's and the solver it chooses (TAO rmtr by
/// default). Returns the exit status: 0, or 2 for an invalid option value.
int print_options_help(int rank) {
  if (rank == 0) std::cout << kUsage;
  try {
    const mlshell::Scene defaults;
    CommandLineOptions o;
    PetscCallAbort(PETSC_COMM_WORLD, command_line_options(defaults, &o));
    const mlshell::SimulationOptions simulation = mlshell::SimulationOptions::from_petsc_options();
    PetscCallAbort(PETSC_COMM_WORLD,
                   mlshell::step_solver_options_help(PETSC_COMM_WORLD, *simulation.solver));
  } catch (const std::exception& e) {
    if (rank == 0) std::cerr << "mlshell: error: " << e.what() << std::endl;
    return 2;
  }
  return 0;
}

/// Large arrays (Hessians, vertex-patch factors, MUMPS's factors, frames) on transparent huge
/// pages: glibc's malloc advises its large chunks with MADV_HUGEPAGE when the process starts with
/// GLIBC_TUNABLES=glibc.malloc.hugetlb=1 (glibc 2.35 and later; earlier ones ignore it, and so
/// does a kernel whose transparent huge pages are `never`). One page fault per 2 MiB instead of
/// per 4 KiB: on a virtual machine whose page faults are slow (an AMD EPYC guest, where they were
/// 7-8 % of a run's samples) the set-up of the trampoline at 51,483 dofs took 0.92 -> 0.72 s on
/// 1 rank and 0.56 -> 0.19 s on 2. A tunable is read only when a process starts, so mlshell sets
/// it and starts itself again, before MPI is initialised. MLSHELL_HUGE_PAGES=0 turns this off;
/// a GLIBC_TUNABLES that names the tunable already is left as it is.
void restart_with_huge_pages(char** argv) {
  const char* choice = std::getenv("MLSHELL_HUGE_PAGES");
  if (choice && std::strcmp(choice, "0") == 0) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string before = tunables ? tunables : "";
  if (before.find("glibc.malloc.hugetlb") != std::string::npos) return;
  const std::string mine = "glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", before.empty() ? mine.c_str() : (before + ":" + mine).c_str(), 1))
    return;
  execv("/proc/self/exe", argv);
  // No /proc (not Linux): go on as started.
  if (tunables)
    setenv("GLIBC_TUNABLES", before.c_str(), 1);
  else
    unsetenv("GLIBC_TUNABLES");
}

}  // namespace

int main(int argc, char** argv) {
  if (wants_help(argc, argv)) {
    std::cout << kUsage << mlshell::scene_format_help() << std::endl;
    return 0;
  }
  if (wants_version(argc, argv)) {
    std::cout << mlshell::build_description() << std::endl;
    return 0;
  }
  const char* scene_path = scene_argument(argc, argv);
  const bool options_help = !scene_path && wants_petsc_help(argc, argv);
  if (!scene_path && !options_help) {
    std::cerr << kUsage;
    return 1;
  }
  if (!options_help) restart_with_huge_pages(argv);
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 1;
  int rank = 0, size = 1, status = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (options_help) {
    status = print_options_help(rank);
    PetscFinalize();
    return status;
  }
  OptionErrors option_errors;  // PETSc's message for a refused solver option value
  bool report = false, solver_built = false;
  try {
    mlshell::Scene scene = mlshell::parse_scene(scene_path);
    CommandLineOptions options;
    PetscCallAbort(PETSC_COMM_WORLD, command_line_options(scene, &options));
    apply_scene_solver_file(scene, options.scene_solver, argc, argv);
    // The user's options are all in; mlshell's defaults come later and are never reported.
    mlshell::note_given_options(argc, argv);
    apply_overrides(options, scene);
    report = options.options_left;
    if (options.material_csv) {  // the material alone: no mesh, no solve
      if (rank == 0) mlshell::write_material_table(scene.material, *options.material_csv);
      if (rank == 0)
        std::cout << "mlshell: material table in " << *options.material_csv << std::endl;
      if (report) report_unused_options(rank, false, scene.solver.options_file);
      PetscFinalize();
      return 0;
    }
    const mlshell::SimulationOptions simulation = mlshell::SimulationOptions::from_petsc_options();
    solver_built = !simulation.evaluate_only;
    const auto options_file = scene.solver.options_file;  // for the report after the run
    mlshell::Simulation sim(PETSC_COMM_WORLD, std::move(scene), simulation);
    PetscErrorCode error;
    {
      const OptionErrors::Scope catching(option_errors);
      error = sim.run(&status);
    }
    if (error && option_errors.message.empty()) PETSCABORT(PETSC_COMM_WORLD, error);
    if (error) throw mlshell::SceneError(option_errors.message);
    // Warnings after the run's own last line; a run that did not converge (exit 3) too.
    if (report) report_unused_options(rank, solver_built, options_file);
  } catch (const mlshell::OutputError& e) {
    if (rank == 0 || !e.every_rank()) std::cerr << "mlshell: error: " << e.what() << std::endl;
    // Most results are written by rank 0 alone: an error there that the other ranks do not
    // share cannot be told to them, so it ends the run with MPI_Abort.
    if (size > 1 && !e.every_rank()) MPI_Abort(PETSC_COMM_WORLD, 4);
    status = 4;
  } catch (const std::exception& e) {
    // Scene, mesh, selection and option errors are raised identically on every rank.
    const std::string what = option_errors.message.empty() ? e.what() : option_errors.message;
    if (rank == 0) std::cerr << "mlshell: error: " << what << std::endl;
    status = 2;
  }
  PetscFinalize();
  return status;
}
