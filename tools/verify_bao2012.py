#!/usr/bin/python3
"""Regenerates docs/verification/bao2012.{md,json} and the figures in docs/verification/figures/:
the viscous-boundary benchmarks of Bao, Hatzor & Huang (2012) run with build/ddafem.

  A  P-wave bar (section 4.1): free, vb1, vb2, dashpot x impedance (textbook, effective)
     x dt (1e-5, 5e-5, 1e-4) x frequency (100, 50 Hz); sxx at M1 = 50.5 m.
  B  S-wave column (section 4.2): the same boundaries x joint stiffness (2500, 12500 GN/m),
     dt 1e-5; horizontal displacement at M1 = 30.5 m above the base.
  Stability map: the bar at 100 Hz, dt from 1e-6 to 1e-3 s, every boundary; efficiency and
     energy growth against dt with VB I's predicted limit x0 = 1.688 and the paper's bounds.

Efficiency (docs/reference/physics.md section 6): eta = (|Ai| - |Ar|) / |Ai| with absolute extrema in windows.
  eta_window:   Ar from the run itself in the reflection window.
  eta_boundary: Ar = the run minus a run on a model three times longer (no reflection in the
                window), normalised by the same difference for a free end (instead of |Ai|):
                the boundary alone, without the algorithmic damping of the longer path.

usage: /usr/bin/python3 tools/verify_bao2012.py [--build build] [--jobs 2] [--quick]
"""
import argparse
import concurrent.futures
import json
import math
import os
import subprocess
import tempfile

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BAR = os.path.join(TOP, "examples/bao2012/p_wave_bar.yaml")
COLUMN = os.path.join(TOP, "examples/bao2012/s_wave_column.yaml")

RHO, E, NU = 2650.0, 50e9, 0.25
SHEAR_RATIO = 0.4

# Published boundary-only efficiencies [%] (docs/reference/benchmarks.md).
PAPER_A = {("vb1", 1e-5): 96.2, ("vb1", 5e-5): 98.6, ("vb1", 1e-4): 91.1,
           ("vb2", 1e-5): 62.3, ("vb2", 5e-5): 62.2, ("vb2", 1e-4): 62.2}
PAPER_B = {("vb1", 2.5e12): 87.8, ("vb1", 1.25e13): 97.0,
           ("vb2", 2.5e12): 54.7, ("vb2", 1.25e13): 63.0}

BOUNDARIES = [("free", "textbook"), ("vb1", "textbook"), ("vb1", "effective"),
              ("vb2", "textbook"), ("vb2", "effective"), ("dashpot", "textbook"),
              ("dashpot", "effective")]
# Models three times longer than the benchmarks: no reflection reaches the monitors in the window.
LONG_BAR = {"blocks.0.grid.count": "[300, 1]", "boundaries.0.on_line.point": "[300, 0]"}
LONG_COLUMN = {"blocks.1.grid.count": "[1, 150]", "boundaries.0.on_line.point": "[0, 151]"}
VB1_THRESHOLD = 1.68789  # root of 2 / (1 + exp(-x)) = x (dda/viscous_boundary.cc)


def run(ddafem, scene, settings, allow_unstable=False):
    """Runs a scene with --set overrides; returns (failure or None, time,
    {monitor: (sxx, ux)}, {energy: history})."""
    with tempfile.TemporaryDirectory() as out:
        cmd = [ddafem, "run", scene, "-o", out, "--quiet"]
        for key, value in settings.items():
            cmd += ["--set", f"{key}={value}"]
        if allow_unstable:
            cmd.append("--allow-unstable")
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode not in (0, 1) or not os.path.exists(os.path.join(out, "histories.h5")):
            raise SystemExit(f"failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stderr}")
        with open(os.path.join(out, "summary.json")) as f:
            failure = json.load(f).get("failure")
        if failure is not None and not allow_unstable:
            raise SystemExit(f"failed: {' '.join(cmd)}\n{failure}")
        with h5py.File(os.path.join(out, "histories.h5"), "r") as f:
            time = f["time"][:]
            monitors = {name: (f[f"monitors/{name}/stress"][:, 0],
                               f[f"monitors/{name}/displacement"][:, 0])
                        for name in f["monitors"]}
            energy = {name: f[f"energy/{name}"][:] for name in f["energy"]}
    return failure, time, monitors, energy


def window_max(time, signal, t0, t1):
    mask = (time >= t0) & (time <= t1)
    return float(np.max(np.abs(signal[mask]))) if np.any(mask) else 0.0


def interpolate(time, signal, onto):
    return np.interp(onto, time, signal)


def jointed_speed(modulus, springs_per_area_times_depth):
    return math.sqrt(1.0 / (1.0 / modulus + 1.0 / springs_per_area_times_depth) / RHO)


def efficiencies(time, signal, ref_time, ref_signal, free_time, free_signal, incident, reflected):
    """(eta_window, eta_boundary, |Ai|) from a run, the long reference and the free end."""
    ai = window_max(time, signal, *incident)
    ar = window_max(time, signal, *reflected)
    ref = interpolate(ref_time, ref_signal, time)
    free = interpolate(ref_time, ref_signal, free_time)
    boundary_reflection = window_max(time, signal - ref, *reflected)
    free_reflection = window_max(free_time, free_signal - free, *reflected)
    return 100.0 * (1.0 - ar / ai), 100.0 * (1.0 - boundary_reflection / free_reflection), ai


def boundary_settings(boundary, impedance):
    return {"boundaries.0.type": boundary, "boundaries.0.impedance": impedance}


# ---- A: the P-wave bar ------------------------------------------------------------------------

def bar_windows(frequency):
    """Incident and reflection windows at M1 (50.5 m) of the 100 m bar [s]."""
    p = 2.5e12
    c = jointed_speed(E, 2.0 * p)  # 1 m blocks, two springs p per 1 m^2 joint
    period = 1.0 / frequency
    return (45.5 / c, 50.5 / c + period + 0.002), ((149.5 - 5.0) / c, 149.5 / c + period + 0.002)


def benchmark_a(ddafem, pool, dts, frequencies, geometry):
    records, histories = [], {}
    jobs = {}
    for f in frequencies:
        end = 0.05 if f >= 100 else 0.06
        for dt in dts:
            common = {"time.dt": dt, "time.end_time": end, "analysis.geometry": geometry,
                      "point_loads.0.time_function.frequency": f}
            jobs[("long", dt, f)] = pool.submit(run, ddafem, BAR, {**common, **LONG_BAR})
            for boundary, impedance in BOUNDARIES:
                jobs[(boundary, impedance, dt, f)] = pool.submit(
                    run, ddafem, BAR, {**common, **boundary_settings(boundary, impedance)})
    for f in frequencies:
        incident, reflected = bar_windows(f)
        for dt in dts:
            _, lt, lm, _ = jobs[("long", dt, f)].result()
            _, ft, fm, _ = jobs[("free", "textbook", dt, f)].result()
            for boundary, impedance in BOUNDARIES:
                _, t, m, _ = jobs[(boundary, impedance, dt, f)].result()
                histories[(boundary, impedance, dt, f)] = (t, m)
                eta_w, eta_b, ai = efficiencies(t, m["M1"][0], lt, lm["M1"][0], ft, fm["M1"][0],
                                                incident, reflected)
                records.append({
                    "benchmark": "A_p_wave_bar", "boundary": boundary,
                    "impedance": None if boundary == "free" else impedance,
                    "dt": dt, "frequency_hz": f, "contact_stiffness": 2.5e12,
                    "eta_window": round(eta_w, 2), "eta_boundary": round(eta_b, 2),
                    "incident_peak_pa": round(ai, 1),
                    "incident_loss_percent": round(100.0 * (1.0 - ai / 1e6), 2),
                    "paper_eta": PAPER_A.get((boundary, dt)) if f == 100 and impedance == "textbook" else None,
                })
    return records, histories


# ---- B: the S-wave column ---------------------------------------------------------------------

def column_windows(p):
    """Incident and reflection windows at M1 (30.5 m above the base top) [s]."""
    g = E / (2.0 * (1.0 + NU))
    c = jointed_speed(g, 2.0 * SHEAR_RATIO * p / 50.0 * 1.0)  # two shear springs per 50 m joint
    period = 0.01
    # The base starts moving at t = 0 at y = 1; M1 is at y = 31.5, the free top at y = 51.
    return (30.5 / c - 0.002, 30.5 / c + period + 0.003), \
           ((50.0 + 19.5) / c - 0.003, (50.0 + 19.5) / c + period + 0.003), c


def benchmark_b(ddafem, pool, stiffnesses, geometry):
    records, histories = [], {}
    jobs = {}
    for p in stiffnesses:
        common = {"joint_materials.bonded.normal_stiffness": p, "analysis.geometry": geometry}
        jobs[("long", p)] = pool.submit(run, ddafem, COLUMN, {**common, **LONG_COLUMN})
        for boundary, impedance in BOUNDARIES:
            jobs[(boundary, impedance, p)] = pool.submit(
                run, ddafem, COLUMN, {**common, **boundary_settings(boundary, impedance)})
    for p in stiffnesses:
        incident, reflected, _ = column_windows(p)
        _, lt, lm, _ = jobs[("long", p)].result()
        _, ft, fm, _ = jobs[("free", "textbook", p)].result()
        for boundary, impedance in BOUNDARIES:
            _, t, m, _ = jobs[(boundary, impedance, p)].result()
            histories[(boundary, impedance, p)] = (t, m)
            eta_w, eta_b, _ = efficiencies(t, m["M1"][1], lt, lm["M1"][1], ft, fm["M1"][1],
                                           incident, reflected)
            records.append({
                "benchmark": "B_s_wave_column", "boundary": boundary,
                "impedance": None if boundary == "free" else impedance,
                "dt": 1e-5, "frequency_hz": 100.0, "contact_stiffness": p,
                "eta_window": round(eta_w, 2), "eta_boundary": round(eta_b, 2),
                "paper_eta": PAPER_B.get((boundary, p)) if impedance == "textbook" else None,
            })
    return records, histories


# ---- stability map ----------------------------------------------------------------------------

def stability_map(ddafem, pool, dts):
    rows = []
    jobs = {}
    for dt in dts:
        # Long enough after the pulse has left for a source to show itself (<= 5000 steps).
        end = 0.05 if dt < 1e-4 else 0.5
        common = {"time.dt": dt, "time.end_time": end, "analysis.geometry": "small_displacement"}
        jobs[("long", dt)] = pool.submit(run, ddafem, BAR, {**common, **LONG_BAR})
        for boundary, impedance in BOUNDARIES:
            jobs[(boundary, impedance, dt)] = pool.submit(
                run, ddafem, BAR, {**common, **boundary_settings(boundary, impedance)}, True)
    incident, reflected = bar_windows(100.0)
    for dt in dts:
        _, lt, lm, _ = jobs[("long", dt)].result()
        _, ft, fm, _ = jobs[("free", "textbook", dt)].result()
        for boundary, impedance in BOUNDARIES:
            failure, t, m, en = jobs[(boundary, impedance, dt)].result()
            work_in = float(np.max(en["work_of_loads"]))
            stored = en["kinetic"] + en["strain"] + en["spring"]
            growth = float(stored[-1] / work_in) if work_in > 0 else None
            completed = failure is None and t[-1] >= reflected[1]
            eta_b = None
            if completed:
                _, eta_b, _ = efficiencies(t, m["M1"][0], lt, lm["M1"][0], ft, fm["M1"][0],
                                           incident, reflected)
            stopped = None
            if failure is not None:
                stopped = "energy growth" if "stored energy grew" in failure else \
                    "indefinite step matrix" if "not positive definite" in failure else failure
            rows.append({"boundary": boundary, "impedance": impedance, "dt": dt,
                         "eta_boundary": None if eta_b is None else round(eta_b, 2),
                         "final_stored_over_input": None if growth is None else round(growth, 4),
                         "stopped_by": stopped, "stopped_at_s": float(t[-1]) if stopped else None})
    return rows


# ---- figures and tables -----------------------------------------------------------------------

LABEL = {("free", "textbook"): "free", ("vb1", "textbook"): "VB I",
         ("vb1", "effective"): "VB I (effective Z)", ("vb2", "textbook"): "VB II",
         ("vb2", "effective"): "VB II (effective Z)", ("dashpot", "textbook"): "dashpot",
         ("dashpot", "effective"): "dashpot (effective Z)"}
FIGURE_BOUNDARIES = [("free", "textbook"), ("vb1", "textbook"), ("vb2", "textbook"),
                     ("dashpot", "effective")]


def figure_histories(histories, case, monitors, component, scale, unit, what, path):
    """One panel per boundary of FIGURE_BOUNDARIES: a monitor quantity against time.
    case: the history key after (boundary, impedance); component 0 = sxx, 1 = ux."""
    fig, axes = plt.subplots(len(FIGURE_BOUNDARIES), 1, figsize=(8, 9), sharex=True)
    for ax, key in zip(axes, FIGURE_BOUNDARIES):
        t, m = histories[key + case]
        for name in monitors:
            ax.plot(1e3 * t, scale * m[name][component], label=name)
        ax.set_title(f"{LABEL[key]}: {what}", fontsize=9)
        ax.set_ylabel(unit)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[-1].set_xlabel("time [ms]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def boundary_limits():
    """The bar's end block (1 m x 1 m): dt of VB I's source limit x0 m / cn, of the paper's
    bound m / cn (eq. 44) and of its warning 2 m / ct [s]."""
    vp = math.sqrt(E * (1 - NU) / (RHO * (1 + NU) * (1 - 2 * NU)))
    vs = math.sqrt(E / (2 * RHO * (1 + NU)))
    mass, cn, ct = RHO * 1.0, RHO * 1.0 * vp, RHO * 1.0 * vs
    return {"vb1_source": VB1_THRESHOLD * mass / cn, "m_over_cn": mass / cn,
            "two_m_over_ct": 2 * mass / ct}


def mark_limits(efficiency_axis, growth_axis):
    """The boundary limits of boundary_limits() as vertical lines on both axes of a stability
    figure (dashed: VB I's source limit, labelled; dotted: m / cn; dash-dot: 2 m / ct)."""
    limits = boundary_limits()
    for ax in (efficiency_axis, growth_axis):
        ax.axvline(limits["vb1_source"], color="k", ls="--", lw=1)
        ax.axvline(limits["m_over_cn"], color="gray", ls=":", lw=1)
        ax.axvline(limits["two_m_over_ct"], color="gray", ls="-.", lw=1)
        ax.grid(alpha=0.3, which="both")
    efficiency_axis.text(limits["vb1_source"], 5, " VB I source limit\n x0 m / cn", fontsize=8)
    efficiency_axis.set_ylim(-60, 101)


def figure_stability(rows, path):
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 8), sharex=True)
    for key in BOUNDARIES:
        sub = [r for r in rows if (r["boundary"], r["impedance"]) == key]
        a1.semilogx([r["dt"] for r in sub if r["eta_boundary"] is not None],
                    [r["eta_boundary"] for r in sub if r["eta_boundary"] is not None],
                    "o-", label=LABEL[key])
        grown = [r for r in sub if r["final_stored_over_input"] is not None]
        a2.loglog([r["dt"] for r in grown], [max(r["final_stored_over_input"], 1e-6) for r in grown],
                  "o-", label=LABEL[key])
    mark_limits(a1, a2)
    a1.set_ylabel("boundary-only efficiency [%]")
    a1.legend(fontsize=7, loc="lower left")
    a2.set_ylabel("stored energy at the end / energy put in\n(0.05 s for dt < 1e-4 s, else 0.5 s)")
    a2.set_xlabel("dt [s] (dotted: m/cn, eq. 44; dash-dot: 2m/ct)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_markdown(path, records_a, records_b, stability, quick, geometry):
    with open(path, "w") as f:
        f.write("# Viscous boundaries: Bao, Hatzor & Huang (2012) reproduced\n\n")
        f.write("Generated by `/usr/bin/python3 tools/verify_bao2012.py`" + (" --quick" if quick else "")
                + f"; DDA geometry `{geometry}`. Efficiencies in %, boundary-only and raw window "
                "as defined in docs/reference/physics.md section 6 (see the script's docstring). `effective` "
                "impedance uses the wave speeds the model carries (dda/viscous_boundary.h).\n\n")
        f.write("## A. P-wave bar (section 4.1), sxx at M1 = 50.5 m\n\n")
        f.write("| f [Hz] | dt [s] | boundary | impedance | paper | eta_boundary | eta_window | "
                "incident loss |\n|---:|---:|---|---|---:|---:|---:|---:|\n")
        for r in records_a:
            paper = "" if r["paper_eta"] is None else f"{r['paper_eta']:.1f}"
            f.write(f"| {r['frequency_hz']:g} | {r['dt']:g} | {r['boundary']} | "
                    f"{r['impedance'] or ''} | {paper} | {r['eta_boundary']:.1f} | "
                    f"{r['eta_window']:.1f} | {r['incident_loss_percent']:.1f}% |\n")
        f.write("\nIncident loss: 1 - |Ai| / 1 MPa at M1, DDA's algorithmic damping over 50 m.\n\n")
        f.write("## B. S-wave column (section 4.2), ux at M1 = 30.5 m above the base\n\n")
        f.write("| joint p [GN/m] | boundary | impedance | paper | eta_boundary | eta_window |\n"
                "|---:|---|---|---:|---:|---:|\n")
        for r in records_b:
            paper = "" if r["paper_eta"] is None else f"{r['paper_eta']:.1f}"
            f.write(f"| {r['contact_stiffness'] / 1e9:g} | {r['boundary']} | {r['impedance'] or ''} | "
                    f"{paper} | {r['eta_boundary']:.1f} | {r['eta_window']:.1f} |\n")
        f.write("\n## Stability map (bar, 100 Hz, small-displacement analysis)\n\n")
        f.write("![stability](figures/stability_map.png)\n\n")
        f.write("| dt [s] | boundary | impedance | eta_boundary | stored / input at the end | "
                "stopped by |\n|---:|---|---|---:|---:|---|\n")
        for r in stability:
            eta = "" if r["eta_boundary"] is None else f"{r['eta_boundary']:.1f}"
            growth = "" if r["final_stored_over_input"] is None else f"{r['final_stored_over_input']:.3g}"
            stop = "" if r["stopped_by"] is None else f"{r['stopped_by']} at {1e3 * r['stopped_at_s']:.1f} ms"
            f.write(f"| {r['dt']:g} | {r['boundary']} | {r['impedance']} | {eta} | {growth} | {stop} |\n")
        f.write("\n## Figures\n\n")
        for name in sorted(os.listdir(os.path.join(os.path.dirname(path), "figures"))):
            if name != "stability_map.png":
                f.write(f"![{name}](figures/{name})\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--quick", action="store_true",
                        help="100 Hz, dt 1e-4 and 5e-5 only; shorter stability sweep")
    parser.add_argument("--geometry", default="updated", choices=["updated", "small_displacement"])
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "verification"))
    args = parser.parse_args()
    ddafem = os.path.join(args.build, "ddafem")
    figures = os.path.join(args.out, "figures")
    os.makedirs(figures, exist_ok=True)

    dts = [1e-4, 5e-5] if args.quick else [1e-5, 5e-5, 1e-4]
    frequencies = [100.0] if args.quick else [100.0, 50.0]
    sweep = [1e-5, 1e-4, 3e-4, 4e-4] if args.quick else \
        [1e-6, 3e-6, 1e-5, 3e-5, 1e-4, 2e-4, 3e-4, 3.4e-4, 3.7e-4, 4e-4, 5e-4, 7e-4, 1e-3]
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        records_a, hist_a = benchmark_a(ddafem, pool, dts, frequencies, args.geometry)
        records_b, hist_b = benchmark_b(ddafem, pool, [2.5e12, 1.25e13], args.geometry)
        stability = stability_map(ddafem, pool, sweep)

    for dt in dts:
        figure_histories(hist_a, (dt, 100.0), ("M1", "M2"), 0, 1e-6, "MPa",
                         f"sxx, dt = {dt:g} s, 100 Hz",
                         os.path.join(figures, f"bar_100Hz_dt{dt:g}.png"))
    for p in (2.5e12, 1.25e13):
        figure_histories(hist_b, (p,), ("M0", "M1", "M2"), 1, 1e3, "mm",
                         f"ux, joint stiffness {p / 1e9:g} GN/m",
                         os.path.join(figures, f"column_p{p / 1e9:g}GN.png"))
    figure_stability(stability, os.path.join(figures, "stability_map.png"))

    with open(os.path.join(args.out, "bao2012.json"), "w") as f:
        json.dump(records_a + records_b, f, indent=1)
    with open(os.path.join(args.out, "stability_map.json"), "w") as f:
        json.dump(stability, f, indent=1)
    write_markdown(os.path.join(args.out, "bao2012.md"), records_a, records_b, stability,
                   args.quick, args.geometry)
    for r in records_a + records_b:
        if r["paper_eta"] is not None:
            print(f"{r['benchmark']:16s} {r['boundary']:8s} dt {r['dt']:g} p {r['contact_stiffness']:g}: "
                  f"paper {r['paper_eta']:.1f}, ours {r['eta_boundary']:.1f}")
    print(f"wrote {args.out}/bao2012.md, bao2012.json, stability_map.json, figures/")


if __name__ == "__main__":
    main()
