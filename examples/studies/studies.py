#!/usr/bin/python3
"""mlshell convergence studies (paper §7): runs each study on 2 MPI ranks, writes one CSV per
study, PNG plots and REPORT.md with the paper's values side by side.

  examples/studies/studies.py --quick            minutes: small cases, used by the test suite
  examples/studies/studies.py --full             the paper's resolutions: hours on 2 cores
  examples/studies/studies.py --full --only peers parallel --scenes trampoline
  examples/studies/studies.py --full --only scaling --solvers rmtr-patch   (refills those rows)
  examples/studies/studies.py --full --only triangle --max-dofs 30000   (triangle scenes)
  examples/studies/studies.py --full --only progressive   (accuracy against time, per level)
  examples/studies/studies.py --report-only --out DIR   redraw REPORT.md from DIR's CSVs

Studies: iterations (Tables 3-5), work (Tables 6-7), projection (Table 8), condition (Fig. 9),
timestep (Fig. 10), accuracy (error vs wall time, Pareto front), peers (RMTR vs PETSc TAO/SNES
with GAMG, BoomerAMG, MUMPS), parallel (1 vs 2 ranks, -log_view stages), scaling (V-cycles,
time and peak memory against resolution: Dogleg, vertex-patch and paper smoothers, TR, bnls),
triangle (RMTR on paper 2's decimation hierarchies of the triangle-mesh scenes, its three coarse
models against projected Newton and TR, against resolution), progressive (paper 2's progressive
runs against the direct fine and coarse runs and RMTR: each level's time and error).
Every solve runs in OUT/runs/<study>/<case>/ (command.txt, stdout.txt, summary.json)."""
import argparse
import datetime
import json
import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import report  # noqa: E402
import study_accuracy  # noqa: E402
import study_condition  # noqa: E402
import study_iterations  # noqa: E402
import study_parallel  # noqa: E402
import study_peers  # noqa: E402
import study_progressive  # noqa: E402
import study_projection  # noqa: E402
import study_scaling  # noqa: E402
import study_timestep  # noqa: E402
import study_triangle  # noqa: E402
import study_work  # noqa: E402
from context import Context  # noqa: E402
from runner import SCENES, SOURCE, Runner  # noqa: E402
from solvers import SOLVERS  # noqa: E402

STUDIES = {m.NAME: m for m in (study_iterations, study_work, study_projection, study_condition,
                               study_timestep, study_accuracy, study_peers, study_parallel,
                               study_scaling, study_triangle, study_progressive)}


def arguments(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog=__doc__.split("\n\n", 1)[1])
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--quick", dest="mode", action="store_const", const="quick",
                      help="small cases, minutes (default)")
    mode.add_argument("--full", dest="mode", action="store_const", const="full",
                      help="the paper's resolutions, hours")
    p.add_argument("--only", nargs="+", metavar="STUDY", choices=list(STUDIES),
                   help=f"run only these ({', '.join(STUDIES)})")
    scenes = list(dict.fromkeys(list(SCENES) + list(study_triangle.SCENES) +
                                list(study_progressive.SCENES)))
    p.add_argument("--scenes", nargs="+", metavar="SCENE", choices=scenes,
                   help=f"only these scenes ({', '.join(scenes)}); default: each study's own")
    p.add_argument("--solvers", nargs="+", metavar="SOLVER",
                   choices=list(SOLVERS) + list(study_progressive.ROUTES),
                   help="only these solver configurations (studies that compare several: "
                        "iterations, parallel, scaling; progressive: its routes); their rows "
                        "replace only the same solvers' rows")
    p.add_argument("--max-refine", type=int, default=8, metavar="R",
                   help="skip solves finer than geometry.refine R (e.g. 3: at most 3,675 dofs)")
    p.add_argument("--max-dofs", type=int, metavar="N",
                   help="skip the triangle study's resolutions above about N dofs (e.g. 30000)")
    p.add_argument("--build", default=str(SOURCE / "build"), help="folder holding mlshell")
    p.add_argument("--out", help="output folder (default BUILD/studies-MODE)")
    p.add_argument("--ranks", type=int, default=2, help="MPI ranks per solve (default 2)")
    p.add_argument("--timeout", type=float,
                   help="seconds one solve may take before it is killed and reported "
                        "(default 300 quick, 3600 full)")
    p.add_argument("--report-only", action="store_true", help="only redraw REPORT.md")
    a = p.parse_args(argv)
    a.mode = a.mode or "quick"
    if a.ranks < 1:
        p.error(f"--ranks must be >= 1; got {a.ranks}")
    if a.max_dofs is not None and a.max_dofs < 1:
        p.error(f"--max-dofs must be >= 1; got {a.max_dofs}")
    if a.timeout is not None and a.timeout <= 0:
        p.error(f"--timeout must be positive; got {a.timeout}")
    a.timeout_given = a.timeout is not None
    a.timeout = a.timeout or (300.0 if a.mode == "quick" else 3600.0)
    a.out = Path(a.out or Path(a.build) / f"studies-{a.mode}").resolve()
    return a


def main(argv):
    a = arguments(argv)
    a.out.mkdir(parents=True, exist_ok=True)
    if a.report_only:
        print(f"wrote {report.Report(a.out).write()}")
        return 0
    names = a.only or list(STUDIES)
    runner = Runner(a.build, a.out, a.ranks, a.timeout, max_refine=a.max_refine)
    ctx = Context(runner, a.mode, a.out, a.scenes, a.solvers, a.max_dofs)
    start = time.monotonic()
    for i, name in enumerate(names, 1):
        print(f"studies: [{i}/{len(names)}] {name} ({a.mode}), {time.monotonic() - start:.0f} s "
              "so far", flush=True)
        STUDIES[name].run(ctx)
    command = " ".join(["examples/studies/studies.py", f"--{a.mode}"] +
                       (["--only", *a.only] if a.only else []) +
                       (["--scenes", *a.scenes] if a.scenes else []) +
                       (["--solvers", *a.solvers] if a.solvers else []) +
                       ([f"--ranks {a.ranks}"] if a.ranks != 2 else []) +
                       ([f"--timeout {a.timeout:g}"] if a.timeout_given else []) +
                       ([f"--max-refine {a.max_refine}"] if a.max_refine < 8 else []) +
                       ([f"--max-dofs {a.max_dofs}"] if a.max_dofs is not None else []))
    # Several invocations may fill one folder (e.g. --only peers, then --only parallel): the
    # report lists every one of them.
    meta_path = a.out / "meta.json"
    meta = json.loads(meta_path.read_text()) if meta_path.is_file() else {"runs": []}
    if meta.get("mode", a.mode) != a.mode or not isinstance(meta.get("runs"), list):
        meta = {"runs": []}
    meta.update(mode=a.mode, ranks=a.ranks, cores=os.cpu_count())
    meta.pop("commit", None)  # the checkout's, which need not be the build's: each run says its own
    meta["runs"].append({"command": command, "studies": names, "elapsed": time.monotonic() - start,
                         "date": datetime.datetime.now().isoformat(timespec="seconds"),
                         "build": runner.build()})
    tmp = meta_path.with_suffix(".json.tmp")  # never a half-written meta.json
    tmp.write_text(json.dumps(meta, indent=1) + "\n")
    tmp.replace(meta_path)
    path = report.Report(a.out).write()
    print(f"studies: done in {time.monotonic() - start:.0f} s; report: {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
