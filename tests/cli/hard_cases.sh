#!/usr/bin/env bash
# The quick hard-case stability suite (tests/hard_cases/run.sh --quick) on 2 ranks.
#
# usage: bash hard_cases.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail
[[ $# -eq 3 ]] || { echo "usage: $0 MLSHELL SOURCE_DIR WORK_DIR" >&2; exit 2; }
exec bash "$2/tests/hard_cases/run.sh" "$1" "$3" --quick 2
