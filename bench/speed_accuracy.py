#!/usr/bin/python3
"""Speed against accuracy of the truncations (issue 8): runs a matrix of configurations of three
cases with build/ddafem and writes

  OUT/results.csv, OUT/results.json   one row per run (keys: KEYS below)
  OUT/speed_accuracy_<case>.png/.svg  error against wall time, one marker per method, Pareto front
  OUT/stability_map.png/.svg          efficiency and energy growth against dt per boundary
  OUT/cost_per_step.png/.svg          cost per step against model size, fitted slopes
  OUT/../performance.md               the tables, charts, machine and recommendations

Cases (the reference of each is a row with reference = true and error 0):
  bar          the P-wave bar of Bao et al. (2012), examples/bao2012/p_wave_bar.yaml, 100 Hz, to
               0.05 s. Reference: the DDA-only bar three times longer (verify_bao2012.LONG_BAR:
               nothing returns to M1 in the window) at the finest dt. Methods per dt: dda_large
               (that long bar), free (no boundary: the worst case), vb1 (textbook impedance),
               dashpot (effective impedance), hybrid (examples/coupled/p_wave_bar_hybrid.yaml).
               error = relative L2 of sxx at M1 (50.5 m) from t = 0 to the end of the
               reflection window (verify_bao2012.bar_windows) against the reference.
  bar_stability  the bar beyond the limits (--allow-unstable, small-displacement analysis, to
               0.5 s for dt >= 1e-4 s as verify_bao2012.stability_map): vb1, vb2, dashpot
               (textbook and effective), hybrid, with the long and the free bar per dt for
               eta_boundary (verify_bao2012.efficiencies).
  line_source  examples/coupled/point_source_2d.yaml (verify_coupling's 2D case). Reference: the
               far field truncated at +-120 m. Methods: hybrid (Lysmer + springs) and
               hybrid_dashpots (springs removed) at +-40/60/80 m, the hybrid at other dt,
               blocks only (the far field replaced by 1 m blocks) with vb1 or the dashpot on the
               outer edges at +-40/60/80 m and dda_large (blocks to +-120 m, free edges).
               error = worst relative L2 of the monitors' displacement (verify_coupling.worst_l2,
               on the reference's times).
  tunnel       examples/tunnel/stable_sv.yaml with --set tunnel.truncation=reference|hybrid|
               vb1|dashpot|blocks (blocks: not with --quick, and only if `ddafem check` accepts
               it; about 33,000 blocks, minutes), the hybrid also
               with other tunnel.points_per_wavelength and tunnel.margin. error = the keyblock
               history error of verify_tunnel.history_error, peak_error its keyblock peak error.
  tunnel_size  the hybrid with tunnel.near_field.size_factor 3 and 6 (and, without --quick,
               examples/tunnel/large_circular_sv.yaml): cost only.

energy_error = |put in + initial - (absorbed + left + dissipated)| / (put in + initial) at the
end (verify_coupling.energy_budget; initial: the blocks' energy at the start of the dynamic
stage); energy_growth = left / (put in + initial); energy_absorbed, energy_dissipated: absorbed
and dissipated / (put in + initial), the latter the integrators' algorithmic damping. ddafem
computes each part's dissipated energy as the rest of that part's balance, so energy_error is 0
by construction for blocks only and measures the tie work's bookkeeping between blocks and far
field in coupled runs. stable = false if check refused the run (exit 2), it failed (summary.json
failure), energy_growth > 1 or the boundary is a source (energy_absorbed < -SOURCE_TOLERANCE).
Every run writes snapshots at its first and last step only (output.interval=1), so wall times
are the computation's.
Profile (not with --quick): bench/profile_tunnel.py's before/after of the default tunnel, run
alone after the matrix, into OUT/profile_tunnel.{json,md,png} and a section of performance.md.
--quick (the ctest bench.speed_accuracy_quick): a few short runs of each case.

usage: /usr/bin/python3 bench/speed_accuracy.py [--quick] [--jobs 2] [--build build]
                                                [--out docs/performance]
"""
import argparse
import concurrent.futures
import csv
import hashlib
import json
import math
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time

import h5py
import matplotlib
import numpy as np
import yaml

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(TOP, "tools"))
import verify_bao2012 as BAO  # noqa: E402
import verify_coupling as COUPLING  # noqa: E402
import verify_tunnel as TUNNEL  # noqa: E402

sys.path.insert(0, os.path.join(TOP, "bench"))
import coupled_bench as COUPLED_BENCH  # noqa: E402
import profile_tunnel as PROFILE  # noqa: E402

BAR_HYBRID = os.path.join(TOP, "examples/coupled/p_wave_bar_hybrid.yaml")
TUNNEL_SCENE = os.path.join(TOP, "examples/tunnel/stable_sv.yaml")
LARGE_TUNNEL = os.path.join(TOP, "examples/tunnel/large_circular_sv.yaml")

KEYS = ["case", "method", "variant", "reference", "dt", "block_size_m", "element_size_m",
        "domain_size_m", "blocks", "dofs", "far_field_dofs", "steps", "wall_time_s", "setup_s",
        "ms_per_step", "error", "peak_error", "eta_boundary", "energy_error", "energy_growth",
        "energy_absorbed", "energy_dissipated", "stable", "reason"]
CASES = ["bar", "line_source", "tunnel"]
ACCURACY = 0.05  # "within 5%" of the reference
SPEED_UP = 5.0   # the tunnel acceptance: the hybrid at least 5 times faster than blocks only
PICK_ACCURACIES = [ACCURACY, 0.01]
SOURCE_TOLERANCE = 1e-3  # a boundary doing more work on the model than this fraction is a source
METHOD_TEXT = {
    "dda_large": "DDA only, large domain", "free": "DDA only, free end", "vb1": "DDA + VB I",
    "vb2": "DDA + VB II", "dashpot": "DDA + dashpot",
    "dashpot_effective": "DDA + dashpot (effective Z)",
    "hybrid": "DDA + FE far field (Lysmer)", "hybrid_dashpots": "DDA + FE (Lysmer, no springs)",
    "reference": "reference: large FE far field", "blocks": "DDA only, large domain (blocks)",
}


# ---- running ddafem ---------------------------------------------------------------------------

def spec(case, method, variant, scene, settings, reference=False, allow_unstable=False, **meta):
    """One run of the matrix: a scene with --set overrides and what the row needs besides."""
    return {"case": case, "method": method, "variant": variant, "scene": scene,
            "settings": {**settings, "output.interval": 1}, "reference": reference,
            "allow_unstable": allow_unstable, **meta}


def run(ddafem, job, out):
    """Runs one spec into OUT; returns the spec with exit, stderr, dir and summary."""
    cmd = [ddafem, "run", job["scene"], "-o", out, "--quiet"]
    for key, value in job["settings"].items():
        cmd += ["--set", f"{key}={value}"]
    if job["allow_unstable"]:
        cmd.append("--allow-unstable")
    proc = subprocess.run(cmd, capture_output=True, text=True)
    path = os.path.join(out, "summary.json")
    summary = {}
    if proc.returncode in (0, 1) and os.path.exists(path):
        with open(path) as f:
            summary = json.load(f)
    return {**job, "exit": proc.returncode, "stderr": proc.stderr.strip(), "dir": out,
            "summary": summary}


def verification_arguments(doc, check_help):
    """The command line of a verification table's tool (tools/verify_*.py): --build, --jobs,
    --out (docs/verification) and --check with its meaning."""
    parser = argparse.ArgumentParser(description=doc.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "verification"))
    parser.add_argument("--check", action="store_true", help=check_help)
    return parser.parse_args()


def write_verification(out, name, data, write_markdown):
    """OUT/NAME.json (data) and OUT/NAME.md (write_markdown(path, data))."""
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, name + ".json"), "w") as f:
        json.dump(data, f, indent=1)
    write_markdown(os.path.join(out, name + ".md"), data)


def frozen_binary(build, directory):
    """A copy of BUILD/ddafem and of the far-field module beside it
    (libddafem_far_field.so, loaded from the executable's directory) in directory: every run of
    the matrix uses the same binaries even if the build directory is rebuilt meanwhile."""
    source = os.path.join(build, "ddafem")
    module = os.path.join(build, "libddafem_far_field.so")
    for path in (source, module):
        if not os.access(path, os.R_OK) or os.path.getsize(path) == 0:
            raise SystemExit(f"{path} is missing or being linked: build it first")
    shutil.copy2(module, os.path.join(directory, "libddafem_far_field.so"))
    return shutil.copy2(source, os.path.join(directory, "ddafem"))


def binaries_sha256(ddafem):
    """SHA-256 of the executable's bytes followed by those of the far-field module beside it
    (when there is one): what identifies the code that ran."""
    digest = hashlib.sha256()
    module = os.path.join(os.path.dirname(ddafem), "libddafem_far_field.so")
    for path in (ddafem, module):
        if os.path.exists(path):
            with open(path, "rb") as f:
                digest.update(f.read())
    return digest.hexdigest()


def check_accepts(ddafem, scene, settings):
    """Whether `ddafem check` accepts the scene with these overrides (exit 0)."""
    cmd = [ddafem, "check", scene]
    for key, value in settings.items():
        cmd += ["--set", f"{key}={value}"]
    return subprocess.run(cmd, capture_output=True, text=True).returncode == 0


def run_all(ddafem, jobs, root, n_jobs):
    """Runs every spec, the longest first (est_s), n_jobs at a time."""
    order = sorted(range(len(jobs)), key=lambda i: -jobs[i].get("est_s", 1.0))
    with concurrent.futures.ThreadPoolExecutor(max_workers=n_jobs) as pool:
        futures = {i: pool.submit(run, ddafem, jobs[i], os.path.join(root, f"run{i:03d}"))
                   for i in order}
        return [futures[i].result() for i in range(len(jobs))]


def completed(r):
    return r["exit"] == 0 and r["summary"].get("failure") is None


# ---- the common part of a row -----------------------------------------------------------------

def energy(summary):
    """{energy_error, energy_growth, energy_absorbed, energy_dissipated} at the end of a run
    (module docstring); {} if nothing was put in."""
    budget = COUPLING.energy_budget(summary)
    total_in = budget["put_in"] + summary["energy_J"].get("initial", 0.0)
    if total_in <= 0.0:
        return {}
    balance = total_in - budget["absorbed"] - budget["left"] - budget["dissipated"]
    return {"energy_error": abs(balance) / total_in, "energy_growth": budget["left"] / total_in,
            "energy_absorbed": budget["absorbed"] / total_in,
            "energy_dissipated": budget["dissipated"] / total_in}


def stability(r, growth, absorbed):
    """(stable, reason) of a run."""
    if r["exit"] == 2:
        message = r["stderr"].splitlines()[-1].removeprefix("error: ")
        message = message.removeprefix(r["scene"] + ": ").split(": expected")[0]
        return False, "refused by check: " + message
    if r["exit"] not in (0, 1) or not r["summary"]:
        return False, f"exit {r['exit']}: " + (r["stderr"].splitlines() or [""])[-1]
    failure = r["summary"].get("failure")
    if failure is not None:
        return False, "failed: " + str(failure).split("; ")[0].split(": ")[0]
    if growth is not None and growth > 1.0:
        return False, f"energy grew: stored / put in = {growth:.3g}"
    if absorbed is not None and absorbed < -SOURCE_TOLERANCE:
        return False, f"the boundary is a source: it did work {-absorbed:.1%} of the energy put in"
    return True, ""


def base_row(r):
    """The keys every case fills the same way; error, peak_error, eta_boundary left None."""
    s = r["summary"]
    model = s.get("model", {})
    row = {k: None for k in KEYS}
    row.update(case=r["case"], method=r["method"], variant=r["variant"],
               reference=r["reference"], dt=s.get("dt_s", r["settings"].get("time.dt")),
               block_size_m=r.get("block_size_m"), domain_size_m=r.get("domain_size_m"))
    if s:
        setup = s.get("far_field", {}).get("timings_s", {}).get("setup", 0.0)
        steps = s["steps"]
        per_step = 1e3 * (s["wall_time_s"] - setup) / steps if steps else None
        row.update(blocks=model.get("blocks"), far_field_dofs=model.get("far_field_dofs", 0),
                   dofs=model.get("dofs", 0) + model.get("far_field_dofs", 0),
                   element_size_m=model.get("element_size_m"), steps=steps,
                   wall_time_s=round(s["wall_time_s"], 3), setup_s=round(setup, 3),
                   ms_per_step=per_step and round(per_step, 4),
                   **energy(s))
    row["stable"], row["reason"] = stability(r, row["energy_growth"], row["energy_absorbed"])
    return row


# ---- bar ----------------------------------------------------------------------------------------

def bar_method(method, dt, end, geometry=None):
    """(scene, settings) of a bar method."""
    common = {"time.dt": dt, "time.end_time": end}
    if geometry:
        common["analysis.geometry"] = geometry
    if method == "hybrid":
        return BAR_HYBRID, common
    if method == "dda_large":
        return BAO.BAR, {**common, **BAO.LONG_BAR}
    if method == "dashpot_effective":
        return BAO.BAR, {**common, **BAO.boundary_settings("dashpot", "effective")}
    return BAO.BAR, {**common, **BAO.boundary_settings(method, "textbook")}


def bar_specs(quick):
    dts = [5e-5, 4e-4] if quick else [1e-5, 2e-5, 5e-5, 1e-4, 2e-4, 4e-4]
    reference_dt = 1e-5 if quick else 5e-6
    specs = [spec("bar", "dda_large", f"300 m, dt {reference_dt:g}",
                  *bar_method("dda_large", reference_dt, 0.05), reference=True,
                  block_size_m=1.0, domain_size_m=300.0)]
    for dt in dts:
        for method in ["dda_large", "free", "vb1", "dashpot_effective", "hybrid"]:
            specs.append(spec("bar", method, f"dt {dt:g}", *bar_method(method, dt, 0.05),
                              block_size_m=1.0,
                              domain_size_m=300.0 if method == "dda_large" else 100.0))
    sweep = [1e-4, 4e-4] if quick else \
        [1e-5, 3e-5, 1e-4, 2e-4, 3e-4, 3.4e-4, 3.7e-4, 4e-4, 5e-4, 7e-4, 1e-3]
    methods = ["dda_large", "free", "vb1", "dashpot_effective", "hybrid"] if quick else \
        ["dda_large", "free", "vb1", "vb2", "dashpot", "dashpot_effective", "hybrid"]
    for dt in sweep:
        end = 0.05 if dt < 1e-4 else 0.5  # as verify_bao2012.stability_map
        for method in methods:
            specs.append(spec("bar_stability", method, f"dt {dt:g}",
                              *bar_method(method, dt, end, "small_displacement"),
                              allow_unstable=True, block_size_m=1.0,
                              domain_size_m=300.0 if method == "dda_large" else 100.0))
    return specs


def m1_sxx(r):
    with h5py.File(os.path.join(r["dir"], "histories.h5"), "r") as f:
        return f["time"][:], f["monitors/M1/stress"][:, 0]


def relative_l2(t, x, t_ref, x_ref, t1):
    """Relative L2 difference of x against x_ref (interpolated) over [0, t1]."""
    keep = t <= t1
    y = np.interp(t[keep], t_ref, x_ref)
    return float(np.sqrt(np.sum((x[keep] - y) ** 2) / np.sum(y ** 2)))


def bar_rows(results):
    """Rows of the bar and bar_stability cases."""
    incident, reflected = BAO.bar_windows(100.0)
    reference = next(r for r in results if r["case"] == "bar" and r["reference"])
    t_ref, x_ref = m1_sxx(reference)
    by = {(r["case"], r["method"], r["variant"]): r for r in results if not r["reference"]}
    rows = []
    for r in [reference] + [r for r in results if not r["reference"]]:
        row = base_row(r)
        if r["summary"] and r["summary"]["time_reached_s"] >= reflected[1]:
            t, x = m1_sxx(r)
            row["error"] = relative_l2(t, x, t_ref, x_ref, reflected[1])
            long, free = by.get((r["case"], "dda_large", r["variant"])), \
                by.get((r["case"], "free", r["variant"]))
            if not r["reference"] and long and free and completed(long) and completed(free):
                row["eta_boundary"] = round(BAO.efficiencies(
                    t, x, *m1_sxx(long), *m1_sxx(free), incident, reflected)[1], 2)
        rows.append(row)
    return rows


# ---- line source ------------------------------------------------------------------------------

def blocks_only_scene(directory, half_width, boundary):
    """The point-source scene without its far field: blocks to +-half_width with `boundary`
    (vb1, dashpot or free) on the outer edges; returns the path of the written scene."""
    with open(COUPLING.POINT_SOURCE) as f:
        scene = yaml.safe_load(f)
    del scene["far_field"], scene["interface"]
    scene["blocks"][0]["grid"].update(origin=[-half_width, -half_width],
                                      count=[2 * half_width, 2 * half_width])
    if boundary != "free":
        scene["boundaries"] = [{"type": boundary, "outer": True}]
    path = os.path.join(directory, f"point_source_blocks_{half_width}_{boundary}.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(scene, f)
    return path


def line_source_specs(quick, directory):
    ref_width, end = (80, 0.02) if quick else (COUPLING.REFERENCE_TRUNCATION, 0.04)
    truncations = [40] if quick else COUPLING.TRUNCATIONS
    common = {"far_field.element_size": COUPLING.COMMON_ELEMENT_SIZE, "time.end_time": end}
    without_springs = COUPLING.scene_without_springs(directory)

    def hybrid(method, scene, width, dt=2e-4, reference=False):
        variant = f"+-{width} m" + ("" if dt == 2e-4 else f", dt {dt:g}")
        return spec("line_source", method, variant, scene,
                    {**COUPLING.extent(width), **common, "time.dt": dt}, reference=reference,
                    block_size_m=1.0, domain_size_m=2.0 * width, est_s=width ** 2 / 500)

    def blocks(method, boundary, width):
        return spec("line_source", method, f"+-{width} m",
                    blocks_only_scene(directory, width, boundary), {"time.end_time": end},
                    block_size_m=1.0, domain_size_m=2.0 * width, est_s=width ** 2 / 300)

    specs = [hybrid("reference", COUPLING.POINT_SOURCE, ref_width, reference=True)]
    for width in truncations:
        specs.append(hybrid("hybrid", COUPLING.POINT_SOURCE, width))
        specs.append(blocks("vb1", "vb1", width))
        if not quick:
            specs.append(hybrid("hybrid_dashpots", without_springs, width))
            specs.append(blocks("dashpot", "dashpot", width))
    if not quick:
        specs += [hybrid("hybrid", COUPLING.POINT_SOURCE, 80, dt) for dt in (1e-4, 4e-4)]
        specs.append(blocks("dda_large", "free", COUPLING.REFERENCE_TRUNCATION))
    return specs


def monitors_on(r, times):
    """verify_coupling-style monitors {name: {displacement}} interpolated onto `times`."""
    with h5py.File(os.path.join(r["dir"], "histories.h5"), "r") as f:
        t = f["time"][:]
        return {"monitors": {name: {"displacement": np.column_stack(
            [np.interp(times, t, f[f"monitors/{name}/displacement"][:, k]) for k in range(2)])}
            for name in f["monitors"]}}


def line_source_rows(results):
    reference = next(r for r in results if r["case"] == "line_source" and r["reference"])
    with h5py.File(os.path.join(reference["dir"], "histories.h5"), "r") as f:
        times = f["time"][:]
    ref = monitors_on(reference, times)
    large = next((r for r in results if r["method"] == "dda_large" and completed(r)), None)
    rows = []
    for r in results:
        row = base_row(r)
        if completed(r):
            monitors = monitors_on(r, times)
            row["error"] = COUPLING.worst_l2(monitors, ref, "displacement")[0]
            if large and r["method"] in ("vb1", "dashpot"):
                row["error_vs_blocks"] = COUPLING.worst_l2(monitors, monitors_on(large, times),
                                                           "displacement")[0]
        rows.append(row)
    return rows


def blocks_only_note(rows):
    """The line source's blocks-only truncations against the blocks-only model to +-120 m."""
    sub = [r for r in rows if r["case"] == "line_source" and "error_vs_blocks" in r]
    if not sub:
        return ""
    large = next(r for r in rows if r["case"] == "line_source" and r["method"] == "dda_large")
    return ("The blocks-only models differ from the FE reference by about as much whatever "
            f"their truncation (free edges at +-120 m: {large['error']:.1%}): the blocks and the "
            "FE far field are different models of the rock beyond the 20 x 20 blocks, and that "
            "difference, not the truncation, is their error. Against the blocks-only model to "
            "+-120 m instead, the truncations' own errors are: " + "; ".join(
                f"{METHOD_TEXT[r['method']]} {r['variant']}: {r['error_vs_blocks']:.1%}"
                for r in sub) + ".")


# ---- tunnel -----------------------------------------------------------------------------------

def tunnel_specs(quick, ddafem):
    """The tunnel's specs and the methods `ddafem check` refused (not run)."""
    def truncation(method, extra=None, variant="default", case="tunnel", scene=TUNNEL_SCENE,
                   est_s=5.0):
        # The wave's window alike for every truncation (blocks-only ones would settle after it).
        return spec(case, method, variant, scene,
                    {"tunnel.truncation": method, "tunnel.settle.enabled": "false",
                     **(extra or {})}, reference=method == "reference", est_s=est_s)

    specs = [truncation("reference", est_s=20), truncation("hybrid"),
             truncation("dashpot", est_s=0.5)]
    missing = []
    if quick:
        return specs, missing
    # Blocks only, big enough (about 33,000 blocks, minutes): not in --quick.
    if check_accepts(ddafem, TUNNEL_SCENE, {"tunnel.truncation": "blocks"}):
        specs.append(truncation("blocks", est_s=400))
    else:
        missing.append("blocks")
    specs.append(truncation("vb1", est_s=11))
    for ppw in (6, 8, 14):
        specs.append(truncation("hybrid", {"tunnel.points_per_wavelength": ppw},
                                f"{ppw} points per wavelength"))
    for margin in (20, 40, 100):
        specs.append(truncation("hybrid", {"tunnel.margin": margin}, f"margin {margin} m"))
    for factor in (3, 6):
        specs.append(truncation("hybrid", {"tunnel.near_field.size_factor": factor},
                                f"near field {factor} x the opening", case="tunnel_size",
                                est_s=3 * factor))
    specs.append(truncation("hybrid", None, "large_circular_sv.yaml", case="tunnel_size",
                            scene=LARGE_TUNNEL, est_s=300))
    return specs, missing


def tunnel_geometry(summary):
    """(mean near-field block size, domain width) [m] of a tunnel run from summary.json (the
    outer blocks of truncation blocks, outer_block_size_m, are not counted)."""
    t = summary["tunnel"]
    lower, upper = t["near_field_lower_m"], t["near_field_upper_m"]
    width = upper[0] - lower[0]
    area = width * (upper[1] - lower[1]) - sum(
        o["area_m2"] for o in summary["keyblocks"]["openings"])
    near_blocks = summary["model"]["blocks"] - t.get("outer_blocks", 0)
    side = t.get("side_margin_m", t.get("margin_m", 0.0))
    return math.sqrt(area / near_blocks), width + 2.0 * side


def keyblock_history_error(r, reference, peak_id):
    """verify_tunnel.history_error, None if the run has no keyblock of the reference's id."""
    try:
        return TUNNEL.history_error(r, reference, peak_id)
    except KeyError:
        return None


def tunnel_rows(results):
    reference = next(r for r in results if r["case"] == "tunnel" and r["reference"])
    if not completed(reference):
        raise SystemExit("the tunnel reference failed: " + reference["stderr"])
    peak_id = reference["summary"]["keyblocks"]["keyblock_peak_id"]
    peak_ref = reference["summary"]["keyblocks"]["keyblock_peak_m"]
    rows = []
    for r in results:
        if r["summary"].get("keyblocks"):
            r["block_size_m"], r["domain_size_m"] = tunnel_geometry(r["summary"])
        row = base_row(r)
        if completed(r) and r["case"] == "tunnel":
            row["error"] = keyblock_history_error(r, reference, peak_id)
            peak = r["summary"]["keyblocks"]["keyblock_peak_m"]
            row["peak_error"] = abs(peak - peak_ref) / peak_ref
        row["phases_text"] = phases_text(r["summary"]) if completed(r) else ""
        rows.append(row)
    return rows


# ---- derived numbers --------------------------------------------------------------------------

def usable(row):
    return row["stable"] and row["error"] is not None and row["wall_time_s"] is not None


def pareto(rows):
    """The rows no other row beats in both wall time and error, by wall time."""
    front, best = [], math.inf
    for row in sorted(rows, key=lambda r: (r["wall_time_s"], r["error"])):
        if row["error"] < best:
            front.append(row)
            best = row["error"]
    return front


def recommendation(rows, case, accuracy=ACCURACY):
    """(cheapest usable non-reference row within accuracy, most accurate one, reference)."""
    candidates = [r for r in rows if r["case"] == case and not r["reference"] and usable(r)]
    within = [r for r in candidates if r["error"] <= accuracy]
    reference = next(r for r in rows if r["case"] == case and r["reference"])
    cheapest = min(within, key=lambda r: r["wall_time_s"]) if within else None
    best = min(candidates, key=lambda r: r["error"]) if candidates else None
    return cheapest, best, reference


def tunnel_verdict(rows, missing):
    """The acceptance sentence on the tunnel, computed from the rows."""
    tunnel = [r for r in rows if r["case"] == "tunnel"]
    hybrids = [r for r in tunnel
               if r["method"] == "hybrid" and usable(r) and r["error"] <= ACCURACY]
    blocks = [r for r in tunnel if r["method"] == "blocks" and usable(r)]
    if not hybrids:
        return ("**Not met**: no hybrid run reaches the reference within 5% (keyblock history "
                "error); the closest: " + row_text(min((r for r in tunnel if r["method"] == "hybrid"
                                                         and usable(r)), key=lambda r: r["error"])))
    hybrid = min(hybrids, key=lambda r: r["wall_time_s"])
    limit = hybrid["phases_text"]
    if not blocks:
        reference = next(r for r in tunnel if r["reference"])
        why = "is missing from this build (`ddafem check` rejects it)" if "blocks" in missing \
            else "has no usable run (" + "; ".join(
                r["reason"] or "no keyblock history to compare" for r in tunnel
                if r["method"] == "blocks") + ")"
        truncated = "; ".join(row_text(r) for r in tunnel if r["method"] in ("vb1", "dashpot")
                              and usable(r))
        return (f"**Undecided**: the blocks-only model (`tunnel.truncation=blocks`) {why}, so "
                f"the 5x comparison cannot be made. The cheapest hybrid within 5% "
                f"({row_text(hybrid)}) is {reference['wall_time_s'] / hybrid['wall_time_s']:.1f}x "
                f"faster than the large FE reference ({reference['wall_time_s']:.1f} s). {limit} "
                f"The blocks-only models truncated at the near field's edge are no substitute: "
                f"{truncated or 'none ran'}.")
    block = min(blocks, key=lambda r: r["wall_time_s"])
    ratio = block["wall_time_s"] / hybrid["wall_time_s"]
    met = ratio >= SPEED_UP
    text = (f"**{'Met' if met else 'Not met'}**: the cheapest hybrid within 5% "
            f"({row_text(hybrid)}) is {ratio:.1f}x faster than the blocks-only model "
            f"({row_text(block)}); required {SPEED_UP:g}x.")
    if block["error"] > ACCURACY:
        text += (f" The blocks-only model itself is {100 * block['error']:.1f}% from the "
                 f"reference (keyblock history; peak {100 * block['peak_error']:.2f}%): a finer "
                 "or bigger one would be closer and cost more, so the ratio is a lower bound.")
    return text if met else f"{text} {limit}"


def phases_text(summary):
    """The two largest parts of a run's wall time (bench/coupled_bench.split for coupled runs),
    as a sentence."""
    t = summary["timings_s"]
    if "interface" in summary:
        ms, setup = COUPLED_BENCH.split(summary)
        parts = {f"{name} steps": v * summary["steps"] / 1e3 for name, v in ms.items()}
        parts["the far field's set-up (factorization)"] = setup["far_field_setup_s"]
        parts["the condensation onto the ties"] = setup["condensation_s"]
    else:
        parts = {"DDA steps": sum(t[k] for k in ("broad_phase", "narrow_phase", "assemble",
                                                 "solve", "update"))}
    parts["output"] = t["output"]
    wall = summary["wall_time_s"]
    top = sorted(parts.items(), key=lambda kv: -kv[1])[:2]
    return ("Its wall time goes mostly to " + " and ".join(
        f"{name} ({100 * v / wall:.0f}%)" for name, v in top) + f", over {summary['steps']} steps "
        "(static stage included).")


def row_text(row):
    variant = "" if row["variant"] in (None, "default") else f", {row['variant']}"
    return (f"{METHOD_TEXT.get(row['method'], row['method'])}{variant}: error "
            f"{100 * row['error']:.2f}% in {row['wall_time_s']:.2f} s")


def fitted_slope(x, y):
    """Slope of log y against log x (None for fewer than two distinct sizes)."""
    if len(set(x)) < 2:
        return None
    return float(np.polyfit(np.log(x), np.log(y), 1)[0])


# ---- charts -----------------------------------------------------------------------------------

def save(fig, out, name):
    fig.tight_layout()
    fig.savefig(os.path.join(out, name + ".png"), dpi=110)
    fig.savefig(os.path.join(out, name + ".svg"))
    plt.close(fig)


def figure_speed_accuracy(rows, case, out):
    floor = 1e-4
    fig, ax = plt.subplots(figsize=(7.5, 5))
    sub = [r for r in rows if r["case"] == case and not r["reference"] and usable(r)]
    for i, method in enumerate(sorted({r["method"] for r in sub})):
        pts = [r for r in sub if r["method"] == method]
        ax.loglog([r["wall_time_s"] for r in pts], [max(r["error"], floor) for r in pts],
                  "osD^v<>ph*"[i % 10], color=f"C{i}", ls="none",
                  label=METHOD_TEXT.get(method, method))
    front = pareto(sub)
    ax.step([r["wall_time_s"] for r in front], [max(r["error"], floor) for r in front], "k-",
            where="post", lw=1, alpha=0.6, label="Pareto front")
    for r in front:
        ax.annotate(r["variant"], (r["wall_time_s"], max(r["error"], floor)), fontsize=6,
                    xytext=(3, 3), textcoords="offset points")
    reference = next(r for r in rows if r["case"] == case and r["reference"])
    ax.axvline(reference["wall_time_s"], color="gray", ls=":", lw=1,
               label=f"reference ({reference['wall_time_s']:.1f} s)")
    ax.axhline(ACCURACY, color="gray", ls="--", lw=1, label="5% error")
    ax.set_xlabel("wall time [s] (ddafem's own)")
    ax.set_ylabel("error against the reference")
    ax.set_title(f"{case}: error against wall time (stable runs)", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    save(fig, out, f"speed_accuracy_{case}")


def figure_stability_map(rows, out):
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 8), sharex=True)
    sub = [r for r in rows if r["case"] == "bar_stability"]
    for i, method in enumerate(m for m in ("vb1", "vb2", "dashpot", "dashpot_effective", "hybrid")
                               if any(r["method"] == m for r in sub)):
        pts = sorted((r for r in sub if r["method"] == method), key=lambda r: r["dt"])
        eta = [r for r in pts if r["eta_boundary"] is not None]
        style = "osD^v"[i] + "-"
        a1.semilogx([r["dt"] for r in eta], [r["eta_boundary"] for r in eta], style,
                    color=f"C{i}", mfc="none", label=METHOD_TEXT[method])
        grown = [r for r in pts if r["energy_growth"] is not None]
        a2.loglog([r["dt"] for r in grown], [max(r["energy_growth"], 1e-6) for r in grown], style,
                  color=f"C{i}", mfc="none", label=METHOD_TEXT[method])
        bad = [r for r in grown if not r["stable"]]
        a2.loglog([r["dt"] for r in bad], [max(r["energy_growth"], 1e-6) for r in bad], "kx", ms=10)
    BAO.mark_limits(a1, a2)
    a1.set_ylabel("boundary-only efficiency eta_boundary [%]")
    a1.legend(fontsize=7, loc="lower left")
    a2.axhline(1.0, color="r", lw=0.8)
    a2.set_ylabel("energy growth: stored / put in at the end\n(floored at 1e-6; x: unstable)")
    a2.set_xlabel("dt [s] (dotted: m/cn, eq. 44; dash-dot: 2m/ct; the hybrid has no limit)")
    a1.set_title("P-wave bar, 100 Hz: efficiency and energy growth against dt", fontsize=10)
    save(fig, out, "stability_map")


def cost_series(rows):
    """{label: rows} of the size sweeps of the cost chart (x = DOFs)."""
    return {
        "tunnel hybrid, near field 3/4/6 x the opening (+ large scene)":
            [r for r in rows if r["case"] == "tunnel_size" or
             (r["case"] == "tunnel" and r["method"] == "hybrid" and r["variant"] == "default")],
        "line source, blocks only (VB I; free edges at +-120 m)":
            [r for r in rows if r["case"] == "line_source" and r["method"] in ("vb1", "dda_large")],
        "line source, hybrid (Lysmer + springs)":
            [r for r in rows if r["case"] == "line_source"
             and r["method"] in ("hybrid", "reference") and "dt" not in r["variant"]],
        "bar, DDA only (100 and 300 m), dt 5e-5":
            [r for r in rows if r["case"] == "bar" and r["method"] in ("free", "dda_large")
             and r["variant"] == "dt 5e-05"],
    }


def figure_cost(rows, out):
    fig, ax = plt.subplots(figsize=(7.5, 5))
    slopes = {}
    for i, (label, pts) in enumerate(cost_series(rows).items()):
        pts = sorted((r for r in pts if r["ms_per_step"] and r["dofs"]), key=lambda r: r["dofs"])
        if not pts:
            continue
        x, y = [r["dofs"] for r in pts], [r["ms_per_step"] for r in pts]
        slopes[label] = fitted_slope(x, y)
        text = "" if slopes[label] is None else f" (slope {slopes[label]:.2f})"
        ax.loglog(x, y, "o-", color=f"C{i}", label=label + text)
    ax.set_xlabel("DOFs (blocks x 6 + far field)")
    ax.set_ylabel("ms per step (wall - far-field set-up) / steps")
    ax.set_title("cost per step against model size", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    save(fig, out, "cost_per_step")
    return slopes


# ---- outputs ----------------------------------------------------------------------------------

def machine():
    """CPU, cores, memory, OS, compiler, deal.II version and git commit."""
    def first(path, prefix):
        with open(path) as f:
            return next((line.split(":", 1)[1].strip() for line in f
                         if line.startswith(prefix)), "?")

    def command(*cmd):
        try:
            return subprocess.run(cmd, capture_output=True, text=True, cwd=TOP).stdout.strip()
        except OSError:
            return "?"

    dealii = "?"
    config = "/usr/share/cmake/deal.II/deal.IIConfig.cmake"
    if os.path.exists(config):
        with open(config) as f:
            dealii = next((line.split('"')[1] for line in f
                           if line.startswith('SET(DEAL_II_PACKAGE_VERSION')), "?")
    with open("/etc/os-release") as f:
        os_name = next((line.split("=", 1)[1].strip().strip('"') for line in f
                        if line.startswith("PRETTY_NAME")), platform.platform())
    dirty = command("git", "status", "--porcelain", "--untracked-files=no")
    return {"cpu": first("/proc/cpuinfo", "model name"), "cores": os.cpu_count(),
            "load": " / ".join(f"{v:.1f}" for v in os.getloadavg()),
            "memory_gb": round(int(first("/proc/meminfo", "MemTotal").split()[0]) / 2 ** 20, 1),
            "os": os_name, "compiler": command("c++", "--version").splitlines()[0],
            "deal_ii": dealii,
            "commit": command("git", "rev-parse", "--short", "HEAD")
            + (" (+ local changes)" if dirty else "")}


def write_results(rows, out):
    with open(os.path.join(out, "results.json"), "w") as f:
        json.dump([{k: r[k] for k in KEYS} for r in rows], f, indent=1)
    with open(os.path.join(out, "results.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=KEYS)
        writer.writeheader()
        for r in rows:
            writer.writerow({k: "" if r[k] is None else r[k] for k in KEYS})


def fmt(value, spec):
    return "" if value is None else format(value, spec)


def table(rows, extra):
    """A markdown table of rows; extra: the case's own column (peak_error or eta_boundary)."""
    head = {"peak_error": "peak error", "eta_boundary": "eta_boundary [%]"}[extra]
    lines = ["| method | variant | dt [s] | block [m] | element [m] | domain [m] | blocks | "
             f"DOFs | steps | wall [s] | ms/step | error | {head} | energy error | absorbed | "
             "dissipated | stable |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        extra_value = fmt(r[extra], ".2%") if extra == "peak_error" else fmt(r[extra], ".1f")
        stable = "yes" if r["stable"] else f"**no**: {r['reason']}"
        reference = " (reference)" if r["reference"] else ""
        lines.append(
            f"| {METHOD_TEXT.get(r['method'], r['method'])}{reference} | "
            f"{r['variant']} | {fmt(r['dt'], 'g')} | {fmt(r['block_size_m'], '.2f')} | "
            f"{fmt(r['element_size_m'], '.2f')} | {fmt(r['domain_size_m'], '.0f')} | "
            f"{fmt(r['blocks'], 'd')} | {fmt(r['dofs'], 'd')} | {fmt(r['steps'], 'd')} | "
            f"{fmt(r['wall_time_s'], '.2f')} | {fmt(r['ms_per_step'], '.3g')} | "
            f"{fmt(r['error'], '.2%')} | {extra_value} | {fmt(r['energy_error'], '.1e')} | "
            f"{fmt(r['energy_absorbed'], '.1%')} | {fmt(r['energy_dissipated'], '.1%')} | "
            f"{stable} |")
    return "\n".join(lines)


def recommendation_text(rows, case):
    cheapest, best, reference = recommendation(rows, case)
    if cheapest is None:
        return (f"No stable run is within 5% of the reference; the most accurate: "
                f"{row_text(best)}." if best else "No stable run besides the reference.")
    speed = reference["wall_time_s"] / cheapest["wall_time_s"]
    return (f"**Pick: {row_text(cheapest)}** (the cheapest stable run within 5% of the reference, "
            f"{speed:.1f}x faster than the reference's {reference['wall_time_s']:.2f} s). "
            f"Most accurate: {row_text(best)}.")


def picks_table(rows):
    """Per case and accuracy: the cheapest stable run within it, from the rows."""
    lines = ["| case | job | pick | error | wall [s] | faster than the reference |",
             "|---|---|---|---:|---:|---:|"]
    for case in CASES:
        for accuracy in PICK_ACCURACIES:
            cheapest, _, reference = recommendation(rows, case, accuracy)
            job = f"cheapest within {accuracy:.0%} of the reference"
            if cheapest is None:
                lines.append(f"| {case} | {job} | none of the runs |  |  |  |")
                continue
            variant = "" if cheapest["variant"] == "default" else f", {cheapest['variant']}"
            lines.append(f"| {case} | {job} | {METHOD_TEXT[cheapest['method']]}{variant} | "
                         f"{cheapest['error']:.2%} | {cheapest['wall_time_s']:.2f} | "
                         f"{reference['wall_time_s'] / cheapest['wall_time_s']:.1f}x |")
    return "\n".join(lines)


CASE_TEXT = {
    "bar": ("The P-wave bar of Bao et al. (2012), 100 m of 1 m blocks, 100 Hz pulse, to 0.05 s. "
            "Reference: the DDA-only bar three times longer at the finest dt (no reflection "
            "reaches M1 in the window). error = relative L2 of sxx at M1 (50.5 m) from t = 0 to "
            "the end of the reflection window, against the reference: it sees both the "
            "reflection from the truncation and DDA's algorithmic damping of the pulse at coarse "
            "dt, the two things a user trades against cost (eta_boundary, the boundary-only "
            "efficiency of verify_bao2012, is the reflection alone). An FE-only bar is not a "
            "--set away: point loads act on blocks only."),
    "line_source": ("`examples/coupled/point_source_2d.yaml`: a 100 Hz point force in 20 x 20 "
                    "bonded 1 m blocks, far elements of 5 m, trapezoidal rule, to 0.04 s. "
                    "Reference: the far field truncated at +-120 m (no reflection returns within "
                    "the window). error = worst relative L2 of the monitors' displacement (both "
                    "components, the whole record, on the reference's times). Blocks only: the "
                    "far field replaced by 1 m blocks to +-W with VB I or the dashpot on the "
                    "outer edges, or free edges at +-120 m (dda_large); their error also holds "
                    "the difference between the blocks and the FE far field at the far monitors. "
                    "FE only does not apply: the source is a point load on a block."),
    "tunnel": ("`examples/tunnel/stable_sv.yaml` (120 blocks around a 6 m tunnel, 25 Hz SV "
               "pulse) with `--set tunnel.truncation=...`. Reference: `reference` (the blocks in a "
               "far field so large that nothing returns within the run). error = the keyblock "
               "history error of `tools/verify_tunnel.py` (relative L2 of the reference's "
               "peak keyblock's displacement, aligned on the wave's arrival); peak error = the "
               "error of the largest keyblock peak. FE only does not apply: the keyblocks are "
               "blocks."),
}


def write_markdown(path, out, rows, missing, slopes, info, quick, jobs, elapsed, profile):
    rel = os.path.relpath(out, os.path.dirname(path))
    lim = BAO.boundary_limits()
    lines = ["# Speed against accuracy", "",
             f"Generated by `/usr/bin/python3 bench/speed_accuracy.py{' --quick' if quick else ''}"
             f" --jobs {jobs}` in {elapsed / 60:.1f} min (do not edit; rerun it). One row per run "
             f"in [results.csv]({rel}/results.csv) and [results.json]({rel}/results.json); the "
             "definitions are in the script's docstring.", "",
             "## Machine", "",
             f"{info['cpu']}, {info['cores']} cores, {info['memory_gb']} GB; {info['os']}; "
             f"{info['compiler']}; deal.II {info['deal_ii']}; commit {info['commit']}. Load "
             f"average (1 / 5 / 15 min) when the runs had finished: {info['load']}.", "",
             f"Wall times are ddafem's own (summary.json `wall_time_s`) with {jobs} runs sharing "
             "the machine at a time (each ddafem uses one core), snapshots at the first and last "
             "step only. ms/step = (wall - far-field set-up) / steps, static stages included.", "",
             "## Definitions", "",
             "- error: against the reference of the case (below); the reference rows have 0.",
             "- energy error = |put in + initial - (absorbed + left + dissipated)| / (put in + "
             "initial) at the end (`verify_coupling.energy_budget`; initial: the blocks' energy "
             "at the start of the dynamic stage). ddafem computes each part's dissipated energy "
             "as the rest of that part's balance, so the energy error is 0 by construction for "
             "blocks only; in coupled runs it measures whether the work through the ties that "
             "leaves the blocks arrives in the far field.",
             "- absorbed, dissipated = absorbed (by the boundary) and dissipated (the integrators' "
             "algorithmic damping: DDA's scheme damps, the trapezoidal rule does not) / (put in "
             "+ initial).",
             "- energy growth = left / (put in + initial) at the end; stable = no refusal by "
             "`ddafem check` (exit 2), no numerical failure, energy growth <= 1 and the boundary "
             f"not a source (absorbed >= -{SOURCE_TOLERANCE:g}: a boundary that does work on the "
             "model feeds energy in even when the integrator's damping hides the growth).",
             "- Recommendations: per case the cheapest stable run within 5% (and 1%) error of "
             "the reference, computed from the rows.", "",
             "## What to pick", "", picks_table(rows), "",
             "Runs that failed or were unstable are never picked; the tables below give every "
             "run.", ""]
    for case in CASES:
        extra = "peak_error" if case == "tunnel" else "eta_boundary"
        lines += [f"## {case}", "", CASE_TEXT[case], "",
                  table([r for r in rows if r["case"] == case], extra), "",
                  recommendation_text(rows, case), "",
                  blocks_only_note(rows) if case == "line_source" else "", "",
                  f"![{case}]({rel}/speed_accuracy_{case}.png)", ""]
        if case == "tunnel":
            lines += ["### Acceptance: the hybrid against a blocks-only model", "",
                      "On the tunnel scene the hybrid must reach the reference within 5% at least "
                      "5 times faster than a blocks-only model big enough to avoid boundary "
                      "reflections.", "", tunnel_verdict(rows, missing), ""]
            if missing:
                lines += ["Missing methods (rejected by `ddafem check`, not run): " +
                          ", ".join(f"`tunnel.truncation={m}`" for m in missing) + ".", ""]
    stab = [r for r in rows if r["case"] == "bar_stability"]
    lines += ["## Stability map", "",
              "The bar (small-displacement analysis, `--allow-unstable`, to 0.5 s for dt >= 1e-4 "
              "s so that a boundary that is a source shows itself) per boundary and dt. "
              f"Theory (docs/reference/physics.md section 3, the 1 m end block): VB I is a source beyond x0 m / "
              f"cn = {lim['vb1_source']:.3g} s (x0 = {BAO.VB1_THRESHOLD}); the paper's bounds "
              f"m / cn = {lim['m_over_cn']:.3g} s and 2 m / ct = {lim['two_m_over_ct']:.3g} s. VB "
              "II, the consistent dashpot and the hybrid's Lysmer dashpots (implicit, docs/reference/physics.md "
              "section 4) have no limit.", "",
              "| boundary | largest stable dt [s] | smallest unstable dt [s] | why |",
              "|---|---:|---:|---|"]
    for method in ("vb1", "vb2", "dashpot", "dashpot_effective", "hybrid"):
        pts = sorted((r for r in stab if r["method"] == method), key=lambda r: r["dt"])
        if not pts:
            continue
        good = [r["dt"] for r in pts if r["stable"]]
        bad = [r for r in pts if not r["stable"]]
        lines.append(f"| {METHOD_TEXT[method]} | {fmt(max(good) if good else None, 'g')} | "
                     f"{fmt(bad[0]['dt'] if bad else None, 'g')} | "
                     f"{bad[0]['reason'] if bad else 'stable at every dt run'} |")
    lines += ["", f"![stability map]({rel}/stability_map.png)", "",
              table(stab, "eta_boundary"), "",
              "## Cost per step against model size", "",
              "Slopes of log(ms/step) against log(DOFs): " + "; ".join(
                  f"{label}: {fmt(s, '.2f') or 'one size only'}" for label, s in slopes.items())
              + ".", "", table([r for r in rows if r["case"] == "tunnel_size"], "peak_error"), "",
              f"![cost per step]({rel}/cost_per_step.png)", ""]
    lines += [PROFILE.markdown_section(profile) if profile else
              "## Profile of the default tunnel scene\n\nNot run with --quick.\n"]
    with open(path, "w") as f:
        f.write("\n".join(lines))


# ---- sanity (the ctest's assertions) ----------------------------------------------------------

def validate(rows, out, md):
    """Problems with the outputs: files, keys, reference errors, stable flags."""
    problems = []
    names = ["results.csv", "results.json", "stability_map.png", "cost_per_step.png"] + \
        [f"speed_accuracy_{c}.png" for c in CASES]
    problems += [f"missing {n}" for n in names if not os.path.exists(os.path.join(out, n))]
    problems += [] if os.path.exists(md) else [f"missing {md}"]
    with open(os.path.join(out, "results.json")) as f:
        saved = json.load(f)
    problems += [f"row {i} lacks {sorted(set(KEYS) - set(r))}" for i, r in enumerate(saved)
                 if set(KEYS) - set(r)]
    for case in CASES:
        refs = [r for r in saved if r["case"] == case and r["reference"]]
        if len(refs) != 1 or refs[0]["error"] != 0.0 or not refs[0]["stable"]:
            problems.append(f"{case}: not one stable reference with error 0: {refs}")
    limit = BAO.boundary_limits()["vb1_source"]
    for r in saved:
        if r["method"] == "vb1" and r["case"].startswith("bar") and r["dt"] > limit and r["stable"]:
            problems.append(f"VB I above its limit flagged stable: {r}")
        if r["stable"] and r["error"] is not None and not (0.0 <= r["error"] < 10.0):
            problems.append(f"stable run with an error out of range: {r}")
        if r["stable"] and r["wall_time_s"] is None:
            problems.append(f"stable run without a wall time: {r}")
    if not any(r["method"] == "vb1" and r["case"].startswith("bar") and r["dt"] > limit
               for r in saved):
        problems.append("no VB I run above its limit")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--quick", action="store_true", help="a few short runs of each case")
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "performance"))
    args = parser.parse_args()
    start = time.monotonic()
    out = os.path.abspath(args.out)
    md = os.path.join(os.path.dirname(out), "performance.md")
    os.makedirs(out, exist_ok=True)

    with tempfile.TemporaryDirectory(prefix="speed_accuracy_") as root:
        ddafem = frozen_binary(os.path.abspath(args.build), root)
        tunnel, missing = tunnel_specs(args.quick, ddafem)
        jobs = bar_specs(args.quick) + line_source_specs(args.quick, root) + tunnel
        results = run_all(ddafem, jobs, root, args.jobs)
        # One run at a time, after the others: the profile's before and after in the same run.
        profile = None if args.quick else PROFILE.profile(ddafem, out, repeat=1)
        if profile:
            PROFILE.write_markdown(profile, out)
        rows = bar_rows([r for r in results if r["case"].startswith("bar")]) + \
            line_source_rows([r for r in results if r["case"] == "line_source"]) + \
            tunnel_rows([r for r in results if r["case"].startswith("tunnel")])

    write_results(rows, out)
    for case in CASES:
        figure_speed_accuracy(rows, case, out)
    figure_stability_map(rows, out)
    slopes = figure_cost(rows, out)
    elapsed = time.monotonic() - start
    write_markdown(md, out, rows, missing, slopes, machine(), args.quick, args.jobs, elapsed,
                   profile)
    for case in CASES:
        print(f"{case}: {recommendation_text(rows, case)}")
    print(tunnel_verdict(rows, missing))
    problems = validate(rows, out, md)
    print(f"wrote {out}/results.csv, .json, charts and {md} in {elapsed:.0f} s")
    if problems:
        sys.exit("sanity check failed:\n" + "\n".join(problems))


if __name__ == "__main__":
    main()
