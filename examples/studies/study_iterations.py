"""Tables 3, 4 and 5: single-level TR iterations vs dofs, and RMTR V-cycles vs number of
levels (the finest level has refine = levels - 1), one step of dt = 1 from rest, on 2 ranks,
for the default `denim` preset and (full mode) Table 1 as printed (`denim-table1`), with the
elastic energy each solve ends with."""
from runner import PRESETS, SCENES, preset_tag, scene_text, solver_fields
from solvers import with_tolerance

NAME = "iterations"
COLUMNS = ["scene", "preset", "solver", "levels", "refine", "dofs", "ranks", "iterations",
           "converged", "reason", "gradient_norm", "energy_elastic", "wall_time", "solve_time"]


def tr_solve(ctx, scene, refine, preset="denim"):
    """Single-level TR (Dogleg) on one step at dt = 1, tolerance (7.1)."""
    tag = f"{scene}-tr-r{refine}" + preset_tag(preset)
    return ctx.run(NAME, tag, scene, refine,
                   with_tolerance("tr", ctx.source, 1e-7, ctx.pick(300, 100000)),
                   scene_text=scene_text(scene, preset))


def rmtr_solve(ctx, scene, levels, refine=None, preset="denim"):
    """RMTR on `levels` levels, finest refine = levels - 1 unless given."""
    refine = levels - 1 if refine is None else refine
    tag = f"{scene}-rmtr-l{levels}-r{refine}" + preset_tag(preset)
    return ctx.run(NAME, tag, scene, refine,
                   with_tolerance("rmtr", ctx.source, 1e-7, ctx.pick(300, 20000))
                   + ["-tao_rmtr_levels", str(levels)], scene_text=scene_text(scene, preset))


def elastic(result):
    s = result["summary"]
    return s["energy"].get("elastic", "") if s else ""


def run(ctx):
    rows = []
    for scene in ctx.scenes(SCENES, SCENES):
        for preset in ctx.pick(PRESETS[:1], PRESETS):
            for refine in ctx.pick((0, 1), (0, 1, 2, 3, 4, 5)):
                r = tr_solve(ctx, scene, refine, preset)
                rows.append({**solver_fields(r), "solver": "tr", "levels": 1, "preset": preset,
                             "energy_elastic": elastic(r)})
            for levels in ctx.pick((2,), (2, 3, 4, 5, 6)):
                r = rmtr_solve(ctx, scene, levels, preset=preset)
                rows.append({**solver_fields(r), "solver": "rmtr", "levels": levels,
                             "preset": preset, "energy_elastic": elastic(r)})
    ctx.write_csv(NAME, rows, COLUMNS)
