#!/usr/bin/env bash
# Contact end to end (docs/contact.md): the strip pulled over a sphere (examples/contact/
# strip_over_sphere.yaml) on 1 and 2 ranks ends in the same state with no intersecting frame,
# its summary reports the contact and the audit, and colliders.obj holds the sphere; in one load
# step instead of four (a 0.3 m pull through the sphere's place, which only CCD's step limit
# keeps out) and with the trust region instead of projected Newton it ends in the same state; a
# strip folded onto itself stays apart by self-contact on 2 ranks, and without self-contact the
# audit stops it (exit 5); a sphere moving up into the held strip pushes it up on 1 and 2
# ranks alike (and under implicit Euler), and pressing it into a plane above stops the run (the
# sphere cannot arrive); the other contact examples run their first two steps; a coarse twist
# winds a rope whose tension raises the barrier's stiffness past IPC's cap, on 1 and 2 ranks
# alike; two bodies (crossed strips) and a coarse crushed can end alike on 1 and 2 ranks;
# and bad contact input exits 2 naming the file and key.
#
# usage: bash contact.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"
sed "s|../../petsc-options|$SRC/petsc-options|" "$SRC/examples/contact/strip_over_sphere.yaml" \
  >strip.yaml

run_scene() {  # run_scene SCENE NAME RANKS [OPTIONS...]: SCENE into out/NAME, exit 0 expected
  local scene=$1 name=$2 ranks=$3
  shift 3
  local rc=0
  timeout 300 mpiexec --oversubscribe -n "$ranks" "$MLSHELL" "$scene" -mlshell_quiet \
    -mlshell_output_dir "out/$name" "$@" >"$name.log" 2>&1 || rc=$?
  [[ $rc -eq 0 ]] || die "$name: exit $rc: $(tail -5 "$name.log")"
}
run() { run_scene strip.yaml "$@"; }  # run NAME RANKS [OPTIONS...]: the strip

echo "check: the strip over the sphere on 1, 2 and 3 ranks, in one load step, and by tr"
run serial 1
run distributed 2 -log_view
run three_ranks 3
run one_step 1 -mlshell_steps 1 -mlshell_dt 1
run trust_region 1 -tao_type tr
$PY - <<'PY' || die "contact outputs"
import json
from pathlib import Path

def summary(name):
    s = json.load(open(f"out/{name}/summary.json"))
    assert s["status"] == "complete" and s["solver"]["converged"], (name, s["status"])
    c, audit = s["contact"], s["intersection_audit"]
    assert c["colliders"] == 1 and c["self"] is True, c
    assert c["active_pairs"] > 0, c  # the strip lies on the sphere
    assert c["thickness"] < c["min_distance"] < c["thickness"] + c["gap"], c
    assert audit["frames"] == s["steps"] + 1 and audit["intersecting_pairs"] == 0, audit
    # The strip's middle rests on the sphere's top (z = -5 mm), not below it: no step tunnelled.
    assert s["probes"]["middle"]["displacement"][2] > -0.01, s["probes"]
    return s

def final(name):
    obj = sorted(Path(f"out/{name}").glob("frame_*.obj"))[-1].read_text().splitlines()
    return [tuple(map(float, l.split()[1:4])) for l in obj if l.startswith("v ")]

one, two, step = summary("serial"), summary("distributed"), summary("one_step")
three = summary("three_ranks")
summary("trust_region")
assert two["contact"]["halo_points"] > 0 and one["contact"]["halo_points"] == 0
assert three["contact"]["halo_points"] > two["contact"]["halo_points"], (two, three)
a, b, c = final("serial"), final("distributed"), final("one_step")
# The same minimiser to the solver's tolerance (1e-7 N on forces of 1e-1 N: ~1e-9 m here).
assert max(abs(p - q) for u, v in zip(a, b) for p, q in zip(u, v)) < 1e-8, "1 vs 2 ranks"
assert max(abs(p - q) for u, v in zip(a, final("three_ranks")) for p, q in zip(u, v)) < 1e-8, \
    "1 vs 3 ranks"
# -log_view lists the contact events of a contact scene (the check below: none without contact).
log = open("distributed.log").read()
for event in ("Contact:proximity", "Contact:ccd", "Effect:contact"):
    assert f"\n{event} " in log, f"-log_view has no {event}"
# In one step κ doubles once more than in four (adaptive κ follows the iterates), which moves
# the resting state by a fraction of the gap (1 mm; 0.22 mm measured), not more.
assert max(abs(p - q) for u, v in zip(a, c) for p, q in zip(u, v)) < 1e-3, "one load step"
d = final("trust_region")
assert max(abs(p - q) for u, v in zip(a, d) for p, q in zip(u, v)) < 1e-6, "tr against pnewton"
import csv
rows = list(csv.DictReader(open("out/serial/steps.csv")))
assert len(rows) == 4 and all(int(r["contact_active_pairs"]) > 0 for r in rows[1:]), rows
assert float(rows[-1]["contact_min_distance"]) == one["contact"]["min_distance"], rows[-1]
obj = Path("out/serial/colliders.obj").read_text()
assert "o collider_0" in obj and obj.count("\nf ") == 1280, "colliders.obj: the sphere"
PY

echo "check: a scene without contact builds none of it: no contact events, summary or colliders"
timeout 300 mpiexec --oversubscribe -n 2 "$MLSHELL" "$SRC/examples/triangle/balloon.yaml" \
  -mlshell_quiet -mlshell_steps 1 -mlshell_output_dir out/no_contact -log_view >no_contact.log 2>&1 \
  || die "balloon: $(tail -5 no_contact.log)"
grep -q "^Effect:elastic " no_contact.log || die "balloon: no -log_view in no_contact.log"
! grep -E "^(Contact:|Effect:contact|Audit)" no_contact.log || die "balloon: contact events"
$PY - <<'PY' || die "balloon: contact outputs"
import json, os
s = json.load(open("out/no_contact/summary.json"))
assert s["status"] == "complete" and "contact" not in s, sorted(s)
assert not os.path.exists("out/no_contact/colliders.obj")
PY

echo "check: SNES newtonls's line search is cut to CCD: whatever it reaches, no frame intersects"
rc=0
timeout 300 "$MLSHELL" strip.yaml -mlshell_quiet -mlshell_output_dir out/snes \
  -mlshell_step_solver snes >snes.log 2>&1 || rc=$?
[[ $rc -eq 0 || $rc -eq 3 ]] || die "snes: exit $rc: $(tail -5 snes.log)"
$PY - <<'PY' || die "snes: outputs"
import json
s = json.load(open("out/snes/summary.json"))
assert s["status"] in ("complete", "solver_failed"), s["status"]
assert s["intersection_audit"]["intersecting_pairs"] == 0, s["intersection_audit"]
assert s["probes"]["middle"]["displacement"][2] > -0.01, s["probes"]  # not through the sphere
PY

echo "check: self-contact keeps a strip folded on itself apart on 2 ranks; without it the audit stops"
# Its right end turned over the left one (a half turn about the y axis): the two halves hang
# against each other.
fold() {
  cat <<YAML
geometry: {mesh: {generator: rectangle, size: [1.0, 0.1], faces: [40, 4]}}
material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: 0.001, volume_density: 1000}
effects:
  - gravity: [0, 0, -9.81]
  - dirichlet: {where: boundary(left)}
  - dirichlet: {where: boundary(right), motion: {rotate: {axis: [0, 1, 0], center: [0.5, 0, 0.03], angle: -3.141592653589793}, over: [0, 1]}}
  - contact: {self: $1}
time: {dt: 0.25, steps: 4, integrator: quasistatic}
solver: {options_file: $SRC/petsc-options/projected-newton.yaml}
YAML
}
fold true >fold.yaml
rc=0
timeout 300 mpiexec --oversubscribe -n 2 "$MLSHELL" fold.yaml -mlshell_quiet \
  -mlshell_output_dir out/fold >fold.log 2>&1 || rc=$?
[[ $rc -eq 0 ]] || die "fold: exit $rc: $(tail -5 fold.log)"
$PY - <<'PY' || die "fold: outputs"
import json
s = json.load(open("out/fold/summary.json"))
assert s["status"] == "complete", s["status"]
c, audit = s["contact"], s["intersection_audit"]
assert c["colliders"] == 0 and c["active_pairs"] > 0 and c["min_distance"] > c["thickness"], c
assert audit["frames"] == 5 and audit["intersecting_pairs"] == 0, audit
PY
fold false >fold_apart.yaml
rc=0
"$MLSHELL" fold_apart.yaml -mlshell_output_dir out/fold_apart >fold_apart.log 2>&1 || rc=$?
[[ $rc -eq 5 ]] || die "fold without self-contact: exit $rc, expected 5: $(tail -3 fold_apart.log)"
grep -q "^mlshell: frame [0-9]* (t = .*) intersects itself: [0-9]* pair(s) of triangles" \
  fold_apart.log || die "fold without self-contact: $(tail -3 fold_apart.log)"
grep -q '"status": "intersection"' out/fold_apart/summary.json || die "fold: status"

echo "check: a sphere moving up into the strip pushes it 0.25 m up, on 1 and 2 ranks alike"
# examples/contact/sphere_lift.yaml: the strip's ends held, the sphere (collider motion) rising
# 0.3 m from below in four steps: between solves it moves as far as CCD allows, with the strip's
# vertices in its way pushed ahead of it, and every step is solved until it has arrived.
sed "s|../../petsc-options|$SRC/petsc-options|" "$SRC/examples/contact/sphere_lift.yaml" >push.yaml
for ranks in 1 2; do run_scene push.yaml "push$ranks" $ranks; done
$PY - <<'PY' || die "push: outputs"
import json
from pathlib import Path

def vertices(path):
    return [tuple(map(float, l.split()[1:4])) for l in Path(path).read_text().splitlines()
            if l.startswith("v ")]

for ranks in (1, 2):
    s = json.load(open(f"out/push{ranks}/summary.json"))
    assert s["status"] == "complete" and s["solver"]["converged"], s["status"]
    assert s["intersection_audit"] == {"frames": 5, "intersecting_pairs": 0}, s["intersection_audit"]
    c = s["contact"]
    # About a move a step (4 measured): the strip's vertices in the way are pushed ahead (carry),
    # so CCD seldom cuts a move short (carrying only the close ones it cut 46 of 50).
    assert 4 <= c["collider_moves"] <= 8 and c["active_pairs"] > 0, c
    # The sphere's top ends at z = 0.25; the strip's middle lies on it (its coarse triangles
    # span the sphere's by a few mm), not below it.
    top = max(z for _, _, z in vertices(f"out/push{ranks}/colliders_000004.obj"))
    assert abs(top - 0.25) < 1e-12, top
    assert max(z for _, _, z in vertices(f"out/push{ranks}/colliders_000000.obj")) < -0.0499
    z = s["probes"]["middle"]["displacement"][2]
    assert 0.25 + c["thickness"] < z < 0.26, z
a, b = vertices("out/push1/frame_000004.obj"), vertices("out/push2/frame_000004.obj")
assert max(abs(p - q) for u, v in zip(a, b) for p, q in zip(u, v)) < 1e-8, "1 vs 2 ranks"
PY

echo "check: under implicit Euler the rising sphere lifts the strip too (6 steps of 50 ms)"
# The colliders move before each solve of an implicit Euler step as well; the step keeps its
# inertia predictor. After 0.3 s the sphere has risen 9 cm: its top is at z = 0.04.
sed 's/^time: {dt: 0.25, steps: 4, integrator: quasistatic, proximal_step: 1.0}/time: {dt: 0.05, steps: 6, integrator: implicit_euler}/; s/^  - gravity:/  - inertia\n  - gravity:/' \
  push.yaml >lift_dynamic.yaml
grep -q "^  - inertia" lift_dynamic.yaml && grep -q "implicit_euler" lift_dynamic.yaml ||
  die "lift_dynamic.yaml: $(cat lift_dynamic.yaml)"
rc=0
timeout 300 "$MLSHELL" lift_dynamic.yaml -mlshell_quiet -mlshell_output_dir out/lift_dynamic \
  >lift_dynamic.log 2>&1 || rc=$?
[[ $rc -eq 0 ]] || die "lift_dynamic: exit $rc: $(tail -5 lift_dynamic.log)"
$PY - <<'PY' || die "lift_dynamic: outputs"
import json
from pathlib import Path
s = json.load(open("out/lift_dynamic/summary.json"))
assert s["status"] == "complete" and s["integrator"] == "implicit_euler", (s["status"], s["integrator"])
assert s["intersection_audit"] == {"frames": 7, "intersecting_pairs": 0}, s["intersection_audit"]
assert s["contact"]["collider_moves"] >= 6, s["contact"]
top = max(float(l.split()[3]) for l in Path("out/lift_dynamic/colliders_000006.obj").read_text().splitlines()
          if l.startswith("v "))
assert abs(top - 0.04) < 1e-12, top
PY

echo "check: the other contact examples run their first steps on 2 ranks, with no intersection"
for scene in balloon_press balloon_in_corner cloth_on_sphere; do
  sed "s|../../petsc-options|$SRC/petsc-options|" "$SRC/examples/contact/$scene.yaml" >"$scene.yaml"
  run_scene "$scene.yaml" "$scene" 2 -mlshell_steps 2
  $PY - "out/$scene" <<'PY' || die "$scene: summary"
import json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
assert s["status"] == "complete" and s["solver"]["converged"], s["status"]
assert s["intersection_audit"] == {"frames": 3, "intersecting_pairs": 0}, s["intersection_audit"]
PY
done

same_on_1_and_2() {  # NAME FRAMES VERTICES TOL: out/NAME1 (1 rank) and out/NAME2 (2 ranks)
  # complete and converged, FRAMES audited frames without intersection, the thickness kept, and
  # the same final state (VERTICES vertices, within TOL m)
  $PY - "$@" <<'PY' || die "$1: 1 against 2 ranks"
import json, sys
from pathlib import Path

name, frames, vertices, tol = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])

def final(run):
    obj = sorted(Path(f"out/{run}").glob("frame_*.obj"))[-1].read_text().splitlines()
    return [tuple(map(float, l.split()[1:4])) for l in obj if l.startswith("v ")]

for run in (name + "1", name + "2"):
    s = json.load(open(f"out/{run}/summary.json"))
    assert s["status"] == "complete" and s["solver"]["converged"], (run, s["status"])
    assert s["intersection_audit"] == {"frames": frames, "intersecting_pairs": 0}, s["intersection_audit"]
    assert s["contact"]["thickness"] < s["contact"]["min_distance"], s["contact"]
a, b = final(name + "1"), final(name + "2")
gap = max(abs(p - q) for u, v in zip(a, b) for p, q in zip(u, v))
assert len(a) == len(b) == vertices and gap < tol, (len(a), gap)
PY
}

echo "check: the twist, coarse (12 x 12 faces, 16 steps of 0.5 s), winds a rope on 1 and 2 ranks alike"
cp "$SRC/examples/contact/twist-options.yaml" .
sed -e 's/faces: \[16, 16\]/faces: [12, 12]/' -e 's/dt: 0.1, steps: 150/dt: 0.5, steps: 16/' \
  "$SRC/examples/contact/twist.yaml" >twist.yaml
grep -q "steps: 16" twist.yaml || die "twist.yaml: $(cat twist.yaml)"
for ranks in 1 2; do run_scene twist.yaml "twist$ranks" $ranks; done
same_on_1_and_2 twist 17 169 1e-5  # |g| < 1e-5 N: the same state
$PY - <<'PY' || die "twist"
import csv, json

for name in ("twist1", "twist2"):
    assert json.load(open(f"out/{name}/summary.json"))["contact"]["active_pairs"] > 100  # layers
    rows = list(csv.DictReader(open(f"out/{name}/steps.csv")))
    kappa = [float(r["contact_stiffness"]) for r in rows]
    # The rope's pull raises κ past IPC's cap of 100 κ₀ (docs/contact.md#stiffness).
    assert max(kappa) > 1000 * kappa[0], kappa
PY

echo "check: two bodies (crossed strips), each with its own material, on 1 and 2 ranks alike"
sed "s|../../petsc-options|$SRC/petsc-options|" "$SRC/examples/contact/crossed_strips.yaml" >crossed.yaml
for ranks in 1 2; do run_scene crossed.yaml "crossed$ranks" $ranks; done
same_on_1_and_2 crossed 5 738 1e-8  # 369 vertices a strip
$PY - <<'PY' || die "crossed strips"
import json

for name in ("crossed1", "crossed2"):
    s = json.load(open(f"out/{name}/summary.json"))
    # The thickest body's thickness; the band presses the rubber strip down.
    assert s["contact"]["active_pairs"] > 100 and s["contact"]["thickness"] == 0.002, s["contact"]
    assert [(b["name"], b["vertices"], b["faces"], b["thickness"]) for b in s["bodies"]] == [
        ("crossed_strips", 369, 640, 0.002), ("band", 369, 640, 0.00066)], s["bodies"]
    assert s["probes"]["band_middle"]["displacement"][2] < -0.01, s["probes"]
PY

echo "check: the crushed can, coarse (24 x 12 faces), folds alike on 1 and 2 ranks"
cp "$SRC/examples/contact/can_crush-options.yaml" .
sed 's/faces: \[32, 16\]/faces: [24, 12]/' "$SRC/examples/contact/can_crush.yaml" >can.yaml
grep -q "faces: \[24, 12\]" can.yaml || die "can.yaml: $(cat can.yaml)"
for ranks in 1 2; do run_scene can.yaml "can$ranks" $ranks; done
# The same folds, not mirror images (with one imperfection mode, 2 ranks folded mirrored):
# |g| < 1e-4 N against a wall stiffness of about 1e7 N/m.
same_on_1_and_2 can 11 312 1e-8
$PY - <<'PY' || die "can"
import json, math
from pathlib import Path

assert json.load(open("out/can1/summary.json"))["contact"]["active_pairs"] > 50  # folds on folds
obj = sorted(Path("out/can1").glob("frame_*.obj"))[-1].read_text().splitlines()
a = [tuple(map(float, l.split()[1:4])) for l in obj if l.startswith("v ")]
# Crushed 3 cm, and buckled: the wall leaves its 33 mm radius by centimetres, not micrometres.
assert abs(max(p[2] for p in a) - 0.07) < 1e-3, max(p[2] for p in a)
assert max(abs(math.hypot(p[0], p[1]) - 0.033) for p in a) > 5e-3
PY

echo "check: the sphere pressing the strip into a plane above cannot arrive: exit 3, no intersection"
sed 's/^time: {dt: 0.25, steps: 4,/time: {dt: 0.25, steps: 3, max_proximal_solves: 8,/' push.yaml |
  awk '/^  - contact/ { print; print "  - collider: {plane: {point: [0, 0, 0.15], normal: [0, 0, -1]}}"; next } { print }' \
  >pinch.yaml
grep -q "max_proximal_solves: 8" pinch.yaml || die "pinch.yaml: $(cat pinch.yaml)"
rc=0
timeout 300 "$MLSHELL" pinch.yaml -mlshell_quiet -mlshell_output_dir out/pinch >pinch.log 2>&1 || rc=$?
[[ $rc -eq 3 ]] || die "pinch: exit $rc, expected 3: $(tail -3 pinch.log)"
grep -q "^mlshell: step 3 did not converge: a collider could not reach its place at t = 0.75 s" \
  pinch.log || die "pinch: no collider message in: $(cat pinch.log)"
$PY - <<'PY' || die "pinch: summary"
import json
s = json.load(open("out/pinch/summary.json"))
assert s["status"] == "solver_failed", s["status"]
assert s["solver"]["reason"] == "DIVERGED_COLLIDER_MOTION", s["solver"]
assert s["intersection_audit"]["intersecting_pairs"] == 0, s["intersection_audit"]
assert s["contact"]["colliders"] == 2 and s["contact"]["collider_moves_cut"] > 0, s["contact"]
PY

echo "check: bad contact input exits 2 naming the file and key"
bad() {  # bad NAME PATTERN OPTIONS... < scene: exit 2 and PATTERN in the message
  local name=$1 pattern=$2
  shift 2
  cat >"$name.yaml"
  local rc=0
  "$MLSHELL" "$name.yaml" -mlshell_output_dir "out/$name" "$@" >"$name.log" 2>&1 || rc=$?
  [[ $rc -eq 2 ]] || die "$name: exit $rc, expected 2: $(tail -3 "$name.log")"
  grep -q -- "$pattern" "$name.log" || die "$name: no '$pattern' in: $(cat "$name.log")"
}
strip_with() {  # the example with its contact and collider lines replaced by $1
  grep -v "^  - contact\|^  - collider" strip.yaml | ADD=$1 awk '/^time:/ { print ENVIRON["ADD"] } { print }'
}
strip_with "  - collider: {sphere: {center: [0.5, 0.1, -0.2], radius: 0.1}}" |
  bad no_contact "no_contact.yaml:[0-9]*: effects\[3\]: a collider needs a \`contact\` effect"
strip_with "  - contact
  - collider: {cone: {center: [0.5, 0.1, -0.2]}}" |
  bad cone "cone.yaml:[0-9]*: effects\[4\].collider.*unknown collider shape 'cone'"
strip_with "  - contact: {thickness: -1}" |
  bad thickness "thickness.yaml:[0-9]*: effects\[3\].contact.thickness.*must be >= 0"
strip_with "  - contact: {gapp: 0.01}" | bad key "key.yaml:[0-9]*: effects\[3\].contact.*gapp"
strip_with "  - contact
  - collider: {sphere: {center: [0.5, 0.1, -0.1], radius: 0.1}}" |
  bad through "through.yaml: geometry.mesh: the input surface intersects itself or a collider: .*collider 0"
strip_with "  - contact
  - collider: {plane: {point: [0, 0, -0.0003], normal: [0, 0, 1]}}" |
  bad touching "touching.yaml: effects\[3\].contact: the shell starts 0.0003 m .* within the contact thickness 0.00066 m"
strip_with "  - contact
  - collider: {sphere: {center: [0.5, 0.1, -0.2], radius: 0.1}}" |
  bad solver "solver.yaml: effects\[3\].contact: the solver 'bnls' does not keep" -tao_type bnls
strip_with "  - contact
  - collider: {sphere: {center: [0.5, 0.1, -0.2], radius: 0.1}}" |
  bad snes_type "snes_type.yaml: effects\[3\].contact: -snes_type ngmres with .* may step beyond" \
  -mlshell_step_solver snes -snes_type ngmres
strip_with "  - contact
  - collider: {sphere: {center: [0.5, 0.1, -0.2], radius: 0.1}}" |
  bad damping "damping.yaml: effects\[3\].contact: -snes_type newtonls with -snes_linesearch_type basic (damping 1.5.*) may step beyond" \
  -mlshell_step_solver snes -snes_linesearch_type basic -snes_linesearch_damping 1.5
strip_with "  - contact
  - collider: {sphere: {center: [0.5, 0.1, -0.2], radius: 0.1}, motion: {translate: [0, 0, 1]}}" |
  bad motion "motion.yaml:[0-9]*: effects\[4\].collider.motion.*over"
strip_with "  - contact
  - collider: {sphere: {center: [0.5, 0.1, -0.2], radius: 0.1}, box: {center: [0, 0, 0], size: [1, 1, 1]}}" |
  bad two_shapes "two_shapes.yaml:[0-9]*: effects\[4\].collider.*a collider is one shape"
cat <<'YAML' | bad cloth "cloth.yaml:[0-9]*: effects\[0\].contact.*triangle-mesh shells"
geometry: {cage: {generator: rectangle, size: [1, 1], faces: [4, 4]}, refine: 1}
material: {model: clyde-orthotropic, preset: denim, thickness: 0.66e-3, density: 0.4}
effects:
  - contact
time: {dt: 0.01, steps: 1}
YAML
sed 's|translate: \[0, 0, 0.02\]|translate: [0, 0, 0]|' crossed.yaml |
  bad bodies_through "bodies_through.yaml: geometry.mesh: the input surface intersects itself or a body: .*of 'band' and triangle [0-9]* of 'crossed_strips'"
echo "PASS"
