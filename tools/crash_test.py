#!/usr/bin/python3
"""Kills runs with SIGKILL at random moments and checks what they leave (issue 20).

usage: /usr/bin/python3 tools/crash_test.py [--build build] [--kills 10] [--seed 1]
                                            [--out docs/verification] [--quick]

For each scene (the default tunnel, examples/tunnel/circular_sv.yaml, blocks tied to a far field;
and the far field alone, examples/far_field/circular_hole.yaml) one uninterrupted run measures its
wall time T; then --kills runs are killed with SIGKILL (kill -9: no handler runs) at moments
drawn uniformly from [0.3 s, 0.95 T] with the given seed. After each kill it checks:

- a run killed before it wrote anything (it builds its models first) left no output directory;
  otherwise summary.json parses and says "running" (or a final status if the run ended first);
- histories.h5 opens with h5py, every dataset reads, every dataset has as many rows as /time,
  and the rows are a prefix of the uninterrupted run's (the same values, bit for bit);
- model.pvd (far_field.pvd for a far field alone) parses, and every file it lists exists and
  parses as XML;
- then `ddafem resume` continues it from its last checkpoint (written every CHECKPOINT_EVERY s
  of wall time: 5 s for the tunnel, 1 s for the far field) and the resumed run's histories must
  equal the uninterrupted run's, every dataset bit for bit. A run killed before its first
  checkpoint (in the tunnel's static stage, or within the first interval) has none: resume
  refuses it with exit code 2, as it should, and the row says so.

It reports per kill the moment, the rows readable, the simulated time they reach, how far the
last flush lay behind the kill, and whether every file parsed; writes crash_test.{md,json} into
--out. Exit status 1 if any file was unreadable or any row differed. Not a timing benchmark:
the moments depend on the machine's speed. --quick: 3 kills of the far field alone (for CI).
"""
import argparse
import json
import os
import platform
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

import h5py
import numpy as np

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = {
    "tunnel": ("examples/tunnel/circular_sv.yaml", "model.pvd"),
    "far_field": ("examples/far_field/circular_hole.yaml", "far_field.pvd"),
}
CHECKPOINT_EVERY = {"tunnel": 5.0, "far_field": 1.0}  # [s] of wall time


def run_command(ddafem, scene, out, every):
    return [ddafem, "run", os.path.join(TOP, scene), "-o", out, "--quiet", "--set",
            f"output.checkpoint_every={every}"]


def run_to_end(ddafem, scene, out, every):
    start = time.perf_counter()
    result = subprocess.run(run_command(ddafem, scene, out, every),
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        sys.exit(f"the uninterrupted run of {scene} failed (exit {result.returncode}):\n"
                 f"{result.stderr[-2000:]}")
    return time.perf_counter() - start


def run_and_kill(ddafem, scene, out, moment, every):
    proc = subprocess.Popen(run_command(ddafem, scene, out, every),
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        proc.wait(timeout=moment)
        return False  # it ended before the kill
    except subprocess.TimeoutExpired:
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        return True


def read_histories(path):
    """{dataset path: array} of every dataset in the file."""
    data = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                data[name] = obj[()]
        f.visititems(visit)
    return data


def check_histories(path, reference):
    """(rows, simulated time reached, problems) of a killed run's histories.h5."""
    problems = []
    try:
        data = read_histories(path)
    except Exception as error:  # h5py raises OSError and others on a damaged file
        return 0, 0.0, [f"histories.h5 unreadable: {error}"]
    if "time" not in data:
        return 0, 0.0, ["histories.h5 has no /time"]
    rows = len(data["time"])
    for name, values in data.items():
        if len(values) != rows:
            problems.append(f"{name} has {len(values)} rows, /time {rows}")
        elif name not in reference:
            problems.append(f"{name} is not in the uninterrupted run's file")
        elif not np.array_equal(values, reference[name][:rows]):
            problems.append(f"{name} differs from the uninterrupted run's first {rows} rows")
    missing = set(reference) - set(data)
    if missing:
        problems.append(f"datasets missing: {sorted(missing)[:3]}")
    reached = float(data["time"][-1]) if rows else 0.0
    return rows, reached, problems


def check_collection(run_dir, pvd):
    """Problems of the PVD collection and every file it lists (each must parse as XML)."""
    path = os.path.join(run_dir, pvd)
    if not os.path.exists(path):
        return [f"{pvd} missing"]
    try:
        files = [d.get("file") for d in ET.parse(path).getroot().iter("DataSet")]
    except ET.ParseError as error:
        return [f"{pvd} does not parse: {error}"]
    problems = []
    for name in files:
        try:
            ET.parse(os.path.join(run_dir, name))
        except (OSError, ET.ParseError) as error:
            problems.append(f"{name} listed in {pvd}: {error}")
    return problems


def resume_and_compare(ddafem, run_dir, reference):
    """(what resuming the killed run gave, its wall time [s])."""
    if not os.path.exists(os.path.join(run_dir, "checkpoint.bin")):
        result = subprocess.run([ddafem, "resume", run_dir, "--quiet"], capture_output=True,
                                text=True)
        refused = result.returncode == 2 and "no checkpoint" in result.stderr
        return ("no checkpoint yet: refused" if refused
                else f"no checkpoint, yet resume gave exit {result.returncode}"), 0.0
    start = time.perf_counter()
    result = subprocess.run([ddafem, "resume", run_dir, "--quiet"], capture_output=True,
                            text=True)
    wall = time.perf_counter() - start
    if result.returncode != 0:
        return f"resume failed (exit {result.returncode}): {result.stderr[-300:]}", wall
    data = read_histories(os.path.join(run_dir, "histories.h5"))
    equal = sorted(data) == sorted(reference) and all(
        data[n].shape == reference[n].shape and data[n].tobytes() == reference[n].tobytes()
        for n in reference)
    line = next((x for x in result.stdout.splitlines() if x.startswith("resumed ")), "")
    at = line.split(" at t = ")[-1].split(",")[0] if line else "?"
    return (f"from t = {at}: equal bit for bit" if equal
            else f"from t = {at}: histories differ"), wall


def check_summary(run_dir):
    """(summary.json's content, problems)."""
    try:
        with open(os.path.join(run_dir, "summary.json")) as f:
            return json.load(f), []
    except (OSError, ValueError) as error:
        return {}, [f"summary.json: {error}"]


def crash_scene(ddafem, name, kills, rng, work):
    scene, pvd = SCENES[name]
    full_dir = os.path.join(work, name + "_full")
    every = CHECKPOINT_EVERY[name]
    wall = run_to_end(ddafem, scene, full_dir, every)
    reference = read_histories(os.path.join(full_dir, "histories.h5"))
    flush_interval = None  # the running summary.json's
    records = []
    for k in range(kills):
        moment = rng.uniform(0.3, max(0.35, 0.95 * wall))
        run_dir = os.path.join(work, f"{name}_kill{k}")
        killed = run_and_kill(ddafem, scene, run_dir, moment, every)
        if os.path.isdir(run_dir):
            summary, problems = check_summary(run_dir)
            status = summary.get("status")
            flush_interval = summary.get("flush_interval_s", flush_interval)
            rows, reached, history_problems = check_histories(
                os.path.join(run_dir, "histories.h5"), reference)
            problems += history_problems + check_collection(run_dir, pvd)
            resumed, resume_wall = resume_and_compare(ddafem, run_dir, reference)
            if "differ" in resumed or "failed" in resumed or "yet resume gave" in resumed:
                problems.append(resumed)
        else:
            status, problems, rows, reached = "nothing written yet", [], 0, 0.0
            resumed, resume_wall = "nothing to resume", 0.0
        records.append({"scene": name, "kill_s": round(moment, 3), "killed": killed,
                        "status": status, "rows": rows, "rows_full": len(reference["time"]),
                        "time_reached_s": reached, "problems": problems, "resumed": resumed,
                        "resume_wall_s": round(resume_wall, 2)})
        print(f"{name} kill {k}: at {moment:.2f} s, {rows} rows to t = {reached:.4g} s, "
              f"status {status}, {'ok' if not problems else '; '.join(problems)}; "
              f"resumed {resumed}", flush=True)
        shutil.rmtree(run_dir, ignore_errors=True)
    return {"scene": scene, "wall_s": wall, "flush_interval_s": flush_interval,
            "checkpoint_every_s": every, "kills": records}


def write_report(results, out, command, seed):
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "crash_test.json"), "w") as f:
        json.dump({"seed": seed, "machine": platform.machine(), "scenes": results}, f, indent=1)
    lines = ["# Killed runs: what they leave", "",
             f"Generated by `{command}` on {platform.machine()}, {os.cpu_count()} cores "
             f"(seed {seed}). Each run is killed with SIGKILL at a random moment; then "
             "summary.json, every dataset of histories.h5 (each a prefix of the uninterrupted "
             "run's, bit for bit) and the PVD collection with every file it lists are read; "
             "then `ddafem resume` continues it from its last checkpoint and its histories "
             "are compared with the uninterrupted run's, every dataset bit for bit.", ""]
    for name, r in results.items():
        bad = sum(1 for k in r["kills"] if k["problems"])
        equal = sum(1 for k in r["kills"] if "equal bit for bit" in k["resumed"])
        lines += [f"## {name}: `{r['scene']}`", "",
                  f"Uninterrupted: {r['wall_s']:.1f} s wall time, "
                  f"{r['kills'][0]['rows_full'] if r['kills'] else 0} history rows; "
                  f"histories flushed every {r['flush_interval_s']} s of wall time "
                  f"(`output.flush_interval`), checkpoints every {r['checkpoint_every_s']} s. "
                  f"**{len(r['kills']) - bad} of {len(r['kills'])} killed runs left every file "
                  f"readable; {equal} of them resumed to histories equal to the uninterrupted "
                  "run's, the others were killed before their first checkpoint.**", "",
                  "| kill at [s] | status | rows readable | to t [s] | files | resumed | "
                  "resume wall [s] |",
                  "|---:|---|---:|---:|---|---|---:|"]
        for k in r["kills"]:
            files = "all read" if not k["problems"] else "; ".join(k["problems"])
            lines.append(f"| {k['kill_s']:.2f} | {k['status']} | {k['rows']} of "
                         f"{k['rows_full']} | {k['time_reached_s']:.4g} | {files} | "
                         f"{k['resumed']} | {k['resume_wall_s']:.1f} |")
        lines.append("")
    with open(os.path.join(out, "crash_test.md"), "w") as f:
        f.write("\n".join(lines))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--kills", type=int, default=10)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "verification"))
    parser.add_argument("--quick", action="store_true",
                        help="3 kills of the far field alone, no report (CI)")
    args = parser.parse_args()
    ddafem = os.path.join(os.path.abspath(args.build), "ddafem")
    rng = random.Random(args.seed)
    names = ["far_field"] if args.quick else ["tunnel", "far_field"]
    kills = 3 if args.quick else args.kills
    results = {}
    with tempfile.TemporaryDirectory(prefix="crash_test_") as work:
        for name in names:
            results[name] = crash_scene(ddafem, name, kills, rng, work)
    if not args.quick:
        command = "/usr/bin/python3 tools/crash_test.py" + (
            f" --kills {args.kills}" if args.kills != 10 else "") + (
            f" --seed {args.seed}" if args.seed != 1 else "")
        write_report(results, args.out, command, args.seed)
    bad = [k for r in results.values() for k in r["kills"] if k["problems"]]
    print(f"{len(bad)} killed runs left an unreadable or differing file, or did not resume to "
          "the uninterrupted run's histories")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
