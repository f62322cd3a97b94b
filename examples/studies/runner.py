"""Runs one mlshell solve for a study and returns what it measured.

Every run is one implicit-Euler step from the scene's initial state (or `steps` of the scene's
own stepping, for the triangle scenes, whose resolution is their mesh spec and not a refine), in
its own output folder (OUT/runs/<study>/<tag>/). The result is summary.json, plus the -log_view stage and event times
when asked for. A run that exceeds its time limit is killed and reported as such, never dropped.
"""
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
SCENES = ("trampoline", "drooping", "reentrant_corner", "drape")
# The re-entrant corner's cage has 91 faces (10×10 minus the cut), not the others' 16: refine 4
# already gives ~70,000 dofs, above the paper's finest (51,483); finer ones are not run.
MAX_REFINE = {"reentrant_corner": 4}
# Every CSV's last column: the mlshell build (commit) that measured the row.
PROVENANCE = "commit"
# The denim presets a study compares: the default (coupling limited, ψ > 0) and Table 1 as printed.
PRESETS = ("denim", "denim-table1")


def comparable_refine(scene, refine):
    """The refine of `scene` whose dof count is nearest the 16-face scenes' at `refine`: the
    re-entrant corner's 91-face cage reaches it one level earlier (1,479 dofs vs 1,083)."""
    return max(0, refine - 1) if scene == "reentrant_corner" else refine


def scene_text(scene, preset):
    """The example scene with its denim preset replaced (None: the scene as it is)."""
    if preset == "denim":
        return None
    text = (SOURCE / "examples" / f"{scene}.yaml").read_text()
    edited = text.replace("preset: denim,", f"preset: {preset},")
    if edited == text:
        raise SystemExit(f"studies: error: examples/{scene}.yaml has no 'preset: denim,' to edit")
    return edited


def preset_tag(preset):
    """The suffix of a run folder's tag: none for the default preset."""
    return "" if preset == "denim" else f"-{preset}"


def mpi_environment():
    env = dict(os.environ)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    return env


class Runner:
    def __init__(self, build, out, ranks=2, timeout=1800.0, verbose=True, max_refine=8):
        self.mlshell = Path(build).resolve() / "mlshell"
        if not self.mlshell.is_file():
            sys.exit(f"studies: error: no mlshell executable at '{self.mlshell}' (build first: "
                     f"bash .ci/build, or pass --build DIR)")
        self.out = Path(out).resolve()
        self.ranks = ranks
        self.timeout = timeout
        self.verbose = verbose
        self.max_refine = max_refine

    def build(self):
        """The commit mlshell was built from (`mlshell --version`), '' if it does not say."""
        try:
            out = subprocess.run([str(self.mlshell), "--version"], capture_output=True,
                                 text=True, timeout=60, env=mpi_environment()).stdout
        except (OSError, subprocess.TimeoutExpired):
            return ""
        m = re.search(r"\(commit ([^)\s]+)\)", out)
        return m.group(1) if m else ""

    def scene_path(self, scene):
        path = SOURCE / "examples" / f"{scene}.yaml"
        if not path.is_file():
            sys.exit(f"studies: error: no scene '{scene}' ({path})")
        return path

    def finest(self, scene):
        """The finest refine this runner solves `scene` at (the scene's and --max-refine's)."""
        return min(MAX_REFINE.get(scene, 8), self.max_refine)

    def run(self, study, tag, scene, refine, options=(), dt=1.0, ranks=None, scene_text=None,
            log_view=False, steps=1):
        """`steps` steps (one by default) of `scene` at `refine` with the given PETSc options;
        returns a dict. refine None: the scene's own resolution (triangle meshes, whose
        resolution `scene_text` sets), no -mlshell_refine."""
        return self.run_copies(study, tag, scene, refine, options, dt, ranks, scene_text,
                               log_view, copies=1, steps=steps)[0]

    def run_copies(self, study, tag, scene, refine, options=(), dt=1.0, ranks=None,
                   scene_text=None, log_view=False, copies=2, steps=1):
        """`copies` identical runs started together (folders <tag>, <tag>-copy2, ...): what
        sharing the machine's memory bandwidth and caches costs one run; returns their dicts."""
        ranks = ranks or self.ranks
        if refine is not None and refine > self.finest(scene):
            return [{"study": study, "tag": tag, "scene": scene, "refine": refine,
                     "ranks": ranks, "dt": dt, "exit_code": None, "timed_out": False,
                     "elapsed": 0.0, "folder": None, "summary": None, "skipped": True}
                    for _ in range(copies)]
        tags = [tag] + [f"{tag}-copy{k}" for k in range(2, copies + 1)]
        # Open MPI binds a 1-rank job to core 0: copies must be free to run on the other cores.
        binding = ["--bind-to", "none"] if copies > 1 else []
        launched = [self._launch(study, t, scene, refine, options, dt, ranks, scene_text,
                                 log_view, binding, steps) for t in tags]
        return [self._collect(*job) for job in launched]

    def _launch(self, study, tag, scene, refine, options, dt, ranks, scene_text, log_view,
                binding, steps=1):
        folder = self.out / "runs" / study / tag
        folder.mkdir(parents=True, exist_ok=True)
        for stale in ("summary.json", "log_view.txt", "limit_surface.csv"):
            (folder / stale).unlink(missing_ok=True)
        if scene_text is None:
            scene_file = self.scene_path(scene)
        else:
            scene_file = folder / f"{scene}.yaml"
            # The copy lies in a run folder: the scene's solver file by its path in the sources
            # (it must exist to parse, although every run ignores it).
            scene_file.write_text(scene_text.replace("options_file: ../", f"options_file: {SOURCE}/"))
        resolution = [] if refine is None else ["-mlshell_refine", str(refine)]
        command = ["mpiexec", "--oversubscribe", *binding, "-n", str(ranks), str(self.mlshell),
                   str(scene_file), "-mlshell_steps", str(steps), "-mlshell_dt", repr(dt),
                   *resolution, "-mlshell_output_dir", str(folder),
                   "-mlshell_quiet", "-mlshell_scene_solver", "false", *map(str, options)]
        if log_view:
            command += ["-log_view", f":{folder / 'log_view.txt'}"]
        (folder / "command.txt").write_text(" ".join(command) + "\n")
        log = open(folder / "stdout.txt", "w")
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT,
                                   env=mpi_environment())
        result = {"study": study, "tag": tag, "scene": scene, "refine": refine, "ranks": ranks,
                  "dt": dt, "exit_code": None, "timed_out": False, "elapsed": 0.0,
                  "folder": folder, "summary": None}
        return result, process, log, time.monotonic(), log_view

    def _collect(self, result, process, log, start, log_view):
        folder, study, tag = result["folder"], result["study"], result["tag"]
        try:
            remaining = max(0.0, self.timeout - (time.monotonic() - start))
            result["exit_code"] = process.wait(timeout=remaining)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
            result["timed_out"] = True
        log.close()
        result["elapsed"] = time.monotonic() - start
        # The studies read summary.json, stdout, -log_view and limit_surface.csv; the frames
        # and checkpoints (gigabytes over a full study) are not kept.
        for pattern in ("*.h5", "*.obj", "*.xdmf", "checkpoint_*.bin"):
            for heavy in folder.glob(pattern):
                heavy.unlink()
        summary = folder / "summary.json"
        if summary.is_file() and not result["timed_out"]:
            result["summary"] = json.loads(summary.read_text())
        if result["exit_code"] not in (0, 3) and not result["timed_out"]:
            tail = (folder / "stdout.txt").read_text().strip().splitlines()[-3:]
            print(f"  [{study}] {tag}: mlshell failed with exit {result['exit_code']}: "
                  f"{' | '.join(tail)}", flush=True)
        if log_view and (folder / "log_view.txt").is_file():
            result["log"] = parse_log_view((folder / "log_view.txt").read_text())
        if self.verbose:
            print(f"  [{study}] {tag}: {describe(result)}", flush=True)
        return result


def converged(result):
    s = result["summary"]
    return bool(s and s["status"] == "complete" and s["solver"]["converged"])


def describe(result):
    s = result["summary"]
    if result.get("skipped"):
        return "not run (finer than the scene's finest studied resolution or --max-refine)"
    if result["timed_out"]:
        return f"timed out after {result['elapsed']:.0f} s"
    if not s:
        return f"no summary (exit {result['exit_code']})"
    v = s["solver"]
    g = s["gradient_norm"]  # null in JSON when the iterate is not finite
    return (f"{s['dofs']} dofs, {v['type']}: {v['iterations']} its, {v['reason']}, "
            f"|g| = {'nan' if g is None else f'{g:.2e}'}, {s['wall_time']:.2f} s")


def solver_fields(result):
    """The columns every study shares, from one run's summary (empty when it has none)."""
    s = result["summary"]
    # The build that measured the row (summary.json "build", mlshell --version): the studies may
    # run a copy of an earlier build than the checkout's.
    build = (s or {}).get("build", {}).get("commit", "")
    base = {"scene": result["scene"], "refine": result["refine"], "ranks": result["ranks"],
            PROVENANCE: build}
    crashed = not result.get("skipped") and not result["timed_out"] and \
        result["exit_code"] not in (0, 3)
    if not s or crashed:  # a summary a crashed run left behind is not its result
        status = ("not run (finer than studied)" if result.get("skipped")
                  else f"timeout after {result['elapsed']:.0f} s" if result["timed_out"]
                  else f"exit {result['exit_code']}")
        return {**base, "dofs": "", "iterations": "", "linear_iterations": "", "converged": 0,
                "reason": status, "gradient_norm": "", "wall_time": "", "solve_time": "",
                "peak_rss_mib": ""}
    v = s["solver"]
    return {**base, "dofs": s["dofs"], "iterations": v["iterations"],
            "linear_iterations": v.get("linear_iterations", ""),
            "converged": int(converged(result)), "reason": v["reason"],
            "gradient_norm": "nan" if s["gradient_norm"] is None else s["gradient_norm"],
            "wall_time": s["wall_time"],
            "solve_time": v.get("solve_time", ""),
            "peak_rss_mib": s.get("memory", {}).get("peak_rss_mib_largest_rank", "")}


_STAGE = re.compile(r"^\s*\d+:\s+(.+?):\s+([0-9.eE+-]+)\s+([0-9.]+)%")
_EVENT_STAGE = re.compile(r"^--- Event Stage \d+: (.+)$")
_EVENT = re.compile(r"^(\S+)\s+(\d+)\s+[0-9.]+\s+([0-9.eE+-]+)\s+[0-9.]+")


def parse_log_view(text):
    """Stage times (seconds, max over ranks) and event times per stage from -log_view output."""
    stages, events, in_summary, stage = {}, {}, False, None
    for line in text.splitlines():
        if line.startswith("Summary of Stages"):
            in_summary = True
            continue
        if in_summary:
            m = _STAGE.match(line)
            if m:
                stages[m.group(1).strip()] = float(m.group(2))
            elif stages and not line.strip():
                in_summary = False
            continue
        m = _EVENT_STAGE.match(line.strip())
        if m:
            stage = m.group(1).strip()
            continue
        if stage:
            m = _EVENT.match(line)
            if m:
                events.setdefault(stage, {})[m.group(1)] = float(m.group(3))
    return {"stages": stages, "events": events}
