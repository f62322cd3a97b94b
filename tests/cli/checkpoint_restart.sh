#!/usr/bin/env bash
# Checkpoint and restart: a denim square held on all edges, 4 steps of dt = 0.05 s with
# a checkpoint every 2 steps. Run A does all 4 steps; run B restarts from A's step-2 checkpoint
# and does steps 3 and 4. Both must end in the same state. Then a damaged checkpoint and one
# written for another refinement level must be refused with a message naming the file.
#
# Both runs are solved to a tight absolute gradient tolerance (-tao_gatol 1e-11, no relative
# test, no force-relative floor), so that the comparison does not depend on solver state carried between steps (with the
# default stateless LU preconditioner the restart is bitwise identical anyway; a preconditioner
# with history, such as -tao_bnk_pc_type lmvm, would otherwise agree only to about 1e-8).
#
# usage: bash checkpoint_restart.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"
mkdir -p logs
TIGHT=(-tao_gatol 1e-11 -tao_grtol 0 -mlshell_force_rtol 0)

# scene FILE OUTDIR REFINE [INITIAL_STATE_LINE]
scene() {
  cat >"$1" <<EOF
name: restart
geometry:
  cage: {generator: rectangle, size: [1.0, 1.0], faces: [4, 4]}
  refine: $3
material: {model: clyde-orthotropic, preset: denim, thickness: 0.66e-3, density: 0.4}
effects:
  - inertia
  - gravity
  - dirichlet: {where: boundary}   # all edges: converges at this dt (see docs/physics.md on denim)
time: {dt: 0.05, steps: 4}
probes:
  center: {at: [0.5, 0.5, 0]}
output: {dir: $2, checkpoint_every: 2, formats: [csv]}
${4:-}
EOF
}

# run LOGNAME EXPECTED_RC COMMAND...: runs COMMAND (with a time limit), output to logs/LOGNAME.*
run() {
  local log=$1 expect=$2
  shift 2
  local rc=0
  timeout 300 "$@" >"logs/$log.stdout" 2>"logs/$log.stderr" || rc=$?
  if [[ $expect != any && $rc -ne $expect ]]; then
    die "$log: exit status $rc, expected $expect
--- stdout (tail)
$(tail -n 15 "logs/$log.stdout")
--- stderr (tail)
$(tail -n 15 "logs/$log.stderr")"
  fi
  return 0
}

scene a.yaml out/a 1
echo "check: run A (steps 1..4, checkpoints at 2 and 4) exits 0"
run A 0 "$MLSHELL" a.yaml "${TIGHT[@]}"
CKPT="$WORK/out/a/checkpoint_000002.bin"
[[ -f $CKPT ]] || die "run A wrote no $CKPT (files: $(ls out/a))"
[[ -f out/a/checkpoint_000004.bin ]] || die "run A wrote no checkpoint_000004.bin"

scene b.yaml out/b 1 "initial_state: {checkpoint: $CKPT}"
echo "check: run B (restart from A's step 2, steps 3..4) exits 0"
run B 0 "$MLSHELL" b.yaml "${TIGHT[@]}"

echo "check: A and B end in the same state (probe displacement, energies)"
"$PY" - <<'EOF'
import csv, json, math, sys

def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)

a, b = load("out/a/summary.json"), load("out/b/summary.json")
errors = []
def check(cond, msg):
    if not cond:
        errors.append(msg)

def close(x, y, rel=1e-10, floor=1e-14):
    return abs(x - y) <= max(rel * max(abs(x), abs(y)), floor)

for name, s, steps in (("A", a, 4), ("B", b, 2)):
    check(s.get("status") == "complete", f"run {name}: status {s.get('status')!r}")
    check(s.get("solver", {}).get("converged") is True, f"run {name}: solver did not converge")
    check(s.get("steps") == steps, f"run {name}: steps {s.get('steps')}, expected {steps}")
    check(close(s.get("time", math.nan), 0.2, 1e-12), f"run {name}: time {s.get('time')}, expected 0.2")
    tol = s.get("solver", {}).get("gradient_tolerance")
    check(tol == 1e-11, f"run {name}: gradient tolerance {tol}, expected the tight 1e-11")

da = a["probes"]["center"]["displacement"]
db = b["probes"]["center"]["displacement"]
for c in range(3):
    check(close(da[c], db[c]), f"probe center displacement[{c}]: A {da[c]!r}, B {db[c]!r}")
check(abs(da[2]) > 1e-3, f"probe center barely moved ({da}): the scene does not test much")
for k, v in a["energy"].items():
    w = b["energy"].get(k, math.nan)
    check(close(v, w), f"energy.{k}: A {v!r}, B {w!r}")

# B's steps.csv holds steps 3 and 4 only, and its rows match A's last two.
with open("out/a/steps.csv", newline="") as f:
    rows_a = list(csv.DictReader(f))
with open("out/b/steps.csv", newline="") as f:
    rows_b = list(csv.DictReader(f))
check([r["step"] for r in rows_a] == ["1", "2", "3", "4"], f"A steps.csv steps {[r['step'] for r in rows_a]}")
check([r["step"] for r in rows_b] == ["3", "4"], f"B steps.csv steps {[r['step'] for r in rows_b]}")
if len(rows_a) == 4 and len(rows_b) == 2:
    for ra, rb in zip(rows_a[2:], rows_b):
        check(close(float(ra["time"]), float(rb["time"]), 1e-14), f"step {rb['step']}: time differs")
        check(close(float(ra["energy_total"]), float(rb["energy_total"])),
              f"step {rb['step']}: energy_total A {ra['energy_total']}, B {rb['energy_total']}")

if errors:
    for e in errors:
        print("FAIL:", e, file=sys.stderr)
    sys.exit(1)
print(f"  center displacement A {da}")
print(f"                      B {db}")
print(f"  energy.total A {a['energy']['total']!r}, B {b['energy']['total']!r}")
EOF

# --- a damaged checkpoint --------------------------------------------------------------------------
# expect_refused NAME DESCRIPTION: NAME.yaml restarts from NAME.bin, which must be refused with
# exit 2, a message naming NAME.bin, no crash and no summary.json.
expect_refused() {
  local name=$1 what=$2 rc=0
  echo "check: $what is refused (exit 2) with a message naming it"
  timeout 300 "$MLSHELL" "$name.yaml" -mlshell_quiet >"logs/$name.stdout" 2>"logs/$name.stderr" || rc=$?
  [[ $rc -eq 2 ]] || die "$what: exit status $rc, expected 2: $(cat "logs/$name.stderr")"
  grep -qF "$name.bin" "logs/$name.stderr" ||
    die "$what: the message does not name $name.bin: $(cat "logs/$name.stderr")"
  [[ ! -e out/$name/summary.json ]] || die "$what: a summary.json was written"
  echo "  exit status $rc: $(head -n 1 "logs/$name.stderr")"
}

# A damaged file is an input error; it must be refused (not restarted from) with a message that
# names the file: it is invalid input (exit 2), on any number of ranks.
cp "$CKPT" truncated.bin
size=$(stat -c %s truncated.bin)
truncate -s $((size / 2)) truncated.bin
scene truncated.yaml out/truncated 1 "initial_state: {checkpoint: truncated.bin}"
expect_refused truncated "a truncated checkpoint"
grep -qE "Segmentation|core dumped|PETSC ERROR" logs/truncated.stdout logs/truncated.stderr &&
  die "truncated checkpoint: crash: $(cat logs/truncated.stderr)"

# One flipped byte in the body: only the checksum can tell.
cp "$CKPT" flipped.bin
"$PY" - <<'EOF'
with open("flipped.bin", "r+b") as f:
    f.seek(200)
    byte = f.read(1)
    f.seek(200)
    f.write(bytes([byte[0] ^ 0x01]))
EOF
scene flipped.yaml out/flipped 1 "initial_state: {checkpoint: flipped.bin}"
expect_refused flipped "a checkpoint with one flipped byte"

echo "check: a truncated checkpoint on 2 ranks ends (no hang) with a non-zero status"
rc=0
timeout 60 mpiexec --oversubscribe -n 2 "$MLSHELL" truncated.yaml -mlshell_quiet \
  >logs/truncated-np2.stdout 2>logs/truncated-np2.stderr || rc=$?
[[ $rc -ne 124 && $rc -ne 137 ]] || die "truncated checkpoint on 2 ranks: no exit within 60 s (hang?)"
[[ $rc -eq 2 ]] ||
  die "truncated checkpoint on 2 ranks: exit status $rc, expected 2: $(head -c 800 logs/truncated-np2.stderr)"
grep -qF "truncated.bin" logs/truncated-np2.stderr ||
  die "truncated checkpoint on 2 ranks: the message does not name truncated.bin"
echo "  exit status $rc on 2 ranks"

# --- a checkpoint from another discretization -------------------------------------------------------
scene refine2.yaml out/refine2 2 "initial_state: {checkpoint: $CKPT}"
echo "check: a checkpoint written for refine 1, loaded with refine 2, is refused with exit 2"
rc=0
timeout 300 "$MLSHELL" refine2.yaml -mlshell_quiet >logs/refine2.stdout 2>logs/refine2.stderr || rc=$?
[[ $rc -eq 2 ]] || die "other refinement: exit status $rc, expected 2: $(cat logs/refine2.stderr)"
grep -qF "checkpoint_000002.bin" logs/refine2.stderr ||
  die "other refinement: the message does not name the checkpoint: $(cat logs/refine2.stderr)"
grep -qF "refine2.yaml" logs/refine2.stderr ||
  die "other refinement: the message does not name the scene: $(cat logs/refine2.stderr)"
[[ ! -e out/refine2/summary.json ]] || die "other refinement: a summary.json was written"
echo "  $(head -n 1 logs/refine2.stderr)"

echo "checkpoint_restart: all checks passed"
