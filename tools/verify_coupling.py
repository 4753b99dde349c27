#!/usr/bin/python3
"""Regenerates the verification of the coupling between DDA blocks and the deal.II far field:

  docs/verification/interface.{json,md,png}       transparency of the tie interface
  docs/verification/head_to_head.{json,md}        hybrid truncation against DDA-native boundaries
  docs/verification/figures/head_to_head_*.png

1. Interface transparency. Runs `BUILD/tests/test_coupling --gtest_filter=*InterfaceTransparency.*`
   with DDAFEM_TRANSPARENCY_RECORDS=<file>: each test appends one JSON line {wave, direction,
   block_size_m, element_size_m, reflection, energy_mismatch, dt_s, coupled, reference}, the
   monitor displacement per step of a plane P or S pulse crossing the interface (blocks into the
   far field, or the far field into the blocks) and of a model without the interface.
   reflection = max|coupled - reference| / max|reference|; energy_mismatch = |energy that
   arrived - energy that crossed the ties| / crossed. Acceptance (the tests' limits): reflection
   < 1% with elements as large as the blocks, < 3% with elements four times larger; energy
   mismatch < 1%. interface.png: per record the two histories and their difference x10.

2. Head to head on the benchmarks of Bao, Hatzor & Huang (2012) (tools/verify_bao2012.py is
   imported for its scenes, windows, long reference models and efficiency definitions):
     p_wave_bar     examples/bao2012/p_wave_bar.yaml, 100 Hz, dt 1e-5, 5e-5, 1e-4; sxx at M1 =
                    50.5 m. Truncation at x = 100 m by
                    (a) VB I on the 100th block (textbook or effective impedance),
                    (b) the consistent dashpot (textbook or effective impedance),
                    (c) the hybrid examples/coupled/p_wave_bar_hybrid.yaml: 60 blocks tied to a
                        40 m FE bar with a Lysmer end.
     s_wave_column  examples/bao2012/s_wave_column.yaml, joint stiffness 2500 GN/m, dt 1e-5 and
                    5e-5; ux at M1 (y = 31.5 m). (a) and (b) on the top y = 51 m, (c) the hybrid
                    examples/coupled/s_wave_column_hybrid.yaml: base and 35 layers tied to a
                    15 m FE column (rollers on its sides) with a Lysmer top.
   Efficiencies (verify_bao2012.efficiencies): eta_window = 1 - |Ar| / |Ai| with Ar the run's
   own extremum in the reflection window; eta_boundary = 1 - max|run - long| / max|free - long|
   in that window, `long` the model three times longer (nothing comes back in the window) and
   `free` the benchmark with a free end, both at the same dt and shared by all methods.
   record_error = max|run - long| from t = 0 to the end of the reflection window over the long
   model's incident peak: it also sees what the windows miss, e.g. a reflection from the
   hybrid's interface, which reaches M1 within the incident window.
   Energy budget of each run at its end (summary.json): put in = work of loads and supports;
   absorbed = by viscous boundaries and Lysmer dashpots; left = kinetic, strain and spring
   energy of blocks and far field and the tie springs; dissipated = the integrators'
   algorithmic damping (put in = absorbed + left + dissipated). Wall times are ddafem's own
   (summary.json wall_time_s), measured with --jobs runs at a time.
   Acceptance: (c) absorbs at least as well (eta_boundary) as the best DDA-native boundary,
   per benchmark and dt.
   Diagnostic (not part of the acceptance): the hybrid with a far field of the intact rock
   instead of the scenes' rock mass (the blocks with their joints as one continuum): the
   stiffer far field reflects at the interface.

3. The 2D case examples/coupled/point_source_2d.yaml: the far field truncated at +-40, +-60,
   +-80 m with Lysmer dashpots and springs (the scene's boundaries) and without the springs (a
   temporary copy of the scene with the `springs` entries removed), against the far field
   truncated at +-120 m (no reflection returns within the 0.04 s window), all with the scene's
   far elements of 5 m (a size that divides every rectangle, so that the meshes agree where they
   overlap; ctest cli.coupled_point_source_2d compares +-80 m against +-120 m).
   Per run the worst relative L2 difference over the monitors, sqrt(sum |x - x_ref|^2 /
   sum |x_ref|^2) over time and both components (as tests/tools/compare_histories.py), of
   displacement and of velocity; the wall time and far-field DOFs.

--quick: dt 1e-5 only, VB I and the hybrid only, the 2D case at +-80 m only.
Runs go to a pool of --jobs worker processes, each running one ddafem at a time.

usage: /usr/bin/python3 tools/verify_coupling.py [--build build] [--jobs 2] [--quick]
"""
import argparse
import concurrent.futures
import importlib.util
import json
import math
import os
import re
import subprocess
import tempfile
import time

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def load_bao2012():
    spec = importlib.util.spec_from_file_location(
        "verify_bao2012", os.path.join(TOP, "tools", "verify_bao2012.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


BAO = load_bao2012()
POINT_SOURCE = os.path.join(TOP, "examples/coupled/point_source_2d.yaml")

DDA_METHODS = [("vb1", "textbook"), ("vb1", "effective"), ("dashpot", "textbook"),
               ("dashpot", "effective")]
HYBRID = ("hybrid", None)
# A diagnostic, not part of the acceptance: the hybrids with a far field of the intact rock
# instead of the rock mass their scenes use. The jointed blocks are softer than the intact rock
# (the column: two normal springs p = 2500 GN/m per 50 m joint in series with a 1 m layer give
# E_eff = 1 / (1/E + 50 m / 2p) = 33.3 GPa, the shear springs G_eff = 2/3 G likewise): a far
# field of intact rock is an impedance contrast at the interface, which reflects.
HYBRID_INTACT = ("hybrid_intact", None)
INTACT_ROCK = {"far_field.material": "rock"}
# E_eff = 1 / (1/E + L / 2p) of the blocks with their joints (edge length L, 1 m blocks).
BAR_MASS_E = 1.0 / (1.0 / BAO.E + 1.0 / (2.0 * 2.5e12))
COLUMN_MASS_E = 1.0 / (1.0 / BAO.E + 50.0 / (2.0 * 2.5e12))
LABEL = {("vb1", "textbook"): "VB I", ("vb1", "effective"): "VB I (effective Z)",
         ("dashpot", "textbook"): "dashpot", ("dashpot", "effective"): "dashpot (effective Z)",
         HYBRID: "hybrid (FE + Lysmer)",
         HYBRID_INTACT: "hybrid, far field of intact rock"}

# What each benchmark truncates, where its efficiency is measured and against which windows.
BENCHMARKS = {
    "p_wave_bar": {
        "title": "P-wave bar (Bao et al. 2012, section 4.1), 100 Hz, sxx at M1 = 50.5 m",
        "scene": BAO.BAR, "hybrid": os.path.join(TOP, "examples/coupled/p_wave_bar_hybrid.yaml"),
        "long": BAO.LONG_BAR, "quantity": "stress", "scale": 1e-6, "unit": "sxx [MPa]",
        "windows": BAO.bar_windows(100.0), "dts": [1e-5, 5e-5, 1e-4], "mass_e": BAR_MASS_E,
        "hybrid_text": "60 blocks + 40 m FE bar of the rock mass (E_eff = 49.5 GPa), Lysmer "
                       "end (a = 0.9682)", "diagnostics": [HYBRID_INTACT],
    },
    "s_wave_column": {
        "title": "S-wave column (Bao et al. 2012, section 4.2), p = 2500 GN/m, ux at M1 "
                 "(y = 31.5 m)",
        "scene": BAO.COLUMN,
        "hybrid": os.path.join(TOP, "examples/coupled/s_wave_column_hybrid.yaml"),
        "long": BAO.LONG_COLUMN, "quantity": "displacement", "scale": 1e3, "unit": "ux [mm]",
        "windows": BAO.column_windows(2.5e12)[:2], "dts": [1e-5, 5e-5], "mass_e": COLUMN_MASS_E,
        "hybrid_text": "base + 35 layers + 15 m FE column of the rock mass (E_eff = 33.3 GPa), "
                       "rollers, Lysmer top",
        "diagnostics": [HYBRID_INTACT],
    },
}
TRUNCATIONS = [40, 60, 80]
REFERENCE_TRUNCATION = 120  # no reflection returns to a monitor within the 0.04 s window
POINT_SOURCE_METHODS = ["lysmer+springs", "lysmer"]
# The scene's far elements: 5 m divides every rectangle, so that all truncations share the mesh
# where they overlap and differ by the truncation alone (sized from a frequency instead, the
# elements would be adjusted to each rectangle, and meshes that differ make differences of their
# own).
COMMON_ELEMENT_SIZE = 5.0


# ---- running ddafem ---------------------------------------------------------------------------

def energy_budget(summary):
    """{put_in, absorbed, left, dissipated} [J] at the end of a run, blocks and far field."""
    blocks = summary["energy_J"]
    far = summary.get("far_field", {}).get("energy_J", {})
    ties = summary.get("interface", {}).get("tie_energy_J", 0.0)
    return {
        "put_in": blocks["work_of_loads"] + blocks["work_of_supports"] + far.get("work_of_input", 0.0),
        "absorbed": -blocks["work_of_boundaries"] - far.get("work_of_dashpots", 0.0),
        "left": blocks["kinetic"] + blocks["strain"] + blocks["spring"]
                + far.get("kinetic", 0.0) + far.get("strain", 0.0) + ties,
        # Rayleigh damping (none in these scenes) is dissipation too.
        "dissipated": blocks["dissipated"] + far.get("dissipated", 0.0)
                      - far.get("work_of_rayleigh", 0.0),
    }


def run(ddafem, scene, settings):
    """Runs a scene with --set overrides; returns {wall_s, far_field_dofs, element_size_m (of
    the far field), energy_J, time, monitors: {name: {displacement, velocity, stress}}}."""
    with tempfile.TemporaryDirectory() as out:
        cmd = [ddafem, "run", scene, "-o", out, "--quiet"]
        for key, value in settings.items():
            cmd += ["--set", f"{key}={value}"]
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode != 0:
            raise RuntimeError(f"failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stderr}")
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        with h5py.File(os.path.join(out, "histories.h5"), "r") as f:
            times = f["time"][:]
            monitors = {name: {q: f[f"monitors/{name}/{q}"][:]
                               for q in ("displacement", "velocity", "stress")}
                        for name in f["monitors"]}
    return {"wall_s": summary["wall_time_s"],
            "far_field_dofs": summary["model"].get("far_field_dofs", 0),
            "element_size_m": summary["model"].get("element_size_m", 0.0),
            "energy_J": energy_budget(summary), "time": times, "monitors": monitors}


def run_transparency_tests(test_coupling):
    """The InterfaceTransparency tests' records (one dict per test) and whether gtest passed."""
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "records.jsonl")
        try:
            proc = subprocess.run([test_coupling, "--gtest_filter=*InterfaceTransparency.*"],
                                  env={**os.environ, "DDAFEM_TRANSPARENCY_RECORDS": path},
                                  capture_output=True, text=True)
        except OSError as e:
            raise RuntimeError(f"cannot run {test_coupling} ({e}); build it: "
                               "cmake --build build --target test_coupling") from e
        if proc.returncode not in (0, 1) or not os.path.exists(path):
            raise RuntimeError(f"{test_coupling} wrote no records (rc {proc.returncode}); rebuild "
                               f"it: cmake --build build --target test_coupling\n{proc.stdout[-2000:]}")
        with open(path) as f:
            return [json.loads(line) for line in f], proc.returncode == 0


# ---- 1. interface transparency ----------------------------------------------------------------

ENERGY_LIMIT = 0.01


def reflection_limit(record):
    return 0.03 if record["element_size_m"] > record["block_size_m"] else 0.01


def interface_summary(records):
    keys = ["wave", "direction", "integrator", "block_size_m", "element_size_m", "reflection",
            "energy_mismatch"]
    rows = []
    for r in records:
        row = {k: r[k] for k in keys}
        row["reflection_limit"] = reflection_limit(r)
        row["passed"] = r["reflection"] < row["reflection_limit"] and r["energy_mismatch"] < ENERGY_LIMIT
        rows.append(row)
    return rows


def figure_interface(records, path):
    ncols = 2
    nrows = math.ceil(len(records) / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(11, 3.0 * nrows), squeeze=False)
    for ax, r in zip(axes.flat, records):
        coupled, reference = np.array(r["coupled"]), np.array(r["reference"])
        n = min(len(coupled), len(reference))
        t = 1e3 * r["dt_s"] * np.arange(1, n + 1)
        ax.plot(t, 1e3 * reference[:n], "k-", lw=2.0, alpha=0.4, label="without interface")
        ax.plot(t, 1e3 * coupled[:n], "C0--", lw=1.0, label="coupled")
        ax.plot(t, 1e4 * (coupled[:n] - reference[:n]), "C3-", lw=1.0, label="difference x10")
        ax.set_title(f"{r['wave']} wave, {r['direction'].replace('_', ' ')} ({r['integrator'].replace('newmark_', '')}), blocks "
                     f"{r['block_size_m']:g} m / elements {r['element_size_m']:g} m: "
                     f"reflection {100 * r['reflection']:.2f}%", fontsize=8)
        ax.set_ylabel("displacement [mm]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    for ax in axes.flat[len(records):]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel("time [ms]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_interface(out, records, gtest_passed):
    """interface.{json,md,png} in `out`; returns the table's rows."""
    rows = interface_summary(records)
    with open(os.path.join(out, "interface.json"), "w") as f:
        json.dump(rows, f, indent=1)
    write_interface_markdown(os.path.join(out, "interface.md"), rows, gtest_passed)
    figure_interface(records, os.path.join(out, "interface.png"))
    for r in rows:
        print(f"interface {r['wave']} {r['direction']:20s} {r['integrator']:19s} h "
              f"{r['element_size_m']:g} m: reflection {100 * r['reflection']:.2f}% "
              f"(< {100 * r['reflection_limit']:g}%), energy {r['energy_mismatch']:.1e}: "
              f"{'pass' if r['passed'] else 'FAIL'}")
    return rows


def write_interface_markdown(path, rows, gtest_passed):
    with open(path, "w") as f:
        f.write("# Tie interface: transparency to plane waves\n\n")
        f.write("Generated by `/usr/bin/python3 tools/verify_coupling.py` from "
                "`tests/test_coupling --gtest_filter=*InterfaceTransparency.*` "
                "(tests/coupling/test_interface_transparency.cc). A one-cycle 100 Hz plane P or "
                "S pulse from the base of a 20 m wide column crosses the interface at 40 m between "
                "bonded 1 m layers and the far field, one way or the other; the blocks with the "
                "trapezoidal rule or Bathe's composite scheme (the coupled scenes' default), the "
                "far field with the trapezoidal rule on each of the blocks' steps (each half step "
                "of Bathe's; the reference too), dt 2e-5 s, nu = 0, joints and ties stiff (0.1% of a layer's "
                "compliance); the monitor 20.5 m above the base, on the source's side, 0.03 s. "
                "reflection = max|coupled - reference| / max|reference| of the monitor "
                "displacement against a model without the interface; energy mismatch = "
                "|arrived - crossed| / crossed (crossed: the ties' work, arrived: what the "
                "receiving side holds and absorbed).\n\n")
        f.write("Acceptance: reflection < 1% with elements as large as the blocks, < 3% with "
                "elements four times larger; energy mismatch < 1%.\n\n")
        f.write("| wave | direction | blocks' integrator | block [m] | element [m] | reflection | "
                "limit | energy mismatch | limit | result |\n"
                "|---|---|---|---:|---:|---:|---:|---:|---:|---|\n")
        for r in rows:
            f.write(f"| {r['wave']} | {r['direction'].replace('_', ' ')} | "
                    f"{r['integrator'].replace('newmark_', '')} | {r['block_size_m']:g} | "
                    f"{r['element_size_m']:g} | {100 * r['reflection']:.2f}% | "
                    f"{100 * r['reflection_limit']:g}% | {r['energy_mismatch']:.1e} | "
                    f"{ENERGY_LIMIT:g} | {'pass' if r['passed'] else 'FAIL'} |\n")
        f.write(f"\ngtest: {'all passed' if gtest_passed else 'FAILED'}.\n\n")
        f.write("![monitor histories](interface.png)\n")


# ---- 2. head to head on the paper's benchmarks ------------------------------------------------

def method_settings(benchmark, method, dt):
    """(scene, --set overrides) of a method at a time step."""
    spec = BENCHMARKS[benchmark]
    if method == HYBRID:
        return spec["hybrid"], {"time.dt": dt}
    if method == HYBRID_INTACT:
        return spec["hybrid"], {"time.dt": dt, **INTACT_ROCK}
    return spec["scene"], {"time.dt": dt, **BAO.boundary_settings(*method)}


def submit_benchmark(pool, ddafem, benchmark, dts, methods):
    spec = BENCHMARKS[benchmark]
    jobs = {}
    for dt in dts:
        jobs[("long", dt)] = pool.submit(run, ddafem, spec["scene"], {"time.dt": dt, **spec["long"]})
        jobs[("free", dt)] = pool.submit(run, ddafem, spec["scene"], {"time.dt": dt})
        for method in methods:
            jobs[(method, dt)] = pool.submit(run, ddafem, *method_settings(benchmark, method, dt))
    return jobs


def monitor_signal(result, quantity):
    """The efficiency's signal at M1: sxx or ux."""
    return result["monitors"]["M1"][quantity][:, 0]


def benchmark_records(benchmark, jobs, dts, methods):
    """Records per method and dt, and the finished runs {key: result}."""
    spec = BENCHMARKS[benchmark]
    incident, reflected = spec["windows"]
    results = {key: job.result() for key, job in jobs.items()}
    records = []
    for dt in dts:
        long, free = results[("long", dt)], results[("free", dt)]
        long_signal = monitor_signal(long, spec["quantity"])
        peak = BAO.window_max(long["time"], long_signal, *incident)
        for method in methods:
            r = results[(method, dt)]
            signal = monitor_signal(r, spec["quantity"])
            eta_w, eta_b, _ = BAO.efficiencies(
                r["time"], signal, long["time"], long_signal,
                free["time"], monitor_signal(free, spec["quantity"]), incident, reflected)
            difference = signal - BAO.interpolate(long["time"], long_signal, r["time"])
            record_error = 100.0 * BAO.window_max(r["time"], difference, 0.0, reflected[1]) / peak
            records.append({"benchmark": benchmark, "method": method[0], "impedance": method[1],
                            "dt": dt, "eta_window": round(eta_w, 2), "eta_boundary": round(eta_b, 2),
                            "record_error": round(record_error, 2), "wall_s": round(r["wall_s"], 2),
                            "energy_J": {k: round(v, 3) for k, v in r["energy_J"].items()}})
    return records, results


def verdicts(records, dts):
    """Per dt: the best DDA-native record (eta_boundary), the hybrid's, whether the hybrid is at
    least as good, and the DDA-native record of the smallest record error."""
    out = []
    for dt in dts:
        at = [r for r in records if r["dt"] == dt]
        hybrid = next(r for r in at if r["method"] == "hybrid")
        native = [r for r in at if (r["method"], r["impedance"]) in DDA_METHODS]
        best = max(native, key=lambda r: r["eta_boundary"])
        out.append({"dt": dt, "best": best, "hybrid": hybrid,
                    "smallest_error": min(native, key=lambda r: r["record_error"]),
                    "margin": hybrid["eta_boundary"] - best["eta_boundary"],
                    "passed": hybrid["eta_boundary"] >= best["eta_boundary"]})
    return out


def figure_benchmark(benchmark, results, records, dts, methods, path):
    """M1 histories at the smallest dt against the long reference, the differences (the
    reflections) with the windows shaded, and eta_boundary per method and dt."""
    spec = BENCHMARKS[benchmark]
    dt = min(dts)
    incident, reflected = spec["windows"]
    fig, (a1, a2, a3) = plt.subplots(3, 1, figsize=(10, 12))
    long = results[("long", dt)]
    reference = spec["scale"] * monitor_signal(long, spec["quantity"])
    a1.plot(1e3 * long["time"], reference, "k-", lw=2.5, alpha=0.35, label="3x longer model")
    for i, method in enumerate(methods):
        r = results[(method, dt)]
        signal = spec["scale"] * monitor_signal(r, spec["quantity"])
        a1.plot(1e3 * r["time"], signal, f"C{i}-", lw=0.9, label=LABEL[method])
        a2.plot(1e3 * r["time"], signal - np.interp(r["time"], long["time"], reference),
                f"C{i}-", lw=0.9, label=LABEL[method])
    for ax in (a1, a2):
        for (t0, t1), shade in ((incident, "0.9"), (reflected, "0.8")):
            ax.axvspan(1e3 * t0, 1e3 * t1, color=shade, zorder=0)
        ax.set_xlabel("time [ms]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
    a1.set_ylabel(spec["unit"])
    a1.set_title(f"{spec['title']}, dt = {dt:g} s\n(shaded: incident and reflection windows)",
                 fontsize=9)
    a2.set_ylabel(f"run - long model, {spec['unit']}")
    a2.set_title("reflections from the truncation", fontsize=9)
    width = 0.8 / len(dts)
    eta = {((r["method"], r["impedance"]), r["dt"]): r["eta_boundary"] for r in records}
    for j, d in enumerate(dts):
        values = [eta[(m, d)] for m in methods]
        bars = a3.bar(np.arange(len(methods)) + (j - (len(dts) - 1) / 2) * width, values, width,
                      label=f"dt = {d:g} s")
        a3.bar_label(bars, fmt="%.1f", fontsize=6)
    a3.set_xticks(np.arange(len(methods)),
                  [LABEL[m].replace(" (", "\n(").replace(", ", ",\n") for m in methods], fontsize=8)
    a3.set_ylabel("eta_boundary [%]")
    a3.set_ylim(min(0.0, a3.get_ylim()[0]), 108)
    a3.grid(alpha=0.3, axis="y")
    a3.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---- 3. the 2D point source -------------------------------------------------------------------

def scene_without_springs(directory):
    """A copy of the point-source scene whose Lysmer sides have no springs; returns its path."""
    with open(POINT_SOURCE) as f:
        text = f.read()
    stripped = re.sub(r",\s*springs:\s*\{[^{}]*\}", "", text)
    if "springs:" in stripped or stripped == text:
        raise RuntimeError(f"could not remove the springs from {POINT_SOURCE}")
    path = os.path.join(directory, "point_source_2d_without_springs.yaml")
    with open(path, "w") as f:
        f.write(stripped)
    return path


def extent(half_width):
    return {"far_field.lower": f"[-{half_width},-{half_width}]",
            "far_field.upper": f"[{half_width},{half_width}]"}


def submit_point_source(pool, ddafem, truncations, without_springs):
    """Jobs {(method, half-width): future}: the reference and every truncation, with and without
    the springs, all with far elements of COMMON_ELEMENT_SIZE."""
    scenes = {"lysmer+springs": POINT_SOURCE, "lysmer": without_springs}
    cases = [("lysmer+springs", REFERENCE_TRUNCATION)]
    cases += [(method, half_width) for half_width in truncations for method in POINT_SOURCE_METHODS]
    jobs = {}
    for method, half_width in cases:
        settings = {**extent(half_width), "far_field.element_size": COMMON_ELEMENT_SIZE}
        jobs[(method, half_width)] = pool.submit(run, ddafem, scenes[method], settings)
    return jobs


def worst_l2(result, reference, quantity):
    """(worst relative L2 difference over the monitors, that monitor)."""
    errors = {}
    for name, ref in reference["monitors"].items():
        x, y = result["monitors"][name][quantity], ref[quantity]
        errors[name] = float(np.sqrt(np.sum((x - y) ** 2) / np.sum(y ** 2)))
    name = max(errors, key=errors.get)
    return errors[name], name


def point_source_records(jobs):
    """One record per run; the references (REFERENCE_TRUNCATION) have no L2 differences."""
    results = {key: job.result() for key, job in jobs.items()}
    records = []
    for (method, half_width), r in results.items():
        record = {"benchmark": "point_source_2d", "method": method, "truncation_m": half_width,
                  "element_size_m": round(r["element_size_m"], 3),
                  "reference": half_width == REFERENCE_TRUNCATION,
                  "l2_displacement": None, "worst_monitor_displacement": None,
                  "l2_velocity": None, "worst_monitor_velocity": None,
                  "wall_s": round(r["wall_s"], 2), "far_field_dofs": r["far_field_dofs"],
                  "energy_J": {k: round(v, 3) for k, v in r["energy_J"].items()}}
        if not record["reference"]:
            reference = results[("lysmer+springs", REFERENCE_TRUNCATION)]
            l2_u, record["worst_monitor_displacement"] = worst_l2(r, reference, "displacement")
            l2_v, record["worst_monitor_velocity"] = worst_l2(r, reference, "velocity")
            record["l2_displacement"], record["l2_velocity"] = round(l2_u, 5), round(l2_v, 5)
        records.append(record)
    return records


def figure_point_source(records, path):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for i, method in enumerate(POINT_SOURCE_METHODS):
        sub = sorted((r for r in records if r["method"] == method and not r["reference"]),
                     key=lambda r: r["truncation_m"])
        x = [r["truncation_m"] for r in sub]
        ax.semilogy(x, [100 * r["l2_displacement"] for r in sub], f"C{i}o-",
                    label=f"{method}: displacement")
        ax.semilogy(x, [100 * r["l2_velocity"] for r in sub], f"C{i}s--",
                    label=f"{method}: velocity")
    ax.set_xlabel("far field half-width [m] (blocks: +-10 m)")
    ax.set_ylabel(f"worst relative L2 difference\nagainst +-{REFERENCE_TRUNCATION} m [%]")
    ax.set_title(f"point source in 20 x 20 blocks, far field truncated with Lysmer dashpots\n"
                 f"(far elements of {COMMON_ELEMENT_SIZE:g} m in every run)", fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---- head_to_head.md --------------------------------------------------------------------------

def method_text(r):
    return LABEL[(r["method"], r["impedance"])]


def percent(part, whole):
    return f"{100 * part / whole:.1f}%"


def write_benchmark_section(f, benchmark, records, dts):
    spec = BENCHMARKS[benchmark]
    f.write(f"## {spec['title']}\n\n")
    f.write(f"Hybrid: `{os.path.relpath(spec['hybrid'], TOP)}` ({spec['hybrid_text']}).\n\n")
    f.write("| dt [s] | method | eta_boundary [%] | eta_window [%] | record error [%] | wall [s] | "
            "put in [J] | absorbed | left | dissipated |\n"
            "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n")
    for r in records:
        e = r["energy_J"]
        f.write(f"| {r['dt']:g} | {method_text(r)} | {r['eta_boundary']:.1f} | "
                f"{r['eta_window']:.1f} | {r['record_error']:.1f} | {r['wall_s']:.1f} | "
                f"{e['put_in']:.4g} | {percent(e['absorbed'], e['put_in'])} | "
                f"{percent(e['left'], e['put_in'])} | {percent(e['dissipated'], e['put_in'])} |\n")
    f.write("\nAcceptance: the hybrid absorbs at least as well as the best DDA-native boundary "
            "(eta_boundary). The last two columns compare the record errors.\n\n"
            "| dt [s] | best DDA-native | its eta_boundary | hybrid | margin [points] | verdict | "
            "smallest DDA-native record error | hybrid's |\n"
            "|---:|---|---:|---:|---:|---|---:|---:|\n")
    rows = verdicts(records, dts)
    for v in rows:
        smallest = v["smallest_error"]
        f.write(f"| {v['dt']:g} | {method_text(v['best'])} | {v['best']['eta_boundary']:.2f} | "
                f"{v['hybrid']['eta_boundary']:.2f} | {v['margin']:+.2f} | "
                f"{'met' if v['passed'] else 'not met'} | {smallest['record_error']:.1f} "
                f"({method_text(smallest)}) | {v['hybrid']['record_error']:.1f} |\n")
    f.write(f"\nVerdict: met at {sum(v['passed'] for v in rows)} of {len(rows)} time steps.\n")
    if any((r["method"], r["impedance"]) == HYBRID_INTACT for r in records):
        write_intact_note(f, records, dts, BENCHMARKS[benchmark]["mass_e"])
    f.write(f"\n![{benchmark}](figures/head_to_head_{benchmark}.png)\n\n")


def write_intact_note(f, records, dts, mass_e):
    """What the far field's material does: the rock mass (Young's modulus mass_e) against the
    intact rock."""
    ratio = math.sqrt(mass_e / BAO.E)
    f.write("\nThe hybrid's far field is the rock mass: the blocks with their joints as one "
            "continuum (the scene's `rock_mass`). A far field of the intact rock is stiffer than "
            "the jointed blocks and reflects at the interface: with E_eff = "
            f"{mass_e / 1e9:.2f} GPa an impedance contrast of {ratio:.3f} reflects "
            f"(1 - {ratio:.3f}) / (1 + {ratio:.3f}) = {100 * (1 - ratio) / (1 + ratio):.1f}% of "
            "the incident amplitude. That reflection passes the monitor inside the incident "
            "window, so neither efficiency sees it; the record error does. Diagnostic runs with "
            "`--set far_field.material=rock`:\n\n"
            "| dt [s] | record error, hybrid (rock mass) | hybrid (intact rock) |\n"
            "|---:|---:|---:|\n")
    for dt in dts:
        at = {(r["method"], r["impedance"]): r for r in records if r["dt"] == dt}
        if HYBRID_INTACT in at:
            f.write(f"| {dt:g} | {at[HYBRID]['record_error']:.1f}% | "
                    f"{at[HYBRID_INTACT]['record_error']:.1f}% |\n")


def write_head_to_head_markdown(path, bench_records, dts_of, point_records, quick, jobs, elapsed):
    with open(path, "w") as f:
        f.write("# Hybrid truncation (blocks + FE far field) against DDA-native boundaries\n\n")
        f.write("Generated by `/usr/bin/python3 tools/verify_coupling.py" + (" --quick" if quick else "")
                + f"` in {elapsed / 60:.1f} min with {jobs} runs at a time (wall times below are "
                "ddafem's own, measured under that load). See the script's docstring for the "
                "definitions.\n\n")
        f.write("- eta_boundary = 1 - max|run - long| / max|free - long| in the reflection window "
                "(the boundary alone; `long`: the model three times longer, `free`: a free end, "
                "both at the same dt); eta_window = 1 - |Ar| / |Ai| (tools/verify_bao2012.py, "
                "docs/reference/physics.md section 6).\n"
                "- record error = max|run - long| from t = 0 to the end of the reflection window, "
                "in % of the incident peak at M1: every difference from the untruncated model, "
                "including reflections from the hybrid's interface, which arrive in the incident "
                "window.\n"
                "- Energy budget at the end of each run, in % of the energy put in: absorbed by "
                "the boundary (viscous boundary or Lysmer dashpots), left in the model (blocks, "
                "far field, tie springs), dissipated by the integrators' algorithmic damping.\n\n")
        for benchmark, records in bench_records.items():
            write_benchmark_section(f, benchmark, records, dts_of[benchmark])
        f.write("## 2D: point source, far field truncated at several distances\n\n")
        f.write("`examples/coupled/point_source_2d.yaml` (20 x 20 bonded 1 m blocks in a graded "
                "FE_Q2 far field, plane strain, trapezoidal rule, 0.04 s) with the far field's "
                f"half-width changed, against a half-width of {REFERENCE_TRUNCATION} m from which "
                "no reflection returns within the window. lysmer+springs: the scene's "
                "viscous-spring boundary (springs G / R beside the dashpots); lysmer: dashpots "
                "only. Worst relative L2 difference over the five monitors (both components, "
                "the whole record; in brackets the monitor).\n\n"
                f"Far elements of {COMMON_ELEMENT_SIZE:g} m in every run (the scene's), so that "
                "the truncated models share the reference's mesh where they overlap and differ by "
                "the truncation alone; the far field is the scene's rock mass.\n\n")
        f.write("| half-width [m] | boundary | far element [m] | far-field DOFs | "
                "wall [s] | L2 displacement | L2 velocity |\n"
                "|---:|---|---:|---:|---:|---:|---:|\n")
        for r in point_records:
            if r["reference"]:
                errors = "reference | reference"
            else:
                errors = (f"{100 * r['l2_displacement']:.2f}% ({r['worst_monitor_displacement']}) | "
                          f"{100 * r['l2_velocity']:.2f}% ({r['worst_monitor_velocity']})")
            f.write(f"| {r['truncation_m']} | {r['method']} | "
                    f"{r['element_size_m']:.2f} | {r['far_field_dofs']} | {r['wall_s']:.1f} | "
                    f"{errors} |\n")
        f.write("\n![point source](figures/head_to_head_point_source_2d.png)\n")


# ---- main -------------------------------------------------------------------------------------

def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--quick", action="store_true",
                        help="dt 1e-5, VB I and the hybrid only; the 2D case at +-80 m only")
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "verification"))
    parser.add_argument("--interface-only", action="store_true",
                        help="only part 1: interface.{md,json,png}")
    args = parser.parse_args()
    start = time.monotonic()
    if args.interface_only:
        interface_raw, gtest_passed = run_transparency_tests(
            os.path.join(args.build, "tests", "test_coupling"))
        write_interface(args.out, interface_raw, gtest_passed)
        return 0 if gtest_passed else 1
    ddafem = os.path.join(args.build, "ddafem")
    figures = os.path.join(args.out, "figures")
    os.makedirs(figures, exist_ok=True)

    methods_of = {b: [("vb1", "textbook"), ("vb1", "effective"), HYBRID] if args.quick
                  else DDA_METHODS + [HYBRID] + spec["diagnostics"] for b, spec in BENCHMARKS.items()}
    dts_of = {b: [1e-5] if args.quick else spec["dts"] for b, spec in BENCHMARKS.items()}
    truncations = [80] if args.quick else TRUNCATIONS

    with tempfile.TemporaryDirectory() as tmp, \
            concurrent.futures.ProcessPoolExecutor(max_workers=args.jobs) as pool:
        # The longest runs first.
        transparency = pool.submit(run_transparency_tests,
                                   os.path.join(args.build, "tests", "test_coupling"))
        point_jobs = submit_point_source(pool, ddafem, truncations, scene_without_springs(tmp))
        bench_jobs = {b: submit_benchmark(pool, ddafem, b, dts_of[b], methods_of[b])
                      for b in BENCHMARKS}

        bench_records = {}
        for benchmark, jobs in bench_jobs.items():
            methods = methods_of[benchmark]
            records, results = benchmark_records(benchmark, jobs, dts_of[benchmark], methods)
            bench_records[benchmark] = records
            figure_benchmark(benchmark, results, records, dts_of[benchmark], methods,
                             os.path.join(figures, f"head_to_head_{benchmark}.png"))
        point_records = point_source_records(point_jobs)
        figure_point_source(point_records, os.path.join(figures, "head_to_head_point_source_2d.png"))
        interface_raw, gtest_passed = transparency.result()

    interface_rows = write_interface(args.out, interface_raw, gtest_passed)

    all_records = [r for records in bench_records.values() for r in records] + point_records
    with open(os.path.join(args.out, "head_to_head.json"), "w") as f:
        json.dump(all_records, f, indent=1)
    elapsed = time.monotonic() - start
    write_head_to_head_markdown(os.path.join(args.out, "head_to_head.md"), bench_records, dts_of,
                                point_records, args.quick, args.jobs, elapsed)

    for benchmark, records in bench_records.items():
        for v in verdicts(records, dts_of[benchmark]):
            print(f"{benchmark} dt {v['dt']:g}: hybrid {v['hybrid']['eta_boundary']:.1f}%, best "
                  f"DDA-native {method_text(v['best'])} {v['best']['eta_boundary']:.1f}%: "
                  f"{'met' if v['passed'] else 'not met'} ({v['margin']:+.2f} points); record "
                  f"error hybrid {v['hybrid']['record_error']:.1f}%")
    for r in (r for r in point_records if not r["reference"]):
        print(f"point_source_2d +-{r['truncation_m']} m {r['method']:15s}: L2 u "
              f"{100 * r['l2_displacement']:.2f}%, v {100 * r['l2_velocity']:.2f}%, "
              f"{r['wall_s']:.1f} s, {r['far_field_dofs']} far-field DOFs")
    print(f"wrote {args.out}/interface.*, head_to_head.*, figures/head_to_head_*.png "
          f"in {elapsed:.0f} s")


if __name__ == "__main__":
    main()
