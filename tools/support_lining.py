"""The lining's cases of tools/verify_support.py: the roof wedge hanging on a shotcrete lining.

examples/support/lined_wedge.yaml: the roof wedge of examples/failure/roof_wedge.yaml (faces
frictionless, no cohesion: they open as it sags, so the lining carries all of it) under a lining
along the roof y = 0 with nodes every `segment` m from -3 + segment / 2 (blocks at E = 1e12 Pa:
rigid, as the hand calculation takes them), so that no node lies on
a joint and one element of length L = segment straddles each of the wedge's joints (x = -+1).
Every other element lies on one block and moves with it. Hand calculation of each straddling
element: a beam with both ends held from turning (the abutments are fixed; the wedge does not
turn, by symmetry), loaded by half the wedge: V = W / 2, M = -+V L / 2 at its ends (statics:
M_b - M_a = V L; equal and opposite by symmetry of the end rotations), N = 0. Demands: the
extreme fibre 6 M / t^2 against the tensile strength (`bending` cases, f_t set to 1.02 and
0.98 of it, shear not checked), and the section's shear stress 1.5 V / t against the shear
strength (`shear` cases, f_t 100 times the bending demand). Expected: at 1.02 the wedge stays
(no element broken, the forces at rest within 2 % of the hand values, no motion in the dynamic
stage), at 0.98 both straddling elements break in the static stage and the wedge falls.
"""
import os
import tempfile

import h5py
import numpy as np

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(TOP, "examples", "support", "lined_wedge.yaml")
WEIGHT = 2650 * 9.81 * 2.75  # N per metre
THICKNESS = 0.05  # m, as in the scene
YOUNGS_MODULUS = 30e9  # Pa, as in the scene
TOLERANCE = 0.02
# name: segment length [m], governing check
CASES = {"bending_L0.1": (0.1, "bending"), "bending_L0.5": (0.5, "bending"),
         "shear_L0.1": (0.1, "shear")}
FACTORS = [1.02, 0.98]


def hand_values(segment):
    """V [N/m], M [N m/m] and the fibre and shear stresses [Pa] of a straddling element, and
    its second-order axial force [N/m]: the wedge's end sags delta = V L^3 / (12 EI) across the
    chord, which lengthens it by delta^2 / (2 L): N = EA delta^2 / (2 L^2) (membrane action,
    which the linear hand values leave out: 6.8 N/m at L = 0.1 m, 4.3 kN/m at 0.5 m)."""
    shear = WEIGHT / 2
    moment = shear * segment / 2
    ea, ei = YOUNGS_MODULUS * THICKNESS, YOUNGS_MODULUS * THICKNESS ** 3 / 12
    sag = shear * segment ** 3 / (12 * ei)
    return {"shear_n_per_m": shear, "moment_nm_per_m": moment,
            "axial_second_order_n_per_m": ea * sag ** 2 / (2 * segment ** 2),
            "fibre_stress_pa": 6 * moment / THICKNESS ** 2,
            "shear_stress_pa": 1.5 * shear / THICKNESS}


def case(run, name, factor):
    """One run (`run(scene, settings, out)` -> bench/speed_accuracy.run's result)."""
    segment, check = CASES[name]
    hand = hand_values(segment)
    start = -3 + segment / 2
    # Rigid blocks, as the hand calculation takes them (at 10 GPa the wedge's own strain as it
    # hangs squeezes the elements: N = -3.5 kN/m, examples/support/README.md).
    settings = {"linings.0.points": f"[[{start:.6g}, 0], [{-start:.6g}, 0]]",
                "linings.0.segment_length": f"{segment:.6g}",
                "materials.rock.youngs_modulus": "1e12", "materials.key.youngs_modulus": "1e12"}
    if check == "bending":
        demand = hand["fibre_stress_pa"]
        settings["linings.0.tensile_strength"] = f"{factor * demand:.8g}"
    else:
        demand = hand["shear_stress_pa"]
        settings["linings.0.tensile_strength"] = f"{100 * hand['fibre_stress_pa']:.8g}"
        settings["linings.0.shear_strength"] = f"{factor * demand:.8g}"
    row = {"case": name, "segment_m": segment, "check": check, "capacity_over_demand": factor,
           "demand_pa": demand, **hand, "expected": "stays" if factor > 1 else "falls"}
    with tempfile.TemporaryDirectory() as out:
        result = run(SCENE, settings, os.path.join(out, "r"))
        row["exit"] = result["exit"]
        if result["exit"] != 0:
            return {**row, "message": result["stderr"][-300:]}
        with h5py.File(os.path.join(out, "r", "histories.h5"), "r") as f:
            uy = f["monitors/key/displacement"][:, 1]
    lining = result["summary"]["linings"][0]
    elements = lining["coupling_elements"]
    row.update({"coupling_elements": len(elements),
                "broken_elements": lining["broken_elements"],
                "first_break_time_s": lining["first_break_time_s"],
                "max_utilisation": lining["max_utilisation"],
                "dynamic_stage_uy_m": float(uy[-1]),
                "dynamic_stage_max_abs_uy_m": float(np.abs(uy).max())})
    if row["broken_elements"] == 0:
        row["shear_n_per_m_computed"] = [abs(e["shear_force_n_per_m"]) for e in elements]
        row["moment_nm_per_m_computed"] = [
            max(abs(e["moment_a_nm_per_m"]), abs(e["moment_b_nm_per_m"])) for e in elements]
        row["axial_n_per_m_computed"] = [e["axial_force_n_per_m"] for e in elements]
        row["utilisation_computed"] = [e["utilisation"] for e in elements]
        row["shear_error"] = max(abs(v / hand["shear_n_per_m"] - 1)
                                 for v in row["shear_n_per_m_computed"])
        row["moment_error"] = max(abs(m / hand["moment_nm_per_m"] - 1)
                                  for m in row["moment_nm_per_m_computed"])
        row["axial_error_over_shear"] = max(
            abs(n - hand["axial_second_order_n_per_m"]) for n in row["axial_n_per_m_computed"]) / \
            hand["shear_n_per_m"]
        row["utilisation_error"] = max(abs(u * factor - 1) for u in row["utilisation_computed"])
    row["outcome"] = outcome(row)
    return row


def outcome(row):
    """stays: nothing broken and the wedge within 0.1 mm of its equilibrium in the dynamic
    stage; falls: both straddling elements broken and the wedge more than 1 m down (free fall
    g t^2 / 2 = 1.23 m in 0.5 s); else `other`."""
    if row["broken_elements"] == 0 and row["dynamic_stage_max_abs_uy_m"] < 1e-4:
        return "stays"
    if row["broken_elements"] == 2 and row["dynamic_stage_uy_m"] < -1.0:
        return "falls"
    return "other"


def passed(row):
    if row.get("outcome") != row["expected"] or row["coupling_elements"] != 2:
        return False
    if row["expected"] == "stays":
        return max(row["shear_error"], row["moment_error"], row["utilisation_error"],
                   row["axial_error_over_shear"]) <= TOLERANCE
    return True


def cases():
    return [(n, f) for n in CASES for f in FACTORS]


def markdown(rows):
    """The section of docs/verification/support.md."""
    lines = ["", "## Lining: the roof wedge on a shotcrete lining", "",
             f"W = {WEIGHT:.1f} N per metre, t = {THICKNESS} m, the lining along the roof with "
             "one element of length L (the segment) straddling each joint of the wedge "
             "(`tools/support_lining.py`). Hand values of each straddling element: V = W / 2, "
             "M = V L / 2 at both ends, N = 0 to first order (to second order the chord's stretch "
             "under the sag delta = V L^3 / 12 EI: N2 = EA delta^2 / 2 L^2); the demand is "
             "6 M / t^2 against f_t (bending) or 1.5 V / t against f_v (shear). Blocks at "
             "E = 1e12 Pa (rigid, as the hand calculation takes them). Acceptance: at 1.02 of "
             "the demand the wedge stays and |V|, max |M| and the utilisation x 1.02 are within "
             "2 % of the hand values and |N - N2| within 2 % of V; at 0.98 both elements break "
             "and the wedge falls.", "",
             "| case | L [m] | capacity / demand | demand [MPa] | expected | outcome | "
             "V / hand | M / hand | N [N/m] (N2) | utilisation | dynamic stage uy [m] | pass |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if "outcome" not in r:
            lines.append(f"| {r['case']} | {r['segment_m']} | {r['capacity_over_demand']} | "
                         f"{r['demand_pa'] / 1e6:.4g} | {r['expected']} | exit {r['exit']}: "
                         f"{r.get('message', '')} | | | | | | no |")
            continue
        if "shear_error" in r:
            hand = ", ".join(f"{v / r['shear_n_per_m']:.5f}" for v in r["shear_n_per_m_computed"])
            moment = ", ".join(f"{m / r['moment_nm_per_m']:.5f}"
                               for m in r["moment_nm_per_m_computed"])
            axial = ", ".join(f"{n:.4g}" for n in r["axial_n_per_m_computed"])
            forces = f"{hand} | {moment} | {axial} ({r['axial_second_order_n_per_m']:.3g})"
        else:
            forces = "- | - | -"
        lines.append(f"| {r['case']} | {r['segment_m']} | {r['capacity_over_demand']} | "
                     f"{r['demand_pa'] / 1e6:.4g} | {r['expected']} | {r['outcome']} | {forces} | "
                     f"{r['max_utilisation']:.5f} | {r['dynamic_stage_uy_m']:.3g} | "
                     f"{'yes' if passed(r) else 'no'} |")
    return lines


def describe(r):
    """One line of the tool's progress output."""
    text = f"lining {r['case']:12s} capacity {r['capacity_over_demand']}: " + \
        str(r.get("outcome", r.get("message")))
    if "shear_error" in r:
        text += (f", V error {r['shear_error']:.2e}, M error {r['moment_error']:.2e}, "
                 f"(N - N2) / V {r['axial_error_over_shear']:.1e}")
    return text + ("" if passed(r) else "  FAIL")
