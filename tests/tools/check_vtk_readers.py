#!/usr/bin/python3
"""Opens a run's model.pvd with VTK's own XML readers (what ParaView uses) and checks it.

usage: check_vtk_readers.py RUN_DIR EXPECTED_BLOCKS EXPECTED_STEPS

model.pvd lists, per snapshot time, one file per part: 0 blocks, 1 contacts, and in coupled runs
2 far field, 3 ties (app/run/run_outputs.cc). Checks that every file reads with
vtkXMLUnstructuredGridReader; that there are EXPECTED_STEPS snapshot times; that every blocks
file has EXPECTED_BLOCKS polygon cells with finite cell arrays displacement, velocity, stress and
von_mises; that contacts (and ties) carry finite state, gap and slip; that far-field files have
cells and finite point arrays displacement and sxx, syy, sxy; and that the time stored in each
file matches the PVD. Needs python3-vtk9 (scripts/setup.sh installs it).
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

try:
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
except ImportError:
    sys.exit("FAIL: VTK's Python modules are missing: install python3-paraview (scripts/setup.sh)")

import numpy as np

# Part number in model.pvd -> (name, cell arrays, point arrays) every file of the part has.
PARTS = {
    0: ("blocks", ("block_id", "displacement", "velocity", "stress", "von_mises"), ()),
    1: ("contacts", ("state", "gap", "slip", "normal_force", "shear_force"), ()),
    2: ("far field", (), ("displacement", "velocity", "sxx", "syy", "sxy")),
    3: ("ties", ("state", "gap", "slip"), ()),
}
VTK_POLYGON = 7


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def read(path):
    if not os.path.isfile(path):
        fail(f"{path} does not exist")
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if reader.GetErrorCode() != 0 or grid is None:
        fail(f"VTK cannot read {path}")
    return grid


def check_arrays(grid, names, data, where, path):
    for name in names:
        array = data.GetArray(name)
        if array is None:
            fail(f"{path}: no {where} array {name!r}")
        values = vtk_to_numpy(array)
        if len(values) != (grid.GetNumberOfCells() if where == "cell" else
                           grid.GetNumberOfPoints()):
            fail(f"{path}: {where} array {name!r} has {len(values)} tuples")
        if not np.all(np.isfinite(values)):
            fail(f"{path}: {where} array {name!r} is not finite")


def main():
    run_dir, expected_blocks, expected_steps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    pvd = ET.parse(os.path.join(run_dir, "model.pvd")).getroot()
    entries = pvd.findall("./Collection/DataSet")
    times = sorted({float(e.get("timestep")) for e in entries})
    if len(times) != expected_steps:
        fail(f"model.pvd has {len(times)} time steps, expected {expected_steps}")
    counts = {}
    for entry in entries:
        part = int(entry.get("part"))
        if part not in PARTS:
            fail(f"model.pvd: unknown part {part}")
        name, cell_arrays, point_arrays = PARTS[part]
        path = os.path.join(run_dir, entry.get("file"))
        grid = read(path)
        counts[name] = counts.get(name, 0) + 1
        if part == 0:
            if grid.GetNumberOfCells() != expected_blocks:
                fail(f"{path}: {grid.GetNumberOfCells()} cells, expected {expected_blocks} blocks")
            if any(grid.GetCellType(k) != VTK_POLYGON for k in range(grid.GetNumberOfCells())):
                fail(f"{path}: a block cell is not a polygon")
        if part == 2 and grid.GetNumberOfCells() == 0:
            fail(f"{path}: the far field has no cells")
        check_arrays(grid, cell_arrays, grid.GetCellData(), "cell", path)
        check_arrays(grid, point_arrays, grid.GetPointData(), "point", path)
        if grid.GetNumberOfPoints() and not np.all(np.isfinite(vtk_to_numpy(
                grid.GetPoints().GetData()))):
            fail(f"{path}: point coordinates are not finite")
        stored = grid.GetFieldData().GetArray("TimeValue")
        if stored is not None and not math.isclose(stored.GetValue(0),
                                                   float(entry.get("timestep")),
                                                   rel_tol=1e-9, abs_tol=1e-12):
            fail(f"{path}: TimeValue {stored.GetValue(0)}, model.pvd says {entry.get('timestep')}")
    for name, n in counts.items():
        if n != len(times):
            fail(f"{name}: {n} files for {len(times)} time steps")
    if "blocks" not in counts:
        fail("model.pvd has no blocks part")
    print(f"ok: {run_dir}: {len(times)} time steps of {', '.join(sorted(counts))}, read by VTK")


if __name__ == "__main__":
    main()
