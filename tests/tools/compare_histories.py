#!/usr/bin/python3
"""Compares the monitor histories of two runs of the same scene (a truncated model against a
larger reference): for every monitor, the L2 norm over the window of the difference of QUANTITY
(displacement or velocity, both components) relative to the reference's L2 norm must stay below
TOLERANCE. Prints one line per monitor.

usage: compare_histories.py RUN_DIR REFERENCE_DIR QUANTITY TOLERANCE
"""
import sys

import h5py
import numpy as np


def main():
    run_dir, reference_dir, quantity, tolerance = sys.argv[1:5]
    tolerance = float(tolerance)
    worst = 0.0
    with h5py.File(f"{run_dir}/histories.h5", "r") as a, \
            h5py.File(f"{reference_dir}/histories.h5", "r") as b:
        if not np.allclose(a["time"][:], b["time"][:]):
            print("FAIL: the runs have different times")
            return 1
        for name in sorted(b["monitors"]):
            x = a[f"monitors/{name}/{quantity}"][:]
            y = b[f"monitors/{name}/{quantity}"][:]
            error = float(np.sqrt(np.sum((x - y) ** 2) / np.sum(y ** 2)))
            worst = max(worst, error)
            print(f"{name}: relative L2 difference of {quantity} {error:.4f}")
    if worst >= tolerance:
        print(f"FAIL: {worst:.4f} >= {tolerance}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
