"""Accuracy against time (the users' request): for each scene, the error of the probe
displacement and of the limit surface against wall time, for every resolution and solver
tolerance, RMTR and PETSc's solvers on one plot — a Pareto front to choose resolution and
tolerance for a budget.

The reference is the same step solved by RMTR two levels finer than the finest resolution
studied. The limit-surface error is the L2 distance of the displacement fields over the
reference configuration, by the trapezoidal rule on the reference level's elements: both runs
write the limit surface at the corners of the reference elements (-mlshell_limit_csv, 2^d
samples per element edge on a level d refinements coarser), which are the same parametric
points on every level because Catmull-Clark refinement is nested."""
import csv
import math

from runner import SCENES, converged, solver_fields
from solvers import with_tolerance

NAME = "accuracy"
COLUMNS = ["scene", "solver", "refine", "levels", "dofs", "tolerance", "iterations", "converged",
           "reason", "gradient_norm", "wall_time", "solve_time", "probe", "probe_error",
           "l2_error", "reference_dofs", "reference_gradient_norm"]


def read_limit_surface(path):
    """Rows of limit_surface.csv as (reference point, displacement) pairs."""
    with open(path, newline="") as f:
        return [((float(r["X"]), float(r["Y"]), float(r["Z"])),
                 (float(r["ux"]), float(r["uy"]), float(r["uz"]))) for r in csv.DictReader(f)]


def _key(point):
    return tuple(round(c, 9) for c in point)


def l2_distance(coarse_rows, reference_rows):
    """L2 distance of two displacement fields: the trapezoidal rule on the reference elements
    (each consecutive four rows of `reference_rows`: corners (0,0), (1,0), (0,1), (1,1))."""
    coarse = {_key(p): u for p, u in coarse_rows}
    total = 0.0
    for e in range(0, len(reference_rows), 4):
        corners = reference_rows[e:e + 4]
        (a, _), (b, _), (d, _), (c, _) = corners
        ac = [c[i] - a[i] for i in range(3)]
        bd = [d[i] - b[i] for i in range(3)]
        cross = (ac[1] * bd[2] - ac[2] * bd[1], ac[2] * bd[0] - ac[0] * bd[2],
                 ac[0] * bd[1] - ac[1] * bd[0])
        area = 0.5 * math.sqrt(sum(x * x for x in cross))
        for p, u_ref in corners:
            u = coarse.get(_key(p))
            if u is None:
                raise RuntimeError(f"limit-surface point {p} of the reference has no match")
            total += area / 4 * sum((u[i] - u_ref[i]) ** 2 for i in range(3))
    return math.sqrt(total)


def probe_displacement(summary):
    name, probe = next(iter(summary["probes"].items()))
    return name, probe["displacement"]


def run(ctx):
    refines = ctx.pick((0, 1), (1, 2, 3))
    tolerances = ctx.pick((1e-3, 1e-5), (1e-3, 1e-4, 1e-5, 1e-6, 1e-7))
    solvers = ctx.pick(("rmtr", "bntr-mumps"),
                       ("rmtr", "tr", "bntr-mumps", "bnls-mumps", "bntr-gamg", "snes-mumps",
                        "snes-boomeramg"))
    reference_refine = max(refines) + 2
    rows = []
    for scene in ctx.scenes(("trampoline",), SCENES):
        ref = ctx.run(NAME, f"{scene}-reference-r{reference_refine}", scene, reference_refine,
                      with_tolerance("rmtr", ctx.source, 1e-7, ctx.pick(300, 20000))
                      + ["-mlshell_limit_csv", "1"])
        s = ref["summary"]
        # A reference stopped at the limiting gradient (a few 1e-7) is still far more accurate
        # than the runs it judges; one that stopped far from a minimiser is not used.
        if not s or s["gradient_norm"] > 1e-5:
            print(f"  [{NAME}] {scene}: the reference did not converge; no accuracy rows")
            continue
        reference_rows = read_limit_surface(ref["folder"] / "limit_surface.csv")
        probe, u_ref = probe_displacement(s)
        for solver in solvers:
            for refine in refines:
                for tol in tolerances:
                    samples = 2 ** (reference_refine - refine)
                    r = ctx.run(NAME, f"{scene}-{solver}-r{refine}-tol{tol:g}", scene, refine,
                                with_tolerance(solver, ctx.source, tol, ctx.pick(300, 5000))
                                + ["-mlshell_limit_csv", str(samples)])
                    row = {**solver_fields(r), "solver": solver, "tolerance": tol,
                           "levels": refine + 1 if solver == "rmtr" else 1,
                           "reference_dofs": s["dofs"],
                           "reference_gradient_norm": s["gradient_norm"], "probe": probe}
                    if converged(r):
                        _, u = probe_displacement(r["summary"])
                        row["probe_error"] = math.dist(u, u_ref)
                        row["l2_error"] = l2_distance(
                            read_limit_surface(r["folder"] / "limit_surface.csv"),
                            reference_rows)
                    rows.append(row)
    ctx.write_csv(NAME, rows, COLUMNS)
