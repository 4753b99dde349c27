#!/usr/bin/python3
"""tools/step_anatomy.py on a run directory made here with known steps (CI test
tools.step_anatomy): ten steps at dt_max in the shake stage; in the settle stage, before a block's
removal at 0.02 s, a step after a cut (level 1), a step shortened without a cut (level 2, then
back to level 0), eight steps at dt_max and one more shortened step; ten steps at dt_max after
the removal. Checks the counts per phase and level, and that bad input exits 2 naming the file.

    check_step_anatomy.py SOURCE_DIR WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np


def make_run(run):
    rows = [(0.0, 0.0, 0)] + [(0.001 * i, 0.001, 0) for i in range(1, 11)]
    rows += [(0.0105, 0.0005, 1), (0.01075, 0.00025, 0), (0.01175, 0.001, 0)]
    rows += [(0.01275 + 0.001 * i, 0.001, 0) for i in range(8)]
    rows += [(0.02, 0.00025, 0)] + [(0.02 + 0.001 * i, 0.001, 0) for i in range(1, 11)]
    t, dt, cuts = (np.array(c, dtype=float) for c in zip(*rows))
    with h5py.File(os.path.join(run, "histories.h5"), "w") as h:
        h["time"] = t
        h["steps/dt"] = dt
        h["steps/cuts"] = cuts
    summary = {"wall_time_s": 1.0,
               "time_step": {"attempts": 33, "cuts": 1, "dt_max_s": 0.001},
               "stages": [{"name": "excavate", "mode": "static"},
                          {"name": "shake", "mode": "dynamic", "end_time_s": 0.01,
                           "time_reached_s": 0.01},
                          {"name": "settle", "mode": "settle", "end_time_s": 1.0,
                           "time_reached_s": 0.03, "removed": [{"block": 3, "time_s": 0.02}]}]}
    with open(os.path.join(run, "summary.json"), "w") as f:
        json.dump(summary, f)


def main(source, work):
    tool = [sys.executable, os.path.join(source, "tools", "step_anatomy.py")]
    shutil.rmtree(work, ignore_errors=True)
    run = os.path.join(work, "run")
    os.makedirs(run)
    make_run(run)
    out = os.path.join(work, "anatomy.json")
    subprocess.run(tool + [run, "-o", os.path.join(work, "anatomy.md"), "--json", out], check=True)
    phases = json.load(open(out))["phases"]
    got = [(p["steps"], {int(k): v["steps"] for k, v in p["levels"].items()},
            p["steps_after_cuts"], p["shortened_without_cut"]) for p in phases]
    expected = [(10, {0: 10}, 0, 0), (12, {0: 9, 1: 1, 2: 2}, 1, 2), (10, {0: 10}, 0, 0)]
    assert got == expected, got
    assert abs(sum(v["time_s"] for v in phases[1]["levels"].values()) - 0.01) < 1e-12, phases[1]
    assert "removal at 0.020 s" in phases[1]["phase"], phases[1]
    assert open(os.path.join(work, "anatomy.md")).read().count("\n| ") == 4
    # Bad input: no directory; a history without the step channels.
    bad = subprocess.run(tool + [os.path.join(work, "missing")], capture_output=True, text=True)
    assert bad.returncode == 2 and "missing: no such directory" in bad.stderr, bad.stderr
    with h5py.File(os.path.join(run, "histories.h5"), "w") as h:
        h["time"] = np.zeros(1)
    bad = subprocess.run(tool + [run], capture_output=True, text=True)
    assert bad.returncode == 2 and "no dataset `steps/dt`" in bad.stderr, bad.stderr
    print("step_anatomy: counts per phase and level as built; bad input exits 2")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
