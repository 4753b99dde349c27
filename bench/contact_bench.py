#!/usr/bin/python3
"""Times DDA contact mechanics: a 2,020-block dry running-bond wall collapsing under gravity
(bench/scenes/collapsing_wall_50x40.yaml) and, for comparison, the Bao et al. (2012) bar (100
bonded blocks, no contacts). Prints and writes docs/performance/contact_bench.{md,json,png}: time
per step split into broad phase, narrow phase, assembly, solve (the open-close iteration with its
factorizations or CG iterations) and update, open-close iterations per step, time-step cuts and
peak memory, with each `solver.method` (direct, block_pcg), and block_pcg on 1 and 2 threads
(with a check that both give the same histories, bit for bit).

usage: /usr/bin/python3 bench/contact_bench.py [--build build] [--end-time 0.1] [--repeats 5]
                                              [--perf]

The wall runs to a fixed simulated time (default 0.1 s: about 2,700 steps, 5 minutes with `direct`
and under a minute with `block_pcg` on a quiet machine; the engine is deterministic, so the
number of steps is fixed too). `direct` runs once; block_pcg on 1 and 2 threads runs `repeats`
times each, alternately, and the run with the median time per step is reported. --perf also samples
the wall run with `perf record` and lists the hottest functions. Not a test: timings depend on
the machine and its load.
"""
import argparse
import hashlib
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
TARGET_MS = 20.0  # issue 19: the collapsing wall at 2 threads
TARGET_THREAD_SPEEDUP = 1.6  # issue 19: 2 threads against 1 on the collapsing wall
# (name, solver.method, --threads): the wall's runs
RUNS = [("direct", "direct", 2), ("block_pcg_1_thread", "block_pcg", 1),
        ("block_pcg", "block_pcg", 2)]
METHODS = ["direct", "block_pcg"]


def histories_digest(path):
    """SHA-256 over every dataset of a histories file (names and bytes), to compare runs."""
    digest = hashlib.sha256()
    with h5py.File(path, "r") as h:
        def add(name, item):
            if isinstance(item, h5py.Dataset):
                digest.update(name.encode())
                digest.update(item[()].tobytes())
        h.visititems(add)
    return digest.hexdigest()


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
    summary["histories_sha256"] = histories_digest(os.path.join(out, "histories.h5"))
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


def wall_result(wall, wall_counts):
    n_steps = wall["steps"]
    iterations = wall["contacts"]["open_close_iterations"]
    solver = wall["solver"]
    return {
        "blocks": wall["model"]["blocks"], "dofs": wall["model"]["dofs"],
        "simulated_time_s": wall["time_reached_s"], "steps": n_steps,
        "attempts": wall["time_step"]["attempts"], "cuts": wall["time_step"]["cuts"],
        "steps_cut": wall["time_step"]["steps_cut"],
        "smallest_dt_s": wall["time_step"]["smallest_dt_s"],
        "mean_dt_s": wall["time_reached_s"] / n_steps,
        "open_close_iterations": iterations,
        "iterations_per_step": iterations / n_steps,
        "iterations_per_attempt": iterations / wall["time_step"]["attempts"],
        "solver": solver["name"],
        "factorizations": solver["factorizations"],
        "solves": solver["solves"],
        "pcg_solves": solver.get("pcg_solves", 0),
        "pcg_iterations": solver.get("pcg_iterations", 0),
        "pcg_fallbacks": solver.get("pcg_fallbacks", 0),
        "contacts_at_end": wall_counts,
        "ms_per_step": per_step(wall),
        "ms_per_iteration_in_solve": 1e3 * wall["timings_s"]["solve"] / iterations,
        "peak_memory_mb": wall["peak_memory_mb"],
        "wall_time_s": wall["wall_time_s"],
        "cpu_time_s": wall["cpu_s"],
        "status": wall["status"],
        "histories_sha256": wall["histories_sha256"],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--end-time", type=float, default=0.1, help="simulated time of the wall [s]")
    parser.add_argument("--perf", action="store_true", help="profile the wall with perf record")
    parser.add_argument("--repeats", type=int, default=5,
                        help="runs of block_pcg on 1 and 2 threads each, alternately (medians)")
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "performance"))
    parser.add_argument("--previous", metavar="JSON",
                        help="the run to compare with (default: OUT/contact_bench.json as it was "
                             "before this run)")
    parser.add_argument("--render-only", action="store_true",
                        help="contact_bench.md again from OUT/contact_bench.json (and --previous)")
    args = parser.parse_args()
    path = os.path.join(args.out, "contact_bench.json")
    previous = previous_run(args.previous or path)
    if args.render_only:
        with open(path) as f:
            result = json.load(f)
        if args.previous:
            result["previous"] = previous
        write_result(args.out, result, None, None)
        return
    ddafem = os.path.join(args.build, "ddafem")
    use_perf = args.perf and shutil.which("perf") is not None

    # direct once (far from the target); block_pcg on 1 and 2 threads alternately, `repeats`
    # times each, the run of median total reported; perf samples an extra run (it slows it).
    order = [RUNS[0]] + [r for _ in range(args.repeats) for r in RUNS[1:]]
    runs_of, steps_of, profile = {}, {}, []
    with tempfile.TemporaryDirectory() as tmp:
        for k, (name, method, threads) in enumerate(order + ([RUNS[-1]] if use_perf else [])):
            perf_data = os.path.join(tmp, "perf.data") if k == len(order) else None
            wall, steps, counts = run(
                ddafem, WALL, os.path.join(tmp, "wall_" + name),
                ["--set", f"time.end_time={args.end_time}", "--set", "output.history_every=1",
                 "--set", f"output.interval={args.end_time}",
                 "--set", f"solver.method={method}", "--threads", str(threads)], perf_data)
            if perf_data:
                profile = hottest(perf_data)
                continue
            result = wall_result(wall, counts)
            result["threads"] = threads
            runs_of.setdefault(name, []).append(result)
            if name in METHODS:
                steps_of[name] = steps
        bar, _, _ = run(ddafem, BAR, os.path.join(tmp, "bar"), [])
    walls = {}
    for name, runs in runs_of.items():
        totals = [r["ms_per_step"]["total"] for r in runs]
        walls[name] = sorted(runs, key=lambda r: r["ms_per_step"]["total"])[(len(runs) - 1) // 2]
        walls[name]["runs"] = len(runs)
        walls[name]["total_ms_per_step_of_each_run"] = totals
        walls[name]["same_histories_in_every_run"] = \
            len({r["histories_sha256"] for r in runs}) == 1

    bar_ms = per_step(bar)
    result = {
        "machine": f"{platform.machine()}, {os.cpu_count()} cores",
        "load_average": os.getloadavg(),
        "target_ms_per_step": TARGET_MS,
        "target_thread_speedup": TARGET_THREAD_SPEEDUP,
        "thread_speedup": walls["block_pcg_1_thread"]["ms_per_step"]["total"]
        / walls["block_pcg"]["ms_per_step"]["total"],
        "same_histories_on_1_and_2_threads": walls["block_pcg_1_thread"]["histories_sha256"]
        == walls["block_pcg"]["histories_sha256"]
        and walls["block_pcg_1_thread"]["same_histories_in_every_run"]
        and walls["block_pcg"]["same_histories_in_every_run"],
        "repeats": args.repeats,
        "wall": {"scene": WALL, "methods": walls},
        "bar": {
            "scene": BAR, "blocks": bar["model"]["blocks"], "steps": bar["steps"],
            "ms_per_step": bar_ms, "peak_memory_mb": bar["peak_memory_mb"],
            "factorizations": bar["solver"]["factorizations"],
        },
        "perf_hottest": [{"percent": p, "function": f, "method": METHODS[-1]}
                         for p, f in profile],
        "perf": use_perf,
        "previous": previous,
    }
    write_result(args.out, result, steps_of, bar)


def previous_run(path):
    """What the next report compares with of an earlier run's JSON at PATH (None if none): its
    per-step totals and narrow phase, and the bar's step (the machine's speed then)."""
    if not os.path.exists(path):
        return None
    with open(path) as f:
        old = json.load(f)
    walls = old["wall"]["methods"]
    return {"bar_ms_per_step": old["bar"]["ms_per_step"]["total"],
            "total_ms_per_step": {k: w["ms_per_step"]["total"] for k, w in walls.items()},
            "narrow_phase_ms_per_step": {k: w["ms_per_step"]["narrow_phase"]
                                         for k, w in walls.items()},
            "thread_speedup": old["thread_speedup"]}


def write_result(out, result, steps_of, bar):
    """contact_bench.json, .md and (with the runs' steps) .png into OUT."""
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "contact_bench.json"), "w") as f:
        json.dump(result, f, indent=2)
        f.write("\n")
    walls = result["wall"]["methods"]
    bar_ms = result["bar"]["ms_per_step"]
    if steps_of is not None:
        write_figure(out, walls, steps_of, bar, bar_ms)
    profile = [(p["percent"], p["function"]) for p in result["perf_hottest"]]
    lines = report_lines(result, walls, bar_ms, profile, result.get("perf", bool(profile)))
    with open(os.path.join(out, "contact_bench.md"), "w") as f:
        f.write("\n".join(lines))
    print("\n".join(lines))


def write_figure(out, walls, steps_of, bar, bar_ms):
    """Time per step by phase for each method and the bar; iterations and dt per step."""
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(12, 4.5))
    names = PHASES + ["total"]
    x = list(range(len(names)))
    colours = {"direct": "#c44e52", "block_pcg": "#55a868"}
    width = 0.8 / (len(walls) + 1)
    for k, method in enumerate(METHODS):
        w = walls[method]
        ax0.bar([i + (k - 1) * width for i in x], [max(w["ms_per_step"][p], 1e-4) for p in names],
                width=width, color=colours[method],
                label=f"wall, solver.method {method}, {w['threads']} threads")
    ax0.bar([i + (len(METHODS) - 1) * width for i in x], [max(bar_ms[p], 1e-4) for p in names],
            width=width, color="#4c72b0", label=f"bar ({bar['model']['blocks']} bonded blocks)")
    ax0.axhline(TARGET_MS, color="k", ls="--", lw=1, label=f"target {TARGET_MS:g} ms (wall)")
    ax0.set_xticks(x)
    ax0.set_xticklabels([n.replace("_", "\n") for n in names])
    ax0.set_yscale("log")
    ax0.set_ylabel("ms per step")
    ax0.set_title("time per step by phase")
    ax0.legend(fontsize=8)
    for method, steps in steps_of.items():
        index = list(range(1, len(steps["dt"]) + 1))
        ax1.semilogy(index, steps["dt"], color=colours[method], lw=1, label=f"dt, {method}")
    ax1.set_xlabel("step")
    ax1.set_ylabel("dt [s]")
    ax1.set_title("collapsing wall: dt per step")
    ax1.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "contact_bench.png"), dpi=110)


def previous_lines(result, walls, bar_ms):
    """This run against the previous one, the bar's step (an engine path without contacts) as
    the machine's speed then and now."""
    old = result.get("previous")
    if not old:
        return []
    speed = bar_ms["total"] / old["bar_ms_per_step"]
    g, g1 = walls["block_pcg"]["ms_per_step"], walls["block_pcg_1_thread"]["ms_per_step"]
    return [
        "Against the previous run of this benchmark (the JSON this run replaced): block_pcg on 2 "
        f"threads {g['total']:.1f} against {old['total_ms_per_step']['block_pcg']:.1f} ms per "
        f"step, on 1 thread {g1['total']:.1f} against "
        f"{old['total_ms_per_step']['block_pcg_1_thread']:.1f}, the narrow phase on 2 threads "
        f"{g['narrow_phase']:.2f} against {old['narrow_phase_ms_per_step']['block_pcg']:.2f}, "
        f"2 threads against 1 {result['thread_speedup']:.2f} against "
        f"{old['thread_speedup']:.2f} times. The bar's step took {bar_ms['total']:.3f} against "
        f"{old['bar_ms_per_step']:.3f} ms, one run each, a rough gauge of the machine's speed: "
        f"{speed:.2f} times " + ("slower" if speed >= 1 else "faster") + " than then (this "
        "2-core machine runs some processes about a third slower than others, and the two "
        "runs' wall columns cannot be compared closer than that).", ""]


def report_lines(result, walls, bar_ms, profile, use_perf):
    d, g1, g = walls["direct"], walls["block_pcg_1_thread"], walls["block_pcg"]
    cols = [d, g1, g]
    bar = result["bar"]

    def row(label, values, last=""):
        return f"| {label} | " + " | ".join(values) + f" | {last} |"

    lines = [
        "# Contact benchmark: a collapsing 2,000-block wall",
        "",
        f"Generated by `/usr/bin/python3 bench/contact_bench.py{' --perf' if use_perf else ''}` "
        f"on {result['machine']} (load average {result['load_average'][0]:.2f} at the end; "
        "timings vary by tens of percent on a shared machine). `direct` ran once; block_pcg on "
        f"1 and 2 threads ran {result['repeats']} times each, alternately, and each column shows "
        "the run of median time per step (the totals of every run: "
        + "; ".join(f"{w['threads']} thread{'s' if w['threads'] > 1 else ''} "
                    + ", ".join(f"{t:.1f}" for t in w["total_ms_per_step_of_each_run"])
                    for w in (g1, g)) + " ms).",
        "",
        f"Scene `{WALL}` (written by `bench/scenes/make_collapsing_wall.py`): 50 x 40 dry "
        "running-bond wall of 1 m x 0.5 m bricks, frictional joints (phi 30 deg, no cohesion, "
        "p = 1e10 N/m), a fixed base under its left half only and a fixed floor 3 m below the "
        "right half; all bricks start touching. Adaptive dt from 1 ms, step displacement bound "
        "1.06 cm, up to 6 open-close iterations (Shi). Run with each `solver.method`, and "
        "block_pcg on 1 and 2 threads (`--threads`).",
        "",
        "| | wall, direct, 2 threads | wall, block_pcg, 1 thread | wall, block_pcg, 2 threads "
        "| bar (bonded, no contacts), direct |",
        "|---|---:|---:|---:|---:|",
        row("blocks", [str(w["blocks"]) for w in cols], str(bar["blocks"])),
        row("steps", [f"{w['steps']} (to t = {w['simulated_time_s']:.4g} s)" for w in cols],
            str(bar["steps"])),
        row("attempts (steps tried)", [str(w["attempts"]) for w in cols]),
    ]
    for phase in PHASES:
        lines.append(row(f"{phase.replace('_', ' ')} [ms/step]",
                         [f"{w['ms_per_step'][phase]:.2f}" for w in cols],
                         f"{bar_ms[phase]:.4f}"))
    lines += [
        row("**total [ms/step]**", [f"**{w['ms_per_step']['total']:.1f}**" for w in cols],
            f"**{bar_ms['total']:.3f}**"),
        row("open-close iterations per step", [f"{w['iterations_per_step']:.2f}" for w in cols]),
        row("factorizations / triangular solves",
            [f"{w['factorizations']} / {w['solves']}" for w in cols], str(bar["factorizations"])),
        row("CG solves / iterations / fallbacks",
            [""] + [f"{w['pcg_solves']} / {w['pcg_iterations']} / {w['pcg_fallbacks']}"
                    for w in (g1, g)]),
        row("solve per open-close iteration [ms]",
            [f"{w['ms_per_iteration_in_solve']:.2f}" for w in cols]),
        row("peak memory [MB]", [f"{w['peak_memory_mb']:.0f}" for w in cols],
            f"{bar['peak_memory_mb']:.0f}"),
        row("run [s] elapsed / CPU", [f"{w['wall_time_s']:.0f} / {w['cpu_time_s']:.0f}"
                                      for w in cols]),
        "",
        f"**Two threads against one (block_pcg): {result['thread_speedup']:.2f} times** "
        f"(target {TARGET_THREAD_SPEEDUP:g}); the histories of the two runs are "
        + ("the same, bit for bit." if result["same_histories_on_1_and_2_threads"]
           else "**not** the same (a bug: they must be)."),
        "",
        "The collapse is chaotic: the two methods' solutions differ by their tolerances (1e-9 "
        "of ||b|| after refinement on reused factors; 1e-10 in the diagonal blocks' norm), and "
        "the runs take different numbers of steps to the same time (mean dt "
        f"{d['mean_dt_s']:.3g} s and {g['mean_dt_s']:.3g} s; {d['cuts']} and {g['cuts']} cuts). "
        "Over the first 100 steps of a 46-block collapsing wall they take the same open-close "
        "iterations and contact states at every step and vertices within 1.2e-8 m "
        "(`Contacts.BlockPcgFollowsTheDirectSolver`).",
        "",
        f"Target: under {TARGET_MS:g} ms per step on 2 cores. "
        + (f"Met with block_pcg ({g['ms_per_step']['total']:.1f} ms)."
           if g["ms_per_step"]["total"] < TARGET_MS else
           f"**Not met yet: {g['ms_per_step']['total']:.0f} ms per step with block_pcg on 2 "
           f"threads, {g['ms_per_step']['total'] / TARGET_MS:.1f} times the target.**"),
        "",
    ] + previous_lines(result, walls, bar_ms) + [
        "![time per step and dt](contact_bench.png)",
        "",
        "## Why",
        "",
        f"With `direct`, the solve is {100 * d['ms_per_step']['solve'] / d['ms_per_step']['total']:.0f}% "
        "of the step: every open-close iteration after a change of contact states changes the "
        "matrix by the springs of the contacts that opened, closed or started to slide (1e10 "
        "N/m, of the order of a brick's mass term rho A / (beta dt^2) = 4e10 N/m at dt = 0.25 "
        "ms), so the reused factors precondition CG poorly and the matrix is factorized again "
        f"({d['factorizations'] / d['steps']:.1f} factorizations and "
        f"{d['solves'] / d['steps']:.0f} triangular solves per step). With `block_pcg` the "
        "preconditioner is the inverse of each block's 6x6 diagonal, rebuilt in one pass, and CG "
        "starts from the last solution: "
        f"{g['pcg_iterations'] / max(g['pcg_solves'], 1):.0f} iterations per solve, no "
        f"factorization, {d['ms_per_step']['solve'] / max(g['ms_per_step']['solve'], 1e-9):.1f} "
        "times less solve time per step. What remains: the solve itself (CG's products and "
        "preconditioner on the threads, and the contacts' trial states; on one, the contact "
        "springs of the blocks whose contacts changed state and every contact's force), then the "
        "narrow phase "
        f"({g['ms_per_step']['narrow_phase']:.1f} ms per step on 2 threads; a step's first "
        "attempt finds the vertex-edge pairs of every candidate block pair and matches about "
        "12,000 contacts to the previous step's, its retries reuse that), then broad phase, "
        "assembly and update near or below 1 ms each.",
        "",
        "The bar (bonded joints, no contacts, matrix unchanged in structure) reuses one "
        "factorization for all its steps with `direct`; its cost per step is the reference of "
        "the engine without contacts.",
        "",
    ]
    if profile:
        lines += [f"## Where the time goes (perf, self time of the {METHODS[-1]} wall run)", "",
                  "| % | function |", "|---:|---|"]
        lines += [f"| {p:.1f} | `{f}` |" for p, f in profile]
        lines.append("")
    return lines


if __name__ == "__main__":
    main()
