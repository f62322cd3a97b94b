#!/usr/bin/python3
"""Unit tests of the study tools that need no solver: the L2 distance of two sampled limit
surfaces, the Pareto front, the -log_view parser, and REPORT.md built from known CSV rows."""
import csv
import json
import math
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "examples" / "studies"))

import report  # noqa: E402
import studies  # noqa: E402
from context import Context, read_csv  # noqa: E402
from solvers import SOLVERS  # noqa: E402
from plots import pareto_front  # noqa: E402
from runner import parse_log_view, solver_fields  # noqa: E402
from study_accuracy import l2_distance  # noqa: E402
from study_scaling import too_big  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from quick_outputs import failed_runs, report_problems  # noqa: E402

RESULTS = Path(__file__).resolve().parents[2] / "examples" / "studies" / "results"


def unit_square_elements(n, displacement):
    """Rows (point, displacement) of an n×n grid of elements on [0,1]², four corners each."""
    rows = []
    for j in range(n):
        for i in range(n):
            for dj in (0, 1):
                for di in (0, 1):
                    p = ((i + di) / n, (j + dj) / n, 0.0)
                    rows.append((p, displacement(p)))
    return rows


class ScalingMemoryGuard(unittest.TestCase):
    def test_factorising_solvers_are_not_started_beyond_the_memory(self):
        # TR peaked at 3,621 MiB per rank at 201,243 dofs: 6× on 2 ranks is 42 GiB.
        why = too_big("tr", "3621", 2, 22000.0)
        self.assertIsNotNone(why)
        self.assertIn("predicted 42 GiB on 2 ranks > 18 GiB, 85% of the 21 GiB available", why)
        # bnls peaked at 2,585 MiB at 201,243 dofs: 4.5× on 2 ranks is 22.7 GiB, within the
        # 23 GiB available but not within the headroom.
        self.assertIsNotNone(too_big("bnls-mumps", "2585", 2, 23500.0))
        # The patch smoother (2,076 MiB, grows ~4×) fits; so does anything with no history.
        self.assertIsNone(too_big("rmtr-patch", "2076", 2, 22000.0))
        self.assertIsNone(too_big("tr", "", 2, 22000.0))
        self.assertIsNone(too_big("tr", "3621", 2, None))


class L2Distance(unittest.TestCase):
    def test_constant_difference_times_root_area(self):
        ref = unit_square_elements(4, lambda p: (0.0, 0.0, 0.0))
        coarse = unit_square_elements(2, lambda p: (0.0, 0.0, 0.3))
        # Coarse samples at the reference's corners: 2 samples per coarse element edge.
        coarse += [(p, (0.0, 0.0, 0.3)) for p, _ in ref]
        self.assertAlmostEqual(l2_distance(coarse, ref), 0.3, places=12)

    def test_linear_field_is_integrated_exactly(self):
        # ∫∫ x² over the unit square = 1/3; the trapezoidal rule on 8×8 elements: 1/3 + 1/384.
        ref = unit_square_elements(8, lambda p: (0.0, 0.0, 0.0))
        coarse = [(p, (p[0], 0.0, 0.0)) for p, _ in ref]
        self.assertAlmostEqual(l2_distance(coarse, ref) ** 2, 1 / 3 + 1 / 384, places=12)

    def test_missing_point_is_an_error(self):
        ref = unit_square_elements(2, lambda p: (0.0, 0.0, 0.0))
        with self.assertRaises(RuntimeError):
            l2_distance(ref[:-1], ref + [((0.1, 0.1, 0.0), (0.0, 0.0, 0.0))] * 4)


class ParetoFront(unittest.TestCase):
    def test_keeps_only_undominated_points(self):
        pts = [(1.0, 1e-2), (2.0, 1e-3), (3.0, 5e-3), (4.0, 1e-4), (0.5, 1e-1)]
        self.assertEqual(pareto_front(pts), [(0.5, 1e-1), (1.0, 1e-2), (2.0, 1e-3), (4.0, 1e-4)])


LOG_VIEW = """
Summary of Stages:   ----- Time ------  ----- Flop ------  --- Messages ---  -- Message Lengths --  -- Reductions --
                        Avg     %Total     Avg     %Total    Count   %Total     Avg         %Total    Count   %Total
 0:      Main Stage: 1.0000e-02   1.0%  0.0000e+00   0.0%  0.000e+00   0.0%  0.000e+00        0.0%  0.000e+00   0.0%
 1:           Setup: 2.5000e-01  25.0%  0.0000e+00   0.0%  0.000e+00   0.0%  0.000e+00        0.0%  0.000e+00   0.0%
 2:           Solve: 7.0000e-01  70.0%  1.0000e+06 100.0%  0.000e+00   0.0%  0.000e+00        0.0%  0.000e+00   0.0%
 3:          Output: 4.0000e-02   4.0%  0.0000e+00   0.0%  0.000e+00   0.0%  0.000e+00        0.0%  0.000e+00   0.0%

------------------------------------------------------------------------------------------------------------------------
Event                Count      Time (sec)     Flop                              --- Global ---  --- Stage ----  Total
--- Event Stage 2: Solve

MatMult               10 1.0 1.5000e-02 1.1 2.00e+05 1.0 0.0e+00 0.0e+00 0.0e+00  2 20  0  0  0   2 20  0  0  0    13
MatCholFctrNum         3 1.0 3.0000e-01 1.0 0.00e+00 0.0 0.0e+00 0.0e+00 0.0e+00 30  0  0  0  0  43  0  0  0  0     0
"""


class LogView(unittest.TestCase):
    def test_stages_and_events(self):
        log = parse_log_view(LOG_VIEW)
        self.assertEqual(log["stages"], {"Main Stage": 0.01, "Setup": 0.25, "Solve": 0.7,
                                         "Output": 0.04})
        self.assertEqual(log["events"]["Solve"], {"MatMult": 0.015, "MatCholFctrNum": 0.3})


def write(folder, name, rows):
    columns = studies.STUDIES[name].COLUMNS if name in studies.STUDIES else list(rows[0])
    with open(folder / f"{name}.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        for r in rows:
            w.writerow({c: r.get(c, "") for c in columns})


def section(text, heading):
    """The `## heading` section of a report, up to the next `## ` heading."""
    return text.split(f"\n## {heading}\n", 1)[1].split("\n## ", 1)[0]


def headline_groups(text):
    """The headline's groups as (title, compares, header, rows): each a `### ` title, the
    sentence that says what it compares, and its table."""
    groups = []
    for block in section(text, "Headline").split("\n### ")[1:]:
        title, rest = block.split("\n", 1)
        paragraphs = [p for p in rest.strip().split("\n\n") if p]
        lines = [line for line in paragraphs[1].splitlines()]
        cells = [[c.strip() for c in line.strip("|").split("|")] for line in lines]
        groups.append((title, paragraphs[0], cells[0], cells[2:]))
    return groups


def run_row(scene, dofs, iterations, converged=1, **extra):
    return {"scene": scene, "dofs": dofs, "iterations": iterations, "converged": converged,
            "reason": "CONVERGED_GATOL" if converged else "DIVERGED_TR_REDUCTION",
            "gradient_norm": 1e-8 if converged else 0.5, "ranks": 2, **extra}


class ReportFromKnownRows(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.out = Path(self.dir.name)

    def tearDown(self):
        self.dir.cleanup()

    def build(self):
        return report.Report(self.out).write().read_text()

    def test_vcycles_side_by_side_and_goal(self):
        write(self.out, "iterations", [
            run_row("trampoline", 363, 12, solver="rmtr", levels=2, refine=1),
            run_row("drooping", 363, 46, 0, solver="rmtr", levels=2, refine=1),
            run_row("trampoline", 147, 7, solver="tr", levels=1, refine=0)])
        text = self.build()
        self.assertIn("12 / 633", text)          # Table 4, trampoline, 2 levels
        self.assertIn("7 / 1,385", text)         # Table 3, trampoline, 147 dofs
        self.assertIn("stopped: tr_reduction", text)
        self.assertIn("| 1 of 2 cells | **not met** |", text)

    def test_presets_side_by_side_with_their_elastic_energy(self):
        write(self.out, "iterations", [
            run_row("drooping", 363, 93, solver="rmtr", levels=2, refine=1, preset="denim",
                    energy_elastic=0.0485),
            run_row("drooping", 363, 172, solver="rmtr", levels=2, refine=1,
                    preset="denim-table1", energy_elastic=-10.66),
            {**run_row("drooping", "", "", 0, solver="rmtr", levels=3, refine=2,
                       preset="denim-table1"), "reason": "not run (finer than studied)"}])
        text = self.build()
        self.assertIn("| drooping | 93 / 4,671 |", text)  # Table 4 shows the default preset
        self.assertNotIn("172 / 4,671", text)
        self.assertIn("| drooping | rmtr | 2 | 363 | denim-table1 | 172 | -10.66 |", text)
        self.assertIn("| drooping | rmtr | 2 | 363 | denim | 93 | 0.0485 |", text)
        self.assertNotIn("| 3 |  | denim-table1", text)  # rows not run are left out

    def test_peer_ratios_speedup_and_goals_at_51483(self):
        write(self.out, "peers", [
            run_row("trampoline", 51483, 5, solver="rmtr", wall_time=10.0, linear_iterations=5),
            run_row("trampoline", 51483, 20, solver="bntr-gamg", wall_time=40.0,
                    linear_iterations=900),
            run_row("trampoline", 51483, 9, 0, solver="bnls-mumps", wall_time=5.0)])
        write(self.out, "parallel", [
            run_row("trampoline", 51483, 5, refine=5, ranks=1, wall_time=20.0, stage_solve=18.0),
            run_row("trampoline", 51483, 5, refine=5, ranks=2, wall_time=16.0, stage_solve=14.0),
            run_row("trampoline", 51483, 1, refine=5, ranks=1, wall_time=19.0, stage_solve=9.0,
                    solver="rmtr-patch", shared_wall_time=20.5),
            run_row("trampoline", 51483, 1, refine=5, ranks=2, wall_time=10.0, stage_solve=4.5,
                    solver="rmtr-patch", runs=3, slowest_wall_time=11.5),
            run_row("drooping", 51483, 12, refine=5, ranks=1, wall_time=72.0, stage_solve=71.0,
                    solver="rmtr-patch-dogleg"),
            run_row("drooping", 51483, 13, refine=5, ranks=2, wall_time=45.0, stage_solve=44.0,
                    solver="rmtr-patch-dogleg")])
        text = self.build()
        # Paths of different length on 1 and 2 ranks: the speed per V-cycle, 72/12 against
        # 45/13 s, beside the whole run's 1.60×.
        self.assertIn("(drooping, rmtr-patch-dogleg) | 1.60×; 12 against 13 V-cycles, 1.73× per "
                      "V-cycle;", text)
        self.assertNotIn("per V-cycle", text.split("(trampoline, rmtr-patch) |")[1].split("\n")[0])
        self.assertIn("| 4.00 |", text)  # bntr-gamg: 40 s / 10 s
        # The failed bnls is not "best"; the headline names both solvers it compares.
        self.assertIn("| trampoline | 51,483 | rmtr | bntr-gamg | 4.00× |",
                      section(text, "Headline"))
        self.assertIn("| 4.00× | met |", text)
        self.assertRegex(text, r"\| 1\.25×; RMTR on 2 ranks: [^|]*Solve 14 s \| \*\*not met\*\* \|")
        # Rows without a solver are the default's; each configuration has its own goal row.
        self.assertIn("| trampoline | rmtr | 51,483 | 1 | 20 |", text)
        # Two 1-rank copies at once take 20.5 s each: at most 2 × 19 / 20.5 = 1.85× on 2 ranks
        # (not the 1.90× measured: the ceiling comes from the shared copies, not the 2-rank run).
        self.assertIn("(trampoline, rmtr-patch) | 1.90× (this machine's ceiling 1.85×) | met |",
                      text)
        self.assertIn("| trampoline | rmtr-patch | 51,483 | 1 | 19 |", text)
        self.assertRegex(text, r"\| 1 \| 19 \|[^\n]*\| 20\.5 \| 1\.85 \|")
        self.assertNotIn("ceiling", text.split("(trampoline, rmtr)")[1].split("\n")[0])
        # The fastest of three runs in turn, the slowest beside it; a single run says 1.
        self.assertIn("| trampoline | rmtr-patch | 51,483 | 2 | 10 | 3 (11.5) |", text)
        self.assertIn("| trampoline | rmtr-patch | 51,483 | 1 | 19 | 1 |", text)

    def test_a_ratio_just_short_of_its_goal_is_not_rounded_up_to_it(self):
        write(self.out, "parallel", [
            run_row("trampoline", 51483, 2, refine=5, ranks=1, wall_time=8.66, stage_solve=7.0,
                    solver="rmtr-patch-dogleg", shared_wall_time=6.87),
            run_row("trampoline", 51483, 2, refine=5, ranks=2, wall_time=4.82, stage_solve=4.0,
                    solver="rmtr-patch-dogleg")])
        text = self.build()
        # 8.66 / 4.82; the shared copies ran faster than the run alone (2 × 8.66 / 6.87 = 2.52):
        # noise, and no code can gain more than 2× on 2 ranks.
        self.assertIn("(trampoline, rmtr-patch-dogleg) | 1.797× (this machine's ceiling 2.00×)",
                      text)
        self.assertRegex(text, r"rmtr-patch-dogleg\) \| 1\.797×[^\n]*\| \*\*not met\*\* \|")

    def test_scaling_table_ratios_and_goals(self):
        write(self.out, "scaling", [
            run_row("trampoline", 51483, 2, solver="rmtr", refine=5, wall_time=15.0,
                    peak_rss_mib=1040),
            run_row("trampoline", 51483, 8, solver="rmtr-patch", refine=5, wall_time=10.0,
                    peak_rss_mib=864),
            run_row("trampoline", 51483, 9, solver="tr", refine=5, wall_time=16.0,
                    peak_rss_mib=927),
            run_row("trampoline", 51483, 30, 0, solver="bnls-mumps", refine=5, wall_time=8.0),
            run_row("trampoline", 201243, 25, solver="rmtr-patch", refine=6, wall_time=100.0,
                    peak_rss_mib=3000),
            {**run_row("trampoline", "", "", 0, solver="tr", refine=6),
             "reason": "timeout after 900 s"}])
        text = self.build()
        self.assertIn("| 5 | 51,483 | 2 · 15 s · 1,040 MiB | 8 · 10 s · 864 MiB |", text)
        self.assertIn("timeout after 900 s", text)
        # The failed bnls run is not the best single-level solver: TR's 16 s is.
        self.assertIn("| trampoline | 51,483 | rmtr-patch | tr | 1.60× |",
                      section(text, "Headline"))
        self.assertIn("| 1.60× | **not met** |", text)
        self.assertIn("no single-level solver converged | **not met** |", text)
        self.assertIn("| 8, 25 | **not met** |", text)  # 25 > 20 V-cycles at 201,243 dofs
        self.assertIn("](scaling.png)", text)

    def test_triangle_table_headline_and_goals(self):
        def tri(solver, res, dofs, its, wall, energy, converged=1, levels=1):
            return run_row("shell_indent", dofs, its, converged, solver=solver, resolution=res,
                           steps=2, levels=levels, wall_time=wall, peak_rss_mib=100,
                           energy=energy)
        write(self.out, "triangle", [
            tri("pnewton", 16, 2325, 12, 6.0, 0.047),
            tri("tr", 16, 2325, 40, 9.0, 0.047),
            tri("rmtr-patch-dogleg", 16, 2325, 3, 5.0, 0.047, levels=2),
            tri("rmtr-own", 16, 2325, 30, 20.0, 0.047, 0, levels=2),
            tri("pnewton", 64, 36000, 20, 60.0, 0.05),
            tri("rmtr-patch-dogleg", 64, 36000, 5, 15.0, 0.05 * (1 + 2e-12), levels=4),
            tri("rmtr-proxy", 64, 36000, 6, 12.0, 0.05, levels=4)])
        text = self.build()
        self.assertIn("| 16 | 2,325 | 2 | 12 · 6 s · 100 MiB | 40 · 9 s · 100 MiB | "
                      "3 · 5 s · 100 MiB | 30 (stopped: tr_reduction, \\|g\\| 5.0e-01) |",
                      text)
        self.assertIn("| 2.0e-12 |", text)  # the converged runs' energies agree
        head = section(text, "Headline")
        # The fastest RMTR coarse model against the fastest single-level solver.
        self.assertIn("| shell_indent | 36,000 | rmtr-proxy | 6 | pnewton | 20 | 5.00× |", head)
        self.assertIn("| shell_indent | 2,325 | rmtr-patch-dogleg | 3 | pnewton | 12 | 1.20× |",
                      head)
        # The goals are the default's: 60 / 15 s at 36,000 dofs (within 1.6× of 50,000).
        self.assertRegex(text, r"about 50,000 dofs \(shell_indent\) \| 4\.00× against pnewton"
                               r" \(36,000 dofs\) \| met \|")
        self.assertRegex(text, r"about 200,000 dofs \(shell_indent\) \| not measured in this "
                               r"run \(finest: 36,000 dofs\) \|  \|")
        self.assertIn("| 3 (2,325), 5 (36,000) | **not met** |", text)  # 5 > 1.5 × 3
        self.assertIn("](triangle.png)", text)
        self.assertTrue((self.out / "triangle.png").is_file())

    def test_scaling_of_each_scene_in_its_own_table(self):
        # A free-hanging scene's rows get their own table and plot, and stay out of the
        # trampoline's goals (its faster single-level run is no trampoline peer).
        write(self.out, "scaling", [
            run_row("trampoline", 51483, 1, solver="rmtr-patch", refine=5, wall_time=10.0,
                    peak_rss_mib=300),
            run_row("trampoline", 51483, 9, solver="tr", refine=5, wall_time=25.0,
                    peak_rss_mib=450),
            run_row("drooping", 51483, 11, solver="rmtr", refine=5, wall_time=109.0,
                    peak_rss_mib=900),
            run_row("drooping", 51483, 400, solver="tr", refine=5, wall_time=2.0,
                    peak_rss_mib=400)])
        text = self.build()
        self.assertIn("RMTR at scale on free-hanging cloth: drooping", text)
        self.assertIn("| 5 | 51,483 | 11 · 109 s · 900 MiB | 400 · 2 s · 400 MiB |", text)
        self.assertIn("| 5 | 51,483 | 1 · 10 s · 300 MiB | 9 · 25 s · 450 MiB |", text)
        self.assertIn("| trampoline | 51,483 | rmtr-patch | tr | 2.50× |",
                      section(text, "Headline"))
        self.assertIn("](scaling_drooping.png)", text)
        self.assertTrue((self.out / "scaling_drooping.png").exists())

    def test_free_hanging_goals_use_the_scenes_own_solver_and_table_4(self):
        # Off the trampoline the goals are the scene solver's (rmtr-patch-dogleg): V-cycles
        # within 1/5 of Table 4 (drooping: 707 at 3,675 dofs, 333 at 51,483 and, beyond the
        # paper's resolutions, at 201,243), and its time against a single-level solver only
        # where one was run. Table 4's cells go by the number of levels, refine + 1, whatever
        # the cage: the re-entrant corner's 91-face cage gives 5,115 dofs at 3 levels (1,508).
        write(self.out, "scaling", [
            run_row("drooping", 3675, 29, solver="rmtr-patch-dogleg", refine=3, wall_time=6.0),
            run_row("drooping", 51483, 10, solver="rmtr-patch-dogleg", refine=5,
                    wall_time=40.0),
            run_row("drooping", 51483, 240, solver="bnls-mumps", refine=5, wall_time=480.0),
            {**run_row("drooping", "", "", 0, solver="tr", refine=5),
             "reason": "timeout after 1500 s"},
            run_row("drooping", 201243, 70, solver="rmtr-patch-dogleg", refine=6,
                    wall_time=150.0),
            run_row("reentrant_corner", 5115, 128, solver="rmtr-patch-dogleg", refine=2,
                    wall_time=35.0),
            run_row("reentrant_corner", 18939, 101, solver="rmtr-patch-dogleg", refine=3,
                    wall_time=123.0)])
        text = self.build()
        self.assertIn("| rmtr-patch-dogleg: at most 1/5 of Table 4's V-cycles at every "
                      "resolution (drooping) | 29, 10, 70 (limits 141, 67, 67) | **not met** |",
                      text)
        self.assertIn("| rmtr-patch-dogleg ≥ 3× faster than the best single-level solver at "
                      "51,483 dofs (drooping) | 12.00× | met |", text)
        self.assertNotIn("201,243 dofs (drooping)", text)  # no single-level run there
        self.assertIn("| rmtr-patch-dogleg: at most 1/5 of Table 4's V-cycles at every "
                      "resolution (reentrant_corner) | 128, 101 (limits 302, 56) | **not met** |",
                      text)
        self.assertNotIn("faster than the best single-level solver at 51,483 dofs "
                         "(reentrant_corner)", text)

    def test_peer_ratios_are_to_the_scenes_own_configuration(self):
        # The trampoline's own configuration (rmtr-patch) is the reference where it was run, and
        # rmtr.yaml's row is neither the reference nor a peer.
        write(self.out, "peers", [
            run_row("trampoline", 51483, 1, solver="rmtr", wall_time=4.0),
            run_row("trampoline", 51483, 1, solver="rmtr-patch", wall_time=3.0),
            run_row("trampoline", 51483, 7, solver="bnls-mumps", wall_time=12.0)])
        text = self.build()
        self.assertIn("| trampoline | 51,483 | rmtr-patch | bnls-mumps | 4.00× |",
                      section(text, "Headline"))
        self.assertIn("| rmtr-patch ≥ 3× faster than the best PETSc solver at 51,483 dofs "
                      "(trampoline) | 4.00× | met |", text)
        self.assertIn("| trampoline | 51,483 | rmtr | 4 | 1 |  | 1.33 |", text)

    def test_goals_not_measured_are_said_so(self):
        write(self.out, "projection", [run_row("trampoline", 3675, 81, projection="reverse",
                                               levels=4)])
        text = self.build()
        self.assertIn("81 / 81", text)
        self.assertEqual(text.count("not measured in this run"), 2)

    def test_projection_and_timestep_by_preset(self):
        write(self.out, "projection", [
            run_row("drooping", 3675, 700, projection="lsq", levels=4, preset="denim"),
            run_row("drooping", 3675, 650, projection="reverse", levels=4, preset="denim"),
            run_row("drooping", 3675, 900, projection="reverse", levels=4,
                    preset="denim-table1")])
        rows = []
        for preset, largest in (("denim", 1.0), ("denim-table1", 0.5)):
            for dt in (0.5, 1.0):
                rows.append(run_row("drape", 1083, 10, int(dt <= largest), solver="tr", dt=dt,
                                    preset=preset))
        write(self.out, "timestep", rows)
        text = self.build()
        self.assertIn("| drooping | denim | 4 | 3,675 | 700 / 659 | 650 / 707 |", text)
        self.assertIn("| drooping | denim-table1 | 4 | 3,675 | not run / 659 | 900 / 707 |", text)
        self.assertIn("| drape (1,083 dofs) | drape, denim-table1 (1,083 dofs) |", text)
        self.assertIn("| tr | 1 | 1/2 |", text)

    def test_accuracy_front_table(self):
        rows = []
        for solver, wall, err in (("rmtr", 1.0, 1e-3), ("rmtr", 2.0, 1e-5), ("tr", 3.0, 1e-4)):
            rows.append(run_row("trampoline", 1083, 3, solver=solver, wall_time=wall,
                                l2_error=err, probe_error=err, tolerance=1e-5,
                                reference_dofs=13467))
        write(self.out, "accuracy", rows)
        text = self.build()
        self.assertIn("reference: 13,467 dofs", text)
        front = text.split("### trampoline")[1]
        self.assertIn("| 2 | 1.000e-05 |", front)
        self.assertNotIn("| 3 | 1.000e-04 |", front)  # dominated by rmtr at 2 s
        self.assertTrue((self.out / "accuracy_trampoline.png").is_file())


class ReportOrder(unittest.TestCase):
    """A newcomer reads what the studies are, then the headline, then the studies; the commands
    and builds that filled the folder come last. Every headline row says what it compares."""

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.out = Path(self.dir.name)
        write(self.out, "iterations", [
            run_row("trampoline", 363, 3, solver="rmtr-patch-dogleg", levels=2, refine=1),
            run_row("drooping", 363, 10, solver="rmtr-patch-dogleg", levels=2, refine=1),
            run_row("trampoline", 147, 12, solver="tr", levels=1, refine=0)])
        write(self.out, "peers", [
            run_row("trampoline", 51483, 1, solver="rmtr-patch", wall_time=3.0),
            run_row("trampoline", 51483, 7, solver="bnls-mumps", wall_time=12.0)])
        write(self.out, "parallel", [
            run_row("trampoline", 51483, 1, refine=5, ranks=1, wall_time=19.0, stage_solve=9.0,
                    solver="rmtr-patch"),
            run_row("trampoline", 51483, 1, refine=5, ranks=2, wall_time=10.0, stage_solve=4.5,
                    solver="rmtr-patch")])
        write(self.out, "scaling", [
            run_row("trampoline", 51483, 1, solver="rmtr-patch", refine=5, wall_time=10.0,
                    solve_time=8.0, peak_rss_mib=300),
            run_row("trampoline", 51483, 9, solver="tr", refine=5, wall_time=25.0,
                    solve_time=24.0, peak_rss_mib=450)])
        (self.out / "meta.json").write_text(json.dumps({
            "mode": "full", "ranks": 2, "cores": 2,
            "runs": [{"command": "examples/studies/studies.py --full --only scaling",
                      "date": "2026-12-06T03:16:59", "elapsed": 877.0, "build": "06682cb"}]}))
        self.text = report.Report(self.out).write().read_text()

    def tearDown(self):
        self.dir.cleanup()

    def test_title_and_what_the_studies_are_then_the_headline(self):
        intro = self.text.split("\n## ", 1)[0]
        self.assertTrue(intro.startswith("# mlshell convergence studies\n"))
        self.assertIn("paper's tables", intro)
        self.assertIn("single-level solvers", intro)
        self.assertIn("2 MPI ranks of a 2-core machine", intro)
        self.assertLessEqual(len([line for line in intro.splitlines() if line.strip()]), 3)
        self.assertTrue(self.text.split("\n## ", 1)[1].startswith("Headline\n"))
        self.assertNotIn("studies.py --full", intro)

    def test_sections_in_order_and_the_commands_and_builds_last(self):
        headings = [line[3:] for line in self.text.splitlines() if line.startswith("## ")]
        self.assertEqual(headings[:2], ["Headline", "Performance goals"])
        self.assertEqual(headings[-2:], ["Reproduce", "Provenance"])
        studies = headings[2:-2]
        self.assertEqual(studies[0], "Tables 3–5: iterations per step, dt = 1")
        self.assertIn("RMTR at scale: V-cycles, time and memory against resolution", studies)
        # The commands, their dates and builds appear only under Reproduce; each row's build
        # only under Provenance.
        before, after = self.text.split("\n## Reproduce\n")
        self.assertNotIn("--only scaling", before)
        self.assertIn("- `examples/studies/studies.py --full --only scaling` "
                      "(2026-12-06T03:16:59, 877 s, build 06682cb)", after)
        self.assertNotIn("| scaling.csv |", before)
        self.assertIn("| scaling.csv | 2 | not recorded (2) |", section(self.text, "Provenance"))

    def test_each_study_section_says_what_it_measures_against_what(self):
        headings = [line[3:] for line in self.text.splitlines() if line.startswith("## ")]
        for heading in headings[2:-2]:
            first = section(self.text, heading).strip().split("\n\n")[0]
            self.assertRegex(first, r"^\*\*Measures\*\* .+, \*\*against\*\* .+\.$", heading)

    def test_each_headline_row_names_what_it_compares(self):
        groups = {title: (compares, header, rows)
                  for title, compares, header, rows in headline_groups(self.text)}
        self.assertEqual(list(groups), [
            "V-cycles: mlshell's default (`rmtr-patch-dogleg`) against the paper's Table 4",
            "Time: RMTR against the fastest single-level solver",
            "Time: RMTR against PETSc's solvers",
            "Parallel: 2 MPI ranks against 1"])
        for title, (compares, header, rows) in groups.items():
            self.assertTrue(compares.startswith("Compares "), title)
            self.assertTrue(rows, title)
            if "RMTR" in header:
                # Different solvers on each side: each row names both.
                other = next(i for i, h in enumerate(header) if h.endswith("solver"))
                for row in rows:
                    mine, theirs = row[header.index("RMTR")], row[other]
                    self.assertTrue(mine in SOLVERS and theirs in SOLVERS and mine != theirs,
                                    f"{title}: {row}")
            elif "solver" in header:
                # One solver against itself: the row names it, the sentence says so.
                self.assertIn("with itself", compares)
                for row in rows:
                    self.assertTrue(row[header.index("solver")] in SOLVERS, f"{title}: {row}")
            else:
                # mlshell's solver against the paper's: the sentence names both, each cell
                # holds both numbers.
                self.assertIn("`rmtr-patch-dogleg`", compares)
                self.assertIn("the paper's own RMTR configuration", compares)
                self.assertEqual(header, ["scene", "2 levels"])
                for row in rows:
                    self.assertTrue(all(" / " in cell for cell in row[1:]), row)
        self.assertEqual(groups["V-cycles: mlshell's default (`rmtr-patch-dogleg`) against the "
                                "paper's Table 4"][2],
                         [["trampoline", "3 / 633 (363)"], ["drooping", "10 / 4,671 (363)"]])
        self.assertEqual(groups["Time: RMTR against the fastest single-level solver"][2],
                         [["trampoline", "51,483", "rmtr-patch", "tr", "2.50×", "3.00×"]])
        self.assertEqual(groups["Time: RMTR against PETSc's solvers"][2],
                         [["trampoline", "51,483", "rmtr-patch", "bnls-mumps", "4.00×"]])
        self.assertEqual(groups["Parallel: 2 MPI ranks against 1"][2],
                         [["trampoline", "rmtr-patch", "1.90×"]])


class CommittedReport(unittest.TestCase):
    def test_the_committed_report_has_every_section_in_order(self):
        # The check quick_outputs.py makes of a quick run's report, on the committed one
        # (examples/studies/studies.py --report-only --out examples/studies/results).
        self.assertEqual(report_problems((RESULTS / "REPORT.md").read_text()), [])


class CsvMerge(unittest.TestCase):
    def test_a_solver_run_replaces_only_its_own_rows(self):
        with tempfile.TemporaryDirectory() as d:
            ctx = Context(runner=None, mode="full", out=Path(d))
            cols = ["scene", "solver", "wall_time"]
            ctx.write_csv("t", [{"scene": "a", "solver": "x", "wall_time": 1},
                                {"scene": "a", "solver": "y", "wall_time": 2},
                                {"scene": "b", "solver": "x", "wall_time": 3}], cols,
                          key=("scene", "solver"))
            ctx.write_csv("t", [{"scene": "a", "solver": "y", "wall_time": 9}], cols,
                          key=("scene", "solver"))
            rows = {(r["scene"], r["solver"]): r["wall_time"] for r in read_csv(Path(d) / "t.csv")}
            self.assertEqual(rows, {("a", "x"): "1", ("b", "x"): "3", ("a", "y"): "9"})
            ctx.write_csv("t", [{"scene": "a", "solver": "z", "wall_time": 5}], cols)
            rows = {(r["scene"], r["solver"]) for r in read_csv(Path(d) / "t.csv")}
            self.assertEqual(rows, {("b", "x"), ("a", "z")})  # by scene: all of a's rows go


class Provenance(unittest.TestCase):
    """Every row says which mlshell build measured it; rows from before keep theirs empty."""

    def test_rows_carry_the_build_and_older_rows_are_kept_unrecorded(self):
        with tempfile.TemporaryDirectory() as d:
            out = Path(d)
            cols = ["scene", "solver", "wall_time"]
            write(out, "t", [{"scene": "a", "solver": "x", "wall_time": 1}])  # no commit column
            summary = {"status": "complete", "dofs": 363, "gradient_norm": 1e-9,
                       "wall_time": 2.0, "build": {"commit": "abc1234"},
                       "solver": {"iterations": 4, "reason": "CONVERGED_GATOL",
                                  "converged": True}}
            fields = solver_fields({"scene": "b", "refine": 1, "ranks": 2, "exit_code": 0,
                                    "timed_out": False, "elapsed": 2.0, "summary": summary})
            self.assertEqual(fields["commit"], "abc1234")
            ctx = Context(runner=None, mode="full", out=out)
            ctx.write_csv("t", [{**fields, "solver": "x"}], cols, key=("scene", "solver"))
            rows = read_csv(out / "t.csv")
            self.assertEqual(list(rows[0]), cols + ["commit"])
            self.assertEqual({(r["scene"], r["commit"]) for r in rows},
                             {("a", ""), ("b", "abc1234")})
            text = report.Report(out).write().read_text()
            self.assertIn("| t.csv | 2 | abc1234 (1), not recorded (1) |", text)


class FailedRuns(unittest.TestCase):
    """A crash or a timeout must never pass for a solver's own outcome."""

    def result(self, exit_code, timed_out=False, summary=True):
        s = {"status": "complete", "dofs": 363, "gradient_norm": 1e-9, "wall_time": 1.0,
             "solver": {"iterations": 4, "reason": "CONVERGED_GATOL", "converged": True}}
        return {"scene": "trampoline", "refine": 1, "ranks": 2, "exit_code": exit_code,
                "timed_out": timed_out, "elapsed": 9.0, "summary": s if summary else None}

    def test_a_crash_after_the_summary_is_a_crash(self):
        row = solver_fields(self.result(139))
        self.assertEqual((row["reason"], row["converged"]), ("exit 139", 0))
        self.assertEqual(failed_runs("iterations", [row]), ["trampoline: exit 139"])

    def test_timeouts_and_solver_outcomes(self):
        timeout = solver_fields(self.result(None, timed_out=True, summary=False))
        self.assertTrue(timeout["reason"].startswith("timeout after 9 s"))
        self.assertEqual(len(failed_runs("work", [timeout])), 1)
        converged = solver_fields(self.result(0))
        self.assertEqual(converged["reason"], "CONVERGED_GATOL")
        self.assertEqual(failed_runs("work", [converged]), [])


if __name__ == "__main__":
    unittest.main()
