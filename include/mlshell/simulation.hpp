// A scene run end to end: cage → subdivision levels → distributed problems on every level
// RMTR uses → time stepping with a TAO solver (default RMTR on all levels 0..refine) → result
// files (HDF5/XDMF, OBJ, CSV, summary.json, checkpoints).
//
// Options (besides PETSc's own, e.g. -tao_monitor, -log_view):
//   -mlshell_evaluate            print every enabled effect's energy and the gradient norm at
//                                the initial state, write summary.json, and exit
//   -mlshell_gauss_points <3>    Gauss points per direction on each element (2..6)
//   -mlshell_quiet               no per-step progress lines
//   -mlshell_hierarchy_view      print the subdivision levels 0..refine and their transfers
//   -mlshell_hierarchy_write DIR write each level's cage and limit surface (OBJ) to DIR
//   -mlshell_condition           estimate cond₂ of the Hessian at the final state (at the
//                                initial state with -mlshell_evaluate); see hessian_spectrum.hpp
//   -mlshell_condition_steps <60> Lanczos steps of that estimate
//   -mlshell_limit_csv K         write limit_surface.csv: the final limit surface sampled on a
//                                (K+1)×(K+1) grid per element, points shared by elements
//                                repeated (reference point, displacement)
// PETSc log stages (-log_view): Setup (levels, problems, solver), Solve, Output.
#pragma once

#include <petscvec.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mlshell/effect_builder.hpp"
#include "mlshell/hessian_spectrum.hpp"
#include "mlshell/multilevel_problem.hpp"
#include "mlshell/output_files.hpp"
#include "mlshell/parallel_layout.hpp"
#include "mlshell/proxy_step.hpp"
#include "mlshell/scene.hpp"
#include "mlshell/step_failure.hpp"
#include "mlshell/step_solver.hpp"
#include "mlshell/subdivision/level_hierarchy.hpp"
#include "mlshell/subdivision/subdivision_discretization.hpp"
#include "mlshell/subdivision/subdivision_hierarchy.hpp"
#include "mlshell/triangle/triangle_mesh.hpp"
#include "mlshell/time_stepper.hpp"

namespace mlshell {

class ContactTerm;
class ColliderMotion;

struct SimulationOptions {
  bool evaluate_only = false;
  int gauss_points = 3;
  bool quiet = false;
  bool hierarchy_view = false;
  std::string hierarchy_write;  ///< folder, empty: don't write
  bool condition = false;
  int condition_steps = 60;
  int limit_csv_samples = 0;  ///< 0: no limit_surface.csv
  /// -mlshell_audit_intersections: every written frame of a triangle mesh is checked for
  /// intersecting triangles (exactly, CGAL); one that has any stops the run (exit 5).
  bool audit_intersections = false;
  /// A progressive run (time.integrator progressive, progressive_run.cpp):
  /// -mlshell_progressive_stop_level k ends it after level k (-1: run to the finest);
  /// -mlshell_progressive_hessian own|galerkin: the proxy steps' Newton matrix, the level's own
  /// M_l/h² + PSD(∇²E_l) (default: as good a preview, 5.6× faster on a buckling plate) or the
  /// Galerkin J_Pᵀ PSD(∇²Ψ) J_P (a fine Hessian and a triple product per iteration);
  /// -mlshell_progressive_gradient exact|frozen: J_Pᵀ∇Ψ or eq. (10)'s Uᵀ∇Ψ.
  int progressive_stop_level = -1;
  bool progressive_own_hessian = true;
  bool progressive_frozen_gradient = false;
  /// -mlshell_step_solver, -mlshell_hessian_psd, ...; if empty, the simulation reads them.
  std::optional<StepSolverOptions> solver;
  /// Reads the groups "mlshell: simulation", "mlshell: measuring" and "mlshell: step solver"
  /// (PetscOptionsBegin/End, listed by -help); an invalid value throws SceneError or
  /// std::invalid_argument naming the option and the value.
  static SimulationOptions from_petsc_options();
};

/// Exit status of a run: 0 converged, 3 a step's solver did not converge, 5 a written frame
/// intersects itself (the intersection audit), 130 interrupted (SIGINT or SIGTERM; a
/// progressive run ends after its current proxy step with valid output).
constexpr int kExitSolverFailed = 3;
constexpr int kExitIntersection = 5;
constexpr int kExitInterrupted = 130;

struct DecimationHierarchy;

class Simulation {
 public:
  Simulation(MPI_Comm comm, Scene scene, SimulationOptions options);
  ~Simulation();
  /// Runs the scene (or only evaluates it). Returns the exit status.
  PetscErrorCode run(int* status);

  /// The finest level's discretization (SubdivisionDiscretization or TriangleDiscretization).
  const Discretization& discretization() const { return *disc_; }
  LevelProblem& problem() { return *problem_; }
  Vec displacement() const { return u_; }
  /// Solver iterations summed over the steps run so far.
  long iterations() const { return total_iterations_; }
  /// RMTR work summed over the steps run so far (empty levels for other solvers).
  const RmtrStatistics& rmtr_totals() const { return rmtr_totals_; }
  /// Natural-order displacement on rank 0.
  PetscErrorCode natural_displacement(std::vector<double>& u) const;

 private:
  struct Output;
  PetscErrorCode set_initial_state();
  PetscErrorCode evaluate(int* status);
  PetscErrorCode step(int n, SolveReport& report);
  /// Adds a step's solve (its report and wall time) to the run's totals.
  void count_solve(const SolveReport& report, double wall);
  /// Step n's solve fell through the energy floor: says why and what to change, and returns
  /// to the state of step n − 1.
  PetscErrorCode stop_unbounded(int n, SolveReport& report);
  struct FrameSeries;
  /// Step n's frame of the run (if due), its audit and its checkpoint.
  PetscErrorCode write_frame(int n, double t, bool force, bool converged);
  /// A frame of `series` at state u (audited first if `audit`).
  PetscErrorCode write_series_frame(FrameSeries& series, Vec u, int n, double t, bool audit);
  PetscErrorCode write_frame_files(
      FrameSeries& series, Vec u, int n, double t, bool xdmf, bool obj,
      const std::vector<std::pair<std::string, std::vector<double>>>& fields);
  PetscErrorCode write_summary(const std::string& status, const SolveReport* last);
  PetscErrorCode estimate_condition();
  PetscErrorCode write_limit_csv();

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  Scene scene_;
  SimulationOptions options_;
  CageFrame frame_;
  std::unique_ptr<SubdivisionHierarchy> hierarchy_;  // subdivision shells only
  std::unique_ptr<Levels> levels_;                   // all levels for RMTR, else the finest alone
  std::unique_ptr<MultilevelProblem> multilevel_;    // the scene on each of them
  const Discretization* disc_ = nullptr;             // the finest level's
  const ParallelLayout* layout_ = nullptr;
  LevelProblem* problem_ = nullptr;
  std::unique_ptr<StepSolver> solver_;
  std::unique_ptr<TimeStepper> stepper_;
  std::unique_ptr<Output> output_;
  Vec u_ = nullptr, v_ = nullptr;
  Vec u_last_ = nullptr, v_last_ = nullptr;  // the state before the step being solved
  EnergyScale energy_scale_;
  int first_step_ = 0;
  /// A probe: displacement Σ w_i u_{nodes[i]} at the reference point X.
  struct ProbePoint {
    std::vector<int> nodes;
    std::vector<double> weights;
    Point3 reference;
  };
  std::vector<ProbePoint> probes_;
  void setup_subdivision();
  void setup_triangles();
  /// The scene's geometry.hierarchy of `mesh` (SceneError naming the key if it cannot be built).
  std::shared_ptr<const DecimationHierarchy> decimate_mesh(const TriangleMesh& mesh);
  double wall_start_ = 0.0;
  long total_iterations_ = 0;
  long total_linear_iterations_ = 0;
  long total_solves_ = 0;    ///< minimisations (quasistatic: proximal solves)
  double solve_time_ = 0.0;  ///< seconds in the steps' solves (no setup, no output)
  RmtrStatistics rmtr_totals_;
  MaterialReport material_final_;  // the last step's solution
  long steps_beyond_fit_ = 0, steps_negative_ = 0;
  double min_energy_density_ = INFINITY;  // over all steps' solutions
  PetscErrorCode report_material(int step);
  /// Largest violation of each penalty term (index of terms()): last step and all steps.
  std::vector<double> violation_last_, violation_max_;
  PetscErrorCode report_constraints(int step);
  /// A penalty condition violated by more than this fraction of h is reported after the step.
  static constexpr double kConstraintWarning = 0.05;
  bool all_converged_ = true;
  int steps_done_ = 0;
  /// The intersection audit (-mlshell_audit_intersections, triangle meshes): the state u of a
  /// series as positions, its intersecting triangle pairs (on every rank) and the message naming
  /// them.
  PetscErrorCode audit_frame(const FrameSeries& series, Vec u, int n, double t, long* pairs,
                             std::string* message);
  long audited_frames_ = 0, intersecting_pairs_ = 0;
  /// The finest level's contact term (null without contact; contact_run.cpp): its colliders
  /// are audited with every frame and written once as colliders.obj.
  ContactTerm* contact_ = nullptr;
  /// Contact scenes: refuses a solver that ignores CCD's step limit (exit 2).
  void check_contact_solver() const;
  /// Contact scenes at the first frame: the shell must start farther than the thickness ξ from
  /// itself and the colliders (else SceneError); writes colliders.obj.
  PetscErrorCode start_contact();
  /// The colliders where they are now, one object each, into `file` (rank 0): colliders.obj
  /// at the start, and colliders_NNNNNN.obj with every frame when they move.
  void write_colliders(const std::string& file) const;
  /// Scripted colliders (collider_motion.hpp; null when every collider is static).
  std::unique_ptr<ColliderMotion> collider_motion_;
  /// Contact scenes with moving colliders: the driver, at the places of `time`, given to the
  /// time stepper.
  void start_collider_motion(double time);
  /// The contact section of summary.json (collective; null without contact).
  PetscErrorCode contact_summary(Json* out) const;
  std::string audit_message_;  ///< of the last frame audited, if it intersects
  std::optional<SpectrumEstimate> spectrum_;
  PetscLogStage stage_setup_ = 0, stage_solve_ = 0, stage_output_ = 0;

  // A progressive run (progressive_run.cpp).
  /// What a progressive run found on each level, for the summary.
  struct ProgressiveLevel {
    int level = 0;
    int vertices = 0;
    double wall_time = 0.0;      ///< on this level (s)
    double time_to_level = 0.0;  ///< from the start of the solve to this level's end (s)
    int proxy_steps = 0;         ///< the finest level: its proximal solves
    long iterations = 0, linear_iterations = 0;
    double energy = 0.0;         ///< E at the level's result on the finest mesh (no proximal)
    double max_violation = 0.0;  ///< of the boundary conditions there (m)
    bool equilibrium = false;    ///< the finest level: converged
    std::string stop;
    Vec preview = nullptr;  ///< a coarse level's result prolonged to the finest
  };
  std::vector<ProgressiveLevel> progressive_levels_;
  std::string progressive_outcome_;  ///< empty while running, then the summary's status
  PetscErrorCode run_progressive(int* status);
  /// Refinement from level l to l + 1: x_{l+1} = P_{l+1}^l(x_l). The seam where contact's safe
  /// initialisation (paper 2 §4.4, Alg. 2) will replace the plain prolongation.
  PetscErrorCode refine(int l, Vec coarse, Vec fine);
  /// Proxy steps of level l from x (in place) until it is in equilibrium (level 0: the loading
  /// first); appends the level's record. *interrupted: SIGINT or SIGTERM on some rank.
  PetscErrorCode preview_level(int l, Vec x, double solve_start, bool* interrupted);
  PetscErrorCode write_progress_row(int level, int step, double time, const ProxyStepReport& r,
                                    double wall);
  /// The summary's `progressive` section (collective).
  PetscErrorCode progressive_summary(Json* section);
};

/// Builds the level-0 cage with its ghost ring from the scene's geometry.
QuadMesh build_cage(const GeometrySpec& geometry);

}  // namespace mlshell
