"""RMTR on triangle-mesh hierarchies (issue 48's goals): V-cycles, wall time and peak memory
against resolution for RMTR on paper 2's decimation hierarchies, with its three coarse models
(mlshell's default `rmtr-patch-dogleg`: Galerkin models J_Pᵀ H J_P; `rmtr-own`: first order,
each coarse mesh's own energy; `rmtr-proxy`: first order, paper 2's proxy Ψ(P^l(x_l))), against
the single-level solvers it must beat: projected Newton + MUMPS (`pnewton`, the triangle
scenes' own solver) and single-level TR + MUMPS (`tr`).

Scenes (examples/triangle): the plate buckling (a stiff steel sheet pushed into post-buckling),
the shell indent (a dome snapping through) and the unstructured drape (denim hanging from two
corners). The resolution is the scene's mesh spec, rewritten per run (RESOLUTIONS): the
rectangle's `faces: [n, n]`, the dome's `rings`, the Delaunay rectangle's `edge_length`. Each
RMTR run gets `hierarchy: {levels: L, ratio: 4}` with the fewest levels whose coarsest has at
most COARSEST_VERTICES vertices; the single-level solvers run the scene without its hierarchy
(it is built whenever a scene declares it, and would only add to their setup). Each run makes
the scene's first STEPS load steps (quick: one), the iterations column sums the Newton
iterations or V-cycles over them, and the final total energy says whether every solver reached
the same minimiser. A solver that times out at one resolution is not run at the finer ones;
--max-dofs skips resolutions above a size (by their dofs in RESOLUTIONS)."""
import math
import re

from runner import solver_fields
from solvers import with_tolerance

NAME = "triangle"
COLUMNS = ["scene", "solver", "resolution", "dofs", "ranks", "steps", "levels", "coarsest_dofs",
           "iterations", "converged", "reason", "gradient_norm", "energy", "coarse_accepted",
           "coarse_rejected", "wall_time", "solve_time", "peak_rss_mib"]
SCENES = ("plate_buckling", "shell_indent", "unstructured_drape")
SINGLE_LEVEL = ("pnewton", "tr")
RMTR = ("rmtr-patch-dogleg", "rmtr-own", "rmtr-proxy")
SOLVERS = SINGLE_LEVEL + RMTR
QUICK_SCENES = ("plate_buckling", "shell_indent")
QUICK_SOLVERS = ("pnewton", "rmtr-patch-dogleg")
# The load steps each run makes (the drape's scene has one: it hangs under gravity in one
# quasistatic step of proximal solves).
STEPS = {"unstructured_drape": 1}
FULL_STEPS = 2
# The mesh key each scene's resolution rewrites, and its resolutions with their dofs (measured
# where below 10,000 dofs; the finer ones scale as n² or 1/h², to within a few per cent).
MESH_KEY = {"plate_buckling": "faces", "shell_indent": "rings", "unstructured_drape": "edge_length"}
RESOLUTIONS = {
    "plate_buckling": ((16, 867), (32, 3267), (64, 12675), (128, 49923), (258, 201243)),
    "shell_indent": ((16, 2325), (32, 9054), (64, 36000), (152, 204000)),
    "unstructured_drape": ((0.05, 1530), (0.025, 5916), (0.0125, 23300), (0.00625, 93000),
                           (0.0042, 205000)),
}
RATIO = 4
COARSEST_VERTICES = 600
MAX_IT = 2000  # per solve: the drape takes projected Newton 861 iterations at 1,530 dofs


def hierarchy_levels(dofs):
    """The fewest levels (at least 2) whose coarsest level, each `RATIO` times coarser than the
    next, has at most COARSEST_VERTICES vertices."""
    vertices = dofs / 3
    return max(2, 1 + math.ceil(math.log(vertices / COARSEST_VERTICES, RATIO)))


def scene_text(source, scene, resolution, levels):
    """examples/triangle/<scene>.yaml at `resolution`, with `levels` levels (None: no
    hierarchy) and its solver file by absolute path (the copy lies in a run folder)."""
    path = source / "examples" / "triangle" / f"{scene}.yaml"
    text = path.read_text()
    key = MESH_KEY[scene]
    value = f"[{resolution}, {resolution}]" if key == "faces" else f"{resolution}"
    pattern = r"faces: \[\d+, \d+\]" if key == "faces" else rf"{key}: [0-9.]+"
    text, n = re.subn(pattern, f"{key}: {value}", text)
    if n != 1:
        raise SystemExit(f"studies: error: {path} has {n} '{key}' mesh keys; expected one")
    hierarchy = r"  hierarchy: \{[^}]*\}[^\n]*\n"
    text, n = re.subn(hierarchy, "" if levels is None else
                      f"  hierarchy: {{levels: {levels}, ratio: {RATIO}}}\n", text)
    if n != 1:
        raise SystemExit(f"studies: error: {path} has no 'hierarchy:' line to edit")
    return text.replace("options_file: ../../", f"options_file: {source}/")


def rmtr_fields(result):
    """Levels, the coarsest level's dofs and the coarse corrections accepted and rejected over
    every level and step (1 level and blanks for a single-level solver)."""
    rm = ((result["summary"] or {}).get("solver") or {}).get("rmtr")
    if not rm:
        return {"levels": 1, "coarsest_dofs": "", "coarse_accepted": "", "coarse_rejected": ""}
    levels = rm["levels"]
    return {"levels": len(levels), "coarsest_dofs": levels[0]["dofs"],
            "coarse_accepted": sum(int(l["coarse_accepted"]) for l in levels),
            "coarse_rejected": sum(int(l["coarse_rejected"]) for l in levels)}


def energy(result):
    """The final total energy to 12 digits (a string: the CSV writer keeps 6 of a float's),
    enough to tell round-off from another minimiser."""
    total = ((result["summary"] or {}).get("energy") or {}).get("total")
    return "" if total is None else f"{total:.12g}"


def run(ctx):
    rows = []
    for scene in ctx.scenes(QUICK_SCENES, SCENES):
        steps = STEPS.get(scene, ctx.pick(1, FULL_STEPS))
        given_up = set()
        for resolution, dofs in ctx.pick(RESOLUTIONS[scene][:1], RESOLUTIONS[scene]):
            if ctx.max_dofs is not None and dofs > ctx.max_dofs:
                print(f"  [{NAME}] {scene}-{resolution}: about {dofs:,} dofs, above --max-dofs "
                      f"{ctx.max_dofs:,}: not run", flush=True)
                continue
            for solver in ctx.solvers(ctx.pick(QUICK_SOLVERS, SOLVERS)):
                if solver in given_up:
                    continue
                levels = None if solver in SINGLE_LEVEL else hierarchy_levels(dofs)
                r = ctx.run(NAME, f"{scene}-{resolution}-{solver}", scene, None,
                            with_tolerance(solver, ctx.source, 1e-7, MAX_IT, relative=False),
                            scene_text=scene_text(ctx.source, scene, resolution, levels),
                            steps=steps)
                if r["timed_out"]:
                    given_up.add(solver)
                row = {**solver_fields(r), **rmtr_fields(r), "solver": solver,
                       "resolution": resolution, "steps": steps, "energy": energy(r)}
                if row["dofs"] == "":
                    row.update(levels=levels or 1, energy="")
                rows.append(row)
    ctx.write_csv(NAME, rows, COLUMNS, key=("scene", "solver"))
