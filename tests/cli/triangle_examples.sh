#!/usr/bin/env bash
# The triangle-shell examples (examples/triangle, paper 2 §5.2) end to end, at their own
# resolution but with fewer load steps: each converges on 2 ranks, writes an XDMF series of
# triangles with the per-face fields (membrane_strain, bending_energy) and OBJ frames of
# triangles, and reports its probes; and RMTR on its decimation hierarchy converges on 2 ranks
# (one load step) on all three levels. Then a quasistatic checkpoint restart: the balloon
# restarted from its step-2 checkpoint ends where the uninterrupted run ends.
#
# usage: bash triangle_examples.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"
EX="$SRC/examples/triangle"

for scene in plate_buckling plate_shearing shell_indent unstructured_drape balloon embossed_panel; do
  echo "check: $scene converges on 2 ranks (2 load steps) and writes triangles with face fields"
  sed "s|../../petsc-options|$SRC/petsc-options|" "$EX/$scene.yaml" >"$scene.yaml"
  rc=0
  timeout 300 mpiexec --oversubscribe -n 2 "$MLSHELL" "$scene.yaml" -mlshell_quiet \
    -mlshell_steps 2 -mlshell_output_dir "out/$scene" >"$scene.log" 2>&1 || rc=$?
  [[ $rc -eq 0 ]] || die "$scene: exit $rc: $(tail -5 "$scene.log")"
  $PY - "out/$scene" "$scene" <<'PY' || die "$scene: outputs"
import json, re, sys
from pathlib import Path
out, name = Path(sys.argv[1]), sys.argv[2]
s = json.load(open(out / "summary.json"))
assert s["status"] == "complete" and s["solver"]["converged"], s["solver"]
assert s["solver"]["type"] == "pnewton", s["solver"]["type"]
assert s["probes"], "no probes reported"
x = (out / f"{name}.xdmf").read_text()
assert 'TopologyType="Triangle"' in x, "XDMF topology is not Triangle"
for field in ("membrane_strain", "bending_energy"):
    assert f'Name="{field}"' in x and 'Center="Cell"' in x, f"no cell field {field}"
obj = sorted(out.glob("frame_*.obj"))[-1].read_text()
faces = [l for l in obj.splitlines() if l.startswith("f ")]
assert faces and all(len(f.split()) == 4 for f in faces), "OBJ faces are not triangles"
PY
  echo "check: $scene: RMTR on its 3-level hierarchy converges on 2 ranks (1 load step)"
  rc=0
  timeout 300 mpiexec --oversubscribe -n 2 "$MLSHELL" "$scene.yaml" -mlshell_quiet -tao_type rmtr \
    -mlshell_steps 1 -mlshell_output_dir "out/$scene-rmtr" >"$scene-rmtr.log" 2>&1 || rc=$?
  [[ $rc -eq 0 ]] || die "$scene with rmtr: exit $rc: $(tail -5 "$scene-rmtr.log")"
  $PY - "out/$scene-rmtr" <<'PY' || die "$scene with rmtr: summary"
import json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
assert s["status"] == "complete" and s["solver"]["converged"], s["solver"]
rmtr = s["solver"]["rmtr"]
assert len(rmtr["levels"]) == 3, rmtr["levels"]
PY
done

echo "check: other solvers run triangle shells too: tr, bnls, rmtr and SNES"
sed "s|../../petsc-options|$SRC/petsc-options|" "$EX/balloon.yaml" >solvers.yaml
for solver in "-tao_type tr" "-tao_type bnls" "-tao_type rmtr" "-mlshell_step_solver snes"; do
  rm -rf out/solvers
  # shellcheck disable=SC2086  # the solver options are words
  "$MLSHELL" solvers.yaml -mlshell_quiet -mlshell_steps 1 -mlshell_output_dir out/solvers \
    -mlshell_hessian_psd 0 $solver >solvers.log 2>&1 || die "$solver: $(tail -3 solvers.log)"
  $PY -c "import json; s = json.load(open('out/solvers/summary.json')); assert s['solver']['converged'], s['solver']" \
    || die "$solver did not converge"
done

echo "check: a quasistatic restart from a checkpoint ends where the uninterrupted run ends"
sed -e "s|../../petsc-options|$SRC/petsc-options|" -e 's|formats: \[xdmf, obj, csv\]|formats: [csv], checkpoint_every: 2|' \
  "$EX/balloon.yaml" >restart.yaml
TIGHT=(-tao_gatol 1e-10 -mlshell_force_rtol 0)
"$MLSHELL" restart.yaml -mlshell_quiet -mlshell_steps 4 -mlshell_output_dir out/full "${TIGHT[@]}" \
  >full.log 2>&1 || die "full run: $(tail -3 full.log)"
[[ -f out/full/checkpoint_000002.bin ]] || die "no checkpoint_000002.bin"
cp restart.yaml restarted.yaml
printf 'initial_state: {checkpoint: out/full/checkpoint_000002.bin}\n' >>restarted.yaml
"$MLSHELL" restarted.yaml -mlshell_quiet -mlshell_steps 4 -mlshell_output_dir out/restarted \
  "${TIGHT[@]}" >restarted.log 2>&1 || die "restarted run: $(tail -3 restarted.log)"
$PY - <<'PY' || die "restart differs"
import json
a = json.load(open("out/full/summary.json"))["probes"]["north"]["displacement"]
b = json.load(open("out/restarted/summary.json"))["probes"]["north"]["displacement"]
scale = max(abs(v) for v in a)
assert max(abs(x - y) for x, y in zip(a, b)) <= 1e-8 * scale, (a, b)
PY
echo "PASS"
