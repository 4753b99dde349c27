#!/usr/bin/python3
"""ddafem beside ntdda (Doolin's C port of Shi's DDA) on the Bao et al. (2012) P-wave bar (100
bonded blocks, 5000 steps) and a bonded 2000-block wall under gravity (200 steps): per-step time
of the time stepping alone and whole-process time and memory, the two codes run alternately,
medians over --runs, with the machine's load average before and after. Writes
docs/performance/peers.{md,json}.

usage: /usr/bin/python3 bench/peer_bench.py --ntdda-git DIR [--build build] [--runs 5]

DIR is the git directory of a clone of github.com/doolin/ntdda (`fetch github:doolin/ntdda`
gives one under /work/.mirror); ntdda is built from it by bench/peers/ntdda/build.sh into a
temporary directory. Per step: ntdda's `ddanalysis` wall time (its driver prints it) over its
steps; ddafem's phase timings (contact detection, assembly, solve, update, output) over its
steps. Whole process: elapsed time and peak resident memory of the child (os.wait4). Start-up:
`ddafem --version` and `ddafem check` of the block stack (a blocks-only scene), the same way,
three times per run. Not a test: timings depend on the machine and its load.
"""
import argparse
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import tempfile
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GLUE = os.path.join(TOP, "bench", "peers", "ntdda")
CASES = {
    # name: (ddafem scene, ntdda generator, ntdda binary, extra ddafem settings)
    "bar": ("examples/bao2012/p_wave_bar.yaml", "gen_bar.py", "ntdda_run", []),
    "wall": ("bench/scenes/wall_50x40.yaml", "gen_wall.py", "ntdda_run_cap", []),
}
PHASES = ["broad_phase", "narrow_phase", "assemble", "solve", "update", "output", "tie_terms",
          "tied_body"]


def run_with_rusage(cmd, cwd=None):
    """(elapsed s, peak RSS MiB, returncode, stderr) via os.wait4 on the child."""
    start = time.perf_counter()
    with tempfile.TemporaryFile(mode="w+") as err:
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        elapsed = time.perf_counter() - start
        proc.returncode = os.waitstatus_to_exitcode(status)
        err.seek(0)
        stderr = err.read()
    return elapsed, usage.ru_maxrss / 1024.0, proc.returncode, stderr


def build_ntdda(git_dir, work):
    env = dict(os.environ, NTDDA_GIT=git_dir, WORK=work)
    subprocess.run(["sh", os.path.join(GLUE, "build.sh")], env=env, check=True,
                   stdout=subprocess.DEVNULL)
    with open(os.path.join(work, "REVISION")) as f:
        return f.read().strip()


def run_ntdda(work, case, scratch):
    _, generator, binary, _ = CASES[case]
    os.makedirs(scratch, exist_ok=True)
    subprocess.run(["/usr/bin/python3", os.path.join(GLUE, generator), scratch], check=True,
                   stdout=subprocess.DEVNULL)
    cmd = [os.path.join(work, binary), os.path.join(scratch, case + ".geo"),
           os.path.join(scratch, case + ".ana")]
    elapsed, rss, rc, stderr = run_with_rusage(cmd, cwd=scratch)
    m = re.search(r"steps=(\d+) analysis_s=([0-9.]+)", stderr)
    if rc != 0 or not m:
        raise SystemExit(f"ntdda failed on {case} (exit {rc}):\n{stderr[-2000:]}")
    steps, analysis = int(m.group(1)), float(m.group(2))
    return {"ms_per_step": 1e3 * analysis / steps, "steps": steps, "process_s": elapsed,
            "peak_rss_mib": rss}


def run_ddafem(ddafem, case, out):
    scene, _, _, extra = CASES[case]
    cmd = [ddafem, "run", os.path.join(TOP, scene), "-o", out, "--quiet",
           "--set", "output.interval=1"] + extra
    elapsed, rss, rc, stderr = run_with_rusage(cmd)
    if rc != 0:
        raise SystemExit(f"ddafem failed on {case} (exit {rc}):\n{stderr[-2000:]}")
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    stepping = sum(summary["timings_s"].get(p, 0.0) for p in PHASES)
    return {"ms_per_step": 1e3 * stepping / summary["steps"], "steps": summary["steps"],
            "process_s": elapsed, "peak_rss_mib": rss}


STARTS = {
    # name: ddafem arguments
    "version": ["--version"],
    "check_block_stack": ["check", os.path.join(TOP, "examples", "block_stack", "stack.yaml")],
}


def measure_start(ddafem, args):
    elapsed, rss, rc, stderr = run_with_rusage([ddafem] + args)
    if rc != 0:
        raise SystemExit(f"ddafem {' '.join(args)} failed (exit {rc}):\n{stderr[-2000:]}")
    return {"process_s": elapsed, "peak_rss_mib": rss}


def medians(runs):
    return {k: statistics.median(r[k] for r in runs) for k in runs[0]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--ntdda-git", required=True,
                        help="git directory of a clone of github.com/doolin/ntdda")
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "performance"))
    args = parser.parse_args()
    ddafem = os.path.join(args.build, "ddafem")
    if not os.path.isdir(args.ntdda_git):
        raise SystemExit(f"--ntdda-git {args.ntdda_git}: no such directory (expected the git "
                         "directory of a clone of github.com/doolin/ntdda)")
    if not os.access(ddafem, os.X_OK):
        raise SystemExit(f"--build {args.build}: no ddafem binary there (build it first)")

    load_before = os.getloadavg()
    results = {case: {"ntdda": [], "ddafem": []} for case in args.cases}
    starts = {name: [] for name in STARTS}
    with tempfile.TemporaryDirectory() as tmp:
        revision = build_ntdda(args.ntdda_git, os.path.join(tmp, "ntdda"))
        for k in range(args.runs):
            for case in args.cases:
                # alternate which code goes first, so that a drift in load hits both alike
                order = ["ntdda", "ddafem"] if k % 2 == 0 else ["ddafem", "ntdda"]
                for code in order:
                    scratch = os.path.join(tmp, f"{code}_{case}_{k}")
                    r = (run_ntdda(os.path.join(tmp, "ntdda"), case, scratch) if code == "ntdda"
                         else run_ddafem(ddafem, case, scratch))
                    results[case][code].append(r)
                    shutil.rmtree(scratch, ignore_errors=True)
                    print(f"run {k + 1}/{args.runs} {case} {code}: {r['ms_per_step']:.4f} ms/step,"
                          f" {r['process_s']:.2f} s, {r['peak_rss_mib']:.0f} MiB", flush=True)
            for name, start_args in STARTS.items():
                starts[name] += [measure_start(ddafem, start_args) for _ in range(3)]
    load_after = os.getloadavg()

    table = {}
    for case in args.cases:
        n, d = medians(results[case]["ntdda"]), medians(results[case]["ddafem"])
        table[case] = {"ntdda": n, "ddafem": d,
                       "per_step_speedup": n["ms_per_step"] / d["ms_per_step"],
                       "process_speedup": n["process_s"] / d["process_s"]}
    record = {"machine": f"{platform.machine()}, {os.cpu_count()} cores",
              "load_average_before": load_before, "load_average_after": load_after,
              "runs": args.runs, "ntdda_revision": revision, "medians": table, "all_runs": results,
              "start_up": {name: medians(r) for name, r in starts.items()},
              "start_up_runs": starts}
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "peers.json"), "w") as f:
        json.dump(record, f, indent=2)
        f.write("\n")
    lines = report(record)
    with open(os.path.join(args.out, "peers.md"), "w") as f:
        f.write("\n".join(lines))
    print("\n".join(lines))


def report(record):
    t = record["medians"]
    lines = [
        "# ddafem beside ntdda",
        "",
        "Generated by `/usr/bin/python3 bench/peer_bench.py --ntdda-git DIR` on "
        f"{record['machine']}: {record['runs']} runs of each code on each case, alternately; "
        f"medians. Load average (1, 5, 15 min) before "
        f"{', '.join(f'{x:.2f}' for x in record['load_average_before'])}, after "
        f"{', '.join(f'{x:.2f}' for x in record['load_average_after'])}. ntdda "
        f"(github.com/doolin/ntdda) at {record['ntdda_revision'][:10]}, built by "
        "`bench/peers/ntdda/build.sh` (-O2).",
        "",
        "| case | ntdda ms/step | ddafem ms/step | per step | ntdda process | ddafem process | "
        "whole process | ntdda memory | ddafem memory |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    names = {"bar": "Bao (2012) bar, 100 bonded blocks x 5000 steps",
             "wall": "bonded wall, 2000 blocks x 200 steps"}
    for case, r in t.items():
        n, d = r["ntdda"], r["ddafem"]
        lines.append(
            f"| {names[case]} | {n['ms_per_step']:.3f} | {d['ms_per_step']:.3f} | "
            f"**{r['per_step_speedup']:.1f}x** | {n['process_s']:.2f} s | {d['process_s']:.2f} s "
            f"| **{r['process_speedup']:.2f}x** | {n['peak_rss_mib']:.0f} MiB | "
            f"{d['peak_rss_mib']:.0f} MiB |")
    lines += [
        "",
        "Per step: ntdda's `ddanalysis` wall time over its steps (contact detection, assembly, "
        "solve, update and its own output: it writes measured points every step and dumps the "
        "first step's matrix); ddafem's phase timings (contact detection, assembly, solve, "
        "update, output at `output.interval=1`) over its steps. Whole process: elapsed time "
        "from start to exit, start-up and input included. Speed-ups are ntdda / ddafem (above 1: ddafem faster). Memory: peak resident "
        "set of the process.",
        "",
        "ntdda needs its sparse-profile capacity raised (FORTY 40 -> 400, `ntdda_run_cap`) to "
        "run the wall at all: stock ntdda overflows that array and aborts.",
        "",
        "## ddafem's start-up",
        "",
        "| command | process (median) | peak memory |",
        "|---|---:|---:|",
    ]
    for name, r in record["start_up"].items():
        command = "ddafem " + " ".join(STARTS[name]).replace(TOP + os.sep, "")
        lines.append(f"| `{command}` | {1e3 * r['process_s']:.1f} ms | "
                     f"{r['peak_rss_mib']:.0f} MiB |")
    lines += [
        "",
        f"{3 * record['runs']} runs each. The far field (deal.II, Trilinos and their ~200 shared "
        "libraries) is a module loaded only for scenes that have one (docs/design.md, \"Two "
        "binaries\").",
        "",
    ]
    return lines


if __name__ == "__main__":
    main()
