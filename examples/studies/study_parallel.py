"""The same RMTR solve on 1 and 2 ranks: speedup, and the time split by -log_view stage
(Setup, Solve, Output) with the costliest events of the Solve stage. RMTR with Dogleg smoothing
(the default) on every scene, and the factorisation-free configuration (full-multigrid start,
vertex-patch smoothing) on the trampoline, the scene it converges on."""
from runner import solver_fields
from solvers import with_tolerance

NAME = "parallel"
COLUMNS = ["scene", "solver", "refine", "dofs", "ranks", "iterations", "converged", "reason",
           "wall_time", "solve_time", "stage_setup", "stage_solve", "stage_output"]
EVENT_COLUMNS = ["scene", "solver", "refine", "ranks", "event", "time"]
TOP_EVENTS = 12
SOLVERS = ("rmtr", "rmtr-patch")


def run(ctx):
    rows, events = [], []
    for scene in ctx.scenes(("trampoline",), ("trampoline", "drooping")):
        for solver in ctx.solvers(SOLVERS):
            # The patch smoother does not converge on the free-hanging scenes (README).
            if solver != "rmtr" and scene != "trampoline":
                continue
            for refine in ctx.pick((2,), (4, 5)):
                for ranks in (1, 2):
                    r = ctx.run(NAME, f"{scene}-r{refine}-{solver}-n{ranks}", scene, refine,
                                with_tolerance(solver, ctx.source, 1e-7, ctx.pick(300, 1000)),
                                ranks=ranks, log_view=True)
                    log = r.get("log", {"stages": {}, "events": {}})
                    st = log["stages"]
                    rows.append({**solver_fields(r), "solver": solver,
                                 "stage_setup": st.get("Setup", ""),
                                 "stage_solve": st.get("Solve", ""),
                                 "stage_output": st.get("Output", "")})
                    solve = sorted(log["events"].get("Solve", {}).items(), key=lambda e: -e[1])
                    for event, t in solve[:TOP_EVENTS]:
                        events.append({"scene": scene, "solver": solver, "refine": refine,
                                       "ranks": ranks, "event": event, "time": t})
    ctx.write_csv(NAME, rows, COLUMNS, key=("scene", "solver"))
    ctx.write_csv("parallel_events", events, EVENT_COLUMNS, key=("scene", "solver"))
