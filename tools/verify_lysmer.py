#!/usr/bin/python3
"""Regenerates docs/verification/lysmer_angles.{md,json,png}: FE-measured against analytic
Lysmer-Kuhlemeyer reflection coefficients of plane P and SV waves (issue 5). Usage:
    tools/verify_lysmer.py [--build build] [--epw 5] [--margin 1] [--runs 4]
Builds nothing: `cmake --build BUILD --target lysmer_angles` first. The analytic coefficients of
the driver (fem/lysmer_reflection.cc) are checked against an independent solve of the boundary
conditions here (numpy, from the stress tensor). Exit 1 if a measured R_P or R_S is more than 0.02
off up to 45 degrees, or if the two analytic solutions disagree."""
import argparse
import json
import pathlib
import subprocess
import time

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
KEYS = ["incident", "angle_deg", "R_P", "R_S", "energy_reflected", "analytic_R_P",
        "analytic_R_S", "analytic_energy"]
RHO, VS = 2000.0, 1000.0  # the driver's medium (tools/lysmer/lysmer_measurement.cc), nu = 0.25
VP = np.sqrt(3.0) * VS
TOLERANCE = 0.02


def reflection(kind, theta_deg, a=1.0, b=1.0):
    """Independent of fem/lysmer_reflection.cc: plane waves u = d exp(i w (p x + eta y - t)) in
    y > 0; the traction sigma.n (n = (0, -1)) of each wave from its full stress tensor must equal
    -D v on y = 0, D = rho diag(b VS, a VP). Returns (|R_P| or None, |R_S| or None, reflected
    energy fraction), displacement amplitudes relative to the incident one."""
    mu = RHO * VS ** 2
    lam = RHO * VP ** 2 - 2.0 * mu
    c_in = VP if kind == "P" else VS
    th = np.radians(theta_deg)
    p = np.sin(th) / c_in
    eta_p = np.sqrt(complex(1.0 / VP ** 2 - p ** 2))  # principal root: imaginary part >= 0
    eta_s = np.sqrt(complex(1.0 / VS ** 2 - p ** 2))

    def p_wave(eta):
        return np.array([p, eta]), VP * np.array([p, eta])

    def s_wave(eta):
        return np.array([p, eta]), VS * np.array([-eta, p])

    def condition(wave):
        s, d = wave
        grad = np.outer(d, s)  # grad u / (i w)
        sigma = lam * np.trace(grad) * np.eye(2) + mu * (grad + grad.T)
        traction = sigma @ np.array([0.0, -1.0])
        velocity = -d  # v / (i w)
        return traction + RHO * np.diag([b * VS, a * VP]) @ velocity

    incident = p_wave(-np.cos(th) / VP) if kind == "P" else s_wave(-np.cos(th) / VS)
    matrix = np.column_stack([condition(p_wave(eta_p)), condition(s_wave(eta_s))])
    r = np.linalg.solve(matrix, -condition(incident))
    flux_in = c_in * np.cos(th)
    out = []
    energy = 0.0
    for coefficient, eta, c in ((r[0], eta_p, VP), (r[1], eta_s, VS)):
        if abs(eta.imag) > 0.0:
            out.append(None)
        else:
            out.append(abs(coefficient))
            energy += abs(coefficient) ** 2 * c * c * eta.real / flux_in
    return out[0], out[1], energy


def fmt(x):
    return "null" if x is None else f"{x:.4f}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--epw", type=float, default=5.0, help="Q2 elements per S wavelength at f0")
    ap.add_argument("--margin", type=float, default=1.0,
                    help="periods between t = 0 and the pulse front reaching a specular point")
    ap.add_argument("--runs", type=int, default=4, help="most fixed-point runs per case")
    ap.add_argument("--from-json", help="reuse a saved lysmer_angles output instead of running")
    args = ap.parse_args()
    start = time.time()
    if args.from_json:
        out = pathlib.Path(args.from_json).read_text()
    else:
        exe = pathlib.Path(args.build) / "tools" / "lysmer" / "lysmer_angles"
        out = subprocess.run([str(exe), "--epw", str(args.epw), "--margin", str(args.margin),
                              "--runs", str(args.runs)],
                             check=True, capture_output=True, text=True).stdout
    runs = json.loads(out)
    wall = time.time() - start

    # The driver's analytic values against the independent solve.
    analytic_mismatch = 0.0
    for r in runs:
        rp, rs, energy = reflection(r["incident"], r["angle_deg"])
        for mine, theirs in ((rp, r["analytic_R_P"]), (rs, r["analytic_R_S"]),
                             (energy, r["analytic_energy"])):
            if (mine is None) != (theirs is None):
                analytic_mismatch = float("inf")
            elif mine is not None:
                analytic_mismatch = max(analytic_mismatch, abs(mine - theirs))

    records = [{k: r[k] for k in KEYS} for r in runs]
    outdir = ROOT / "docs" / "verification"
    outdir.mkdir(parents=True, exist_ok=True)
    (outdir / "lysmer_angles.json").write_text(json.dumps(records, indent=2) + "\n")

    worst = 0.0
    worst_60 = 0.0
    for r in runs:
        for m, a in (("R_P", "analytic_R_P"), ("R_S", "analytic_R_S")):
            if (r[m] is None) != (r[a] is None):
                error = float("inf")
            elif r[m] is None:
                continue
            else:
                error = abs(r[m] - r[a])
            if r["angle_deg"] <= 45:
                worst = max(worst, error)
            else:
                worst_60 = max(worst_60, error)
    passed = worst <= TOLERANCE and analytic_mismatch <= 1e-6  # the driver prints 6 decimals
    seconds = sum(r["seconds"] for r in runs)
    lines = [
        "# Lysmer-Kuhlemeyer boundary: reflection against incidence angle", "",
        "Generated by `tools/verify_lysmer.py` (driver `tools/lysmer/lysmer_angles`: "
        f"{args.epw:g} Q2 elements per S wavelength at the Ricker peak frequency f0 = 10 Hz, "
        "25 steps per period, "
        f"margin {args.margin:g} period, at most {args.runs} fixed-point runs; "
        f"{seconds:.0f} s of runs, {wall:.0f} s wall). Medium: rho = 2000 kg/m^3, VS = 1000 m/s, "
        "nu = 0.25 (VP = 1732 m/s, critical SV angle 35.26 deg). Analytic values: "
        "`fem/lysmer_reflection.h`, derivation in `docs/lysmer.md`; an independent numpy solve of "
        "the boundary conditions in this script agrees to "
        f"{analytic_mismatch:.1e}. R_P, R_S: moduli of the displacement-amplitude ratios of the "
        "reflected P and S waves to the incident wave, null where evanescent; energy: reflected "
        "fraction of the incident energy flux. Method: `docs/lysmer.md` (FE measurement).", "",
        "Acceptance (issue 5): |measured - analytic| <= 0.02 up to 45 degrees.", "",
        "| incident | angle | R_P | analytic R_P | R_S | analytic R_S | energy | analytic energy "
        "| runs | last change | rms misfit | dofs | s |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in runs:
        history = r["runs"]
        change = 0.0
        if len(history) > 1:
            for key in ("R_P", "R_S"):
                if history[-1][key] is not None:
                    change = max(change, abs(history[-1][key] - history[-2][key]))
        lines.append(
            f"| {r['incident']} | {r['angle_deg']:g} | {fmt(r['R_P'])} | "
            f"{fmt(r['analytic_R_P'])} | {fmt(r['R_S'])} | {fmt(r['analytic_R_S'])} | "
            f"{fmt(r['energy_reflected'])} | {fmt(r['analytic_energy'])} | {len(history)} | "
            f"{change:.4f} | {history[-1]['rms_residual']:.4f} | {r['n_dofs']} | "
            f"{r['seconds']:.1f} |")
    lines += [
        "", f"Largest |measured - analytic| up to 45 degrees: {worst:.4f} "
        f"({'PASS' if worst <= TOLERANCE else 'FAIL'} against {TOLERANCE}); at 60 degrees "
        f"(not part of the acceptance): {worst_60:.4f}.", "",
        "runs: FE runs of the fixed-point iteration (run 1 starts from the incident wave alone, "
        "run k from the incident plus the reflected waves measured by run k - 1); last change: "
        "of R_P or R_S in the last run; rms misfit: of the fit over the window, relative to the "
        "rms incident velocity at the monitor.", "",
        "First runs (incident wave alone in the initial state), to show what the iteration "
        "removes:", "",
        "| incident | angle | R_P run 1 | R_S run 1 |", "|---|---|---|---|"]
    for r in runs:
        lines.append(f"| {r['incident']} | {r['angle_deg']:g} | {fmt(r['runs'][0]['R_P'])} | "
                     f"{fmt(r['runs'][0]['R_S'])} |")
    lines += ["", "![measured against analytic](lysmer_angles.png)", ""]
    (outdir / "lysmer_angles.md").write_text("\n".join(lines))

    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    fine = np.linspace(0.0, 70.0, 281)
    for ax, kind in zip(axes, ["P", "SV"]):
        curves = [reflection(kind, a) for a in fine]
        rs = [r for r in runs if r["incident"] == kind]
        for index, (key, colour) in enumerate((("R_P", "C0"), ("R_S", "C1"),
                                               ("energy", "C2"))):
            values = [c[index] for c in curves]
            ax.plot(fine, [np.nan if v is None else v for v in values], "-", color=colour,
                    label=f"{key} analytic")
            mkey = "energy_reflected" if key == "energy" else key
            pts = [(r["angle_deg"], r[mkey]) for r in rs if r[mkey] is not None]
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o", color=colour,
                    label=f"{key} FE")
        if kind == "SV":
            ax.axvline(np.degrees(np.arcsin(VS / VP)), color="0.6", ls=":", lw=1)
        ax.set_title(f"{kind} incidence")
        ax.set_xlabel("incidence angle [deg]")
        ax.grid(True)
    axes[0].set_ylabel("|R| (displacement) / reflected energy fraction")
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(outdir / "lysmer_angles.png", dpi=120)
    print(f"worst |error| up to 45 deg: {worst:.4f} (60 deg: {worst_60:.4f}); analytic check "
          f"{analytic_mismatch:.1e}; wrote {outdir}/lysmer_angles.*")
    return 0 if passed else 1


if __name__ == "__main__":
    raise SystemExit(main())
