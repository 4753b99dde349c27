#!/usr/bin/python3
"""Plot a `ddafem sweep` (DIR/sweep.json): each run's largest keyblock residual displacement
relative to the rock against the swept value, the runs that exceeded in red, the bracket of the
critical value shaded; beside it, when each run ran (the asynchronous schedule). Writes DIR/sweep.png and links it from DIR/sweep.md.

    /usr/bin/python3 tools/plot_sweep.py results/sweep
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def plot_schedule(ax, sweep):
    """Each run as a bar from its start to its end, at its value."""
    for c in sweep["cases"]:
        color = "0.6" if c.get("cancelled") else "C3" if c["exceeded"] else "C0"
        start = c["started_s"]
        ax.plot([start, start + c["wall_s"]], [c["value"]] * 2, "-", color=color, lw=5,
                solid_capstyle="butt")
    ax.plot([], [], "-", color="0.6", lw=5, label="stopped: no longer needed")
    ax.set_xlabel("time into the sweep [s] (%d runs, %.0f s)" % (len(sweep["cases"]),
                                                                 sweep["wall_s"]))
    ax.set_ylabel(sweep["key"].split(".")[-1])
    ax.set_title("when each run ran", fontsize=10)
    ax.legend(fontsize=8)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    directory = sys.argv[1]
    sweep = json.load(open(os.path.join(directory, "sweep.json")))
    every = sweep["cases"]
    cases = sorted([c for c in every if not c.get("cancelled")], key=lambda c: c["value"])
    timed = all("started_s" in c for c in every)  # sweeps before the asynchronous search: not
    if timed:
        fig, (ax, schedule) = plt.subplots(1, 2, figsize=(11, 4.2),
                                           gridspec_kw={"width_ratios": [3, 2]})
    else:
        fig, ax = plt.subplots(figsize=(7, 4.2))
    x = [c["value"] for c in cases]
    y = [max(1e3 * c["max_relative_residual_m"], 1e-4) for c in cases]
    ax.semilogy(x, y, "-", color="0.6", lw=1)
    for c, yi in zip(cases, y):
        ax.semilogy(c["value"], yi, "o", color="C3" if c["exceeded"] else "C0", ms=7)
    if sweep.get("highest_holding") is not None and sweep.get("lowest_exceeding") is not None:
        ax.axvspan(sweep["highest_holding"], sweep["lowest_exceeding"], color="C1", alpha=0.25,
                   label="critical value: (%.4g, %.4g]" % (sweep["highest_holding"],
                                                           sweep["lowest_exceeding"]))
    if sweep["find"] == "displacement":
        ax.axhline(1e3 * sweep["threshold_m"], color="k", ls="--", lw=0.8, label="threshold")
    ax.plot([], [], "o", color="C0", label="held")
    ax.plot([], [], "o", color="C3", label="a keyblock fell" if sweep["find"] == "first_fall"
            else "exceeded")
    ax.set_xlabel(sweep["key"])
    ax.set_ylabel("largest keyblock residual relative displacement [mm]")
    ax.set_title(os.path.basename(sweep["scene"]) + ": " + sweep["find"], fontsize=10)
    ax.legend(fontsize=8)
    if timed:
        plot_schedule(schedule, sweep)
    fig.tight_layout()
    png = os.path.join(directory, "sweep.png")
    fig.savefig(png, dpi=110)
    md = os.path.join(directory, "sweep.md")
    text = open(md).read()
    if "](sweep.png)" not in text:
        open(md, "w").write(text.rstrip() + "\n\n![sweep](sweep.png)\n")
    print("wrote", png)


if __name__ == "__main__":
    main()
