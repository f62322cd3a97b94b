"""Figure 9: condition number of the Hessian at the solution of one dt = 1 step of the
trampoline, vs dofs (left) and vs the penalty parameter beta at 1,083 dofs (right).

How it is obtained: mlshell -mlshell_condition runs Lanczos with full reorthogonalisation on H
(largest |eigenvalue|) and on H^-1 through a MUMPS LDL^T factorisation (smallest |eigenvalue|);
cond_2 = |lambda|max / |lambda|min. See include/mlshell/hessian_spectrum.hpp."""
import re

from runner import solver_fields
from solvers import with_tolerance

NAME = "condition"
COLUMNS = ["scene", "sweep", "refine", "dofs", "beta", "lambda_min", "lambda_max", "condition",
           "settled", "converged", "reason"]
SCENE = "trampoline"


def _row(result, sweep, beta):
    row = {**solver_fields(result), "sweep": sweep, "beta": beta}
    s = result["summary"]
    if s and "hessian" in s:
        h = s["hessian"]
        row.update(lambda_min=abs(h["lambda_min"]), lambda_max=abs(h["lambda_max"]),
                   condition=h["condition"], settled=int(h["settled"]))
    return row


def scene_with_penalty(ctx, beta):
    """The trampoline scene with the boundary penalty fixed to `beta` instead of h^-5."""
    text = ctx.runner.scene_path(SCENE).read_text()
    new, n = re.subn(r"dirichlet: \{where: boundary\}",
                     f"dirichlet: {{where: boundary, penalty: {beta:g}}}", text)
    if n != 1:
        raise RuntimeError(f"cannot set the penalty in {SCENE}.yaml: its dirichlet entry changed")
    return new


def run(ctx):
    options = with_tolerance("rmtr", ctx.source, 1e-7, ctx.pick(300, 20000)) + [
        "-mlshell_condition", "-mlshell_condition_steps", str(ctx.pick(40, 80))]
    rows = []
    for refine in ctx.pick((0, 1), (0, 1, 2, 3, 4, 5)):
        r = ctx.run(NAME, f"{SCENE}-r{refine}", SCENE, refine, options)
        rows.append(_row(r, "dofs", ""))
    refine = ctx.pick(1, 2)
    for exponent in ctx.pick((2, 6), (1, 2, 3, 4, 5, 6, 7, 8, 9)):
        beta = 10.0 ** exponent
        r = ctx.run(NAME, f"{SCENE}-r{refine}-beta1e{exponent}", SCENE, refine, options,
                    scene_text=scene_with_penalty(ctx, beta))
        rows.append(_row(r, "beta", beta))
    ctx.write_csv(NAME, rows, COLUMNS)
