#!/usr/bin/env bash
# -mlshell_hierarchy_view and -mlshell_hierarchy_write on 2 ranks. A 4x4 square refined twice:
# one line per level with the paper's dof counts, S/R/Q statistics between levels, and an OBJ
# cage and limit surface per level. The shell indent's dome decimated into 3 levels: one line
# per level, rest-shape recovery to round-off, and per level its rest mesh and its prolongation
# to the finest level.
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
sed -e 's|out/shell_indent|out|' -e "s|options_file: \.\./\.\./|options_file: $SRC/|" \
  "$SRC/examples/triangle/shell_indent.yaml" >dome.yaml
echo "check: the triangle hierarchy view lists 3 levels with rest-shape errors at round-off"
timeout 120 mpiexec --oversubscribe -n 2 "$MLSHELL" dome.yaml -mlshell_evaluate \
  -mlshell_hierarchy_view -mlshell_hierarchy_write dome_levels >dome.log 2>&1 ||
  die "exit $?: $(cat dome.log)"
grep -q "triangle hierarchy (3 levels, fingerprint [0-9a-f]\{16\})" dome.log ||
  die "no triangle hierarchy header: $(cat dome.log)"
[[ $(grep -c "rest shape: P_" dome.log) -eq 2 ]] || die "expected two rest-shape lines: $(cat dome.log)"
"$PY" - dome.log <<'EOF_PY' || die "rest-shape errors above 1e-12: $(cat dome.log)"
import re, sys
errors = [float(x) for x in re.findall(r"P[_^]\S* ([0-9.e+-]+)", open(sys.argv[1]).read())]
sys.exit(0 if len(errors) == 4 and max(errors) < 1e-12 else 1)
EOF_PY
fine=$(grep -c '^v ' dome_levels/level_2.obj)
for l in 0 1; do
  [[ $(grep -c '^v ' dome_levels/level_$l.obj) -lt $fine ]] || die "level $l is not coarser"
  [[ $(grep -c '^v ' dome_levels/level_${l}_to_finest.obj) -eq $fine ]] ||
    die "level_${l}_to_finest.obj does not have the finest level's $fine vertices"
done
echo "PASS"
