#!/usr/bin/env bash
# Result files of a 2-step run on 2 ranks with every output format: summary.json, steps.csv,
# the XDMF series and the HDF5 frames it references, the OBJ frames; no temporary files left.
# summary.json and --version name the build (version, source commit, PETSc).
#
# usage: bash outputs.sh MLSHELL SOURCE_DIR WORK_DIR
set -euo pipefail

source "$(dirname "$0")/lib/common.bash" "$@"

cat >outputs.yaml <<'EOF'
name: outputs
geometry:
  cage: {generator: rectangle, size: [1.0, 1.0], faces: [4, 4]}
  refine: 1
material: {model: isotropic-svk, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: 1.0e-3,
           density: 0.4}
effects:
  - inertia
  - gravity
  - clamp: {where: boundary(left)}
time: {dt: 0.05, steps: 2}
probes:
  tip: {at: [1.0, 0.5, 0]}
output: {dir: out/outputs, formats: [xdmf, obj, csv], samples_per_face: 2}
EOF

echo "check: a 2-step run on 2 ranks with formats [xdmf, obj, csv] exits 0"
rc=0
timeout 300 mpiexec --oversubscribe -n 2 "$MLSHELL" outputs.yaml >stdout.txt 2>stderr.txt || rc=$?
[[ $rc -eq 0 ]] || die "exit status $rc, expected 0
--- stdout
$(tail -n 20 stdout.txt)
--- stderr
$(tail -n 20 stderr.txt)"
grep -q "results in" stdout.txt || die "stdout does not say 'results in': $(cat stdout.txt)"

echo "check: --version names mlshell's version, the source commit and PETSc's version"
version_line=$("$MLSHELL" --version) || die "mlshell --version: exit status $?"
[[ $version_line =~ ^mlshell\ [0-9]+\.[0-9]+\.[0-9]+\ \(commit\ [^\)]+\),\ PETSc\ [0-9]+\.[0-9]+\.[0-9]+$ ]] ||
  die "mlshell --version printed '$version_line'"
# In a git checkout the commit is the one the sources are at (a build that did not follow the
# checkout would name an older one); the test runs after the build, so HEAD has not moved.
head_commit=unknown
if git -C "$SRC" rev-parse --git-dir >/dev/null 2>&1; then
  head_commit=$(git -C "$SRC" rev-parse HEAD)
fi

echo "check: summary.json, steps.csv, XDMF + HDF5, OBJ frames; no temporary files"
VERSION_LINE=$version_line HEAD_COMMIT=$head_commit "$PY" - out/outputs <<'EOF'
import csv, json, math, os, re, sys
import xml.etree.ElementTree as ET

out = sys.argv[1]
errors = []
def check(cond, msg):
    if not cond:
        errors.append(msg)
def path(name):
    return os.path.join(out, name)

# summary.json
try:
    with open(path("summary.json"), encoding="utf-8") as f:
        s = json.load(f)
except (OSError, ValueError) as e:
    print(f"FAIL: summary.json: {e}", file=sys.stderr)
    sys.exit(1)
check(s.get("status") == "complete", f"summary.json: status {s.get('status')!r}, expected 'complete'")
check(s.get("ranks") == 2, f"summary.json: ranks {s.get('ranks')}, expected 2")
check(s.get("steps") == 2, f"summary.json: steps {s.get('steps')}, expected 2")
check(s.get("dofs") == 363, f"summary.json: dofs {s.get('dofs')}, expected 363")
solver = s.get("solver", {})
check(solver.get("converged") is True, f"summary.json: solver.converged {solver.get('converged')!r}")
check(isinstance(solver.get("iterations"), int) and solver["iterations"] > 0,
      f"summary.json: solver.iterations {solver.get('iterations')!r}")
energy = s.get("energy", {})
for k in ("elastic", "inertia", "gravity", "clamp", "total"):
    check(isinstance(energy.get(k), float) and math.isfinite(energy[k]), f"summary.json: energy.{k} {energy.get(k)!r}")
tip = s.get("probes", {}).get("tip", {})
check(len(tip.get("displacement", [])) == 3 and tip["displacement"][2] < 0,
      f"summary.json: probe tip displacement {tip.get('displacement')!r} (expected to fall)")
for k in ("gradient_norm", "wall_time", "time"):
    check(isinstance(s.get(k), (int, float)), f"summary.json: {k} {s.get(k)!r}")
# The build that wrote it: the same as --version says, at the checkout's commit.
build = s.get("build", {})
described = f"mlshell {build.get('mlshell')} (commit {build.get('commit')}), PETSc {build.get('petsc')}"
check(described == os.environ["VERSION_LINE"],
      f"summary.json: build {build!r} differs from --version: {os.environ['VERSION_LINE']!r}")
head, commit = os.environ["HEAD_COMMIT"], str(build.get("commit"))
if head == "unknown":
    check(commit == "unknown", f"summary.json: build.commit {commit!r} outside a git checkout")
else:
    hash_part = commit.removesuffix("-modified")
    check(len(hash_part) >= 7 and head.startswith(hash_part),
          f"summary.json: build.commit {commit!r} is not the checkout's HEAD {head}")

# steps.csv: a header and one row per step
with open(path("steps.csv"), newline="", encoding="utf-8") as f:
    rows = list(csv.reader(f))
check(len(rows) == 3, f"steps.csv: {len(rows)} lines, expected a header and 2 rows")
if rows:
    header = rows[0]
    for col in ("step", "time", "energy_total", "iterations", "converged"):
        check(col in header, f"steps.csv: no column {col!r} in {header}")
    for r in rows[1:]:
        check(len(r) == len(header), f"steps.csv: row {r} has {len(r)} fields, header {len(header)}")
    if "step" in header and len(rows) == 3:
        check([r[header.index("step")] for r in rows[1:]] == ["1", "2"], "steps.csv: steps are not 1, 2")
    if "energy_total" in header and len(rows) == 3:
        last = float(rows[2][header.index("energy_total")])
        check(abs(last - energy.get("total", math.nan)) <= 1e-12 * max(1.0, abs(last)),
              f"steps.csv: last energy_total {last} differs from summary.json {energy.get('total')}")

# XDMF: valid XML, a temporal collection of frames 0, 1, 2 whose HDF5 files exist
xdmf = [n for n in os.listdir(out) if n.endswith(".xdmf")]
check(xdmf == ["outputs.xdmf"], f"XDMF files {xdmf}, expected ['outputs.xdmf']")
frames, h5 = [], set()
if "outputs.xdmf" in xdmf:
    try:
        root = ET.parse(path("outputs.xdmf")).getroot()
    except ET.ParseError as e:
        errors.append(f"outputs.xdmf is not valid XML: {e}")
        root = None
    if root is not None:
        collection = root.find("./Domain/Grid")
        check(collection is not None and collection.get("CollectionType") == "Temporal",
              "outputs.xdmf: no temporal collection Domain/Grid")
        for grid in (collection.findall("Grid") if collection is not None else []):
            t = grid.find("Time")
            frames.append(float(t.get("Value")) if t is not None else math.nan)
            for item in grid.iter("DataItem"):
                if item.get("Format") == "HDF":
                    h5.add(item.text.strip().split(":")[0])
        check(len(frames) == 3, f"outputs.xdmf: {len(frames)} frames, expected 3 (steps 0..2)")
        check(all(abs(a - b) < 1e-12 for a, b in zip(frames, [0.0, 0.05, 0.1])),
              f"outputs.xdmf: frame times {frames}, expected [0, 0.05, 0.1]")
check(h5 == {f"outputs_{n:06d}.h5" for n in range(3)}, f"outputs.xdmf references {sorted(h5)}")
for name in sorted(h5):
    p = path(name)
    if not os.path.isfile(p):
        errors.append(f"{name}, referenced by outputs.xdmf, does not exist")
        continue
    with open(p, "rb") as f:
        check(f.read(8) == b"\x89HDF\r\n\x1a\n", f"{name} is not an HDF5 file")

# OBJ frames 0..2 with vertices and faces
for n in range(3):
    name = f"frame_{n:06d}.obj"
    p = path(name)
    if not os.path.isfile(p):
        errors.append(f"{name} does not exist")
        continue
    v = f = 0
    with open(p, encoding="utf-8") as fh:
        for line in fh:
            if line.startswith("v "):
                v += 1
            elif line.startswith("f "):
                f += 1
    check(v > 0 and f > 0, f"{name}: {v} 'v' lines and {f} 'f' lines")
extra = [n for n in os.listdir(out) if re.fullmatch(r"frame_\d+\.obj", n) and n not in
         {f"frame_{k:06d}.obj" for k in range(3)}]
check(not extra, f"unexpected OBJ frames {extra}")

# nothing half-written left behind
for dirpath, _, names in os.walk(out):
    for n in names:
        check(".tmp." not in n and not n.endswith(".tmp"), f"temporary file left: {os.path.join(dirpath, n)}")

if errors:
    for e in errors:
        print("FAIL:", e, file=sys.stderr)
    sys.exit(1)
print(f"  {len(frames)} XDMF frames, {len(h5)} HDF5 files, 3 OBJ frames, {len(rows) - 1} CSV rows")
EOF
echo "outputs: all checks passed"
