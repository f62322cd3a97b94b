"""The solver configurations the studies compare, each a name, a description and PETSc options.

Tolerances are set by `with_tolerance`, so that every solver stops on the same test: the
gradient norm ‖∇f‖₂ (TAO gatol, SNES atol; paper eq. 7.1 uses 1e-7). Every run ignores the
scene's own default solver (`-mlshell_scene_solver false`, runner.py), so a name below means
the same configuration on every scene.
"""

_HYPRE = ["-pc_hypre_type", "boomeramg", "-pc_hypre_boomeramg_nodal_coarsen", "1",
          "-pc_hypre_boomeramg_vec_interp_variant", "2"]


def _bnk(prefix_options):
    return [o if not o.startswith("-pc_") and not o.startswith("-ksp_") else "-tao_bnk_" + o[1:]
            for o in prefix_options]


SOLVERS = {
    "rmtr": ("RMTR, factorised Dogleg smoothing on every level (rmtr.yaml; mlshell's default "
             "until 2026-12-05)", ["-options_file", "@petsc-options/rmtr.yaml"]),
    "rmtr-paper": ("RMTR, 10 ST-CG smoothing steps, Dogleg coarse (paper §7.3)",
                   ["-options_file", "@petsc-options/rmtr-paper.yaml"]),
    "rmtr-patch": ("RMTR, full-multigrid start, vertex-patch-preconditioned ST-CG smoothing "
                   "(40 its), Dogleg coarse (no fine factorisation)",
                   ["-options_file", "@petsc-options/rmtr-patch.yaml"]),
    "rmtr-patch-vcycles": ("RMTR as rmtr-patch, V-cycles from the given iterate (no "
                           "full-multigrid start)",
                           ["-options_file", "@petsc-options/rmtr-patch.yaml",
                            "-tao_rmtr_fmg_cycles", "0"]),
    "rmtr-galerkin": ("RMTR as rmtr, Galerkin coarse models (the finer quadratic model "
                      "J_P^T H J_P on each coarser level)",
                      ["-options_file", "@petsc-options/rmtr.yaml",
                       "-tao_rmtr_coarse_model", "galerkin"]),
    "rmtr-patch-galerkin": ("RMTR, the patch smoother (100 ST-CG its) with Galerkin coarse "
                            "models, each coarser level solved by the full-multigrid start, a "
                            "subspace step after each V-cycle, retried smoothing steps",
                            ["-options_file", "@petsc-options/rmtr-patch-galerkin.yaml"]),
    "tr": ("single-level TR, Dogleg (Alg. 4.1)", ["-tao_type", "tr", "-tao_max_it", "100000"]),
    "bntr-mumps": ("TAO bntr, ST-CG + MUMPS LU", ["-tao_type", "bntr"]),
    "rmtr-patch-dogleg": ("RMTR, Dogleg smoothing with inexact Newton points (patch-"
                          "preconditioned CG, 60 its), Galerkin coarse models, subspace steps "
                          "and retries (no fine factorisation; mlshell's default)",
                          ["-options_file", "@petsc-options/rmtr-patch-dogleg.yaml"]),
    "bnls-mumps": ("TAO bnls, ST-CG + MUMPS LU (line-search Newton)", ["-tao_type", "bnls"]),
    "bntr-gamg": ("TAO bntr, ST-CG + GAMG",
                  ["-tao_type", "bntr"] + _bnk(["-ksp_type", "stcg", "-ksp_max_it", "500",
                                                "-pc_type", "gamg"])),
    "bnls-gamg": ("TAO bnls, ST-CG + GAMG",
                  ["-tao_type", "bnls"] + _bnk(["-ksp_type", "stcg", "-ksp_max_it", "500",
                                                "-pc_type", "gamg"])),
    "bntr-boomeramg": ("TAO bntr, ST-CG + hypre BoomerAMG",
                       ["-tao_type", "bntr"] + _bnk(["-ksp_type", "stcg", "-ksp_max_it", "500",
                                                     "-pc_type", "hypre"] + _HYPRE)),
    "bnls-boomeramg": ("TAO bnls, ST-CG + hypre BoomerAMG",
                       ["-tao_type", "bnls"] + _bnk(["-ksp_type", "stcg", "-ksp_max_it", "500",
                                                     "-pc_type", "hypre"] + _HYPRE)),
    # Inexact Newton: a GMRES solve that stops at its iteration cap still gives the step.
    "snes-boomeramg": ("SNES newtonls (bt line search), GMRES + hypre BoomerAMG",
                       ["-mlshell_step_solver", "snes", "-snes_type", "newtonls",
                        "-snes_max_linear_solve_fail", "1000000", "-ksp_type", "gmres",
                        "-ksp_max_it", "500", "-ksp_rtol", "1e-6", "-pc_type", "hypre"]
                       + _HYPRE),
    "snes-mumps": ("SNES newtonls (bt line search), MUMPS LU",
                   ["-mlshell_step_solver", "snes", "-snes_type", "newtonls"]),
    # Triangle-mesh shells (paper 2): its single-level default, and RMTR on the decimation
    # hierarchy with first-order coarse models of each coarse mesh's own energy or of paper 2's
    # proxy energy Ψ(P^l(x_l)) (eq. 2) in place of the Galerkin models of mlshell's default.
    "pnewton": ("projected Newton (PSD-projected element Hessians, MUMPS LU, Armijo line "
                "search; the triangle scenes' own solver, paper 2 §4.5)",
                ["-tao_type", "pnewton", "-mlshell_hessian_psd", "1"]),
    "rmtr-own": ("RMTR as rmtr-patch-dogleg, first-order coarse models of each coarse mesh's "
                 "own energy", ["-options_file", "@petsc-options/rmtr-patch-dogleg.yaml",
                                "-tao_rmtr_coarse_model", "first_order",
                                "-mlshell_coarse_energy", "own"]),
    "rmtr-proxy": ("RMTR as rmtr-patch-dogleg, first-order coarse models of paper 2's proxy "
                   "energy Ψ(P^l(x_l)) (the finest energy at the direct prolongation)",
                   ["-options_file", "@petsc-options/rmtr-patch-dogleg.yaml",
                    "-tao_rmtr_coarse_model", "first_order", "-mlshell_coarse_energy", "proxy"]),
    "dampednewton": ("damped Newton, alpha = 0.3", ["-tao_type", "dampednewton"]),
    "linearized": ("linearized equation (one Newton step)", ["-tao_type", "linearized"]),
}

# The configuration without fine factorisations that solves each scene: the trampoline names its
# own (examples/trampoline.yaml), the others use mlshell's default.
SCENE_SOLVERS = {"trampoline": "rmtr-patch"}
DEFAULT_SOLVER = "rmtr-patch-dogleg"


def scene_solver(scene):
    return SCENE_SOLVERS.get(scene, DEFAULT_SOLVER)


PEERS = ["bntr-mumps", "bnls-mumps", "bntr-gamg", "bnls-gamg", "bntr-boomeramg",
         "bnls-boomeramg", "snes-boomeramg", "snes-mumps"]


def options(name, source):
    """PETSc options of solver `name`; '@' marks a path relative to the source tree."""
    if name not in SOLVERS:
        raise KeyError(f"unknown solver '{name}'; known: {', '.join(SOLVERS)}")
    return [str(source / o[1:]) if o.startswith("@") else o for o in SOLVERS[name][1]]


def with_tolerance(name, source, tol, max_it=None, relative=True):
    """Options of `name` stopping at ‖∇f‖₂ < tol (and at most max_it iterations if given).
    With relative=False the relative test ‖∇f‖/‖∇f₀‖ < 1e-10 is off too, so that a solve from a
    state with a large gradient (the drape's prescribed corners: ‖∇f₀‖ > 10⁵) is not stopped
    far above tol."""
    opts = options(name, source)
    if "-mlshell_step_solver" in opts:
        opts += ["-snes_atol", repr(tol)] + (["-snes_max_it", str(max_it)] if max_it else [])
        opts += [] if relative else ["-snes_rtol", "0"]
    else:
        opts += ["-tao_gatol", repr(tol)] + (["-tao_max_it", str(max_it)] if max_it else [])
        opts += [] if relative else ["-tao_gttol", "0"]
    return opts


def describe(name):
    return SOLVERS[name][0]
