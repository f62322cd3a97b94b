#!/usr/bin/env bash
# Hard-case stability suite (issue: hard cases stay numerically stable). Every case has an
# expected outcome, and today every one of them is to converge (eq. 7.1 or the limiting-accuracy
# stop: exit 0, status "complete", a CONVERGED_* reason). A case expected to stop instead names
# the reason (exit 3, status "solver_failed"). No case may crash or write NaN or Inf, every case
# must print RMTR's V-cycle monitor, and RMTR's energy must never increase from one V-cycle to the
# next.
#
# Cases: dt = 1 on the four paper scenes; penalty beta = 1e10; cages with extraordinary vertices
# of valence 3, 5 and 8; the re-entrant corner with 5 levels; thickness 0.066 mm; fast boundary
# motion (an edge lifted 0.3 m in one step).
#
# usage: bash tests/hard_cases/run.sh MLSHELL WORK_DIR [--quick|--full] [RANKS]
#   --quick (default, ctest cli.hard_cases): 363 dofs (2 levels; the re-entrant corner 1,479),
#           one step, at most 600 V-cycles (about 2 minutes on 2 cores).
#   --full: 13,467 dofs for the paper scenes (refine 4), 5 levels for the re-entrant corner,
#           three steps, at most 1000 V-cycles (hours on 2 cores; meant for a larger machine).
set -euo pipefail
MLSHELL=$(realpath "$1")
WORK=$2
MODE=${3:---quick}
RANKS=${4:-2}
SRC=$(cd "$(dirname "$0")/../.." && pwd)
PY=/usr/bin/python3
export OMPI_ALLOW_RUN_AS_ROOT=${OMPI_ALLOW_RUN_AS_ROOT:-1}
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=${OMPI_ALLOW_RUN_AS_ROOT_CONFIRM:-1}
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
[[ -n $WORK && $WORK != / ]] || { echo "bad WORK_DIR: '$WORK'" >&2; exit 2; }
rm -rf "$WORK" && mkdir -p "$WORK" && cd "$WORK"

case $MODE in
  --quick) REFINE=1; STEPS=1; LREFINE=1; MAX_IT=600 ;;
  --full) REFINE=4; STEPS=3; LREFINE=3; MAX_IT=1000 ;;
  *) echo "unknown mode '$MODE' (--quick or --full)" >&2; exit 2 ;;
esac

failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# A fan cage: one interior vertex of the given valence, two rings of quads (OBJ).
fan_obj() {
  $PY - "$1" >"fan$1.obj" <<'EOF'
import math, sys
n = int(sys.argv[1])
pts = [(0.0, 0.0, 0.0)]
for r in range(2):
    for k in range(n):
        a, b = 2 * math.pi * k / n, 2 * math.pi * (k + 0.5) / n
        pts.append(((r + 1) * 0.3 * math.cos(a), (r + 1) * 0.3 * math.sin(a), 0.0))
        pts.append(((r + 1.3) * 0.3 * math.cos(b), (r + 1.3) * 0.3 * math.sin(b), 0.0))
spoke = lambda r, k: 2 + r * 2 * n + 2 * (k % n)
mid = lambda r, k: 3 + r * 2 * n + 2 * (k % n)
quads = []
for k in range(n):
    quads.append((1, spoke(0, k), mid(0, k), spoke(0, k + 1)))
    quads.append((spoke(0, k), spoke(1, k), mid(1, k), mid(0, k)))
    quads.append((mid(0, k), mid(1, k), spoke(1, k + 1), spoke(0, k + 1)))
for p in pts:
    print("v %.10f %.10f %.10f" % p)
for q in quads:
    print("f %d %d %d %d" % q)
EOF
}

# run NAME SCENE_FILE [OPTIONS...]: runs, then checks the outcome against EXPECT (a reason
# prefix; CONVERGED unless the caller sets EXPECT for this one call: EXPECT=DIVERGED_X run ...).
run() {
  local name=$1 scene=$2 expect=${EXPECT:-CONVERGED}
  shift 2
  local status=0
  mpiexec --oversubscribe -n "$RANKS" "$MLSHELL" "$scene" -mlshell_output_dir "out/$name" \
    -mlshell_steps "$STEPS" -tao_max_it "$MAX_IT" -tao_rmtr_monitor "$@" >"$name.log" 2>&1 || status=$?
  local summary="out/$name/summary.json"
  if [[ $status -ne 0 && $status -ne 3 ]]; then
    fail "$name: exit status $status (expected 0 or 3); see $WORK/$name.log"
    tail -5 "$name.log" >&2
    return
  fi
  [[ -f $summary ]] || { fail "$name: no summary.json"; return; }
  if ! $PY - "$summary" "$name.log" "$status" "out/$name/steps.csv" "$expect" <<'EOF'; then
import json, math, os, re, sys
summary_path, log_path, status, csv_path = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
expect = sys.argv[5]
text = open(summary_path).read()
s = json.loads(text)
problems = []
def finite(x, where):
    if isinstance(x, float) and not math.isfinite(x):
        problems.append("non-finite number at " + where)
    elif isinstance(x, dict):
        for k, v in x.items():
            finite(v, where + "." + k)
    elif isinstance(x, list):
        for i, v in enumerate(x):
            finite(v, "%s[%d]" % (where, i))
finite(s, "summary")
if re.search(r"\b(nan|inf)\b", text, re.I):
    problems.append("summary.json contains nan/inf")
if os.path.exists(csv_path) and re.search(r"\b(nan|inf)\b", open(csv_path).read(), re.I):
    problems.append("steps.csv contains nan/inf")
reason = s["solver"]["reason"]
if not reason.startswith(expect):
    problems.append("expected a %s* outcome, got %s (exit %d)" % (expect, reason, status))
if status == 0:
    if s["status"] != "complete" or not reason.startswith("CONVERGED"):
        problems.append("exit 0 but status %s, reason %s" % (s["status"], reason))
else:
    if s["status"] != "solver_failed" or not reason.startswith("DIVERGED"):
        problems.append("exit 3 but status %s, reason %s" % (s["status"], reason))
# RMTR: f never increases from one V-cycle to the next within a step, beyond its rounding: near
# the limiting accuracy a step is accepted on the gradients' trapezoidal reduction if f rose by
# less than 10 times its evaluation error (about 1e-12 |f| for Table 1's sums; docs/solvers.md), so a
# rise below 1e-10 |f| is round-off, and a wrongly accepted step rises far more.
previous, cycles = None, 0
for line in open(log_path):
    m = re.match(r"\s*rmtr cycle\s+(\d+)\s+f\s+(\S+)", line)
    if not m:
        continue
    cycle, f = int(m.group(1)), float(m.group(2))
    cycles += 1
    if not math.isfinite(f):
        problems.append("non-finite energy in V-cycle %d" % cycle)
    if cycle > 1 and previous is not None and f > previous + 1e-10 * abs(previous):
        problems.append("energy rose in V-cycle %d: %.17g > %.17g" % (cycle, f, previous))
    previous = f
if cycles == 0:
    problems.append("no 'rmtr cycle' monitor line in the log: the energy check saw nothing")
for p in problems:
    print(p)
sys.exit(1 if problems else 0)
EOF
    fail "$name: see above and $WORK/$name.log"
    return
  fi
  local outcome
  outcome=$(grep -E '^step ' "$name.log" | tail -1 | awk '{for (i = 1; i <= NF; ++i) if ($i ~ /^(CONVERGED|DIVERGED)/) print $i}')
  printf 'ok   %-24s exit %d  %s\n' "$name" "$status" "$outcome"
}

# scene_copy NAME EXAMPLE REFINE SED_EXPRESSION...: examples/EXAMPLE.yaml at REFINE, edited into
# NAME.yaml. An expression that changes nothing (the example was edited since) is an error, so a
# case never silently runs the unedited scene.
scene_copy() {
  local name=$1 example=$2 refine=$3
  shift 3
  # The copy lies elsewhere: the scene's solver file by its path in the source tree.
  sed -e "s/^\(  refine:\) *[0-9]*/\1 $refine/" \
    -e "s|options_file: \.\./|options_file: $SRC/|" "$SRC/examples/$example.yaml" >"$name.yaml"
  grep -qE "^  refine: $refine( |\$)" "$name.yaml" || {
    echo "hard cases: error: examples/$example.yaml has no '  refine:' line to set" >&2; exit 2; }
  for e in "$@"; do
    sed -e "$e" "$name.yaml" >"$name.yaml.tmp"
    if cmp -s "$name.yaml" "$name.yaml.tmp"; then
      echo "hard cases: error: '$e' changes nothing in examples/$example.yaml" >&2
      exit 2
    fi
    mv "$name.yaml.tmp" "$name.yaml"
  done
}

for scene in trampoline drooping drape; do
  scene_copy "$scene" "$scene" "$REFINE"
  run "dt1-$scene" "$scene.yaml" -mlshell_dt 1
done
scene_copy reentrant reentrant_corner "$LREFINE"
run "dt1-reentrant-corner" reentrant.yaml -mlshell_dt 1

scene_copy penalty trampoline "$REFINE" 's/dirichlet: {where: boundary}/dirichlet: {where: boundary, penalty: 1.0e10}/'
run "penalty-1e10" penalty.yaml

for valence in 3 5 8; do
  fan_obj "$valence"
  cat >"valence$valence.yaml" <<EOF
name: valence$valence
geometry:
  cage: {obj: fan$valence.obj}
  refine: $REFINE
material: {model: clyde-orthotropic, preset: denim, thickness: 0.66e-3, density: 0.4}
effects:
  - inertia
  - gravity: [0, 0, -9.81]
  - dirichlet: {where: boundary}
time: {dt: 1.0, steps: 3}
output: {dir: out/valence$valence, formats: [csv]}
EOF
  run "valence-$valence" "valence$valence.yaml"
done

scene_copy thin trampoline "$REFINE" 's/thickness: 0.66e-3/thickness: 0.066e-3/'
run "thickness-0.066mm" thin.yaml

scene_copy fast trampoline "$REFINE" \
  's/dirichlet: {where: boundary}/dirichlet: {where: boundary(left), motion: {translate: [0, 0, 0.3], over: [0, 1]}}\n  - dirichlet: {where: boundary(right)}/'
run "fast-boundary-motion" fast.yaml

if [[ $failures -gt 0 ]]; then
  echo "$failures hard case(s) failed" >&2
  exit 1
fi
echo "all hard cases had their expected outcome"
