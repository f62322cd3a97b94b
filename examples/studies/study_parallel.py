"""The same RMTR solve on 1 and 2 ranks: speedup, and the time split by -log_view stage
(Setup, Solve, Output) with the costliest events of the Solve stage. RMTR with Dogleg smoothing
(the default) and with inexact Newton points from vertex-patch-preconditioned CG
(rmtr-patch-dogleg, no factorisation above the coarsest level) on every scene, and vertex-patch
ST-CG smoothing after a full-multigrid start (rmtr-patch) on the trampoline, the scene it
converges on. Two copies of the 1-rank
run started together measure what sharing the machine's memory bandwidth and caches costs one
core: 2 × (1-rank wall) / (a shared copy's wall) is the most 2 ranks can gain on this machine.
The full mode runs each pair (1 rank, 2 ranks, the shared copies) three times in turn and keeps
each one's fastest run: a wall time on a shared machine only ever gains noise, so the least of
three is the measurement and the slowest shows the spread."""
from runner import PROVENANCE, solver_fields
from solvers import with_tolerance

NAME = "parallel"
COLUMNS = ["scene", "solver", "refine", "dofs", "ranks", "iterations", "converged", "reason",
           "wall_time", "solve_time", "stage_setup", "stage_solve", "stage_output",
           "shared_wall_time", "shared_solve_time", "runs", "slowest_wall_time"]
EVENT_COLUMNS = ["scene", "solver", "refine", "ranks", "event", "time"]
TOP_EVENTS = 12
REPEATS = (1, 3)  # quick, full: how many times each pair of runs is made
SOLVERS = ("rmtr", "rmtr-patch", "rmtr-patch-dogleg")


def run(ctx):
    rows, events = [], []
    for scene in ctx.scenes(("trampoline",), ("trampoline", "drooping")):
        for solver in ctx.solvers(SOLVERS):
            # rmtr-patch's one V-cycle per level in the start does not converge on the
            # free-hanging scenes (docs/solvers.md); they need rmtr-patch-galerkin.
            if solver == "rmtr-patch" and scene != "trampoline":
                continue
            options = with_tolerance(solver, ctx.source, 1e-7, ctx.pick(300, 1000))
            for refine in ctx.pick((2,), (4, 5)):
                runs, shares = {1: [], 2: []}, []
                for k in range(ctx.pick(*REPEATS)):
                    again = f"-run{k + 1}" if k else ""
                    for ranks in (1, 2):
                        # The first run of each is shared with other studies (ctx.run remembers
                        # it); the repeats must run again.
                        go = ctx.run if k == 0 else ctx.runner.run
                        runs[ranks].append(go(NAME, f"{scene}-r{refine}-{solver}-n{ranks}{again}",
                                              scene, refine, options, ranks=ranks, log_view=True))
                    shares.append(shared(ctx, f"{scene}-r{refine}-{solver}-n1-shared{again}",
                                         scene, refine, options))
                for ranks in (1, 2):
                    r = fastest(runs[ranks])
                    log = r.get("log", {"stages": {}, "events": {}})
                    st = log["stages"]
                    walls = [w for w in map(wall, runs[ranks]) if w is not None]
                    row = {**solver_fields(r), "solver": solver,
                           "stage_setup": st.get("Setup", ""),
                           "stage_solve": st.get("Solve", ""),
                           "stage_output": st.get("Output", ""),
                           "runs": len(walls), "slowest_wall_time": max(walls, default="")}
                    if ranks == 1:
                        row.update(min((s for s in shares if s),
                                       key=lambda s: s["shared_wall_time"], default={}))
                    rows.append(row)
                    solve = sorted(log["events"].get("Solve", {}).items(), key=lambda e: -e[1])
                    for event, t in solve[:TOP_EVENTS]:
                        events.append({"scene": scene, "solver": solver, "refine": refine,
                                       "ranks": ranks, "event": event, "time": t,
                                       PROVENANCE: row[PROVENANCE]})
    ctx.write_csv(NAME, rows, COLUMNS, key=("scene", "solver"))
    ctx.write_csv("parallel_events", events, EVENT_COLUMNS, key=("scene", "solver"))


def wall(result):
    """A converged run's wall time, else None."""
    f = solver_fields(result)
    return f["wall_time"] if f["converged"] else None


def fastest(results):
    """The converged run with the least wall time (the first run if none converged)."""
    done = [r for r in results if wall(r) is not None]
    return min(done, key=wall) if done else results[0]


def shared(ctx, tag, scene, refine, options):
    """The 1-rank run twice at once: the mean wall and solve times of the two copies (empty
    unless both converged)."""
    copies = ctx.runner.run_copies(NAME, tag, scene, refine, options, ranks=1, copies=2)
    fields = [solver_fields(c) for c in copies]
    if not all(f["converged"] for f in fields):
        return {}
    return {"shared_wall_time": sum(f["wall_time"] for f in fields) / len(fields),
            "shared_solve_time": sum(f["solve_time"] for f in fields) / len(fields)}
