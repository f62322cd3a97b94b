"""Draws the levels of a triangle hierarchy that `-mlshell_hierarchy_write DIR` wrote: the top row
each level's rest mesh (level_<l>.obj), the bottom row its prolongation to the finest level
(level_<l>_to_finest.obj, P^l of that rest mesh on the finest topology), which recovers the
finest rest shape exactly (paper 2 §4.3).

  mlshell examples/triangle/embossed_panel.yaml -mlshell_evaluate -mlshell_hierarchy_write levels
  /usr/bin/python3 examples/render_hierarchy.py levels --out levels.png --zscale 5
"""
import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_obj(path):
    points, triangles = [], []
    for line in path.read_text().splitlines():
        if line.startswith("v "):
            points.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            triangles.append([int(w.split("/")[0]) - 1 for w in line.split()[1:4]])
    return points, triangles


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir", type=Path, help="the folder -mlshell_hierarchy_write wrote")
    parser.add_argument("--out", type=Path, help="PNG to write (default: DIR/levels.png)")
    parser.add_argument("--zscale", type=float, default=1.0, help="exaggerate z by this factor")
    parser.add_argument("--elev", type=float, default=35.0)
    parser.add_argument("--azim", type=float, default=-60.0)
    args = parser.parse_args()
    levels = sorted(int(p.stem.split("_")[1]) for p in args.dir.glob("level_*.obj")
                    if p.stem.count("_") == 1)
    if not levels:
        sys.exit(f"render_hierarchy: no level_<l>.obj in {args.dir}")
    n = len(levels)
    fig = plt.figure(figsize=(4 * n, 7.5))
    for row, suffix in enumerate(["", "_to_finest"]):
        for col, level in enumerate(levels):
            path = args.dir / f"level_{level}{suffix}.obj"
            if not path.exists():
                continue  # the finest level has no prolongation of its own
            points, triangles = read_obj(path)
            ax = fig.add_subplot(2, n, row * n + col + 1, projection="3d")
            x, y, z = zip(*points)
            ax.plot_trisurf(x, y, [args.zscale * v for v in z], triangles=triangles,
                            color="#9fb8d8", edgecolor="#30405a", linewidth=0.15, shade=True)
            ax.view_init(elev=args.elev, azim=args.azim)
            ax.set_box_aspect((max(x) - min(x), max(y) - min(y),
                               max(1e-9, args.zscale * (max(z) - min(z)))))
            ax.set_axis_off()
            title = (f"level {level}: {len(points)} vertices" if not suffix
                     else f"P^{level}: level {level} on the finest mesh")
            ax.set_title(title, fontsize=10)
    if args.zscale != 1.0:
        fig.suptitle(f"z exaggerated {args.zscale:g}x", fontsize=9)
    fig.tight_layout()
    out = args.out or args.dir / "levels.png"
    fig.savefig(out, dpi=110)
    print(f"render_hierarchy: wrote {out}")


if __name__ == "__main__":
    main()
