#!/usr/bin/env bash
# -mlshell_hierarchy_view and -mlshell_hierarchy_write on a 4x4 square refined twice, on 2 ranks:
# one line per level with the paper's dof counts, S/R/Q statistics between levels, and an OBJ
# cage and limit surface per level.
#
# usage: bash hierarchy_view.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"

sed -e 's|out/trampoline|out|' -e "s|options_file: \.\./|options_file: $SRC/|" \
  "$SRC/examples/trampoline.yaml" >scene.yaml
echo "check: the hierarchy view lists levels 0..2 with 147, 363 and 1083 dofs, and S, R, Q"
timeout 120 mpiexec --oversubscribe -n 2 "$MLSHELL" scene.yaml -mlshell_evaluate \
  -mlshell_hierarchy_view -mlshell_hierarchy_write levels >view.log 2>&1 || die "exit $?: $(cat view.log)"
for dofs in 147 363 1083; do
  grep -qE "level [0-2]: .* $dofs dofs" view.log || die "no level with $dofs dofs: $(cat view.log)"
done
for op in "S (prolongation)" "R = S^T (restriction)" "Q (reverse subdivision)"; do
  [[ $(grep -cF "$op" view.log) -eq 2 ]] || die "expected two '$op' lines: $(cat view.log)"
done
grep -qE "Q \(reverse subdivision\) +0 <-> 1: +9\.00 entries/row" view.log ||
  die "Q between levels 0 and 1 should have 9 entries per row: $(cat view.log)"

echo "check: one cage and one limit surface OBJ per level"
for l in 0 1 2; do
  for kind in cage surface; do
    f=levels/level_${l}_$kind.obj
    [[ -s $f ]] || die "missing $f"
    grep -q '^v ' "$f" && grep -q '^f ' "$f" || die "$f has no vertices or faces"
  done
done
# The level-l cage has the paper's control point count: 49, 121, 361.
for pair in 0:49 1:121 2:361; do
  n=$(grep -c '^v ' "levels/level_${pair%%:*}_cage.obj")
  [[ $n -eq ${pair##*:} ]] || die "level ${pair%%:*} cage has $n vertices, expected ${pair##*:}"
done
echo "PASS"
