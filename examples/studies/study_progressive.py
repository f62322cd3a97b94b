"""Progressive shell quasistatics (issue 46, paper 2 §3 and §5): what each level's accuracy costs in
time. Every scene runs its whole loading along four routes, all solving to the same tolerance:
- `direct-fine`: quasistatic on the fine mesh, with the scene's solver (projected Newton + MUMPS);
- `direct-coarse`: the same, on the coarsest level's mesh alone (its own energy, no proxy);
- `progressive`: the loading on the coarsest level's proxy, then refined to the converged fine
  result (`time.integrator: progressive`);
- `rmtr`: quasistatic on the fine mesh by RMTR on the same hierarchy (mlshell's default RMTR).

The progressive run gives a row per level: `time` is the wall time from the start of the solve
to that level's end (setup excluded, as for the others' `solve_time`), and `error` is the largest
and RMS vertex distance of that level's result, prolonged to the fine mesh, to the converged fine
result. Every route also gives its probe's distance to the direct fine run's probe (`probe_error`):
the only error a coarse mesh's own result has, since its vertices are not the fine ones.

`--solvers` picks routes (direct-coarse, progressive, rmtr; the direct fine run, every error's
reference, always runs); a run replaces the rows of the scenes, resolutions and routes it ran.

The hierarchy is the scene's `hierarchy: {levels: L, ratio: 4}` with the fewest levels whose
coarsest has at most study_triangle.COARSEST_VERTICES vertices; the coarsest level's mesh comes
from `-mlshell_hierarchy_write`."""
import math
import re

from runner import solver_fields
from solvers import with_tolerance
import study_triangle

NAME = "progressive"
COLUMNS = ["scene", "route", "resolution", "dofs", "level", "level_dofs", "levels", "steps",
           "time", "wall_time", "iterations", "converged", "reason", "max_error", "rms_error",
           "probe_error", "final_rms", "energy"]
SCENES = ("plate_buckling", "plate_shearing", "shell_indent", "unstructured_drape", "balloon")
QUICK_SCENES = ("plate_buckling",)
ROUTES = ("direct-fine", "direct-coarse", "progressive", "rmtr")
MESH_KEY = dict(study_triangle.MESH_KEY, plate_shearing="faces", balloon="subdivisions")
# Resolutions and their dofs: quick runs the first, full the others, --max-dofs permitting: about
# 10,000 dofs, and the goal, a finest level of at least 50,000 dofs.
RESOLUTIONS = {
    "plate_buckling": ((16, 867), (64, 12675), (128, 49923)),
    "plate_shearing": ((16, 867), (64, 12675), (128, 49923)),
    "shell_indent": ((16, 2325), (32, 9054), (76, 50700)),
    "unstructured_drape": ((0.05, 1530), (0.025, 5916), (0.008, 57000)),
    "balloon": ((3, 1926), (4, 7686), (6, 122886)),
}
TOLERANCE = 1e-7
MAX_IT = 2000
# The steel plates' gradient cannot fall below 2e-6 ... 2e-5 (their round-off floor), 20 to 170
# times TOLERANCE: projected Newton may end there as converged at the limiting accuracy within
# this factor of it (its default, 100, fails the plate shearing's direct fine run at 170).
LIMITING_FACTOR = 1000


def scene_text(source, scene, resolution, levels, integrator="quasistatic", mesh_obj=None):
    """The scene at `resolution` with `levels` levels (None: none), its integrator, and its mesh
    replaced by an OBJ file if `mesh_obj` is given."""
    if scene in study_triangle.MESH_KEY:
        text = study_triangle.scene_text(source, scene, resolution, levels)
    else:
        text = (source / "examples" / "triangle" / f"{scene}.yaml").read_text()
        key = MESH_KEY[scene]
        value = f"[{resolution}, {resolution}]" if key == "faces" else f"{resolution}"
        text = re.sub(r"faces: \[\d+, \d+\]" if key == "faces" else rf"{key}: [0-9.]+",
                      f"{key}: {value}", text, count=1)
        text = re.sub(r"  hierarchy: \{[^}]*\}[^\n]*\n", "" if levels is None else
                      f"  hierarchy: {{levels: {levels}, ratio: {study_triangle.RATIO}}}\n", text)
        text = text.replace("options_file: ../../", f"options_file: {source}/")
    text = text.replace("integrator: quasistatic", f"integrator: {integrator}")
    if mesh_obj is not None:
        text, n = re.subn(r"  mesh: \{[^}]*\}", f"  mesh: {{obj: {mesh_obj}}}", text)
        if n != 1:
            raise SystemExit(f"studies: error: {scene} has no one-line 'mesh:' to replace")
        # Named sides and corners exist on generated rectangles only: the same places as boxes
        # and points (every studied rectangle is [0, 1]²).
        for name, where in OBJ_SELECTIONS.items():
            text = text.replace(name, where)
    return text


_SIDE = "{{box: {{min: [{0}, {1}, -1], max: [{2}, {3}, 1]}}}}"
OBJ_SELECTIONS = {
    "boundary(left)": _SIDE.format(-1e-9, -1, 1e-9, 2),
    "boundary(right)": _SIDE.format(1 - 1e-9, -1, 1 + 1e-9, 2),
    "corner(top-left)": "{at: [0, 1, 0]}",
    "corner(top-right)": "{at: [1, 1, 0]}",
}


def steps_of(source, scene):
    text = (source / "examples" / "triangle" / f"{scene}.yaml").read_text()
    return int(re.search(r"steps: (\d+)", text).group(1))


def probe(result):
    """The first probe's displacement, or None."""
    probes = (result["summary"] or {}).get("probes") or {}
    return next((p["displacement"] for p in probes.values()), None)


def distance(a, b):
    return "" if a is None or b is None else math.dist(a, b)


def energy(result):
    total = ((result["summary"] or {}).get("energy") or {}).get("total")
    return "" if total is None else f"{total:.12g}"


def run(ctx):
    rows = []
    for scene in ctx.scenes(QUICK_SCENES, SCENES):
        steps = steps_of(ctx.source, scene)
        for resolution, dofs in ctx.pick(RESOLUTIONS[scene][:1], RESOLUTIONS[scene][1:]):
            if ctx.max_dofs is not None and dofs > ctx.max_dofs:
                continue
            rows += run_scene(ctx, scene, resolution, dofs, steps)
    ctx.write_csv(NAME, rows, COLUMNS, key=("scene", "resolution", "route"))


def run_scene(ctx, scene, resolution, dofs, steps):
    levels = study_triangle.hierarchy_levels(dofs)
    tag = f"{scene}-{resolution}"
    common = {"resolution": resolution, "levels": levels, "steps": steps}
    solver = with_tolerance("pnewton", ctx.source, TOLERANCE, MAX_IT, relative=False) + \
        ["-tao_pnewton_limiting_factor", str(LIMITING_FACTOR)]

    def text(levels_, integrator="quasistatic", mesh_obj=None):
        return scene_text(ctx.source, scene, resolution, levels_, integrator, mesh_obj)

    rows = []
    routes = ctx.solvers(ROUTES)
    # The reference of every error: always run.
    fine = ctx.run(NAME, f"{tag}-direct-fine", scene, None, solver, scene_text=text(None),
                   steps=steps)
    reference = probe(fine)
    rows.append({**solver_fields(fine), **common, "route": "direct-fine", "level": "",
                 "level_dofs": fine["summary"]["dofs"] if fine["summary"] else "",
                 "time": (fine["summary"] or {}).get("solver", {}).get("solve_time", ""),
                 "max_error": 0.0 if fine["summary"] else "",
                 "rms_error": 0.0 if fine["summary"] else "",
                 "probe_error": 0.0 if fine["summary"] else "", "energy": energy(fine)})
    # The coarsest level's mesh, written by the hierarchy of the same scene.
    levels_dir = ctx.out / "runs" / NAME / f"{tag}-levels" / "levels"
    ctx.run(NAME, f"{tag}-levels", scene, None,
            ["-mlshell_evaluate", "-mlshell_hierarchy_write", str(levels_dir)],
            scene_text=text(levels), steps=1)
    coarse_mesh = levels_dir / "level_0.obj"
    if coarse_mesh.is_file() and "direct-coarse" in routes:
        coarse = ctx.run(NAME, f"{tag}-direct-coarse", scene, None, solver,
                         scene_text=text(None, mesh_obj=coarse_mesh), steps=steps)
        rows.append({**solver_fields(coarse), **common, "route": "direct-coarse", "level": 0,
                     "level_dofs": (coarse["summary"] or {}).get("dofs", ""),
                     "time": (coarse["summary"] or {}).get("solver", {}).get("solve_time", ""),
                     "probe_error": distance(probe(coarse), reference),
                     "energy": energy(coarse)})
    if "progressive" in routes:
        rows += progressive_rows(ctx, NAME, tag, scene, solver, text(levels, "progressive"),
                                 common, levels, steps, reference)
    if "rmtr" in routes:
        rm = ctx.run(NAME, f"{tag}-rmtr", scene, None,
                     with_tolerance("rmtr-patch-dogleg", ctx.source, TOLERANCE, MAX_IT,
                                    relative=False),
                     scene_text=text(levels), steps=steps)
        rows.append({**solver_fields(rm), **common, "route": "rmtr", "level": "",
                     "level_dofs": (rm["summary"] or {}).get("dofs", ""),
                     "time": (rm["summary"] or {}).get("solver", {}).get("solve_time", ""),
                     "probe_error": distance(probe(rm), reference), "energy": energy(rm)})
    for r in rows:
        r["scene"] = scene
    return rows


def progressive_rows(ctx, study, tag, scene, solver, text, common, levels, steps, reference):
    """A progressive run's rows, one per level."""
    rows = []
    prog = ctx.run(study, f"{tag}-progressive", scene, None, solver, scene_text=text,
                   steps=steps)
    section = (prog["summary"] or {}).get("progressive") or {}
    base = {**solver_fields(prog), **common, "route": "progressive",
            "final_rms": section.get("final_rms_displacement") or ""}
    for level in section.get("levels", []):
        error = level.get("preview_error") or {}
        last = level["level"] == levels - 1
        p = next((q["displacement"] for q in (level.get("probes") or {}).values()), None)
        rows.append({**base, "level": level["level"], "level_dofs": level["dofs"],
                     "time": level["time_to_level"], "iterations": level["iterations"],
                     "converged": int(level["equilibrium"]), "reason": level["stop"],
                     "max_error": 0.0 if last else error.get("max_distance", ""),
                     "rms_error": 0.0 if last else error.get("rms_distance", ""),
                     "probe_error": distance(probe(prog) if last else p, reference),
                     "energy": f"{level['energy']:.12g}"})
    if not rows:
        rows.append({**base, "level": "", "level_dofs": ""})
    return rows
