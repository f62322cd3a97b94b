"""Tables 3, 4 and 5: single-level TR iterations vs dofs, and RMTR V-cycles vs number of
levels (the finest level has refine = levels - 1), one step of dt = 1 from rest, on 2 ranks,
for the default `denim` preset and (full mode) Table 1 as printed (`denim-table1`), with the
elastic energy each solve ends with. RMTR runs factorised Dogleg smoothing (`rmtr`) and
mlshell's default (`rmtr-patch-dogleg`); --solvers picks among tr and those. Every solve stops
at the paper's test (7.1), ‖g‖ < 1e-7, with no relative test (the drape's prescribed corners
start it at ‖g₀‖ > 10⁵)."""
from runner import PRESETS, SCENES, preset_tag, scene_text, solver_fields
from solvers import DEFAULT_SOLVER, with_tolerance

NAME = "iterations"
RMTR_SOLVERS = ("rmtr", DEFAULT_SOLVER)
COLUMNS = ["scene", "preset", "solver", "levels", "refine", "dofs", "ranks", "iterations",
           "converged", "reason", "gradient_norm", "energy_elastic", "wall_time", "solve_time"]


def tr_solve(ctx, scene, refine, preset="denim"):
    """Single-level TR (Dogleg) on one step at dt = 1, tolerance (7.1)."""
    tag = f"{scene}-tr-r{refine}" + preset_tag(preset)
    return ctx.run(NAME, tag, scene, refine,
                   with_tolerance("tr", ctx.source, 1e-7, ctx.pick(300, 100000), relative=False),
                   scene_text=scene_text(scene, preset))


def rmtr_solve(ctx, scene, levels, refine=None, preset="denim", solver="rmtr"):
    """RMTR (`solver`, one of RMTR_SOLVERS) on `levels` levels, finest refine = levels - 1
    unless given."""
    refine = levels - 1 if refine is None else refine
    tag = f"{scene}-{solver}-l{levels}-r{refine}" + preset_tag(preset)
    return ctx.run(NAME, tag, scene, refine,
                   with_tolerance(solver, ctx.source, 1e-7, ctx.pick(300, 20000), relative=False)
                   + ["-tao_rmtr_levels", str(levels)], scene_text=scene_text(scene, preset))


def elastic(result):
    s = result["summary"]
    return s["energy"].get("elastic", "") if s else ""


def run(ctx):
    rows = []
    for scene in ctx.scenes(SCENES, SCENES):
        for preset in ctx.pick(PRESETS[:1], PRESETS):
            for refine in ctx.pick((0, 1), (0, 1, 2, 3, 4, 5)) if ctx.solvers(["tr"]) else ():
                r = tr_solve(ctx, scene, refine, preset)
                rows.append({**solver_fields(r), "solver": "tr", "levels": 1, "preset": preset,
                             "energy_elastic": elastic(r)})
            for solver in ctx.solvers(RMTR_SOLVERS):
                for levels in ctx.pick((2,), (2, 3, 4, 5, 6)):
                    r = rmtr_solve(ctx, scene, levels, preset=preset, solver=solver)
                    rows.append({**solver_fields(r), "solver": solver, "levels": levels,
                                 "preset": preset, "energy_elastic": elastic(r)})
    ctx.write_csv(NAME, rows, COLUMNS, key=("scene", "solver"))
