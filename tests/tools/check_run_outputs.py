#!/usr/bin/python3
"""Checks the outputs of one `ddafem run`: summary.json, histories.h5, blocks.pvd + .vtu, and
that tools/plot_histories.py turns the histories into PNGs.

usage: check_run_outputs.py RUN_DIR EXPECTED_STATUS SOURCE_DIR
"""
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main():
    run_dir, expected_status, source_dir = sys.argv[1:4]
    with open(os.path.join(run_dir, "summary.json")) as f:
        summary = json.load(f)
    if summary["status"] != expected_status:
        fail(f"status {summary['status']!r}, expected {expected_status!r}")
    for key in ("scene", "version", "steps", "wall_time_s", "dt_s", "solver", "warnings"):
        if key not in summary:
            fail(f"summary.json lacks {key!r}")
    # DDA runs write blocks.pvd (one polygon per block); far-field runs far_field.pvd (cells).
    pvd_name = summary["outputs"].get("blocks") or summary["outputs"]["far_field"]
    n_cells = summary["model"]["blocks"] or summary["model"]["far_field_cells"]

    with h5py.File(os.path.join(run_dir, "histories.h5"), "r") as h5:
        time = h5["time"][:]
        # A run that fails before its first step (a static stage) has one row.
        if len(time) < (1 if expected_status != "completed" else 2) or np.any(np.diff(time) <= 0):
            fail("time is not increasing")
        if abs(time[-1] - summary["time_reached_s"]) > 1e-9:
            fail(f"last history time {time[-1]} != time reached {summary['time_reached_s']}")
        for name in h5["monitors"]:
            stress = h5[f"monitors/{name}/stress"]
            if stress.shape != (len(time), 3) or stress.attrs["unit"] not in ("Pa", b"Pa"):
                fail(f"monitor {name}: stress shape {stress.shape} or unit wrong")
        for name in ("kinetic", "strain", "dissipated"):
            if h5[f"energy/{name}"].shape != (len(time),):
                fail(f"energy/{name} has the wrong shape")

    pvd = ET.parse(os.path.join(run_dir, pvd_name)).getroot()
    datasets = pvd.findall("./Collection/DataSet")
    if len(datasets) != summary["outputs"]["snapshots"]:
        fail(f"{len(datasets)} PVD entries, summary says {summary['outputs']['snapshots']}")
    times = [float(d.get("timestep")) for d in datasets]
    if times != sorted(times):
        fail("PVD times are not increasing")
    last = ET.parse(os.path.join(run_dir, datasets[-1].get("file"))).getroot()
    piece = last.find("./UnstructuredGrid/Piece")
    if summary["model"]["blocks"] and int(piece.get("NumberOfCells")) != n_cells:
        fail(f"last VTU has {piece.get('NumberOfCells')} cells, expected {n_cells}")
    if not summary["model"]["blocks"] and int(piece.get("NumberOfCells")) < n_cells:
        # DataOut writes each cell as degree^2 patches.
        fail(f"last VTU has {piece.get('NumberOfCells')} cells, expected at least {n_cells}")

    if "contacts" in summary["outputs"]:
        contacts = ET.parse(os.path.join(run_dir, summary["outputs"]["contacts"])).getroot()
        entries = contacts.findall("./Collection/DataSet")
        if len(entries) != len(datasets):
            fail(f"{len(entries)} contact snapshots, {len(datasets)} block snapshots")
        piece = ET.parse(os.path.join(run_dir, entries[-1].get("file"))).getroot().find(
            "./UnstructuredGrid/Piece")
        names = {a.get("Name") for a in piece.findall("./CellData/DataArray")}
        for name in ("state", "normal_force", "shear_force", "gap", "slip", "normal"):
            if name not in names:
                fail(f"contact VTU lacks {name!r}")

    if "model" in summary["outputs"]:
        # One PVD for the whole model: every snapshot time lists each part (blocks, contacts,
        # and for coupled runs far field and ties) once, and every file exists.
        model = ET.parse(os.path.join(run_dir, summary["outputs"]["model"])).getroot()
        entries = model.findall("./Collection/DataSet")
        n_parts = 4 if "far_field" in summary["outputs"] else 2
        if len(entries) != n_parts * len(datasets):
            fail(f"model.pvd has {len(entries)} entries, expected {n_parts} x {len(datasets)}")
        for k, entry in enumerate(entries):
            if int(entry.get("part")) != k % n_parts:
                fail(f"model.pvd entry {k} has part {entry.get('part')}")
            if abs(float(entry.get("timestep")) - times[k // n_parts]) > 1e-9:
                fail(f"model.pvd entry {k} has time {entry.get('timestep')}")
            if not os.path.exists(os.path.join(run_dir, entry.get("file"))):
                fail(f"model.pvd names {entry.get('file')}, which does not exist")

    if expected_status == "completed":
        png = os.path.join(run_dir, "check.png")
        subprocess.run(["/usr/bin/python3", os.path.join(source_dir, "tools/plot_histories.py"),
                        os.path.join(run_dir, "histories.h5"), "-o", png], check=True)
        for p in (png, png.replace(".png", "_energy.png")):
            if not os.path.exists(p) or os.path.getsize(p) < 1000:
                fail(f"plot {p} missing or empty")
    print(f"ok: {run_dir}: {summary['status']}, {len(time)} history rows, {len(datasets)} snapshots")


if __name__ == "__main__":
    main()
