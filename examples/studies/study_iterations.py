"""Tables 3, 4 and 5: single-level TR iterations vs dofs, and RMTR V-cycles vs number of
levels (the finest level has refine = levels - 1), one step of dt = 1 from rest, on 2 ranks."""
from runner import SCENES, solver_fields
from solvers import with_tolerance

NAME = "iterations"
COLUMNS = ["scene", "solver", "levels", "refine", "dofs", "ranks", "iterations", "converged",
           "reason", "gradient_norm", "wall_time", "solve_time"]


def tr_solve(ctx, scene, refine):
    """Single-level TR (Dogleg) on one step at dt = 1, tolerance (7.1)."""
    return ctx.run(NAME, f"{scene}-tr-r{refine}", scene, refine,
                   with_tolerance("tr", ctx.source, 1e-7, ctx.pick(300, 100000)))


def rmtr_solve(ctx, scene, levels, refine=None):
    """RMTR on `levels` levels, finest refine = levels - 1 unless given."""
    refine = levels - 1 if refine is None else refine
    return ctx.run(NAME, f"{scene}-rmtr-l{levels}-r{refine}", scene, refine,
                   with_tolerance("rmtr", ctx.source, 1e-7, ctx.pick(300, 20000))
                   + ["-tao_rmtr_levels", str(levels)])


def run(ctx):
    rows = []
    for scene in ctx.scenes(SCENES, SCENES):
        for refine in ctx.pick((0, 1), (0, 1, 2, 3, 4, 5)):
            rows.append({**solver_fields(tr_solve(ctx, scene, refine)), "solver": "tr",
                         "levels": 1})
        for levels in ctx.pick((2,), (2, 3, 4, 5, 6)):
            rows.append({**solver_fields(rmtr_solve(ctx, scene, levels)), "solver": "rmtr",
                         "levels": levels})
    ctx.write_csv(NAME, rows, COLUMNS)
