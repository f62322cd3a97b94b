#!/usr/bin/env bash
# time.integrator progressive (paper 2 §3, Alg. 1) on the buckling plate (16 x 16, levels 3):
#   - the converged fine result equals the direct fine quasistatic solve to the solver tolerance,
#     on the same buckling branch (the centre moves down, as in the direct run), and every
#     level's preview buckles the same way;
#   - 1 and 2 ranks reach the same final state;
#   - -mlshell_progressive_stop_level 1 ends after level 1 with complete series and a summary
#     that says it stopped there (status preview, exit 0);
#   - SIGINT ends the run after the current proxy step (exit 130, status interrupted) with valid
#     series of the levels done;
#   - bad input: progressive without geometry.hierarchy, preview parameters without the
#     progressive integrator, nonsense preview values and a stop level beyond the finest exit 2
#     naming the key or option.
#
# usage: bash progressive.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"

sed -e "s|../../petsc-options|$SRC/petsc-options|" -e 's|formats: \[xdmf, obj, csv\]|formats: [xdmf, csv]|' \
  -e 's|integrator: quasistatic|integrator: progressive|' \
  "$SRC/examples/triangle/plate_buckling.yaml" >progressive.yaml
sed -e 's|integrator: progressive|integrator: quasistatic|' progressive.yaml >direct.yaml

echo "check: progressive and direct fine reach the same state; 1 and 2 ranks agree"
timeout 300 "$MLSHELL" direct.yaml -mlshell_quiet -mlshell_output_dir out/direct >direct.log 2>&1 ||
  die "direct: exit $?: $(tail -5 direct.log)"
timeout 300 "$MLSHELL" progressive.yaml -mlshell_output_dir out/one >one.log 2>&1 ||
  die "progressive: exit $?: $(tail -5 one.log)"
timeout 300 mpiexec --oversubscribe -n 2 "$MLSHELL" progressive.yaml -mlshell_quiet \
  -mlshell_output_dir out/two >two.log 2>&1 || die "progressive, 2 ranks: exit $?: $(tail -5 two.log)"
grep -q "^level 0/2  step   10 " one.log || die "no progress line of level 0's last load step"
grep -q "^mlshell: level 2/2 (finest): .* converged" one.log || die "no line of the finest level"
$PY - out/direct out/one out/two <<'PY' || die "progressive: summary.json"
import json, sys
direct, one, two = (json.load(open(d + "/summary.json")) for d in sys.argv[1:])
for s in (one, two):
    assert s["status"] == "complete" and s["integrator"] == "progressive", s["status"]
    p = s["progressive"]
    assert [l["level"] for l in p["levels"]] == [0, 1, 2] and not p["stopped_early"], p
    assert all(l["equilibrium"] for l in p["levels"]), [l["stop"] for l in p["levels"]]
# The same minimiser: energies and the centre's deflection (4 cm) agree far below its size.
e0 = direct["energy"]["total"]
for s in (one, two):
    assert abs(s["energy"]["total"] - e0) <= 1e-6 * direct["solver"]["energy_scale"], (s["energy"], e0)
    z, z0 = s["probes"]["center"]["displacement"][2], direct["probes"]["center"]["displacement"][2]
    assert z0 < -0.03 and abs(z - z0) <= 1e-6, (z, z0)
# Every preview buckles down as the fine result does, within a few millimetres.
for l in one["progressive"]["levels"][:-1]:
    z = l["probes"]["center"]["displacement"][2]
    assert z < -0.03 and l["probes"]["center"]["error"] < 0.01, l
    assert 0 < l["preview_error"]["rms_distance"] <= l["preview_error"]["max_distance"] < 0.02, l
    assert l["max_boundary_violation"] < 1e-4, l
# 1 and 2 ranks: the same final state to round-off, and the same previews.
assert abs(one["energy"]["total"] - two["energy"]["total"]) <= 1e-9 * direct["solver"]["energy_scale"]
for a, b in zip(one["progressive"]["levels"], two["progressive"]["levels"]):
    assert a["proxy_steps"] == b["proxy_steps"], (a, b)
    assert abs(a["energy"] - b["energy"]) <= 1e-8 * direct["solver"]["energy_scale"], (a, b)
PY
for l in 0 1 2; do [[ -s out/one/plate_buckling_level$l.xdmf ]] || die "no series of level $l"; done
$PY - out/one/steps.csv <<'PY' || die "steps.csv"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert list(rows[0])[:5] == ["level", "step", "time", "energy", "iterations"], list(rows[0])
# Level 0 carries the loading (t = 1..10, then at the final load); the finer levels refine at the
# final load only.
assert [float(r["time"]) for r in rows if r["level"] == "0"][:10] == list(range(1, 11)), rows
assert all(float(r["time"]) == 10 for r in rows if r["level"] != "0"), rows
PY

echo "check: -mlshell_progressive_stop_level 1 stops after level 1 and says so"
timeout 300 "$MLSHELL" progressive.yaml -mlshell_quiet -mlshell_output_dir out/one \
  -mlshell_progressive_stop_level 1 >stop.log 2>&1 || die "stop level: exit $?: $(tail -5 stop.log)"
grep -q "results are previews, not the converged fine solution" stop.log || die "stop: $(cat stop.log)"
[[ ! -e out/one/plate_buckling_level2.xdmf ]] || die "stop level 1: the earlier run's level 2 series is left"
$PY - out/one <<'PY' || die "stop level: summary.json"
import json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
assert s["status"] == "preview" and not s["solver"]["converged"], s["status"]
p = s["progressive"]
assert p["stopped_early"] and p["last_level"] == 1 and len(p["levels"]) == 2, p
PY

echo "check: SIGINT ends the run after the current proxy step, exit 130, valid output"
# Many small proxy steps on level 0 (one Newton iteration each) so the signal lands in them.
sed -e 's|time: {dt: 1.0, steps: 10,|time: {preview: {max_iterations: 1}, dt: 0.01, steps: 1000,|' \
  progressive.yaml >long.yaml
rc=0
"$MLSHELL" long.yaml -mlshell_output_dir out/long >long.log 2>&1 &
pid=$!
# The handler is in place once the proxy steps print; a loaded machine may take a while.
for _ in $(seq 600); do grep -q "^level 0/2  step   50 " long.log 2>/dev/null && break; sleep 0.1; done
grep -q "^level 0/2  step   50 " long.log || { kill $pid; die "no proxy step 50 within 60 s"; }
kill -INT $pid
wait $pid || rc=$?
[[ $rc -eq 130 ]] || die "SIGINT: exit $rc, expected 130: $(tail -3 long.log)"
$PY - out/long <<'PY' || die "SIGINT: summary.json"
import json, sys, xml.etree.ElementTree as ET
d = sys.argv[1]
s = json.load(open(d + "/summary.json"))
assert s["status"] == "interrupted", s["status"]
p = s["progressive"]
assert p["stopped_early"] and p["levels"][-1]["stop"] == "INTERRUPTED", p["levels"][-1]
steps = p["levels"][-1]["proxy_steps"]
assert 50 <= steps < 1000, steps
grids = ET.parse(d + "/plate_buckling_level0.xdmf").getroot().iter("Grid")
assert sum(1 for g in grids if g.get("GridType") == "Uniform") == steps + 1
PY

echo "check: bad input exits 2 naming the key"
expect_exit2() {  # NAME PATTERN [options...]: runs NAME.yaml
  local name=$1 pattern=$2 rc=0
  shift 2
  "$MLSHELL" "$name.yaml" -mlshell_quiet "$@" >"$name.log" 2>&1 || rc=$?
  [[ $rc -eq 2 ]] || die "$name: exit $rc, expected 2: $(tail -3 "$name.log")"
  grep -q "$pattern" "$name.log" || die "$name: the message does not say '$pattern': $(cat "$name.log")"
}
grep -v "hierarchy:" progressive.yaml >no_hierarchy.yaml
expect_exit2 no_hierarchy "no_hierarchy.yaml.*time.integrator.*no geometry.hierarchy"
sed -e 's|integrator: progressive|integrator: quasistatic, preview: {max_iterations: 3}|' progressive.yaml >preview_quasistatic.yaml
expect_exit2 preview_quasistatic "time.preview.*only a progressive integrator"
sed -e 's|integrator: progressive|integrator: progressive, preview: {tolerance: -1}|' progressive.yaml >bad_tolerance.yaml
expect_exit2 bad_tolerance "time.preview.tolerance.*-1"
sed -e 's|integrator: progressive|integrator: progressive, preview: {min_step: 1.5}|' progressive.yaml >bad_min_step.yaml
expect_exit2 bad_min_step "time.preview.min_step.*1.5"
sed -e 's|integrator: progressive|integrator: progressive, preview: {max_iter: 3}|' progressive.yaml >bad_key.yaml
expect_exit2 bad_key "max_iter"
cp progressive.yaml stop_level.yaml
expect_exit2 stop_level "progressive_stop_level: must be in 0..2.*got '5'" -mlshell_progressive_stop_level 5
expect_exit2 stop_level "progressive_hessian: must be galerkin or own" -mlshell_progressive_hessian exact

echo "PASS"
