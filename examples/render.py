"""Renders one frame of an mlshell result folder with ParaView: the deformed surface (the XDMF
series' geometry) coloured by the displacement magnitude, smooth-shaded, seen from above at an
angle, with a colour bar, and the colliders of a contact scene (colliders.obj, or the frame's
colliders_NNNNNN.obj when they move) in grey; --zscale exaggerates z (the out-of-plane wrinkles
of a stiff plate),
--elev/--azim turn the view.

  xvfb-run -a pvpython examples/render.py out/drape                  -> out/drape/final.png
  xvfb-run -a pvpython examples/render.py out/drape --frame 5 --out drape5.png
  xvfb-run -a pvpython examples/render.py out/plate_buckling --zscale 20
  xvfb-run -a pvpython examples/render.py out/drape --size 1200 500 --no-title --out banner.png
  xvfb-run -a pvpython examples/render.py out/plate_buckling --series plate_buckling_level0

--frame is a step number (default: the last frame written). Units of the colour bar: m when the
largest displacement reaches 0.1 m, else mm (--units to choose)."""
import argparse
import math
import re
import sys
from pathlib import Path

import numpy as np
from paraview import servermanager as sm
from paraview import simple as pv
from paraview.vtk.util.numpy_support import vtk_to_numpy


def frames_of(xdmf):
    """{step: time} of the grids the XDMF lists (mlshell names them step_NNNNNN)."""
    grids = re.findall(r'Name="step_(\d+)"[^>]*>\s*<Time Value="([^"]+)"', xdmf.read_text())
    return {int(step): float(t) for step, t in grids}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("folder", help="an mlshell output folder with one *.xdmf series")
    p.add_argument("--series", help="the series' name when the folder has several (a "
                   "progressive run's <scene>_level<l>)")
    p.add_argument("--frame", type=int, help="step number (default: the last frame)")
    p.add_argument("--out", help="PNG path (default FOLDER/final.png)")
    p.add_argument("--size", type=int, nargs=2, default=(800, 600), metavar=("W", "H"))
    p.add_argument("--zscale", type=float, default=1.0, help="exaggerate z by this factor")
    p.add_argument("--elev", type=float, default=30.0, help="view elevation (degrees)")
    p.add_argument("--azim", type=float, default=-60.0, help="view azimuth from +x (degrees)")
    p.add_argument("--zoom", type=float, default=1.0, help="zoom in (> 1) or out after fitting")
    p.add_argument("--units", choices=("m", "mm"), help="colour bar units (default: by size)")
    p.add_argument("--title", help="caption (default: scene, step and time)")
    p.add_argument("--no-title", action="store_true", help="no caption")
    a = p.parse_args()
    if not a.zscale > 0:
        sys.exit(f"render: --zscale must be > 0, got {a.zscale}")
    folder = Path(a.folder)
    series = sorted(folder.glob(f"{a.series}.xdmf" if a.series else "*.xdmf"))
    if len(series) != 1:
        sys.exit(f"render: expected one {a.series or '*'}.xdmf in {folder}, found "
                 f"{len(series)} (does the scene's output list xdmf? several series: --series)")
    frames = frames_of(series[0])
    if not frames:
        sys.exit(f"render: {series[0]} lists no frames")
    step = max(frames) if a.frame is None else a.frame
    if step not in frames:
        sys.exit(f"render: no step {step} in {series[0]}; it has steps {sorted(frames)}")
    t = frames[step]

    reader = pv.OpenDataFile(str(series[0]))
    reader.UpdatePipeline(t)
    umax = reader.PointData["displacement"].GetRange(-1)[1]
    units = a.units or ("m" if umax >= 0.1 else "mm")
    factor = 1.0 if units == "m" else 1000.0
    # The magnitude before the z exaggeration, which would stretch the vectors too.
    magnitude = pv.Calculator(Input=reader, ResultArrayName="u",
                              Function=f"mag(displacement)*{factor}")
    shape = pv.Transform(Input=magnitude)
    shape.Transform.Scale = [1.0, 1.0, a.zscale]
    surface = pv.GenerateSurfaceNormals(Input=pv.ExtractSurface(Input=shape), Splitting=0)

    view = pv.CreateRenderView()
    view.ViewSize = list(a.size)
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    view.ViewTime = t
    shown = pv.Show(surface, view)
    pv.ColorBy(shown, ("POINTS", "u"))
    lut = pv.GetColorTransferFunction("u")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    lut.RescaleTransferFunction(0.0, max(umax * factor, 1e-30))
    shown.Specular, shown.SpecularPower = 0.25, 40.0
    # Contact scenes write their colliders (grey, beside the shell): once, or with every frame
    # when they move.
    colliders = folder / f"colliders_{step:06d}.obj"
    if not colliders.exists():
        colliders = folder / "colliders.obj"
    if colliders.exists():
        obstacle = pv.Transform(Input=pv.OpenDataFile(str(colliders)))
        obstacle.Transform.Scale = [1.0, 1.0, a.zscale]
        solid = pv.Show(obstacle, view)
        solid.ColorArrayName = ['POINTS', '']
        solid.AmbientColor = solid.DiffuseColor = [0.72, 0.72, 0.74]
    bar = pv.GetScalarBar(lut, view)
    bar.Title, bar.ComponentTitle = f"displacement magnitude [{units}]", ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.TitleFontSize, bar.LabelFontSize = 16, 14
    bar.RangeLabelFormat = "%-#.3g"
    bar.WindowLocation = "Any Location"
    bar.Position, bar.ScalarBarLength = [0.88, 0.12], 0.6
    bar.Visibility = 1
    if not a.no_title:
        caption = a.title or f"{series[0].stem}: step {step}, t = {t:g} s"
        if a.zscale != 1.0:
            caption += f" (z x{a.zscale:g})"
        text = pv.Text(Text=caption)
        label = pv.Show(text, view)
        label.Color, label.FontSize, label.WindowLocation = [0.1, 0.1, 0.1], 16, "Upper Center"

    # From above at an angle: elevation over the xy plane, azimuth from +x, z up.
    (x0, x1, y0, y1, z0, z1) = surface.GetDataInformation().GetBounds()
    centre = [(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2]
    el, az = math.radians(a.elev), math.radians(a.azim)
    direction = [math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)]
    camera = view.GetActiveCamera()
    camera.SetFocalPoint(centre)
    camera.SetPosition([c + d for c, d in zip(centre, direction)])
    camera.SetViewUp([0.0, 0.0, 1.0] if abs(a.elev) < 89 else [0.0, 1.0, 0.0])
    view.ResetCamera(False)
    # Zoom until the surface's points fill the picture left of the colour bar.
    m = camera.GetCompositeProjectionTransformMatrix(a.size[0] / a.size[1], -1, 1)
    m = np.array([[m.GetElement(i, j) for j in range(4)] for i in range(4)])
    x = vtk_to_numpy(sm.Fetch(surface).GetPoints().GetData())
    h = np.c_[x, np.ones(len(x))] @ m.T
    extent = np.abs(h[:, :2] / h[:, 3:]).max(axis=0)
    camera.Zoom(a.zoom * min(0.74 / extent[0], (0.92 if a.no_title else 0.84) / extent[1]))

    out = Path(a.out) if a.out else folder / "final.png"
    out.parent.mkdir(parents=True, exist_ok=True)
    pv.SaveScreenshot(str(out), view, ImageResolution=list(a.size))
    print(f"render: wrote {out} (step {step}, t = {t:g} s, max |displacement| {umax:.3g} m)")


if __name__ == "__main__":
    main()
