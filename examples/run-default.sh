#!/usr/bin/env bash
# The main job: installs missing Debian packages, builds mlshell, and runs the default example
# (the paper's trampoline scene, 1,083 dofs, 10 implicit Euler steps of dt = 1 s) on 2 MPI ranks.
# Results go to out/trampoline/ (summary.json, steps.csv, trampoline.xdmf for ParaView, OBJ frames).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/build
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# One BLAS thread per MPI rank: the ranks already occupy the cores.
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
mpiexec --oversubscribe -n 2 build/mlshell examples/trampoline.yaml "$@"
echo "Open out/trampoline/trampoline.xdmf in ParaView; per-step statistics: out/trampoline/steps.csv; summary: out/trampoline/summary.json"
