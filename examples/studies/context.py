"""What every study gets: the runner, the mode, the output folder and a CSV writer."""
import csv
from pathlib import Path

from runner import SOURCE, Runner


class Context:
    def __init__(self, runner: Runner, mode: str, out: Path, scenes=None):
        self.runner = runner
        self.selected_scenes = scenes  # None: every scene a study defines
        self.mode = mode  # "quick" or "full"
        self.out = Path(out)
        self.source = SOURCE
        self._memo = {}

    def pick(self, quick, full):
        return quick if self.mode == "quick" else full

    def scenes(self, quick, full):
        """The scenes of this mode, less those --scenes leaves out."""
        chosen = self.pick(quick, full)
        return [s for s in chosen if self.selected_scenes is None or s in self.selected_scenes]

    def run(self, study, tag, scene, refine, options=(), **kwargs):
        """Runner.run, remembered: an identical solve asked for by two studies runs once."""
        key = (scene, refine, tuple(map(str, options)),
               tuple(sorted((k, str(v)) for k, v in kwargs.items())))
        if key not in self._memo:
            self._memo[key] = self.runner.run(study, tag, scene, refine, options, **kwargs)
        return self._memo[key]

    def write_csv(self, name, rows, columns):
        """Writes OUT/<name>.csv (header `columns`), atomically; returns its path. Rows an
        earlier invocation wrote for other scenes are kept (--scenes runs fill one table)."""
        path = self.out / f"{name}.csv"
        if path.is_file():
            old = read_csv(path)
            mine = {r["scene"] for r in rows}
            if old and list(old[0]) == columns:
                rows = [r for r in old if r["scene"] not in mine] + list(rows)
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
