#!/usr/bin/env bash
# -mlshell_audit_intersections: the exact intersection audit of the input and of every written
# frame. A buckling plate on 2 ranks stays clean (summary.json counts its audited frames and
# 0 intersecting pairs); a sheet whose OBJ folds through itself is refused at the start (exit 2,
# naming the file and the triangles); without the option nothing is audited.
#
# usage: bash intersection_audit.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"

echo "check: a buckling plate on 2 ranks, every frame audited, none intersecting"
sed -e "s|../../petsc-options|$SRC/petsc-options|" -e 's|formats: \[xdmf, obj, csv\]|formats: [obj]|' \
  "$SRC/examples/triangle/plate_buckling.yaml" >plate.yaml
timeout 300 mpiexec --oversubscribe -n 2 "$MLSHELL" plate.yaml -mlshell_quiet -mlshell_steps 2 \
  -mlshell_output_dir out/plate -mlshell_audit_intersections >plate.log 2>&1 ||
  die "exit $?: $(tail -5 plate.log)"
$PY - out/plate <<'PY' || die "plate: summary.json"
import json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
assert s["status"] == "complete", s["status"]
assert s["intersection_audit"] == {"frames": 3, "intersecting_pairs": 0}, s["intersection_audit"]
PY

echo "check: a sheet folded through itself is refused at the start (exit 2, naming the file)"
$PY - <<'PY'
import math
n, m = 16, 4
tilt = math.radians(10)
points = []
for j in range(m + 1):
    for i in range(n + 1):
        x, y, z = i / n, 0.25 * j / m, 0.0
        if x > 0.5 - 1e-12:  # turned back under the left half, rising through it
            s = x - 0.5
            x, z = 0.5 - s * math.cos(tilt), -0.02 + s * math.sin(tilt)
        points.append((x, y, z))
with open("folded.obj", "w") as f:
    for p in points:
        f.write("v %.17g %.17g %.17g\n" % p)
    for j in range(m):
        for i in range(n):
            a, b = j * (n + 1) + i + 1, j * (n + 1) + i + 2
            c, d = a + n + 1, b + n + 1
            f.write(f"f {a} {b} {d}\nf {a} {d} {c}\n")
PY
cat >folded.yaml <<'YAML'
geometry: {mesh: {obj: folded.obj}}
material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: 0.001, volume_density: 500}
effects:
  - gravity: [0, 0, -9.81]
  - clamp: {where: boundary}
time: {dt: 1.0, steps: 1, integrator: quasistatic}
output: {dir: out/folded, formats: [obj]}
YAML
rc=0
"$MLSHELL" folded.yaml -mlshell_audit_intersections >folded.log 2>&1 || rc=$?
[[ $rc -eq 2 ]] || die "folded sheet: exit $rc, expected 2: $(tail -3 folded.log)"
grep -q "folded.yaml: geometry.mesh: the input surface intersects itself: [0-9]* pair(s) of triangles" \
  folded.log || die "folded sheet: the message does not name the file and the triangles: $(cat folded.log)"
[[ ! -e out/folded/summary.json ]] || die "folded sheet: a summary.json was written"

echo "check: a strip coiling through itself stops at the frame (exit 5, status intersection)"
cat >coil.yaml <<'YAML'
name: coil
geometry:
  mesh: {generator: rectangle, size: [0.5, 0.05], faces: [60, 4]}
material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.45, thickness: 0.001, volume_density: 1100}
effects:
  - clamp: {where: boundary(left)}
  - clamp:
      where: boundary(right)
      motion:
        rotate: {axis: [1, 0, 0], center: [0.5, 0.025, 0], angle: 18.84955592153876}
        translate: [-0.35, 0, 0]
        over: [0, 6]
time: {dt: 1.0, steps: 6, integrator: quasistatic}
output: {dir: out/coil, formats: [obj]}
YAML
sed -i "/^time:/a solver: {options_file: $SRC/petsc-options/projected-newton.yaml}" coil.yaml
rc=0
timeout 300 "$MLSHELL" coil.yaml -mlshell_audit_intersections >coil.log 2>&1 || rc=$?
[[ $rc -eq 5 ]] || die "coil: exit $rc, expected 5: $(tail -3 coil.log)"
grep -q "^mlshell: frame [0-9]* (t = .*) intersects itself: [0-9]* pair(s) of triangles intersect" coil.log ||
  die "coil: no message naming the frame: $(tail -3 coil.log)"
$PY - out/coil <<'PY' || die "coil: summary.json"
import json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
assert s["status"] == "intersection", s["status"]
a = s["intersection_audit"]
assert a["intersecting_pairs"] > 0 and a["frames"] == s["steps"] + 1, (a, s["steps"])
PY

echo "check: without the option nothing is audited"
"$MLSHELL" folded.yaml -mlshell_evaluate >plain.log 2>&1 || die "exit $?: $(tail -3 plain.log)"
$PY -c "import json; s = json.load(open('out/folded/summary.json')); assert s.get('intersection_audit') is None, s['intersection_audit']" ||
  die "an audit was reported without the option"
echo "PASS"
