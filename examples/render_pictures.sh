#!/usr/bin/env bash
# Runs every example scene (examples/*.yaml, examples/triangle/*.yaml, examples/contact/*.yaml)
# at its default resolution and steps on 2 ranks into out/pictures/<scene>/, and renders its last frame with ParaView
# (examples/render.py) to examples/pictures/<scene>.png; the drape also to the README's banner,
# docs/pictures/drape.png. Needs build/mlshell and pvpython (Debian python3-paraview, xvfb);
# examples/pvpython.sh runs pvpython under xvfb-run.
#
#   bash examples/render_pictures.sh                  # all scenes (a few minutes on 2 cores)
#   bash examples/render_pictures.sh drape balloon    # only these
#   bash examples/render_pictures.sh --no-run         # render the runs already in out/pictures
set -euo pipefail
cd "$(dirname "$0")/.."
run=1; [ "${1:-}" = --no-run ] && { run=0; shift; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
# Steel and acrylic plates bend by millimetres or less: z is exaggerated (the caption says so).
declare -A view=([plate]="--zscale 1000" [clamped_plate]="--zscale 1000"
                 [plate_buckling]="--zscale 5" [plate_shearing]="--zscale 5"
                 [balloon]="--elev 20" [unstructured_drape]="--elev 12"
                 [strip_over_sphere]="--elev 20 --azim=-100 --size 800 450"
                 [balloon_press]="--elev 15" [balloon_in_corner]="--elev=-12 --azim=-120"
                 [sphere_lift]="--elev 20 --azim=-100 --size 800 450" [cloth_on_sphere]="--elev 30"
                 [can_crush]="--elev 10" [crossed_strips]="--elev 20 --azim=-60")
mkdir -p examples/pictures docs/pictures out/pictures
for scene in examples/*.yaml examples/triangle/*.yaml examples/contact/*.yaml; do
  name=$(basename "$scene" .yaml)
  [[ $name == *-options ]] && continue  # a scene's PETSc options, not a scene
  [ $# -eq 0 ] || [[ " $* " == *" $name "* ]] || continue
  out=out/pictures/$name
  echo "render_pictures: $scene -> examples/pictures/$name.png"
  if [ $run = 1 ]; then
    mpiexec --oversubscribe -n 2 build/mlshell "$scene" -mlshell_output_dir "$out" \
      > "$out.log" 2>&1 || { tail -20 "$out.log"; exit 1; }
  fi
  # shellcheck disable=SC2086  # the view options are words
  bash examples/pvpython.sh examples/render.py "$out" --out "examples/pictures/$name.png" \
    ${view[$name]:-}
  if [ "$name" = drape ]; then
    bash examples/pvpython.sh examples/render.py "$out" --out docs/pictures/drape.png \
      --size 1200 500 --no-title --azim=-45 --elev 20
  fi
done
