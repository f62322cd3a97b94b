#!/usr/bin/env bash
# Iterations of one time step at dt = 1 for the four paper scenes (paper Tables 3-5): TR
# (Dogleg) iterations and RMTR V-cycles with mlshell's default Dogleg smoothing and with the
# paper's ten STCG iterations, at 1,083 dofs (3 levels) and 3,675 dofs (4 levels).
#
# usage: bash studies/solver_table.sh [BUILD_DIR] [RANKS] [MAX_IT]   (defaults: build 2 1000)
# Prints one line per run: scene, dofs, solver, iterations, converged reason, wall time.
set -euo pipefail
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$(realpath "${1:-$SRC/build}")
RANKS=${2:-2}
MAX_IT=${3:-1000}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
printf '%-18s %6s %-12s %6s %-24s %8s\n' scene dofs solver its reason wall_s
for refine in 2 3; do
  for scene in trampoline drooping reentrant_corner drape; do
    sed "s/^\(  refine:\) *[0-9]*/\1 $refine/" "$SRC/examples/$scene.yaml" >"$WORK/$scene.yaml"
    for solver in tr rmtr rmtr-stcg; do
      case $solver in
        tr) opts=(-tao_type tr) ;;
        rmtr) opts=(-tao_type rmtr) ;;
        rmtr-stcg) opts=(-tao_type rmtr -tao_rmtr_smoother_qp stcg) ;;
      esac
      line=$(mpiexec --oversubscribe -n "$RANKS" "$BUILD/mlshell" "$WORK/$scene.yaml" \
        -mlshell_steps 1 -mlshell_dt 1 -mlshell_output_dir "$WORK/out" -tao_max_it "$MAX_IT" \
        "${opts[@]}" 2>&1 | grep '^step' || true)
      dofs=$(grep -o '"dofs": [0-9]*' "$WORK/out/summary.json" | head -1 | grep -o '[0-9]*$')
      its=$(sed -n 's/.*its = *\([0-9]*\).*/\1/p' <<<"$line")
      reason=$(awk '{for (i = 1; i <= NF; ++i) if ($i ~ /^(CONVERGED|DIVERGED)/) print $i}' <<<"$line")
      wall=$(awk '{print $(NF-1)}' <<<"$line")
      printf '%-18s %6s %-12s %6s %-24s %8s\n' "$scene" "$dofs" "$solver" "$its" "$reason" "$wall"
    done
  done
done
