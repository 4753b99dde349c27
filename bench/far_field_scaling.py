#!/usr/bin/python3
"""The distributed far field's cost against its size and its ranks (issue 22): runs
bench/far_field_scaling.cc under `mpirun -np 1` and `-np 2` from 10k to 2M DOFs with CG preconditioned by
its diagonal and by ML AMG (and MUMPS up to 500k), and writes docs/performance/far_field_scaling/{results.json, table.md,
scaling.png, strong.{md,json}}: median ms per step, set-up, CG iterations, peak memory per
rank, the speed-up from 1 to 2 ranks at each size, and at 1M DOFs the strong scaling from five
alternating runs of each (medians and their ratio), with 4 kB pages and with transparent huge
pages asked of glibc's malloc (GLIBC_TUNABLES=glibc.malloc.hugetlb=1); and condensation.{md,json,
png}: the seconds of the ties' condensation G = N P^-1 N^T by the number of right-hand sides
solved at once (MUMPS and CG, 1 and 2 ranks).

usage: /usr/bin/python3 bench/far_field_scaling.py [--build build] [--quick | --strong-only | --condensation-only]
Not a test: timings depend on the machine and on its load (2 shared cores here).
"""
import argparse
import json
import os
import platform
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(TOP, "docs", "performance", "far_field_scaling")
# (label, cells per side, timed steps, solvers): Q2 on N x N cells has 2 (2N + 1)^2 DOFs.
SIZES = [
    ("10k", 36, 100, ["cg_jacobi", "cg_amg", "mumps"]),
    ("100k", 112, 100, ["cg_jacobi", "cg_amg", "mumps"]),
    ("500k", 250, 100, ["cg_jacobi", "cg_amg", "mumps"]),
    ("1M", 352, 100, ["cg_jacobi"]),
    ("1M", 352, 30, ["cg_amg"]),
    ("2M", 500, 30, ["cg_jacobi"]),
]
# Strong scaling at 1M DOFs: 1 and 2 ranks alternately, REPEATS times each (this shared machine
# varies by 10-20 % from run to run): the medians and their ratio.
STRONG = ("1M", 352, 30, "cg_jacobi")
REPEATS = 5
QUICK = [("10k", 36, 20, ["cg_jacobi", "cg_amg", "mumps"]),
         ("100k", 112, 20, ["cg_jacobi", "cg_amg"])]
ENVIRONMENT = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
# glibc's malloc asks the kernel for transparent huge pages (2 MB) for its large blocks: this
# machine's kernel gives them only when asked (transparent_hugepage = madvise), and with 4 kB
# pages the matrix's 600 MB cost a TLB miss every few rows, which two ranks pay together.
HUGE_PAGES = "glibc.malloc.hugetlb=1"


def run(driver, ranks, cells, steps, solver, huge_pages=False, extra=()):
    environment = dict(ENVIRONMENT, GLIBC_TUNABLES=HUGE_PAGES if huge_pages else "")
    cmd = ["mpirun", "-np", str(ranks), "--oversubscribe", "--bind-to", "none",
           "-x", "GLIBC_TUNABLES", driver,
           "--cells", str(cells), "--steps", str(steps), "--solver", solver] + list(extra)
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=3600, env=environment)
    if out.returncode != 0:
        raise SystemExit(f"failed: {' '.join(cmd)}\n{out.stdout}\n{out.stderr}")
    result = json.loads(out.stdout.strip().splitlines()[-1])
    result["load_average"] = os.getloadavg()[0]
    return result


def table(rows):
    lines = ["| size | DOFs | solver | ranks | ms/step (median) | solve ms | CG its/step | "
             "set-up s | memory/rank MB | speed-up 1 to 2 |", "|" + "---|" * 10]
    by_key = {(r["label"], r["solver"], r["ranks"]): r for r in rows}
    for r in rows:
        one = by_key.get((r["label"], r["solver"], 1))
        speedup = ("%.2f" % (one["median_step_ms"] / r["median_step_ms"])
                   if one and r["ranks"] == 2 else "")
        lines.append("| %s | %d | %s | %d | %.1f | %.1f | %.1f | %.1f | %.0f | %s |" % (
            r["label"], r["dofs"], r["solver"], r["ranks"], r["median_step_ms"],
            r["solve_ms_per_step"], r["iterations_per_step"], r["setup_s"] + r["warm_up_s"],
            r["peak_memory_mb_per_rank"], speedup))
    return "\n".join(lines) + "\n"


def chart(rows, png):
    fig, (cost, memory) = plt.subplots(1, 2, figsize=(11, 4.2))
    for solver, marker in (("cg_jacobi", "^"), ("cg_amg", "o"), ("mumps", "s")):
        for ranks, color in ((1, "C0"), (2, "C3")):
            pts = [r for r in rows if r["solver"] == solver and r["ranks"] == ranks]
            if not pts:
                continue
            label = "%s, %d rank%s" % (solver, ranks, "s" if ranks > 1 else "")
            cost.loglog([p["dofs"] for p in pts], [p["median_step_ms"] for p in pts],
                        marker + "-", color=color, label=label, mfc="none" if solver == "mumps"
                        else color)
            memory.loglog([p["dofs"] for p in pts], [p["peak_memory_mb_per_rank"] for p in pts],
                          marker + "-", color=color, label=label,
                          mfc="none" if solver == "mumps" else color)
    dofs = [1e4, 2e6]
    cost.loglog(dofs, [1e3 * d / 2e7 for d in dofs], "k:", lw=1,
                label="2e7 DOF-updates/s (step-48, explicit)")
    cost.set_xlabel("far-field DOFs")
    cost.set_ylabel("ms per step (median, slowest rank)")
    memory.set_xlabel("far-field DOFs")
    memory.set_ylabel("peak memory per rank [MB]")
    cost.legend(fontsize=8)
    memory.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def strong_scaling(driver, repeats):
    """1 and 2 ranks alternately, with 4 kB pages and with huge pages, `repeats` times each."""
    label, cells, steps, solver = STRONG
    modes = {"4 kB pages": False, "huge pages": True}
    times = {m: {1: [], 2: []} for m in modes}
    loads = []
    for _ in range(repeats):
        for mode, huge_pages in modes.items():
            for ranks in (1, 2):
                r = run(driver, ranks, cells, steps, solver, huge_pages)
                times[mode][ranks].append(r["median_step_ms"])
                loads.append(r["load_average"])
    result = {"label": label, "solver": solver, "steps": steps, "load_average": loads, "modes": {}}
    for mode in modes:
        median = {r: sorted(t)[len(t) // 2] for r, t in times[mode].items()}
        result["modes"][mode] = {"ms_per_step": times[mode], "median_ms": median,
                                 "speedup": median[1] / median[2]}
    return result


def strong_table(strong):
    lines = ["\n| pages | ranks | ms per step, %d runs alternating | median | speed-up |"
             % (len(strong["load_average"]) // 4), "|---|---|---|---|---|"]
    for mode, m in strong["modes"].items():
        for r in (1, 2):
            lines.append("| %s | %d | %s | %.1f | %s |" % (
                mode, r, ", ".join("%.0f" % t for t in m["ms_per_step"][r]), m["median_ms"][r],
                "%.2f" % m["speedup"] if r == 2 else ""))
    return "\n".join(lines) + "\n"


# The condensation G = N P^-1 N^T of the default tunnel's size: 351 ties (702 right-hand sides)
# on a 33k-DOF square, the right-hand sides solved WIDTHS at a time.
CONDENSATION = (64, 351)
WIDTHS = (1, 2, 4, 8, 16, 64)


def condensation_sweep(driver):
    """Seconds for G (with the solver's set-up) by solver, ranks and block width."""
    cells, ties = CONDENSATION
    rows = []
    for solver in ("mumps", "cg_jacobi"):
        for ranks in (1, 2):
            for width in WIDTHS:
                cmd_extra = ["--ties", str(ties), "--width", str(width)]
                r = run(driver, ranks, cells, 5, solver, extra=cmd_extra)
                rows.append({k: r[k] for k in ("solver", "ranks", "dofs", "ties",
                                               "condensation_width", "condensation_s",
                                               "load_average")})
                print("condensation %s np%d width %d: %.2f s" % (solver, ranks, width,
                                                                 r["condensation_s"]), flush=True)
    return rows


def condensation_outputs(rows):
    lines = ["| solver | ranks | " + " | ".join("width %d [s]" % w for w in WIDTHS) +
             " | best against width 1 |", "|---|---|" + "---|" * (len(WIDTHS) + 1)]
    fig, ax = plt.subplots(figsize=(6, 4))
    for solver in ("mumps", "cg_jacobi"):
        for ranks in (1, 2):
            pts = [r for r in rows if r["solver"] == solver and r["ranks"] == ranks]
            s = [p["condensation_s"] for p in pts]
            lines.append("| %s | %d | %s | %.2f |" % (solver, ranks, " | ".join(
                "%.2f" % x for x in s), s[0] / min(s)))
            ax.semilogx([p["condensation_width"] for p in pts], s, "o-" if solver == "mumps"
                        else "^-", label="%s, %d rank%s" % (solver, ranks, "s" * (ranks > 1)),
                        base=2)
    ax.set_xlabel("right-hand sides solved at once")
    ax.set_ylabel("condensation G [s] (with set-up)")
    ax.set_title("G of %d ties on %d DOFs" % (rows[0]["ties"], rows[0]["dofs"]), fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "condensation.png"), dpi=110)
    json.dump(rows, open(os.path.join(OUT, "condensation.json"), "w"), indent=1)
    text = ("G = N P^-1 N^T of %d ties (%d right-hand sides) on the %d-DOF square (load average "
            "%.1f to %.1f):\n\n" % (rows[0]["ties"], 2 * rows[0]["ties"], rows[0]["dofs"],
                                     min(r["load_average"] for r in rows),
                                     max(r["load_average"] for r in rows)) + "\n".join(lines) + "\n")
    open(os.path.join(OUT, "condensation.md"), "w").write(text)
    print(text)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--strong-only", action="store_true",
                        help="only the strong scaling at 1M DOFs (strong.md, strong.json)")
    parser.add_argument("--condensation-only", action="store_true",
                        help="only the condensation by block width (condensation.{md,json,png})")
    args = parser.parse_args()
    driver = os.path.join(args.build, "bench", "far_field_scaling")
    os.makedirs(OUT, exist_ok=True)
    if not args.quick and not args.strong_only:
        condensation_outputs(condensation_sweep(driver))
        if args.condensation_only:
            return
    if not args.quick:
        strong = strong_scaling(driver, REPEATS)
        json.dump(strong, open(os.path.join(OUT, "strong.json"), "w"), indent=1)
        open(os.path.join(OUT, "strong.md"), "w").write(
            "Strong scaling at %s DOFs (%s, %d timed steps a run, load average %.1f to %.1f; huge "
            "pages: GLIBC_TUNABLES=%s):\n%s"
            % (strong["label"], strong["solver"], strong["steps"], min(strong["load_average"]),
               max(strong["load_average"]), HUGE_PAGES, strong_table(strong)))
        print(strong_table(strong))
        if args.strong_only:
            return
    rows = []
    for label, cells, steps, solvers in QUICK if args.quick else SIZES:
        for solver in solvers:
            for ranks in (1, 2):
                r = run(driver, ranks, cells, steps, solver)
                r["label"] = label
                rows.append(r)
                print("%s %s np%d: %.1f ms/step, %.0f MB/rank" % (
                    label, solver, ranks, r["median_step_ms"], r["peak_memory_mb_per_rank"]),
                    flush=True)
    json.dump({"machine": platform.node(), "cores": os.cpu_count(), "rows": rows},
              open(os.path.join(OUT, "results.json"), "w"), indent=1)
    open(os.path.join(OUT, "table.md"), "w").write(table(rows))
    chart(rows, os.path.join(OUT, "scaling.png"))
    print(table(rows))


if __name__ == "__main__":
    main()
