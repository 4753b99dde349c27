#!/usr/bin/python3
"""Compare the keyblocks of two runs of one scene (e.g. two solvers or two dt).

Sample command line:

    /usr/bin/python3 tools/compare_keyblocks.py results/direct results/block_pcg

Reads RUN_DIR/summary.json and RUN_DIR/histories.h5 of each run and prints, per keyblock, the
peak and the final magnitude of its displacement relative to the rock around its opening
(`keyblocks/block_N/relative_displacement`) in both runs and their largest difference over the
time both runs cover (on 400 common instants, linear interpolation), then each run's wall time,
steps, end time, fallen and loosened counts. Exit 2 if a run is missing a file or the two runs
have different keyblocks.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402
from report import keyblock_histories, open_histories  # noqa: E402  (tools/ on the path first)


def load(run):
    """(summary, time [s], {block id: relative displacement (n, 2) [m]}) of a run."""
    try:
        with open(os.path.join(run, "summary.json")) as f:
            summary = json.load(f)
    except (OSError, ValueError) as e:
        print(f"{run}: cannot read its summary.json: {e}", file=sys.stderr)
        sys.exit(2)
    path = os.path.join(run, "histories.h5")
    if not os.path.isfile(path):
        print(f"{run}: no histories.h5", file=sys.stderr)
        sys.exit(2)
    with open_histories(path) as h5:
        return summary, h5["time"][()], keyblock_histories(h5, "relative_displacement")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run_a")
    parser.add_argument("run_b")
    args = parser.parse_args()
    (sa, ta, ra), (sb, tb, rb) = load(args.run_a), load(args.run_b)
    if sorted(ra) != sorted(rb):
        print(f"the runs have different keyblocks: {sorted(ra)} against {sorted(rb)}",
              file=sys.stderr)
        sys.exit(2)
    grid = np.linspace(0.0, min(ta[-1], tb[-1]), 400)
    print("| keyblock | peak A [mm] | peak B [mm] | final A [mm] | final B [mm] | "
          "largest difference [mm] |")
    print("|---|---:|---:|---:|---:|---:|")
    for block in sorted(ra):
        a, b = ra[block], rb[block]
        on_grid = [np.column_stack([np.interp(grid, t, r[:, k]) for k in range(2)])
                   for t, r in ((ta, a), (tb, b))]
        largest = np.max(np.linalg.norm(on_grid[0] - on_grid[1], axis=1))
        peak_a, peak_b = (np.max(np.linalg.norm(r, axis=1)) for r in (a, b))
        final_a, final_b = (np.linalg.norm(r[-1]) for r in (a, b))
        print(f"| block_{block} | {1e3 * peak_a:.2f} | {1e3 * peak_b:.2f} | {1e3 * final_a:.2f} | "
              f"{1e3 * final_b:.2f} | {1e3 * largest:.2f} |")
    for label, s in (("A", sa), ("B", sb)):
        k = s.get("keyblocks", {})
        print(f"{label}: {s.get('wall_time_s', float('nan')):.1f} s, {s.get('steps')} steps to "
              f"t = {s.get('time_reached_s', float('nan')):.3f} s, fell {k.get('fell')}, "
              f"loosened {k.get('loosened')} of {k.get('count')}")


if __name__ == "__main__":
    main()
