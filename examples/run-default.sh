#!/usr/bin/env bash
# The main job: installs missing Debian packages, builds mlshell, and runs the default example
# (the paper's drape, Fig. 1: two corners moved 20 cm towards each other, 1,083 dofs, 10 implicit
# Euler steps of dt = 1 s) on 2 MPI ranks. Results go to out/drape/ (summary.json, steps.csv,
# drape.xdmf for ParaView, OBJ frames).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/build
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# One BLAS thread per MPI rank: the ranks already occupy the cores.
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
mpiexec --oversubscribe -n 2 build/mlshell examples/drape.yaml "$@"
echo "Open out/drape/drape.xdmf in ParaView (Apply, colour by displacement, Play; docs/outputs.md);"
echo "per-step statistics: out/drape/steps.csv; summary: out/drape/summary.json"
