"""RMTR at scale: V-cycles (or iterations), solve time and peak memory against resolution for
RMTR with Dogleg smoothing (a factorisation of each level's Hessian per smoothing step, rmtr.yaml,
mlshell's default until 2026-12-05), with vertex-patch-preconditioned ST-CG smoothing (no
factorisation above the coarsest level) after a full-multigrid start and without it, each of the
two also with Galerkin coarse models (rmtr-galerkin; rmtr-patch-galerkin, which solves the
coarser levels in the start), Dogleg smoothing with inexact Newton points from
patch-preconditioned CG (rmtr-patch-dogleg, mlshell's default: no factorisation above the
coarsest level either), with the paper's plain ST-CG, and for the
single-level solvers they must beat (TR with Dogleg + MUMPS, TAO bnls + MUMPS). One step of
dt = 1 on the trampoline, and in full mode on the free-hanging drooping cloth, re-entrant
corner and drape. A configuration that times out at one resolution is not run at the
finer ones, nor one whose peak memory, grown by MEMORY_GROWTH, would not fit in
MEMORY_HEADROOM of the memory available now (the factorising solvers at 795,675 dofs on a 24 GiB
machine)."""
from runner import solver_fields
from solvers import with_tolerance

NAME = "scaling"
COLUMNS = ["scene", "solver", "refine", "dofs", "ranks", "iterations", "converged", "reason",
           "gradient_norm", "wall_time", "solve_time", "peak_rss_mib"]
SOLVERS = ("rmtr", "rmtr-galerkin", "rmtr-patch", "rmtr-patch-galerkin", "rmtr-patch-dogleg",
           "rmtr-patch-vcycles", "rmtr-paper", "tr", "bnls-mumps")
SINGLE_LEVEL = ("tr", "bnls-mumps")
# Growth of the peak memory per refinement (4× the dofs), measured from 51,483 to 201,243
# dofs (rounded up): bnls 4.2×, TR 5.8×, Dogleg-smoothed RMTR 6.0×, patch-smoothed RMTR 3.7×.
MEMORY_GROWTH = {"rmtr": 6.0, "tr": 6.0, "bnls-mumps": 4.5}
MEMORY_GROWTH_OTHERS = 4.0
# The share of the available memory a run may be predicted to need: a prediction that close to
# the machine's memory has no room for its own error, and a run past the memory meets the OOM
# killer (bnls + MUMPS at 795,675 dofs, predicted 22.7 GiB of 23 GiB available, held 21 GiB and
# was still growing when it was stopped, 2026-12-05).
MEMORY_HEADROOM = 0.85


def available_mib():
    """MemAvailable of /proc/meminfo in MiB (None where there is none)."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return None


def too_big(solver, previous_peak_mib, ranks, available):
    """Why a run of `solver` whose previous resolution peaked at `previous_peak_mib` per rank is
    not started (None: start it)."""
    if not previous_peak_mib or available is None:
        return None
    growth = MEMORY_GROWTH.get(solver, MEMORY_GROWTH_OTHERS)
    predicted = growth * float(previous_peak_mib) * ranks
    if predicted <= MEMORY_HEADROOM * available:
        return None
    return (f"not run (predicted {predicted / 1024:.0f} GiB on {ranks} ranks > "
            f"{MEMORY_HEADROOM * available / 1024:.0f} GiB, {MEMORY_HEADROOM:.0%} of the "
            f"{available / 1024:.0f} GiB available)")


# The free-hanging scenes (full mode): the finest refinement each solver is run at there. Their
# solves are governed by the nonlinearity: single-level TR takes 439 iterations (4 min) on the
# drooping cloth at 13,467 dofs, so the single-level solvers stop at 51,483 dofs (where a solve
# past --timeout is reported as such); the patch smoother needs the coarser levels solved and
# Galerkin coarse models (rmtr-patch's one V-cycle per level does not converge, and the
# rediscretised coarse models of its free-hanging states cost it 3× the V-cycles), and the
# paper's smoother stalls already on the trampoline. The re-entrant corner (91 cage faces:
# 5,115 dofs at refine 2, 18,939 at 3, 72,795 at 4) takes RMTR 118–477 V-cycles at 5,115 dofs
# (docs/solvers.md). The drape (two corners drawn together) runs the default up to 51,483 dofs, with
# factorised Dogleg smoothing and bnls + MUMPS below it as references.
# mlshell's default runs the drooping cloth at 795,675 dofs too (15 V-cycles, 15 min, 5.6 GiB
# per rank on 2026-12-05).
FREE_HANGING_MAX_REFINE = {
    "drooping": {"rmtr": 6, "rmtr-galerkin": 5, "rmtr-patch-galerkin": 6, "rmtr-patch-dogleg": 7,
                 "tr": 5, "bnls-mumps": 5},
    "reentrant_corner": {"rmtr": 3, "rmtr-patch-galerkin": 3, "rmtr-patch-dogleg": 4, "tr": 2,
                         "bnls-mumps": 2},
    "drape": {"rmtr": 4, "rmtr-patch-dogleg": 5, "bnls-mumps": 3},
}


def run(ctx):
    rows = []
    for scene in ctx.scenes(("trampoline",), ("trampoline", "drooping", "reentrant_corner",
                                                "drape")):
        given_up, peak = set(), {}
        for refine in ctx.pick((1, 2), (2, 3, 4, 5, 6, 7)):
            for solver in ctx.solvers(SOLVERS):
                # The paper's smoother stalls (300 V-cycles leave |g| ~ 1e-2; docs/rmtr-on-cloth.md): it is
                # measured where that costs seconds, not hours.
                if solver in given_up or (solver == "rmtr-paper" and refine > ctx.pick(1, 3)):
                    continue
                if (scene != "trampoline" and
                        refine > FREE_HANGING_MAX_REFINE[scene].get(solver, 0)):
                    continue
                # Without the full-multigrid start the patch smoother needs 40 V-cycles at
                # 201,243 dofs (~6 min): the comparison stops there.
                if solver == "rmtr-patch-vcycles" and refine > ctx.pick(2, 6):
                    continue
                ranks = ctx.runner.ranks
                why = too_big(solver, peak.get(solver), ranks, available_mib())
                if why:
                    print(f"  [{NAME}] {scene}-r{refine}-{solver}: {why}", flush=True)
                    rows.append({"scene": scene, "solver": solver, "refine": refine,
                                 "ranks": ranks, "dofs": "", "converged": 0, "reason": why})
                    given_up.add(solver)
                    continue
                max_it = ctx.pick(50, 300) if solver == "rmtr-paper" else ctx.pick(300, 1000)
                r = ctx.run(NAME, f"{scene}-r{refine}-{solver}", scene, refine,
                            with_tolerance(solver, ctx.source, 1e-7, max_it, relative=False))
                if r["timed_out"]:
                    given_up.add(solver)
                row = {**solver_fields(r), "solver": solver}
                peak[solver] = row["peak_rss_mib"]
                rows.append(row)
    ctx.write_csv(NAME, rows, COLUMNS, key=("scene", "solver"))
