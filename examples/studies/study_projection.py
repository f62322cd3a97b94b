"""Table 8: RMTR V-cycles with the reverse-subdivision projection (5.19) vs the least-squares
fit (5.18), 3,675 dofs and four levels."""
from runner import SCENES, solver_fields
from solvers import with_tolerance

NAME = "projection"
COLUMNS = ["scene", "projection", "levels", "dofs", "iterations", "converged", "reason",
           "gradient_norm", "wall_time"]


def run(ctx):
    refine, levels = ctx.pick((1, 2), (3, 4))
    max_it = ctx.pick(300, 20000)
    rows = []
    for scene in ctx.scenes(("trampoline",), SCENES):
        for projection in ("lsq", "reverse"):
            r = ctx.run(NAME, f"{scene}-{projection}", scene, refine,
                        with_tolerance("rmtr", ctx.source, 1e-7, max_it)
                        + ["-tao_rmtr_levels", str(levels), "-tao_rmtr_projection", projection])
            rows.append({**solver_fields(r), "projection": projection, "levels": levels})
    ctx.write_csv(NAME, rows, COLUMNS)
