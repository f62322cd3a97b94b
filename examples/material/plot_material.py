#!/usr/bin/python3
"""The two denim presets side by side: Table 1 as printed (`denim-table1`) and mlshell's default
(`denim`, the coupling limited by the Cauchy-Schwarz bound of the warp and weft energies).

  /usr/bin/python3 examples/material/plot_material.py [--build build] [--out denim.png]

Runs `mlshell SCENE -mlshell_material_csv` for each preset (the material as mlshell evaluates
it), then draws the uniaxial stress-strain curves (identical for both presets by construction)
and the energy landscape psi(E11, E22) at E12 = 0, with the region where the presets differ
shaded and the negative well of Table 1 outlined."""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

SOURCE = Path(__file__).resolve().parents[2]
SCENE = """geometry: {{cage: {{generator: rectangle}}}}
material: {{model: clyde-orthotropic, preset: {preset}}}
time: {{dt: 1.0, steps: 1}}
"""


def table(mlshell, preset, folder):
    scene = Path(folder) / f"{preset}.yaml"
    scene.write_text(SCENE.format(preset=preset))
    path = Path(folder) / f"{preset}.csv"
    subprocess.run([str(mlshell), str(scene), "-mlshell_material_csv", str(path)], check=True,
                   stdout=subprocess.DEVNULL)
    with open(path) as f:
        return list(csv.DictReader(f))


def curve(rows, kind, stress):
    r = [x for x in rows if x["kind"] == kind]
    strain = {"warp": "e11", "weft": "e22", "shear": "e12"}[kind]
    return (np.array([float(x[strain]) for x in r]), np.array([float(x[stress]) for x in r]),
            np.array([x["beyond_fit"] == "1" for x in r]))


def plane(rows):
    r = [x for x in rows if x["kind"] == "plane"]
    e11 = np.array([float(x["e11"]) for x in r])
    e22 = np.array([float(x["e22"]) for x in r])
    n = int(round(np.sqrt(len(r))))
    shape = (n, n)
    return (e11.reshape(shape), e22.reshape(shape),
            np.array([float(x["psi"]) for x in r]).reshape(shape),
            np.array([x["coupling_limited"] == "1" for x in r]).reshape(shape))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default=str(SOURCE / "build"), help="folder holding mlshell")
    p.add_argument("--out", default=str(SOURCE / "examples" / "material" / "denim.png"))
    a = p.parse_args()
    mlshell = Path(a.build) / "mlshell"
    if not mlshell.is_file():
        sys.exit(f"plot_material: no mlshell at {mlshell} (build first: bash .ci/build)")
    with tempfile.TemporaryDirectory() as folder:
        t1, d = table(mlshell, "denim-table1", folder), table(mlshell, "denim", folder)
    fig = plt.figure(figsize=(14, 4.6))
    ax = fig.add_subplot(1, 3, 1)
    for kind, stress, color in (("warp", "s11", "C0"), ("weft", "s22", "C1"),
                                ("shear", "s12", "C2")):
        e, s, beyond = curve(d, kind, stress)
        ax.plot(e, s / 1e6, color=color, label=kind)
        ax.plot(np.where(beyond, e, np.nan), s / 1e6 * np.where(beyond, 1, np.nan), color=color,
                lw=3, alpha=0.35)
        _, s1, _ = curve(t1, kind, stress)
        assert np.allclose(s, s1, rtol=1e-12, atol=1e-6), f"{kind}: presets differ uniaxially"
    ax.set(xlabel="strain Ẽ (the other components 0)", ylabel="stress ∂ψ/∂Ẽ [MPa]",
           title="Uniaxial responses, identical for both presets\n(thick: the C² continuation "
                 "beyond the fitted range)")
    ax.set_yscale("symlog", linthresh=0.1)
    ax.axhline(0, color="k", lw=0.5)
    ax.legend(fontsize=8)
    for k, (rows, name) in enumerate(((t1, "denim-table1 (Table 1 as printed)"),
                                      (d, "denim (coupling limited, mlshell default)"))):
        ax = fig.add_subplot(1, 3, 2 + k)
        e11, e22, psi, limited = plane(rows)
        levels = np.concatenate([-np.geomspace(2e4, 1e2, 6), [0], np.geomspace(1e2, 1e6, 9)])
        c = ax.contourf(e11, e22, psi, levels=levels, cmap="RdBu_r",
                        norm=matplotlib.colors.SymLogNorm(1e2, vmin=-2e4, vmax=1e6), extend="both")
        ax.contour(e11, e22, psi, levels=[0], colors="k", linewidths=1.5)
        _, _, _, region = plane(d)
        ax.contourf(e11, e22, region.astype(float), levels=[0.5, 1.5], colors="none",
                    hatches=["//"])
        ax.contour(e11, e22, region.astype(float), levels=[0.5], colors="0.3", linewidths=0.8)
        i = np.unravel_index(np.argmin(psi), psi.shape)
        ax.plot(e11[i], e22[i], "k*", ms=9)
        ax.set(xlabel="Ẽ11 (warp)", ylabel="Ẽ22 (weft)", aspect="equal",
               title=f"{name}\nψ(Ẽ11, Ẽ22, 0); min {psi[i] / 1e6:.4f} MPa (star)")
        fig.colorbar(c, ax=ax, label="ψ [Pa]", shrink=0.8)
    fig.text(0.5, 0.01, "Hatched: where the presets differ (the coupling limit acts). Black line: "
             "ψ = 0; Table 1's negative well lies inside it.", ha="center", fontsize=9)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    Path(a.out).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(a.out, dpi=110)
    print(f"plot_material: wrote {a.out}")


if __name__ == "__main__":
    main()
