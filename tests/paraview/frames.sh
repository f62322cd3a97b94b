#!/usr/bin/env bash
# ctest paraview.frames: what ParaView shows of mlshell's frames. Runs a small subdivision sheet
# (tests/paraview/sheet.yaml: 6 x 4 elements, 3 samples per face edge) and a small triangle scene
# (examples/triangle/plate_buckling.yaml, 16 x 16 squares, 2 of its steps) on 2 ranks, checks both
# XDMF series with ParaView's readers (check_frames.py: counts, fields, deformed geometry,
# watertightness), renders each last frame with examples/render.py and checks the picture is
# not blank, and finally checks that check_frames.py fails on a wrong element count.
#
#   bash tests/paraview/frames.sh build/mlshell . /tmp/pv-frames
set -euo pipefail
mlshell=$1 root=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
pv() { bash "$root/examples/pvpython.sh" "$@"; }
run() { mpiexec --oversubscribe -n 2 "$mlshell" "$@" > "$work/$(basename "$1" .yaml).log" 2>&1 ||
          { cat "$work/$(basename "$1" .yaml).log"; exit 1; }; }

run "$root/tests/paraview/sheet.yaml" -mlshell_output_dir "$work/sheet"
run "$root/examples/triangle/plate_buckling.yaml" -mlshell_steps 2 \
    -mlshell_output_dir "$work/plate_buckling"
pv "$root/examples/render.py" "$work/sheet"
pv "$root/examples/render.py" "$work/plate_buckling" --zscale 20

status=0
pv "$root/tests/paraview/check_frames.py" "$work/sheet/sheet.xdmf" --steps 2 --quads 6 4 \
   --samples 3 --png "$work/sheet/final.png" || status=1
pv "$root/tests/paraview/check_frames.py" "$work/plate_buckling/plate_buckling.xdmf" --steps 2 \
   --triangles 16 16 --png "$work/plate_buckling/final.png" || status=1
# The checker itself: told the sheet has 6 x 5 elements, it must fail.
if pv "$root/tests/paraview/check_frames.py" "$work/sheet/sheet.xdmf" --steps 2 --quads 6 5 \
      --samples 3 > "$work/wrong_count.log" 2>&1; then
  echo "FAIL check_frames.py passed a sheet of 6 x 5 elements (it has 6 x 4)"; status=1
else
  echo "ok   check_frames.py fails on a wrong element count" \
       "($(grep -c '^FAIL' "$work/wrong_count.log") checks)"
fi
exit $status
