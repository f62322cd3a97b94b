#!/usr/bin/env bash
# A solve whose energy falls without bound stops within a few dozen iterations and says why
# (step_solver.hpp, the energy floor): a balloon far beyond its limit pressure, with its own
# solver (pnewton) on 2 ranks and with rmtr, tr and bnls (whose line search fails on the way
# down), and a loaded sheet that nothing holds, with rmtr and pnewton. Each exits 3 with
# summary.json status solver_failed, names the scene's cause (and no dt where dt changes
# nothing), ends its results at the last good step and prints or writes no NaN or Inf.
#
# usage: bash unbounded_energy.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"

# The example balloon (limit pressure about 2 kPa) at 1 MPa, on a coarser sphere, 2 load steps.
sed -e "s|../../petsc-options|$SRC/petsc-options|" -e 's|pressure: 200,|pressure: 1.0e6,|' \
  -e 's|subdivisions: 3|subdivisions: 2|' -e 's|formats: \[xdmf, obj, csv\]|formats: [csv]|' \
  "$SRC/examples/triangle/balloon.yaml" >burst.yaml
grep -q 'pressure: 1.0e6' burst.yaml || die "burst.yaml: the pressure was not raised"
cat >free.yaml <<'YAML'
# A sheet under gravity that nothing holds, quasistatic with an almost vanishing proximal term.
name: free
geometry:
  mesh: {generator: rectangle, size: [1.0, 1.0], faces: [4, 4]}
material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: 0.0005, volume_density: 1000}
effects:
  - gravity: [0, 0, -9.81]
time: {dt: 1.0, steps: 2, integrator: quasistatic, proximal_step: 1.0e6}
output: {dir: out/free, formats: [csv]}
YAML

# run NAME SCENE RANKS CAUSE [SOLVER OPTIONS...]
run() {
  local name=$1 scene=$2 ranks=$3 cause=$4
  shift 4
  echo "check: $name stops fast, exit 3, naming '$cause'"
  local rc=0
  timeout 120 mpiexec --oversubscribe -n "$ranks" "$MLSHELL" "$scene" -mlshell_steps 2 \
    -mlshell_output_dir "out/$name" "$@" >"$name.log" 2>&1 || rc=$?
  [[ $rc -eq 3 ]] || die "$name: exit $rc, expected 3: $(tail -5 "$name.log")"
  grep -q "^mlshell: step 1 stopped after [0-9]* iterations: the energy fell to -[0-9.e+]* J, below" \
    "$name.log" || die "$name: no 'step 1 stopped ... the energy fell to': $(tail -5 "$name.log")"
  grep -q "it has no minimum near this state" "$name.log" || die "$name: no 'no minimum'"
  # The message and its causes, up to where the results end.
  sed -n '/step 1 stopped/,/results end at step 0/p' "$name.log" >"$name.message"
  grep -q -- "$cause" "$name.message" || die "$name: the causes do not name '$cause': $(cat "$name.message")"
  ! grep -qw 'dt' "$name.message" || die "$name: names dt, which changes nothing here: $(cat "$name.message")"
  ! grep -qiwE 'nan|-?inf(inity)?' "$name.log" "out/$name/summary.json" "out/$name/steps.csv" ||
    die "$name: NaN or Inf printed or written"
  $PY - "out/$name" "$name.log" <<'PY' || die "$name: summary.json or the iteration count"
import json, re, sys
from pathlib import Path
out, log = Path(sys.argv[1]), Path(sys.argv[2]).read_text()
s = json.load(open(out / "summary.json"))
assert s["status"] == "solver_failed", s["status"]
assert s["solver"]["reason"] == "DIVERGED_ENERGY_UNBOUNDED", s["solver"]["reason"]
assert s["steps"] == 0 and s["time"] == 0, (s["steps"], s["time"])  # results end at step 0
its = int(re.search(r"step 1 stopped after (\d+) iterations", log).group(1))
assert its < 100 and s["solver"]["iterations"] < 100, (its, s["solver"]["iterations"])
rows = (out / "steps.csv").read_text().splitlines()
assert len(rows) == 1, rows  # the header: no row of the divergent state
PY
}

run burst-pnewton burst.yaml 2 "the pressure (1e+06 Pa) may exceed the shell's limit pressure"
run burst-rmtr burst.yaml 1 "the pressure (1e+06 Pa)" -tao_type rmtr -mlshell_hessian_psd 0
run burst-tr burst.yaml 1 "the pressure (1e+06 Pa)" -tao_type tr -mlshell_hessian_psd 0
run burst-bnls burst.yaml 1 "the pressure (1e+06 Pa)" -tao_type bnls -mlshell_hessian_psd 0
grep -q "PETSC ERROR" burst-bnls.log && die "burst-bnls: PETSc's line search error was printed"
run free-rmtr free.yaml 2 "nothing holds the shell against its loads (gravity)"
run free-pnewton free.yaml 1 "nothing holds the shell against its loads (gravity)" -tao_type pnewton
echo "PASS"
