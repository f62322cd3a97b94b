#!/usr/bin/env bash
# -mlshell_evaluate on a flat 1 m x 1 m St. Venant-Kirchhoff square: the energies printed and
# written to summary.json, zero elastic energy in the reference state, the closed-form membrane
# energy of a uniform 1 % stretch, only the listed effects in the summary, and the same numbers
# on 2 ranks as on 1.
#
# usage: bash evaluate_mode.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"
mkdir -p logs

# scene NAME [INITIAL_STATE_LINE [EXTRA_EFFECT_LINE]]
scene() {
  cat >"$1.yaml" <<EOF
name: $1
geometry:
  cage: {generator: rectangle, size: [1.0, 1.0], faces: [4, 4]}
  refine: 1
material: {model: isotropic-svk, youngs_modulus: 1.0e7, poisson_ratio: 0.3, thickness: 1.0e-3,
           density: 1.0}
effects:
  - gravity
  - dirichlet: {where: boundary(left)}
${3:-}
time: {dt: 1.0, steps: 1}
output: {dir: out/$1, formats: [csv]}
${2:-}
EOF
}
scene flat
scene stretch 'initial_state: {affine: [[1.01, 0, 0], [0, 1, 0], [0, 0, 1]]}'
# A general initial state (shear, tilt, lift) so that every listed effect has a nonzero energy.
scene general 'initial_state: {affine: [[1.01, 0.02, 0], [0, 0.99, 0], [0.1, 0.05, 1]], translate: [0, 0, 0.01]}' \
  '  - inertia'

# evaluate NAME OUTDIR [mpi]: runs -mlshell_evaluate, checks exit 0 and the printed lines.
evaluate() {
  local name=$1 out=$2 ranks=${3:-1}
  local cmd=("$MLSHELL" "$name.yaml" -mlshell_evaluate -mlshell_output_dir "$out")
  [[ $ranks -eq 1 ]] || cmd=(mpiexec --oversubscribe -n "$ranks" "${cmd[@]}")
  echo "check: $name on $ranks rank(s): -mlshell_evaluate exits 0 and prints every energy"
  local log
  log="logs/$(basename "$out")"
  local rc=0
  timeout 120 "${cmd[@]}" >"$log.stdout" 2>"$log.stderr" || rc=$?
  [[ $rc -eq 0 ]] || die "$name ($ranks ranks): exit status $rc, expected 0: $(head -c 800 "$log.stderr")"
  local effect
  for effect in elastic gravity dirichlet total; do
    grep -qE "^ *energy +$effect +" "$log.stdout" ||
      die "$name ($ranks ranks): no 'energy $effect' line in stdout: $(cat "$log.stdout")"
  done
  grep -q "gradient norm" "$log.stdout" || die "$name ($ranks ranks): no 'gradient norm' line"
  [[ -f $out/summary.json ]] || die "$name ($ranks ranks): $out/summary.json missing"
}

evaluate flat out/flat
evaluate stretch out/stretch
evaluate general out/general
evaluate stretch out/stretch-np2 2
evaluate general out/general-np2 2

echo "check: summary.json contents, closed-form stretch energy, 1 vs 2 ranks"
"$PY" - <<'EOF'
import json, math, sys

def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)

errors = []
def check(cond, msg):
    if not cond:
        errors.append(msg)

flat = load("out/flat/summary.json")
stretch = load("out/stretch/summary.json")
general = load("out/general/summary.json")

for name, s in (("flat", flat), ("stretch", stretch), ("general", general)):
    check(s.get("status") == "evaluated", f"{name}: status {s.get('status')!r}, expected 'evaluated'")
    check(s.get("dofs") == 363, f"{name}: dofs {s.get('dofs')}, expected 363")
    check(s.get("ranks") == 1, f"{name}: ranks {s.get('ranks')}, expected 1")
    check(s.get("steps") == 0, f"{name}: steps {s.get('steps')}, expected 0")
    e = s.get("energy", {})
    total = sum(v for k, v in e.items() if k != "total")
    check(abs(e.get("total", math.nan) - total) <= 1e-12 * max(1.0, abs(total)),
          f"{name}: energy.total {e.get('total')} is not the sum of the effects {total}")

# Only the listed effects (the elastic energy is always there) and the total.
for name, s, keys in (("flat", flat, {"elastic", "gravity", "dirichlet", "total"}),
                      ("stretch", stretch, {"elastic", "gravity", "dirichlet", "total"}),
                      ("general", general, {"elastic", "gravity", "dirichlet", "inertia", "total"})):
    got = set(s["energy"])
    check(got == keys, f"{name}: energy keys {sorted(got)}, expected {sorted(keys)}")

# Reference state: no strain, no elastic energy.
el = flat["energy"]["elastic"]
check(abs(el) < 1e-14, f"flat: elastic energy {el!r} in the reference state, expected 0")

# Uniform stretch x -> 1.01 x: Green-Lagrange E11 = (1.01^2 - 1)/2, E22 = E12 = 0, no bending;
# plane-stress SVK psi = E/(2(1 - nu^2)) E11^2 per volume, times thickness and area 1.
E, nu, t = 1.0e7, 0.3, 1.0e-3
e11 = (1.01 ** 2 - 1.0) / 2.0
expected = E / (2.0 * (1.0 - nu ** 2)) * e11 ** 2 * t
got = stretch["energy"]["elastic"]
rel = abs(got - expected) / expected
check(rel <= 1e-9, f"stretch: elastic energy {got!r}, closed form {expected!r} (relative error {rel:.3e})")

# Gravity on the lifted, tilted state: -rho g . integral of u = 9.81 * mean(u_z) with
# u_z = 0.1 x + 0.05 y + 0.01 over the unit square (density 1 kg/m^2).
g_expected = 9.81 * (0.1 * 0.5 + 0.05 * 0.5 + 0.01)
g_got = general["energy"]["gravity"]
check(abs(g_got - g_expected) <= 1e-10 * g_expected,
      f"general: gravity energy {g_got!r}, closed form {g_expected!r}")

for name, s in (("general", general),):
    for k, v in s["energy"].items():
        if k not in ("inertia",):  # the inertia predictor is the state itself: zero
            check(abs(v) > 1e-12, f"{name}: energy.{k} = {v!r}, expected nonzero for this state")

# 2 ranks against 1: every energy and the gradient norm to 1e-12 relative.
def close(a, b, rel=1e-12, floor=1e-14):
    return abs(a - b) <= max(rel * max(abs(a), abs(b)), floor)

for name, one in (("stretch", stretch), ("general", general)):
    two = load(f"out/{name}-np2/summary.json")
    check(two.get("ranks") == 2, f"{name}-np2: ranks {two.get('ranks')}, expected 2")
    check(set(two["energy"]) == set(one["energy"]),
          f"{name}: 2-rank energy keys {sorted(two['energy'])} differ from 1-rank {sorted(one['energy'])}")
    for k, v in one["energy"].items():
        w = two["energy"].get(k, math.nan)
        check(close(v, w), f"{name}: energy.{k}: 1 rank {v!r}, 2 ranks {w!r}")
    check(close(one["gradient_norm"], two["gradient_norm"]),
          f"{name}: gradient_norm: 1 rank {one['gradient_norm']!r}, 2 ranks {two['gradient_norm']!r}")

if errors:
    for e in errors:
        print("FAIL:", e, file=sys.stderr)
    sys.exit(1)
print(f"  stretch elastic energy {got!r}, closed form {expected!r} (relative error {rel:.2e})")
EOF
echo "evaluate_mode: all checks passed"
