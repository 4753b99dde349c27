#!/usr/bin/python3
"""Times DDA contact mechanics: a 2,020-block dry running-bond wall collapsing under gravity
(bench/scenes/collapsing_wall_50x40.yaml) and, for comparison, the Bao et al. (2012) bar (100
bonded blocks, no contacts). Prints and writes docs/performance/contact_bench.{md,json,png}: time
per step split into broad phase, narrow phase, assembly, solve (the open-close iteration with its
factorizations) and update, open-close iterations per step, time-step cuts and peak memory.

usage: /usr/bin/python3 bench/contact_bench.py [--build build] [--end-time 0.1] [--perf]

The wall runs to a fixed simulated time (default 0.1 s: about 460 steps, 75 s on a quiet
machine; the engine is deterministic, so the number of steps is fixed too). --perf also samples
the wall run with `perf record` and lists the hottest functions. Not a test: timings depend on
the machine and its load.
"""
import argparse
import json
import os
import platform
import re
import resource
import shutil
import subprocess
import tempfile

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WALL = "bench/scenes/collapsing_wall_50x40.yaml"
BAR = "examples/bao2012/p_wave_bar.yaml"
PHASES = ["broad_phase", "narrow_phase", "assemble", "solve", "update", "output"]
TARGET_MS = 5.0


def run(ddafem, scene, out, extra, perf_data=None):
    cmd = [ddafem, "run", os.path.join(TOP, scene), "-o", out, "--quiet"] + extra
    if perf_data:
        cmd = ["perf", "record", "-F", "499", "-g", "-o", perf_data, "--"] + cmd
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise SystemExit(f"failed: {' '.join(cmd)}\n{proc.stderr}")
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    summary["cpu_s"] = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    with h5py.File(os.path.join(out, "histories.h5"), "r") as h:
        steps = {"time": h["time"][1:].tolist(), "dt": h["steps/dt"][1:].tolist(),
                 "iterations": h["steps/open_close_iterations"][1:].tolist()}
        counts = {k: int(h["contacts/" + k][-1]) for k in ("open", "slide", "lock")}
    return summary, steps, counts


def per_step(summary):
    n = summary["steps"]
    t = summary["timings_s"]
    ms = {p: 1e3 * t[p] / n for p in PHASES}
    ms["total"] = sum(ms.values())
    return ms


def hottest(perf_data, n=12):
    """The functions with the most samples (self time), as (percent, name)."""
    out = subprocess.run(["perf", "report", "-i", perf_data, "--stdio", "--no-children",
                          "--sort", "symbol", "-g", "none"],
                         capture_output=True, text=True).stdout
    rows = []
    for line in out.splitlines():
        line = line.strip()
        if not line or line.startswith("#") or "%" not in line:
            continue
        percent, _, rest = line.partition("%")
        try:
            value = float(percent)
        except ValueError:
            continue
        name = re.split(r"\s{2,}", rest.split("]", 1)[-1].strip())[0]
        name = name.replace("ddafem::dda::", "").replace("(anonymous namespace)::", "")
        name = name.split("(")[0].strip()[:90]
        if name:
            rows.append((value, name))
        if len(rows) == n:
            break
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--end-time", type=float, default=0.1, help="simulated time of the wall [s]")
    parser.add_argument("--perf", action="store_true", help="profile the wall with perf record")
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "performance"))
    args = parser.parse_args()
    ddafem = os.path.join(args.build, "ddafem")
    use_perf = args.perf and shutil.which("perf") is not None

    with tempfile.TemporaryDirectory() as tmp:
        perf_data = os.path.join(tmp, "perf.data") if use_perf else None
        wall, wall_steps, wall_counts = run(
            ddafem, WALL, os.path.join(tmp, "wall"),
            ["--set", f"time.end_time={args.end_time}", "--set", "output.history_every=1",
             "--set", f"output.interval={args.end_time}"], perf_data)
        profile = hottest(perf_data) if use_perf else []
        bar, _, _ = run(ddafem, BAR, os.path.join(tmp, "bar"), [])

    wall_ms, bar_ms = per_step(wall), per_step(bar)
    n_steps = wall["steps"]
    iterations = wall["contacts"]["open_close_iterations"]
    result = {
        "machine": f"{platform.machine()}, {os.cpu_count()} cores",
        "target_ms_per_step": TARGET_MS,
        "wall": {
            "scene": WALL, "blocks": wall["model"]["blocks"], "dofs": wall["model"]["dofs"],
            "simulated_time_s": wall["time_reached_s"], "steps": n_steps,
            "attempts": wall["time_step"]["attempts"], "cuts": wall["time_step"]["cuts"],
            "steps_cut": wall["time_step"]["steps_cut"],
            "smallest_dt_s": wall["time_step"]["smallest_dt_s"],
            "mean_dt_s": wall["time_reached_s"] / n_steps,
            "open_close_iterations": iterations,
            "iterations_per_step": iterations / n_steps,
            "iterations_per_attempt": iterations / wall["time_step"]["attempts"],
            "factorizations": wall["solver"]["factorizations"],
            "solves": wall["solver"]["solves"],
            "contacts_at_end": wall_counts,
            "ms_per_step": wall_ms,
            "ms_per_iteration_in_solve": 1e3 * wall["timings_s"]["solve"] / iterations,
            "peak_memory_mb": wall["peak_memory_mb"],
            "wall_time_s": wall["wall_time_s"],
            "cpu_time_s": wall["cpu_s"],
            "status": wall["status"],
        },
        "bar": {
            "scene": BAR, "blocks": bar["model"]["blocks"], "steps": bar["steps"],
            "ms_per_step": bar_ms, "peak_memory_mb": bar["peak_memory_mb"],
            "factorizations": bar["solver"]["factorizations"],
        },
        "perf_hottest": [{"percent": p, "function": f} for p, f in profile],
    }
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "contact_bench.json"), "w") as f:
        json.dump(result, f, indent=2)
        f.write("\n")

    # Figure: time per step by phase; open-close iterations and dt per step.
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(12, 4.5))
    names = PHASES + ["total"]
    x = list(range(len(names)))
    ax0.bar([i - 0.2 for i in x], [max(wall_ms[p], 1e-4) for p in names], width=0.4,
            color="#c44e52", label=f"wall ({wall['model']['blocks']} blocks, contacts)")
    ax0.bar([i + 0.2 for i in x], [max(bar_ms[p], 1e-4) for p in names], width=0.4,
            color="#4c72b0", label=f"bar ({bar['model']['blocks']} bonded blocks)")
    ax0.axhline(TARGET_MS, color="k", ls="--", lw=1, label=f"target {TARGET_MS:g} ms (wall)")
    ax0.set_xticks(x)
    ax0.set_xticklabels([n.replace("_", "\n") for n in names])
    ax0.set_yscale("log")
    ax0.set_ylabel("ms per step")
    ax0.set_title("time per step by phase")
    ax0.legend(fontsize=8)
    step_index = list(range(1, len(wall_steps["iterations"]) + 1))
    ax1.plot(step_index, wall_steps["iterations"], ".", color="#c44e52", ms=3,
             label="open-close iterations (accepted attempt)")
    ax1.set_xlabel("step")
    ax1.set_ylabel("iterations")
    ax1.set_title(f"collapsing wall: {n_steps} steps to t = {wall['time_reached_s']:.3g} s")
    ax2 = ax1.twinx()
    ax2.semilogy(step_index, wall_steps["dt"], color="#4c72b0", lw=1, label="dt [s]")
    ax2.set_ylabel("dt [s]")
    h1, l1 = ax1.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax1.set_ylim(0, max(wall_steps["iterations"]) + 2)
    ax1.legend(h1 + h2, l1 + l2, fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "contact_bench.png"), dpi=110)

    w = result["wall"]
    lines = [
        "# Contact benchmark: a collapsing 2,000-block wall",
        "",
        f"Generated by `/usr/bin/python3 bench/contact_bench.py{' --perf' if use_perf else ''}` "
        f"on {result['machine']} (shared with other jobs: timings vary by tens of percent).",
        "",
        f"Scene `{WALL}` (written by `bench/scenes/make_collapsing_wall.py`): 50 x 40 dry "
        "running-bond wall of 1 m x 0.5 m bricks, frictional joints (phi 30 deg, no cohesion, "
        "p = 1e10 N/m), a fixed base under its left half only and a fixed floor 3 m below the "
        "right half; all bricks start touching. Adaptive dt from 1 ms, step displacement bound "
        "1.06 cm, up to 6 open-close iterations (Shi).",
        "",
        "| | wall | bar (bonded, no contacts) |",
        "|---|---:|---:|",
        f"| blocks | {w['blocks']} | {result['bar']['blocks']} |",
        f"| steps | {n_steps} (to t = {w['simulated_time_s']:.4g} s) | {result['bar']['steps']} |",
    ]
    for phase in PHASES:
        lines.append(f"| {phase.replace('_', ' ')} [ms/step] | {wall_ms[phase]:.2f} | "
                     f"{bar_ms[phase]:.4f} |")
    lines += [
        f"| **total [ms/step]** | **{wall_ms['total']:.1f}** | **{bar_ms['total']:.3f}** |",
        f"| peak memory [MB] | {w['peak_memory_mb']:.0f} | "
        f"{result['bar']['peak_memory_mb']:.0f} |",
        "",
        f"Wall: {w['iterations_per_step']:.2f} open-close iterations per accepted step "
        f"({w['iterations_per_attempt']:.2f} per attempt), {w['attempts']} attempts for "
        f"{n_steps} steps ({w['cuts']} cuts of dt, {w['steps_cut']} steps needed one), mean dt "
        f"{w['mean_dt_s']:.3g} s, smallest {w['smallest_dt_s']:.3g} s; "
        f"{w['factorizations']} factorizations and {w['solves']} solves; "
        f"{w['ms_per_iteration_in_solve']:.1f} ms of solve per open-close iteration. Contacts at "
        f"the end: {w['contacts_at_end']['lock']} locked, {w['contacts_at_end']['slide']} "
        f"sliding, {w['contacts_at_end']['open']} open. The run took {w['wall_time_s']:.0f} s "
        f"and {w['cpu_time_s']:.0f} s of CPU (the phase timings are elapsed times: on a loaded "
        "machine they include waiting; the engine runs on one thread).",
        "",
        f"Target: under {TARGET_MS:g} ms per step on 2 cores. "
        + (f"Met ({wall_ms['total']:.1f} ms)." if wall_ms["total"] < TARGET_MS else
           f"**Not met: {wall_ms['total']:.0f} ms per step, {wall_ms['total'] / TARGET_MS:.0f} "
           "times the target.**"),
        "",
        "![time per step and iterations](contact_bench.png)",
        "",
        "## Why",
        "",
        f"The solve phase is {100 * wall_ms['solve'] / wall_ms['total']:.0f}% of the step. It is "
        "the open-close iteration: every iteration after a change of contact states changes "
        "the matrix by the springs of the contacts that opened, closed or started to slide "
        "(1e10 N/m, of the order of the mass term rho A / (beta dt^2) = 4e10 N/m of a brick at "
        "dt = 0.25 ms), so FactorizationReusingSolver either iterates on the previous factors "
        f"or factorizes the {w['dofs']}-unknown matrix again: {w['factorizations']} "
        f"factorizations ({w['factorizations'] / n_steps:.1f} per step) and {w['solves']} "
        f"triangular solves ({w['solves'] / n_steps:.0f} per step) in {n_steps} steps, "
        f"{w['ms_per_iteration_in_solve']:.0f} ms of solve per open-close iteration. Next comes "
        f"the narrow phase, {wall_ms['narrow_phase']:.0f} ms per step, itself above the target: "
        "each attempt finds the vertex-edge pairs of every candidate block pair, matches about "
        "12,000 contacts to the previous step's (sorted) and rebuilds the matrix structure. "
        "Broad phase, assembly and update stay near or below 1 ms. Reaching 5 ms per step needs "
        "far fewer factorizations and triangular solves per step (fewer open-close iterations, "
        "a cheaper update of the factors for a few changed contacts) and a narrow phase that "
        "only revisits pairs whose blocks moved.",
        "",
        "The bar (bonded joints, no contacts, matrix unchanged in structure) reuses one "
        "factorization for all its steps; its cost per step is the reference of the engine "
        "without contacts.",
        "",
    ]
    if profile:
        lines += ["## Where the time goes (perf, self time of the wall run)", "",
                  "| % | function |", "|---:|---|"]
        lines += [f"| {p:.1f} | `{f}` |" for p, f in profile]
        lines.append("")
    with open(os.path.join(args.out, "contact_bench.md"), "w") as f:
        f.write("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
