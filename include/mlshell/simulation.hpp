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
#include "mlshell/parallel_layout.hpp"
#include "mlshell/scene.hpp"
#include "mlshell/step_failure.hpp"
#include "mlshell/step_solver.hpp"
#include "mlshell/subdivision/level_hierarchy.hpp"
#include "mlshell/subdivision/subdivision_discretization.hpp"
#include "mlshell/subdivision/subdivision_hierarchy.hpp"
#include "mlshell/triangle/triangle_mesh.hpp"
#include "mlshell/time_stepper.hpp"

namespace mlshell {

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
  /// -mlshell_step_solver, -mlshell_hessian_psd, ...; if empty, the simulation reads them.
  std::optional<StepSolverOptions> solver;
  /// Reads the groups "mlshell: simulation", "mlshell: measuring" and "mlshell: step solver"
  /// (PetscOptionsBegin/End, listed by -help); an invalid value throws SceneError or
  /// std::invalid_argument naming the option and the value.
  static SimulationOptions from_petsc_options();
};

/// Exit status of a run: 0 converged, 3 a step's solver did not converge, 5 a written frame
/// intersects itself (the intersection audit).
constexpr int kExitSolverFailed = 3;
constexpr int kExitIntersection = 5;

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
  /// Step n's solve fell through the energy floor: says why and what to change, and returns
  /// to the state of step n − 1.
  PetscErrorCode stop_unbounded(int n, SolveReport& report);
  PetscErrorCode write_frame(int n, double t, bool force, bool converged);
  PetscErrorCode write_frame_files(
      int n, double t, bool xdmf, bool obj,
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
  /// The intersection audit (-mlshell_audit_intersections, triangle meshes): the state u_ as
  /// positions, its intersecting triangle pairs (on every rank) and the message naming them.
  PetscErrorCode audit_frame(int n, double t, long* pairs, std::string* message);
  long audited_frames_ = 0, intersecting_pairs_ = 0;
  std::string audit_message_;  ///< of the last frame audited, if it intersects
  std::optional<SpectrumEstimate> spectrum_;
  PetscLogStage stage_setup_ = 0, stage_solve_ = 0, stage_output_ = 0;
};

/// Builds the level-0 cage with its ghost ring from the scene's geometry.
QuadMesh build_cage(const GeometrySpec& geometry);

}  // namespace mlshell
