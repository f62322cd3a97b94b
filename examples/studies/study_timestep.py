"""Figure 10: which solvers converge for one step of size dt in 1/24 ... 1 s from rest, at 1,083
dofs (the re-entrant corner: 1,479), for both denim presets (full mode); the report shows the
largest dt each one converges at."""
from runner import PRESETS, SCENES, comparable_refine, preset_tag, scene_text, solver_fields
from solvers import with_tolerance

NAME = "timestep"
COLUMNS = ["scene", "preset", "solver", "dt", "dofs", "iterations", "converged", "reason",
           "gradient_norm", "wall_time"]
SOLVERS = ("rmtr", "tr", "bnls-mumps", "dampednewton", "linearized")
TIMESTEPS = ((24, 1 / 24), (12, 1 / 12), (6, 1 / 6), (3, 1 / 3), (2, 1 / 2), (1, 1.0))


def run(ctx):
    steps = ctx.pick((TIMESTEPS[0], TIMESTEPS[-1]), TIMESTEPS)
    rows = []
    for scene in ctx.scenes(("trampoline",), SCENES):
        refine = comparable_refine(scene, ctx.pick(1, 2))
        for preset in ctx.pick(PRESETS[:1], PRESETS):
            for solver in SOLVERS:
                max_it = 100000 if solver == "tr" else 1000
                for inverse, dt in steps:
                    r = ctx.run(NAME, f"{scene}-{solver}-dt1_{inverse}" + preset_tag(preset),
                                scene, refine,
                                with_tolerance(solver, ctx.source, 1e-7, ctx.pick(300, max_it)),
                                dt=dt, scene_text=scene_text(scene, preset))
                    rows.append({**solver_fields(r), "solver": solver, "dt": dt,
                                 "preset": preset})
    ctx.write_csv(NAME, rows, COLUMNS)
