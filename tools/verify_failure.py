#!/usr/bin/python3
"""The failure regime (docs/reference/benchmarks.md section D) with every time integrator of build/ddafem, and
regenerates docs/verification/failure.{md,json} and docs/verification/figures/failure_*.png.

  1  Newmark (1965) rigid sliding block: a 1 m x 0.5 m block with a frictional joint (cohesion
     and tensile strength 0) on a 20 m base block whose two fixed points follow a prescribed
     displacement u_b(t) along the slope, so that the base accelerates with
     a_b(t) = A sin(2 pi f t) for `cycles` cycles (then rests). The scene is drawn in the slope's
     frame: x runs down the slope of incline alpha and gravity is g (sin alpha, -cos alpha).
     u_b(t) = A t / w - A sin(w t) / w^2 (w = 2 pi f) is given as a table (`type: csv`) sampled
     at dt / 4 or finer: ddafem has no time function whose second derivative is a sine.
     A static stage settles the block first; the dynamic stage starts from there at t = 0.
     Measured: s(t) = ux(block centroid monitor) - ux(base monitor under it), the block's
     displacement relative to the base along the slope, positive down the slope.
     Reference: newmark_reference() below, an event-driven integration of the rigid block's
     relative motion s'' = g sin alpha - a_b(t) - sign(s') g cos alpha tan phi: the block sticks
     while the friction it needs, |g sin alpha - a_b|, is at most g cos alpha tan phi, slides
     otherwise and stops when s' returns to zero. Within a phase s' and s are closed forms; the
     phase changes are found on a grid of REFERENCE_STEP (1e-6 s) and refined by bisection.
     final_error = |s(T) - s_ref(T)| / |s_ref(T)| at the end of the run;
     history_error = max_t |s(t) - s_ref(t)| / max_t |s_ref(t)| over the history rows.
     Below yield (s_ref = 0) the largest |s| is reported instead (the contact's elastic shear
     only: pass if below NO_SLIP_LIMIT).
  2  Roof wedge and keyblock: a symmetric wedge of semi-apex angle beta in a roof between two
     fixed abutments, no clamping: it falls freely, u = g t^2 / 2 whatever the joints'
     friction; a block on a fixed base whose face dips b, friction phi < b: it slides down the
     dip with u = g (sin b - cos b tan phi) t^2 / 2. The same two errors on u (the centroid
     monitor's displacement along gravity, respectively along the dip).
  3  The P-wave bar of Bao et al. (2012) (examples/bao2012/p_wave_bar.yaml): each integrator's
     wave accuracy, measured as bench/speed_accuracy.py measures the bar's record error. Every
     run is the DDA-only bar three times longer (verify_bao2012.LONG_BAR: 300 blocks, so nothing
     returns from the far end to the monitors before t = 0.05 s). Runs: each integrator at
     dt = 5e-5 and 1e-4 s (200 and 100 steps per period of the 100 Hz pulse); reference: the
     same long bar with the trapezoidal rule (second order, no algorithmic damping) at
     BAR_REFERENCE_DT. record error = relative L2 (speed_accuracy.relative_l2) of sxx at M1
     (50.5 m) from t = 0 to the end of the reflection window of the 100 m bar
     (verify_bao2012.bar_windows(100), 46.6 ms): the incident pulse after 50 m of travel and
     its dispersive tail. Informational: m2_error, the same at M2 (98.5 m, the pulse after
     98 m) from t = 0 to the end of M2's incident window (98.5 m / c + one period + 2 ms,
     34.8 ms). The reference's own error is estimated from the same long bar at half its dt.

Integrators: every value of time.integrator that the binary accepts (`ddafem scene-reference`),
or --integrators. dt: the tool's choice per part (NEWMARK_DT, ROOF_DT, the bar's two), the same
for every integrator; time.control stays adaptive (the default) for parts 1 and 2, so a step
that fails is cut (the steps are in the tables). Acceptance for the default integrator (the
reference's default of time.integrator): parts 1 and 2 within 1% (final and history), the bar's
record error at M1 within 1% at 200 and 3% at 100 steps per period.

--quick (CI, about 20 s): three Newmark cases (one-way, two-way, below yield), both roof
scenes, the long bar at dt = 1e-4 only against a reference at 1e-5 s; checks that the files and
keys exist (exit 1 if not; the acceptance verdicts are printed and stored, not enforced).

usage: /usr/bin/python3 tools/verify_failure.py [--build build] [--jobs 2] [--quick]
           [--out docs/verification] [--integrators dda,newmark_trapezoidal]
"""
import argparse
import json
import math
import os
import re
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
sys.path.insert(0, os.path.join(TOP, "bench"))
import verify_bao2012 as BAO  # noqa: E402
import speed_accuracy as SA  # noqa: E402

G = 9.81
REFERENCE_STEP = 1e-6      # s, grid on which the reference finds its phase changes
NEWMARK_DT = 1e-3          # s, the dynamic step of the sliding-block runs
ROOF_DT = 1e-3             # s, the wedge and keyblock runs
BAR_DTS = [5e-5, 1e-4]     # s: 200 and 100 steps per period of the 100 Hz pulse
BAR_REFERENCE_DT = 5e-6    # s
BAR_REFERENCE_INTEGRATOR = "newmark_trapezoidal"
ACCEPT_SLIDE = 0.01        # parts 1 and 2: final and history error
ACCEPT_BAR = {5e-5: 0.01, 1e-4: 0.03}
NO_SLIP_LIMIT = 1e-4       # m: largest |s| below yield (elastic shear of the contact only)
# N/m, contact penalty of the sliding scenes: the reference's block is rigid, so the contact
# must be stiff against the motion: 10 E x 1 m (E = 10 GPa), within DDA's usual 10 to 100 E.
# Part 1b shows what a softer joint's elastic shear adds.
JOINT_STIFFNESS = 1e11
# Part 1b: the default integrator on the cases that slide to and fro, per contact penalty, with
# slip reversals localised (time.reversal_tolerance 1e-6, the default) and not (0).
SWEEP_CASES = ["two_way_flat_4Hz", "one_way_10deg_5Hz"]
SWEEP_STIFFNESS = [1e10, 1e11, 1e12]
REVERSAL_TOLERANCE = 1e-6  # m, time.reversal_tolerance of the localised runs (the default)
ROCK = {"density": 2650, "youngs_modulus": 10e9, "poisson_ratio": 0.25}

# Newmark cases: incline alpha [deg], friction phi [deg], amplitude A over the yield acceleration
# (down the slope, g (cos alpha tan phi - sin alpha)), frequency [Hz], cycles.
NEWMARK_CASES = [
    {"name": "one_way_15deg_2Hz", "incline": 15, "friction": 35, "ratio": 1.5, "frequency": 2,
     "cycles": 3},
    {"name": "one_way_20deg_1Hz", "incline": 20, "friction": 35, "ratio": 2.0, "frequency": 1,
     "cycles": 2},
    {"name": "one_way_10deg_5Hz", "incline": 10, "friction": 30, "ratio": 1.2, "frequency": 5,
     "cycles": 4},
    {"name": "two_way_flat_2Hz", "incline": 0, "friction": 30, "ratio": 1.5, "frequency": 2,
     "cycles": 2.5},
    {"name": "two_way_flat_4Hz", "incline": 0, "friction": 35, "ratio": 2.0, "frequency": 4,
     "cycles": 3.5},
    {"name": "below_yield_10deg_3Hz", "incline": 10, "friction": 35, "ratio": 0.8,
     "frequency": 3, "cycles": 3},
]
QUICK_NEWMARK = ["one_way_15deg_2Hz", "two_way_flat_2Hz", "below_yield_10deg_3Hz"]

# Roof scenes: a free-falling wedge (frictionless and rough joints) and a keyblock sliding on a
# joint of dip b.
WEDGE_HALF_WIDTH, WEDGE_BETA = 1.0, 20.0   # m, deg (semi-apex angle)
ROOF_CASES = [
    {"name": "wedge_frictionless", "kind": "wedge", "friction": 0, "end_time": 0.3},
    {"name": "wedge_rough_30deg", "kind": "wedge", "friction": 30, "end_time": 0.3},
    {"name": "keyblock_dip40_phi20", "kind": "slide", "dip": 40, "friction": 20,
     "end_time": 0.5},
]


# ---- the binary and its integrators -----------------------------------------------------------

def frozen_binary(build, directory, wait_s=600):
    """speed_accuracy.frozen_binary, waiting while the build directory relinks the binary."""
    deadline = time.monotonic() + wait_s
    while True:
        try:
            return SA.frozen_binary(build, directory)
        except SystemExit:
            if time.monotonic() > deadline:
                raise
            time.sleep(10)


def integrators_accepted(ddafem):
    """(names, default) of time.integrator from `ddafem scene-reference` (docs/scene_reference.md
    if the binary cannot print it): the row `integrator` of the section `time`."""
    proc = subprocess.run([ddafem, "scene-reference"], capture_output=True, text=True)
    text = proc.stdout
    if proc.returncode != 0 or "## `time`" not in text:
        with open(os.path.join(TOP, "docs", "scene_reference.md")) as f:
            text = f.read()
    section = text.split("## `time`", 1)[1].split("\n## ", 1)[0]
    row = next(line for line in section.splitlines() if line.startswith("| `integrator` |"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    default = re.findall(r"`([a-z_]+)`", cells[3])[0]
    return re.findall(r"`([a-z_]+)`", cells[4]), default


class PlainDumper(yaml.SafeDumper):
    """Writes repeated objects in full (no YAML anchors and aliases)."""

    def ignore_aliases(self, data):
        return True


def write_scene(scene, path):
    with open(path, "w") as f:
        yaml.dump(scene, f, Dumper=PlainDumper, sort_keys=False)
    return path


def binary_version(ddafem):
    """`ddafem --version` and the commit of the tree (and whether it had changes)."""
    version = subprocess.run([ddafem, "--version"], capture_output=True, text=True).stdout
    git = ["git", "-C", TOP]
    commit = subprocess.run(git + ["rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    dirty = subprocess.run(git + ["status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True).stdout.strip()
    return f"{version.strip()}, tree at {commit}" + (" with uncommitted changes" if dirty else "")


# ---- 1: Newmark's sliding block ---------------------------------------------------------------

def yield_acceleration(incline, friction):
    """Base acceleration [m/s^2] (up the slope) at which the block starts sliding down."""
    a, p = math.radians(incline), math.radians(friction)
    return G * (math.cos(a) * math.tan(p) - math.sin(a))


class SineBase:
    """Base acceleration a_b(t) = A sin(w t) for 0 <= t <= T = cycles / f, 0 after; its first
    (B) and second (C) integrals from rest at t = 0: velocity and displacement of the base."""

    def __init__(self, amplitude, frequency, cycles):
        self.A, self.w, self.T = amplitude, 2.0 * math.pi * frequency, cycles / frequency

    def acceleration(self, t):
        t = np.asarray(t, dtype=float)
        return np.where(t <= self.T, self.A * np.sin(self.w * t), 0.0)

    def velocity(self, t):
        tm = np.minimum(np.asarray(t, dtype=float), self.T)
        return self.A / self.w * (1.0 - np.cos(self.w * tm))

    def displacement(self, t):
        t = np.asarray(t, dtype=float)
        tm = np.minimum(t, self.T)
        return (self.A / self.w * tm - self.A / self.w ** 2 * np.sin(self.w * tm)
                + self.velocity(self.T) * np.maximum(t - self.T, 0.0))


def bisect(f, t0, t1, iterations=60):
    """The root of f in [t0, t1] (f(t0) <= 0 < f(t1))."""
    for _ in range(iterations):
        tm = 0.5 * (t0 + t1)
        if f(tm) > 0.0:
            t1 = tm
        else:
            t0 = tm
    return t1


def newmark_reference(incline, friction, base, end_time, step=REFERENCE_STEP):
    """Rigid block on a plane of incline alpha [deg], friction phi [deg], base acceleration
    base.acceleration(t) along the slope (+ down the slope). Returns the phases
    [(t0, t1, direction, s0, c)]: direction 0 stick (s = s0), +-1 sliding down / up the slope
    with s(t) = s0 + c (t - t0)^2 / 2 - (C(t) - C(t0) - B(t0) (t - t0)) where c = g sin alpha -
    direction g cos alpha tan phi and B, C the base's velocity and displacement (s'(t0) = 0 at
    every phase start)."""
    a, p = math.radians(incline), math.radians(friction)
    gs, friction_limit = G * math.sin(a), G * math.cos(a) * math.tan(p)
    grid = np.arange(0.0, end_time + step, step)
    drive = gs - base.acceleration(grid)   # relative acceleration without friction
    phases, t0, s0, i0 = [], 0.0, 0.0, 0
    direction = 0
    while t0 < end_time:
        if direction == 0:   # stick until the friction needed exceeds the limit
            over = np.nonzero(np.abs(drive[i0 + 1:]) > friction_limit)[0]
            if over.size == 0:
                phases.append((t0, end_time, 0, s0, 0.0))
                break
            i = i0 + 1 + over[0]
            t1 = bisect(lambda t: abs(gs - float(base.acceleration(t))) - friction_limit,
                        max(grid[i - 1], t0), grid[i])
            phases.append((t0, t1, 0, s0, 0.0))
            t0, direction = t1, (1 if gs - float(base.acceleration(t1)) > 0 else -1)
            i0 = int(t0 / step)
            continue
        c = gs - direction * friction_limit
        b0 = float(base.velocity(t0))

        def speed(t):   # s'(t) along the sliding direction
            return direction * (c * (t - t0) - (base.velocity(t) - b0))

        ahead = grid[i0 + 1:]
        ahead = ahead[ahead > t0 + 1e-12]
        stopped = np.nonzero(speed(ahead) <= 0.0)[0]
        if stopped.size == 0:
            phases.append((t0, end_time, direction, s0, c))
            break
        j = stopped[0]
        left = t0 if j == 0 else ahead[j - 1]
        t1 = bisect(lambda t: -float(speed(t)), left, ahead[j])
        phases.append((t0, t1, direction, s0, c))
        s0 = float(phase_displacement(phases[-1], base, t1))
        t0 = t1
        i0 = int(t0 / step)
        needed = gs - float(base.acceleration(t0))
        direction = 0 if abs(needed) <= friction_limit else (1 if needed > 0 else -1)
    return phases


def phase_displacement(phase, base, t):
    t0, _, direction, s0, c = phase
    if direction == 0:
        return s0 + 0.0 * np.asarray(t, dtype=float)
    dt = np.asarray(t, dtype=float) - t0
    return s0 + c * dt ** 2 / 2.0 - (base.displacement(t) - base.displacement(t0)
                                     - base.velocity(t0) * dt)


def reference_displacement(phases, base, times):
    """s_ref at the given times from the phases of newmark_reference."""
    times = np.asarray(times, dtype=float)
    s = np.zeros_like(times)
    for phase in phases:
        inside = (times >= phase[0]) & (times <= phase[1])
        s[inside] = phase_displacement(phase, base, times[inside])
    last = phases[-1]
    s[times > last[1]] = phase_displacement(last, base, last[1])
    return s


def newmark_base(case):
    return SineBase(case["ratio"] * yield_acceleration(case["incline"], case["friction"]),
                    case["frequency"], case["cycles"])


def newmark_end_time(case, phases):
    """The pulse, or the last slide if it ends later, plus 0.25 s at rest."""
    base = newmark_base(case)
    last_slide = max([p[1] for p in phases if p[2] != 0], default=0.0)
    return round(float(max(base.T, last_slide)) + 0.25, 3)


def newmark_scene(case, directory, end_time, dt):
    """Writes the scene (and the base's displacement table) of a Newmark case; returns its path."""
    base = newmark_base(case)
    a = math.radians(case["incline"])
    h = min(dt / 4.0, 1e-4)
    t = np.arange(0.0, end_time + dt + h, h)
    table = os.path.join(directory, case["name"] + "_base.csv")
    np.savetxt(table, np.column_stack([t, base.displacement(t)]), delimiter=",", fmt="%.12g")
    motion = {"type": "csv", "file": os.path.basename(table)}
    scene = {
        "name": "newmark_" + case["name"],
        "description": "Newmark (1965) rigid sliding block, in the slope's frame (x down the "
                       "slope); the base follows a sine acceleration along x.",
        "materials": {"base": ROCK, "block": ROCK},
        "joint_materials": {"sliding": {"normal_stiffness": JOINT_STIFFNESS,
                                        "friction_angle": case["friction"], "cohesion": 0,
                                        "tensile_strength": 0, "bonded": False}},
        "joints": {"default": "sliding"},
        "blocks": [{"material": "base", "vertices": [[-10, -1], [10, -1], [10, 0], [-10, 0]]},
                   {"material": "block", "vertices": [[-0.5, 0], [0.5, 0], [0.5, 0.5],
                                                      [-0.5, 0.5]]}],
        "fixed_points": [{"point": [x, -0.5], "displacement_x": motion} for x in (-9, 9)],
        "gravity": [G * math.sin(a), -G * math.cos(a)],
        "monitors": [{"name": "block", "point": [0, 0.25]}, {"name": "base", "point": [0, -0.5]}],
        "stages": [{"name": "settle", "mode": "static", "tolerance": 1e-6, "max_steps": 5000},
                   {"name": "shake", "mode": "dynamic"}],
        "time": {"dt": dt, "end_time": end_time},
    }
    return write_scene(scene, os.path.join(directory, case["name"] + ".yaml"))


# ---- 2: roof wedge and keyblock ---------------------------------------------------------------

def roof_scene(case, directory, dt):
    """A wedge between two fixed abutments, or a block on a fixed base dipping b."""
    joint = {"normal_stiffness": JOINT_STIFFNESS, "friction_angle": case["friction"],
             "cohesion": 0, "tensile_strength": 0, "bonded": False}
    if case["kind"] == "wedge":
        b = WEDGE_HALF_WIDTH
        h = b / math.tan(math.radians(WEDGE_BETA))
        top = h + 1.0
        blocks = [{"material": "rock", "vertices": [[-b - 2, 0], [-b, 0], [0, h], [0, top],
                                                    [-b - 2, top]]},
                  {"material": "rock", "vertices": [[b, 0], [b + 2, 0], [b + 2, top], [0, top],
                                                    [0, h]]},
                  {"material": "key", "vertices": [[-b, 0], [b, 0], [0, h]]}]
        fixed = [[-b - 1.5, top - 0.5], [-b - 0.5, top - 0.5], [b + 0.5, top - 0.5],
                 [b + 1.5, top - 0.5]]
        monitor = [0.0, h / 3.0]
    else:
        c, s = math.cos(math.radians(case["dip"])), math.sin(math.radians(case["dip"]))
        d, n = np.array([c, -s]), np.array([s, c])   # down the dip, out of the base
        p0, p1 = -3.0 * d, 3.0 * d
        blocks = [{"material": "rock",
                   "vertices": [list(p0 - 1.5 * n), list(p1 - 1.5 * n), list(p1), list(p0)]},
                  {"material": "key",
                   "vertices": [list(-0.5 * d), list(0.5 * d), list(0.5 * d + 0.5 * n),
                                list(-0.5 * d + 0.5 * n)]}]
        fixed = [list(-2.0 * d - 0.75 * n), list(2.0 * d - 0.75 * n)]
        monitor = list(0.25 * n)
    scene = {
        "name": case["name"],
        "materials": {"rock": ROCK, "key": ROCK},
        "joint_materials": {"joint": joint},
        "joints": {"default": "joint"},
        "blocks": [{"material": blk["material"],
                    "vertices": [[float(x), float(y)] for x, y in blk["vertices"]]}
                   for blk in blocks],
        "fixed_points": [{"point": [float(x), float(y)]} for x, y in fixed],
        "gravity": [0, -G],
        "monitors": [{"name": "key", "point": [float(x) for x in monitor]}],
        "time": {"dt": dt, "end_time": case["end_time"]},
    }
    return write_scene(scene, os.path.join(directory, case["name"] + ".yaml"))


def roof_analytic(case, t):
    """u(t) along gravity (wedge) or down the dip (keyblock)."""
    if case["kind"] == "wedge":
        a = G
    else:
        b, p = math.radians(case["dip"]), math.radians(case["friction"])
        a = G * (math.sin(b) - math.cos(b) * math.tan(p))
    return 0.5 * a * np.asarray(t) ** 2


def roof_measured(case, displacement):
    if case["kind"] == "wedge":
        return -displacement[:, 1]
    b = math.radians(case["dip"])
    return displacement[:, 0] * math.cos(b) - displacement[:, 1] * math.sin(b)


# ---- running and reading ----------------------------------------------------------------------

def monitors(r):
    """time and {name: displacement (n, 2)} of a run."""
    with h5py.File(os.path.join(r["dir"], "histories.h5"), "r") as f:
        return f["time"][:], {k: f[f"monitors/{k}/displacement"][:] for k in f["monitors"]}


def errors(t, s, s_ref):
    """(final_error, history_error) relative to |s_ref(T)| and max |s_ref|."""
    return (float(abs(s[-1] - s_ref[-1]) / abs(s_ref[-1])),
            float(np.max(np.abs(s - s_ref)) / np.max(np.abs(s_ref))))


def run_status(r):
    s = r["summary"]
    ok = r["exit"] == 0 and bool(s)
    return ok, ("ok" if ok else (s.get("failure") or r["stderr"][-300:] or f"exit {r['exit']}"))


def newmark_rows(results, cases, references):
    rows, curves = [], {}
    for r in results:
        case = cases[r["case_name"]]
        base, phases = references[case["name"]]
        ok, status = run_status(r)
        row = {"case": case["name"], "integrator": r["integrator"], "dt": r["dt"],
               "incline_deg": case["incline"], "friction_deg": case["friction"],
               "amplitude_over_yield": case["ratio"], "frequency_hz": case["frequency"],
               "cycles": case["cycles"],
               "yield_acceleration": yield_acceleration(case["incline"], case["friction"]),
               "steps": r["summary"].get("steps"), "wall_s": r["summary"].get("wall_time_s"),
               "status": status, "final_m": None, "final_reference_m": None,
               "max_abs_m": None, "final_error": None, "history_error": None, "pass": False}
        if ok or r["exit"] == 1:
            t, m = monitors(r)
            s = m["block"][:, 0] - m["base"][:, 0]
            s_ref = reference_displacement(phases, base, t)
            curves[(case["name"], r["integrator"])] = (t, s)
            row.update(final_m=float(s[-1]), final_reference_m=float(s_ref[-1]),
                       max_abs_m=float(np.max(np.abs(s))))
            if case["ratio"] > 1.0:
                row["final_error"], row["history_error"] = errors(t, s, s_ref)
                row["pass"] = bool(ok and max(row["final_error"], row["history_error"]) <= ACCEPT_SLIDE)
            else:
                row["pass"] = bool(ok and row["max_abs_m"] <= NO_SLIP_LIMIT)
        rows.append(row)
    return rows, curves


def roof_rows(results, cases):
    rows, curves = [], {}
    for r in results:
        case = cases[r["case_name"]]
        ok, status = run_status(r)
        row = {"case": case["name"], "integrator": r["integrator"], "dt": r["dt"],
               "steps": r["summary"].get("steps"), "status": status,
               "analytic_acceleration": float(roof_analytic(case, 1.0) * 2.0),
               "final_m": None, "final_reference_m": None, "final_error": None,
               "history_error": None, "pass": False}
        if ok or r["exit"] == 1:
            t, m = monitors(r)
            u, u_ref = roof_measured(case, m["key"]), roof_analytic(case, t)
            curves[(case["name"], r["integrator"])] = (t, u)
            row.update(final_m=float(u[-1]), final_reference_m=float(u_ref[-1]))
            row["final_error"], row["history_error"] = errors(t, u, u_ref)
            row["pass"] = bool(ok and max(row["final_error"], row["history_error"]) <= ACCEPT_SLIDE)
        rows.append(row)
    return rows, curves


def bar_record_windows():
    """{monitor: t1}: the records compared, from t = 0 to t1 [s]. M1 (50.5 m): the end of the
    reflection window of the 100 m bar (verify_bao2012.bar_windows, as speed_accuracy); M2
    (98.5 m): the end of its incident window, 98.5 m / c + one period + 2 ms (bar_windows' rule)."""
    c = BAO.jointed_speed(BAO.E, 2.0 * 2.5e12)
    return {"M1": BAO.bar_windows(100.0)[1][1], "M2": 98.5 / c + 0.01 + 0.002}


def bar_sxx(r):
    """time and {monitor: sxx} of a bar run."""
    with h5py.File(os.path.join(r["dir"], "histories.h5"), "r") as f:
        return f["time"][:], {m: f[f"monitors/{m}/stress"][:, 0] for m in ("M1", "M2")}


def bar_errors(run, reference):
    """{monitor: relative L2 of its sxx against the reference over [0, t1]}."""
    (t, x), (t_ref, x_ref) = run, reference
    return {m: SA.relative_l2(t, x[m], t_ref, x_ref[m], t1)
            for m, t1 in bar_record_windows().items()}


def bar_rows(results, reference, half_reference):
    ref = bar_sxx(reference)
    reference_error = bar_errors(bar_sxx(half_reference), ref)
    rows, curves = [], {}
    for r in results:
        ok, status = run_status(r)
        row = {"integrator": r["integrator"], "dt": r["dt"],
               "steps_per_period": round(0.01 / r["dt"]), "status": status,
               "record_error": None, "m2_error": None,
               "reference_error": reference_error["M1"],
               "reference_m2_error": reference_error["M2"],
               "limit": ACCEPT_BAR.get(r["dt"]), "pass": False}
        if ok:
            run = bar_sxx(r)
            curves[(r["integrator"], r["dt"])] = run
            e = bar_errors(run, ref)
            row["record_error"], row["m2_error"] = e["M1"], e["M2"]
            row["pass"] = bool(row["limit"] is not None and row["record_error"] <= row["limit"])
        rows.append(row)
    return rows, curves, ref


# ---- figures ----------------------------------------------------------------------------------

def figure_newmark(cases, references, curves, integrators, path):
    fig, axes = plt.subplots(len(cases), 1, figsize=(8, 2.3 * len(cases)), squeeze=False)
    for ax, case in zip(axes[:, 0], cases):
        base, phases = references[case["name"]]
        end = max([curves[k][0][-1] for k in curves if k[0] == case["name"]], default=1.0)
        t = np.linspace(0.0, end, 2000)
        ax.plot(t, 1e3 * reference_displacement(phases, base, t), "k-", lw=2.5, alpha=0.4,
                label="reference (rigid block)")
        for name in integrators:
            if (case["name"], name) in curves:
                tt, s = curves[(case["name"], name)]
                ax.plot(tt, 1e3 * s, lw=1, label=name)
        ax.set_ylabel("s [mm]")
        ax.set_title(f"{case['name']}: alpha {case['incline']} deg, phi {case['friction']} deg, "
                     f"A = {case['ratio']} a_y, {case['frequency']} Hz x {case['cycles']}",
                     fontsize=9)
        ax.legend(fontsize=7)
    axes[-1, 0].set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def figure_roof(cases, curves, integrators, path):
    fig, axes = plt.subplots(1, len(cases), figsize=(4 * len(cases), 3.5), squeeze=False)
    for ax, case in zip(axes[0], cases):
        t = np.linspace(0.0, case["end_time"], 200)
        ax.plot(t, 1e3 * roof_analytic(case, t), "k-", lw=2.5, alpha=0.4, label="analytic")
        for name in integrators:
            if (case["name"], name) in curves:
                tt, u = curves[(case["name"], name)]
                ax.plot(tt, 1e3 * u, lw=1, label=name)
        ax.set_title(case["name"], fontsize=9)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("u [mm]")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def figure_bar(curves, reference, integrators, dts, label, path):
    windows = bar_record_windows()
    fig, axes = plt.subplots(len(dts), 2, figsize=(12, 3 * len(dts)), squeeze=False)
    for row, dt in zip(axes, dts):
        for ax, (monitor, position) in zip(row, (("M1", 50.5), ("M2", 98.5))):
            t1 = windows[monitor]
            keep = reference[0] <= t1
            ax.plot(1e3 * reference[0][keep], 1e-6 * reference[1][monitor][keep], "k-", lw=2.5,
                    alpha=0.4, label=f"reference ({label})")
            for name in integrators:
                if (name, dt) in curves:
                    t, x = curves[(name, dt)]
                    ax.plot(1e3 * t[t <= t1], 1e-6 * x[monitor][t <= t1], lw=1, label=name)
            start = 0.8 * position / BAO.jointed_speed(BAO.E, 5e12)
            ax.set_xlim(1e3 * start, 1e3 * t1)
            ax.set_title(f"long bar, sxx at {monitor} ({position} m), dt {dt:g} s "
                         f"({round(0.01 / dt)} steps per period)", fontsize=9)
            ax.set_ylabel("sxx [MPa]")
            ax.legend(fontsize=7)
    for ax in axes[-1]:
        ax.set_xlabel("time [ms]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---- report -----------------------------------------------------------------------------------

def pct(value):
    return "-" if value is None else f"{100.0 * value:.2f}%"


def mm(value):
    return "-" if value is None else f"{1e3 * value:.3f}"


def verdicts(newmark, roof, bar, default):
    """Acceptance of the default integrator, computed from the rows."""
    mine = lambda rows: [r for r in rows if r["integrator"] == default]  # noqa: E731
    result = {
        "newmark": bool(mine(newmark)) and all(r["pass"] for r in mine(newmark)),
        "roof": bool(mine(roof)) and all(r["pass"] for r in mine(roof)),
        "bar": bool(mine(bar)) and all(r["pass"] for r in mine(bar)),
    }
    result["all"] = all(result.values())
    return result


def sweep_lines(d):
    """Part 1b: the default integrator per contact penalty, reversals localised or not."""
    rows = d["newmark"].get("sweep", [])
    if not rows:
        return []
    lines = [
        "### 1b. The joint's stiffness and the localisation of slip reversals", "",
        f"{d['default_integrator']} at dt {NEWMARK_DT:g} s on the cases that slide to and fro, "
        "per contact normal stiffness (shear 0.4 of it), with slip reversals localised "
        f"(`time.reversal_tolerance: {REVERSAL_TOLERANCE:g}`: a step in which a sliding contact "
        "turns around is redone to end just before it, and the step at the turn is redone "
        "with the integrator restarted at the friction's jump; the default) and not "
        "(`time.reversal_tolerance: 0`; docs/design.md, Integrators). The elastic shear spring "
        "of a softer joint "
        "stores mu N / p_s at every reversal and gives it back: an error of the joint, not of "
        "the integrator, that shrinks as the joint stiffens. Without localisation each "
        "reversal leaves the friction acting the wrong way for part of a step.", "",
        "| case | normal stiffness [N/m] | reversals localised | steps shortened | steps | "
        "final error | history error |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['case']} | {r['stiffness_n_m']:g} | "
                     f"{'yes' if r['localised'] else 'no'} | {r.get('slip_reversals')} | "
                     f"{r['steps']} | {pct(r['final_error'])} | {pct(r['history_error'])} |")
    return lines


def write_markdown(path, data):
    d = data
    lines = [
        "# The failure regime: sliding, falling and sliding-out blocks, per time integrator", "",
        "Generated by `tools/verify_failure.py` (do not edit)"
        + (" with `--quick`" if d["quick"] else "") + f"; {d['elapsed_s']:.0f} s. "
        f"Integrators: {', '.join(d['integrators'])}; the default is **{d['default_integrator']}**"
        " (time.integrator's default in `ddafem scene-reference`). docs/reference/benchmarks.md section D.", "",
        "## Acceptance of the default integrator", "",
        "| part | criterion | met |", "|---|---|---|",
        f"| 1 Newmark sliding block | final and history error <= {pct(ACCEPT_SLIDE)} (below yield: "
        f"max abs s <= {1e3 * NO_SLIP_LIMIT:g} mm), dt {NEWMARK_DT:g} s | "
        f"{'yes' if d['acceptance']['newmark'] else '**no**'} |",
        f"| 2 roof wedge, keyblock | final and history error <= {pct(ACCEPT_SLIDE)}, dt "
        f"{ROOF_DT:g} s | {'yes' if d['acceptance']['roof'] else '**no**'} |",
        "| 3 P-wave bar (long bar, sxx at M1) | record error <= 1% at 200, <= 3% at 100 steps "
        "per period | "
        f"{'yes' if d['acceptance']['bar'] else '**no**'} |", "",
        "## Worst case per integrator", "",
        "The largest of the final and history errors over the sliding cases above yield (part "
        "1) and the roof cases (part 2), and the bar's record error at M1 per dt (part 3).", "",
        "| integrator | part 1 worst | part 2 worst | "
        + " | ".join(f"bar, dt {r['dt']:g}" for r in d["bar"]["rows"]
                     if r["integrator"] == d["integrators"][0]) + " |",
        "|---|---|---|" + "---|" * len([r for r in d["bar"]["rows"]
                                        if r["integrator"] == d["integrators"][0]])]
    for name in d["integrators"]:
        worst = [max([max(r["final_error"], r["history_error"]) if r["final_error"] is not None
                      else math.inf for r in d[part]["rows"] if r["integrator"] == name
                      and r.get("amplitude_over_yield", 2.0) > 1.0], default=None)
                 for part in ("newmark", "roof")]
        lines.append(f"| {name} | {pct(worst[0])} | {pct(worst[1])} | " + " | ".join(
            pct(r["record_error"]) for r in d["bar"]["rows"] if r["integrator"] == name) + " |")
    lines += [
        "", f"Binary: `{d['version']}`.", "",
        "## 1. Newmark (1965) rigid sliding block", "",
        "A 1 m x 0.5 m block (frictional joint, no cohesion or tensile strength, normal stiffness "
        f"{JOINT_STIFFNESS:g} N/m) on a 20 m x 1 m base whose two fixed points follow u_b(t) = "
        "A t / w - A sin(w t) / w^2 (a table sampled at dt / 4), i.e. a base acceleration "
        "A sin(w t) for the given cycles. The scene is in the slope's frame (x down the slope, "
        "gravity g (sin alpha, -cos alpha)). A static stage settles the block, then the base "
        "shakes. s = ux(block centroid) - ux(base below it), positive down the slope. "
        "a_y = g (cos alpha tan phi - sin alpha): the base acceleration up the slope at which the "
        "block starts sliding down. Reference: the rigid block's relative motion, event-driven "
        f"(stick while |g sin alpha - a_b| <= g cos alpha tan phi; phase changes on a "
        f"{REFERENCE_STEP:g} s grid refined by bisection, closed forms within phases).", "",
        "final error = |s(T) - s_ref(T)| / |s_ref(T)| at the end of the run; history error = "
        "max over the history rows of |s - s_ref| / max |s_ref|. Below yield: the largest |s|. "
        "Where the sliding reverses without a stick phase (two_way_flat_4Hz: six times), each "
        "reversal leaves the friction acting the wrong way for part of a step unless "
        "`time.reversal_tolerance` localises it (1e-6 m by default; part 1b; "
        "docs/design.md, section Integrators).",
        "",
        "| case | alpha [deg] | phi [deg] | A / a_y | f [Hz] x cycles | integrator | steps | "
        "s_ref(T) [mm] | s(T) [mm] | final error | history error | max abs s [mm] | pass |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in d["newmark"]["rows"]:
        lines.append(
            f"| {r['case']} | {r['incline_deg']} | {r['friction_deg']} | "
            f"{r['amplitude_over_yield']} | {r['frequency_hz']} x {r['cycles']} | "
            f"{r['integrator']} | {r['steps']} | {mm(r['final_reference_m'])} | "
            f"{mm(r['final_m'])} | {pct(r['final_error'])} | {pct(r['history_error'])} | "
            f"{mm(r['max_abs_m'])} | {'yes' if r['pass'] else '**no**'} |"
            + ("" if r["status"] == "ok" else f" {r['status']} |"))
    lines += ["", "![Newmark](figures/failure_newmark.png)", ""] + sweep_lines(d) + ["",
              "## 2. Roof wedge and keyblock", "",
              f"A symmetric wedge (half width {WEDGE_HALF_WIDTH:g} m, semi-apex angle "
              f"{WEDGE_BETA:g} deg) between two fixed abutments with no clamping falls freely, "
              "u = g t^2 / 2, whatever the joints' friction (moving down opens both joints). A "
              "1 m x 0.5 m block on a fixed base whose face dips b, friction phi < b, slides "
              "down the dip: u = g (sin b - cos b tan phi) t^2 / 2. u from the centroid monitor, "
              "along gravity (wedge) or the dip (keyblock). Errors as in part 1 against the "
              "analytic u.", "",
              "| case | integrator | steps | analytic accel. [m/s^2] | u_ref(T) [mm] | u(T) [mm] "
              "| final error | history error | pass |", "|---|---|---|---|---|---|---|---|---|"]
    for r in d["roof"]["rows"]:
        lines.append(
            f"| {r['case']} | {r['integrator']} | {r['steps']} | "
            f"{r['analytic_acceleration']:.3f} | {mm(r['final_reference_m'])} | "
            f"{mm(r['final_m'])} | {pct(r['final_error'])} | {pct(r['history_error'])} | "
            f"{'yes' if r['pass'] else '**no**'} |"
            + ("" if r["status"] == "ok" else f" {r['status']} |"))
    bar = d["bar"]
    lines += ["", "![roof](figures/failure_roof.png)", "",
              "## 3. P-wave bar of Bao et al. (2012): the record error on the long bar", "",
              "Each integrator's wave accuracy, measured as `bench/speed_accuracy.py` measures "
              "the bar's record error. Every run is `examples/bao2012/p_wave_bar.yaml` made "
              "three times longer (`verify_bao2012.LONG_BAR`: 300 blocks of 1 m, so nothing "
              "returns from the far end to the monitors before the run ends at 0.05 s) with "
              "`--set time.integrator=...`; the reference is the same long bar with "
              f"{bar['reference_integrator']} (second order, no algorithmic damping) at dt "
              f"{bar['reference_dt']:g} s. **record error** = relative L2 of sxx at M1 (50.5 m) "
              f"from t = 0 to {1e3 * bar['windows_s']['M1']:.1f} ms, the end of the 100 m "
              "bar's reflection window (`verify_bao2012.bar_windows(100)`): the incident pulse "
              "after 50 m of travel and its dispersive tail (`speed_accuracy.relative_l2`). "
              "**M2 error** (informational) = the same at M2 (98.5 m) from t = 0 to "
              f"{1e3 * bar['windows_s']['M2']:.1f} ms, the end of its incident window: the "
              "pulse after 98 m. The reference's own error, estimated as the error of the same "
              f"long bar at dt {bar['reference_dt'] / 2:g} s against it: "
              f"{pct(bar['reference_error'])} at M1, {pct(bar.get('reference_m2_error'))} at "
              "M2. The acceptance applies to the record error at M1.", "",
              "| integrator | dt [s] | steps per period | record error (M1) | limit | pass "
              "| M2 error |",
              "|---|---|---|---|---|---|---|"]
    for r in bar["rows"]:
        lines.append(f"| {r['integrator']} | {r['dt']:g} | {r['steps_per_period']} | "
                     f"{pct(r['record_error'])} | {pct(r['limit'])} | "
                     f"{'yes' if r['pass'] else '**no**'} | {pct(r.get('m2_error'))} |"
                     + ("" if r["status"] == "ok" else f" {r['status']} |"))
    lines += ["", "![bar](figures/failure_bar.png)", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


JSON_KEYS = {"integrators", "default_integrator", "quick", "elapsed_s", "acceptance", "newmark",
             "roof", "bar"}
ROW_KEYS = {"newmark": {"case", "integrator", "dt", "final_error", "history_error", "pass"},
            "roof": {"case", "integrator", "dt", "final_error", "history_error", "pass"},
            "bar": {"integrator", "dt", "record_error", "m2_error", "pass"}}


def validate(out):
    """Missing files and keys of the outputs."""
    problems = []
    files = ["failure.md", "failure.json"] + [f"figures/failure_{n}.png"
                                              for n in ("newmark", "roof", "bar")]
    problems += [f"missing {n}" for n in files if not os.path.exists(os.path.join(out, n))]
    if problems:
        return problems
    with open(os.path.join(out, "failure.json")) as f:
        saved = json.load(f)
    problems += [f"failure.json lacks {k}" for k in sorted(JSON_KEYS - set(saved))]
    for part, keys in ROW_KEYS.items():
        rows = saved.get(part, {}).get("rows", [])
        if not rows:
            problems.append(f"failure.json: no {part} rows")
        problems += [f"{part} row {i} lacks {sorted(keys - set(r))}" for i, r in enumerate(rows)
                     if keys - set(r)]
        for integrator in saved.get("integrators", []):
            if not any(r["integrator"] == integrator for r in rows):
                problems.append(f"{part}: no row of {integrator}")
    return problems


# ---- main -------------------------------------------------------------------------------------

def integrator_settings(name):
    """The --set overrides of an integrator given as NAME or NAME:RHO (generalized_alpha's
    spectral radius at infinite frequency)."""
    integrator, _, rho = name.partition(":")
    settings = {"time.integrator": integrator}
    if rho:
        settings["time.spectral_radius"] = float(rho)
    return settings


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--quick", action="store_true", help="fewer cases (CI)")
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "verification"))
    parser.add_argument("--integrators", default=None,
                        help="comma-separated, NAME or NAME:RHO (generalized_alpha with "
                             "time.spectral_radius RHO); default: every one the binary accepts")
    args = parser.parse_args()
    start = time.monotonic()
    out = os.path.abspath(args.out)
    os.makedirs(os.path.join(out, "figures"), exist_ok=True)

    with tempfile.TemporaryDirectory(prefix="verify_failure_") as root:
        ddafem = frozen_binary(os.path.abspath(args.build), root)
        accepted, default = integrators_accepted(ddafem)
        version = binary_version(ddafem)
        integrators = args.integrators.split(",") if args.integrators else accepted
        unknown = sorted(set(i.split(":")[0] for i in integrators) - set(accepted))
        if unknown:
            sys.exit(f"the binary does not accept time.integrator {unknown}; it accepts "
                     f"{accepted}")
        scenes = os.path.join(root, "scenes")
        os.makedirs(scenes)

        newmark_cases = [c for c in NEWMARK_CASES if not args.quick or c["name"] in QUICK_NEWMARK]
        references, jobs = {}, []
        for case in newmark_cases:
            base = newmark_base(case)
            phases = newmark_reference(case["incline"], case["friction"], base, base.T + 1.5)
            end = newmark_end_time(case, phases)
            references[case["name"]] = (base, phases)
            scene = newmark_scene(case, scenes, end, NEWMARK_DT)
            for name in integrators:
                jobs.append(SA.spec("newmark", name, case["name"], scene,
                                    integrator_settings(name), case_name=case["name"],
                                    integrator=name, dt=NEWMARK_DT, est_s=end))
        for case in [c for c in newmark_cases if c["name"] in SWEEP_CASES]:
            scene = newmark_scene(case, scenes, newmark_end_time(case, references[case["name"]][1]),
                                  NEWMARK_DT)
            for k in SWEEP_STIFFNESS:
                for localised in (True, False):
                    settings = {**integrator_settings(default),
                                "joint_materials.sliding.normal_stiffness": k}
                    settings["time.reversal_tolerance"] = REVERSAL_TOLERANCE if localised else 0
                    jobs.append(SA.spec("newmark_sweep", default, f"{case['name']} {k:g} "
                                        f"{localised}", scene, settings, case_name=case["name"],
                                        integrator=default, dt=NEWMARK_DT, est_s=2.0,
                                        stiffness=k, localised=localised))
        for case in ROOF_CASES:
            scene = roof_scene(case, scenes, ROOF_DT)
            for name in integrators:
                jobs.append(SA.spec("roof", name, case["name"], scene,
                                    integrator_settings(name), case_name=case["name"],
                                    integrator=name, dt=ROOF_DT, est_s=case["end_time"]))
        bar_dts = [1e-4] if args.quick else BAR_DTS
        reference_dt = 1e-5 if args.quick else BAR_REFERENCE_DT
        reference_integrator = BAR_REFERENCE_INTEGRATOR if BAR_REFERENCE_INTEGRATOR in accepted \
            else default
        long_bar = dict(BAO.LONG_BAR)
        for dt in [reference_dt, reference_dt / 2.0]:
            jobs.append(SA.spec("bar_reference", reference_integrator, f"dt {dt:g}", BAO.BAR,
                                {**long_bar, "time.integrator": reference_integrator,
                                 "time.dt": dt},
                                integrator=reference_integrator, dt=dt, est_s=0.15 / dt * 1e-3))
        for dt in bar_dts:
            for name in integrators:
                jobs.append(SA.spec("bar", name, f"dt {dt:g}", BAO.BAR,
                                    {**long_bar, **integrator_settings(name), "time.dt": dt},
                                    integrator=name, dt=dt, est_s=0.15 / dt * 1e-3))
        results = SA.run_all(ddafem, jobs, root, args.jobs)

        by_case = {c["name"]: c for c in newmark_cases}
        newmark, newmark_curves = newmark_rows([r for r in results if r["case"] == "newmark"],
                                               by_case, references)
        sweep = []
        for r in [r for r in results if r["case"] == "newmark_sweep"]:
            row = newmark_rows([r], by_case, references)[0][0]
            row.update(stiffness_n_m=r["stiffness"], localised=r["localised"],
                       slip_reversals=r["summary"].get("time_step", {}).get("slip_reversals"))
            sweep.append(row)
        roof, roof_curves = roof_rows([r for r in results if r["case"] == "roof"],
                                      {c["name"]: c for c in ROOF_CASES})
        ref_runs = [r for r in results if r["case"] == "bar_reference"]
        for r in ref_runs:
            if run_status(r)[0] is False:
                sys.exit(f"the bar reference failed: {run_status(r)[1]}")
        bar, bar_curves, bar_reference = bar_rows([r for r in results if r["case"] == "bar"],
                                                  ref_runs[0], ref_runs[1])

        figures = os.path.join(out, "figures")
        figure_newmark(newmark_cases, references, newmark_curves, integrators,
                       os.path.join(figures, "failure_newmark.png"))
        figure_roof(ROOF_CASES, roof_curves, integrators, os.path.join(figures, "failure_roof.png"))
        figure_bar(bar_curves, bar_reference, integrators, bar_dts,
                   f"{reference_integrator}, dt {reference_dt:g}",
                   os.path.join(figures, "failure_bar.png"))

    data = {"integrators": integrators, "default_integrator": default, "quick": args.quick,
            "version": version,
            "elapsed_s": time.monotonic() - start,
            "acceptance": verdicts(newmark, roof, bar, default),
            "newmark": {"dt": NEWMARK_DT, "reference_step": REFERENCE_STEP,
                        "no_slip_limit_m": NO_SLIP_LIMIT, "cases": newmark_cases,
                        "joint_stiffness_n_m": JOINT_STIFFNESS, "rows": newmark,
                        "sweep": sweep},
            "roof": {"dt": ROOF_DT, "cases": ROOF_CASES, "rows": roof},
            "bar": {"reference_integrator": reference_integrator, "reference_dt": reference_dt,
                    "reference_error": bar[0]["reference_error"] if bar else None,
                    "reference_m2_error": bar[0]["reference_m2_error"] if bar else None,
                    "windows_s": bar_record_windows(), "long_bar": BAO.LONG_BAR,
                    "rows": bar}}
    with open(os.path.join(out, "failure.json"), "w") as f:
        json.dump(data, f, indent=1)
    write_markdown(os.path.join(out, "failure.md"), data)

    for part, rows in (("newmark", newmark), ("roof", roof)):
        for r in rows:
            print(f"{part:8s} {r['case']:24s} {r['integrator']:20s} final {pct(r['final_error'])}"
                  f" history {pct(r['history_error'])} max|s| {mm(r.get('max_abs_m'))} mm "
                  f"{'pass' if r['pass'] else 'FAIL'} {'' if r['status'] == 'ok' else r['status']}")
    for r in bar:
        print(f"bar      dt {r['dt']:<8g} {r['integrator']:20s} record (M1) "
              f"{pct(r['record_error'])} (limit {pct(r['limit'])}) "
              f"{'pass' if r['pass'] else 'FAIL'}; M2 {pct(r['m2_error'])}")
    acceptance = data["acceptance"]
    print(f"acceptance of the default integrator {default}: " + ", ".join(
        f"{k} {'met' if v else 'NOT met'}" for k, v in acceptance.items()))
    problems = validate(out)
    print(f"wrote {out}/failure.md, failure.json, figures/failure_*.png in "
          f"{data['elapsed_s']:.0f} s")
    if problems:
        sys.exit("sanity check failed:\n" + "\n".join(problems))


if __name__ == "__main__":
    main()
