#!/usr/bin/python3
"""Convergence in dt of the default tunnel with its default damping, and the round-off envelope
damped against undamped (issue 53, must-have 3); regenerates
docs/verification/damping_convergence.{md,json}.

Each series is an ensemble of N runs of examples/tunnel/circular_sv.yaml whose incident
amplitude is 0.5 m/s x (1 + k 1e-12), k = 0 .. N-1 (perturbations of round-off's size: equally
valid models that differ where the system branches). Series: the default damping at dt, dt / 2
and dt / 4 (`tunnel.dt`, the coupled ladder's top level), and undamped (`tunnel.damping.ratio=0`)
at dt.

Per keyblock (every block with a keyblock record, not released by the excavation): the median
residual displacement relative to the rock with its distribution-free 95 % interval (order
statistics of the binomial(N, 1/2): ranks r and N + 1 - r, r the largest with
P(Bin(N, 1/2) < r) <= 2.5 %), the 5-95 % envelope (empirical quantiles), and P(loosened),
P(fell) with 95 % Wilson intervals (benchmarks.md E).

Acceptance (issue 53): for each keyblock, the three dt's medians agree within max(10 %, 0.2 mm)
or their 95 % intervals overlap; each dt's P(loosened) and P(fell) lies in the other dts' Wilson
intervals. The envelope table gives the width of the 5-95 % band damped and undamped and by how
much damping narrows it.

usage: /usr/bin/python3 tools/damping_convergence.py [--build build] [--members 16] [--jobs 2]
           [--dts 1,2,4] [--out docs/verification]
Not part of CI: 4 x 16 tunnel runs, about an hour on 2 cores.
"""
import argparse
import concurrent.futures
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(TOP, "examples", "tunnel", "circular_sv.yaml")
AMPLITUDE = 0.5
Z95 = 1.959963984540054
AGREE_FRACTION, AGREE_FLOOR_M = 0.10, 2e-4


def wilson(k, n, z=Z95):
    """95 % Wilson score interval of a binomial proportion k / n (benchmarks.md E)."""
    if n == 0:
        return (0.0, 1.0)
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return (max(0.0, centre - half), min(1.0, centre + half))


def median_ranks(n):
    """1-based ranks (r, n + 1 - r) of the distribution-free 95 % interval of the median."""
    cdf, r = 0.0, 0
    for k in range(n + 1):
        cdf += math.comb(n, k) / 2.0 ** n   # P(Bin(n, 1/2) <= k)
        if cdf > 0.025:
            break
        r = k + 1
    return max(r, 1), n + 1 - max(r, 1)


def quantile(sorted_values, q):
    """Linear-interpolation quantile (numpy's default) of an ascending list."""
    if not sorted_values:
        return None
    x = q * (len(sorted_values) - 1)
    lo = int(math.floor(x))
    hi = min(lo + 1, len(sorted_values) - 1)
    return sorted_values[lo] + (x - lo) * (sorted_values[hi] - sorted_values[lo])


def run_member(ddafem, settings, out):
    cmd = [ddafem, "run", SCENE, "-o", out, "--quiet", "--threads", "1",
           "--set", "output.interval=0"]
    for key, value in settings.items():
        cmd += ["--set", f"{key}={value}"]
    start = time.monotonic()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    try:
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
    except (OSError, ValueError):
        summary = {}
    return {"exit": proc.returncode, "stderr": proc.stderr[-400:], "summary": summary,
            "wall_s": time.monotonic() - start}


def keyblock_outcomes(summary):
    """{id: (residual_relative_m, loosened, fell)} of the keyblocks not released."""
    blocks = summary.get("keyblocks", {}).get("blocks", [])
    return {b["id"]: (b["residual_relative_m"], b["loosened"], b["fell"])
            for b in blocks if not b.get("released")}


def series_statistics(members):
    """Per keyblock: median and its interval, 5-95 % envelope, P(loosened), P(fell)."""
    ok = [m for m in members if m["exit"] == 0 and m["summary"].get("keyblocks")]
    ids = sorted({i for m in ok for i in keyblock_outcomes(m["summary"])})
    stats = {}
    for i in ids:
        rows = [keyblock_outcomes(m["summary"]).get(i) for m in ok]
        rows = [r for r in rows if r is not None]
        n = len(rows)
        residuals = sorted(r[0] for r in rows)
        lo, hi = median_ranks(n)
        loosened, fell = sum(r[1] for r in rows), sum(r[2] for r in rows)
        stats[i] = {"n": n, "median_m": quantile(residuals, 0.5),
                    "median_interval_m": [residuals[lo - 1], residuals[hi - 1]],
                    "q05_m": quantile(residuals, 0.05), "q95_m": quantile(residuals, 0.95),
                    "p_loosened": loosened / n, "loosened_interval": wilson(loosened, n),
                    "p_fell": fell / n, "fell_interval": wilson(fell, n)}
    return {"members": len(members), "completed": len(ok),
            "failed": len(members) - len(ok), "keyblocks": stats,
            "median_wall_s": quantile(sorted(m["wall_s"] for m in members), 0.5)}


def agree(a, b):
    """Two series' keyblock statistics agree (issue 53's rule)."""
    close = abs(a["median_m"] - b["median_m"]) <= max(
        AGREE_FRACTION * max(abs(a["median_m"]), abs(b["median_m"])), AGREE_FLOOR_M)
    overlap = (a["median_interval_m"][0] <= b["median_interval_m"][1] and
               b["median_interval_m"][0] <= a["median_interval_m"][1])
    inside = all(lo <= a[p] <= hi for p, key in (("p_loosened", "loosened_interval"),
                                                   ("p_fell", "fell_interval"))
                 for lo, hi in [b[key]])
    return (close or overlap) and inside


def convergence_rows(series, dts):
    rows = []
    names = [f"dt/{d}" if d > 1 else "dt" for d in dts]
    ids = sorted(set.intersection(*[set(series[n]["keyblocks"]) for n in names]))
    for i in ids:
        s = [series[n]["keyblocks"][i] for n in names]
        ok = all(agree(s[a], s[b]) for a in range(len(s)) for b in range(len(s)) if a != b)
        rows.append({"id": i, "series": dict(zip(names, s)), "agree": ok})
    return rows


def envelope_rows(damped, undamped):
    rows = []
    for i in sorted(set(damped["keyblocks"]) & set(undamped["keyblocks"])):
        d, u = damped["keyblocks"][i], undamped["keyblocks"][i]
        wd, wu = d["q95_m"] - d["q05_m"], u["q95_m"] - u["q05_m"]
        rows.append({"id": i, "damped_width_m": wd, "undamped_width_m": wu,
                     "narrowed": None if wu == 0 else 1.0 - wd / wu,
                     "damped_median_m": d["median_m"], "undamped_median_m": u["median_m"]})
    return rows


def mm(x):
    return "-" if x is None else f"{1e3 * x:.2f}"


def pct(p, interval):
    return f"{100 * p:.0f} % [{100 * interval[0]:.0f}, {100 * interval[1]:.0f}]"


def write_markdown(path, data):
    names = list(data["series"])
    lines = ["# The default tunnel: convergence in dt with damping, and the round-off envelope",
             "", f"Regenerated by `/usr/bin/python3 tools/damping_convergence.py --members "
             f"{data['members']}` ({data['elapsed_s'] / 60:.0f} min on {data['jobs']} "
             "processes). Each series: the incident amplitude 0.5 m/s x (1 + k 1e-12), k = 0 .. "
             f"{data['members'] - 1}. Damping: the tunnel default (docs/damping.md).", "",
             "| series | runs | completed | median wall [s] |", "|---|---|---|---|"]
    for n in names:
        s = data["series"][n]
        lines.append(f"| {n} | {s['members']} | {s['completed']} | {s['median_wall_s']:.0f} |")
    lines += ["", "## Convergence in dt (damped)", "",
              "Median residual relative to the rock [mm] with its 95 % interval; P(loosened), "
              "P(fell) with 95 % Wilson intervals. Agree: medians within max(10 %, 0.2 mm) or "
              "intervals overlapping, and each probability inside the other dts' intervals.", "",
              "| block | " + " | ".join(f"{n} median [mm]" for n in data["dts"]) + " | " +
              " | ".join(f"{n} P(loosened)" for n in data["dts"]) + " | " +
              " | ".join(f"{n} P(fell)" for n in data["dts"]) + " | agree |",
              "|---" * (3 * len(data["dts"]) + 2) + "|"]
    for r in data["convergence"]:
        s = [r["series"][n] for n in data["dts"]]
        lines.append(f"| {r['id']} | " + " | ".join(
            f"{mm(x['median_m'])} [{mm(x['median_interval_m'][0])}, "
            f"{mm(x['median_interval_m'][1])}]" for x in s) + " | " +
            " | ".join(pct(x["p_loosened"], x["loosened_interval"]) for x in s) + " | " +
            " | ".join(pct(x["p_fell"], x["fell_interval"]) for x in s) +
            f" | {'yes' if r['agree'] else '**no**'} |")
    n_agree = sum(r["agree"] for r in data["convergence"])
    lines += ["", f"{n_agree} of {len(data['convergence'])} keyblocks agree across "
              f"{', '.join(data['dts'])}.", "",
              "## Round-off envelope, damped against undamped (at dt)", "",
              "Width of the 5-95 % band of each keyblock's residual [mm].", "",
              "| block | undamped median | undamped 5-95 % width | damped median | damped width "
              "| narrowed by |", "|---|---|---|---|---|---|"]
    for r in data["envelope"]:
        narrowed = "-" if r["narrowed"] is None else f"{100 * r['narrowed']:.0f} %"
        lines.append(f"| {r['id']} | {mm(r['undamped_median_m'])} | "
                     f"{mm(r['undamped_width_m'])} | {mm(r['damped_median_m'])} | "
                     f"{mm(r['damped_width_m'])} | {narrowed} |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--members", type=int, default=16)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--dts", default="1,2,4", help="divisors of the tunnel's dt")
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "verification"))
    args = parser.parse_args()
    start = time.monotonic()
    ddafem = os.path.join(os.path.abspath(args.build), "ddafem")
    proc = subprocess.run([ddafem, "check", SCENE], capture_output=True, text=True)
    dt = float(re.search(r"time: dt ([0-9.eE+-]+) s", proc.stdout).group(1))
    dts = [int(d) for d in args.dts.split(",")]
    plans = {(f"dt/{d}" if d > 1 else "dt"): {"tunnel.dt": dt / d} for d in dts}
    plans["undamped"] = {"tunnel.dt": dt, "tunnel.damping.ratio": 0}
    jobs = []
    with tempfile.TemporaryDirectory(prefix="damping_convergence_") as root:
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            for name, settings in plans.items():
                for k in range(args.members):
                    s = {**settings,
                         "tunnel.wave.velocity.amplitude": repr(AMPLITUDE * (1 + k * 1e-12))}
                    jobs.append((name, pool.submit(run_member, ddafem, s,
                                                   os.path.join(root, f"{name.replace('/', '_')}"
                                                                      f"_{k:03d}"))))
            members = {}
            for name, future in jobs:
                members.setdefault(name, []).append(future.result())
    series = {name: series_statistics(m) for name, m in members.items()}
    names = [n for n in plans if n != "undamped"]
    data = {"members": args.members, "jobs": args.jobs, "dt_s": dt, "dts": names,
            "series": series, "convergence": convergence_rows(series, dts),
            "envelope": envelope_rows(series["dt"], series["undamped"]),
            "elapsed_s": time.monotonic() - start}
    with open(os.path.join(args.out, "damping_convergence.json"), "w") as f:
        json.dump(data, f, indent=1)
    write_markdown(os.path.join(args.out, "damping_convergence.md"), data)
    print(f"damping_convergence: {data['elapsed_s'] / 60:.1f} min -> "
          f"{os.path.join(args.out, 'damping_convergence.md')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
