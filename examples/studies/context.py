"""What every study gets: the runner, the mode, the output folder and a CSV writer."""
import csv
from pathlib import Path

from runner import PROVENANCE, SOURCE, Runner


class Context:
    def __init__(self, runner: Runner, mode: str, out: Path, scenes=None, solvers=None,
                 max_dofs=None):
        self.runner = runner
        self.selected_scenes = scenes  # None: every scene a study defines
        self.selected_solvers = solvers  # None: every solver a study compares
        self.mode = mode  # "quick" or "full"
        self.max_dofs = max_dofs  # None: every resolution (studies whose scenes have no refine)
        self.out = Path(out)
        self.source = SOURCE
        self._memo = {}

    def pick(self, quick, full):
        return quick if self.mode == "quick" else full

    def scenes(self, quick, full):
        """The scenes of this mode, less those --scenes leaves out."""
        chosen = self.pick(quick, full)
        return [s for s in chosen if self.selected_scenes is None or s in self.selected_scenes]

    def solvers(self, chosen):
        """The solvers of a study, less those --solvers leaves out."""
        return [s for s in chosen if self.selected_solvers is None or s in self.selected_solvers]

    def run(self, study, tag, scene, refine, options=(), **kwargs):
        """Runner.run, remembered: an identical solve asked for by two studies runs once."""
        key = (scene, refine, tuple(map(str, options)),
               tuple(sorted((k, str(v)) for k, v in kwargs.items())))
        if key not in self._memo:
            self._memo[key] = self.runner.run(study, tag, scene, refine, options, **kwargs)
        return self._memo[key]

    def write_csv(self, name, rows, columns, key=("scene",)):
        """Writes OUT/<name>.csv (header `columns`, then PROVENANCE), atomically; returns its
        path. Rows an earlier invocation wrote for other values of `key` (scenes; for some
        studies scene and solver) are kept, so that --scenes and --solvers runs fill one table."""
        path = self.out / f"{name}.csv"
        columns = list(columns) + ([] if PROVENANCE in columns else [PROVENANCE])
        if path.is_file():
            old = read_csv(path)
            mine = {tuple(str(r[k]) for k in key) for r in rows}
            # Rows written before the build column existed keep it empty: "not recorded".
            if old and [c for c in old[0] if c != PROVENANCE] == columns[:-1]:
                rows = [r for r in old if tuple(r[k] for k in key) not in mine] + list(rows)
        tmp = path.with_suffix(".csv.tmp")
        with open(tmp, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
            w.writeheader()
            for r in rows:
                w.writerow({c: _cell(r.get(c, "")) for c in columns})
        tmp.replace(path)
        print(f"  wrote {path} ({len(rows)} rows)", flush=True)
        return path


def _cell(v):
    if isinstance(v, float):
        return f"{v:.6g}"
    return v


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(v, default=None):
    """A CSV cell as a float (None, or `default`, when empty or not a number)."""
    try:
        return float(v)
    except (TypeError, ValueError):
        return default
