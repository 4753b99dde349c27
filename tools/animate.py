#!/usr/bin/python3
"""An animation of a run's near field: RUN_DIR/animation.mp4 (with ffmpeg) or .gif (without).

    /usr/bin/python3 tools/animate.py RUN_DIR [--fps 8] [--gif] [--out FILE]

Left, the blocks at each snapshot (RUN_DIR/blocks.pvd), coloured by their displacement relative
to the rock around the opening since the wave's stage began (the keyblocks' measure, summary.json
`keyblocks`: a block's centroid displacement minus the mean of the blocks 0.75 to 1.5 opening
sizes from the opening's centre), with the contacts that slide (orange) and the joints that are
open (grey) as dots, the blocks that fell outlined in red and their ids, bolts as lines if the
run has any (RUN_DIR/bolts.pvd), the lining if it has one (RUN_DIR/lining.pvd: blue, its broken
elements red). Right, the motion at the near field's base (monitor
near_field_base, histories.h5) and the bonded joints left, with a cursor at the frame's time.
Frames are the run's snapshots (output.interval). report.md links the file when it exists.
"""
import argparse
import json
import os
import shutil
import sys
import xml.etree.ElementTree as ET

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import animation  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402


def series(run_dir, name):
    """(time, path) of each VTU file of RUN_DIR/NAME.pvd, in time order; [] if none."""
    path = os.path.join(run_dir, name + ".pvd")
    if not os.path.isfile(path):
        return []
    root = ET.parse(path).getroot()
    items = [(float(d.get("timestep")), os.path.join(run_dir, d.get("file")))
             for d in root.findall("./Collection/DataSet")]
    return sorted(items)


def read_vtu(path):
    """Points (n x 2), cells (lists of point indices) and cell/point arrays of an ASCII VTU."""
    root = ET.parse(path).getroot()
    piece = root.find("./UnstructuredGrid/Piece")

    def numbers(element):
        return np.array(element.text.split(), dtype=float)

    points = numbers(piece.find("./Points/DataArray")).reshape(-1, 3)[:, :2]
    cells_element = piece.find("./Cells")
    arrays = {a.get("Name"): a for a in cells_element.findall("DataArray")}
    connectivity = numbers(arrays["connectivity"]).astype(int)
    offsets = numbers(arrays["offsets"]).astype(int)
    starts = np.concatenate([[0], offsets[:-1]])
    cells = [connectivity[s:e] for s, e in zip(starts, offsets)]
    data = {}
    for group in ("CellData", "PointData"):
        element = piece.find(group)
        for a in ([] if element is None else element.findall("DataArray")):
            values = numbers(a) if a.text and a.text.strip() else np.zeros(0)
            components = int(a.get("NumberOfComponents", "1"))
            data[a.get("Name")] = values.reshape(-1, components) if components > 1 else values
    return points, cells, data


def relative_displacements(frames, opening, start_index):
    """|u - mean u of the ring - the same at the start frame| per block and frame [m] (0 before
    the start frame); blocks matched by block_id, since removed debris leaves the snapshots."""
    centre = 0.5 * (np.array(opening["lower_m"]) + np.array(opening["upper_m"]))
    size = opening["size_m"]
    points0, cells0, data0 = frames[start_index]["vtu"]
    centroids = np.array([points0[c].mean(axis=0) for c in cells0])
    distance = np.linalg.norm(centroids - centre, axis=1)
    ring_ids = set(data0["block_id"][(distance >= 0.75 * size) & (distance <= 1.5 * size)]
                   .astype(int))

    def relative(frame):
        _, _, data = frame["vtu"]
        ids = data["block_id"].astype(int)
        u = data["displacement"][:, :2]
        ring = np.array([i in ring_ids for i in ids])
        return ids, u - (u[ring].mean(axis=0) if ring.any() else 0.0)

    base_ids, base_u = relative(frames[start_index])
    base = dict(zip(base_ids, base_u))
    values = []
    for k, frame in enumerate(frames):
        ids, u = relative(frame)
        if k < start_index:
            values.append(np.zeros(len(ids)))
            continue
        values.append(np.array([np.linalg.norm(ui - base.get(i, ui)) for i, ui in zip(ids, u)]))
    return values


def dynamic_start(frames):
    """Index of the frame the wave's stage starts from: the last snapshot at t = 0 (a static
    stage runs in pseudo time: its snapshots, if any, come before, also at t = 0)."""
    at_zero = [i for i, f in enumerate(frames) if f["time"] <= 1e-12]
    return at_zero[-1] if at_zero else 0


def contact_dots(path):
    """Positions of sliding and of open contacts in a contacts VTU."""
    points, cells, data = read_vtu(path)
    state = data.get("state", np.zeros(0))
    where = np.array([points[c].mean(axis=0) for c in cells]) if cells else np.zeros((0, 2))
    return where[state == 1], where[state == 0]


def load(run_dir):
    summary = json.load(open(os.path.join(run_dir, "summary.json")))
    frames = [{"time": t, "vtu": read_vtu(p)} for t, p in series(run_dir, "blocks")]
    if not frames:
        sys.exit("animate.py: %s has no blocks.pvd: nothing to animate" % run_dir)
    contacts = dict(series(run_dir, "contacts"))
    bolts = dict(series(run_dir, "bolts"))
    linings = dict(series(run_dir, "lining"))
    for frame in frames:
        frame["contacts"] = contacts.get(frame["time"])
        frame["bolts"] = bolts.get(frame["time"])
        frame["lining"] = linings.get(frame["time"])
    with h5py.File(os.path.join(run_dir, "histories.h5"), "r") as h:
        history = {"time": h["time"][:]}
        if "monitors/near_field_base/velocity" in h:
            history["base"] = h["monitors/near_field_base/velocity"][:]
        if "contacts/bonded_joints" in h:
            history["bonded"] = h["contacts/bonded_joints"][:]
    return summary, frames, history


def near_field_box(summary, frames):
    keyblocks = summary.get("keyblocks") or {}
    openings = keyblocks.get("openings") or []
    if openings:
        o = openings[0]
        centre = 0.5 * (np.array(o["lower_m"]) + np.array(o["upper_m"]))
        half = 2.2 * o["size_m"]
        return centre - half, centre + half, o
    points = frames[0]["vtu"][0]
    return points.min(axis=0), points.max(axis=0), None


def draw(run_dir, out, fps, force_gif):
    summary, frames, history = load(run_dir)
    lower, upper, opening = near_field_box(summary, frames)
    start = dynamic_start(frames)
    if opening:
        colours = relative_displacements(frames, opening, start)
    else:
        colours = [np.linalg.norm(f["vtu"][2]["displacement"][:, :2], axis=1) for f in frames]
    cap = max(1e-6, np.percentile(np.concatenate(colours), 99))
    fallen = set()
    for b in (summary.get("keyblocks") or {}).get("blocks", []):
        if b.get("fell"):
            fallen.add(b["id"])

    fig = plt.figure(figsize=(11, 6))
    ax = fig.add_axes([0.04, 0.08, 0.5, 0.84])
    side = [fig.add_axes([0.66, 0.56, 0.32, 0.36]), fig.add_axes([0.66, 0.1, 0.32, 0.36])]
    ax.set_aspect("equal")
    ax.set_xlim(lower[0], upper[0])
    ax.set_ylim(lower[1], upper[1])
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    collection = PolyCollection([], cmap="viridis", edgecolors="0.25", linewidths=0.5)
    collection.set_clim(0.0, 1e3 * cap)
    ax.add_collection(collection)
    bar = fig.colorbar(collection, ax=ax, fraction=0.04, pad=0.02)
    bar.set_label("displacement relative to the rock around the opening [mm]")
    slide = ax.plot([], [], "o", color="C1", ms=3, label="sliding contact")[0]
    opened = ax.plot([], [], "o", color="0.55", ms=2, label="open contact")[0]
    outlines = PolyCollection([], facecolors="none", edgecolors="red", linewidths=1.6)
    ax.add_collection(outlines)
    ax.plot([], [], "-", color="red", label="fell")
    ax.legend(loc="lower left", fontsize=7, framealpha=0.8)
    title = ax.set_title("")
    bolt_lines = []

    time = history["time"]
    cursors = []
    if "base" in history:
        v = history["base"]
        side[0].plot(time, v[:, 0], lw=0.8, label="v_x")
        side[0].plot(time, v[:, 1], lw=0.8, label="v_y")
        side[0].legend(fontsize=7, loc="upper right")
    side[0].set_title("motion at the near field's base [m/s]", fontsize=9)
    if "bonded" in history:
        side[1].plot(time, history["bonded"], color="C2", lw=1)
    side[1].set_title("bonded joints left (the others broke)", fontsize=9)
    side[1].set_xlabel("t [s]")
    for a in side:
        cursors.append(a.axvline(frames[0]["time"], color="k", lw=0.8))

    def update(k):
        frame = frames[k]
        points, cells, data = frame["vtu"]
        polygons = [points[c] for c in cells]
        collection.set_verts(polygons)
        collection.set_array(1e3 * colours[k])
        ids = data.get("block_id", np.arange(len(cells))).astype(int)
        outlines.set_verts([p for p, i in zip(polygons, ids) if i in fallen])
        if frame["contacts"]:
            s, o = contact_dots(frame["contacts"])
            slide.set_data(s[:, 0], s[:, 1])
            opened.set_data(o[:, 0], o[:, 1])
        while bolt_lines:
            bolt_lines.pop().remove()
        if frame["bolts"]:
            bp, bc, _ = read_vtu(frame["bolts"])
            for c in bc:
                bolt_lines.extend(ax.plot(bp[c, 0], bp[c, 1], "-", color="k", lw=1.2))
        if frame["lining"]:
            lp, lc, ld = read_vtu(frame["lining"])
            broken = ld.get("state", np.zeros(len(lc))) == 1
            for c, b in zip(lc, broken):
                bolt_lines.extend(ax.plot(lp[c, 0], lp[c, 1], "-", color="red" if b else "C0",
                                          lw=2.0))
        stage = "excavation" if k < start else "wave and settling"
        title.set_text("%s: t = %.3f s (%s)" % (summary.get("name", ""), frame["time"], stage))
        for c in cursors:
            c.set_xdata([frame["time"], frame["time"]])
        return [collection, outlines, slide, opened, title] + cursors

    movie = animation.FuncAnimation(fig, update, frames=len(frames), blit=False)
    use_mp4 = not force_gif and shutil.which("ffmpeg") is not None
    if out is None:
        out = os.path.join(run_dir, "animation." + ("mp4" if use_mp4 else "gif"))
    writer = (animation.FFMpegWriter(fps=fps, bitrate=2400) if out.endswith(".mp4")
              else animation.PillowWriter(fps=fps))
    movie.save(out, writer=writer, dpi=90)
    plt.close(fig)
    return out, len(frames)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run_dir")
    parser.add_argument("--fps", type=float, default=8.0)
    parser.add_argument("--gif", action="store_true", help="a GIF even if ffmpeg is there")
    parser.add_argument("--out", help="output file (.mp4 or .gif)")
    args = parser.parse_args()
    if not os.path.isfile(os.path.join(args.run_dir, "summary.json")):
        sys.exit("animate.py: %s: no summary.json: expected a ddafem run's directory"
                 % args.run_dir)
    out, n = draw(args.run_dir, args.out, args.fps, args.gif)
    print("wrote %s (%d frames)" % (out, n))


if __name__ == "__main__":
    main()
