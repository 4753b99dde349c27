"""Grouted bolts crossing a sliding joint against the hand calculation (tools/verify_support.py
runs these cases and appends them to docs/verification/support.{md,json}).

A slider (2 m x 1 m, rho 2650 kg/m^3: W = 51 993 N per metre) on a frictional joint (friction
angle 20 deg, no cohesion) steeper than its friction angle (30 deg; the scenes draw the joint
horizontal and tilt gravity instead), held by one grouted bolt across the joint
(examples/support/grouted_slider*.yaml). Hand limit equilibrium at rest, the joint's friction
fully mobilised (the slider came to rest from sliding): the slider has slid u along the joint;
the crossing's relative displacement (base side minus slider side) is delta = (-u, 0), its
opening o = delta . e and slip s = delta . t (e the bolt's direction from head to anchor,
t = (-e_y, e_x)); N = k_a o, S = k_s s; the bolt's force on the slider F = N e + S t; and along
the joint W sin 30 + F_x = tan 20 (W cos 30 - F_y), linear in u. k_a = E_s A_s / L_d and
k_s = K / (4 beta), beta = (pi K / (E_s A_s^2))^(1/4) (docs/support.md).

- `dowel_normal`: the bolt normal to the joint: a pure dowel, S = W (sin 30 - tan 20 cos 30);
- `inclined_29deg`: the bolt 29 deg from the joint's normal, leaning so that the sliding
  stretches it: N and S both act, and N presses the slider onto the joint.

Each runs a static stage (the slider settles into its bolt) and 0.5 s of motion with the
capacities (shear capacity, and the yield force where the bolt carries an axial force) at 1.02
and 0.98 of the hand forces. Expected: at 1.02 the slider stays (crossing elastic, no motion
in the dynamic stage, N and S within 2 % of the hand values); at 0.98 it slides (the crossing
yields and the slip grows to more than 5 times the hand value: the static stage finds no
equilibrium, the slider creeps on in it, and the run stops there with exit code 1).
"""
import math
import os
import tempfile

import h5py
import numpy as np

G = 9.81
WEIGHT = 2650 * G * 2.0  # N per metre: the slider's area is 2 m^2
SLOPE, FRICTION = math.radians(30), math.radians(20)
E_STEEL, AREA, GROUT, DEBONDED = 200e9, 5e-4, 10e9, 0.5  # Pa, m^2, Pa, m
AXIAL_STIFFNESS = E_STEEL * AREA / DEBONDED
SHEAR_STIFFNESS = GROUT / (4 * (math.pi * GROUT / (E_STEEL * AREA ** 2)) ** 0.25)
SCENES = {
    # name: scene, bolt, head, anchor, whether the yield force is scaled (the bolt pulls)
    "dowel_normal": ("grouted_slider.yaml", "dowel", (1.0, 1.0), (1.0, -0.8), False),
    "inclined_29deg": ("grouted_slider_inclined.yaml", "inclined", (1.5, 1.0), (0.5, -0.8), True),
}
FACTORS = [1.02, 0.98]
TOLERANCE = 0.02


def hand(head, anchor):
    """(u [m], N [N], S [N], slip [m]) at rest by limit equilibrium (the module's docstring)."""
    ex, ey = anchor[0] - head[0], anchor[1] - head[1]
    length = math.hypot(ex, ey)
    ex, ey = ex / length, ey / length
    tx, ty = -ey, ex
    opening, slip = -ex, -tx  # per metre of u: delta = (-1, 0)
    n, s = AXIAL_STIFFNESS * max(opening, 0.0) + 0.0, SHEAR_STIFFNESS * slip  # + 0.0: not -0.0
    fx, fy = n * ex + s * tx, n * ey + s * ty
    demand = WEIGHT * (math.sin(SLOPE) - math.tan(FRICTION) * math.cos(SLOPE))
    u = demand / (-fx - math.tan(FRICTION) * fy)
    return u, n * u, s * u, slip * u


def case(sa, ddafem, top, name, factor):
    scene, bolt, head, anchor, scale_yield = SCENES[name]
    u, axial, shear, slip_hand = hand(head, anchor)
    settings = {"bolts.0.shear_capacity": f"{factor * abs(shear):.6g}"}
    if scale_yield:
        settings["bolts.0.yield_force"] = f"{factor * axial:.6g}"
    row = {"scene": name, "capacity_over_demand": factor, "hand_slide_m": u,
           "hand_axial_force_n": axial, "hand_shear_force_n": shear, "hand_slip_m": slip_hand,
           "expected": "stays" if factor > 1 else "slides"}
    with tempfile.TemporaryDirectory() as out:
        run = sa.run(ddafem, {"scene": os.path.join(top, "examples", "support", scene),
                              "settings": settings, "allow_unstable": False},
                     os.path.join(out, "r"))
        row["exit"] = run["exit"]
        stages = run["summary"].get("stages", [])
        # Below the demand no static equilibrium exists: the static stage creeps on (exit 1,
        # "did not reach equilibrium") with the crossing yielding; the run stops there.
        row["static_equilibrium"] = bool(stages and stages[0].get("converged"))
        if run["exit"] != 0 and (run["exit"] != 1 or row["static_equilibrium"]
                                 or "grouted_bolts" not in run["summary"]):
            return {**row, "message": run["stderr"][-300:]}
        with h5py.File(os.path.join(out, "r", "histories.h5"), "r") as f:
            at = f"bolts/{bolt}/crossing0/"
            time = f["time"][:]
            slip = f[at + "slip"][:]
            row.update({"final_axial_force_n": float(f[at + "axial_force"][-1]),
                        "final_shear_force_n": float(f[at + "shear_force"][-1]),
                        "final_slip_m": float(slip[-1]),
                        "final_opening_m": float(f[at + "opening"][-1])})
    # The dynamic stage's motion: the slip's change after the static stage (time 0).
    static_end = np.nonzero(time <= 0.0)[0]
    base = slip[static_end[-1]] if len(static_end) else 0.0
    row["dynamic_stage_slip_m"] = float(np.abs(slip - base)[time > 0.0].max(initial=0.0))
    crossing = run["summary"]["grouted_bolts"][0]["crossings"][0]
    row["final_state"] = crossing["final_state"]
    row["axial_error"] = (abs(row["final_axial_force_n"] / axial - 1) if axial > 0
                          else None)
    row["shear_error"] = abs(row["final_shear_force_n"] / shear - 1)
    row["outcome"] = outcome(row)
    return row


def outcome(row):
    """stays: static equilibrium, the crossing elastic and the slip changing less than 0.01 mm
    in the dynamic stage; slides: the crossing yielding or ruptured and the slip over 5 times the
    hand value, and either no static equilibrium (the static stage creeps on: Shi's static
    analysis of a block that cannot be held) or motion in the dynamic stage; else `other`."""
    if row["static_equilibrium"] and row["final_state"] == "elastic" and \
            row["dynamic_stage_slip_m"] < 1e-5:
        return "stays"
    if row["final_state"] in ("yielding", "ruptured") and \
            abs(row["final_slip_m"]) > 5 * row["hand_slide_m"] and \
            (not row["static_equilibrium"] or row["dynamic_stage_slip_m"] > 1e-3):
        return "slides"
    return "other"


def passed(row):
    if row.get("outcome") != row["expected"]:
        return False
    if row["expected"] == "stays":
        return row["shear_error"] <= TOLERANCE and (row["axial_error"] or 0.0) <= TOLERANCE
    return True


def markdown(rows):
    """The section appended to docs/verification/support.md."""
    lines = ["", "## Grouted bolts across a sliding joint", "",
             "A slider on a 30 deg joint (friction angle 20 deg, no cohesion) held by one grouted "
             "bolt across the joint (`tools/verify_grouted.py`, examples/support/grouted_slider*"
             ".yaml). Hand limit equilibrium with the joint's friction fully mobilised: "
             f"k_a = {AXIAL_STIFFNESS:.4g} N/m, k_s = {SHEAR_STIFFNESS:.4g} N/m, W = "
             f"{WEIGHT:.0f} N. Capacities (shear, and yield where the bolt pulls) at 1.02 and "
             "0.98 of the hand forces. Acceptance: at 1.02 the slider stays (static equilibrium, "
             "crossing elastic, slip change < 0.01 mm in 0.5 s of motion) with N and S within 2 % "
             "of the hand values; at 0.98 it slides (crossing yielding, slip > 5 x the hand "
             "value, no static equilibrium: the static stage creeps on for its 5000 steps and "
             "the run stops with exit code 1).", "",
             "| bolt | capacity / demand | expected | outcome | hand N [N] | N / hand | "
             "hand S [N] | S / hand | hand slide u [mm] | hand slip [mm] | final slip [mm] | state | "
             "pass |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if "outcome" not in r:
            lines.append(f"| {r['scene']} | {r['capacity_over_demand']} | {r['expected']} | "
                         f"exit {r['exit']}: {r.get('message', '')} | | | | | | | | | no |")
            continue
        n_ratio = (f"{r['final_axial_force_n'] / r['hand_axial_force_n']:.5f}"
                   if r["hand_axial_force_n"] > 0 else f"({r['final_axial_force_n']:.3g} N)")
        lines.append(
            f"| {r['scene']} | {r['capacity_over_demand']} | {r['expected']} | {r['outcome']} | "
            f"{r['hand_axial_force_n']:.1f} | {n_ratio} | {r['hand_shear_force_n']:.1f} | "
            f"{r['final_shear_force_n'] / r['hand_shear_force_n']:.5f} | "
            f"{1e3 * r['hand_slide_m']:.4f} | {1e3 * r['hand_slip_m']:.4f} | "
            f"{1e3 * r['final_slip_m']:.4f} | "
            f"{r['final_state']} | {'yes' if passed(r) else 'no'} |")
    return lines


def cases():
    return [(n, f) for n in SCENES for f in FACTORS]
