"""Tables 6 and 7: assembly and QP work units (eq. 7.3-7.4), TR vs RMTR with three levels at
1,083 dofs. TR: one work unit per fine Hessian assembly and per QP solve; RMTR: each level's
calls weighted by its share of the finest level's control points."""
from runner import SCENES, solver_fields
from study_iterations import rmtr_solve, tr_solve

NAME = "work"
COLUMNS = ["scene", "solver", "levels", "dofs", "iterations", "converged", "reason",
           "assembly_work", "qp_work", "assembly_work_per_iteration", "qp_work_per_iteration"]


def work_units(result):
    """(assembly, QP) work units of one run, or empty cells when it has no summary."""
    s = result["summary"]
    if not s:
        return "", ""
    v = s["solver"]
    if "rmtr" in v:
        return v["rmtr"]["assembly_work_units"], v["rmtr"]["qp_work_units"]
    return v["hessian_evaluations"], v["iterations"]


def run(ctx):
    refine, levels = ctx.pick((1, 2), (2, 3))
    rows = []
    for scene in ctx.scenes(("trampoline", "drooping"), SCENES):
        # The same solves as the iterations study: remembered, not repeated.
        for solver, r in (("tr", tr_solve(ctx, scene, refine)),
                          ("rmtr", rmtr_solve(ctx, scene, levels, refine))):
            assembly, qp = work_units(r)
            row = {**solver_fields(r), "solver": solver,
                   "levels": 1 if solver == "tr" else levels,
                   "assembly_work": assembly, "qp_work": qp}
            its = row["iterations"]
            if its not in ("", 0) and assembly != "":
                row["assembly_work_per_iteration"] = assembly / its
                row["qp_work_per_iteration"] = qp / its
            rows.append(row)
    ctx.write_csv(NAME, rows, COLUMNS)
