#!/usr/bin/python3
"""The tunnel scenes' speed against a start commit (issue 54), measured side by side in one
invocation: writes docs/performance/tunnel_bench.{md,json,png}.

The start commit is checked out in a git worktree beside this tree (build/tunnel_bench/start)
and built there (or --start-build names a build of it). Both builds run the start commit's own
scene files; the current build with block damping off (`--set tunnel.damping.ratio=0`, the
start commit has no block damping). Each case runs on --variants round-off variants, the
incident wave's amplitude times 1 + k 1e-12 (k = 0, 1, ...), start and current alternating
(A B A B: load that comes and goes hits both). A tunnel near the Mohr-Coulomb limit branches on
round-off, so single runs of one build differ by tens of percent in their steps: the medians of
the total wall time and of the wall time per step attempt (summary.json's
time_step.attempts) are compared, and their ratios are the result, never absolute times. The
load average is recorded before and after each run, the profile by phase from summary.json.

Cases (the issue's acceptance in brackets):
  default            examples/tunnel/circular_sv.yaml   [total >= 5x, per attempt >= 4x]
  default_threads1   the same, --threads 1 for both     [total >= 4x]
  horseshoe          examples/tunnel/horseshoe_p.yaml   [total >= 3x]
  stable             examples/tunnel/stable_sv.yaml     [total >= 3x]

usage: /usr/bin/python3 bench/tunnel_bench.py [--start 32f44ae] [--start-build DIR]
           [--build build] [--variants 4] [--cases default,...] [--out docs/performance]

Not part of CI (minutes to hours, and timings depend on the machine and its load).
"""
import argparse
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
START = "32f44ae"  # the commit at which issue 54 was filed
CASES = {
    # name: (scene in the start commit, extra options for both builds, required total ratio,
    #        required ratio per step attempt or None)
    "default": ("examples/tunnel/circular_sv.yaml", [], 5.0, 4.0),
    "default_threads1": ("examples/tunnel/circular_sv.yaml", ["--threads", "1"], 4.0, None),
    "horseshoe": ("examples/tunnel/horseshoe_p.yaml", [], 3.0, None),
    "stable": ("examples/tunnel/stable_sv.yaml", [], 3.0, None),
}
# The phases of summary.json's timings_s (seconds of the whole run); tie_terms is part of solve.
PHASES = ["broad_phase", "narrow_phase", "assemble", "solve", "tie_terms", "tied_body", "update",
          "output"]
AMPLITUDE_KEY = "tunnel.wave.velocity.amplitude"


def git(*args, cwd=TOP):
    return subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True,
                          text=True).stdout.strip()


def start_build(start, build_dir):
    """The start commit's ddafem: build_dir/ddafem if given, else the worktree
    build/tunnel_bench/start at `start`, configured and built (incrementally) there."""
    if build_dir:
        exe = os.path.join(os.path.abspath(build_dir), "ddafem")
        if not os.access(exe, os.X_OK):
            sys.exit(f"--start-build {build_dir}: no executable ddafem there")
        return exe
    tree = os.path.join(TOP, "build", "tunnel_bench", "start")
    if not os.path.isdir(tree):
        git("worktree", "add", "--detach", tree, start)
    if git("rev-parse", "HEAD", cwd=tree) != git("rev-parse", start):
        git("checkout", "--detach", start, cwd=tree)
    build = os.path.join(tree, "build")
    if not os.path.isfile(os.path.join(build, "CMakeCache.txt")):
        subprocess.run(["cmake", "-S", tree, "-B", build, "-DCMAKE_BUILD_TYPE=Release"],
                       check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", build, "-j", str(os.cpu_count() or 2), "--target",
                    "ddafem", "ddafem_far_field"], check=True, stdout=subprocess.DEVNULL)
    return os.path.join(build, "ddafem")


def scene_of(start, path, work):
    """The start commit's own copy of a scene file, written into the work folder."""
    text = git("show", f"{start}:{path}")
    out = os.path.join(work, "scenes", os.path.basename(path))
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(out, "w") as f:
        f.write(text + "\n")
    return out


def amplitude_of(scene):
    """The incident wave's velocity amplitude [m/s] of a tunnel scene: the first `amplitude:`
    after `wave:` (the tunnel scenes write the wave's velocity on one line)."""
    with open(scene) as f:
        text = f.read()
    found = re.search(r"\bwave:.*?\bamplitude:\s*([-+0-9.eE]+)", text, re.S)
    if not found:
        sys.exit(f"{scene}: no tunnel.wave.velocity.amplitude found")
    return float(found.group(1))


def run_once(exe, scene, out, options):
    """One run: wall time of the process [s], the load average before and after, and the parts
    of summary.json the bench reports."""
    load_before = os.getloadavg()[0]
    t0 = time.perf_counter()
    proc = subprocess.run([exe, "run", scene, "-o", out, "--quiet", *options],
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        sys.exit(f"failed ({proc.returncode}): {exe} run {scene} {' '.join(options)}\n"
                 f"{proc.stderr[-2000:]}")
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    fell = sorted(b["id"] for b in s.get("keyblocks", {}).get("blocks", []) if b.get("fell"))
    loosened = sorted(b["id"] for b in s.get("keyblocks", {}).get("blocks", [])
                      if b.get("loosened"))
    return {"wall_s": wall, "summary_wall_s": s["wall_time_s"],
            "attempts": s["time_step"]["attempts"], "steps": s["steps"],
            "per_attempt_ms": 1e3 * wall / s["time_step"]["attempts"],
            "phases_s": {p: s["timings_s"].get(p, 0.0) for p in PHASES},
            "fell": fell, "loosened": loosened,
            "load_before": load_before, "load_after": os.getloadavg()[0]}


def run_case(name, exes, start, variants, work):
    """Both builds on the case's variants, alternating; returns the runs of each build."""
    path, extra, _, _ = CASES[name]
    scene = scene_of(start, path, work)
    amplitude = amplitude_of(scene)
    runs = {"start": [], "current": []}
    for k in range(variants):
        value = repr(amplitude * (1.0 + k * 1e-12))
        for build in ("start", "current"):
            options = [*extra, "--set", f"{AMPLITUDE_KEY}={value}"]
            if build == "current":
                options += ["--set", "tunnel.damping.ratio=0"]
            out = os.path.join(work, "runs", f"{name}_{build}_{k}")
            r = run_once(exes[build], scene, out, options)
            r["variant"] = k
            runs[build].append(r)
            print(f"{name} k={k} {build}: {r['wall_s']:.1f} s, {r['attempts']} attempts, "
                  f"{r['per_attempt_ms']:.2f} ms/attempt, load {r['load_before']:.2f}",
                  flush=True)
    return runs


def ensemble_pace(exe, work, members):
    """Must-have 2: an ensemble of the stable tunnel (round-off members, one thread each) run
    one member at a time and then on all cores; its wall time on the cores against the sum of
    the members' wall times alone, divided by the cores."""
    scene = os.path.join(TOP, "examples", "tunnel", "stable_sv.yaml")
    cores = os.cpu_count() or 1
    record = {"scene": os.path.relpath(scene, TOP), "members": members, "cores": cores}
    for jobs in (1, cores):
        out = os.path.join(work, "runs", f"ensemble_j{jobs}")
        load = os.getloadavg()[0]
        t0 = time.perf_counter()
        subprocess.run([exe, "ensemble", scene, "-n", str(members), "--roundoff", "-j",
                        str(jobs), "--threads", "1", "-q", "-o", out], check=True,
                       stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - t0
        member_walls = []
        for k in range(members):
            with open(os.path.join(out, f"member_{k:03d}", "summary.json")) as f:
                member_walls.append(json.load(f)["wall_time_s"])
        record[f"j{jobs}"] = {"wall_s": wall, "member_walls_s": member_walls, "load": load}
        print(f"ensemble -j {jobs}: {wall:.1f} s, members {sum(member_walls):.1f} s in all",
              flush=True)
    alone = sum(record["j1"]["member_walls_s"])
    record["ratio"] = record[f"j{cores}"]["wall_s"] / (alone / cores)
    record["met"] = record["ratio"] <= 1.1
    return record


def medians(runs):
    return {"wall_s": statistics.median(r["wall_s"] for r in runs),
            "per_attempt_ms": statistics.median(r["per_attempt_ms"] for r in runs),
            "attempts": statistics.median(r["attempts"] for r in runs),
            "phases_s": {p: statistics.median(r["phases_s"][p] for r in runs) for p in PHASES}}


def summarize(name, runs):
    """Medians, ratios (start / current) and the acceptance of one case."""
    _, _, need_total, need_attempt = CASES[name]
    a, b = medians(runs["start"]), medians(runs["current"])
    ratio_total = a["wall_s"] / b["wall_s"]
    ratio_attempt = a["per_attempt_ms"] / b["per_attempt_ms"]
    pairs = [s["wall_s"] / c["wall_s"] for s, c in zip(runs["start"], runs["current"])]
    return {"start": a, "current": b, "ratio_total": ratio_total,
            "ratio_per_attempt": ratio_attempt, "ratio_of_pairs": pairs,
            "required_total": need_total, "required_per_attempt": need_attempt,
            "met": ratio_total >= need_total and (need_attempt is None
                                                 or ratio_attempt >= need_attempt),
            "fell": {build: [r["fell"] for r in runs[build]] for build in runs},
            "loosened": {build: [r["loosened"] for r in runs[build]] for build in runs},
            "load": [r["load_before"] for build in runs for r in runs[build]]}


def figure(results, path):
    names = list(results)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.2))
    x = range(len(names))
    ax.bar([i - 0.2 for i in x], [results[n]["ratio_total"] for n in names], 0.4,
           label="total wall time")
    ax.bar([i + 0.2 for i in x], [results[n]["ratio_per_attempt"] for n in names], 0.4,
           label="wall time per step attempt")
    for i, n in enumerate(names):
        ax.hlines(results[n]["required_total"], i - 0.4, i + 0.4, colors="k", linestyles="--")
    ax.set_xticks(list(x))
    ax.set_xticklabels(names, fontsize=8)
    ax.set_ylabel("start / current (median)")
    ax.set_title("speed-up against the start commit (dashed: required)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, axis="y")
    case = "default" if "default" in results else names[0]
    colors = plt.cm.tab10.colors
    for row, build in enumerate(("start", "current")):
        left = 0.0
        phases = results[case][build]["phases_s"]
        for k, p in enumerate(q for q in PHASES if q != "tie_terms"):
            bx.barh(row, phases[p], left=left, color=colors[k], label=p if row == 0 else None)
            left += phases[p]
    bx.set_yticks([0, 1])
    bx.set_yticklabels(["start", "current"])
    bx.set_xlabel("median seconds per run")
    bx.set_title(f"{case}: time by phase")
    bx.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def markdown(doc):
    lines = [
        "# The tunnels against the start commit (issue 54)",
        "",
        f"Start commit `{doc['start']}`, current `{doc['current']}`; {doc['variants']} "
        "round-off variants per case (incident amplitude x (1 + k 1e-12)), the two builds "
        f"alternating; the current build with `--set tunnel.damping.ratio=0`. "
        f"{doc['machine']}, {doc['cores']} cores; the load average before the runs "
        f"{min(doc['loads']):.2f} to {max(doc['loads']):.2f}. Generated by "
        "`/usr/bin/python3 bench/tunnel_bench.py`.",
        "",
        "| case | start wall [s] | current wall [s] | ratio (req.) | start ms/attempt | "
        "current ms/attempt | ratio (req.) | attempts start / current | met |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    for name, r in doc["results"].items():
        a, b = r["start"], r["current"]
        req_a = f" ({r['required_per_attempt']:g}x)" if r["required_per_attempt"] else ""
        lines.append(
            f"| {name} | {a['wall_s']:.1f} | {b['wall_s']:.1f} | {r['ratio_total']:.2f} "
            f"({r['required_total']:g}x) | {a['per_attempt_ms']:.2f} | {b['per_attempt_ms']:.2f} "
            f"| {r['ratio_per_attempt']:.2f}{req_a} | {a['attempts']:.0f} / {b['attempts']:.0f} "
            f"| {'yes' if r['met'] else 'no'} |")
    lines += ["", "Per pair (start / current, same variant): " + "; ".join(
        f"{n}: " + ", ".join(f"{x:.2f}" for x in r["ratio_of_pairs"])
        for n, r in doc["results"].items()) + ".", "", "## Time by phase (medians) [s]", "",
              "| case | build | " + " | ".join(PHASES) + " |",
              "|---|---|" + "---:|" * len(PHASES)]
    for name, r in doc["results"].items():
        for build in ("start", "current"):
            ph = r[build]["phases_s"]
            lines.append(f"| {name} | {build} | " + " | ".join(f"{ph[p]:.2f}" for p in PHASES)
                         + " |")
    lines += ["", "`tie_terms` is part of `solve`; `tied_body` (the far field and the ties' "
              "algebra) runs beside the contact phases on a thread of its own.", "",
              "## Verdicts", "", "| case | build | fallen blocks per variant | "
              "loosened keyblocks per variant |", "|---|---|---|---|"]
    for name, r in doc["results"].items():
        for build in ("start", "current"):
            lines.append(f"| {name} | {build} | {r['fell'][build]} | "
                         f"{[len(x) for x in r['loosened'][build]]} |")
    pace = doc.get("ensemble_pace")
    if pace:
        cores = pace["cores"]
        lines += ["", "## Ensembles at the pace of the cores", "",
                  f"`ddafem ensemble {pace['scene']} -n {pace['members']} --roundoff --threads 1`"
                  f": one member at a time, {pace['j1']['wall_s']:.1f} s (the members' wall "
                  f"times sum to {sum(pace['j1']['member_walls_s']):.1f} s); with -j {cores}, "
                  f"{pace[f'j{cores}']['wall_s']:.1f} s: {pace['ratio']:.2f} x (the sum alone) / "
                  f"{cores} cores (required at most 1.1: {'met' if pace['met'] else 'not met'})."]
    lines += ["", "![tunnel bench](tunnel_bench.png)", ""]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--start", default=START)
    parser.add_argument("--start-build", default=None,
                        help="a build folder of the start commit (default: build it)")
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--variants", type=int, default=4)
    parser.add_argument("--cases", default=",".join(CASES))
    parser.add_argument("--members", type=int, default=4,
                        help="members of the ensemble-pace measurement (0: none)")
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "performance"))
    parser.add_argument("--work", default=os.path.join(TOP, "build", "tunnel_bench", "work"))
    args = parser.parse_args()
    cases = args.cases.split(",")
    unknown = [c for c in cases if c not in CASES]
    if unknown:
        sys.exit(f"--cases: unknown {unknown}, expected some of {list(CASES)}")
    exes = {"start": start_build(args.start, args.start_build),
            "current": os.path.join(os.path.abspath(args.build), "ddafem")}
    os.makedirs(args.work, exist_ok=True)
    results = {c: summarize(c, run_case(c, exes, args.start, args.variants, args.work))
               for c in cases}
    pace = ensemble_pace(exes["current"], args.work, args.members) if args.members else None
    doc = {"start": git("rev-parse", "--short", args.start),
           "current": git("rev-parse", "--short", "HEAD"), "variants": args.variants,
           "machine": platform.platform(), "cores": os.cpu_count(),
           "loads": [x for r in results.values() for x in r["load"]], "results": results,
           "ensemble_pace": pace}
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "tunnel_bench.json"), "w") as f:
        json.dump(doc, f, indent=1)
    with open(os.path.join(args.out, "tunnel_bench.md"), "w") as f:
        f.write(markdown(doc))
    figure(results, os.path.join(args.out, "tunnel_bench.png"))
    print(markdown(doc))


if __name__ == "__main__":
    main()
