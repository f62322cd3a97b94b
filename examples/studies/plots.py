"""PNG plots of the study CSVs (matplotlib, Agg backend). Each function returns the file name it
wrote, or None when its CSV has nothing to plot."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import paper  # noqa: E402
from context import number  # noqa: E402
from solvers import DEFAULT_SOLVER  # noqa: E402

MARKERS = "osD^v<>ph*"


def _save(fig, out, name):
    fig.tight_layout()
    fig.savefig(out / name, dpi=110)
    plt.close(fig)
    return name


def iterations(rows, out):
    """Table 3/4 as curves: TR iterations vs dofs and RMTR V-cycles vs levels (rmtr.yaml solid,
    mlshell's default dashed), with the paper's."""
    if not rows:
        return None
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 4.4))
    for k, scene in enumerate(paper.SCENES):
        color = f"C{k}"
        tr = [(number(r["dofs"]), number(r["iterations"])) for r in rows
              if r["scene"] == scene and r["solver"] == "tr" and r["converged"] == "1"]
        if tr:
            left.loglog(*zip(*tr), MARKERS[k] + "-", color=color, label=f"{scene} (mlshell)")
        ref = [(d, i) for d, i in zip(paper.DOFS, paper.TR_ITERATIONS[scene]) if i]
        left.loglog(*zip(*ref), MARKERS[k] + ":", color=color, alpha=0.5, mfc="none",
                    label=f"{scene} (paper)")
        for solver, style in (("rmtr", "-"), (DEFAULT_SOLVER, "--")):
            rm = [(number(r["levels"]), number(r["iterations"])) for r in rows
                  if r["scene"] == scene and r["solver"] == solver and r["converged"] == "1"]
            if rm:
                right.semilogy(*zip(*rm), MARKERS[k] + style, color=color,
                               label=f"{scene} ({solver})")
        right.semilogy(paper.LEVELS, paper.RMTR_CYCLES[scene], MARKERS[k] + ":", color=color,
                       alpha=0.5, mfc="none", label=f"{scene} (paper)")
    left.set(xlabel="dofs", ylabel="TR iterations", title="Table 3: single-level TR, dt = 1")
    right.set(xlabel="levels", ylabel="RMTR V-cycles", title="Table 4: RMTR, dt = 1")
    left.legend(fontsize=6)
    right.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.02, 1.0))  # beside the curves
    return _save(fig, out, "iterations.png")


def condition(rows, out):
    dofs = [(number(r["dofs"]), number(r["condition"])) for r in rows
            if r["sweep"] == "dofs" and number(r["condition"])]
    beta = [(number(r["beta"]), number(r["condition"])) for r in rows
            if r["sweep"] == "beta" and number(r["condition"])]
    if not dofs and not beta:
        return None
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    if dofs:
        left.loglog(*zip(*dofs), "o-")
    left.set(xlabel="dofs", ylabel="cond$_2$(H)", title="Fig. 9 left: trampoline, dt = 1")
    if beta:
        right.loglog(*zip(*beta), "s-")
    right.set(xlabel=r"penalty $\beta$", ylabel="cond$_2$(H)", title="Fig. 9 right")
    return _save(fig, out, "condition.png")


def largest_timestep(table, out):
    """Figure 10 as bars: the largest dt each solver converged at, per scene."""
    if not table:
        return None
    scenes = list(dict.fromkeys(s for s, _ in table))  # the report's column order
    solvers = list(dict.fromkeys(v for _, v in table))
    fig, ax = plt.subplots(figsize=(max(9, 1.4 * len(scenes)), 4.6))
    width = 0.8 / max(1, len(solvers))
    for j, solver in enumerate(solvers):
        values = [table.get((s, solver)) or 0.0 for s in scenes]
        ax.bar([i + j * width for i in range(len(scenes))], values, width, label=solver)
    ax.set_yscale("log")
    ax.set_ylim(1 / 48, 4.0)  # room for the legend above the bars
    ax.set_xticks([i + 0.4 - width / 2 for i in range(len(scenes))],
                  [s.replace(", ", "\n") for s in scenes], fontsize=8)
    ax.set(ylabel="largest dt that converges [s]", title="Fig. 10: robustness vs dt")
    ax.legend(fontsize=7, ncol=len(solvers), loc="upper center")
    return _save(fig, out, "timestep.png")


def accuracy(rows, out, scene):
    """Error against wall time for one scene; the Pareto front over every run as a line."""
    pts = [r for r in rows if r["scene"] == scene and number(r["l2_error"]) is not None]
    if not pts:
        return None
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, column, label in ((axes[0], "l2_error", "limit surface L$^2$ error [m$^2$]"),
                              (axes[1], "probe_error", "probe displacement error [m]")):
        for k, solver in enumerate(dict.fromkeys(r["solver"] for r in pts)):
            mine = [r for r in pts if r["solver"] == solver]
            ax.loglog([number(r["wall_time"]) for r in mine],
                      [max(number(r[column]), 1e-16) for r in mine], MARKERS[k % 10],
                      label=solver, alpha=0.8)
        front = pareto_front([(number(r["wall_time"]), max(number(r[column]), 1e-16))
                              for r in pts])
        ax.loglog(*zip(*front), "k-", lw=1, label="Pareto front")
        ax.set(xlabel="wall time [s]", ylabel=label, title=f"{scene}: accuracy vs time")
        ax.legend(fontsize=7)
    return _save(fig, out, f"accuracy_{scene}.png")


def pareto_front(points):
    """The points no other point beats in both time and error, by increasing time. A point must
    lower the error by 1 % to count: differences at the solver's round-off are not progress."""
    front, best = [], float("inf")
    for t, e in sorted(points):
        if e < best * (1 - 1e-2):
            front.append((t, e))
            best = e
    return front


def peers(rows, out):
    ok = [r for r in rows if r["converged"] == "1" and number(r["wall_time"])]
    if not ok:
        return None
    groups = list(dict.fromkeys((r["scene"], r["dofs"]) for r in ok))
    solvers = list(dict.fromkeys(r["solver"] for r in rows))
    fig, ax = plt.subplots(figsize=(10, 4))
    width = 0.8 / len(solvers)
    for j, solver in enumerate(solvers):
        values = [next((number(r["wall_time"]) for r in ok if (r["scene"], r["dofs"]) == g
                        and r["solver"] == solver), 0.0) for g in groups]
        ax.bar([i + j * width for i in range(len(groups))], values, width, label=solver)
    ax.set_yscale("log")
    ax.set_xticks([i + 0.4 - width / 2 for i in range(len(groups))],
                  [f"{s}\n{d} dofs" for s, d in groups])
    ax.set(ylabel="wall time [s] (converged runs)", title="RMTR vs PETSc solvers, dt = 1")
    ax.legend(fontsize=6, ncol=3)
    return _save(fig, out, "peers.png")


def parallel(rows, out):
    """One panel per scene and resolution: for each solver the 1- and 2-rank runs side by side,
    stacked by -log_view stage, with the speedup of the whole run above the 2-rank bar."""
    ok = [r for r in rows if number(r["stage_solve"]) is not None]
    if not ok:
        return None
    cases = list(dict.fromkeys((r["scene"], r["dofs"]) for r in ok))
    fig, axes = plt.subplots(1, len(cases), figsize=(max(7, 3.2 * len(cases)), 4.2),
                             squeeze=False)
    colours = {"setup": "tab:blue", "solve": "tab:orange", "output": "tab:green"}
    for ax, (scene, dofs) in zip(axes[0], cases):
        group = [r for r in ok if (r["scene"], r["dofs"]) == (scene, dofs)]
        solvers = list(dict.fromkeys(r.get("solver", "rmtr") for r in group))
        for k, solver in enumerate(solvers):
            walls = {}
            for r in group:
                if r.get("solver", "rmtr") != solver:
                    continue
                ranks = int(number(r["ranks"], 1))
                x = k + (0.2 if ranks > 1 else -0.2)
                bottom = 0.0
                for stage, colour in colours.items():
                    v = number(r[f"stage_{stage}"], 0.0)
                    ax.bar(x, v, 0.38, bottom=bottom, color=colour,
                           label=stage if k == 0 and ranks == 1 else None)
                    bottom += v
                walls[ranks] = (x, bottom, number(r["wall_time"]))
            if 1 in walls and 2 in walls and walls[1][2] and walls[2][2]:
                x, top, wall = walls[2]
                ax.annotate(f"{walls[1][2] / wall:.2f}×", (x, top), ha="center", va="bottom",
                            fontsize=8)
        ax.set_xticks(range(len(solvers)))
        ax.set_xticklabels([f"{s}\n1 | 2 ranks" for s in solvers], fontsize=7)
        ax.set_title(f"{scene}, {int(number(dofs)):,} dofs", fontsize=9)
        ax.margins(y=0.12)
    axes[0][0].set_ylabel("time [s] (-log_view stages)")
    axes[0][0].legend(fontsize=7)
    fig.suptitle("1 vs 2 ranks: whole-run speedup above each 2-rank bar")
    return _save(fig, out, "parallel.png")


def scaling(rows, out, scene="trampoline"):
    """V-cycles (iterations), wall time and peak memory per rank against dofs, per solver, for
    one scene (scaling.png for the trampoline, scaling_<scene>.png for the others)."""
    solvers = list(dict.fromkeys(r["solver"] for r in rows))
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    drawn = False
    for k, solver in enumerate(solvers):
        ok = [r for r in rows if r["solver"] == solver and r["converged"] == "1"]
        for ax, column in zip(axes, ("iterations", "wall_time", "peak_rss_mib")):
            points = [(number(r["dofs"]), number(r[column])) for r in ok if number(r[column])]
            if points:
                ax.loglog(*zip(*points), MARKERS[k % len(MARKERS)] + "-", label=solver)
                drawn = True
    if not drawn:
        plt.close(fig)
        return None
    for ax, label in zip(axes, ("V-cycles / iterations", "wall time [s]",
                                "peak resident memory, largest rank [MiB]")):
        ax.set(xlabel="dofs", ylabel=label)
        ax.legend(fontsize=7)
    axes[0].set_title(f"{scene}, one step dt = 1 (converged runs)")
    return _save(fig, out, "scaling.png" if scene == "trampoline" else f"scaling_{scene}.png")


def triangle(rows, out):
    """RMTR on triangle hierarchies: per scene (columns), wall time against dofs for every
    solver (top) and V-cycles / Newton iterations against dofs (bottom; RMTR solid, the
    single-level solvers dashed). Converged runs only."""
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    solvers = list(dict.fromkeys(r["solver"] for r in rows))
    if not any(r["converged"] == "1" for r in rows):
        return None
    fig, axes = plt.subplots(2, len(scenes), figsize=(4.6 * len(scenes), 7.4), squeeze=False)
    for j, scene in enumerate(scenes):
        top, bottom = axes[0][j], axes[1][j]
        for k, solver in enumerate(solvers):
            ok = sorted((r for r in rows if r["scene"] == scene and r["solver"] == solver
                         and r["converged"] == "1"), key=lambda r: number(r["dofs"]))
            if not ok:
                continue
            style = MARKERS[k % len(MARKERS)] + ("-" if solver.startswith("rmtr") else "--")
            dofs = [number(r["dofs"]) for r in ok]
            top.loglog(dofs, [number(r["wall_time"]) for r in ok], style, color=f"C{k}",
                       label=solver)
            bottom.loglog(dofs, [number(r["iterations"]) for r in ok], style, color=f"C{k}",
                          label=solver)
        steps = next((r["steps"] for r in rows if r["scene"] == scene), "?")
        top.set(xlabel="dofs", ylabel="wall time [s]",
                title=f"{scene}, first {steps} step(s)")
        bottom.set(xlabel="dofs", ylabel="V-cycles (RMTR) / iterations, summed over steps")
        top.legend(fontsize=7)
        bottom.legend(fontsize=7)
    return _save(fig, out, "triangle.png")


def progressive(rows, out):
    """Progressive runs: per scene and resolution, the error of each route's result (the probe's distance to the
    direct fine run's, log scale) against the whole-run wall time a user waits for it: the
    progressive levels joined in order, the direct coarse and fine runs and RMTR. The converged
    fine results (direct fine, RMTR, progressive's finest level) differ by round-off: they are
    drawn on the dotted line at the bottom."""
    groups = list(dict.fromkeys((r["scene"], r["resolution"]) for r in rows))
    if not any(number(r["wall_time"]) for r in rows):
        return None
    columns = min(4, len(groups))
    lines = -(-len(groups) // columns)
    fig, axes = plt.subplots(lines, columns, figsize=(4.4 * columns, 3.8 * lines), squeeze=False)
    for ax in axes.flat[len(groups):]:
        ax.set_visible(False)
    for ax, (scene, resolution) in zip(axes.flat, groups):
        mine = [r for r in rows if r["scene"] == scene and r["resolution"] == resolution
                and number(r["wall_time"])]
        dofs = max((number(r["dofs"], 0) for r in mine), default=0)
        prog = [r for r in mine if r["route"] == "progressive" and r["level"] != ""]
        last = max((number(r["time"], 0.0) for r in prog), default=0.0)
        # The fine results (solved to the tolerance: their differences are round-off).
        fine = [r for r in mine if r["route"] in ("direct-fine", "rmtr")] + prog[-1:]
        errors = [number(r["probe_error"]) for r in mine
                  if r not in fine and number(r["probe_error"])]
        floor = min(errors, default=1e-6) / 10

        def wall(r):
            if r["route"] == "progressive" and r["level"] != "":
                return number(r["wall_time"]) - last + number(r["time"], 0.0)
            return number(r["wall_time"])

        def error(r):
            return floor if r in fine else max(number(r["probe_error"], 0.0), floor)

        if prog:
            ax.loglog([wall(r) for r in prog], [error(r) for r in prog], "o-", color="C0",
                      label="progressive (levels)")
            for r in prog:
                ax.annotate(f"L{r['level']}", (wall(r), error(r)), fontsize=7,
                            textcoords="offset points", xytext=(4, 4))
        for k, route in enumerate(("direct-fine", "direct-coarse", "rmtr"), 1):
            pts = [r for r in mine if r["route"] == route]
            if pts:
                ax.loglog([wall(r) for r in pts], [error(r) for r in pts], MARKERS[k],
                          color=f"C{k}", label=route)
        ax.axhline(floor, color="0.7", lw=0.8, ls=":")
        ax.set(xlabel="wall time [s]", ylabel="probe error [m] (dotted: converged)",
               title=f"{scene}, {dofs:,.0f} dofs")
        ax.legend(fontsize=7)
    return _save(fig, out, "progressive.png")

