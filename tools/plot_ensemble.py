#!/usr/bin/python3
"""Draw a `ddafem ensemble` (DIR/ensemble.json): the opening twice, each keyblock coloured by its
probability of falling (left) and of loosening (right) over the completed runs (falling in
place: a block the excavation released falls whatever the shaking and is hatched instead), on
the blocks of the first completed member's first snapshot. Where the members' blocks differ
(joint-set seeds), the keyblocks cannot be matched by id: the opening's perimeter is drawn in its
sectors (ensemble.json `sectors`, degrees from the crown clockwise) coloured by the probability
that a keyblock there fell (loosened), over the first member's blocks in grey. Writes
DIR/ensemble.png.

    /usr/bin/python3 tools/plot_ensemble.py results/ensemble
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import patheffects  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.patches import Wedge  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report import frame_to_scale, pvd_entries, read_blocks_vtu  # noqa: E402


def first_member(directory, ensemble):
    """The folder and summary.json of the first completed member."""
    for m in ensemble["members"]:
        if m.get("counted"):
            run = os.path.join(directory, m["directory"])
            with open(os.path.join(run, "summary.json")) as f:
                return run, json.load(f)
    sys.exit("plot_ensemble: no completed member in %s" % directory)


def opening_frames(summary):
    """(centre, radius) of each opening from the keyblock report's bounding boxes."""
    frames = []
    for o in summary.get("keyblocks", {}).get("openings", []):
        lower, upper = np.array(o["lower_m"]), np.array(o["upper_m"])
        frames.append(((lower + upper) / 2.0, 0.5 * float(np.max(upper - lower))))
    return frames


def by_location(ensemble):
    """True where some keyblock is not in every completed run (the blocks differ)."""
    return any(k["n"] != ensemble["n_counted"] for k in ensemble["keyblocks"])


def draw_blocks_by_id(ax, ensemble, polygons, ids, cmap, outcome):
    index = {block_id: k for k, block_id in enumerate(ids)}
    ax.add_collection(PolyCollection(polygons, facecolors="0.93", edgecolors="0.55",
                                     linewidths=0.3))
    shown, values, released = [], [], []
    for k in ensemble["keyblocks"]:
        if k["id"] not in index:
            continue
        polygon = polygons[index[k["id"]]]
        if k["released"] == k["n"]:
            released.append(polygon)
            continue
        shown.append(polygon)
        values.append(k[outcome]["p"])
        label = "%d\n%.0f %%" % (k["id"], 100 * k[outcome]["p"])
        ax.annotate(label, polygon.mean(axis=0), ha="center", va="center", fontsize=6,
                    path_effects=[patheffects.withStroke(linewidth=2, foreground="white")])
    collection = PolyCollection(shown, array=np.array(values), cmap=cmap, edgecolors="black",
                                linewidths=0.8)
    ax.add_collection(collection)
    if released:
        ax.add_collection(PolyCollection(released, facecolors="none", edgecolors="black",
                                         hatch="xx", linewidths=0.8))
    return collection


def draw_sectors(ax, ensemble, frames, polygons, cmap, outcome):
    ax.add_collection(PolyCollection(polygons, facecolors="0.93", edgecolors="0.55",
                                     linewidths=0.3))
    norm = plt.Normalize(0.0, 1.0)
    for s in ensemble["sectors"]:
        centre, radius = frames[s["opening"]]
        wedge = Wedge(centre, 1.35 * radius, 90.0 - s["to_deg"], 90.0 - s["from_deg"],
                      width=0.35 * radius, facecolor=cmap(norm(s[outcome]["p"])),
                      edgecolor="black", linewidth=0.5)
        ax.add_patch(wedge)
    return plt.cm.ScalarMappable(norm=norm, cmap=cmap)


def frame_axes(ax, frames):
    """Zoom on the openings (two radii around each), to scale."""
    box = None
    if frames:
        box = (np.min([c - 2.2 * r for c, r in frames], axis=0),
               np.max([c + 2.2 * r for c, r in frames], axis=0))
    frame_to_scale(ax, box)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    directory = sys.argv[1]
    with open(os.path.join(directory, "ensemble.json")) as f:
        ensemble = json.load(f)
    run, summary = first_member(directory, ensemble)
    entries = pvd_entries(os.path.join(run, summary.get("outputs", {}).get("blocks",
                                                                            "blocks.pvd")))
    polygons, ids, _ = read_blocks_vtu(os.path.join(run, entries[0][1]))
    frames = opening_frames(summary)
    cmap = plt.get_cmap("Reds")
    figure, axes = plt.subplots(1, 2, figsize=(13.0, 6.0))
    sectors = by_location(ensemble)
    width = (ensemble["sectors"][0]["to_deg"] - ensemble["sectors"][0]["from_deg"]
             if ensemble["sectors"] else 10)
    for ax, (verb, by_id, by_sector) in zip(axes, (("falls", "fell_in_place", "fell"),
                                                   ("loosens", "loosened", "loosened"))):
        if sectors:
            mappable = draw_sectors(ax, ensemble, frames, polygons, cmap, by_sector)
            title = "P(a keyblock %s) by %g deg sector" % (verb, width)
        else:
            mappable = draw_blocks_by_id(ax, ensemble, polygons, ids, cmap, by_id)
            title = "P(keyblock %s)" % verb + (", released hatched" if verb == "falls" else "")
        mappable.set_clim(0.0, 1.0)
        figure.colorbar(mappable, ax=ax, label="probability", shrink=0.8)
        frame_axes(ax, frames)
        ax.set_title("%s over %d runs" % (title, ensemble["n_counted"]), fontsize="medium")
    figure.tight_layout()
    path = os.path.join(directory, "ensemble.png")
    figure.savefig(path, dpi=150)
    print("plot_ensemble: %s" % path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
