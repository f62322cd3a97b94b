#!/usr/bin/python3
"""Mutation check of the test suite (run by hand, not in CI): breaks the code in one place at a
time, rebuilds, runs the suite and reports which tests failed. Every mutation must be caught.

Each mutation replaces one exact piece of source text (which must occur once) and is reverted
afterwards, whatever happens. The suite run is `ctest` less its three long end-to-end tests
(studies.quick, cli.hard_cases, cli.paper_scenes), plus those a mutation names in `also`.

usage: tests/mutation/mutations.py BUILD_DIR [NAME ...]   (default: every mutation)
       tests/mutation/mutations.py --check   (each text occurs once: no mutation has gone stale;
                                              ctest mutations.texts)
Writes BUILD_DIR/mutations.md (the table) and prints it."""
import os
import re
import subprocess
import sys
import time
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
LONG = ("studies.quick", "cli.hard_cases", "cli.paper_scenes")

# name, file, old text, new text, what it breaks, long tests to run as well
MUTATIONS = [
    ("studies-row-build-dropped", "examples/studies/runner.py",
     '    build = (s or {}).get("build", {}).get("commit", "")', '    build = ""',
     "the studies' rows do not name the mlshell build that measured them", ()),
    ("studies-old-rows-dropped", "examples/studies/context.py",
     "            if old and [c for c in old[0] if c != PROVENANCE] == columns[:-1]:",
     "            if old and list(old[0]) == columns:",
     "a CSV written before the build column loses its rows when a study adds its own", ()),
    ("trial-gradient-discarded", "solvers/local_trust_region.cpp",
     "  if (trial_gradient_) {  // f and ∇f at x + s are known already",
     "  if (false) {  // f and ∇f at x + s are known already",
     "an accepted trial point is evaluated again although its gradient came with its value", ()),
    ("trial-reduction-no-trapezoid", "solvers/local_trust_region.cpp",
     "if (predicted < 1e3 * f_error && direct > -10.0 * f_error) {", "if (false) {",
     "the actual reduction is f(x) − f(x+s) also below the noise of f (Local_TR and RMTR's "
     "coarse corrections)", ()),
    ("trial-measured-direct", "solvers/local_trust_region.cpp",
     "  trial_measured_ = *actual;\n", "",
     "an accepted step adds f(x) − f(x+s) to the reduction since the start, also where "
     "trial_reduction took the trapezoidal rule", ()),
    ("rmtr-coarse-reduction-difference", "solvers/tao_rmtr.cpp",
     "PetscReal coarse_reduction = lc.tr->reduction();",
     "PetscReal coarse_reduction = f0 - lc.tr->value();",
     "RMTR's coarse reduction is the difference of two coarse values (round-off of either sign "
     "below the noise of h)", ()),
    ("galerkin-half-dropped", "solvers/coarse_level_model.cpp",
     "    *h = wr + 0.5 * wgw;", "    *h = wr + wgw;",
     "the Galerkin coarse model's value is ⟨r, w⟩ + wᵀGw (the quadratic term doubled)", ()),
    ("galerkin-first-order", "solvers/tao_rmtr.cpp",
     "    if (c.coarse_model == kGalerkin) {",
     "    if (c.coarse_model == -1) {",
     "-tao_rmtr_coarse_model galerkin builds the first-order models (4.3)", ()),
    ("stagnation-always-converged", "solvers/local_trust_region.cpp",
     "? TAO_CONVERGED_STEPTOL : TAO_DIVERGED_USER;",
     "? TAO_CONVERGED_STEPTOL : TAO_CONVERGED_STEPTOL;",
     "the stagnation test of (7.1) reports convergence however far ‖g‖ is above the tolerance",
     ()),
    ("floor-ignores-steady-progress", "solvers/local_trust_region.cpp",
     "std::abs(floor_decrease_ + df) <= noise", "true",
     "a slow solve that lowers f steadily by less than its noise per iteration is declared at "
     "the floor (converged at the limiting accuracy) far from its minimiser", ()),
    ("stagnation-ignores-gradient", "solvers/local_trust_region.cpp",
     "if (!(delta > 1e15) || since_best_ < stagnation_window) return false;",
     "if (!(delta > 1e15)) return false;",
     "the stagnation test of (7.1) stops V-cycles that still contract ‖g‖ once f stops "
     "changing in its last bits", ()),
    ("scene-solver-file-mixed", "src/cli/main.cpp",
     "  if (const char* file = command_line_options_file(argc, argv)) {",
     "  if (const char* file = nullptr) {",
     "a command-line -options_file is layered over the scene's solver file instead of replacing "
     "it: two configurations mixed", ()),
    ("scene-solver-switch-ignored", "src/cli/main.cpp",
     "  if (!use_scene) scene.solver.options_file.reset();\n", "",
     "-mlshell_scene_solver false still reads the scene's solver file", ()),
    ("inexact-newton-unshifted", "solvers/trust_region_qp.cpp",
     "  if (*reason == KSP_DIVERGED_INDEFINITE_MAT) {\n", "  if (false) {\n",
     "Dogleg's CG Newton point that meets negative curvature is not shifted: Cauchy steps",
     ()),
    ("inexact-newton-ignored", "solvers/tao_rmtr.cpp",
     "InexactNewton{pc_type, static_cast<int>(stcg_max_it), newton_rtol}", "InexactNewton{}",
     "Dogleg smoothing with -tao_rmtr_smoother_pc factorises above the coarsest level anyway",
     ()),
    ("redundant-inertia-unread", "solvers/trust_region_qp.cpp",
     "  if (redundant) {\n", "  if (false) {\n",
     "under pc_type redundant Dogleg misses an indefinite Hessian: the unshifted Newton point",
     ()),
    ("fmg-floor-at-finest-factor", "solvers/tao_rmtr.cpp",
     "  rule.limiting_factor = PETSC_INFINITY;  // the floor ends a start's level wherever it lies\n",
     "", "a full-multigrid level whose round-off floor lies above 100x the finest tolerance runs "
     "all its V-cycles at that floor", ()),
    ("coarse-never-redundant", "solvers/tao_rmtr.cpp",
     "                l == 0 && lv.stats.dofs <= c->coarse_redundant),",
     "                false),",
     "the default coarsest level is factorised by MUMPS distributed over the ranks, which "
     "varies from run to run (-tao_rmtr_coarse_redundant ignored)", ()),
    ("default-retries-dropped", "solvers/step_solver.cpp",
     '                                      {"rmtr_retries", "3"},\n', "",
     "mlshell's default no longer matches petsc-options/rmtr-patch-dogleg.yaml, which claims "
     "to spell it out", ()),
    ("factorisations-uncounted", "solvers/trust_region_qp.cpp",
     "  if (!iterative_) ++factorisations_;\n", "",
     "RMTR's per-level factorisation count stays 0 (no factorisation seen anywhere)", ()),
    ("subspace-reach-kept", "solvers/subspace_acceleration.cpp",
     "        reach_ = std::max<PetscReal>(kMinReach, p.gamma1 * std::min(reach_, d_norm / s_norm));\n",
     "        reach_ = std::max<PetscReal>(kMinReach, reach_);\n",
     "a rejected subspace step leaves its reach as it was: the same rejected step again", ()),
    ("stagnation-window-one", "solvers/local_trust_region.cpp",
     "since_best_ < stagnation_window", "since_best_ < 1",
     "the stagnation test's window shrunk to one iteration: a V-cycle that raises ‖g‖ a little "
     "ends a solve that is still converging", ()),
    ("coarse-start-iterate-ignored", "solvers/tao_rmtr.cpp",
     "  if (lc.anchored)\n", "  if (false)\n",
     "-tao_rmtr_coarse_start iterate ignored: every coarse solve starts from the projection "
     "of the fine iterate", ()),
    ("retries-ignored", "solvers/tao_rmtr.cpp",
     "    if (!it.accepted && tries < c.retries) {", "    if (false) {",
     "-tao_rmtr_retries ignored: a rejected smoothing step waits a V-cycle for the next", ()),
    ("subspace-hard-case-inside", "solvers/subspace_acceleration.cpp",
     "      y(0) += tau;\n", "",
     "the subspace step's small trust-region problem stops inside the ball in the hard case "
     "(negative curvature not followed to the boundary)", ()),
    ("subspace-no-acceptance-test", "solvers/subspace_acceleration.cpp",
     "      if (out->rho > p.eta1) {\n        PetscCall(tr.accept_trial());",
     "      if (true) {\n        PetscCall(tr.accept_trial());",
     "the subspace step after a V-cycle is taken whatever its ratio ρ (the energy may rise)",
     ()),
    ("stcg-target-ignored", "solvers/trust_region_qp.cpp",
     "std::max(atol_, target_)", "atol_",
     "STCG runs its full iteration count whatever the model gradient (-tao_rmtr_stcg_target "
     "ignored)", ()),
    ("rmtr-coarse-radius", "solvers/tao_rmtr.cpp",
     "PetscReal coarse_delta = *delta;", "PetscReal coarse_delta = 1e-3 * *delta;",
     "RMTR's coarse radius is 1e-3·Δ (a useless coarse level)", ()),
    ("lsq-projection-nothing", "solvers/transfer/linear_transfer.cpp",
     "      PetscCall(least_squares_(fine, coarse));\n", "",
     "-tao_rmtr_projection lsq computes nothing (stale coarse start)", ()),
    ("inertia-rho-over-dt", "src/physics/shell/inertia_term.cpp",
     "coefficient_(area_density / (dt * dt))", "coefficient_(area_density / dt)",
     "inertia coefficient ρ/dt instead of ρ/dt²", ()),
    ("denim-alpha13", "src/scene/denim_preset.cpp",
     "{{-7.80, 10.80, 18.95, -12.89, 1.61},", "{{-7.80, 10.80, 18.59, -12.89, 1.61},",
     "a typo in Table 1's α₁₃", ()),
    ("denim-mu14", "src/scene/denim_preset.cpp", "2407.67, 3416.79}", "2407.76, 3416.79}",
     "a transposed digit in Table 1's μ₁₄ (the fit stays continuable)", ()),
    ("frames-reference-geometry", "mesh/distributed_sampling.cpp",
     "PetscCall(VecWAXPY(*geometry, 1.0, reference_, *displacement));",
     "PetscCall(VecCopy(reference_, *geometry));",
     "the XDMF frames hold the reference geometry for every frame", ()),
    ("obj-reference-geometry", "mesh/discretization.cpp",
     "      s.points[3 * p + c] += d[c];\n", "",
     "whole-surface samples (limit_surface.csv, serial OBJ files) hold the reference geometry",
     ()),
    ("obj-frames-rank-zero-vertices", "src/io/obj_writer.cpp",
     "  vertices = io_detail::gather_text(comm, std::move(vertices));\n",
     "  if (false) vertices = io_detail::gather_text(comm, std::move(vertices));\n",
     "OBJ frames written in parallel hold only rank 0's vertices (wrong on 2 ranks only)", ()),
    ("parallel-frames-slice", "mesh/subdivision/surface_sampler.cpp",
     "const auto [first, last] = slice_range(num_elements, part, parts);",
     "const auto [first, last] = slice_range(num_elements, 0, parts);",
     "every rank samples the first rank's elements (wrong on 2 ranks only)", ()),
    ("parallel-frames-local-cells", "mesh/subdivision/surface_sampler.cpp",
     "cells.insert(cells.end(), {numbering.index(e, i, j), numbering.index(e, i + 1, j),",
     "cells.insert(cells.end(), {numbering.index(e, i, j) - first_point, numbering.index(e, i + 1, j),",
     "a part's cells number their first corners from the part's first point, not the whole's "
     "(wrong on 2 ranks only)", ()),
    ("frames-edge-one-direction", "mesh/subdivision/surface_sampler.cpp",
     "return edge_[4 * e + c] + (q[c] < q[(c + 1) % 4] ? t - 1 : k - 1 - t);",
     "return edge_[4 * e + c] + t - 1;",
     "the frames' cells find a shared edge's points in their own direction, not the edge's "
     "canonical one (a face whose edge runs from its higher to its lower vertex folds)", ()),
    ("line-load-weight", "src/simulation/effect_builder.cpp",
     "s.weight * s.point.basis.w[kValue][i] * l->force_per_length[c];",
     "s.point.basis.w[kValue][i] * l->force_per_length[c];",
     "line loads lose their quadrature weight (wrong magnitude)", ()),
    ("ramp-ignored", "src/physics/linear_load_term.cpp",
     "return ramp_time_ > 0.0 ? std::clamp(time_ / ramp_time_, 0.0, 1.0) : 1.0;",
     "return 1.0;", "ramped loads act in full from t = 0", ()),
    ("never-accept", "solvers/local_trust_region.cpp",
     "  if (it->rho > p.eta1) {", "  if (it->rho > 2 * p.eta1 + 1) {",
     "Local_TR never accepts a step: every hard case fails", ("cli.hard_cases",)),
    # Five of our own: physics, transfers, solver stopping.
    ("bending-lever-arm", "src/physics/shell/shell_kinematics.cpp",
     "z_.push_back((rule.points[k] - 0.5) * thickness);",
     "z_.push_back(0.8 * (rule.points[k] - 0.5) * thickness);",
     "physics: through-thickness lever arm 0.8 z (bending stiffness × 0.64)", ()),
    ("penalty-gradient-factor", "src/physics/penalty_term.cpp",
     "(scale_ * s.weight * r[c] - (lambda && components_[c] ? lambda[c] : 0.0))",
     "(2 * scale_ * s.weight * r[c] - (lambda && components_[c] ? lambda[c] : 0.0))",
     "physics: the penalty gradient is twice its energy's", ()),
    ("reverse-subdivision-weight", "mesh/subdivision/reverse_subdivision.cpp",
     "c2 = -4.0 / (t * (t - 3.0))", "c2 = -3.0 / (t * (t - 3.0))",
     "transfers: a wrong weight of eq. (5.19) at extraordinary vertices", ()),
    ("limiting-factor", "include/mlshell/local_trust_region.hpp",
     "limiting_factor = 100.0;", "limiting_factor = 1e8;",
     "stopping: a stall far above the floor is reported as converged", ()),
    ("damped-newton-alpha", "solvers/tao_newton_baselines.cpp",
     "PetscReal alpha = 0.3;", "PetscReal alpha = 0.5;",
     "baselines: damped Newton with α = 0.5 instead of 0.3", ()),
    # Triangle shells (paper 2): physics, assembly, stepping, projected Newton.
    ("membrane-lame", "src/physics/triangle/triangle_elastic_term.cpp",
     "return {E / (2.0 * (1.0 + nu)), E * nu / (1.0 - nu * nu), thickness};",
     "return {E / (2.0 * (1.0 + nu)), E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), thickness};",
     "triangles: the membrane takes the 3-D Lamé λ instead of plane stress", ()),
    ("hinge-owner", "src/physics/triangle/triangle_elastic_term.cpp",
     "const bool owned = layout.face_owner(h.faces[0]) == layout.rank();",
     "const bool owned = true;",
     "triangles: every rank assembles every hinge it sees (counted twice on 2 ranks)", ()),
    ("pressure-reference-volume", "src/physics/triangle/pressure_term.cpp",
     "  energy.add(p * reference_volume_);\n", "",
     "triangles: the pressure energy is not measured from the reference volume", ()),
    ("pressure-edge-sign", "src/physics/triangle/pressure_term.cpp",
     "const Eigen::Matrix3d S = (pressure / 6.0) * cross_matrix(w);",
     "const Eigen::Matrix3d S = (-pressure / 6.0) * cross_matrix(w);",
     "triangles: the pressure's edge blocks have the wrong sign (not the Hessian of −pV)", ()),
    ("pressure-edge-one-opposite", "src/physics/triangle/pressure_term.cpp",
     "  const Eigen::Vector3d w = xc - xd;\n", "  const Eigen::Vector3d w = xc;\n",
     "triangles: an edge's pressure block takes one opposite vertex, not the difference of both "
     "(not the exact Hessian, and it depends on the origin)", ()),
    ("pressure-edge-unprojected", "src/physics/triangle/pressure_term.cpp",
     "  if (!project) return M;\n", "  return M;\n",
     "triangles: -mlshell_pressure_psd leaves the pressure's edge blocks indefinite", ()),
    ("pressure-edge-projection-not-halved", "src/physics/triangle/pressure_term.cpp",
     "  M *= 0.5;\n", "",
     "triangles: the projected edge block keeps all of M_e (not ½ M_e + ½ |M_e|)", ()),
    ("pressure-edge-projection-suction", "src/physics/triangle/pressure_term.cpp",
     "(std::abs(pressure) / 12.0)", "(pressure / 12.0)",
     "triangles: under a negative pressure (suction) the projected edge block is not PSD", ()),
    ("pressure-edges-on-both-ranks", "src/physics/triangle/pressure_term.cpp",
     "    if (layout.face_owner(h.faces[0]) == layout.rank())\n      edges_",
     "    if (layout.face_owner(h.faces[0]) == layout.rank() ||\n"
     "        layout.face_owner(h.faces[1]) == layout.rank())\n      edges_",
     "triangles: an edge whose faces lie on two ranks adds its pressure block on both", ()),
    ("pressure-psd-by-default", "solvers/step_solver.cpp",
     "  return options.hessian_psd && (term != \"pressure\" || options.pressure_psd);",
     "  return options.hessian_psd;",
     "-mlshell_hessian_psd projects the pressure's Hessian without -mlshell_pressure_psd "
     "(projected Newton linear on a stable balloon)", ()),
    ("pressure-psd-option-ignored", "solvers/step_solver.cpp",
     "  o->pressure_psd = pressure_psd;\n", "",
     "-mlshell_pressure_psd is read but not applied", ()),
    ("pressure-volume-one-rank", "src/physics/triangle/pressure_term.cpp",
     "  MPI_Allreduce(MPI_IN_PLACE, &enclosed_volume_, 1, MPI_DOUBLE, MPI_SUM, layout.comm());\n",
     "", "triangles: the orientation check sees only this rank's part of V(X)", ()),
    ("pressure-orientation-unchecked", "src/simulation/triangle_effect_builder.cpp",
     "      if (!(term->enclosed_volume() > 0.0)) {", "      if (false) {",
     "triangles: pressure on an inward-oriented closed surface is accepted (and deflates it)",
     ()),
    ("clamp-mirror", "src/physics/triangle/clamp_hinge_term.cpp",
     "h.virtual_vertex = X[a] + X[b] - X[c];", "h.virtual_vertex = X[a] + X[b] - 0.9 * X[c];",
     "triangles: the clamp's virtual triangle is not the rest mirror (a bent rest)", ()),
    ("clamp-motion", "src/physics/triangle/clamp_hinge_term.cpp",
     "placement.position(h.virtual_vertex),", "h.virtual_vertex,",
     "triangles: the clamp's virtual triangle stays behind when the clamp moves", ()),
    ("clamp-hinge-not-turned", "src/physics/triangle/clamp_hinge_term.cpp",
     "placement.position(h.virtual_vertex),", "h.virtual_vertex + placement.translation,",
     "triangles: a turning clamp's virtual triangle translates but does not turn (the clamped "
     "slope stays at rest)", ()),
    ("midedge-clamp-not-turned", "src/physics/triangle/midedge_clamp_term.cpp",
     "x[k] = placement.position(e.reference[k]);",
     "x[k] = e.reference[k] + placement.translation;",
     "triangles: a turning midedge clamp's virtual wings translate but do not turn", ()),
    ("motion-rotation-sign", "src/scene/scene.cpp",
     "R[i][j] += sin_a * K[i][j]", "R[i][j] += -sin_a * K[i][j]",
     "scene: rotations turn left-handed about their axis", ()),
    ("motion-rotation-jumps", "src/scene/scene.cpp",
     "const double alpha = progress(t) * rotate->angle;", "const double alpha = rotate->angle;",
     "scene: a rotation jumps to its full angle instead of growing over `over`", ()),
    ("motion-rotation-about-origin", "include/mlshell/prescribed_motion.hpp",
     "return rotation * (X - center) + center + translation;",
     "return rotation * X + translation;",
     "scene: rotations turn about the axis through the origin, not through `center`", ()),
    ("motion-rotate-ignored", "src/scene/effects_section.cpp",
     "  if (rotate) motion.rotate = read_rotation(*rotate);\n", "",
     "scene: a motion's `rotate` is read past and never turns anything", ()),
    ("motion-without-parts-accepted", "src/scene/effects_section.cpp",
     "field.check(translate || rotate,", "field.check(true,",
     "scene: a motion with neither `translate` nor `rotate` is accepted (and does nothing)", ()),
    ("triangle-dirichlet-sample-local-index", "src/simulation/triangle_effect_builder.cpp",
     "beta * w, 0.0, disc.points()[v]});\n      }\n",
     "beta * w, 0.0, disc.points()[layout.local_of(v)]});\n      }\n",
     "triangles: a turning curve condition takes its reference points by their local index "
     "(right on 1 rank only)", ("mpi.two_ranks",)),
    ("motion-zero-axis-accepted", "src/scene/effects_section.cpp",
     "axis.check(length > 0.0 && std::isfinite(length),", "axis.check(std::isfinite(length),",
     "scene: a zero rotation axis is accepted (and gives NaN targets)", ()),
    ("penalty-target-translation-only", "src/physics/penalty_term.cpp",
     "    const Eigen::Vector3d d = placement.displacement(s.reference);",
     "    const Eigen::Vector3d d = placement.translation;",
     "physics: a turning dirichlet or clamp holds its points at the translation alone", ()),
    ("multiplier-target-translation-only", "src/physics/penalty_term.cpp",
     "  const Eigen::Vector3d d = placement.displacement(s.reference);\n  Eigen::Vector3d r",
     "  const Eigen::Vector3d d = placement.translation;\n  Eigen::Vector3d r",
     "physics: the augmented Lagrangian's multipliers and violation miss a turning target", ()),
    ("clamp-slope-not-turned", "src/physics/penalty_term.cpp",
     ": placement.turn(s.reference_conormal);", ": Eigen::Vector3d::Zero();",
     "physics: a turning subdivision clamp holds the boundary's slope at rest", ()),
    ("penalty-sample-reference-dropped", "src/simulation/effect_builder.cpp",
     "      p.reference = s.point.x;\n", "",
     "subdivision: a turning curve condition turns its samples as if they sat at the origin", ()),
    ("clamp-conormal-reversed", "src/simulation/effect_builder.cpp",
     "p.reference_conormal = s.conormal_direction;",
     "p.reference_conormal = -s.conormal_direction;",
     "subdivision: a turning clamp turns the slope across the boundary the wrong way", ()),
    ("triangle-clamp-sample-at-origin", "src/simulation/triangle_effect_builder.cpp",
     "      for (const auto& [v, w] : vertex_weights(disc, layout, vertices))\n"
     "        samples.push_back({{layout.local_of(v)}, {1.0}, {}, beta * w, 0.0, disc.points()[v]});",
     "      for (const auto& [v, w] : vertex_weights(disc, layout, vertices))\n"
     "        samples.push_back({{layout.local_of(v)}, {1.0}, {}, beta * w, 0.0});",
     "triangles: a turning clamp's vertices turn as if they sat at the origin", ()),
    ("multiplier-sign", "src/physics/penalty_term.cpp",
     "multipliers_[k] -= scale_ * samples_[k].weight", "multipliers_[k] += scale_ * samples_[k].weight",
     "triangles: the augmented-Lagrangian update pushes the wrong way", ()),
    ("quasistatic-one-solve", "src/simulation/time_stepper.cpp",
     "    if (energy_gradient <= solve.gradient_tolerance || limiting) {",
     "    if (true) {",
     "stepping: a quasistatic step ends after one proximal solve, out of equilibrium", ()),
    ("pnewton-no-psd", "solvers/step_solver.cpp",
     "PetscBool on = solver_type == \"pnewton\" ? PETSC_TRUE : PETSC_FALSE;",
     "PetscBool on = PETSC_FALSE;",
     "projected Newton without the PSD projection by default", ()),
    ("vpatch-point-blocks", "mesh/parallel_layout.cpp",
     "        if (w != v) members.insert(local_of_natural_[w]);  // local: the constructor sees to it",
     "        if (false) members.insert(local_of_natural_[w]);  // local: the constructor sees to it",
     "vertex patches shrink to their centre point (a 3x3 block Jacobi smoother)", ()),
    ("w-cycle-one-visit", "solvers/tao_rmtr.cpp",
     "const int visits = c.cycle_type == kWCycle && l - 1 > 0 ? 2 : 1;",
     "const int visits = 1;",
     "-tao_rmtr_cycle_type w runs V-cycles", ()),
    ("vpatch-partition-edge-patches", "mesh/parallel_layout.cpp",
     "          for (int w : disc.corners(f)) local[w] = 1;",
     "          for (int w : disc.corners(f)) (void)w;",
     "the patches of ghost-ring points at the partition's edge lose the corners no local element "
     "reaches (PC vpatch differs between 1 and 2 ranks)", ()),
    ("vpatch-scalar-rows-dropped", "solvers/vertex_patch_pc.cpp",
     "    if (!blocked)\n      for (int c = 0; c < 3; ++c) add_row(rows, 3 * r + c, 3 * a + c);",
     "    if (false)\n      for (int c = 0; c < 3; ++c) add_row(rows, 3 * r + c, 3 * a + c);",
     "vertex patches drop the rows that do not store full 3x3 blocks", ()),
    ("vpatch-block-transposed", "solvers/vertex_patch_pc.cpp",
     "D(3 * a + c, 3 * b + d) = rows.values[ia[c] + e + d];",
     "D(3 * a + d, 3 * b + c) = rows.values[ia[c] + e + d];",
     "vertex patches read each 3x3 block transposed", ()),
    ("vpatch-patch-columns", "solvers/vertex_patch_pc.cpp",
     "if (b >= 0) D(a, 3 * b + dof % 3) = rows.values[e];",
     "if (b >= 0) D(a, 3 * b + a % 3) = rows.values[e];",
     "the patch matrices keep only the diagonal of every 3x3 block", ()),
    ("vpatch-no-off-diagonal-part", "solvers/vertex_patch_pc.cpp",
     "      if (p.off_diagonal.mat) add_block_row(p.off_diagonal, r, a);\n", "",
     "patches next to another rank's points miss their coupling to them (wrong on 2 ranks only)",
     ()),
    ("vpatch-half-product", "solvers/vertex_patch_pc.cpp",
     "    zm.head(i + 1) += Mi.dot(rm.head(i + 1)) * Mi;",
     "    zm[i] += Mi.dot(rm.head(i + 1)) * Mi[i];",
     "the patch solve applies only the diagonal of L^-T", ()),
    ("fmg-start-discarded", "solvers/tao_rmtr.cpp",
     "  PetscCall(\n      keep_lower(*top.objective, top.trial, f_fine, tao->solution, moved, f_moved, "
     "top.correction));\n",
     "",
     "the full-multigrid start solves the coarse levels and then starts from the given iterate",
     ()),
    ("fmg-unprolongated-levels", "solvers/tao_rmtr.cpp",
     "      PetscCall(keep_lower(f, lv.trial, std::isfinite(f0) ? f0 : PETSC_INFINITY, lv.x0, &taken, "
     "&fp,\n                           lv.restricted));\n",
     "",
     "the full-multigrid start solves each level from the projected start, not the coarser solution",
     ()),
    ("fmg-one-cycle-per-level", "solvers/tao_rmtr.cpp",
     "  while (*cycles < c.fmg_cycles && ", "  while (*cycles < 1 && ",
     "the full-multigrid start stops each level after one V-cycle instead of solving it", ()),
    ("fmg-from-any-iterate", "solvers/tao_rmtr.cpp",
     "(c->fmg_always || x_max == 0.0)", "(c->fmg_always || x_max >= 0.0)",
     "the full-multigrid start runs before every solve, also from a previous step's state", ()),
    ("mumps-workspace-shift", "solvers/trust_region_qp.cpp",
     "|| attempt == 6) break;", "|| attempt >= 0) break;",
     "Dogleg shifts H when MUMPS runs out of workspace instead of giving it more", ()),
    ("mumps-factor-unprefixed", "solvers/trust_region_qp.cpp",
     "      PetscCall(MatSetOptionsPrefix(F, prefix));\n", "",
     "the factor reads no options under the solver's prefix (-rmtr_levels_2_mat_mumps_...)", ()),
    ("hessian-only-at-start", "solvers/local_trust_region.cpp",
     "  if (force || kept_ >= hessian_lag_)\n    hessian_due_ = true;",
     "  if (force)\n    hessian_due_ = true;",
     "Local_TR keeps the first Hessian for the whole solve (an accepted step never marks it due)",
     ()),
    ("csr-assembly-transposed-block", "mesh/element_matrix_assembly.cpp",
     "      dst[1] += s[1];\n      dst[2] += s[2];",
     "      dst[1] += s[2];\n      dst[2] += s[1];",
     "element matrices enter the CSR arrays with two columns of each block swapped", ()),
    ("csr-assembly-search-off-by-one", "mesh/element_matrix_assembly.cpp",
     "base = row[stride * (base + half)] <= column ? base + half : base;",
     "base = row[stride * (base + half)] < column ? base + half : base;",
     "the block search lands one block before the column it looks for", ()),
    ("report-gradient-dropped", "src/physics/level_problem.cpp",
     "  PetscCall(layout_.add_to_global(g_local_, g));\n  PetscCall(add_nonlocal_gradients(g, nullptr));\n"
     "  PetscCall(VecNorm(g, NORM_2, gnorm));",
     "  PetscCall(VecNorm(g, NORM_2, gnorm));",
     "the reported gradient norm (summary.json, -mlshell_evaluate) is that of a zero vector", ()),
    ("csr-prefill-column-split", "mesh/element_matrix_assembly.cpp",
     "  const auto owned = [&](PetscInt b) { return b >= first_owned && b < first_owned + num_owned; };",
     "  const auto owned = [&](PetscInt b) { return b >= first_owned && b <= first_owned + num_owned; };",
     "the next rank's first block column lands in the diagonal part (wrong on 2 ranks only)", ()),
    ("mass-on-first-column", "mesh/element_matrix_assembly.cpp",
     "        PetscScalar* row = a + ia[3 * r + c] + c;",
     "        PetscScalar* row = a + ia[3 * r + c];",
     "M ⊗ I₃ lands in each block's first column instead of its diagonal", ()),
    ("mass-without-off-diagonal-part", "mesh/element_matrix_assembly.cpp",
     "  for (int p = 0; p < 2; ++p) {\n    if (!a_parts[p]) continue;",
     "  for (int p = 0; p < 1; ++p) {\n    if (!a_parts[p]) continue;",
     "the mass couplings to other ranks' points are dropped (wrong on 2 ranks only)", ()),
    ("csr-assembly-drops-other-ranks-rows", "mesh/element_matrix_assembly.cpp",
     "      PetscCall(add_ghost_row(A, *bc, n, nodes, i, rows, width));\n",
     "",
     "element rows owned by another rank are dropped (wrong on 2 ranks only)", ()),
    ("huge-pages-never-asked", "src/cli/main.cpp",
     "  execv(\"/proc/self/exe\", argv);\n", "",
     "mlshell never restarts itself with glibc's malloc on transparent huge pages", ()),
    ("ghost-rows-sent-twice", "mesh/element_matrix_assembly.cpp",
     "  std::fill(g.values.begin(), g.values.end(), 0.0);\n  PartArrays csr;",
     "  PartArrays csr;",
     "the ghost rows' blocks are not zeroed once sent: every later assembly adds them again "
     "(wrong on 2 ranks only)", ()),
    ("ghost-block-in-next-slot", "mesh/element_matrix_assembly.cpp",
     "g.slot_part[s] = p, g.slot_row[s] = r, g.slot_block[s] = position;",
     "g.slot_part[s] = p, g.slot_row[s] = r, g.slot_block[s] = position + (position + 1 < 3);",
     "a block another rank sends lands one block to the right in some rows (wrong on 2 ranks "
     "only)", ()),
    ("ghost-fallback-dropped", "mesh/element_matrix_assembly.cpp",
     "    PetscCall(MatSetValuesBlockedLocal(A, 1, &nodes[i], 1, &nodes[j], block, ADD_VALUES));\n",
     "",
     "a ghost-row block outside the ghost rows' pattern is dropped instead of going through "
     "PETSc's stash (wrong on 2 ranks only)", ()),
    ("midedge-free-edge", "src/physics/triangle/midedge_bending.cpp",
     "if (nf > 0 && nw > 0) Kww -= Kwf * Kff.llt().solve(Kwf.transpose());",
     "if (false) Kww -= Kwf * Kff.llt().solve(Kwf.transpose());",
     "midedge bending: a free edge's tilt is held at zero instead of eliminated", ()),
    ("midedge-clamp-half-angle", "src/physics/triangle/midedge_bending.cpp",
     "scale[i] = (wings[i] == EdgeWing::kClamp ? 1.0 : 0.5) * height;",
     "scale[i] = 0.5 * height;",
     "midedge bending: a clamped edge's normal turns by half the angle to the clamp", ()),
    ("radius-skips-boundary-steps", "solvers/local_trust_region.cpp",
     "      while (shrunk >= used * delta) shrunk *= gamma1;",
     "      while (shrunk >= 0.5 * used * delta) shrunk *= gamma1;",
     "a rejection shrinks the radius a step further than the radii that would repeat the step",
     ()),
    ("dogleg-newton-radius-needed", "solvers/trust_region_qp.cpp",
     "        result.radius_needed = std::max(result.radius_needed, pnorm);",
     "        result.radius_needed = result.radius_needed;",
     "Dogleg reports the Cauchy point's length as the radius an interior Newton step needs", ()),
    ("dogleg-shift-from-last", "solvers/trust_region_qp.cpp",
     "last_shift_ > 0 ? last_shift_ / 10 : 1e-10 * norm",
     "last_shift_ > 0 ? last_shift_ : 1e-10 * norm",
     "the shift search starts at the last shift, so it never comes down", ()),
    ("unused-options-silent", "src/cli/main.cpp",
     '    std::cerr << "mlshell: warning: " << mlshell::describe(o) << std::endl;\n', "",
     "a misspelt option (-tao_rmtr_smoothr_qp) goes unreported after the run", ()),
    ("default-check-reads-option", "solvers/step_solver.cpp",
     "    PetscCall(option_given(option, &set));",
     "    PetscCall(PetscOptionsHasName(nullptr, nullptr, option.c_str(), &set));",
     "an options file's key that the chosen solver ignores counts as read once mlshell checked "
     "it for its default (-tao_rmtr_smoother_qp under -tao_type tr)", ()),
    ("output-folder-raw-error", "src/simulation/simulation.cpp",
     "  create_output_folder(comm, output_->dir);",
     "  if (rank_ == 0) std::filesystem::create_directories(output_->dir);",
     "an output folder that cannot be created exits 2 with a raw filesystem error, not 4", ()),
    ("energy-floor-never-crossed", "solvers/step_solver.cpp",
     "  crossed = crossed || f < start - bound();", "  crossed = false;",
     "a solve whose energy falls without bound runs to -tao_max_it (E = -4e101 J) instead of "
     "stopping as DIVERGED_ENERGY_UNBOUNDED", ()),
    ("energy-floor-tao-test-dropped", "solvers/step_solver.cpp",
     "  PetscCallAbort(comm, TaoSetConvergenceTest(tao_, floor_then_default_test, &floor_));\n",
     "",
     "TAO solvers never see the energy floor (only SNES and bnls's line-search error stop)", ()),
    ("shell-jacobian-normal-turn-dropped", "mesh/prolongation/shell_prolongation.cpp",
     "const Eigen::Matrix3d da = a_direct[j] + K * dn;",
     "const Eigen::Matrix3d da = a_direct[j];",
     "the shell prolongation's Jacobian misses the in-plane offset's turn with the normal "
     "(J_P no longer the derivative of P)", ()),
    ("shell-tangent-frame-flipped", "mesh/prolongation/shell_prolongation.cpp",
     "normal.cross(edge).dot(d)", "edge.cross(normal).dot(d)",
     "the rest offsets t are written in a frame whose second axis is turned over: P(x̄_c) no "
     "longer recovers the fine rest shape", ()),
    ("shell-restriction-inserts", "mesh/prolongation/triangle_transfer.cpp",
     "  PetscCall(VecScatterBegin(gather_, gathered_, coarse_gradient, ADD_VALUES, SCATTER_REVERSE));\n"
     "  PetscCall(VecScatterEnd(gather_, gathered_, coarse_gradient, ADD_VALUES, SCATTER_REVERSE));",
     "  PetscCall(VecScatterBegin(gather_, gathered_, coarse_gradient, INSERT_VALUES, SCATTER_REVERSE));\n"
     "  PetscCall(VecScatterEnd(gather_, gathered_, coarse_gradient, INSERT_VALUES, SCATTER_REVERSE));",
     "the shell transfer's restriction keeps one rank's share of a coarse vertex's gradient "
     "(J_Pᵀ g wrong on 2 ranks: mpi.two_ranks)", ()),
    ("decimation-boundary-not-straight", "mesh/decimation/decimation.cpp",
     "      if (t <= 0.0 || t >= 1.0 || (ap - t * ac).norm() > tolerance * std::sqrt(length2))",
     "      if (false)",
     "decimation removes boundary vertices however far the new edge is from the fine boundary: "
     "corners go, a dome's rim is cut",
     ()),
    ("decimation-group-vertex-moves", "mesh/decimation/decimation.cpp",
     "  if (g0 != 0) return Keep::kV0;\n", "",
     "an interior group vertex at an edge's first end moves to the quadric's placement or goes",
     ()),
    ("decimation-slivers-allowed", "mesh/decimation/decimation.cpp",
     "      if (min_angle(after[0], after[1], after[2]) < bound) return boost::none;\n", "",
     "decimation makes triangles with angles below min_angle_degrees", ()),
    ("embedding-kept-never-moves", "mesh/decimation/intrinsic_embedding.cpp",
     "    position[record.kept] = record.placement;\n", "",
     "the intrinsic embedding flattens each collapse's one-ring with kept vertices where the fine "
     "mesh had them, not where earlier collapses placed them", ()),
    ("embedding-moved-kept-vertex-not-anchored", "mesh/decimation/intrinsic_embedding.cpp",
     "      if (v == record.kept && record.placement == record.kept_from) continue;",
     "      if (v == record.kept) continue;",
     "a vertex moved by its collapse's placement rides on itself (weight 1) instead of being "
     "anchored where it was: P is not U on flat meshes", ()),
    ("decimation-boundary-deviation-tenfold", "mesh/decimation/decimation.cpp",
     "      if (t <= 0.0 || t >= 1.0 || (ap - t * ac).norm() > tolerance * std::sqrt(length2))",
     "      if (t <= 0.0 || t >= 1.0 || (ap - t * ac).norm() > 10 * tolerance * std::sqrt(length2))",
     "curved boundaries coarsen ten times farther from the fine boundary than boundary_deviation "
     "allows", ()),
    ("triangle-galerkin-pairs-dropped", "mesh/triangle/triangle_levels.cpp",
     "          galerkin_pairs_[l].push_back({a, b});", "          continue;",
     "coarse triangle levels lack the pattern of J_Pᵀ H J_P: Galerkin coarse models fail to "
     "assemble", ()),
    ("triangle-owners-tie-to-higher-rank", "mesh/triangle/triangle_levels.cpp",
     "    owner[t] = static_cast<int>(std::max_element(first, first + num_ranks) - first);",
     "    owner[t] = num_ranks - 1 - static_cast<int>(std::max_element(std::make_reverse_iterator("
     "first + num_ranks), std::make_reverse_iterator(first)) - std::make_reverse_iterator(first + "
     "num_ranks));",
     "a coarse triangle whose vertices' owners tie goes to the higher rank", ()),
    ("rmtr-coarse-step-not-pulled-into-radius", "solvers/tao_rmtr.cpp",
     "      if (step_norm > *delta)\n        PetscCall(pull_into_radius(",
     "      if (false)\n        PetscCall(pull_into_radius(",
     "a shell prolongation that stretches a coarse step beyond the fine radius is tried as it is "
     "(eq. 4.7 broken on triangle levels)", ()),
    ("proxy-gradient-not-restricted", "src/physics/proxy_energy.cpp",
     "    PetscCall(direct_.restrict_gradient(u, fine_g_, g));",
     "    PetscCall(direct_.project(fine_g_, g));",
     "the proxy energy's gradient takes the fine gradient at the surviving vertices instead of "
     "J_P(x)ᵀ∇Ψ", ()),
    ("proxy-frozen-gradient-exact", "src/physics/proxy_energy.cpp",
     "  if (gradient_ == Gradient::kFrozenOffset && shell)",
     "  if (false && shell)",
     "the frozen-offset gradient (paper 2 eq. 10) is the exact one", ()),
    ("intrinsic-restriction-weights-dropped", "mesh/prolongation/triangle_transfer.cpp",
     "        for (int k = 0; k < 3; ++k) r.segment<3>(3 * k) = w[k] * g;",
     "        for (int k = 0; k < 3; ++k) r.segment<3>(3 * k) = g / 3.0;",
     "Uᵀg spreads each fine gradient evenly over its triangle's corners", ()),
    ("contact-halo-dropped", "src/contact/contact_term.cpp",
     "  if (size > 1) {\n    std::vector<double> boxes(6 * size);",
     "  if (false) {\n    std::vector<double> boxes(6 * size);",
     "no rank receives the other ranks' surface: pairs across ranks are lost", ()),
    ("contact-pairs-owned-twice", "src/contact/contact_term.cpp",
     "    if (shell_v ? !mine_point(v) : layout_.face_owner(f) != rank) continue;\n", "",
     "a point–triangle pair is evaluated by every rank that knows it", ()),
    ("contact-remote-gradient-dropped", "src/contact/contact_term.cpp",
     "  if (!remote_rows_.empty())", "  if (false)",
     "the gradient at another rank's vertices is dropped", ()),
    ("contact-ccd-ignored", "src/contact/contact_term.cpp",
     "    if (r.may_collide) alpha = std::min(alpha, r.toi);", "",
     "max_step never limits a step: solvers may step through a collider", ("cli.contact",)),
    ("contact-push-dropped", "src/contact/contact_term.cpp",
     "    if (!r.may_collide) continue;\n", "    continue;\n",
     "carry pushes no shell vertex ahead of a moving collider", ("cli.contact",)),
    ("contact-obstacle-move-unswept", "src/contact/contact_term.cpp",
     "      if (swept_ && !obstacle_dx_.empty()) d = obstacle_dx_[v - num_shell_points_];\n", "",
     "CCD ignores a moving collider's own motion: it may jump into the shell", ()),
    ("collider-arrival-unreported", "src/simulation/time_stepper.cpp",
     '    total.reason = !arrived                   ? "DIVERGED_COLLIDER_MOTION"',
     '    total.reason = false                      ? "DIVERGED_COLLIDER_MOTION"',
     "a step whose collider cannot arrive is reported as out of proximal solves",
     ("cli.contact",)),
    ("collider-move-unchecked", "src/contact/collider_motion.cpp",
     "    if (alpha >= 1.0) {", "    if (alpha > 0.0) {",
     "a collider takes its whole move even where CCD cut it short", ()),
    ("contact-pattern-kept", "src/contact/contact_term.cpp",
     "  ++version_, ++rebuilds_;", "  ++rebuilds_;",
     "the Hessian's pattern never follows the contact pairs", ()),
    ("contact-stiffness-ipc-cap", "src/contact/contact_term.cpp",
     "    kappa_max_ = std::max(100.0 * kappa_, settings_.max_vertex_force / holding);",
     "    kappa_max_ = 100.0 * kappa_;",
     "adaptive κ stops at IPC's 100 κ₀ although the shell's own tension presses harder", ()),
    ("psd-stencil-assumes-translation-free", "src/physics/psd_projection.cpp",
     "    if (moved > 1e-8 * K * scale) {", "    if (false) {",
     "a stencil Hessian that translations move is projected as if they were in its null space", ()),
    ("psd-stencil-helmert-suffix", "src/physics/psd_projection.cpp",
     "        suffix += helmert(p) * V.row(3 * (p - 1) + c);",
     "        suffix += V.row(3 * (p - 1) + c);",
     "the eigenvectors come back from the reduced motions with a wrong weight", ()),
    ("bodies-self-within-only", "src/contact/contact_term.cpp",
     "    return a != b || settings_.self_contact_of_body[a] != 0;",
     "    return settings_.self_contact_of_body[a] != 0;",
     "pairs between two bodies are dropped when self-contact is off", ()),
    ("bodies-one-material", "src/physics/triangle/triangle_elastic_term.cpp",
     "  const MembraneParameters& lame = lame_[m.body];",
     "  const MembraneParameters& lame = lame_[0];",
     "every body's membrane takes the first body's material", ()),
    ("contact-self-always", "src/contact/contact_term.cpp",
     "    if (shell_v && shell_f && !counts(v, surface_.faces[f][0])) continue;\n", "",
     "`self: false` still counts the shell's point–triangle pairs with itself", ()),
    ("contact-snes-precheck-dropped", "solvers/step_solver.cpp",
     "    PetscCallAbort(comm,\n                   SNESLineSearchSetPreCheck(line_search, admissible_direction, &problem_));",
     "",
     "SNES newtonls's steps are not cut to CCD: the strip tunnels through the sphere",
     ("cli.contact",)),
    ("pnewton-stale-after-accepted", "solvers/tao_projected_newton.cpp",
     "    if (f_obj.revision() != revision) PetscCall(f_obj.objective(x, &f, g));  // contact's κ\n",
     "", "projected Newton keeps f and ∇f of an iterate whose objective accepted() changed", ()),
    ("tr-stale-after-accepted", "solvers/local_trust_region.cpp",
     "  if (f_.revision() != revision) PetscCall(f_.objective(x_, &fx_, g_));  // contact's κ\n",
     "", "the trust region keeps f and ∇f of an iterate whose objective accepted() changed", ()),
    ("contact-any-solver", "src/simulation/contact_run.cpp",
     '  if (type == "pnewton" || type == "tr") return;', "  return;",
     "a contact scene runs with a solver that ignores CCD's step limit", ()),
    ("proxy-step-no-step-norm-stop", "src/simulation/proxy_step.cpp",
     "    if (dnorm < settings.tolerance) {", "    if (false) {",
     "a proxy step never stops on a short Newton step (Alg. 1 line 10): no level is ever in "
     "equilibrium", ("cli.progressive",)),
    ("proxy-step-no-armijo", "src/simulation/proxy_step.cpp",
     "      if (std::isfinite(trial_f) && trial_f <= f + kArmijo * alpha * slope) break;",
     "      if (std::isfinite(trial_f)) break;",
     "the proxy step's line search accepts any finite trial point", ()),
    ("proxy-step-ascent-accepted", "src/simulation/proxy_step.cpp",
     "    if (reason < 0 || !std::isfinite(dnorm) || (dnorm > 0 && !(slope < 0))) {",
     "    if (reason < 0 || !std::isfinite(dnorm)) {",
     "a Newton matrix that is not positive definite gives an ascent direction the proxy step "
     "takes", ()),
    ("progressive-levels-load-again", "src/simulation/progressive_run.cpp",
     "    const double t = (l == 0 ? std::min(k, T) : T) * dt;",
     "    const double t = std::min(k, T) * dt;",
     "every progressive level runs the loading again from the start instead of the final load",
     ("cli.progressive",)),
    ("progressive-interrupt-ignored", "src/simulation/progressive_run.cpp",
     "    *interrupted = InterruptScope::any(comm_);", "    *interrupted = false;",
     "SIGINT does not end a progressive run", ("cli.progressive",)),
    ("audit-self-pairs-not-counted", "src/contact/audit/intersection_audit.cpp",
     "  for (const auto& [a, b] : intersecting(mesh)) {\n    ++report.pairs;",
     "  for (const auto& [a, b] : intersecting(mesh)) {",
     "the intersection audit reports no intersecting pairs within a surface", ()),
    ("audit-input-not-refused", "src/simulation/simulation.cpp",
     "    if (pairs > 0)\n      throw SceneError(scene_.file.string() + \": geometry.mesh: the \" +",
     "    if (false)\n      throw SceneError(scene_.file.string() + \": geometry.mesh: the \" +",
     "an input surface that intersects itself is simulated", ()),
    ("audit-frame-not-stopping", "src/simulation/simulation.cpp",
     "    if (!audit_message_.empty()) {  // write_frame's audit found intersecting triangles",
     "    if (false) {  // write_frame's audit found intersecting triangles",
     "a run goes on past a written frame whose triangles intersect", ()),
    ("collapse-chart-fold-unchecked", "mesh/decimation/collapse_chart.cpp",
     "  bool ok = place_kept_lscm() && after_valid();", "  bool ok = place_kept_lscm();",
     "a collapse whose LSCM after chart folds keeps it (points snapped across the fold, no "
     "kernel or Tutte chart, fallback_charts 0)", ()),
    ("contact-plane-hessian-term-dropped", "src/contact/distance/vector_products.cpp",
     "hN = 2.0 * gf * gf.transpose() + 2.0 * f * hf;", "hN = 2.0 * gf * gf.transpose();",
     "the point–plane and line–line Hessians lose the f ∇²f term of ∇²(f²) (Gauss–Newton only)",
     ()),
    ("contact-mollifier-hessian-term-dropped", "src/contact/distance/edge_edge_mollifier.cpp",
     "*hess = d2m * gc * gc.transpose() + dm * hc;", "*hess = d2m * gc * gc.transpose();",
     "the edge–edge mollifier's Hessian loses m'(c) ∇²c", ()),
    ("contact-edge-edge-parallel-unguarded", "src/contact/distance/edge_edge.cpp",
     "if (D > kEdgeEdgeParallelThreshold * uu * vv) {", "if (D > 0.0) {",
     "nearly parallel edges (sin²θ ≤ 1e-10) take the line–line type, whose closest-point "
     "parameters and f²/g lose their digits: a distance off the segments' true one", ()),
    ("contact-ccd-lp-one-primitive", "src/contact/ccd/additive_ccd.cpp",
     "const double lp = max_a + max_b;", "const double lp = max_b;",
     "additive CCD bounds the closing speed by one primitive's motion only: its steps overshoot "
     "when the point or the first edge moves (false negatives)", ()),
    ("contact-ccd-cap-reports-safe", "src/contact/ccd/additive_ccd.cpp",
     "  result.may_collide = true;  // capped", "  result.may_collide = false;  // capped",
     "additive CCD at its iteration cap reports no collision instead of the time proven safe",
     ()),
    ("contact-broad-phase-boxes-not-swept", "src/contact/broad_phase/primitive_boxes.cpp",
     "lo = std::min({lo, x0[i][k], x1[i][k]});", "lo = std::min({lo, x0[i][k]});",
     "the swept boxes miss the end positions' lower bounds: CCD candidates lost", ()),
    ("contact-spatial-hash-pairs-repeated", "src/contact/broad_phase/spatial_hash.cpp",
     "            grid.key_of_point(intersection_corner(a, b)) == cell)\n          out.edge_edge",
     "            true)\n          out.edge_edge",
     "the spatial hash reports an edge pair from every cell the two boxes share (duplicates)",
     ()),
]


def run(cmd, **kw):
    return subprocess.run(cmd, cwd=kw.pop("cwd", SOURCE), stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, **kw)


def failed_tests(build):
    log = build / "Testing" / "Temporary" / "LastTestsFailed.log"
    if not log.is_file():
        return []
    return [line.split(":", 1)[1].strip() for line in log.read_text().splitlines() if ":" in line]


def check(build, name, path, old, new, what, also):
    file = SOURCE / path
    text = file.read_text()
    if text.count(old) != 1:
        return what, f"NOT APPLIED: the text occurs {text.count(old)} times in {path}", 0.0
    start = time.monotonic()
    try:
        file.write_text(text.replace(old, new))
        b = run(["cmake", "--build", str(build), "-j2"])
        if b.returncode != 0:
            return what, "build failed (caught by the compiler)", time.monotonic() - start
        (build / "Testing" / "Temporary" / "LastTestsFailed.log").unlink(missing_ok=True)
        exclude = "|".join(re.escape(t) for t in LONG if t not in also)
        env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OPENBLAS_NUM_THREADS="1")
        run(["ctest", "-j2", "-E", f"^({exclude})$"], cwd=build, env=env)
        failed = failed_tests(build)
        shown = ", ".join(failed[:6]) + (f", … ({len(failed)} in all)" if len(failed) > 6 else "")
        caught = shown if failed else "**NOT CAUGHT**"
        return what, caught, time.monotonic() - start
    finally:
        file.write_text(text)


def stale():
    """The mutations whose text does not occur exactly once in their file, with the count."""
    names = [m[0] for m in MUTATIONS]
    out = [f"{n}: the name is used {names.count(n)} times" for n in sorted(set(names))
           if names.count(n) > 1]
    for name, path, old, *_ in MUTATIONS:
        file = SOURCE / path
        count = file.read_text().count(old) if file.is_file() else 0
        if count != 1:
            out.append(f"{name}: its text occurs {count} times in {path}")
    return out


def main(argv):
    if len(argv) == 2 and argv[1] == "--check":
        problems = stale()
        print("\n".join(problems) or f"all {len(MUTATIONS)} mutations apply")
        sys.exit(1 if problems else 0)
    if len(argv) < 2:
        sys.exit(__doc__.strip().splitlines()[-4])
    build = Path(argv[1]).resolve()
    chosen = [m for m in MUTATIONS if len(argv) == 2 or m[0] in argv[2:]]
    rows = ["| mutation | what it breaks | tests that failed | s |", "|---|---|---|---|"]
    missed = 0
    for name, path, old, new, what, also in chosen:
        print(f"mutation {name}: {what} ...", flush=True)
        what, caught, seconds = check(build, name, path, old, new, what, also)
        missed += caught.startswith(("**NOT", "NOT"))
        rows.append(f"| {name} | {what} | {caught} | {seconds:.0f} |")
        print(f"  -> {caught}", flush=True)
    run(["cmake", "--build", str(build), "-j2"])  # the unmutated build again
    table = "\n".join(rows) + "\n"
    (build / "mutations.md").write_text(table)
    print(table)
    sys.exit(1 if missed else 0)


if __name__ == "__main__":
    main(sys.argv)
