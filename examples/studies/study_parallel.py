"""The same RMTR solve on 1 and 2 ranks: speedup, and the time split by -log_view stage
(Setup, Solve, Output) with the costliest events of the Solve stage. RMTR with Dogleg smoothing
(the default) and with inexact Newton points from vertex-patch-preconditioned CG
(rmtr-patch-dogleg, no factorisation above the coarsest level) on every scene, and vertex-patch
ST-CG smoothing after a full-multigrid start (rmtr-patch) on the trampoline, the scene it
converges on. Two copies of the 1-rank
run started together measure what sharing the machine's memory bandwidth and caches costs one
core: 2 × (1-rank wall) / (a shared copy's wall) is the most 2 ranks can gain on this machine."""
from runner import PROVENANCE, solver_fields
from solvers import with_tolerance

NAME = "parallel"
COLUMNS = ["scene", "solver", "refine", "dofs", "ranks", "iterations", "converged", "reason",
           "wall_time", "solve_time", "stage_setup", "stage_solve", "stage_output",
           "shared_wall_time", "shared_solve_time"]
EVENT_COLUMNS = ["scene", "solver", "refine", "ranks", "event", "time"]
TOP_EVENTS = 12
SOLVERS = ("rmtr", "rmtr-patch", "rmtr-patch-dogleg")


def run(ctx):
    rows, events = [], []
    for scene in ctx.scenes(("trampoline",), ("trampoline", "drooping")):
        for solver in ctx.solvers(SOLVERS):
            # rmtr-patch's one V-cycle per level in the start does not converge on the
            # free-hanging scenes (README); they need rmtr-patch-galerkin.
            if solver == "rmtr-patch" and scene != "trampoline":
                continue
            options = with_tolerance(solver, ctx.source, 1e-7, ctx.pick(300, 1000))
            for refine in ctx.pick((2,), (4, 5)):
                for ranks in (1, 2):
                    r = ctx.run(NAME, f"{scene}-r{refine}-{solver}-n{ranks}", scene, refine,
                                options, ranks=ranks, log_view=True)
                    log = r.get("log", {"stages": {}, "events": {}})
                    st = log["stages"]
                    row = {**solver_fields(r), "solver": solver,
                           "stage_setup": st.get("Setup", ""),
                           "stage_solve": st.get("Solve", ""),
                           "stage_output": st.get("Output", "")}
                    if ranks == 1:
                        row.update(shared(ctx, f"{scene}-r{refine}-{solver}-n1-shared", scene,
                                          refine, options))
                    rows.append(row)
                    solve = sorted(log["events"].get("Solve", {}).items(), key=lambda e: -e[1])
                    for event, t in solve[:TOP_EVENTS]:
                        events.append({"scene": scene, "solver": solver, "refine": refine,
                                       "ranks": ranks, "event": event, "time": t,
                                       PROVENANCE: row[PROVENANCE]})
    ctx.write_csv(NAME, rows, COLUMNS, key=("scene", "solver"))
    ctx.write_csv("parallel_events", events, EVENT_COLUMNS, key=("scene", "solver"))


def shared(ctx, tag, scene, refine, options):
    """The 1-rank run twice at once: the mean wall and solve times of the two copies (empty
    unless both converged)."""
    copies = ctx.runner.run_copies(NAME, tag, scene, refine, options, ranks=1, copies=2)
    fields = [solver_fields(c) for c in copies]
    if not all(f["converged"] for f in fields):
        return {}
    return {"shared_wall_time": sum(f["wall_time"] for f in fields) / len(fields),
            "shared_solve_time": sum(f["solve_time"] for f in fields) / len(fields)}
