#!/usr/bin/python3
"""Checks a run of a static stage followed by a dynamic one (issue 7): summary.json records the
static stage as converged (out-of-balance ratio within its tolerance) before the dynamic stage,
and every monitor stays at rest until QUIET_UNTIL [s] (a run without a wave, or before it
arrives): its displacement below DISPLACEMENT [m] and its velocity below VELOCITY [m/s].

usage: check_static_then_dynamic.py RUN_DIR QUIET_UNTIL DISPLACEMENT VELOCITY
"""
import json
import sys

import h5py
import numpy as np


def main():
    run_dir = sys.argv[1]
    quiet_until, max_displacement, max_velocity = (float(x) for x in sys.argv[2:5])
    with open(f"{run_dir}/summary.json") as f:
        summary = json.load(f)
    stages = summary["stages"]
    modes = [s["mode"] for s in stages]
    if modes[:2] != ["static", "dynamic"]:
        print(f"FAIL: expected a static then a dynamic stage, found {modes}")
        return 1
    static = stages[0]
    print(f"static stage '{static['name']}': {static['steps']} steps, ratio "
          f"{static['unbalanced_force_ratio']:.3g} (tolerance {static['tolerance']:.3g})")
    if not static["converged"] or static["unbalanced_force_ratio"] > static["tolerance"]:
        print("FAIL: the static stage did not converge")
        return 1
    failed = False
    with h5py.File(f"{run_dir}/histories.h5", "r") as h:
        quiet = h["time"][:] <= quiet_until
        for name in sorted(h["monitors"]):
            u = np.abs(h[f"monitors/{name}/displacement"][:][quiet]).max()
            v = np.abs(h[f"monitors/{name}/velocity"][:][quiet]).max()
            print(f"{name}: until {quiet_until} s, |u| <= {u:.3g} m, |v| <= {v:.3g} m/s")
            failed = failed or u > max_displacement or v > max_velocity
    if failed:
        print("FAIL: a monitor moved")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
