# Shared set-up of the command-line tests (sourced, not run; ctest runs tests/cli/*.sh).
#   usage in a test: source "$(dirname "$0")/lib/common.bash" "$@"
# Sets MLSHELL (absolute path of the program), SRC (source tree), WORK (a fresh, empty scratch
# folder, also the current directory) and PY; exports the Open MPI variables that allow root;
# defines die MESSAGE.
if [[ $# -ne 3 ]]; then
  echo "usage: $0 MLSHELL SOURCE_DIR WORK_DIR" >&2
  exit 2
fi
MLSHELL=$(realpath "$1")
SRC=$(realpath "$2")
WORK=$3
PY=/usr/bin/python3
export OMPI_ALLOW_RUN_AS_ROOT=${OMPI_ALLOW_RUN_AS_ROOT:-1}
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=${OMPI_ALLOW_RUN_AS_ROOT_CONFIRM:-1}
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}

[[ -n $WORK && $WORK != / ]] || { echo "bad WORK_DIR: '$WORK'" >&2; exit 2; }
rm -rf "$WORK"
mkdir -p "$WORK"
WORK=$(realpath "$WORK")
cd "$WORK"

die() {
  echo "FAIL: $*" >&2
  exit 1
}
