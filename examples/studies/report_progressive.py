"""REPORT.md's section on progressive runs (study_progressive.py, issue 46): per scene, the time
each route takes to each level and to the converged fine result, each preview's error, the
speed-ups against the direct fine run, the goals, and the Pareto plot of error against time."""
import plots
from context import number

# Issue 46's goals against the direct fine simulation, whole-run wall time, same run.
GOAL_FINAL = 4.0
GOAL_PREVIEW = 20.0


def _mm(v):
    x = number(v)
    return "" if x is None else f"{1000 * x:.3g}"


def preview_wall(rows, row):
    """The wall time a user waits for a progressive level: the run's setup (its whole wall time
    less the time to its last level) and the time to that level."""
    last = max(number(r["time"], 0.0) for r in rows)
    return number(row["wall_time"], 0.0) - last + number(row["time"], 0.0)


def section(report, table, against, seconds):
    rows = report.csv("progressive")
    if rows is None:
        return
    report.add(
        "## Progressive shell quasistatics\n\n"
        "**Measures** what each level of a progressive run (paper 2 §3, Alg. 1) costs and how "
        "close its preview is to the converged fine result, **against** the direct fine "
        "quasistatic run (projected Newton + MUMPS, the scenes' solver), the direct run on the "
        "coarsest level's own mesh, and RMTR on the same hierarchy; every route runs the "
        "scene's whole loading to \\|g\\| < 1e-7 on the fine mesh. *time*: the solve's wall "
        "time up to that level (setup excluded); *wall*: the whole run a user waits for (setup, "
        "hierarchy, output; for a preview, the setup and the time to its level). *max / RMS "
        "error*: vertex distance of the level's result, prolonged to the fine mesh, to the "
        "converged fine result (mm), and the RMS error relative to the RMS displacement of the "
        "fine result (on the same branch: a few per cent); *probe*: the probe's distance to the "
        "direct fine run's "
        "(mm), the only error a coarse mesh's own result has.\n")
    groups = dict.fromkeys((r["scene"], r["resolution"]) for r in rows)
    # Coarse to fine within a scene (by the direct fine run's dofs).
    size = {g: max((number(r["dofs"], 0.0) for r in rows if (r["scene"], r["resolution"]) == g),
                   default=0.0) for g in groups}
    for scene, resolution in sorted(groups, key=lambda g: (list(groups).index(
            next(h for h in groups if h[0] == g[0])), size[g])):
        mine = [r for r in rows if r["scene"] == scene and r["resolution"] == resolution]
        fine = next((r for r in mine if r["route"] == "direct-fine" and r["converged"] == "1"),
                    None)
        fine_wall = number(fine["wall_time"]) if fine else None
        prog = [r for r in mine if r["route"] == "progressive" and r["level"] != ""]
        body = []
        for r in mine:
            wall = preview_wall(prog, r) if r["route"] == "progressive" and r["level"] != "" \
                else number(r["wall_time"])
            speed = f"{fine_wall / wall:.1f}×" if fine_wall and wall else ""
            scale = number(r.get("final_rms", ""))
            relative = f"{number(r['rms_error']) / scale:.2%}" \
                if scale and number(r["rms_error"]) is not None else ""
            body.append([r["route"], r["level"], f"{int(number(r['level_dofs'], 0)):,}"
                         if r["level_dofs"] else "", seconds(r["time"]), seconds(wall), speed,
                         r["iterations"], r["reason"], _mm(r["max_error"]), _mm(r["rms_error"]),
                         relative, _mm(r["probe_error"])])
        steps = next((r["steps"] for r in mine if r["steps"]), "?")
        dofs = next((r["dofs"] for r in mine if r["route"] == "direct-fine"), "")
        report.add(f"### {scene}: {int(number(dofs, 0)):,} dofs, {steps} load steps\n\n" + table(
            ["route", "level", "dofs", "time [s]", "wall [s]", "direct fine / wall",
             "iterations", "stop", "max error", "RMS error", "RMS / RMS displacement",
             "probe"], body))
        where = f"{scene}, {int(number(dofs, 0)):,} dofs"
        if not fine or not prog:
            report.goals.append((f"progressive ≥ {GOAL_FINAL:g}× faster than direct fine "
                                 f"({where})", "no converged direct fine run" if not fine
                                 else "no progressive run", None))
            continue
        final = prog[-1]
        ok = final["reason"].startswith("CONVERGED")
        ratio = fine_wall / number(final["wall_time"])
        report.goals.append((f"progressive's converged fine result ≥ {GOAL_FINAL:g}× faster "
                             f"than direct fine ({where})",
                             against(ratio, GOAL_FINAL) if ok else final["reason"],
                             ok and ratio >= GOAL_FINAL))
        ratio = fine_wall / preview_wall(prog, prog[0])
        report.goals.append((f"coarsest preview ≥ {GOAL_PREVIEW:g}× faster than direct fine "
                             f"({where})", against(ratio, GOAL_PREVIEW), ratio >= GOAL_PREVIEW))
    report.image(plots.progressive(rows, report.out))
