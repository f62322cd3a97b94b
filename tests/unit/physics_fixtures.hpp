// Small level problems for derivative and parallel tests, each enabling one family of effects.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "mlshell/effect_builder.hpp"
#include "mlshell/effects.hpp"
#include "mlshell/simulation.hpp"
#include "mlshell/subdivision/subdivision_hierarchy.hpp"

namespace mlshell {

/// A cage around an interior extraordinary vertex of the given valence (a fan of quads),
/// slightly curved: two rings of faces, or one (`near_boundary`: the extraordinary vertex is then
/// one edge away from the boundary).
inline QuadMesh fan_cage(int valence, bool near_boundary = false) {
  QuadMesh m;
  m.points.emplace_back(0, 0, 0);
  const double pi = std::acos(-1.0);
  for (int r = 0; r < 2; ++r)
    for (int k = 0; k < valence; ++k) {
      const double a = 2 * pi * k / valence, b = 2 * pi * (k + 0.5) / valence;
      m.points.emplace_back((r + 1) * std::cos(a), (r + 1) * std::sin(a), 0.05 * r);
      m.points.emplace_back((r + 1.3) * std::cos(b), (r + 1.3) * std::sin(b), 0.0);
    }
  auto spoke = [&](int r, int k) { return 1 + r * 2 * valence + 2 * (k % valence); };
  auto mid = [&](int r, int k) { return 2 + r * 2 * valence + 2 * (k % valence); };
  for (int k = 0; k < valence; ++k) {
    m.quads.push_back({0, spoke(0, k), mid(0, k), spoke(0, k + 1)});
    if (near_boundary) continue;
    m.quads.push_back({spoke(0, k), spoke(1, k), mid(1, k), mid(0, k)});
    m.quads.push_back({mid(0, k), mid(1, k), spoke(1, k + 1), spoke(0, k + 1)});
  }
  if (near_boundary) m.points.resize(1 + 2 * valence);  // drop the unused outer ring
  m.ghost.assign(m.quads.size(), 0);
  return m;
}

struct TestProblem {
  Scene scene;
  std::unique_ptr<SubdivisionDiscretization> disc;
  std::unique_ptr<ParallelLayout> layout;
  std::unique_ptr<LevelProblem> problem;

  /// kind: elastic_denim | elastic_svk | inertia | loads | dirichlet | clamp | extraordinary | all
  TestProblem(const std::string& kind, MPI_Comm comm, int refine = 1) {
    scene.material.model = denim_preset();
    scene.material.thickness = 0.66e-3;
    scene.material.density = 0.4;
    scene.time = {0.5, 4};
    RectangleCage rect;
    scene.geometry.cage = rect;
    QuadMesh cage = add_ghost_ring(make_rectangle_cage(1, 1, 4, 4, 0, 0));
    auto where = [](const std::string& text) { return parse_where_text(text, "test"); };
    if (kind == "elastic_svk") scene.material.model = SvkMaterial{1e7, 0.3};
    if (kind == "inertia" || kind == "all") scene.effects.push_back(InertiaEffect{});
    if (kind == "loads" || kind == "all") {
      scene.effects.push_back(GravityEffect{});
      scene.effects.push_back(SurfaceLoadEffect{{0.1, 0.0, -3.0}, true});
      scene.effects.push_back(LineLoadEffect{where("boundary(right)"), {0, 0.5, -4}, false});
      scene.effects.push_back(PointLoadEffect{where("point(0.3, 0.6)"), {0, 0, -1}, true});
    }
    if (kind == "dirichlet" || kind == "all") {
      // A translation with a rotation about a skew axis through the left side.
      Motion m{{0.2, 0.0, 0.1}, {0.0, 2.0}, Rotation{{0, 1, 1}, {0, 0.5, 0}, 0.8}};
      scene.effects.push_back(
          DirichletEffect{where("boundary(left)"), {true, false, true}, m, 5.0, {}});
      scene.effects.push_back(
          DirichletEffect{where("corner(top-right)"), {true, true, true}, {}, 5.0, 1e4});
    }
    if (kind == "clamp" || kind == "all") {
      // Turning about the bottom side's own line: its points stay, its slope turns.
      Motion m{{0.0, 0.0, 0.0}, {0.0, 2.0}, Rotation{{1, 0, 0}, {0.5, 0, 0}, 0.6}};
      scene.effects.push_back(ClampEffect{where("boundary(bottom)"), m, 5.0, {}, {}});
    }
    CageFrame frame = CageFrame::from(scene.geometry);
    if (kind == "extraordinary") {
      cage = add_ghost_ring(fan_cage(5));
      scene.geometry.cage = ObjCage{"fan"};
      frame = CageFrame{};
      CurveSelection box{CurveSelection::Kind::Box, "", {-10, -10, -10}, {10, 0.0, 10}};
      scene.effects.push_back(GravityEffect{});
      scene.effects.push_back(DirichletEffect{{box, "box"}, {true, true, true}, {}, 5.0, {}});
    }
    disc =
        std::make_unique<SubdivisionDiscretization>(SubdivisionHierarchy(cage, refine).finest(), 3);
    layout = std::make_unique<ParallelLayout>(comm, *disc);
    problem = build_level_problem(scene, *disc, *layout, frame);
    problem->set_time(1.0);
    if (auto* inertia = problem->find_term<InertiaTerm>()) {
      Vec p;
      layout->create_vector(&p);
      random_state(p, 1e-2, 99);
      std::vector<double> local;
      layout->to_local(p, local);
      inertia->set_predictor(local);
      VecDestroy(&p);
    }
  }

  /// A smooth-ish random displacement (same values in natural order for any rank count).
  void random_state(Vec u, double scale, unsigned seed) const {
    std::vector<double> nat;
    if (layout->rank() == 0) {
      std::mt19937 rng(seed);
      std::uniform_real_distribution<double> dist(-scale, scale);
      nat.resize(disc->num_dofs());
      for (double& x : nat) x = dist(rng);
    }
    layout->scatter_natural(nat, u);
  }
};

/// A scene run quietly (only summary.json is written, into `dir`): the simulation, its exit
/// status, and the final displacement in natural order on rank 0.
struct SolvedScene {
  std::unique_ptr<Simulation> simulation;
  int status = -1;
  std::vector<double> displacement;
};

/// max |a − b| / max |b|: how far a result (on 2 ranks) is from its reference (on 1).
/// The Hessian check of a problem's derivative tests: H = ∇²f(u) into *H (the caller destroys
/// it), *ref = ‖H d‖ and *err = ‖H d − (g⁺ − g⁻)/2h‖ for the gradients g± at u ± h d (`gp` is
/// overwritten; `Hd` receives H d).
inline void hessian_difference(LevelProblem& problem, Vec u, Vec d, Vec gp, Vec gm, Vec Hd, double h,
                               Mat* H, double* err, double* ref) {
  problem.create_matrix(H);
  problem.hessian(u, *H);
  MatMult(*H, d, Hd);
  VecAXPY(gp, -1.0, gm);
  VecScale(gp, 1.0 / (2 * h));
  VecNorm(Hd, NORM_2, ref);
  VecAXPY(gp, -1.0, Hd);
  VecNorm(gp, NORM_2, err);
}

inline double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0.0, norm = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    norm = std::max(norm, std::abs(b[i]));
  }
  return diff / (norm + 1e-300);
}

inline SolvedScene solve_scene(Scene scene, MPI_Comm comm, const std::string& dir) {
  scene.output.dir = dir;
  scene.output.formats = {};
  scene.output.checkpoint_every = 0;
  SimulationOptions options;
  options.quiet = true;
  SolvedScene out;
  out.simulation = std::make_unique<Simulation>(comm, scene, options);
  PetscCallAbort(comm, out.simulation->run(&out.status));
  out.simulation->natural_displacement(out.displacement);
  return out;
}

}  // namespace mlshell
