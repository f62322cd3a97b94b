#!/usr/bin/env bash
# The test command: installs missing Debian packages, builds mlshell and its tests, and runs the
# whole suite (GoogleTest units, the 2-rank MPI tests, and the command-line tests) with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
# ParaView's pvpython under a virtual X server, for the paraview.frames test only.
bash .ci/build paraview python3-paraview xvfb xauth
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# One BLAS thread per MPI rank: the ranks already occupy the cores.
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
cd build && ctest --output-on-failure -j "$(nproc)" "$@"
