#!/usr/bin/python3
"""Times the DDA engine: the Bao et al. (2012) bar (100 blocks, 5000 steps) and a bonded
50 x 40 wall (2000 blocks), with each sparse direct solver. Prints microseconds per block per
step split into contact detection (broad and narrow phase), assembly, solve, block update and
output, and the peak memory of each run, and writes docs/performance/dda_bench.{csv,md,png}.

usage: /usr/bin/python3 bench/dda_bench.py [--build build] [--quick]
Not a test: timings depend on the machine. The comparison with a peer code (ntdda, Shi's DDA in
C) is measured side by side by bench/peer_bench.py (docs/performance/peers.md); its medians are
quoted here when docs/performance/peers.json exists.
"""
import argparse
import csv
import json
import os
import platform
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PHASES = ["contacts", "assemble", "solve", "update", "output"]

SMALL = ["--set", "analysis.geometry=small_displacement"]
CASES = [
    ("bar_100", "examples/bao2012/p_wave_bar.yaml", []),
    ("bar_100_small_disp", "examples/bao2012/p_wave_bar.yaml", SMALL),
    ("wall_2000", "bench/scenes/wall_50x40.yaml", []),
    ("wall_2000_small_disp", "bench/scenes/wall_50x40.yaml", SMALL),
]
SOLVERS = ["eigen_ldlt", "klu", "block_ldlt"]


def solver_available(ddafem, solver):
    """Whether this build knows the solver (checked against the scene reference)."""
    out = subprocess.run([ddafem, "scene-reference"], capture_output=True, text=True).stdout
    return solver in out


def run(ddafem, scene, solver, extra):
    with tempfile.TemporaryDirectory() as out:
        cmd = [ddafem, "run", os.path.join(TOP, scene), "-o", out, "--quiet",
               "--set", f"solver.type={solver}"] + extra
        proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if proc.returncode != 0:
            raise SystemExit(f"failed: {' '.join(cmd)}\n{proc.stderr}")
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f)  # includes the run's own peak_memory_mb (getrusage)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--quick", action="store_true", help="500 bar steps, 20 wall steps")
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "performance"))
    args = parser.parse_args()
    ddafem = os.path.join(args.build, "ddafem")

    rows = []
    for case, scene, extra in CASES:
        if args.quick:
            extra = extra + ["--set", "time.end_time=" + ("0.005" if case.startswith("bar") else "0.002")]
        for solver in SOLVERS:
            if not solver_available(ddafem, solver):
                continue
            s = run(ddafem, scene, solver, extra)
            n_blocks, n_steps = s["model"]["blocks"], s["steps"]
            t = s["timings_s"]
            per = 1e6 / (n_blocks * n_steps)  # s -> us per block per step
            contacts = t["broad_phase"] + t["narrow_phase"]
            loop = contacts + t["assemble"] + t["solve"] + t["update"] + t["output"]
            rows.append({
                "case": case, "solver": solver, "blocks": n_blocks, "dofs": s["model"]["dofs"],
                "steps": n_steps,
                "us_per_step": 1e6 * loop / n_steps,
                "contacts_us_per_block_step": contacts * per,
                "assemble_us_per_block_step": t["assemble"] * per,
                "solve_us_per_block_step": t["solve"] * per,
                "update_us_per_block_step": t["update"] * per,
                "output_us_per_block_step": t["output"] * per,
                "factorizations": s["solver"]["factorizations"],
                "refinements": s["solver"]["refinement_iterations"],
                "wall_s": s["wall_time_s"],
                "peak_memory_mb": s["peak_memory_mb"],
            })
            r = rows[-1]
            print(f"{case:10s} {solver:11s} {r['us_per_step']:9.1f} us/step  per block-step: "
                  f"contacts {r['contacts_us_per_block_step']:.3f} assemble {r['assemble_us_per_block_step']:.3f} solve "
                  f"{r['solve_us_per_block_step']:.3f} update {r['update_us_per_block_step']:.3f} "
                  f"output {r['output_us_per_block_step']:.3f} us; {r['factorizations']} "
                  f"factorizations; peak {r['peak_memory_mb']:.0f} MB", flush=True)

    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "dda_bench.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)

    write_markdown(args, rows)

    fig, axes = plt.subplots(1, len(CASES), figsize=(4.5 * len(CASES), 4))
    phases = PHASES
    for ax, (case, _, _) in zip(axes, CASES):
        sub = [r for r in rows if r["case"] == case]
        bottom = [0.0] * len(sub)
        for phase in phases:
            values = [r[f"{phase}_us_per_block_step"] for r in sub]
            ax.bar([r["solver"] for r in sub], values, bottom=bottom, label=phase)
            bottom = [b + v for b, v in zip(bottom, values)]
        ax.set_title(f"{case} ({sub[0]['blocks']} blocks)" if sub else case)
        ax.set_ylabel("us per block per step")
        ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "dda_bench.png"), dpi=120)
    print(f"wrote {args.out}/dda_bench.csv, .md, .png")


def peer_medians():
    """ntdda's and ddafem's medians per step on the bar from peers.json, or None."""
    path = os.path.join(TOP, "docs", "performance", "peers.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)["medians"].get("bar")


def write_markdown(args, rows):
    peer = peer_medians()
    with open(os.path.join(args.out, "dda_bench.md"), "w") as f:
        f.write("# DDA engine timings\n\n")
        f.write("Generated by `/usr/bin/python3 bench/dda_bench.py`" +
                (" --quick" if args.quick else "") + f" on {platform.processor() or platform.machine()}"
                f", {os.cpu_count()} cores. Step-loop time (contact detection + assembly + solve + "
                "block update + output) per step, and per block per step by phase.\n\n")
        f.write("| case | solver | blocks | steps | us/step | contacts | assemble | solve | update "
                "| output | factorizations | refinements | peak MB |\n")
        f.write("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n")
        for r in rows:
            f.write(f"| {r['case']} | {r['solver']} | {r['blocks']} | {r['steps']} | "
                    f"{r['us_per_step']:.1f} | {r['contacts_us_per_block_step']:.3f} | "
                    f"{r['assemble_us_per_block_step']:.3f} | "
                    f"{r['solve_us_per_block_step']:.3f} | {r['update_us_per_block_step']:.3f} | "
                    f"{r['output_us_per_block_step']:.3f} | {r['factorizations']} | "
                    f"{r['refinements']} | {r['peak_memory_mb']:.0f} |\n")
        f.write("\nPhase columns are microseconds per block per step; contacts = broad + narrow "
                "phase (the bonded bar and wall still search for contacts every step).\n")
        f.write("\n`_small_disp` rows use `analysis.geometry: small_displacement` (matrix assembled "
                "and factorized once); the others update the geometry every step as Shi's DDA.\n")
        if peer:
            f.write(f"\nThe peer, measured side by side in `bench/peer_bench.py` "
                    f"([peers.md](peers.md)): ntdda {1000 * peer['ntdda']['ms_per_step']:.0f} us "
                    f"per step on the bar, ddafem {1000 * peer['ddafem']['ms_per_step']:.0f} us "
                    f"there (median of its runs; {peer['per_step_speedup']:.1f}x).\n")


if __name__ == "__main__":
    main()
