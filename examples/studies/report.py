#!/usr/bin/python3
"""REPORT.md from the CSV files the studies wrote. In order: a title and what the studies are,
the headline (one small table per kind of comparison, each saying what it compares against
what), the performance goals (met or by how much not), one section per study (each opening with
what it measures and against what: the paper's tables side by side, the plots), and last the
commands that filled the folder and the build behind every row (Reproduce, Provenance).

usage: report.py OUT_DIR     (reads OUT_DIR/*.csv and meta.json, writes OUT_DIR/REPORT.md)"""
import json
import sys
from pathlib import Path

import paper
import plots
import report_progressive
import study_iterations
import study_scaling
import study_triangle
from context import PROVENANCE, number, read_csv
from solvers import DEFAULT_SOLVER, describe, scene_solver

GOAL_SPEEDUP_PEERS = 3.0
GOAL_SPEEDUP_RANKS = 1.8
GOAL_DOFS = 51483
# Issue 13: the scalable RMTR against the best single-level solver, and its V-cycles.
GOAL_SCALING = ((51483, 3.0), (201243, 5.0))
GOAL_SCALING_CYCLES = 20
GOAL_SCALING_TABLE4 = 5  # elsewhere: at most 1/5 of the paper's Table 4 at as many levels
SINGLE_LEVEL = ("tr", "bnls-mumps")
# Issue 48: RMTR on triangle hierarchies against the best single-level solver, at about these
# dofs (a resolution within TRIANGLE_DOFS_SPREAD of them counts), and its V-cycles: those at
# the finest resolution at most TRIANGLE_CYCLE_GROWTH times those at the coarsest ("do not
# grow", with room for the path a post-buckled sheet takes).
GOAL_TRIANGLE = ((50000, 3.0), (200000, 5.0))
TRIANGLE_DOFS_SPREAD = 1.6
TRIANGLE_CYCLE_GROWTH = 1.5
# The headline's groups, in the order they are shown (Report.headline_group).
HEADLINE_ORDER = ("cycles", "single-level", "triangle", "peers", "ranks")


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def count(v):
    x = number(v)
    return "" if x is None else f"{int(x):,}"


def seconds(v):
    x = number(v)
    return "" if x is None else f"{x:.3g}"


def outcome(row, column="iterations"):
    """A converged run's count, or the count with why it stopped."""
    if row is None:
        return "not run"
    if row["dofs"] == "":
        return row["reason"]
    if row["converged"] == "1":
        return count(row[column])
    g = number(row.get("gradient_norm"))
    why = row["reason"].replace("DIVERGED_", "").lower()
    n = count(row[column])
    return (f"{n} " if n else "") + f"(stopped: {why}" + (f", \\|g\\| {g:.1e}" if g else "") + ")"


def measures(what, against):
    """The line that opens a study's section: what it measures and against what."""
    return f"**Measures** {what}, **against** {against}.\n\n"


def paper_cell(v):
    return "—" if v is None else f"{v:,}"


def presets_of(rows):
    """The presets a study's rows hold, the default first (rows from before presets: denim)."""
    return sorted({r.get("preset") or "denim" for r in rows}, key=lambda p: p != "denim")


def of_preset(rows, preset):
    """The rows of `preset` (a row from before presets, or with none given, is denim)."""
    return [r for r in rows if (r.get("preset") or "denim") == preset]


def column_of(row):
    """A scene, with its preset when it is not the default: one column of a per-scene table."""
    preset = row.get("preset") or "denim"
    return row["scene"] if preset == "denim" else f"{row['scene']}, {preset}"


def find(rows, **match):
    return next((r for r in rows if all(r[k] == str(v) for k, v in match.items())), None)


def against(ratio, goal):
    """A measured ratio for a goal's row: two decimals, or three where two would round it up
    to the goal it misses (1.797×, not 1.80×, against 1.8×)."""
    text = f"{ratio:.2f}"
    return (f"{ratio:.3f}" if ratio < goal <= float(text) else text) + "×"


def spread(row):
    """How many runs a parallel row is the fastest of, with the slowest one's wall time."""
    runs, slowest = number(row.get("runs", "")), row.get("slowest_wall_time", "")
    if not runs or runs < 2:
        return "1"
    return f"{runs:.0f} ({seconds(slowest)})"


def bandwidth_ceiling(one):
    """2 × a 1-rank run's wall time / that of one of two copies run at once (None if absent),
    at most 2: copies that ran faster than the run alone measured the machine's noise."""
    if not one:
        return None
    alone, shared = number(one.get("wall_time")), number(one.get("shared_wall_time"))
    return min(2.0, 2.0 * alone / shared) if alone and shared else None


class Report:
    def __init__(self, out):
        self.out = Path(out)
        self.parts = []
        self.headline = {}  # kind -> its group (headline_group)
        self.goals = []
        self.meta = {}
        if (self.out / "meta.json").is_file():
            self.meta = json.loads((self.out / "meta.json").read_text())

    def csv(self, name):
        path = self.out / f"{name}.csv"
        return read_csv(path) if path.is_file() else None

    def add(self, text):
        self.parts.append(text)

    def headline_group(self, kind, title, compares, header):
        """The rows of the headline's group `kind` (one of HEADLINE_ORDER): a small table under
        `title`, opened by `compares`, the sentence that says what its rows compare."""
        return self.headline.setdefault(kind, {"title": title, "compares": compares,
                                               "header": header, "rows": []})["rows"]

    def image(self, name):
        if name:
            self.add(f"![{name}]({name})\n")

    # --- Tables 3, 4, 5 -------------------------------------------------------------------
    def iterations(self):
        rows = self.csv("iterations")
        if rows is None:
            return
        table1 = [r for r in rows if r.get("preset") == "denim-table1"]
        rows = [r for r in rows if r.get("preset") in (None, "", "denim")]
        self.add("## Tables 3–5: iterations per step, dt = 1\n\n" + measures(
                 "the iterations of one step of dt = 1 of single-level TR and of two RMTR "
                 "configurations on the four scenes", "the paper's Tables 3 and 4 (its TR and "
                 "its RMTR)") + "Each cell: mlshell / paper. TR is the single-level trust "
                 "region with Dogleg; RMTR runs factorised Dogleg smoothing (`rmtr.yaml`, "
                 "mlshell's default until 2026-12-05) and mlshell's default "
                 "(`rmtr-patch-dogleg.yaml`). Tolerance (7.1): \\|g\\| < 1e-7; rows without a "
                 "build under [Provenance](#provenance) also stopped at \\|g\\|/\\|g₀\\| < "
                 "1e-10, which ended the drape (\\|g₀\\| > 10⁵) at up to \\|g\\| = 3e-4. "
                 "Every study ignores the scenes' own solver files (the trampoline's is "
                 "`rmtr-patch`; the other scenes use mlshell's default).\n")
        tr = [r for r in rows if r["solver"] == "tr"]
        dofs = sorted({int(r["refine"]) for r in tr})
        body = []
        for scene in paper.SCENES:
            line = [scene]
            for refine in dofs:
                r = find(tr, scene=scene, refine=refine)
                ref = paper.TR_ITERATIONS[scene][refine] if refine < 6 else None
                d = f" ({count(r['dofs'])} dofs)" if r and r["dofs"] else ""
                line.append(f"{outcome(r)} / {paper_cell(ref)}{d}")
            body.append(line)
        self.add("### Table 3: single-level TR iterations\n\n" + table(
            ["scene"] + [f"refine {k}" for k in dofs], body))
        present = [s for s in study_iterations.RMTR_SOLVERS
                   if any(r["solver"] == s for r in rows)]
        for solver in present:
            self.table4(solver, [r for r in rows if r["solver"] == solver],
                        headline=solver == present[-1])
        self.image(plots.iterations(rows, self.out))
        self.iterations_by_preset(rows, table1)

    def table4(self, solver, rm, headline):
        """Table 4 for one RMTR configuration: its V-cycles beside the paper's, in the headline
        if `headline` (mlshell's default's, where measured), and the goal of matching the paper."""
        levels = sorted({int(r["levels"]) for r in rm})
        default = solver == DEFAULT_SOLVER
        title = ("mlshell's default (`rmtr-patch-dogleg.yaml`)" if default else
                 "factorised Dogleg smoothing (`rmtr.yaml`)")
        body, met, compared = [], 0, 0
        if headline:
            who = ("mlshell's default, `rmtr-patch-dogleg` (Dogleg smoothing with "
                   "patch-preconditioned CG Newton points, no fine factorisation)" if default
                   else f"`{solver}` (factorised Dogleg smoothing, `rmtr.yaml`)"
                   if solver == "rmtr" else f"`{solver}` ({describe(solver)})")
            grid = self.headline_group(
                "cycles", "V-cycles: " + ("mlshell's default (`rmtr-patch-dogleg`)" if default
                                          else f"`{solver}`") + " against the paper's Table 4",
                f"Compares the V-cycles of {who} with the paper's Table 4, measured by the "
                "paper's own RMTR configuration (§7.3: ST-CG smoothing, Dogleg on the coarsest "
                "level): different solvers on the same scenes, levels and tolerance (one step "
                "of dt = 1, \\|g\\| < 1e-7). Each cell: mlshell / paper (dofs of the finest "
                "level).",
                ["scene"] + [f"{k} levels" for k in levels])
        for scene in paper.SCENES:
            line, cells = [scene], [scene]
            for lv in levels:
                r = find(rm, scene=scene, levels=lv)
                ref = paper.RMTR_CYCLES[scene][paper.LEVELS.index(lv)] \
                    if lv in paper.LEVELS else None
                line.append(f"{outcome(r)} / {paper_cell(ref)}")
                cells.append(line[-1] if r is None or not r["reason"].startswith("not run")
                             else f"not run / {paper_cell(ref)}")
                if r and r["dofs"] and ref:  # a row not run is not compared
                    compared += 1
                    if r["converged"] == "1" and number(r["iterations"]) <= ref:
                        met += 1
                    cells[-1] += f" ({count(r['dofs'])})"
            body.append(line)
            if headline and any(r["scene"] == scene and r["dofs"] for r in rm):
                grid.append(cells)
        self.add(f"### Table 4: RMTR V-cycles vs number of levels, {title}\n\n" + table(
            ["scene"] + [f"{k} levels" for k in levels], body))
        if compared:
            self.goals.append((f"RMTR V-cycles at or below the paper's Table 4 ({solver})",
                               f"{met} of {compared} cells", met == compared))

    def iterations_by_preset(self, rows, table1):
        """The same solves with Table 1 as printed, and the elastic energy of every final state
        (negative: the cloth fell into the fit's negative well)."""
        if not table1:
            return
        body = []
        ran = [r for r in rows + table1 if not r["reason"].startswith("not run")]
        for r in sorted(ran, key=lambda r: (r["scene"], r["solver"], int(r["refine"]),
                                            r.get("preset", ""))):
            body.append([r["scene"], r["solver"], r["levels"], count(r["dofs"]) if r["dofs"]
                         else "", r.get("preset", "denim"), outcome(r),
                         f"{number(r.get('energy_elastic')):.4g}"
                         if number(r.get("energy_elastic")) is not None else "-"])
        self.add("### Tables 3–4 for both presets, with the final elastic energy [J]\n\n"
                 "`denim` limits Table 1's coupling so that the energy is positive; "
                 "`denim-table1` is the fit as printed, whose negative well free cloth falls "
                 "into (elastic energy < 0).\n\n" + table(
                     ["scene", "solver", "levels", "dofs", "preset", "iterations",
                      "elastic energy"], body))

    # --- Tables 6, 7 ------------------------------------------------------------------------
    def work(self):
        rows = self.csv("work")
        if rows is None:
            return
        body = []
        for scene in paper.SCENES:
            tr, rm = find(rows, scene=scene, solver="tr"), find(rows, scene=scene, solver="rmtr")
            if not tr or not rm:
                continue
            for kind, column, ref in (("assembly", "assembly_work", paper.ASSEMBLY_WORK),
                                      ("QP", "qp_work", paper.QP_WORK)):
                a, b = number(tr[column]), number(rm[column])
                ratio = f"{a / b:.2f}" if a and b else ""
                p = ref[scene]
                body.append([scene, count(tr["dofs"]), kind, f"{outcome(tr, column)} / {p[0]:,}",
                             f"{outcome(rm, column)} / {p[1]:,}", f"{ratio} / {p[0] / p[1]:.2f}",
                             f"{seconds(tr[column + '_per_iteration'])} / {p[2]}",
                             f"{seconds(rm[column + '_per_iteration'])} / {p[3]}"])
        self.add("## Tables 6–7: work units (eq. 7.3–7.4)\n\n" + measures(
                 "the assemblies and QP solves, in fine-level work units, of single-level TR "
                 "and of RMTR (`rmtr.yaml`) on three levels", "the paper's Tables 6 and 7 (its "
                 "TR and its RMTR)") + "mlshell / paper (1,083 dofs, RMTR "
                 "on three levels). "
                 "One work unit is one assembly (or QP solve) on the finest level; coarse levels "
                 "count by their share of control points.\n\n" + table(
                     ["scene", "dofs", "work", "TR total", "RMTR total", "TR/RMTR", "TR per it",
                      "RMTR per cycle"], body))

    # --- Table 8 ----------------------------------------------------------------------------
    def projection(self):
        rows = self.csv("projection")
        if rows is None:
            return
        body = []
        for scene in paper.SCENES:
            for preset in presets_of(rows):
                mine = of_preset(rows, preset)
                lsq = find(mine, scene=scene, projection="lsq")
                rev = find(mine, scene=scene, projection="reverse")
                if lsq or rev:
                    p = paper.PROJECTION_CYCLES[scene]
                    any_row = lsq or rev
                    body.append([scene, preset, any_row["levels"],
                                 count(any_row["dofs"]) if any_row["dofs"] else "",
                                 f"{outcome(lsq)} / {p[0]:,}", f"{outcome(rev)} / {p[1]:,}"])
        self.add("## Table 8: projection operator\n\n" + measures(
                 "the V-cycles of RMTR (`rmtr.yaml`) with the least-squares fit and with "
                 "reverse subdivision as the projection to coarser levels",
                 "the paper's Table 8") + "V-cycles, mlshell / paper (the paper: "
                 "3,675 dofs, four levels; a scene too slow there is solved coarser, with "
                 "levels = refine + 1).\n\n" + table(
                     ["scene", "preset", "levels", "dofs", "least-squares fit (5.18)",
                      "reverse subdivision (5.19)"], body))

    # --- Figure 9 ---------------------------------------------------------------------------
    def condition(self):
        rows = self.csv("condition")
        if rows is None:
            return
        body = [[r["sweep"], count(r["dofs"]), r["beta"] or "h^-5",
                 f"{number(r['lambda_min'], 0):.3e}", f"{number(r['lambda_max'], 0):.3e}",
                 f"{number(r['condition'], 0):.3e}", "yes" if r["settled"] == "1" else "no",
                 "yes" if r["converged"] == "1" else r["reason"]] for r in rows]
        self.add("## Figure 9: condition number of the Hessian\n\n" + measures(
                 "the condition number of the trampoline's Hessian as the resolution and the "
                 "penalty β grow", "the paper's Figure 9 (as its text states it)") +
                 "Trampoline, one step of dt = "
                 "1, Hessian at the final iterate. Estimated by Lanczos with full "
                 "reorthogonalisation on H (largest \\|λ\\|) and on H⁻¹ through a MUMPS LDLᵀ "
                 "factorisation (smallest \\|λ\\|): `mlshell -mlshell_condition`. Paper: "
                 f"{paper.CONDITION_NOTES}.\n\n" + table(
                     ["sweep", "dofs", "β", "\\|λ\\|min", "\\|λ\\|max", "cond₂", "Lanczos settled",
                      "step converged"], body))
        self.image(plots.condition(rows, self.out))

    # --- Figure 10 --------------------------------------------------------------------------
    def timestep(self):
        rows = self.csv("timestep")
        if rows is None:
            return
        largest = {}
        for r in rows:
            key = (column_of(r), r["solver"])
            largest.setdefault(key, None)
            if r["converged"] == "1":
                largest[key] = max(largest[key] or 0.0, number(r["dt"]))
        columns = list(dict.fromkeys(column_of(r) for r in rows))
        solvers = list(dict.fromkeys(r["solver"] for r in rows))
        tried = sorted({number(r["dt"]) for r in rows})
        dofs = {column_of(r): count(r["dofs"]) for r in rows if r["dofs"]}

        def cell(v):
            return "none" if v is None else ("1" if v == 1 else f"1/{round(1 / v)}")
        body = [[solver] + [cell(largest.get((c, solver))) for c in columns]
                for solver in solvers]
        self.add("## Figure 10: largest dt that converges\n\n" + measures(
                 "the largest time step at which each of five solvers (RMTR, single-level TR, "
                 "line-search Newton, damped Newton, the linearized equation) converges on each "
                 "scene",
                 "the paper's Figure 10") + "One step from rest at dt ∈ {" +
                 ", ".join(cell(t) for t in tried) + "}, refine 2 (1,083 dofs; the re-entrant "
                 "corner's finer cage: refine 1). Paper (1,083 dofs): "
                 "the trust-region solvers converge at every dt for every scene; line search, "
                 "damped Newton and the linearized equation need smaller steps.\n\n" +
                 table(["solver"] + [f"{c} ({dofs.get(c, '?')} dofs)" for c in columns], body))
        self.image(plots.largest_timestep(largest, self.out))

    # --- accuracy vs time -------------------------------------------------------------------
    def accuracy(self):
        rows = self.csv("accuracy")
        if rows is None:
            return
        self.add("## Accuracy vs time\n\n" + measures(
                 "the error and the wall time of RMTR's, single-level TR's and PETSc's "
                 "solvers' solutions over resolutions and tolerances", "a finer RMTR "
                 "reference solution (the paper has no such figure)") + "Error of one dt = 1 "
                 "step against a reference solved by RMTR two levels finer than the finest run, "
                 "against wall time (setup, solve and output of the whole run). Limit-surface "
                 "error: L² distance of the displacements over the reference configuration "
                 "(trapezoidal rule on the reference elements). Each point is one resolution × "
                 "tolerance × solver; the line is the Pareto front. The table lists the front: "
                 "for a time budget, take the last row that fits.\n")
        for scene in dict.fromkeys(r["scene"] for r in rows):
            mine = [r for r in rows if r["scene"] == scene and number(r["l2_error"]) is not None]
            if not mine:
                continue
            front = plots.pareto_front([(number(r["wall_time"]), number(r["l2_error"]))
                                        for r in mine])
            body = []
            for t, e in front:
                r = next(r for r in mine if number(r["wall_time"]) == t
                         and number(r["l2_error"]) == e)
                body.append([seconds(t), f"{e:.3e}", f"{number(r['probe_error']):.3e}",
                             r["solver"], count(r["dofs"]), r["tolerance"], count(r["iterations"])])
            failed = sum(1 for r in rows if r["scene"] == scene and r["converged"] != "1")
            self.add(f"### {scene} (reference: {count(mine[0]['reference_dofs'])} dofs)\n\n" +
                     table(["wall [s]", "L² error", "probe error [m]", "solver", "dofs",
                            "tolerance", "iterations"], body) +
                     (f"\n{failed} run(s) did not converge and are not plotted.\n"
                      if failed else ""))
            self.image(plots.accuracy(rows, self.out, scene))

    # --- peers ------------------------------------------------------------------------------
    def peers(self):
        rows = self.csv("peers")
        if rows is None:
            return
        body = []
        head = self.headline_group(
            "peers", "Time: RMTR against PETSc's solvers",
            "Compares the whole-run wall time (setup, solve, output) of the scene's own RMTR "
            "configuration (`rmtr.yaml` where that was not run) with the fastest converged of "
            "PETSc's TAO and SNES Newton solvers (MUMPS, GAMG, BoomerAMG; see *RMTR vs PETSc's "
            "solvers*): different solvers, the same step, tolerance and ranks. Ratio: the PETSc "
            "solver's time / RMTR's (above 1: RMTR is faster).",
            ["scene", "dofs", "RMTR", "fastest PETSc solver", "whole-run time, PETSc / RMTR"])
        for scene, refine in dict.fromkeys((r["scene"], r["refine"]) for r in rows):
            group = [r for r in rows if r["scene"] == scene and r["refine"] == refine]
            dofs = next((r["dofs"] for r in group if r["dofs"]), "")
            # The reference: the scene's own configuration, or rmtr.yaml in rows measured
            # before the study ran it.
            ours = (scene_solver(scene), "rmtr")
            rm = next((r for solver in ours for r in group if r["solver"] == solver), None)
            name = rm["solver"] if rm else "rmtr"
            t_rm = number(rm["wall_time"]) if rm and rm["converged"] == "1" else None
            best = None
            for r in group:
                t = number(r["wall_time"])
                ratio = f"{t / t_rm:.2f}" if t and t_rm and r["converged"] == "1" else ""
                body.append([scene, count(dofs), r["solver"], seconds(r["wall_time"]),
                             outcome(r), count(r["linear_iterations"]), ratio])
                if r["solver"] not in ours and r["converged"] == "1" and t and (
                        best is None or t < number(best["wall_time"])):
                    best = r
            if t_rm and best:
                ratio = number(best["wall_time"]) / t_rm
                head.append([scene, count(dofs), name, best["solver"], f"{ratio:.2f}×"])
                if int(dofs or 0) == GOAL_DOFS:
                    ok = ratio >= GOAL_SPEEDUP_PEERS
                    self.goals.append((f"{name} ≥ {GOAL_SPEEDUP_PEERS:g}× faster than the "
                                       f"best PETSc solver at {GOAL_DOFS:,} dofs ({scene})",
                                       against(ratio, GOAL_SPEEDUP_PEERS) +
                                       ("" if ok else self.time_split(scene, dofs)), ok))
            elif not t_rm:
                head.append([scene, count(dofs), name, "none compared",
                             f"{name} did not converge"])
        self.add("## RMTR vs PETSc's solvers\n\n" + measures(
                 "the wall time, iterations and linear iterations of PETSc's TAO and SNES "
                 "Newton solvers (MUMPS, GAMG, BoomerAMG)",
                 "RMTR on the same step: the scene's own configuration and `rmtr.yaml`") +
                 "Same step (dt = 1), same tolerance (\\|g\\| < "
                 "1e-7), same ranks. `rmtr`: factorised Dogleg smoothing (`rmtr.yaml`); the "
                 "scene's own configuration (`rmtr-patch` on the trampoline) has no factorisation "
                 "above the coarsest level. Ratio: wall time over the scene's own configuration's, "
                 "or over `rmtr`'s where the scene's was not run (above 1: RMTR is faster).\n\n" +
                 table(["scene", "dofs", "solver", "wall [s]", "iterations", "linear its",
                        "time / RMTR"], body))
        self.image(plots.peers(rows, self.out))

    def with_solver(self, name):
        """The rows of CSV `name`, each with a solver (tables written before the parallel
        study compared solvers hold the default's rows)."""
        rows = self.csv(name)
        if rows is not None:
            for r in rows:
                r["solver"] = r.get("solver") or "rmtr"
        return rows

    def time_split(self, scene, dofs, ranks=2, solver="rmtr"):
        """Where a solve's time goes, from the parallel study's -log_view (if it ran)."""
        rows = self.with_solver("parallel") or []
        events = self.with_solver("parallel_events") or []
        r = find(rows, scene=scene, dofs=dofs, ranks=ranks, solver=solver)
        if not r or number(r["stage_solve"]) is None:
            return ""
        top = [e for e in events if e["scene"] == scene and e["ranks"] == str(ranks)
               and e["refine"] == r["refine"] and e["solver"] == solver][:4]
        who = "RMTR" if solver == "rmtr" else solver
        split = (f"; {who} on {ranks} ranks: Setup {seconds(r['stage_setup']) or '?'} s, Solve "
                 f"{seconds(r['stage_solve'])} s")
        return split + (" (" + ", ".join(f"{e['event']} {seconds(e['time'])} s" for e in top) +
                        ")" if top else "")

    # --- parallel ---------------------------------------------------------------------------
    def parallel(self):
        rows = self.with_solver("parallel")
        if rows is None:
            return
        body, speedups = [], {}  # (scene, solver) -> {dofs: 1-rank wall / 2-rank wall}
        for scene, dofs, solver in dict.fromkeys((r["scene"], r["dofs"], r["solver"])
                                                 for r in rows):
            one, two = (find(rows, scene=scene, dofs=dofs, solver=solver, ranks=n)
                        for n in (1, 2))
            ceiling = bandwidth_ceiling(one)
            for r in (one, two):
                if r:
                    body.append([scene, solver, count(dofs), r["ranks"], seconds(r["wall_time"]),
                                 spread(r),
                                 seconds(r["stage_setup"]), seconds(r["stage_solve"]),
                                 seconds(r["stage_output"]), outcome(r),
                                 seconds(r.get("shared_wall_time", "")),
                                 f"{ceiling:.2f}" if ceiling and r is one else ""])
            if one and two and number(one["wall_time"]) and number(two["wall_time"]):
                s = number(one["wall_time"]) / number(two["wall_time"])
                speedups.setdefault((scene, solver), {})[int(dofs or 0)] = s
                if int(dofs or 0) == GOAL_DOFS:
                    ok = s >= GOAL_SPEEDUP_RANKS
                    bound = f" (this machine's ceiling {ceiling:.2f}×)" if ceiling else ""
                    # A partition-dependent smoother (vpatch) can take the ranks along paths
                    # of different length: the time per V-cycle separates speed from path.
                    n1, n2 = number(one["iterations"]), number(two["iterations"])
                    if n1 and n2 and n1 != n2:
                        per = s * n2 / n1
                        bound += (f"; {outcome(one)} against {outcome(two)} V-cycles, "
                                  f"{per:.2f}× per V-cycle")
                    self.goals.append((f"2 ranks ≥ {GOAL_SPEEDUP_RANKS}× faster than 1 at "
                                       f"{GOAL_DOFS:,} dofs ({scene}, {solver})",
                                       against(s, GOAL_SPEEDUP_RANKS) + bound + ("" if ok else
                                                              self.time_split(scene, dofs,
                                                                              solver=solver)),
                                       ok))
        if speedups:
            sizes = sorted({d for by_dofs in speedups.values() for d in by_dofs})
            head = self.headline_group(
                "ranks", "Parallel: 2 MPI ranks against 1",
                "Compares each RMTR configuration with itself: its wall time on 1 MPI rank / "
                "on 2 ranks (the same solver on both sides; this machine's ceiling is under "
                "*Parallel*).",
                ["scene", "solver"] + [f"{d:,} dofs" for d in sizes])
            for (scene, solver), by_dofs in speedups.items():
                head.append([scene, solver] + [f"{by_dofs[d]:.2f}×" if d in by_dofs else ""
                                               for d in sizes])
        self.add("## Parallel: 1 vs 2 ranks\n\n" + measures(
                 "the wall time of each RMTR configuration on 1 and on 2 MPI ranks, by "
                 "`-log_view` stage", "itself: the speedup, beside this machine's ceiling for "
                 "a perfectly parallel code") + "One step of dt = 1; times in seconds by "
                 "`-log_view` stage. `rmtr`: factorised Dogleg smoothing (`rmtr.yaml`); "
                 "`rmtr-patch`: full-multigrid start and vertex-patch smoothing. *Shared*: the wall time of "
                 "one of two 1-rank copies run at once, which share the memory bandwidth and "
                 "caches as 2 ranks do; *ceiling* = 2 × 1-rank wall / shared wall, the speedup "
                 "of a perfectly parallel code on this machine (at most 2: shared copies faster "
                 "than the run alone measure the machine's noise). Where a pair ran more than "
                 "once (*runs*, in turn), each row is its fastest run, the slowest in "
                 "brackets.\n\n" + table(
                     ["scene", "solver", "dofs", "ranks", "wall", "runs (slowest)", "Setup",
                      "Solve", "Output", "V-cycles", "shared", "ceiling"], body))
        events = self.with_solver("parallel_events")
        if events:
            body = [[e["scene"], e["solver"], e["refine"], e["ranks"], e["event"],
                     seconds(e["time"])] for e in events]
            self.add("Costliest events of the Solve stage (max over ranks):\n\n" + table(
                ["scene", "solver", "refine", "ranks", "event", "time [s]"], body))
        self.image(plots.parallel(rows, self.out))

    # --- scaling (issue 13) ------------------------------------------------------------------
    def scaling(self):
        rows = self.csv("scaling")
        if rows is None:
            return
        scenes = sorted({r["scene"] for r in rows}, key=lambda s: (s != "trampoline", s))
        for scene in scenes:
            mine = [r for r in rows if r["scene"] == scene]
            self.scaling_table(scene, mine)
            self.scaling_goals(scene, mine)

    def scaling_table(self, scene, rows):
        order = list(study_scaling.SOLVERS)
        solvers = sorted(dict.fromkeys(r["solver"] for r in rows),
                         key=lambda s: order.index(s) if s in order else len(order))
        body = []
        for refine in sorted({int(r["refine"]) for r in rows}):
            group = [r for r in rows if r["refine"] == str(refine)]
            dofs = next((r["dofs"] for r in group if r["dofs"]), "")
            line = [refine, count(dofs)]
            for solver in solvers:
                r = find(group, solver=solver)
                if r is None:
                    line.append("not run")
                elif r["converged"] != "1":
                    line.append(outcome(r))
                else:
                    line.append(f"{outcome(r)} · {seconds(r['wall_time'])} s · "
                                f"{count(r['peak_rss_mib'])} MiB")
            body.append(line)
        if scene == "trampoline":
            self.add("## RMTR at scale: V-cycles, time and memory against resolution\n\n" +
                     measures("the V-cycles, wall time and peak memory of RMTR configurations "
                              "on the trampoline as the resolution grows",
                              "the single-level solvers `tr` and `bnls-mumps` at the same "
                              "resolutions") +
                     "Trampoline, one step of dt = 1, \\|g\\| < 1e-7. Each cell: V-cycles (RMTR) "
                     "or iterations · wall time · peak resident memory of the largest rank. "
                     "`rmtr`: Dogleg smoothing (a factorisation per smoothing step) after the "
                     "full-multigrid start (`rmtr.yaml`, mlshell's default until 2026-12-05; the "
                     "trampoline scene's own solver is `rmtr-patch`); `rmtr-patch`: the start, "
                     "then vertex-patch ST-CG smoothing (no factorisation above the coarsest level); "
                     "`rmtr-patch-vcycles`: the same V-cycles from the given iterate; "
                     "`rmtr-galerkin`: `rmtr` with Galerkin coarse models (JᵀHJ of the finer "
                     "level's Hessian, no coarse energy evaluations); `rmtr-patch-galerkin`: "
                     "`rmtr-patch` with each coarser level solved in the start, Galerkin "
                     "coarse models, a subspace step after each V-cycle and retried smoothing "
                     "steps; `rmtr-patch-dogleg`: the same with Dogleg smoothing whose Newton "
                     "points come from patch-preconditioned CG (no factorisation either; mlshell's "
                     "default); "
                     "`rmtr-paper`: plain ST-CG (§7.3); `tr`: single-level TR + MUMPS; "
                     "`bnls-mumps`: TAO's line-search Newton + MUMPS. Wall time is the whole run "
                     "(setup, solve, output); the headline adds the ratio of the solve alone. "
                     "Rows of one solver come from one run; different solvers' rows may come "
                     "from different runs (meta.json).\n\n" +
                     table(["refine", "dofs"] + solvers, body))
        else:
            self.add(f"## RMTR at scale on free-hanging cloth: {scene}\n\n" +
                     measures(f"the same as on the trampoline for the {scene} scene",
                              "the single-level solvers where they were run, and 1/"
                              f"{GOAL_SCALING_TABLE4} of the paper's Table 4") +
                     "One step of dt = 1, \\|g\\| < 1e-7, the cells and solvers as for the "
                     "trampoline. The cloth falls far from its flat start, so the solves are "
                     "governed by the nonlinearity.\n\n" +
                     table(["refine", "dofs"] + solvers, body))
        self.image(plots.scaling(rows, self.out, scene))

    def cycle_goal(self, scene, refine):
        """The most V-cycles the issue allows `scene` at `refine` (None: no goal there): 20 on
        the trampoline; elsewhere 1/5 of Table 4 at the same number of levels, beyond its six
        levels 1/5 of that finest cell."""
        if scene == "trampoline":
            return GOAL_SCALING_CYCLES
        cells = paper.RMTR_CYCLES.get(scene)
        levels = paper.levels_for_refine(refine)
        if not cells or levels < paper.LEVELS[0]:
            return None
        return cells[paper.LEVELS.index(min(levels, paper.LEVELS[-1]))] / GOAL_SCALING_TABLE4

    def scaling_goals(self, scene, rows):
        """The issue's goals for the scene's own solver without fine factorisations: V-cycles
        at every resolution, and its (and rmtr.yaml's) time against the best single-level
        solver at 51k and 201k dofs. Off the trampoline a resolution whose single-level
        solvers were not run has no ratio."""
        own = scene_solver(scene)
        where = f"({scene})"
        runs = [r for r in rows if r["solver"] == own and not r["reason"].startswith("not run")]
        limits = [self.cycle_goal(scene, r["refine"]) for r in runs]
        if runs and all(limit is not None for limit in limits):
            ok = all(r["converged"] == "1" and number(r["iterations"]) <= limit
                     for r, limit in zip(runs, limits))
            goal = (f"at most {GOAL_SCALING_CYCLES} V-cycles" if scene == "trampoline" else
                    f"at most 1/{GOAL_SCALING_TABLE4} of Table 4's V-cycles")
            measured = ", ".join(outcome(r) for r in runs)
            if scene != "trampoline":
                measured += " (limits " + ", ".join(f"{limit:.0f}" for limit in limits) + ")"
            self.goals.append((f"{own}: {goal} at every resolution {where}", measured, ok))
        for dofs, goal in GOAL_SCALING:
            group = [r for r in rows if r["dofs"] == str(dofs)]
            ran = [r for r in rows if r["solver"] in SINGLE_LEVEL and r["refine"] in
                   {g["refine"] for g in group}]
            if not group or (scene != "trampoline" and not ran):
                continue
            singles = [r for r in group if r["solver"] in SINGLE_LEVEL and r["converged"] == "1"]
            best = min(singles, key=lambda r: number(r["wall_time"]), default=None)
            name = f"{own} ≥ {goal:g}× faster than the best single-level solver at {dofs:,} dofs"
            for solver in ("rmtr", own):
                r = find(group, solver=solver)
                t = number(r["wall_time"]) if r and r["converged"] == "1" else None
                if best and t:
                    ratio = number(best["wall_time"]) / t
                    solve, best_solve = number(r.get("solve_time")), number(best.get("solve_time"))
                    self.headline_group(
                        "single-level", "Time: RMTR against the fastest single-level solver",
                        "Compares the whole-run wall time (setup, solve, output) of an RMTR "
                        "configuration with the faster converged single-level solver at the "
                        "same resolution, `tr` (single-level trust region, Dogleg + MUMPS) or "
                        "`bnls-mumps` (TAO's line-search Newton + MUMPS): different solvers, "
                        "the same step and tolerance (see *RMTR at scale*). Ratio: the "
                        "single-level solver's time / RMTR's, for the whole run and for the "
                        "Solve stage alone (above 1: RMTR is faster).",
                        ["scene", "dofs", "RMTR", "single-level solver",
                         "whole-run time, single-level / RMTR",
                         "Solve-stage time, single-level / RMTR"]).append(
                        [scene, f"{dofs:,}", solver, best["solver"], f"{ratio:.2f}×",
                         f"{best_solve / solve:.2f}×" if solve and best_solve else ""])
                    if solver == own:
                        self.goals.append((f"{name} {where}", against(ratio, goal),
                                           ratio >= goal))
                elif solver == own:
                    self.goals.append((f"{name} {where}", "no converged run to compare"
                                       if best else "no single-level solver converged", False))

    # --- triangle hierarchies (issue 48) -------------------------------------------------------
    def triangle(self):
        rows = self.csv("triangle")
        if rows is None:
            return
        order = list(study_triangle.SOLVERS)
        solvers = sorted(dict.fromkeys(r["solver"] for r in rows),
                         key=lambda s: order.index(s) if s in order else len(order))
        self.add("## RMTR on triangle hierarchies\n\n" + measures(
                 "the V-cycles, wall time and peak memory of RMTR on paper 2's decimation "
                 "hierarchies of the triangle-mesh scenes, with each of its three coarse models, "
                 "as the resolution grows", "the single-level solvers `pnewton` (projected "
                 "Newton + MUMPS, the scenes' own) and `tr` (single-level TR + MUMPS) on the "
                 "same load steps") +
                 "The first load steps of each scene (`steps`; the drape has one), "
                 "\\|g\\| < 1e-7 on every step. Each cell: V-cycles (RMTR) or iterations, "
                 "summed over the steps · wall time of the whole run (setup, hierarchy, solve, "
                 "output) · peak resident memory of the largest rank. `rmtr-patch-dogleg`: "
                 "mlshell's default RMTR (`-tao_type rmtr`), Galerkin coarse models J_Pᵀ H J_P; "
                 "`rmtr-own`: first-order coarse models of each coarse mesh's own energy; "
                 "`rmtr-proxy`: first-order models of paper 2's proxy Ψ(P^l(x_l)). RMTR runs on "
                 f"`hierarchy: {{levels: L, ratio: {study_triangle.RATIO}}}` with the fewest "
                 f"levels whose coarsest has at most {study_triangle.COARSEST_VERTICES} "
                 "vertices; the single-level solvers run without the hierarchy. *Energy "
                 "spread*: the largest relative difference of the final total energies of the "
                 "converged runs (the same minimiser: round-off).\n")
        for scene in dict.fromkeys(r["scene"] for r in rows):
            mine = [r for r in rows if r["scene"] == scene]
            body = []
            # Coarse to fine (by dofs: an edge length falls as the resolution grows).
            dofs_of = {r["resolution"]: number(r["dofs"], 0.0) for r in mine}
            for resolution in sorted(dofs_of, key=dofs_of.get):
                group = [r for r in mine if r["resolution"] == resolution]
                dofs = next((r["dofs"] for r in group if r["dofs"]), "")
                levels = max((int(number(r["levels"], 1)) for r in group), default=1)
                line = [resolution, count(dofs), levels]
                for solver in solvers:
                    r = find(group, solver=solver)
                    line.append("not run" if r is None else outcome(r) if r["converged"] != "1"
                                else f"{outcome(r)} · {seconds(r['wall_time'])} s · "
                                     f"{count(r['peak_rss_mib'])} MiB")
                energies = [number(r["energy"]) for r in group
                            if r["converged"] == "1" and number(r["energy"]) is not None]
                scale = max((abs(e) for e in energies), default=0.0)
                line.append(f"{(max(energies) - min(energies)) / scale:.1e}"
                            if len(energies) > 1 and scale else "")
                body.append(line)
                self.triangle_headline(scene, dofs, group)
            steps = next((r["steps"] for r in mine if r["steps"]), "?")
            self.add(f"### {scene}: {study_triangle.MESH_KEY[scene]}, first {steps} "
                     "step(s)\n\n" + table([study_triangle.MESH_KEY[scene], "dofs", "levels"] +
                                            solvers + ["energy spread"], body))
            self.triangle_goals(scene, mine)
        self.image(plots.triangle(rows, self.out))

    def progressive(self):
        report_progressive.section(self, table, against, seconds)

    @staticmethod
    def fastest(rows, solvers):
        ok = [r for r in rows if r["solver"] in solvers and r["converged"] == "1"
              and number(r["wall_time"])]
        return min(ok, key=lambda r: number(r["wall_time"]), default=None)

    def triangle_headline(self, scene, dofs, group):
        """One headline row: the fastest RMTR coarse model against the fastest single-level
        solver at one resolution."""
        rm = self.fastest(group, study_triangle.RMTR)
        single = self.fastest(group, study_triangle.SINGLE_LEVEL)
        if not rm or not single:
            return
        self.headline_group(
            "triangle", "Time: RMTR on triangle hierarchies against the fastest single-level "
            "solver",
            "Compares the whole-run wall time of the fastest converged RMTR configuration on a "
            "triangle scene's decimation hierarchy (any of the three coarse models) with the "
            "fastest converged single-level solver (`pnewton`, `tr`; both factorise with MUMPS) "
            "on the same load steps and tolerance (see *RMTR on triangle hierarchies*). Ratio: "
            "single-level time / RMTR's (above 1: RMTR is faster).",
            ["scene", "dofs", "RMTR", "V-cycles", "single-level", "iterations",
             "time, single-level / RMTR"]).append(
            [scene, count(dofs), rm["solver"], count(rm["iterations"]), single["solver"],
             count(single["iterations"]),
             f"{number(single['wall_time']) / number(rm['wall_time']):.2f}×"])

    def triangle_goals(self, scene, rows):
        """Issue 48's goals for mlshell's default RMTR on one scene: V-cycles that do not grow,
        and its time against the fastest single-level solver at about 50k and 200k dofs."""
        own = DEFAULT_SOLVER
        runs = sorted((r for r in rows if r["solver"] == own and r["dofs"]),
                      key=lambda r: number(r["dofs"]))
        if len(runs) > 1:
            ok = all(r["converged"] == "1" for r in runs) and number(runs[-1]["iterations"]) \
                <= TRIANGLE_CYCLE_GROWTH * number(runs[0]["iterations"])
            self.goals.append((f"{own}: V-cycles do not grow with resolution ({scene}; at most "
                               f"{TRIANGLE_CYCLE_GROWTH:g}× from the coarsest to the finest)",
                               ", ".join(f"{outcome(r)} ({count(r['dofs'])})" for r in runs),
                               ok))
        for dofs, goal in GOAL_TRIANGLE:
            name = (f"{own} ≥ {goal:g}× faster than the best single-level solver at about "
                    f"{dofs:,} dofs ({scene})")
            near = [r for r in rows if number(r["dofs"]) and
                    dofs / TRIANGLE_DOFS_SPREAD <= number(r["dofs"]) <= dofs * TRIANGLE_DOFS_SPREAD]
            finest = max((number(r["dofs"]) for r in rows if number(r["dofs"])), default=0)
            if not near:
                self.goals.append((name, f"not measured in this run (finest: {finest:,.0f} "
                                   "dofs)", None))
                continue
            r = find(near, solver=own)
            single = self.fastest(near, study_triangle.SINGLE_LEVEL)
            if not r or r["converged"] != "1" or not single:
                self.goals.append((name, f"{own}: {outcome(r)}" if not single else
                                   "no single-level solver converged", False))
                continue
            ratio = number(single["wall_time"]) / number(r["wall_time"])
            self.goals.append((name, against(ratio, goal) + f" against {single['solver']} "
                               f"({count(r['dofs'])} dofs)", ratio >= goal))

    def reproduce(self):
        """The commands that filled this folder (meta.json), with their dates and builds."""
        runs = self.meta.get("runs", [])
        listed = "".join(f"- `{r['command']}` ({r['date']}, {r['elapsed']:.0f} s"
                         + (f", build {r['build']}" if r.get("build") else "") + ")\n"
                         for r in runs) or "No meta.json: the commands were not recorded.\n"
        return ("## Reproduce\n\nEach command added its studies' CSV files to this folder "
                "(a later run's rows replace the same cases' rows), with its date, its "
                "duration and, where recorded, the mlshell build that ran it; "
                "[Provenance](#provenance) gives the build of every row. "
                "`examples/studies/studies.py --report-only --out DIR` redraws this report "
                "from DIR's CSV files.\n\n" + listed)

    def provenance(self):
        """Which mlshell build measured each CSV's rows (their PROVENANCE column)."""
        body = []
        for path in sorted(self.out.glob("*.csv")):
            rows = read_csv(path)
            builds = {}
            for r in rows:
                build = r.get(PROVENANCE) or "not recorded"
                builds[build] = builds.get(build, 0) + 1
            listed = sorted(builds.items(), key=lambda b: (b[0] == "not recorded", -b[1]))
            body.append([path.name, len(rows), ", ".join(f"{b} ({n})" for b, n in listed)])
        if not body:
            return None
        return ("## Provenance\n\nThe mlshell build (`mlshell --version`, `summary.json` "
                "`build.commit`; `-modified`: with uncommitted changes) that measured each "
                "file's rows, with their number. Rows from before 2026-12-05 did not record "
                "it; [Reproduce](#reproduce) lists the commands and dates.\n\n" +
                table(["file", "rows", "builds (rows)"], body))

    def introduction(self):
        """The title and what the studies are: the two sentences before the headline."""
        m = self.meta
        where = (f"Measured in {m['mode']} mode on {m.get('ranks', '?')} MPI ranks of a "
                 f"{m.get('cores', '?')}-core machine" if m.get("mode") else
                 "Mode, ranks and cores were not recorded (no meta.json)")
        return ("# mlshell convergence studies\n\n"
                "mlshell's RMTR (recursive multilevel trust region) solver on the paper's four "
                "cloth scenes, compared with the paper's tables and figures "
                "(rmtr-subdivision-cloth §7) and with single-level solvers (single-level TR, "
                f"PETSc's TAO and SNES Newton solvers). {where}; the commands, dates and builds "
                "are at the end ([Reproduce](#reproduce), [Provenance](#provenance)).\n")

    def headline_text(self):
        groups = sorted((g for g in self.headline.items() if g[1]["rows"]),
                        key=lambda g: HEADLINE_ORDER.index(g[0]) if g[0] in HEADLINE_ORDER
                        else len(HEADLINE_ORDER))
        if not groups:
            return "## Headline\n\nNo study produced a headline figure.\n"
        return "## Headline\n\n" + "\n".join(
            f"### {g['title']}\n\n{g['compares']}\n\n" + table(g["header"], g["rows"])
            for _, g in groups)

    def write(self):
        for study in (self.iterations, self.work, self.projection, self.condition,
                      self.timestep, self.accuracy, self.peers, self.parallel, self.scaling,
                      self.triangle, self.progressive):
            study()
        # ok None: a goal this folder has no measurement for (neither met nor missed).
        goals = [[g, v, "" if ok is None else "met" if ok else "**not met**"]
                 for g, v, ok in self.goals]
        if not any("PETSc" in g for g, _, _ in self.goals):
            goals.append([f"RMTR ≥ {GOAL_SPEEDUP_PEERS:g}× faster than the best PETSc solver at "
                          f"{GOAL_DOFS:,} dofs", "not measured in this run", ""])
        if not any("ranks" in g for g, _, _ in self.goals):
            goals.append([f"2 ranks ≥ {GOAL_SPEEDUP_RANKS}× faster than 1 at {GOAL_DOFS:,} dofs",
                          "not measured in this run", ""])
        # First what the studies are and what they found; the studies; last how the folder
        # was filled (commands, builds), which a reader of the results needs least.
        head = [self.introduction(), self.headline_text(),
                "## Performance goals\n\n" + table(["goal", "measured", ""], goals)]
        tail = [part for part in (self.reproduce(), self.provenance()) if part]
        text = "\n".join(head + self.parts + tail)
        tmp = self.out / "REPORT.md.tmp"
        tmp.write_text(text)
        tmp.replace(self.out / "REPORT.md")
        return self.out / "REPORT.md"


def main(argv):
    if len(argv) != 2 or not Path(argv[1]).is_dir():
        sys.exit(__doc__.strip().splitlines()[-1] if len(argv) != 2 else
                 f"report.py: error: '{argv[1]}' is not a folder")
    print(f"wrote {Report(argv[1]).write()}")


if __name__ == "__main__":
    main(sys.argv)
