#!/usr/bin/env bash
# Runs every command of the README's "A five-minute tour", in order, from a scratch folder laid
# out like the repository's root (build/mlshell, examples/, petsc-options/), and checks that each
# exits 0 and leaves what the README says it leaves. A tour command that breaks fails this test.
#
# usage: bash readme_tour.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/../cli/lib/common.bash" "$@"
export OMPI_MCA_rmaps_base_oversubscribe=1

mkdir build
ln -s "$MLSHELL" build/mlshell
ln -s "$SRC/examples" examples
ln -s "$SRC/petsc-options" petsc-options

# The tour: the first ```sh block after the heading, without comments.
"$PY" - "$SRC/README.md" >tour.sh <<'PYEOF'
import re, sys
text = open(sys.argv[1]).read()
start = text.index("## A five-minute tour")
block = re.search(r"```sh\n(.*?)```", text[start:], re.S).group(1)
lines = [l for l in block.splitlines() if l.strip() and not l.lstrip().startswith("#")]
print("\n".join(lines))
PYEOF
[[ $(wc -l <tour.sh) -ge 5 ]] || die "the README's tour has fewer than 5 commands: $(cat tour.sh)"

n=0
while IFS= read -r command; do
  n=$((n + 1))
  echo "check: tour command $n exits 0: $command"
  rc=0
  timeout 600 bash -c "$command" >"tour_$n.out" 2>&1 </dev/null || rc=$?
  [[ $rc -eq 0 ]] || { tail -n 30 "tour_$n.out"; die "tour command $n exited $rc: $command"; }
done <tour.sh

echo "check: the runs the tour promises are complete, and the picture exists"
for run in out/trampoline out/my_drape out/progressive_plate; do
  grep -q '"status": "complete"' "$run/summary.json" || die "$run/summary.json is not complete"
done
[[ -s out/trampoline/final.png ]] || die "the tour's picture out/trampoline/final.png is missing"
grep -q "V-cycles\|iterations" tour_*.out || die "no solver output in the tour's runs"
echo "PASS: $n tour commands"
