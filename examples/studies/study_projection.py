"""Table 8: RMTR V-cycles with the reverse-subdivision projection (5.19) vs the least-squares
fit (5.18), for both denim presets (full mode). The paper's resolution is 3,675 dofs on four
levels; a scene is solved at the finest of that and --max-refine (levels = refine + 1), and the
re-entrant corner one refinement lower (its finer cage gives comparable dofs)."""
from runner import PRESETS, SCENES, comparable_refine, preset_tag, scene_text, solver_fields
from solvers import with_tolerance

NAME = "projection"
COLUMNS = ["scene", "preset", "projection", "levels", "refine", "dofs", "iterations",
           "converged", "reason", "gradient_norm", "wall_time"]


def run(ctx):
    max_it = ctx.pick(300, 20000)
    rows = []
    for scene in ctx.scenes(("trampoline",), SCENES):
        refine = comparable_refine(scene, min(ctx.pick(1, 3), ctx.runner.finest(scene)))
        levels = refine + 1
        for preset in ctx.pick(PRESETS[:1], PRESETS):
            for projection in ("lsq", "reverse"):
                r = ctx.run(NAME, f"{scene}-{projection}-r{refine}" + preset_tag(preset), scene,
                            refine, with_tolerance("rmtr", ctx.source, 1e-7, max_it)
                            + ["-tao_rmtr_levels", str(levels), "-tao_rmtr_projection",
                               projection], scene_text=scene_text(scene, preset))
                rows.append({**solver_fields(r), "projection": projection, "levels": levels,
                             "preset": preset})
    ctx.write_csv(NAME, rows, COLUMNS)
