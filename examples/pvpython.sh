#!/usr/bin/env bash
# pvpython on a virtual X server (xvfb-run), without an MPI singleton (--no-mpi), retried when
# ParaView's render window cannot connect to the fresh server: on a loaded machine 1 start in 3
# aborts with "bad X server connection" while the same command then succeeds.
#
#   bash examples/pvpython.sh examples/render.py out/drape
set -uo pipefail
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for try in 1 2 3 4 5; do
  xvfb-run -a pvpython --no-mpi "$@" > "$log" 2>&1
  status=$?
  grep -q "bad X server connection" "$log" || break
  echo "pvpython.sh: no X server connection (try $try of 5); again" >&2
  sleep 1
done
cat "$log"
exit $status
