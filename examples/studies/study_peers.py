"""RMTR against PETSc's own Newton-Krylov solvers on the same step (dt = 1) in the same run:
wall time, iterations and linear iterations; the report gives ratios to RMTR."""
from runner import SCENES, solver_fields
from solvers import PEERS, with_tolerance

NAME = "peers"
COLUMNS = ["scene", "solver", "refine", "dofs", "ranks", "iterations", "linear_iterations",
           "converged", "reason", "gradient_norm", "wall_time", "solve_time"]


def run(ctx):
    rows = []
    for scene in ctx.scenes(("trampoline",), SCENES):
        for refine in ctx.pick((1,), (4, 5)):
            for solver in ["rmtr"] + PEERS:
                r = ctx.run(NAME, f"{scene}-r{refine}-{solver}", scene, refine,
                            with_tolerance(solver, ctx.source, 1e-7, ctx.pick(300, 1000)))
                rows.append({**solver_fields(r), "solver": solver})
    ctx.write_csv(NAME, rows, COLUMNS)
