#!/usr/bin/python3
"""Renders the last (or a given) OBJ frame of an mlshell run to a PNG: the deformed surface (limit
surface quads or triangles) shaded, seen from above at an angle; --zscale exaggerates z (the
out-of-plane wrinkles of a stiff plate), --elev/--azim turn the view.

  /usr/bin/python3 examples/render_frame.py out/drape                 -> out/drape/final.png
  /usr/bin/python3 examples/render_frame.py out/drape --frame 5 --out drape5.png
  /usr/bin/python3 examples/render_frame.py out/plate_buckling --zscale 20"""
import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def read_obj(path):
    v, f = [], []
    for line in open(path):
        if line.startswith("v "):
            v.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            f.append([int(x.split("/")[0]) - 1 for x in line.split()[1:]])
    if not v or not f:
        sys.exit(f"render_frame: {path} has no vertices or faces")
    return np.array(v), f


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("folder", help="an mlshell output folder with frame_*.obj")
    p.add_argument("--frame", type=int, help="frame number (default: the last)")
    p.add_argument("--out", help="PNG path (default FOLDER/final.png)")
    p.add_argument("--title", help="title (default: the OBJ's header line)")
    p.add_argument("--zscale", type=float, default=1.0, help="exaggerate z by this factor")
    p.add_argument("--elev", type=float, default=28.0, help="view elevation (degrees)")
    p.add_argument("--azim", type=float, default=-60.0, help="view azimuth (degrees)")
    a = p.parse_args()
    if not a.zscale > 0:
        sys.exit(f"render_frame: --zscale must be > 0, got {a.zscale}")
    folder = Path(a.folder)
    frames = sorted(folder.glob("frame_*.obj"))
    if not frames:
        sys.exit(f"render_frame: no frame_*.obj in {folder} (does the scene's output list obj?)")
    path = folder / f"frame_{a.frame:06d}.obj" if a.frame is not None else frames[-1]
    if not path.is_file():
        sys.exit(f"render_frame: no {path}")
    x, faces = read_obj(path)
    x[:, 2] *= a.zscale
    header = open(path).readline().lstrip("# ").strip()
    if a.zscale != 1.0:
        header += f" (z x{a.zscale:g})"
    quads = [x[f] for f in faces]
    # Lambert shading from the light direction, two-sided.
    light = np.array([0.3, -0.5, 0.8])
    light /= np.linalg.norm(light)
    shade = []
    for q in quads:
        n = np.cross(q[2] - q[0], q[3] - q[1]) if len(q) == 4 else np.cross(q[1] - q[0], q[2] - q[0])
        norm = np.linalg.norm(n)
        shade.append(abs(n @ light) / norm if norm > 0 else 0.0)
    colors = plt.cm.Blues(0.35 + 0.6 * np.array(shade))
    fig = plt.figure(figsize=(6.4, 5.2))
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(quads, facecolors=colors, edgecolors="none"))
    lo, hi = x.min(axis=0), x.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2
    for k, setter in enumerate((ax.set_xlim, ax.set_ylim, ax.set_zlim)):
        setter(centre[k] - half, centre[k] + half)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=a.elev, azim=a.azim)
    ax.set(xlabel="x [m]", ylabel="y [m]", zlabel="z [m]")
    ax.set_title(a.title or header, fontsize=10)
    out = Path(a.out) if a.out else folder / "final.png"
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print(f"render_frame: wrote {out}")


if __name__ == "__main__":
    main()
