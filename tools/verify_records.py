#!/usr/bin/python3
"""Verifies recorded ground motions (the `record` time function) end to end and regenerates

  docs/verification/records.json   the measures and the errors
  docs/verification/records.md     the tables
  docs/verification/figures/records_column.png   the column's surface and base against theory

1. The processing. This tool processes the record again with numpy, independently of the C++
   (common/ground_motion.cc), as docs/ground_motions.md says: g to m/s^2, a half-cosine taper of
   5 % of the window (at most 0.5 s) at each end, the constrained least-squares polynomial
   baseline (degree 3, tapered like the record), the trapezoidal rule. Its measures (PGA, PGV,
   PGD, Arias intensity, t5, t95, mean frequency, f99) are compared with the run's summary.json
   `records`.
2. The outcrop rule and the wave. examples/far_field/record_column.yaml takes the synthetic
   outcrop record as the outcrop motion of a uniform rock column of height H with a free top:
   the incident wave is half the record. Exactly, the surface moves as the outcrop record H / VS
   later, and the base as v_in(t) + v_in(t - 2 H / VS). The run's monitors are compared with
   both: the largest difference over the record's PGV, and the relative L2 difference.

Usage: tools/verify_records.py [--build build] [--out docs/verification] [--check]
--check exits 1 if the processing differs by more than 1e-6 (relative) or the surface or the
base by more than 2 % of the PGV: the trapezoidal rule in time and quadratic elements with 10
nodes per S wavelength at f99 give phase errors of about (omega dt)^2 / 12 and (kh)^4 / 1440 at
the record's highest frequencies, which carry a few % of its velocity.
"""
import argparse
import json
import os
import subprocess
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "examples/far_field/record_column.yaml")
RECORD = os.path.join(ROOT, "examples/records/synthetic_rock.AT2")
G = 9.80665
HEIGHT, VS = 400.0, None  # m; VS from the material below


def read_peer(path):
    lines = open(path).read().split("\n")
    npts, dt = lines[3].replace(",", " ").split()[1], lines[3].replace(",", " ").split()[3]
    a = np.array([float(x) for line in lines[4:] for x in line.split()])
    assert len(a) == int(npts)
    return a * G, float(dt)


def trapezoid(x, dt):
    return np.concatenate([[0.0], np.cumsum(0.5 * dt * (x[1:] + x[:-1]))])


def taper(x, dt, seconds):
    x = x.copy()
    m = min(len(x) // 2, int(np.ceil(seconds / dt)))
    w = 0.5 * (1.0 - np.cos(np.pi * np.arange(m) * dt / seconds))
    x[:m] *= w
    x[len(x) - m :] *= w[::-1]
    return x


def baseline(a, dt, degree, taper_s):
    n = len(a)
    tau = np.arange(n) * dt / (dt * (n - 1))
    basis = [taper(tau**k, dt, taper_s) for k in range(degree - 1)]
    bu = np.column_stack([trapezoid(trapezoid(b, dt), dt) for b in basis])
    bv = np.array([trapezoid(b, dt)[-1] for b in basis])
    u = trapezoid(trapezoid(a, dt), dt)
    m = len(basis)
    kkt = np.zeros((m + 1, m + 1))
    kkt[:m, :m] = bu.T @ bu
    kkt[:m, m] = bv
    kkt[m, :m] = bv
    c = np.linalg.solve(kkt, np.concatenate([bu.T @ u, [trapezoid(a, dt)[-1]]]))[:m]
    return a - sum(ci * b for ci, b in zip(c, basis))


def measures(a, dt):
    v = trapezoid(a, dt)
    husid = trapezoid(a * a, dt)
    padded = 1 << int(np.ceil(np.log2(len(a))))
    power = np.abs(np.fft.rfft(a, padded)) ** 2
    f = np.fft.rfftfreq(padded, dt)
    band = (f >= 0.25) & (f <= 20.0)
    cumulative = np.cumsum(power[1:])
    return {
        "pga_m_s2": np.max(np.abs(a)),
        "pgv_m_s": np.max(np.abs(v)),
        "pgd_m": np.max(np.abs(trapezoid(v, dt))),
        "arias_intensity_m_s": np.pi / (2 * G) * husid[-1],
        "t5_s": dt * np.searchsorted(husid, 0.05 * husid[-1]),
        "t95_s": dt * np.searchsorted(husid, 0.95 * husid[-1]),
        "mean_frequency_hz": power[band].sum() / (power[band] / f[band]).sum(),
        "f99_hz": f[1:][np.searchsorted(cumulative, 0.99 * cumulative[-1])],
    }


def processed_record():
    a, dt = read_peer(RECORD)
    length = dt * (len(a) - 1)
    taper_s = min(0.5, 0.05 * length)
    a = baseline(taper(a, dt, taper_s), dt, 3, taper_s)
    return a, dt


def run_column(build, out):
    directory = os.path.join(out, "records_run")
    subprocess.run([os.path.join(build, "ddafem"), "run", SCENE, "-o", directory, "-q",
                    "--set", "output.interval=16"], check=True)
    summary = json.load(open(os.path.join(directory, "summary.json")))
    with h5py.File(os.path.join(directory, "histories.h5")) as h:
        t = h["time"][:]
        surface = h["monitors/surface/velocity"][:, 0]
        base = h["monitors/base/velocity"][:, 0]
    return summary, t, surface, base


def compare(t, measured, expected, pgv):
    return {"max_error_over_pgv": float(np.max(np.abs(measured - expected)) / pgv),
            "l2_relative": float(np.linalg.norm(measured - expected) / np.linalg.norm(expected))}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(ROOT, "docs/verification"))
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    os.makedirs(os.path.join(args.out, "figures"), exist_ok=True)

    a, dt = processed_record()
    ours = measures(a, dt)
    summary, t, surface, base = run_column(args.build, args.out)
    theirs = summary["records"][0]
    processing = {k: {"numpy": float(ours[k]), "ddafem": theirs[k],
                      "relative_difference": abs(theirs[k] - ours[k]) / abs(ours[k])}
                  for k in ours}

    vs = np.sqrt(50e9 / (2 * 1.25) / 2650)  # the example's rock: E 50 GPa, nu 0.25
    v_rec = trapezoid(a, dt)
    t_rec = dt * np.arange(len(a))
    record_at = lambda time: np.interp(time, t_rec, v_rec, left=0.0, right=v_rec[-1])  # noqa
    delay = HEIGHT / vs
    expected_surface = record_at(t - delay)
    expected_base = 0.5 * (record_at(t) + record_at(t - 2 * delay))
    pgv = ours["pgv_m_s"]
    waves = {"surface": compare(t, surface, expected_surface, pgv),
             "base": compare(t, base, expected_base, pgv)}
    result = {"scene": os.path.relpath(SCENE, ROOT), "record": os.path.relpath(RECORD, ROOT),
              "vs_m_s": vs, "delay_s": delay, "processing": processing, "waves": waves}
    json.dump(result, open(os.path.join(args.out, "records.json"), "w"), indent=2)

    fig, axes = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    for ax, name, measured, expected in ((axes[0], "surface", surface, expected_surface),
                                         (axes[1], "base", base, expected_base)):
        ax.plot(t, expected, "k-", lw=2.2, label="theory")
        ax.plot(t, measured, "C3-", lw=0.9, label="ddafem")
        ax.set_ylabel(f"{name} velocity [m/s]")
        ax.legend(loc="upper right")
    axes[0].set_title("outcrop record v(t - H/VS) at the surface; v_in(t) + v_in(t - 2H/VS) at "
                      "the base")
    axes[1].set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "figures/records_column.png"), dpi=110)

    lines = ["# Recorded ground motions: verification", "",
             "Regenerated by `/usr/bin/python3 tools/verify_records.py` (the method: its "
             "docstring and docs/ground_motions.md).", "",
             f"Record `{result['record']}`, processed by ddafem (summary.json `records`) and "
             "again by numpy in the tool:", "",
             "| measure | numpy | ddafem | relative difference |", "|---|---|---|---|"]
    for k, p in processing.items():
        lines.append(f"| {k} | {p['numpy']:.6g} | {p['ddafem']:.6g} | "
                     f"{p['relative_difference']:.1e} |")
    lines += ["", f"Scene `{result['scene']}`: the outcrop record into a uniform column "
              f"{HEIGHT:.0f} m high with a free top (VS {vs:.1f} m/s, H / VS {delay:.4f} s):", "",
              "| monitor | theory | max difference / PGV | relative L2 |", "|---|---|---|---|"]
    theory = {"surface": "record v(t - H/VS)", "base": "v_in(t) + v_in(t - 2H/VS), v_in = v / 2"}
    for name, w in waves.items():
        lines.append(f"| {name} | {theory[name]} | {w['max_error_over_pgv']:.2%} | "
                     f"{w['l2_relative']:.2%} |")
    lines += ["", "![surface and base](figures/records_column.png)", ""]
    open(os.path.join(args.out, "records.md"), "w").write("\n".join(lines))
    print("\n".join(lines))

    if args.check:
        bad = [k for k, p in processing.items() if p["relative_difference"] > 1e-6]
        bad += [k for k, w in waves.items() if w["max_error_over_pgv"] > 0.02]
        if bad:
            print("FAILED:", ", ".join(bad))
            sys.exit(1)


if __name__ == "__main__":
    main()
