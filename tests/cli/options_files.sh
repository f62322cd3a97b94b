#!/usr/bin/env bash
# PETSc options files: a scene may name one (solver.options_file, relative to the scene), PETSc's
# own -options_file works with plain and YAML files and replaces the scene's file (the two are
# never mixed), -mlshell_scene_solver false ignores the scene's file, and the command line wins
# over both. summary.json names the file in effect and lists the options in effect.
# petsc-options/rmtr-patch-dogleg.yaml spells out mlshell's default, and on 2 ranks the default
# factorises the coarsest level whole on each rank (-tao_rmtr_coarse_redundant).
#
# usage: bash options_files.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"

mkdir -p scene
cat >scene/opts.yaml <<'YAML'
tao:
  type: bnls
  gatol: 1e-3
YAML
printf -- '-tao_type bntl\n' >plain.rc
sed -e 's|out/plate|out|' -e 's|refine: 3|refine: 1|' "$SRC/examples/plate.yaml" >scene/plate.yaml
printf 'solver: {options_file: opts.yaml}\n' >>scene/plate.yaml

# solver_type ARGS...: runs the plate and prints summary.json's solver type, gradient tolerance
# and options file
solver_type() {
  rm -rf out
  "$MLSHELL" scene/plate.yaml -mlshell_quiet "$@" >run.log 2>&1 || die "exit $?: $(cat run.log)"
  $PY -c "import json, os; s = json.load(open('out/summary.json'))['solver']
f = s['options_file']
print(s['type'], s['gradient_tolerance'], os.path.basename(f) if f else None)"
}

echo "check: the scene's options file selects the solver and its tolerance"
[[ $(solver_type) == "bnls 0.001 opts.yaml" ]] || die "scene options file not applied: $(solver_type)"
echo "check: the command line wins over the scene's options file"
[[ $(solver_type -tao_type bntr) == "bntr 0.001 opts.yaml" ]] || die "command line did not win"
echo "check: PETSc's -options_file (plain) replaces the scene's file: bntl, the default tolerance"
[[ $(solver_type -options_file "$WORK/plain.rc") == "bntl 1e-07 plain.rc" ]] ||
  die "-options_file did not replace the scene's: $(solver_type -options_file "$WORK/plain.rc")"
echo "check: -mlshell_scene_solver false ignores the scene's file: mlshell's built-in default"
[[ $(solver_type -mlshell_scene_solver false) == "rmtr 1e-07 None" ]] ||
  die "scene's file not ignored: $(solver_type -mlshell_scene_solver false)"
echo "check: the shipped options files in petsc-options/ select their solver and converge"
echo "       (the linearized equation takes one step and may stop short: exit 3 is its answer)"
for f in "$SRC"/petsc-options/*.yaml; do
  rm -rf out
  rc=0
  "$MLSHELL" scene/plate.yaml -mlshell_quiet -options_file "$f" >run.log 2>&1 || rc=$?
  expected=$(sed -n 's/^  type: *//p' "$f" | head -n 1)
  if grep -q '^  step_solver: snes' "$f"; then expected="snes-$expected"; fi
  $PY - "$f" "$rc" "$expected" <<'PY' || die "$f: $(cat run.log)"
import json, sys
name, rc, expected = sys.argv[1], int(sys.argv[2]), sys.argv[3]
s = json.load(open("out/summary.json"))
assert s["solver"]["type"] == expected, f"solver {s['solver']['type']} != {expected}"
if expected == "linearized":
    assert rc in (0, 3) and s["solver"]["iterations"] == 1, f"linearized: rc {rc}, {s['solver']}"
else:
    assert rc == 0 and s["solver"]["converged"], f"rc {rc}, {s['solver']}"
PY
done
echo "PASS"

# run_summary NAME ARGS...: one step of the drooping cloth at 363 dofs into NAME/, printing its
# V-cycles, energy and gradient norm
run_summary() {
  local name=$1
  shift
  "$MLSHELL" "$SRC/examples/drooping.yaml" -mlshell_quiet -mlshell_refine 1 -mlshell_steps 1 \
    -mlshell_output_dir "$name" "$@" >"$name.log" 2>&1 || die "$name: exit $?: $(tail -5 "$name.log")"
  $PY -c "import json; d = json.load(open('$name/summary.json'))
print(d['solver']['iterations'], repr(d['energy']['total']), repr(d['gradient_norm']))"
}
echo "check: petsc-options/rmtr-patch-dogleg.yaml spells out mlshell's default (the same run)"
default=$(run_summary default)
spelled=$(run_summary spelled -options_file "$SRC/petsc-options/rmtr-patch-dogleg.yaml")
[[ "$default" == "$spelled" ]] || die "default '$default' but rmtr-patch-dogleg.yaml '$spelled'"
factorised=$(run_summary factorised -options_file "$SRC/petsc-options/rmtr.yaml")
[[ "$default" != "$factorised" ]] || die "rmtr.yaml ran the default: '$factorised'"
echo "check: summary.json records the PETSc options in effect, mlshell's defaults included"
options() { $PY -c "import json; print(json.load(open('$1/summary.json'))['solver']['petsc_options'])"; }
[[ " $(options default) " == *" -tao_rmtr_smoother_pc vpatch "* ]] ||
  die "default run's options: $(options default)"
[[ " $(options factorised) " == *" -tao_rmtr_smoother_pc none "* ]] ||
  die "rmtr.yaml run's options: $(options factorised)"

echo "check: on 2 ranks the default factorises the coarsest level whole on each rank"
coarse_pc() {  # coarse_pc ARGS...: the PC types of the coarsest level's first solve
  mpiexec --oversubscribe -n 2 "$MLSHELL" "$SRC/examples/drooping.yaml" -mlshell_quiet \
    -mlshell_refine 1 -mlshell_steps 1 -mlshell_output_dir coarse -tao_max_it 1 \
    -tao_rmtr_fmg_cycles 0 -rmtr_coarse_ksp_view "$@" >coarse.log 2>&1 || true
  grep -m 2 -o "^ *type: [a-z]*" coarse.log | sed -n 2p | tr -d ' '
}
[[ $(coarse_pc) == "type:redundant" ]] || die "default coarse PC: $(coarse_pc)"
[[ $(coarse_pc -tao_rmtr_coarse_redundant 0) == "type:cholesky" ]] ||
  die "-tao_rmtr_coarse_redundant 0: coarse PC $(coarse_pc -tao_rmtr_coarse_redundant 0)"
[[ $(coarse_pc -tao_rmtr_coarse_redundant 100) == "type:cholesky" ]] ||
  die "-tao_rmtr_coarse_redundant 100 (below the 147-dof level): $(coarse_pc -tao_rmtr_coarse_redundant 100)"
