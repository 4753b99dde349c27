#!/usr/bin/python3
"""The rock's damping (docs/damping.md, issue 53) against analytic solutions; regenerates
docs/verification/damping.{md,json} and docs/verification/figures/damping_*.png.

  1  Free decay: a 1 m block (2650 kg, stiff: E = 1e13 Pa) on a bonded joint whose two end springs
     p = 1e9 N/m carry it over a base block held by fixed points, thrown upwards at 0.01 m/s: the
     oscillator m x'' + c x' + 2 p x = 0, w = sqrt(2 p / m) = 868.8 rad/s. The joint and the blocks
     damped by RATIO at w / 2 pi, 200 steps a period, four periods. Measured: the top's vertical
     displacement x(t) against x0(t) = v0 / wd exp(-zeta w t) sin(wd t), the largest difference
     over the first peak v0 / w (history_error); the damping ratio from the logarithmic
     decrement between the first and the fourth period's largest |x| (zeta_measured).
     Acceptance: history_error and |zeta_measured / zeta - 1| within 2 %.
  2  Energy budget: the same runs' summary.json: the integrator's residual (`dissipated`) against
     the dashpots' work; acceptance |dissipated| <= 1 % of |work_of_damping| for the trapezoidal
     rule (which conserves energy on a linear model; Bathe's scheme's own dissipation is shown).
  3  Attenuation along the P-wave bar of Bao et al. (2012), three times longer
     (verify_bao2012.LONG_BAR), every block and joint damped by RATIO at 100 Hz (the pulse's).
     Stiffness-proportional damping of the whole makes the bar a Kelvin-Voigt medium: a harmonic
     wave's wavenumber is k(w) = w / (c sqrt(1 + i w beta)). The undamped run gives the bar's own
     transfer from M1 (50.5 m) to M2 (98.5 m), T(w) = S2(w) / S1(w) (its discreteness and
     dispersion); the damped M2 is predicted as S1_damped(w) T(w) exp(-i (k(w) - w / c) 48 m) and
     compared with the measured one: relative L2 over M2's window (0 to 98.5 m / c + one period +
     2 ms). Acceptance: within 2 %. The peak's attenuation over 48 m is shown beside exp(-zeta w
     48 m / c).
  4  Newmark's sliding block and the roof wedge and keyblock of tools/verify_failure.py with every
     material and joint material damped by 5 % (at the base motion's frequency; 10 Hz for the
     roof scenes): the errors against the same undamped analytic solutions, acceptance within
     verify_failure's ACCEPT_SLIDE (1 %): the damping acts on deformation only, never on a
     sliding or falling block.

usage: /usr/bin/python3 tools/verify_damping.py [--build build] [--jobs 2]
           [--out docs/verification]
"""
import argparse
import json
import math
import os
import sys
import tempfile
import time

import matplotlib
import numpy as np
import yaml

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(TOP, "tools"))
sys.path.insert(0, os.path.join(TOP, "bench"))
import verify_bao2012 as BAO  # noqa: E402
import verify_failure as VF  # noqa: E402
import speed_accuracy as SA  # noqa: E402

RATIO = 0.05
ACCEPT = 0.02            # free decay, zeta and the bar
ACCEPT_ENERGY = 0.01     # |dissipated| / |work_of_damping|, trapezoidal
P, RHO, V0 = 1e9, 2650.0, 0.01
OMEGA = math.sqrt(2.0 * P / RHO)
PERIODS = 4
BAR_FREQUENCY = 100.0    # Hz, the bar's pulse
BAR_DT = 5e-5
ROOF_FREQUENCY = 10.0    # Hz: the roof scenes have no input; any frequency holds the ratio
INTEGRATORS = ["newmark_trapezoidal", "bathe"]
DT_CASE = "two_way_flat_4Hz"  # section 4b: six reversals without a stick phase, the hardest case
DT_DIVISORS = (1, 2, 4)


def damping(frequency):
    return {"ratio": RATIO, "frequency": float(frequency)}


def damp_scene(path, frequency):
    """Adds `damping` to every material and joint material of the scene file at `path`."""
    with open(path) as f:
        scene = yaml.safe_load(f)
    for section in ("materials", "joint_materials"):
        for material in scene.get(section, {}).values():
            material["damping"] = damping(frequency)
    return VF.write_scene(scene, path)


def oscillator_scene(directory, ratio):
    f0 = OMEGA / (2.0 * math.pi)
    dt = 1.0 / f0 / 200.0
    material = {"density": RHO, "youngs_modulus": 1e13, "poisson_ratio": 0.25}
    joint = {"normal_stiffness": P, "friction_angle": 45, "cohesion": 1e9,
             "tensile_strength": 1e9, "bonded": True}
    if ratio > 0:
        material["damping"] = joint["damping"] = {"ratio": ratio, "frequency": f0}
    scene = {
        "name": f"oscillator_{ratio:g}",
        "materials": {"stiff": material},
        "joint_materials": {"joint": joint},
        "joints": {"default": "joint"},
        "blocks": [{"material": "stiff", "vertices": [[0, 0], [1, 0], [1, 1], [0, 1]]},
                   {"material": "stiff", "vertices": [[0, 1], [1, 1], [1, 2], [0, 2]],
                    "initial_velocity": [0, V0]}],
        "fixed_points": [{"point": p} for p in ([0.1, 0.1], [0.9, 0.1], [0.5, 0.9])],
        "monitors": [{"name": "top", "point": [0.5, 1.5]}],
        "time": {"dt": dt, "end_time": PERIODS / f0, "control": "fixed"},
    }
    return VF.write_scene(scene, os.path.join(directory, f"oscillator_{ratio:g}.yaml")), dt


def decay_row(r):
    ok, status = VF.run_status(r)
    row = {"integrator": r["integrator"], "status": status}
    if not ok:
        return row, None
    t, m = VF.monitors(r)
    x = m["top"][:, 1]
    z = RATIO
    wd = OMEGA * math.sqrt(1.0 - z * z)
    exact = V0 / wd * np.exp(-z * OMEGA * t) * np.sin(wd * t)
    period = 2.0 * math.pi / OMEGA

    def largest(k):
        keep = (t > k * period) & (t <= (k + 1) * period)
        return float(np.max(np.abs(x[keep])))

    decrement = math.log(largest(0) / largest(PERIODS - 1)) / (PERIODS - 1)
    zeta = decrement / math.sqrt(4.0 * math.pi ** 2 + decrement ** 2)
    e = r["summary"].get("energy_J", {})
    row.update(history_error=float(np.max(np.abs(x - exact)) / (V0 / OMEGA)),
               zeta_measured=zeta, zeta_error=abs(zeta / z - 1.0),
               work_of_damping=e.get("work_of_damping"), dissipated=e.get("dissipated"),
               initial=e.get("initial"))
    row["energy_residual"] = abs(row["dissipated"]) / abs(row["work_of_damping"])
    row["pass"] = row["history_error"] <= ACCEPT and row["zeta_error"] <= ACCEPT and (
        r["integrator"] != "newmark_trapezoidal" or row["energy_residual"] <= ACCEPT_ENERGY)
    return row, (t, x, exact)


def bar_prediction(t, s1_damped, s1, s2, beta, c, distance):
    """The damped M2 record predicted from the damped M1, the undamped bar's transfer M1 -> M2
    and the Kelvin-Voigt attenuation over `distance` [m]."""
    n = 4 * len(t)
    w = 2.0 * math.pi * np.fft.rfftfreq(n, t[1] - t[0])
    f1, f1d, f2 = (np.fft.rfft(s, n) for s in (s1, s1_damped, s2))
    keep = np.abs(f1) > 1e-6 * np.max(np.abs(f1))
    transfer = np.where(keep, f2 / np.where(keep, f1, 1.0), 0.0)
    k_damped = w / (c * np.sqrt(1.0 + 1j * w * beta))
    predicted = f1d * transfer * np.exp(-1j * (k_damped - w / c) * distance)
    return np.fft.irfft(predicted, n)[: len(t)]


def bar_row(damped, undamped):
    ok, status = VF.run_status(damped)
    ok_u, status_u = VF.run_status(undamped)
    row = {"status": status if ok else status, "undamped_status": status_u}
    if not (ok and ok_u):
        return row, None
    t, x = VF.bar_sxx(damped)
    t_u, x_u = VF.bar_sxx(undamped)
    c = BAO.jointed_speed(BAO.E, 2.0 * 2.5e12)
    beta = RATIO / (math.pi * BAR_FREQUENCY)
    distance = 98.5 - 50.5
    # Both runs on one time grid (the same fixed dt): the undamped M1, M2 onto the damped times.
    s1 = np.interp(t, t_u, x_u["M1"])
    s2 = np.interp(t, t_u, x_u["M2"])
    predicted = bar_prediction(t, x["M1"], s1, s2, beta, c, distance)
    t1 = VF.bar_record_windows()["M2"]
    error = SA.relative_l2(t, x["M2"], t, predicted, t1)
    keep = t <= t1
    row.update(record_error=error, peak_ratio=float(np.max(np.abs(x["M2"][keep])) /
                                                    np.max(np.abs(x_u["M2"][t_u <= t1]))),
               plane_wave_ratio=math.exp(-RATIO * 2 * math.pi * BAR_FREQUENCY * distance / c),
               pass_=error <= ACCEPT)
    row["pass"] = row.pop("pass_")
    return row, (t, x["M2"], predicted, s2)


def dt_study_jobs(scenes, references):
    """DT_CASE damped and undamped at NEWMARK_DT / k, k in DT_DIVISORS (section 4b)."""
    case = next(c for c in VF.NEWMARK_CASES if c["name"] == DT_CASE)
    base, phases = references[DT_CASE]
    end = VF.newmark_end_time(case, phases)
    jobs = []
    for variant in ("damped", "undamped"):
        folder = os.path.join(scenes, "dt_study_" + variant)
        os.makedirs(folder, exist_ok=True)
        scene = VF.newmark_scene(case, folder, end, VF.NEWMARK_DT)
        if variant == "damped":
            scene = damp_scene(scene, case["frequency"])
        for k in DT_DIVISORS:
            dt = VF.NEWMARK_DT / k
            jobs.append(SA.spec("newmark_dt", "bathe", variant, scene, {"time.dt": dt},
                                case_name=DT_CASE, integrator="bathe", dt=dt, est_s=end * k))
    return jobs


def dt_study_rows(results, references):
    """Per run of the dt study: dt, damped or not, the errors and the reversals localised."""
    runs = [r for r in results if r["case"] == "newmark_dt"]
    rows, _ = VF.newmark_rows(runs, {c["name"]: c for c in VF.NEWMARK_CASES}, references)
    for row, r in zip(rows, runs):
        row["variant"] = r["variant"]
        row["slip_reversals"] = r["summary"].get("time_step", {}).get("slip_reversals")
    return rows


def jobs_of(scenes):
    """Every run: the oscillator (damped with each integrator, undamped with the default), the
    long bar damped and undamped, Newmark's cases and the roof scenes damped."""
    jobs = []
    osc, dt = oscillator_scene(scenes, RATIO)
    for name in INTEGRATORS:
        jobs.append(SA.spec("decay", name, "damped", osc, {"time.integrator": name},
                            integrator=name, dt=dt, est_s=1.0))
    bar = {**BAO.LONG_BAR, "time.dt": BAR_DT, "time.control": "fixed",
           "time.integrator": "newmark_trapezoidal"}
    damped_bar = {**bar, "materials.rock.damping.ratio": RATIO,
                  "materials.rock.damping.frequency": BAR_FREQUENCY,
                  "joint_materials.bonded.damping.ratio": RATIO,
                  "joint_materials.bonded.damping.frequency": BAR_FREQUENCY}
    jobs.append(SA.spec("bar", "newmark_trapezoidal", "damped", BAO.BAR, damped_bar, dt=BAR_DT, est_s=30.0))
    jobs.append(SA.spec("bar", "newmark_trapezoidal", "undamped", BAO.BAR, bar, dt=BAR_DT, est_s=30.0))
    references = {}
    for case in VF.NEWMARK_CASES:
        base = VF.newmark_base(case)
        phases = VF.newmark_reference(case["incline"], case["friction"], base, base.T + 1.5)
        end = VF.newmark_end_time(case, phases)
        references[case["name"]] = (base, phases)
        scene = damp_scene(VF.newmark_scene(case, scenes, end, VF.NEWMARK_DT), case["frequency"])
        jobs.append(SA.spec("newmark", "bathe", case["name"], scene, {}, case_name=case["name"],
                            integrator="bathe", dt=VF.NEWMARK_DT, est_s=end))
    jobs += dt_study_jobs(scenes, references)
    for case in VF.ROOF_CASES:
        scene = damp_scene(VF.roof_scene(case, scenes, VF.ROOF_DT), ROOF_FREQUENCY)
        jobs.append(SA.spec("roof", "bathe", case["name"], scene, {}, case_name=case["name"],
                            integrator="bathe", dt=VF.ROOF_DT, est_s=case["end_time"]))
    return jobs, references


def figures(decay_curves, bar_curve, out):
    fig, ax = plt.subplots(figsize=(7, 3.5))
    for name, (t, x, exact) in decay_curves.items():
        ax.plot(1e3 * t, 1e6 * x, label=f"ddafem, {name}")
    if decay_curves:
        t, _, exact = next(iter(decay_curves.values()))
        ax.plot(1e3 * t, 1e6 * exact, "k--", lw=1, label="damped oscillator (exact)")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("x [um]")
    ax.set_title(f"Free decay of a block on a joint, {100 * RATIO:g} % of critical")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "figures", "damping_decay.png"), dpi=110)
    plt.close(fig)
    if bar_curve is None:
        return
    t, measured, predicted, undamped = bar_curve
    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.plot(1e3 * t, 1e-3 * undamped, color="0.6", label="undamped")
    ax.plot(1e3 * t, 1e-3 * measured, label="damped, ddafem")
    ax.plot(1e3 * t, 1e-3 * predicted, "k--", lw=1, label="damped, Kelvin-Voigt prediction")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("sxx at M2 (98.5 m) [kPa]")
    ax.set_xlim(0, 1e3 * VF.bar_record_windows()["M2"])
    ax.set_title(f"P-wave bar, {100 * RATIO:g} % at {BAR_FREQUENCY:g} Hz")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "figures", "damping_bar.png"), dpi=110)
    plt.close(fig)


def fmt(value, digits=3):
    return "-" if value is None else f"{value:.{digits}g}"


def dt_study_lines(rows):
    def passing(variant):
        dts = [f"{r['dt']:g} s" for r in rows if r["variant"] == variant and r["pass"]]
        return ", ".join(dts) if dts else "none"
    lines = [f"## 4b. {DT_CASE} in dt", "",
             "The hardest of the cases (six reversals without a stick phase; Bathe, scenes' "
             f"dt 1 ms), damped by {100 * RATIO:g} % and undamped, at dt / 1, 2, 4 (where the "
             "sliding reverses, friction acts the wrong way for part of a step unless the "
             "reversal is localised and the integrator restarted at the turn, also after a "
             "stick as short as one step; a stiff contact left undamped rings, sticking and "
             "slipping by turns, with nothing but the integrator to damp it). Within 1 %: damped at "
             f"{passing('damped')}; undamped at {passing('undamped')}.", "",
             "| run | dt [s] | final error | history error | reversals localised | pass |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['variant']} | {r['dt']:g} | {fmt(r.get('final_error'))} | "
                     f"{fmt(r.get('history_error'))} | {r.get('slip_reversals')} | "
                     f"{r['pass']} |")
    return lines + [""]


def write_markdown(path, data):
    d, b = data["decay"], data["bar"]
    lines = [
        "# Damping of the rock: verification",
        "",
        "Regenerated by `/usr/bin/python3 tools/verify_damping.py` "
        f"({data['elapsed_s']:.0f} s, {data['version']}). The damping's form and keys: "
        "[docs/damping.md](../damping.md).",
        "",
        f"## 1, 2. Free decay of a block on a joint ({100 * RATIO:g} % of critical)",
        "",
        f"Oscillator w = {OMEGA:.1f} rad/s, 200 steps a period, {PERIODS} periods. Acceptance: "
        f"history within {100 * ACCEPT:g} % of the first peak, zeta within {100 * ACCEPT:g} % "
        f"of itself, and (trapezoidal rule) the residual within {100 * ACCEPT_ENERGY:g} % of "
        "the dashpots' work.",
        "",
        "| integrator | history error | zeta measured | zeta error | work of damping [J] | "
        "residual [J] | residual / work | pass |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in d:
        lines.append(f"| {r['integrator']} | {fmt(r.get('history_error'))} | "
                     f"{fmt(r.get('zeta_measured'), 4)} | {fmt(r.get('zeta_error'))} | "
                     f"{fmt(r.get('work_of_damping'))} | {fmt(r.get('dissipated'))} | "
                     f"{fmt(r.get('energy_residual'))} | {r.get('pass', r['status'])} |")
    lines += ["", "![free decay](figures/damping_decay.png)", "",
              f"## 3. Attenuation along the P-wave bar ({100 * RATIO:g} % at "
              f"{BAR_FREQUENCY:g} Hz)", "",
              "The damped M2 record predicted from the damped M1 record, the undamped bar's own "
              "transfer M1 -> M2 and the Kelvin-Voigt attenuation exp(-i (k(w) - w / c) 48 m), "
              "k(w) = w / (c sqrt(1 + i w beta)).", "",
              "| record error (M2) | peak damped / undamped at M2 | plane wave at 100 Hz | "
              "pass |", "|---|---|---|---|",
              f"| {fmt(b.get('record_error'))} | {fmt(b.get('peak_ratio'))} | "
              f"{fmt(b.get('plane_wave_ratio'))} | {b.get('pass', b.get('status'))} |",
              "", "![bar](figures/damping_bar.png)", "",
              f"## 4. Sliding and falling blocks, damped by {100 * RATIO:g} %", "",
              "The cases of [failure.md](failure.md) with every material and joint material "
              "damped, against the same undamped analytic solutions; acceptance within "
              f"{100 * VF.ACCEPT_SLIDE:g} % (final and history), as there.", "",
              "| case | final error | history error | pass |", "|---|---|---|---|"]
    for r in data["newmark"] + data["roof"]:
        extra = "" if r.get("final_error") is not None else f" (largest {fmt(r.get('max_abs_m'))} m)"
        lines.append(f"| {r['case']} | {fmt(r.get('final_error'))}{extra} | "
                     f"{fmt(r.get('history_error'))} | {r['pass']} |")
    lines += ["", f"All pass: **{data['all_pass']}**.", ""] + dt_study_lines(data["dt_study"])
    with open(path, "w") as f:
        f.write("\n".join(lines))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "verification"))
    args = parser.parse_args()
    start = time.monotonic()
    out = os.path.abspath(args.out)
    os.makedirs(os.path.join(out, "figures"), exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="verify_damping_") as root:
        ddafem = VF.frozen_binary(os.path.abspath(args.build), root)
        scenes = os.path.join(root, "scenes")
        os.makedirs(scenes)
        jobs, references = jobs_of(scenes)
        results = SA.run_all(ddafem, jobs, root, args.jobs)
        decay, decay_curves = [], {}
        for r in [r for r in results if r["case"] == "decay"]:
            row, curve = decay_row(r)
            decay.append(row)
            if curve:
                decay_curves[r["integrator"]] = curve
        bars = {r["variant"]: r for r in results if r["case"] == "bar"}
        bar, bar_curve = bar_row(bars["damped"], bars["undamped"])
        newmark, _ = VF.newmark_rows([r for r in results if r["case"] == "newmark"],
                                     {c["name"]: c for c in VF.NEWMARK_CASES}, references)
        dt_study = dt_study_rows(results, references)
        roof, _ = VF.roof_rows([r for r in results if r["case"] == "roof"],
                               {c["name"]: c for c in VF.ROOF_CASES})
        figures(decay_curves, bar_curve, out)
        data = {"ratio": RATIO, "decay": decay, "bar": bar, "newmark": newmark, "roof": roof,
                "dt_study": dt_study,
                "version": VF.binary_version(ddafem),
                "elapsed_s": time.monotonic() - start}
    data["all_pass"] = bool(all(r.get("pass") for r in decay + newmark + roof + [bar]))
    with open(os.path.join(out, "damping.json"), "w") as f:
        json.dump(data, f, indent=1, default=float)
    write_markdown(os.path.join(out, "damping.md"), data)
    print(f"damping: all pass {data['all_pass']} ({data['elapsed_s']:.0f} s) -> "
          f"{os.path.join(out, 'damping.md')}")
    return 0 if data["all_pass"] else 1


if __name__ == "__main__":
    sys.exit(main())
