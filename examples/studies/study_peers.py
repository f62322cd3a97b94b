"""RMTR against PETSc's own Newton-Krylov solvers on the same step (dt = 1) in the same run:
wall time, iterations and linear iterations of factorised Dogleg smoothing (rmtr.yaml), of the
scene's own configuration (rmtr-patch on the trampoline) and of the peers; the report gives ratios
to the scene's own configuration."""
from runner import SCENES, solver_fields
from solvers import PEERS, scene_solver, with_tolerance

NAME = "peers"
COLUMNS = ["scene", "solver", "refine", "dofs", "ranks", "iterations", "linear_iterations",
           "converged", "reason", "gradient_norm", "wall_time", "solve_time"]


def run(ctx):
    rows = []
    for scene in ctx.scenes(("trampoline",), SCENES):
        for refine in ctx.pick((1,), (4, 5)):
            for solver in dict.fromkeys(["rmtr", scene_solver(scene)] + PEERS):
                r = ctx.run(NAME, f"{scene}-r{refine}-{solver}", scene, refine,
                            with_tolerance(solver, ctx.source, 1e-7, ctx.pick(300, 1000)))
                rows.append({**solver_fields(r), "solver": solver})
    ctx.write_csv(NAME, rows, COLUMNS)
