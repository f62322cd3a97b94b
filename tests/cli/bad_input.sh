#!/usr/bin/env bash
# Broken inputs are rejected cleanly: every scene in tests/data/bad, a missing scene file, no
# argument at all, broken OBJ cages and a selection that selects nothing. Each must end with
# the documented exit status and a message that names the offending file, without a crash,
# a PETSc error trace or a summary.json; under MPI both ranks must exit (no hang).
#
# usage: bash bad_input.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"

failures=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# Words that only a crash or an unhandled error would print (case-sensitive on purpose:
# mpiexec's normal note on a non-zero exit says "the job has been aborted").
CRASH_PATTERN='Segmentation|Abort|MPI_ABORT|core dumped|PETSC ERROR|signal [0-9]'

# run_case NAME EXPECTED_RC NEEDLE SCENE_OR_EMPTY [ARGS...]
#   Runs mlshell with ARGS in a fresh folder WORK/NAME and checks the exit status, that stderr
#   is non-empty and contains NEEDLE, that nothing looks like a crash, and that no summary.json
#   was written (neither anywhere under the folder nor in the output.dir SCENE names).
run_case() {
  local name=$1 expect=$2 needle=$3 scene=$4
  shift 4
  local dir="$WORK/cases/$name"
  mkdir -p "$dir"
  echo "check: $name: exit $expect, stderr names '$needle'"
  local rc=0
  (cd "$dir" && timeout 120 "$MLSHELL" "$@" >stdout.txt 2>stderr.txt) || rc=$?
  if [[ $rc -ne $expect ]]; then
    fail "$name: exit status $rc, expected $expect; stderr: $(head -c 600 "$dir/stderr.txt")"
  fi
  if [[ ! -s "$dir/stderr.txt" ]]; then
    fail "$name: nothing on stderr"
  elif ! grep -qF -- "$needle" "$dir/stderr.txt"; then
    fail "$name: stderr does not contain '$needle': $(head -c 600 "$dir/stderr.txt")"
  fi
  if grep -qE "$CRASH_PATTERN" "$dir/stdout.txt" "$dir/stderr.txt"; then
    fail "$name: output looks like a crash: $(grep -hE "$CRASH_PATTERN" "$dir/stdout.txt" "$dir/stderr.txt" | head -3)"
  fi
  local found
  found=$(find "$dir" -name summary.json | head -1)
  [[ -z $found ]] || fail "$name: a summary.json was written: $found"
  if [[ -n $scene ]]; then
    # output.dir as the scene names it (default: out), relative to the working folder.
    local outdir
    outdir=$("$PY" - "$scene" <<'EOF'
import re, sys
text = open(sys.argv[1], encoding="utf-8").read()
m = re.search(r"^output:\s*\{[^}]*\bdir:\s*([^,}\s]+)", text, re.M) or \
    re.search(r"^output:\s*\n(?:[ \t]+.*\n)*?[ \t]+dir:\s*(\S+)", text, re.M)
print(m.group(1) if m else "out")
EOF
)
    [[ ! -e "$dir/$outdir/summary.json" ]] || fail "$name: $outdir/summary.json was written"
  fi
}

# run_folder FOLDER PREFIX DESCRIPTION: every scene in tests/data/FOLDER exits 2 naming itself.
run_folder() {
  local folder=$1 prefix=$2 description=$3 scene base
  shopt -s nullglob
  local scenes=("$SRC/tests/data/$folder"/*.yaml)
  shopt -u nullglob
  [[ ${#scenes[@]} -gt 0 ]] || { echo "FAIL: no scenes in $SRC/tests/data/$folder" >&2; exit 1; }
  echo "== ${#scenes[@]} $description"
  for scene in "${scenes[@]}"; do
    base=$(basename "$scene")
    run_case "$prefix-${base%.yaml}" 2 "$base" "$scene" "$scene"
  done
}

# --- every scene in tests/data/bad --------------------------------------------------------------
run_folder bad bad "broken scenes from tests/data/bad"

# --- scenes that parse but fail on their mesh (tests/data/bad_on_mesh) ---------------------------------
# Selections and effects that the mesh itself refutes: still exit 2, naming the scene file.
run_folder bad_on_mesh on-mesh "scenes refuted by their mesh"

# --- the command line -----------------------------------------------------------------------------
echo "== command line"
run_case missing-scene 2 "no_such_scene.yaml" "" no_such_scene.yaml
run_case no-argument 1 "usage" ""
run_case only-options 1 "usage" "" -mlshell_evaluate
# Nonsense option values, mlshell's own and the solvers': exit 2 and one line naming the option
# (no PETSc trace), and no summary.json.
TRAMPOLINE="$SRC/examples/trampoline.yaml"
run_case option-dt 2 "-mlshell_dt" "" "$TRAMPOLINE" -mlshell_dt -1
run_case option-refine 2 "-mlshell_refine" "" "$TRAMPOLINE" -mlshell_refine 12
run_case option-force-rtol 2 "-mlshell_force_rtol" "" "$TRAMPOLINE" -mlshell_force_rtol -1
run_case option-eta1 2 "-tao_rmtr_eta1 = 0.9" "" "$TRAMPOLINE" -tao_rmtr_eta1 0.9
run_case option-projection 2 "-tao_rmtr_projection" "" "$TRAMPOLINE" -tao_rmtr_projection foo
run_case option-stagnation 2 "-tao_rmtr_stagnation" "" "$TRAMPOLINE" -tao_rmtr_stagnation -1
run_case option-tr-gamma 2 "-tao_tr_gamma1 = 2" "" "$TRAMPOLINE" -tao_type tr -tao_tr_gamma1 2
run_case option-levels 2 "-tao_rmtr_levels" "" "$TRAMPOLINE" -tao_rmtr_levels 9

# --- broken OBJ cages -----------------------------------------------------------------------------
echo "== broken OBJ cages"
mkdir -p "$WORK/meshes"
cat >"$WORK/meshes/triangle.obj" <<'EOF'
# a quad and a triangle
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 2 0 0
f 1 2 3 4
f 2 5 3
EOF
cat >"$WORK/meshes/non_manifold.obj" <<'EOF'
# three quads sharing the edge 2-3
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 2 0 0
v 2 1 0
v 1 0 1
v 1 1 1
f 1 2 3 4
f 2 5 6 3
f 3 2 7 8
EOF
cat >"$WORK/meshes/degenerate.obj" <<'EOF'
# the second quad repeats vertex 5
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 2 0 0
v 2 1 0
f 1 2 3 4
f 2 5 5 3
EOF
cat >"$WORK/meshes/index_out_of_range.obj" <<'EOF'
# vertex 9 does not exist
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
f 1 2 3 9
EOF
for mesh in triangle non_manifold degenerate index_out_of_range; do
  cat >"$WORK/meshes/$mesh.yaml" <<EOF
geometry:
  cage: {obj: $mesh.obj}
  refine: 1
material: {model: isotropic-svk, youngs_modulus: 1e7, poisson_ratio: 0.3, thickness: 1e-3,
           density: 1}
effects:
  - gravity
time: {dt: 1.0, steps: 1}
output: {dir: out/$mesh}
EOF
  run_case "obj-$mesh" 2 "$mesh.obj" "$WORK/meshes/$mesh.yaml" "$WORK/meshes/$mesh.yaml"
done

# --- broken OBJ triangle meshes ---------------------------------------------------------------------
# Each names the file and line (and the vertex or face at fault).
echo "== broken OBJ triangle meshes"
write_tri() { printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n' >"$WORK/meshes/$1.obj"; cat >>"$WORK/meshes/$1.obj"; }
write_tri tri_non_manifold <<'EOF'
v 0.5 0.5 1
f 1 2 3
f 1 3 4
f 1 3 5
EOF
write_tri tri_flipped <<'EOF'
f 1 2 3
f 1 4 3
EOF
write_tri tri_degenerate <<'EOF'
v 2 0 0
f 1 2 3
f 1 2 5
EOF
write_tri tri_nan <<'EOF'
v nan 0 0
f 1 2 3
f 3 5 1
EOF
write_tri tri_bad_index <<'EOF'
f 1 2 3
f 1 3 7
EOF
for mesh in tri_non_manifold tri_flipped tri_degenerate tri_nan tri_bad_index; do
  cat >"$WORK/meshes/$mesh.yaml" <<EOF
geometry: {mesh: {obj: $mesh.obj}}
material: {model: neo-hookean, youngs_modulus: 1e6, poisson_ratio: 0.3, thickness: 1e-3,
           volume_density: 500}
effects:
  - gravity
time: {dt: 1.0, steps: 1}
output: {dir: out/$mesh}
EOF
  run_case "obj-$mesh" 2 "$mesh.obj:" "$WORK/meshes/$mesh.yaml" "$WORK/meshes/$mesh.yaml"
done

# --- a selection that selects nothing ---------------------------------------------------------------
echo "== empty selection"
cat >"$WORK/empty_box.yaml" <<'EOF'
geometry:
  cage: {generator: rectangle, size: [1.0, 1.0], faces: [4, 4]}
  refine: 1
material: {model: isotropic-svk, youngs_modulus: 1e7, poisson_ratio: 0.3, thickness: 1e-3,
           density: 1}
effects:
  - gravity
  - dirichlet: {where: {box: {min: [5, 5, 5], max: [6, 6, 6]}}}
time: {dt: 1.0, steps: 1}
output: {dir: out/empty-box}
EOF
run_case empty-box 2 "selects no" "$WORK/empty_box.yaml" "$WORK/empty_box.yaml"

# --- two ranks ----------------------------------------------------------------------------------------
# mpiexec's own status must be 2, and each rank must itself exit with 2. The second run keeps
# Open MPI from killing the other rank once one has exited non-zero, so that a wrapper can
# record each rank's status.
echo "== two ranks"
mpi_case() {
  local name=$1 needle=$2 scene=$3
  shift 3  # the rest: options
  local dir="$WORK/mpi/$name"
  mkdir -p "$dir"
  echo "check: $name on 2 ranks: mpiexec and both ranks exit 2 within 60 s, stderr names '$needle'"
  local rc=0
  (cd "$dir" && timeout 60 mpiexec --oversubscribe -n 2 "$MLSHELL" "$scene" "$@" \
     >stdout.txt 2>stderr.txt) || rc=$?
  [[ $rc -ne 124 && $rc -ne 137 ]] || fail "$name: mpiexec -n 2 did not finish within 60 s (hang?)"
  [[ $rc -eq 2 ]] || fail "$name: mpiexec -n 2 exit status $rc, expected 2; stderr: $(head -c 600 "$dir/stderr.txt")"
  grep -qF -- "$needle" "$dir/stderr.txt" || fail "$name: 2-rank stderr does not contain '$needle'"
  if grep -qE "$CRASH_PATTERN" "$dir/stdout.txt" "$dir/stderr.txt"; then
    fail "$name: 2-rank output looks like a crash: $(grep -hE "$CRASH_PATTERN" "$dir/stdout.txt" "$dir/stderr.txt" | head -3)"
  fi
  rc=0
  # shellcheck disable=SC2016  # expanded by the inner bash, per rank
  (cd "$dir" && OMPI_MCA_orte_abort_on_non_zero_status=0 timeout 60 mpiexec --oversubscribe -n 2 \
     bash -c '"$0" "$@" >/dev/null 2>&1; rc=$?; echo "$rc" >"rank-${OMPI_COMM_WORLD_RANK:-x}.rc"; exit 0' \
     "$MLSHELL" "$scene" "$@" >/dev/null 2>&1) || rc=$?
  [[ $rc -ne 124 && $rc -ne 137 ]] || fail "$name: per-rank run did not finish within 60 s (hang?)"
  local r
  for r in 0 1; do
    if [[ ! -f "$dir/rank-$r.rc" ]]; then
      fail "$name: rank $r recorded no exit status"
    elif [[ $(cat "$dir/rank-$r.rc") != 2 ]]; then
      fail "$name: rank $r exited with $(cat "$dir/rank-$r.rc"), expected 2"
    fi
  done
  [[ -z $(find "$dir" -name summary.json) ]] || fail "$name: a summary.json was written on 2 ranks"
}
mpi_case wrong_type "wrong_type.yaml" "$SRC/tests/data/bad/wrong_type.yaml"
mpi_case named_side_with_obj_cage "named_side_with_obj_cage.yaml" \
  "$SRC/tests/data/bad/named_side_with_obj_cage.yaml"
# Errors raised after the parallel layout exists (mesh, selection) must not hang either.
mpi_case obj-non_manifold "non_manifold.obj" "$WORK/meshes/non_manifold.yaml"
mpi_case empty-box "selects no" "$WORK/empty_box.yaml"
# A solver option refused during setup, on every rank alike.
mpi_case option-levels-2ranks "-tao_rmtr_levels" "$TRAMPOLINE" -tao_rmtr_levels 9

if [[ $failures -gt 0 ]]; then
  echo "bad_input: $failures check(s) failed" >&2
  exit 1
fi
echo "bad_input: all checks passed"
