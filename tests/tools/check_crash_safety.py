#!/usr/bin/python3
"""What a run leaves when it is killed or its disk fills (issue 20), on the paper's bar.

usage: check_crash_safety.py DDAFEM SOURCE_DIR WORK_DIR

1. A run into a directory with an earlier run's results clears them (ddafem's file names only)
   and says so; a file of the user's stays.
2. A run killed with SIGKILL once summary.json reports 1000 steps: summary.json says "running",
   histories.h5 opens, every dataset has as many rows as /time (at least the 1000 flushed) and
   they equal the first rows of an uninterrupted run bit for bit; model.pvd and every VTU it
   lists parse.
3. A file size limit (RLIMIT_FSIZE, as a full disk for one file): exit code 1, not a signal, a
   message naming a file of the run, summary.json readable.
4. A real full disk, a 400 kB tmpfs, where this process may mount one (root in a container):
   exit code 1, the history file's disk named, histories.h5 readable with its rows up to the
   last flush. Where it may not, it says so and checks the rest.
"""
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def datasets(path):
    found = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: found.__setitem__(name, obj[()])
                     if isinstance(obj, h5py.Dataset) else None)
    return found


def check_collection(run_dir):
    root = ET.parse(os.path.join(run_dir, "model.pvd")).getroot()
    for d in root.iter("DataSet"):
        ET.parse(os.path.join(run_dir, d.get("file")))


def clears_earlier_results(ddafem, bar, work):
    out = os.path.join(work, "cleared")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    stale = ["summary.json", "blocks_00099.vtu", "report.md", "report_map.png", "far_field.pvd",
             "histories.h5.tmp"]
    for name in stale + ["notes.txt"]:
        with open(os.path.join(out, name), "w") as f:
            f.write('{"status": "completed", "steps": 386}\n')
    log = subprocess.run([ddafem, "run", bar, "-o", out, "--quiet",
                          "--set", "time.end_time=0.001"], capture_output=True, text=True)
    if log.returncode != 0:
        fail(f"the run into a used directory failed: {log.stderr}")
    if f"cleared {len(stale)} files of an earlier run" not in log.stdout:
        fail(f"no word of the cleared files: {log.stdout!r}")
    for name in ("blocks_00099.vtu", "report.md", "report_map.png", "far_field.pvd",
                 "histories.h5.tmp"):
        if os.path.exists(os.path.join(out, name)):
            fail(f"{name} of the earlier run is still there")
    if not os.path.exists(os.path.join(out, "notes.txt")):
        fail("the user's notes.txt was removed")
    print("ok: an earlier run's results cleared, the user's file kept")


def killed_run_is_readable(ddafem, bar, work):
    full = os.path.join(work, "full")
    subprocess.run([ddafem, "run", bar, "-o", full, "--quiet"], check=True,
                   stdout=subprocess.DEVNULL)
    reference = datasets(os.path.join(full, "histories.h5"))
    out = os.path.join(work, "killed")
    shutil.rmtree(out, ignore_errors=True)
    proc = subprocess.Popen([ddafem, "run", bar, "-o", out, "--quiet", "--set",
                             "time.end_time=10", "--set", "output.flush_interval=0.05"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 60
    steps = 0
    while steps < 1000:
        if time.time() > deadline or proc.poll() is not None:
            proc.kill()
            fail(f"the run did not report 1000 steps in summary.json (it reported {steps})")
        time.sleep(0.02)
        try:
            with open(os.path.join(out, "summary.json")) as f:
                steps = json.load(f).get("steps", 0)
        except (OSError, ValueError) as error:  # not written yet; never half a file
            if isinstance(error, ValueError):
                fail(f"summary.json is not JSON while the run runs: {error}")
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    with open(os.path.join(out, "summary.json")) as f:
        status = json.load(f)["status"]
    if status != "running":
        fail(f"a killed run's summary.json says {status!r}")
    data = datasets(os.path.join(out, "histories.h5"))
    rows = len(data["time"])
    if rows < 1000:
        fail(f"only {rows} rows readable after 1000 steps were flushed")
    for name, values in data.items():
        if len(values) != rows:
            fail(f"{name}: {len(values)} rows, /time {rows}")
        n = min(rows, len(reference[name]))
        if not np.array_equal(values[:n], reference[name][:n]):
            fail(f"{name} differs from the uninterrupted run's first {n} rows")
    check_collection(out)
    print(f"ok: killed after {steps} steps, {rows} rows readable, equal to the full run's")


def limited(limit):
    def apply():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return apply


def file_size_limit_is_an_error(ddafem, bar, work):
    out = os.path.join(work, "limited")
    shutil.rmtree(out, ignore_errors=True)
    proc = subprocess.run([ddafem, "run", bar, "-o", out, "--quiet", "--set",
                           "output.interval=0.0005"], preexec_fn=limited(30000),
                          capture_output=True, text=True)
    if proc.returncode != 1:
        fail(f"exit {proc.returncode} (a negative one is a signal), expected 1: {proc.stderr}")
    if out not in proc.stderr or "error:" not in proc.stderr:
        fail(f"the error names no file of the run: {proc.stderr!r}")
    with open(os.path.join(out, "summary.json")) as f:
        status = json.load(f)["status"]
    if status not in ("error", "running"):
        fail(f"summary.json says {status!r} after a failed write")
    print(f"ok: a file that cannot grow: exit 1, {proc.stderr.strip().splitlines()[-1]}")


def full_disk_keeps_histories(ddafem, bar, work):
    disk = os.path.join(work, "small_disk")
    os.makedirs(disk, exist_ok=True)
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=400k", "tmpfs", disk],
                             capture_output=True, text=True)
    if mounted.returncode != 0:
        print("note: no tmpfs could be mounted here (not root, or no privilege): the real full "
              "disk is not checked")
        return
    try:
        out = os.path.join(disk, "run")
        proc = subprocess.run([ddafem, "run", bar, "-o", out, "--quiet", "--set",
                               "output.flush_interval=0"], capture_output=True, text=True)
        if proc.returncode != 1 or "its disk is full" not in proc.stderr:
            fail(f"a full disk: exit {proc.returncode}, {proc.stderr!r}")
        data = datasets(os.path.join(out, "histories.h5"))
        rows = len(data["time"])
        if rows < 1 or any(len(v) != rows for v in data.values()):
            fail(f"histories.h5 after a full disk: {rows} rows, datasets of "
                 f"{sorted(set(len(v) for v in data.values()))}")
        check_collection(out)
        print(f"ok: a full disk: exit 1, histories.h5 readable with {rows} rows")
    finally:
        subprocess.run(["umount", disk], check=False)


def main():
    ddafem, source, work = sys.argv[1:4]
    bar = os.path.join(source, "examples", "bao2012", "p_wave_bar.yaml")
    os.makedirs(work, exist_ok=True)
    clears_earlier_results(ddafem, bar, work)
    killed_run_is_readable(ddafem, bar, work)
    file_size_limit_is_an_error(ddafem, bar, work)
    full_disk_keeps_histories(ddafem, bar, work)


if __name__ == "__main__":
    main()
