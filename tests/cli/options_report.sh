#!/usr/bin/env bash
# mlshell's options follow PETSc's conventions: `mlshell -help` without a scene exits 0 and lists
# exactly the -mlshell_* options the source reads (and TAO rmtr's); after a run every option
# given that nothing read is named with a "did you mean" (stderr and summary.json), but not
# mlshell's own defaults, and -mlshell_options_left false silences it; an output folder that
# cannot be created exits 4 naming it, on 1 and 2 ranks, without a crash.
#
# usage: bash options_report.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"
SCENE="$SRC/examples/trampoline.yaml"  # names ../petsc-options/rmtr-patch.yaml
CRASH_PATTERN='Segmentation|Abort|MPI_ABORT|core dumped|PETSC ERROR|signal [0-9]'

echo "check: mlshell -help without a scene exits 0 and lists every -mlshell_* option the source reads"
rc=0
"$MLSHELL" -help >help.txt 2>help.err || rc=$?
[[ $rc -eq 0 ]] || die "mlshell -help: exit $rc, expected 0: $(head -c 600 help.err)"
grep -qF "usage: mlshell SCENE.yaml" help.txt || die "mlshell -help prints no usage"
grep -rhoE -- '"-mlshell_[a-z_]+' "$SRC/src" "$SRC/mesh" "$SRC/solvers" | tr -d '"' | sort -u >read.txt
# PETSc's help lines: "  -name <default>: text" or "  -name: <default> text" (the usage's
# own lines, "  -name   text", do not count).
grep -E -- '^  -mlshell_[a-z_]+:? <' help.txt | grep -oE -- '-mlshell_[a-z_]+' | sort -u >listed.txt
[[ $(wc -l <read.txt) -ge 15 ]] || die "only $(wc -l <read.txt) -mlshell_* options found in the source"
missing=$(comm -23 read.txt listed.txt)
[[ -z $missing ]] || die "-help does not list: $missing"
extra=$(comm -13 read.txt listed.txt)
[[ -z $extra ]] || die "-help lists options the source does not read: $extra"
# Each with its default (PETSc's "<now X : formerly Y>" or "<X : Y>").
grep -E -- '^  -mlshell_steps <now 1 : formerly 1>: ' help.txt >/dev/null ||
  die "-help shows no default for -mlshell_steps: $(grep -- -mlshell_steps help.txt | tail -1)"
for o in -tao_rmtr_smoother_qp -tao_rmtr_subspace -tao_gatol; do
  grep -qE -- "^  $o[ :]" help.txt || die "-help does not list TAO's $o"
done
grep -qE -- '^  -tao_rmtr_smoother_qp <now dogleg' help.txt ||
  die "-help does not show mlshell's default -tao_rmtr_smoother_qp dogleg"

# run NAME [ARGS...]: one step of the trampoline into out/NAME, stdout/stderr in NAME.out/.err.
run() {
  local name=$1
  shift
  local rc=0
  timeout 120 "$MLSHELL" "$SCENE" -mlshell_quiet -mlshell_steps 1 -mlshell_output_dir "out/$name" \
    "$@" >"$name.out" 2>"$name.err" || rc=$?
  [[ $rc -eq 0 ]] || die "$name: exit $rc, expected 0: $(tail -5 "$name.err")"
}
# unused_in_summary NAME: the names in out/NAME/summary.json's unused_options, one a line.
unused_in_summary() {
  $PY -c 'import json, sys
for o in json.load(open(sys.argv[1]))["unused_options"]: print(o["name"], o["value"], o["did_you_mean"])' \
    "out/$1/summary.json"
}

echo "check: a correct run warns about nothing, and summary.json lists no unused option"
run clean -tao_rmtr_smoother_qp stcg -tao_monitor -log_view
! grep -q "was never used" clean.err || die "a correct run warns: $(cat clean.err)"
[[ -z $(unused_in_summary clean) ]] || die "summary.json of a correct run: $(unused_in_summary clean)"

echo "check: a misspelt option is named with its suggestion (exit 0, stderr, summary.json)"
run misspelt -tao_rmtr_smoothr_qp stcg -mlshell_quite
expect="mlshell: warning: option -tao_rmtr_smoothr_qp (value stcg) was never used; did you mean -tao_rmtr_smoother_qp?"
grep -qxF "$expect" misspelt.err || die "no warning '$expect' in: $(cat misspelt.err)"
expect="mlshell: warning: option -mlshell_quite was never used; did you mean -mlshell_quiet?"
grep -qxF "$expect" misspelt.err || die "no warning '$expect' in: $(cat misspelt.err)"
[[ $(grep -c "was never used" misspelt.err) -eq 2 ]] || die "more warnings than 2: $(cat misspelt.err)"
unused_in_summary misspelt | grep -qxF -- "-tao_rmtr_smoothr_qp stcg -tao_rmtr_smoother_qp" ||
  die "summary.json: $(unused_in_summary misspelt)"

echo "check: -mlshell_options_left false silences the warnings"
run silenced -tao_rmtr_smoothr_qp stcg -mlshell_options_left false
! grep -q "was never used" silenced.err || die "-mlshell_options_left false still warns: $(cat silenced.err)"

echo "check: the scene's solver file's keys that -tao_type tr does not read are named, mlshell's defaults not"
run tr -tao_type tr
for o in -tao_rmtr_fmg_cycles -tao_rmtr_smoother_qp -rmtr_coarse_pc_type; do
  grep -qF "option $o (value" tr.err || die "-tao_type tr: the file's $o is not named: $(cat tr.err)"
done
# -tao_rmtr_newton_rtol and -tao_rmtr_coarse_redundant are mlshell's defaults, not in the file.
! grep -qE -- "-tao_rmtr_(newton_rtol|coarse_redundant)" tr.err ||
  die "-tao_type tr: mlshell's own defaults are reported: $(cat tr.err)"
grep -qF "come from the options file in effect" tr.err || die "-tao_type tr: no note on the file"

echo "check: -mlshell_evaluate (no solver) names a misspelt command-line option, not the file's keys"
run evaluate -mlshell_evaluate -mlshell_conditon
grep -qxF "mlshell: warning: option -mlshell_conditon was never used; did you mean -mlshell_condition?" \
  evaluate.err || die "-mlshell_evaluate: $(cat evaluate.err)"
[[ $(grep -c "was never used" evaluate.err) -eq 1 ]] || die "-mlshell_evaluate warns about the file: $(cat evaluate.err)"

echo "check: an output folder under a regular file exits 4 naming it, on 1 and 2 ranks"
touch not_a_folder
expect="mlshell: error: cannot create output folder 'not_a_folder/out': Not a directory"
for ranks in 1 2; do
  rc=0
  timeout 120 mpiexec --oversubscribe -n "$ranks" "$MLSHELL" "$SCENE" -mlshell_steps 1 \
    -mlshell_output_dir not_a_folder/out >"unwritable$ranks.out" 2>"unwritable$ranks.err" || rc=$?
  [[ $rc -eq 4 ]] || die "$ranks rank(s): exit $rc, expected 4: $(head -c 600 "unwritable$ranks.err")"
  grep -qxF "$expect" "unwritable$ranks.err" || die "$ranks rank(s): no '$expect' in: $(cat "unwritable$ranks.err")"
  [[ $(grep -c "cannot create output folder" "unwritable$ranks.err") -eq 1 ]] ||
    die "$ranks rank(s): the error is printed more than once"
  ! grep -qE "$CRASH_PATTERN" "unwritable$ranks.out" "unwritable$ranks.err" ||
    die "$ranks rank(s): looks like a crash: $(grep -hE "$CRASH_PATTERN" "unwritable$ranks.err" | head -3)"
done

echo "options_report: all checks passed"
