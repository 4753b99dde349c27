#!/usr/bin/python3
"""Plot a `ddafem fragility` (DIR/fragility.json): per damage state the fraction of the runs at
each level that reached it with its 95 % Wilson interval, the maximum-likelihood lognormal curve
P = Phi(ln(IM / theta) / beta) and the band of the bootstrap curves at the 5-95 % theta and beta
bounds (or, where the runs separate perfectly, the bracket of the median shaded); for context
HAZUS's bored or drilled rock tunnels (median PGA 0.6 g slight, 0.8 g moderate, beta 0.6),
converted to the IM by the input's PGA/PGV relation (fragility.json intensity_measure.pga_g_per_im;
absent: not drawn). Writes DIR/fragility.png.

    /usr/bin/python3 tools/plot_fragility.py results/fragility
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def phi(x):
    return 0.5 * math.erfc(-x / math.sqrt(2.0))


def curve(theta, beta, xs):
    if math.isinf(theta):  # the median beyond every level: nothing reached anywhere
        return [0.0 for _ in xs]
    return [phi(math.log(x / theta) / beta) for x in xs]


def plot_state(ax, f, k, state, xs):
    """Points with Wilson bars, the fit and its bootstrap band (or the separation bracket)."""
    color = "C%d" % k
    # Each state's points a little apart from the others' at the same level.
    ims = [level["im"] * (1.0 + 0.015 * k) for level in f["levels"] if level["n_counted"] > 0]
    props = [level["states"][k] for level in f["levels"] if level["n_counted"] > 0]
    ps = [p["p"] for p in props]
    low = [p["p"] - p["wilson_95"][0] for p in props]
    high = [p["wilson_95"][1] - p["p"] for p in props]
    ax.errorbar(ims, ps, yerr=[low, high], fmt="o", color=color, capsize=3,
                label=state["name"] + " (runs, 95 % Wilson)")
    fit = state["fit"]
    if fit["status"] == "resolved":
        ax.plot(xs, curve(fit["theta"], fit["beta"], xs), "-", color=color,
                label="fit: theta %.3g, beta %.2g" % (fit["theta"], fit["beta"]))
        b = fit["bootstrap"]
        # an unbounded bound (null: resamples drove it to infinity) shades to the plot's edge
        thetas = [float("inf") if t is None else t for t in b["theta_90"]]
        betas = [float("inf") if s is None else s for s in b["beta_90"]]
        corners = [curve(t, s, xs) for t in thetas for s in betas]
        ax.fill_between(xs, [min(c[i] for c in corners) for i in range(len(xs))],
                        [max(c[i] for c in corners) for i in range(len(xs))], color=color,
                        alpha=0.15, lw=0)
    elif fit["highest_none"] is not None and fit["lowest_all"] is not None:
        ax.axvspan(fit["highest_none"], fit["lowest_all"], color=color, alpha=0.12,
                   label="median between (beta unresolved)")


def main():
    directory = sys.argv[1]
    f = json.load(open(os.path.join(directory, "fragility.json")))
    im = f["intensity_measure"]
    ims = [level["im"] for level in f["levels"]]
    lo, hi = min(ims) / 2.0, max(ims) * 2.0
    hazus = [h for h in f["hazus_bored_tunnels"] if h["im_median"] is not None]
    if hazus:
        hi = max(hi, max(h["im_median"] for h in hazus) * 3.0)
        lo = min(lo, min(h["im_median"] for h in hazus) / 3.0)
    xs = [lo * (hi / lo) ** (i / 300.0) for i in range(301)]
    fig, ax = plt.subplots(figsize=(8, 5))
    for k, state in enumerate(f["states"]):
        plot_state(ax, f, k, state, xs)
    for h in hazus:
        ax.plot(xs, curve(h["im_median"], h["beta"], xs), "--", color="0.5",
                label="HAZUS bored tunnel, %s (PGA %.1f g)" % (h["state"], h["pga_median_g"]))
    ax.set_xscale("log")
    ax.set_ylim(-0.02, 1.02)
    unit = " [%s]" % im["unit"] if im["unit"] else ""
    ax.set_xlabel(im["name"] + unit)
    ax.set_ylabel("P(damage state | IM)")
    if im["pga_g_per_im"] is not None:
        top = ax.secondary_xaxis("top", functions=(lambda x: x * im["pga_g_per_im"],
                                                   lambda a: a / im["pga_g_per_im"]))
        top.set_xlabel("PGA (outcrop) [g]")
    ax.set_title(os.path.basename(f["scene"]) + ": " + f["key"], fontsize=10)
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(directory, "fragility.png"), dpi=120)
    print(os.path.join(directory, "fragility.png"))


if __name__ == "__main__":
    main()
