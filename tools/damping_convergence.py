#!/usr/bin/python3
"""Convergence in dt of the default tunnel with its default damping, and the round-off envelope
damped against undamped (issue 53, must-have 3); regenerates
docs/verification/damping_convergence.{md,json}.

Each series is an ensemble (`ddafem ensemble --roundoff`, docs/ensemble.md) of N runs of
examples/tunnel/circular_sv.yaml whose incident amplitude is 0.5 m/s x (1 + k 1e-12),
k = 0 .. N-1 (perturbations of round-off's size: equally
valid models that differ where the system branches). Series: the default damping at dt, dt / 2
and dt / 4 (`tunnel.dt`, the coupled ladder's top level), undamped (`tunnel.damping.ratio=0`)
at dt, the three dts again with the joints' friction angle drawn from truncnormal(35, 2, 25, 45)
deg (the answer over an uncertainty an engineer has), and again with the incident amplitude
drawn from normal(0.5, 0.0005) m/s without round-off (a 0.1 % uncertainty of the input).

Per keyblock (every block with a keyblock record, not released by the excavation): the median
residual displacement relative to the rock with its distribution-free 95 % interval (order
statistics of the binomial(N, 1/2): ranks r and N + 1 - r, r the largest with
P(Bin(N, 1/2) < r) <= 2.5 %), the 5-95 % envelope (empirical quantiles), and P(loosened),
P(fell) with 95 % Wilson intervals (docs/reference/benchmarks.md E).

Acceptance (issue 53): for each keyblock, the three dt's medians agree within max(10 %, 0.2 mm)
or their 95 % intervals overlap; each dt's P(loosened) and P(fell) lies in the other dts' Wilson
intervals. The envelope table gives the width of the 5-95 % band damped and undamped and by how
much damping narrows it.

usage: /usr/bin/python3 tools/damping_convergence.py [--build build] [--members 16]
           [--friction-members 48] [--jobs 2] [--dts 1,2,4] [--work build/damping_convergence] [--out docs/verification]
Not part of CI: 7 x 16 and 3 x 48 tunnel runs, about 2.5 hours on 2 cores. The ensembles stay in --work; an
interrupted call, run again, resumes them (`ddafem resume`).
"""
import argparse
import itertools
import json
import math
import os
import re
import subprocess
import sys
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(TOP, "tools"))
import verify_failure as VF  # noqa: E402
FRICTION = ["--vary", "joint_materials.joint.friction_angle=truncnormal(35,2,25,45)"]
# The incident amplitude uncertain by 0.1 % (sd): of the order of the scheme's relative phase
# error over the 25 Hz pulse at dt, (dt / T)^2 = 6e-4; far above round-off, far below what is
# known of an input.
INPUT = ["--vary", "tunnel.wave.velocity.amplitude=normal(0.5,0.0005)"]
SCENE = os.path.join(TOP, "examples", "tunnel", "circular_sv.yaml")
AGREE_FRACTION, AGREE_FLOOR_M = 0.10, 2e-4


def run_series(ddafem, work, name, settings, members, jobs, extra=(), roundoff=True):
    """One series: `ddafem ensemble [--roundoff]` of the default tunnel into work/name (resumed
    where an earlier call stopped); returns its ensemble.json."""
    out = os.path.join(work, name.replace("/", "_"))
    cmd = [ddafem, "ensemble", SCENE, "-n", str(members), "-o", out] + (
        ["--roundoff"] if roundoff else []) + ["-j", str(jobs), "--quiet"] + list(extra)
    for key, value in settings.items():
        cmd += ["--set", f"{key}={value}"]
    print(f"damping_convergence: {name}: {' '.join(cmd[1:])}", flush=True)
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode not in (0, 1):
        sys.exit(f"damping_convergence: {name} exited {proc.returncode}: {proc.stderr[-800:]}")
    with open(os.path.join(out, "ensemble.json")) as f:
        return json.load(f)


def series_statistics(ensemble):
    """Per keyblock the excavation left in place in every run: the median residual relative to
    the rock with its 95 % order-statistic interval, the 5-95 % envelope, P(loosened) and
    P(fell) with 95 % Wilson intervals, all as ensemble.json gives them."""
    stats = {}
    for k in ensemble["keyblocks"]:
        r = k["residual_relative_m"]
        if k["released"] > 0 or r is None:
            continue
        interval = r["median_95"] or [r["q05"], r["q95"]]
        stats[str(k["id"])] = {
            "n": k["n"], "median_m": r["median"], "median_interval_m": interval,
            "q05_m": r["q05"], "q95_m": r["q95"],
            "p_loosened": k["loosened"]["p"], "loosened_interval": k["loosened"]["wilson_95"],
            "p_fell": k["fell"]["p"], "fell_interval": k["fell"]["wilson_95"]}
    walls = sorted(m["wall_s"] for m in ensemble["members"] if m.get("finished"))
    return {"members": ensemble["members_requested"], "completed": ensemble["n_counted"],
            "failed": len(ensemble["failed"]), "keyblocks": stats,
            "members_wall_s": sum(walls),
            "median_wall_s": walls[len(walls) // 2] if walls else 0.0}


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


def wilson(k, n, z=1.96):
    """95 % Wilson interval of k in n, its ends exactly 0 at k = 0 and 1 at k = n (as
    common/statistics' wilson_interval)."""
    p = k / n
    centre, half = p + z * z / (2 * n), z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return (0.0 if k == 0 else (centre - half) / (1 + z * z / n),
            1.0 if k == n else (centre + half) / (1 + z * z / n))


def homogeneity_p(counts, ns):
    """Exact test that series of ns[i] runs with counts[i] events share one probability
    (Freeman-Halton: given the total, the tables as likely or less than the one observed)."""
    total = sum(counts)

    def probability(table):
        return math.prod(math.comb(n, k) for n, k in zip(ns, table)) / math.comb(sum(ns), total)

    observed = probability(counts)
    return min(1.0, sum(q for table in itertools.product(*[range(n + 1) for n in ns[:-1]])
                        if 0 <= total - sum(table) <= ns[-1]
                        for q in [probability(list(table) + [total - sum(table)])]
                        if q <= observed * (1 + 1e-9)))


def rule_pass_probability(p, ns):
    """The chance that series of ns[i] runs sharing the probability p pass the rule that each
    one's estimate lies inside the others' Wilson intervals (independent binomials)."""
    pmfs = [[math.comb(n, k) * p ** k * (1 - p) ** (n - k) for k in range(n + 1)] for n in ns]
    passed = 0.0
    for table in itertools.product(*[range(n + 1) for n in ns]):
        intervals = [wilson(k, n) for k, n in zip(table, ns)]
        if all(lo <= table[a] / ns[a] <= hi for a in range(len(ns))
               for b, (lo, hi) in enumerate(intervals) if a != b):
            passed += math.prod(pmf[k] for pmf, k in zip(pmfs, table))
    return passed


def convergence_rows(series, names):
    rows = []
    ids = sorted(set.intersection(*[set(series[n]["keyblocks"]) for n in names]))
    for i in ids:
        s = [series[n]["keyblocks"][i] for n in names]
        ok = all(agree(s[a], s[b]) for a in range(len(s)) for b in range(len(s)) if a != b)
        ns = [x["n"] for x in s]
        counts = [round(x["p_loosened"] * x["n"]) for x in s]
        rows.append({"id": i, "series": dict(zip(names, s)), "agree": ok,
                     "loosened_homogeneity_p": homogeneity_p(counts, ns),
                     "loosened_rule_pass": rule_pass_probability(sum(counts) / sum(ns), ns)})
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


def convergence_table(rows, names, labels=None):
    """Per keyblock: each series' median [mm] with its interval and probabilities; agree."""
    labels = labels or names
    lines = ["Median residual relative to the rock [mm] with its 95 % interval; P(loosened), "
             "P(fell) with 95 % Wilson intervals. Agree: medians within max(10 %, 0.2 mm) or "
             "intervals overlapping, and each probability inside the other dts' intervals.", "",
             "| block | " + " | ".join(f"{n} median [mm]" for n in labels) + " | " +
             " | ".join(f"{n} P(loosened)" for n in labels) + " | " +
             " | ".join(f"{n} P(fell)" for n in labels) + " | agree | P(loosened) alike: exact test p [rule passed if alike] |",
             "|---" * (3 * len(names) + 3) + "|"]
    for r in rows:
        s = [r["series"][n] for n in names]
        lines.append(f"| {r['id']} | " + " | ".join(
            f"{mm(x['median_m'])} [{mm(x['median_interval_m'][0])}, "
            f"{mm(x['median_interval_m'][1])}]" for x in s) + " | " +
            " | ".join(pct(x["p_loosened"], x["loosened_interval"]) for x in s) + " | " +
            " | ".join(pct(x["p_fell"], x["fell_interval"]) for x in s) +
            f" | {'yes' if r['agree'] else '**no**'} | {r['loosened_homogeneity_p']:.2f} "
            f"[{100 * r['loosened_rule_pass']:.0f} %] |")
    n_agree = sum(r["agree"] for r in rows)
    n_alike = sum(r["loosened_homogeneity_p"] >= 0.05 for r in rows)
    return lines + ["", f"{n_agree} of {len(rows)} keyblocks agree across "
                    f"{', '.join(labels)}. P(loosened) alike at the 5 % level of the exact "
                    f"(Freeman-Halton) test for {n_alike} of {len(rows)}; the last column gives "
                    "the chance that the rule above passes when the series' probabilities are "
                    "in truth one (the pooled estimate), so that a failure of the rule alone is "
                    "told from a difference."]


def write_markdown(path, data):
    names = list(data["series"])
    lines = ["# The default tunnel: convergence in dt with damping, and the round-off envelope",
             "", f"Regenerated by `/usr/bin/python3 tools/damping_convergence.py --members "
             f"{data['members']} --friction-members {data['friction_members']}` (the runs: "
             f"{sum(x['members_wall_s'] for x in data['series'].values()) / 60:.0f} min of "
             f"members' wall time, {data['jobs']} at a time; this call "
             f"{data['elapsed_s'] / 60:.0f} min, resuming the series where they stood). "
             "Each series: the incident amplitude 0.5 m/s x (1 + k 1e-12), k = 0 .. N - 1 (the "
             "input series: drawn, below). Damping: the tunnel default (docs/damping.md). "
             f"Binary: `{data['version']}`.", "",
             "| series | runs | completed | median wall [s] |", "|---|---|---|---|"]
    for n in names:
        s = data["series"][n]
        lines.append(f"| {n} | {s['members']} | {s['completed']} | {s['median_wall_s']:.0f} |")
    lines += ["", "## Convergence in dt (damped)", ""] + convergence_table(
        data["convergence"], data["dts"]) + [
        "", "## Convergence in dt of the answer over the friction angle (damped)", "",
        "The same at each dt with the joints' friction angle drawn from truncnormal(35, 2, 25, "
        "45) deg (the same draws at every dt, with the round-off): the distribution over an "
        "uncertainty an engineer has, not over round-off alone.", ""] + convergence_table(
        data["friction_convergence"], data["friction_dts"], data["dts"]) + [
        "", "## Convergence in dt over a 0.1 % uncertainty of the input (damped)", "",
        "The same at each dt with the incident amplitude drawn from normal(0.5, 0.0005) m/s, "
        "without round-off: a perturbation of the order of the scheme's relative phase error "
        "over the pulse at dt ((dt / T)^2 = 6e-4): far above round-off, far below what is "
        "known of an input.", ""] + convergence_table(
        data["input_convergence"], data["input_dts"], data["dts"]) + ["",
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
    parser.add_argument("--members", type=int, default=16, help="runs of each round-off series")
    parser.add_argument("--friction-members", type=int, default=48,
                        help="runs of each friction series (a larger value extends them)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--dts", default="1,2,4", help="divisors of the tunnel's dt")
    parser.add_argument("--work", default=os.path.join(TOP, "build", "damping_convergence"),
                        help="the ensembles' folder (kept: a second call resumes them)")
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "verification"))
    args = parser.parse_args()
    start = time.monotonic()
    ddafem = os.path.join(os.path.abspath(args.build), "ddafem")
    proc = subprocess.run([ddafem, "check", SCENE], capture_output=True, text=True)
    dt = float(re.search(r"time: dt ([0-9.eE+-]+) s", proc.stdout).group(1))
    dts = [int(d) for d in args.dts.split(",")]
    plans = {(f"dt/{d}" if d > 1 else "dt"): {"tunnel.dt": repr(dt / d)} for d in dts}
    plans["undamped"] = {"tunnel.dt": repr(dt), "tunnel.damping.ratio": 0}
    os.makedirs(args.work, exist_ok=True)
    for group in ("friction", "input"):
        for d in dts:
            plans[f"{group} dt/{d}" if d > 1 else f"{group} dt"] = {"tunnel.dt": repr(dt / d)}
    series = {name: series_statistics(run_series(
        ddafem, args.work, name.replace(" ", "_"), settings,
        args.friction_members if name.startswith("friction") else args.members, args.jobs,
        FRICTION if name.startswith("friction") else INPUT if name.startswith("input") else (),
        roundoff=not name.startswith("input")))
        for name, settings in plans.items()}
    names = [n for n in plans if n.startswith("dt")]
    friction = [n for n in plans if n.startswith("friction")]
    uncertain_input = [n for n in plans if n.startswith("input")]
    data = {"members": args.members, "friction_members": args.friction_members,
            "jobs": args.jobs, "dt_s": dt, "dts": names, "friction_dts": friction,
            "input_dts": uncertain_input, "series": series,
            "convergence": convergence_rows(series, names),
            "friction_convergence": convergence_rows(series, friction),
            "input_convergence": convergence_rows(series, uncertain_input),
            "envelope": envelope_rows(series["dt"], series["undamped"]),
            "version": VF.binary_version(ddafem),
            "elapsed_s": time.monotonic() - start}
    with open(os.path.join(args.out, "damping_convergence.json"), "w") as f:
        json.dump(data, f, indent=1)
    write_markdown(os.path.join(args.out, "damping_convergence.md"), data)
    print(f"damping_convergence: {data['elapsed_s'] / 60:.1f} min -> "
          f"{os.path.join(args.out, 'damping_convergence.md')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
