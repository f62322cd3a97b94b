#!/usr/bin/python3
"""Runs every study in quick mode and checks what it wrote: each CSV exists, parses, has its
columns and the expected rows (one per case the quick mode defines), the numbers a converged
trampoline run must have are there, the plots are PNG files and REPORT.md names every study.

usage: quick_outputs.py BUILD_DIR WORK_DIR"""
import shutil
import subprocess
import sys
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "examples" / "studies"))

from context import PROVENANCE, number, read_csv  # noqa: E402
from runner import Runner  # noqa: E402
import studies  # noqa: E402

# study CSV -> rows the quick mode must produce, as (key columns -> values) sets.
EXPECTED_ROWS = {
    "iterations": 16,       # 4 scenes x (TR at refine 0, 1 + rmtr and the default on 2 levels)
    "work": 4,              # trampoline, drooping x (TR, RMTR)
    "projection": 2,        # lsq, reverse
    "condition": 4,         # 2 resolutions + 2 penalties
    "timestep": 10,         # 5 solvers x 2 time steps
    "accuracy": 8,          # 2 solvers x 2 resolutions x 2 tolerances
    "peers": 10,            # rmtr.yaml, the scene's own configuration + 8 PETSc ones
    "parallel": 6,          # rmtr, rmtr-patch and rmtr-patch-dogleg on 1 and 2 ranks
    "scaling": 17,          # refine 1: 9 solvers; refine 2: 8 (not the paper's ST-CG)
    "triangle": 4,          # plate buckling, shell indent x (projected Newton, RMTR)
}
# Rows quick mode expects to time out or not to run, as (study, scene, reason prefix); none today.
# Any other row whose run crashed, timed out or was skipped fails the test.
EXPECTED_FAILED_RUNS = set()
FAILED_RUN = ("exit ", "timeout", "not run")
PLOTS = ("iterations.png", "condition.png", "timestep.png", "accuracy_trampoline.png",
         "peers.png", "parallel.png", "scaling.png", "triangle.png")


def fail(message):
    sys.exit(f"quick_outputs: FAIL: {message}")


def failed_runs(name, rows):
    """The rows of study `name` whose run did not end with a result of mlshell's own (exit 0 or
    3), less those EXPECTED_FAILED_RUNS allows."""
    return [f"{r['scene']}: {r['reason']}" for r in rows
            if "reason" in r and r["reason"].startswith(FAILED_RUN)
            and not any(name == s and r["scene"] == c and r["reason"].startswith(p)
                        for s, c, p in EXPECTED_FAILED_RUNS)]


def check(out, build):
    if not build:
        fail("mlshell --version names no commit")
    for name, count in EXPECTED_ROWS.items():
        path = out / f"{name}.csv"
        if not path.is_file():
            fail(f"{path} was not written")
        rows = read_csv(path)
        columns = getattr(studies.STUDIES[name], "COLUMNS") + [PROVENANCE]
        if not rows or list(rows[0].keys()) != columns:
            fail(f"{path}: header is not {columns}")
        # Every row names the build that measured it: this one.
        strangers = {r[PROVENANCE] for r in rows} - {build}
        if strangers:
            fail(f"{path}: rows measured by builds {sorted(strangers)}, not {build!r}")
        if len(rows) != count:
            fail(f"{path}: {len(rows)} rows, expected {count}")
        failed = failed_runs(name, rows)
        if failed:
            fail(f"{path}: runs that crashed, timed out or did not run: {failed}")
    # The trampoline converges with TR and RMTR in quick mode (or, at worst, stops on the
    # round-off floor of the gradient just above 1e-7): its numbers must be real.
    for r in read_csv(out / "iterations.csv"):
        if r["scene"] == "trampoline" and not (
                number(r["iterations"]) and (r["converged"] == "1" or
                                             number(r["gradient_norm"], 1.0) < 1e-6)):
            fail(f"iterations.csv: trampoline {r['solver']} refine {r['refine']} did not "
                 f"converge: {r['reason']}, |g| = {r['gradient_norm']}")
    acc = [r for r in read_csv(out / "accuracy.csv") if r["solver"] == "rmtr"]
    errors = {(r["refine"], r["tolerance"]): number(r["l2_error"]) for r in acc}
    if any(e is None or not e > 0 for e in errors.values()):
        fail(f"accuracy.csv: RMTR rows lack a positive L2 error: {errors}")
    # Finer resolution at the tight tolerance must be closer to the reference.
    if not errors[("1", "1e-05")] < errors[("0", "1e-05")]:
        fail(f"accuracy.csv: the L2 error does not fall with refinement: {errors}")
    cond = [number(r["condition"]) for r in read_csv(out / "condition.csv")
            if r["sweep"] == "dofs"]
    if not all(c and c > 1 for c in cond) or not cond[1] > cond[0]:
        fail(f"condition.csv: condition numbers {cond} do not grow with the dofs")
    par = read_csv(out / "parallel.csv")
    if any(number(r["stage_solve"]) is None for r in par):
        fail("parallel.csv: a run lacks the -log_view Solve stage time")
    if any(r["ranks"] == "1" and not number(r["shared_wall_time"], 0.0) > 0 for r in par):
        fail("parallel.csv: a 1-rank run lacks the wall time of its two copies run at once")
    if not read_csv(out / "parallel_events.csv"):
        fail("parallel_events.csv is empty")
    for r in read_csv(out / "scaling.csv"):
        if r["converged"] == "1" and not number(r["peak_rss_mib"], 0.0) > 0:
            fail(f"scaling.csv: {r['solver']} refine {r['refine']} has no peak memory")
    for r in read_csv(out / "triangle.csv"):
        if not (r["converged"] == "1" and number(r["energy"]) is not None and
                number(r["peak_rss_mib"], 0.0) > 0):
            fail(f"triangle.csv: {r['scene']} {r['solver']} did not converge with an energy and "
                 f"a peak memory: {r['reason']}")
    energies = {}
    for r in read_csv(out / "triangle.csv"):
        energies.setdefault(r["scene"], []).append(number(r["energy"]))
    for scene, e in energies.items():  # projected Newton and RMTR reach the same minimiser
        if max(e) - min(e) > 1e-8 * max(abs(x) for x in e):
            fail(f"triangle.csv: {scene}'s solvers end at different energies {e}")
    for plot in PLOTS:
        data = (out / plot).read_bytes() if (out / plot).is_file() else b""
        if not data.startswith(b"\x89PNG"):
            fail(f"{plot} is missing or not a PNG")
    problems = report_problems((out / "REPORT.md").read_text())
    if problems:
        fail("REPORT.md: " + "; ".join(problems))


def report_problems(report):
    """What is wrong with a REPORT.md of every study: a section or plot missing, or the
    sections out of order (the headline first, the commands and builds last)."""
    problems = [f"no section '{heading}'" for heading in (
        "## Headline", "## Performance goals", "Table 3", "Table 4", "Tables 6–7", "Table 8",
        "Figure 9", "Figure 10", "## Accuracy vs time", "## RMTR vs PETSc", "## Parallel",
        "## RMTR at scale", "## RMTR on triangle hierarchies", "## Reproduce",
        "## Provenance") if heading not in report]
    problems += [f"does not show {plot}" for plot in PLOTS if f"]({plot})" not in report]
    headings = [line[3:] for line in report.splitlines() if line.startswith("## ")]
    if headings[:2] != ["Headline", "Performance goals"] or \
            headings[-2:] != ["Reproduce", "Provenance"]:
        problems.append(f"sections out of order: {headings}")
    return problems


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    build, out = Path(argv[1]), Path(argv[2])
    # Files of an earlier run must not pass for this run's output.
    shutil.rmtree(out, ignore_errors=True)
    code = subprocess.run([sys.executable, str(SOURCE / "examples/studies/studies.py"), "--quick",
                           "--build", str(build), "--out", str(out)]).returncode
    if code != 0:
        fail(f"studies.py --quick exited with {code}")
    check(out, Runner(build, out).build())
    print("quick_outputs: every study wrote its CSV, plots and report section")


if __name__ == "__main__":
    main(sys.argv)
