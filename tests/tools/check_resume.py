#!/usr/bin/python3
"""Checkpoint and resume (issue 20): a run killed or stopped, then continued with
`ddafem resume DIR`, ends with the histories of the run that was never interrupted, bit for bit.

usage: check_resume.py DDAFEM SOURCE_DIR WORK_DIR

Cases, each against its uninterrupted run:
1. blocks alone (examples/tunnel/roof_wedge_sv.yaml with truncation vb1: a static stage, a
   settle stage and the wave in blocks with VB I), killed with SIGKILL at a random moment after
   its first checkpoint (every 0.05 s of wall time; if the run ends first, as a short run can
   on a fast machine, it is run again with a shorter wait, then killed at the checkpoint);
2. a far field alone (examples/far_field/sv_column.yaml to t = 4 s), killed the same way;
3. blocks in a far field after a static stage (examples/coupled/blocks_in_hole_static.yaml),
   killed the same way;
4. a lined tunnel (examples/support/lined_tunnel.yaml: the lining installed after the static
   stage, two of its elements broken at 32 ms), killed once it has reached 40 ms of simulated
   time (its running summary.json), in the dynamic stage;
5. the hybrid bar (examples/coupled/p_wave_bar_hybrid.yaml) stopped by --max-wall-time 1.2 (exit 3),
   which writes a checkpoint where it stops.
Then what `resume` refuses with exit 2 and a message naming the file: a directory without a
checkpoint (a completed run removes its own), and a scene file changed since the run started.
Every dataset of histories.h5 must equal the uninterrupted run's (same shape, same bits), the
resumed summary.json must say "completed", and model.pvd (or far_field.pvd) and every VTU it
lists must parse.
"""
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import numpy as np

from check_crash_safety import datasets


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def same_histories(run_dir, reference_dir, label):
    got = datasets(os.path.join(run_dir, "histories.h5"))
    want = datasets(os.path.join(reference_dir, "histories.h5"))
    if sorted(got) != sorted(want):
        fail(f"{label}: datasets {sorted(got)} against {sorted(want)}")
    for name in want:
        a, b = got[name], want[name]
        if a.shape != b.shape or a.tobytes() != b.tobytes():
            rows = a.shape[0] if a.shape == b.shape else None
            first = None
            if rows is not None:
                first = int(np.nonzero((a != b).reshape(rows, -1).any(axis=1))[0][0])
            fail(f"{label}: {name} differs (shapes {a.shape} and {b.shape}, first row {first})")
    print(f"{label}: {len(want)} datasets of {len(want['time'])} rows equal bit for bit")


def check_collection(run_dir, pvd):
    root = ET.parse(os.path.join(run_dir, pvd)).getroot()
    for d in root.iter("DataSet"):
        ET.parse(os.path.join(run_dir, d.get("file")))


def run(ddafem, args, label, expect):
    done = subprocess.run([ddafem] + args, capture_output=True, text=True, timeout=600)
    if done.returncode != expect:
        fail(f"{label}: exit code {done.returncode}, expected {expect}\n{done.stdout}{done.stderr}")
    return done


def reached(directory):
    """The simulated time [s] the running summary.json says the run has reached (0 if none)."""
    try:
        with open(os.path.join(directory, "summary.json")) as f:
            return json.load(f).get("time_reached_s", 0.0)
    except (OSError, ValueError):
        return 0.0


def killed_and_resumed(ddafem, scene, work, label, pvd, extra=(), after=0.0, after_time=None):
    """`after` [s]: the kill waits that much longer after the first checkpoint; `after_time`
    [s]: and until the run has reached this simulated time (its summary.json, flushed every
    0.02 s of wall time), whatever the machine's speed."""
    reference = os.path.join(work, label + "_whole")
    resumed = os.path.join(work, label + "_resumed")
    for d in (reference, resumed):
        shutil.rmtree(d, ignore_errors=True)
    settings = ["--set", "output.checkpoint_every=0.05"] + list(extra)
    if after_time is not None:
        settings += ["--set", "output.flush_interval=0.02"]
    run(ddafem, ["run", scene, "-o", reference, "--quiet"] + settings, label, 0)
    # The kill comes at a random moment after the first checkpoint; on a fast machine a short
    # run may end first, so the wait shrinks and the run is tried again.
    for wait in (random.uniform(0.0, 0.3), random.uniform(0.0, 0.03), 0.0):
        shutil.rmtree(resumed, ignore_errors=True)
        process = subprocess.Popen([ddafem, "run", scene, "-o", resumed, "--quiet"] + settings,
                                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        checkpoint = os.path.join(resumed, "checkpoint.bin")
        while not os.path.exists(checkpoint) and process.poll() is None:
            time.sleep(0.005)
        while after_time is not None and reached(resumed) < after_time and process.poll() is None:
            time.sleep(0.005)
        time.sleep(after + wait)
        process.send_signal(signal.SIGKILL)
        if process.wait() == -signal.SIGKILL:
            break
    else:
        fail(f"{label}: the run ended before the kill (exit {process.returncode}): expected a "
             f"scene that runs longer than its first checkpoint")
    with open(os.path.join(resumed, "summary.json")) as f:
        killed_at = json.load(f)["time_reached_s"]
    log = run(ddafem, ["resume", resumed, "--quiet"], label, 0).stdout
    if "resumed " + resumed not in log:
        fail(f"{label}: the resumed run does not say where it resumed:\n{log}")
    resumed_line = next(line for line in log.splitlines() if line.startswith("resumed "))
    print(f"{label}: killed after t = {killed_at:.6g} s (last flush); {resumed_line}")
    finished(resumed, reference, label, pvd)


def finished(resumed, reference, label, pvd):
    same_histories(resumed, reference, label)
    with open(os.path.join(resumed, "summary.json")) as f:
        status = json.load(f)["status"]
    if not status.startswith("completed"):
        fail(f"{label}: the resumed run's status is {status}")
    if os.path.exists(os.path.join(resumed, "checkpoint.bin")):
        fail(f"{label}: a completed run kept its checkpoint")
    check_collection(resumed, pvd)


def stopped_and_resumed(ddafem, scene, work, label):
    reference = os.path.join(work, label + "_whole")
    resumed = os.path.join(work, label + "_resumed")
    for d in (reference, resumed):
        shutil.rmtree(d, ignore_errors=True)
    run(ddafem, ["run", scene, "-o", reference, "--quiet"], label, 0)
    run(ddafem, ["run", scene, "-o", resumed, "--quiet", "--max-wall-time", "1.2"], label, 3)
    log = run(ddafem, ["resume", resumed, "--quiet"], label, 0).stdout
    resumed_line = next(line for line in log.splitlines() if line.startswith("resumed "))
    print(f"{label}: stopped by --max-wall-time 1.2; {resumed_line}")
    finished(resumed, reference, label, "model.pvd")
    return resumed


def refusals(ddafem, source, work, completed):
    log = run(ddafem, ["resume", completed], "a completed run", 2)
    if "checkpoint.bin: no checkpoint to resume from" not in log.stderr:
        fail("resuming a completed run: " + log.stderr)
    scene = os.path.join(work, "changed.yaml")
    shutil.copy(os.path.join(source, "examples/coupled/p_wave_bar_hybrid.yaml"), scene)
    out = os.path.join(work, "changed")
    shutil.rmtree(out, ignore_errors=True)
    run(ddafem, ["run", scene, "-o", out, "--quiet", "--max-wall-time", "0.3"], "changed", 3)
    with open(scene, "a") as f:
        f.write("# edited\n")
    log = run(ddafem, ["resume", out], "a changed scene", 2)
    if scene not in log.stderr or "changed or missing since the run" not in log.stderr:
        fail("resuming after the scene changed: " + log.stderr)
    print("refused with exit 2: a completed run, a scene changed since the run started")


def main():
    ddafem, source, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    random.seed(20)
    examples = os.path.join(source, "examples")
    killed_and_resumed(ddafem, os.path.join(examples, "tunnel/roof_wedge_sv.yaml"), work,
                       "blocks", "model.pvd", ["--set", "tunnel.truncation=vb1"])
    killed_and_resumed(ddafem, os.path.join(examples, "far_field/sv_column.yaml"), work,
                       "far_field", "far_field.pvd", ["--set", "time.end_time=4"])
    killed_and_resumed(ddafem, os.path.join(examples, "coupled/blocks_in_hole_static.yaml"),
                       work, "coupled_static", "model.pvd")
    # A lining installed after the static stage, killed in the dynamic stage once two of its
    # elements have broken (at 32 ms of simulated time; a fixed wall-time wait let the run end
    # first on a fast machine).
    killed_and_resumed(ddafem, os.path.join(examples, "support/lined_tunnel.yaml"), work,
                       "lined_tunnel", "model.pvd", after_time=0.04)
    completed = stopped_and_resumed(
        ddafem, os.path.join(examples, "coupled/p_wave_bar_hybrid.yaml"), work, "hybrid_bar")
    refusals(ddafem, source, work, completed)
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
