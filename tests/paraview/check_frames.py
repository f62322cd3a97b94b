"""Reads an mlshell frame series with ParaView's own XDMF readers and checks what a user will see.

  xvfb-run -a pvpython tests/paraview/check_frames.py out/sheet/sheet.xdmf --steps 2 \
      --quads 6 4 --samples 3                      # a subdivision sheet of 6 x 4 elements
  xvfb-run -a pvpython tests/paraview/check_frames.py out/plate_buckling/plate_buckling.xdmf \
      --steps 2 --triangles 16 16                  # a structured 16 x 16 triangle rectangle
  ... --png out/sheet/final.png                    # also: the rendered picture is not blank

The sheet is a rectangle of nx x ny elements. A subdivision frame samples each element on a k x k
grid of quads (k = samples per face edge); merged at shared edges that is (k nx + 1)(k ny + 1)
points, k^2 nx ny quads and 2k(nx + ny) boundary edges. A triangle frame is the mesh itself:
(nx + 1)(ny + 1) points, 2 nx ny triangles, 2(nx + ny) boundary edges, and the per-face fields
membrane_strain and bending_energy. Checked for each reader (XDMF Reader, and the Xdmf3 reader
that OpenDataFile and the GUI pick), at every time step:
  - steps + 1 time steps (step 0 is the rest state);
  - point and cell counts, cell types, and the counts the XDMF says its HDF5 datasets hold;
  - a `displacement` point field of 3 components (and the triangle cell fields);
  - geometry - displacement is the same reference surface in every frame and equals frame 0's
    geometry, and the last frame has moved: the geometry is the deformed surface;
  - watertight: Clean (merging points closer than 1e-9 of the diagonal) keeps every point, and
    FeatureEdges finds exactly the sheet's outline as boundary edges and no non-manifold edge.
Prints one line per check and exits 1 if any fails."""
import argparse
import re
import sys

import numpy as np
from paraview import servermanager as sm
from paraview import simple as pv
from paraview.vtk.util.numpy_support import vtk_to_numpy

failures = []


def check(ok, what):
    print(f"{'ok  ' if ok else 'FAIL'} {what}")
    if not ok:
        failures.append(what)


def xdmf_dimensions(path):
    """(points, cells) of each grid as the XDMF declares its HDF5 datasets."""
    text = open(path).read()
    points = [int(n) for n in re.findall(r'Dimensions="(\d+) 3"[^>]*>[^<]*:/geometry<', text)]
    cells = [int(n) for n in re.findall(r'Dimensions="(\d+) [34]"[^>]*>[^<]*:/topology<', text)]
    return points, cells


def fetch(source, t):
    source.UpdatePipeline(t)
    return sm.Fetch(source)


def check_reader(name, reader, a, expect):
    times = list(reader.TimestepValues or [])
    check(len(times) == a.steps + 1, f"{name}: {len(times)} time steps, expected {a.steps + 1}")
    if not times:
        return
    surface = pv.ExtractSurface(Input=reader)
    clean = pv.Clean(Input=surface, PointMerging=1, Tolerance=1e-9, ToleranceIsAbsolute=0)
    edges = pv.FeatureEdges(Input=surface, BoundaryEdges=1, FeatureEdges=0, NonManifoldEdges=0,
                            ManifoldEdges=0)
    nonmanifold = pv.FeatureEdges(Input=surface, BoundaryEdges=0, FeatureEdges=0,
                                  NonManifoldEdges=1, ManifoldEdges=0)
    reference0, moved = None, 0.0
    for i, t in enumerate(times):
        at = f"{name} t={t:g}"
        grid = fetch(reader, t)
        npts, ncells = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
        check(npts == expect["points"], f"{at}: {npts} points, expected {expect['points']}")
        check(ncells == expect["cells"], f"{at}: {ncells} cells, expected {expect['cells']}")
        types = {grid.GetCellType(c) for c in range(ncells)}
        check(types == {expect["cell_type"]}, f"{at}: VTK cell types {sorted(types)}, "
              f"expected {{{expect['cell_type']}}}")
        u = grid.GetPointData().GetArray("displacement")
        check(u is not None and u.GetNumberOfComponents() == 3 and u.GetNumberOfTuples() == npts,
              f"{at}: point field displacement with 3 components")
        for field in expect["cell_fields"]:
            f = grid.GetCellData().GetArray(field)
            check(f is not None and f.GetNumberOfComponents() == 1
                  and f.GetNumberOfTuples() == ncells, f"{at}: cell field {field} with 1 component")
        if u is None or u.GetNumberOfComponents() != 3:
            continue
        x = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
        reference = x - vtk_to_numpy(u)
        scale = np.ptp(x, axis=0).max()
        if i == 0:
            reference0 = x
            d = np.abs(reference - x).max()
            check(d <= 1e-12 * scale, f"{at}: step 0 is the rest state (|displacement| <= {d:.1e})")
        else:
            d = np.abs(reference - reference0).max()
            check(d <= 1e-9 * scale, f"{at}: geometry - displacement = frame 0's geometry "
                  f"(max difference {d:.1e} m)")
            moved = np.abs(x - reference0).max()
        merged = fetch(clean, t).GetNumberOfPoints()
        check(merged == npts, f"{at}: Clean merges coincident points: {npts} -> {merged} "
              "(watertight: unchanged)")
        nb = fetch(edges, t).GetNumberOfCells()
        check(nb == expect["boundary"], f"{at}: {nb} boundary edges, expected the outline's "
              f"{expect['boundary']}")
        nn = fetch(nonmanifold, t).GetNumberOfCells()
        check(nn == 0, f"{at}: {nn} non-manifold edges")
    check(moved > 0, f"{name}: the last frame moved from the rest state ({moved:.3g} m in one "
          "coordinate)")
    for s in (nonmanifold, edges, clean, surface):
        pv.Delete(s)


def check_png(path):
    from paraview.vtk.vtkIOImage import vtkPNGReader

    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    image = r.GetOutput()
    w, h, _ = image.GetDimensions()
    check(w * h > 0, f"{path}: {w} x {h} pixels")
    if w * h == 0:
        return
    rgb = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].astype(int)
    background = np.median(rgb[np.r_[0:w, -w:0]], axis=0)  # the top and bottom rows
    drawn = np.mean(np.abs(rgb - background).sum(axis=1) > 30)
    colours = len(np.unique(rgb // 8, axis=0))
    check(drawn > 0.05 and colours > 50, f"{path}: not blank ({drawn:.0%} of the pixels differ "
          f"from the background, {colours} colours)")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("xdmf")
    p.add_argument("--steps", type=int, required=True, help="time steps the run took")
    shape = p.add_mutually_exclusive_group(required=True)
    shape.add_argument("--quads", type=int, nargs=2, metavar=("NX", "NY"),
                       help="a subdivision rectangle of NX x NY elements (finest level)")
    shape.add_argument("--triangles", type=int, nargs=2, metavar=("NX", "NY"),
                       help="a structured triangle rectangle of NX x NY squares")
    p.add_argument("--samples", type=int, default=1, help="samples per face edge (subdivision)")
    p.add_argument("--png", help="a rendered picture that must not be blank")
    a = p.parse_args()
    if a.quads:
        (nx, ny), k = a.quads, a.samples
        expect = {"points": (k * nx + 1) * (k * ny + 1), "cells": k * k * nx * ny, "cell_type": 9,
                  "boundary": 2 * k * (nx + ny), "cell_fields": []}
    else:
        nx, ny = a.triangles
        expect = {"points": (nx + 1) * (ny + 1), "cells": 2 * nx * ny, "cell_type": 5,
                  "boundary": 2 * (nx + ny), "cell_fields": ["membrane_strain", "bending_energy"]}
    points, cells = xdmf_dimensions(a.xdmf)
    check(len(points) == a.steps + 1 and set(points) == {expect["points"]},
          f"{a.xdmf}: HDF5 geometry datasets of {sorted(set(points))} points in {len(points)} "
          f"grids, expected {expect['points']} in {a.steps + 1}")
    check(set(cells) == {expect["cells"]},
          f"{a.xdmf}: HDF5 topology datasets of {sorted(set(cells))} cells, "
          f"expected {expect['cells']}")
    check_reader("XDMF Reader", pv.XDMFReader(FileNames=[a.xdmf]), a, expect)
    opened = pv.OpenDataFile(a.xdmf)
    check_reader(f"OpenDataFile ({opened.GetXMLName()})", opened, a, expect)
    if a.png:
        check_png(a.png)
    print(f"check_frames: {len(failures)} check(s) failed" if failures else "check_frames: all ok")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
