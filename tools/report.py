#!/usr/bin/python3
"""Write RUN_DIR/report.md: the key numbers of a ddafem run and pictures of it, for people.

Sample command lines:

    /usr/bin/python3 tools/report.py results/circular_sv
    /usr/bin/python3 tools/report.py results/circular_sv --top 5

Reads RUN_DIR/summary.json, RUN_DIR/histories.h5 and the last snapshot of RUN_DIR/blocks.pvd
and writes, next to them:
  report.md                     scene, model size, stages (static equilibrium ratio), wall time,
                                warnings, the keyblock table sorted by peak displacement,
                                detached and fallen keyblocks, links to the outputs;
  report_displacement.png       monitor displacements against time (tools/plot_histories.py);
  report_velocity.png           monitor velocities against time;
  report_energy.png             the energy balance (blocks, and far field in coupled runs);
  report_keyblocks.png          |u| of the keyblocks against time (the largest peaks);
  report_bolts.png              the bolts' axial forces against time (runs with bolts);
  report_map.png                the blocks at the end, coloured by |u| over the dynamic stage
                                (from its start; the whole run when there is no dynamic stage),
                                keyblocks outlined and numbered; the openings are the holes.
Pictures that have nothing to show (no monitors, no keyblocks) are left out. See
docs/outputs.md for what each number means.
"""

import argparse
import json
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
from matplotlib import patheffects  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_histories  # noqa: E402  (tools/ on the path first)
from plot_histories import h5py  # noqa: E402  (its import explains a missing h5py)


def fail(message):
    sys.exit("report.py: " + message)


# ---- reading -------------------------------------------------------------------------------

def open_histories(path):
    """histories.h5 for reading; without HDF5's lock if a run still holds it."""
    return plot_histories.open_histories(path, fail)[0]


def pvd_entries(path):
    """(time, file, part) of every DataSet of a PVD collection, in file order."""
    root = ET.parse(path).getroot()
    return [(float(d.get("timestep")), d.get("file"), int(d.get("part", "0")))
            for d in root.findall("./Collection/DataSet")]


def data_array(piece, name, section):
    """An ASCII DataArray of a VTU piece as a float array (one row per tuple)."""
    for array in piece.findall("./%s/DataArray" % section):
        if array.get("Name") == name:
            values = np.array(array.text.split(), dtype=float)
            return values.reshape(-1, int(array.get("NumberOfComponents", "1")))
    return None


def read_blocks_vtu(path):
    """Block polygons (current vertices) and cell data of one blocks VTU (dda/vtu_writer.cc)."""
    piece = ET.parse(path).getroot().find("./UnstructuredGrid/Piece")
    for array in piece.findall("./Points/DataArray"):
        points = np.array(array.text.split(), dtype=float).reshape(-1, 3)[:, :2]
    connectivity = data_array(piece, "connectivity", "Cells").astype(int).ravel()
    offsets = data_array(piece, "offsets", "Cells").astype(int).ravel()
    starts = np.concatenate(([0], offsets[:-1]))
    polygons = [points[connectivity[s:e]] for s, e in zip(starts, offsets)]
    ids = data_array(piece, "block_id", "CellData")
    ids = ids.astype(int).ravel() if ids is not None else np.arange(len(polygons))
    return polygons, ids, data_array(piece, "displacement", "CellData")[:, :2]


# ---- pictures ------------------------------------------------------------------------------

def plot_monitor_histories(h5, time_ms, histories, run_dir):
    """Monitor displacement and velocity, and the energy, through tools/plot_histories.py."""
    written = []
    for quantity in ("displacement", "velocity"):
        path = os.path.join(run_dir, "report_%s.png" % quantity)
        args = argparse.Namespace(histories=histories, quantity=quantity, component=None,
                                  monitors=None)
        if plot_histories.plot_monitors(h5, time_ms, args, path):
            written.append(("Monitor %s" % quantity, path))
    path = os.path.join(run_dir, "report_energy.png")
    if plot_histories.plot_energy(h5, time_ms, argparse.Namespace(histories=histories), path):
        written.append(("Energy", path))
    return written


def keyblock_histories(h5, channel="displacement"):
    """{block id: (n, 2) array} of a keyblock channel in histories.h5: displacement or
    relative_displacement [m], or joints (largest |slip|, largest opening) [m]."""
    group = h5.get("keyblocks")
    if group is None:
        return {}
    return {int(name.split("_")[-1]): np.asarray(group[name][channel][...], dtype=float)
            for name in group if channel in group[name]}


def plot_keyblocks(time_ms, h5, keyblocks, top, path):
    """The `top` keyblocks with the largest peaks against time: |u| relative to the rock around
    the opening (absolute where the histories have no relative channel), and the largest slip
    and opening of their joints."""
    ranked = sorted(keyblocks["blocks"], key=lambda b: -b.get("peak_relative_m",
                                                               b["peak_displacement_m"]))[:top]
    relative = keyblock_histories(h5, "relative_displacement")
    displacement = relative or keyblock_histories(h5)
    joints = keyblock_histories(h5, "joints")
    figure, axes = plt.subplots(2 if joints else 1, 1, figsize=(8.0, 7.5 if joints else 4.5),
                                sharex=True, squeeze=False)
    for block in ranked:
        label = "block %d%s" % (block["id"], " (fell)" if block["fell"] else
                                " (detached)" if block["detached"] else "")
        u = displacement.get(block["id"])
        if u is None:
            continue
        n = min(len(time_ms), len(u))
        line, = axes[0, 0].plot(time_ms[:n], 1e3 * np.linalg.norm(u[:n], axis=1), label=label)
        j = joints.get(block["id"])
        if j is not None:
            axes[1, 0].plot(time_ms[:n], 1e3 * j[:n, 0], color=line.get_color())
            axes[1, 0].plot(time_ms[:n], 1e3 * j[:n, 1], "--", color=line.get_color())
    axes[0, 0].set_ylabel("|u| of the centroid%s [mm]"
                          % (" relative to the rock" if relative else ""))
    axes[0, 0].legend(loc="best", fontsize="small", ncol=2)
    axes[0, 0].set_title("Keyblocks%s "
                         "(largest %d peaks)" % (" relative to the rock around the opening"
                                                 if relative else "", len(ranked)),
                         fontsize="medium")
    if joints:
        axes[1, 0].set_ylabel("their joints: slip (solid), opening (dashed) [mm]")
    for ax in axes[:, 0]:
        ax.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel("time [ms]")
    figure.tight_layout()
    figure.savefig(path, dpi=150)
    plt.close(figure)


def plot_bolt_forces(time_ms, h5, path):
    """Every bolt's axial force against time (histories bolts/<name>/axial_force [N]), in kN;
    False if the run has no bolts."""
    group = h5.get("bolts")
    if group is None or not len(group):
        return False
    figure, ax = plt.subplots(figsize=(8.0, 4.5))
    for name in sorted(group):
        if "axial_force" not in group[name]:
            continue
        force = np.asarray(group[name]["axial_force"][...], dtype=float).reshape(-1)
        n = min(len(time_ms), len(force))
        ax.plot(time_ms[:n], 1e-3 * force[:n], label=name)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("axial force N [kN] (tension positive)")
    ax.set_title("Bolts", fontsize="medium")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small", ncol=2)
    figure.tight_layout()
    figure.savefig(path, dpi=150)
    plt.close(figure)
    return True


def frame_to_scale(ax, box):
    """Axes to scale in metres, on box = (lower, upper) corners, or on the data (None)."""
    if box is not None:
        ax.set_xlim(box[0][0], box[1][0])
        ax.set_ylim(box[0][1], box[1][1])
    else:
        ax.autoscale_view()
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")


def plot_map(run_dir, summary, path):
    """The blocks of the last snapshot coloured by |u| since the first (the dynamic stage's
    start), keyblocks outlined and numbered. Returns a caption, or None without blocks.pvd."""
    pvd = os.path.join(run_dir, summary.get("outputs", {}).get("blocks", "blocks.pvd"))
    if not os.path.isfile(pvd):
        return None
    entries = pvd_entries(pvd)
    if not entries:
        return None
    polygons, ids, u_last = read_blocks_vtu(os.path.join(run_dir, entries[-1][1]))
    u = u_last
    since = "t = 0"
    if len(entries) > 1:
        _, first_ids, u_first = read_blocks_vtu(os.path.join(run_dir, entries[0][1]))
        if np.array_equal(first_ids, ids):
            u = u_last - u_first
            since = "t = %.4g s" % entries[0][0]
    magnitude = 1e3 * np.linalg.norm(u, axis=1)
    # Zoom on the openings (with a margin of one opening size) when there are keyblocks; the
    # colour range is that of the blocks in view.
    keyblocks = summary.get("keyblocks") or {}
    openings = keyblocks.get("openings", [])
    centres = np.array([p.mean(axis=0) for p in polygons])
    in_view = np.ones(len(polygons), dtype=bool)
    if openings:
        margin = max(o["size_m"] for o in openings)
        lower = np.min([o["lower_m"] for o in openings], axis=0) - margin
        upper = np.max([o["upper_m"] for o in openings], axis=0) + margin
        in_view = np.all((centres >= lower) & (centres <= upper), axis=1)
    figure, ax = plt.subplots(figsize=(8.0, 7.0))
    collection = PolyCollection(polygons, array=magnitude, cmap="viridis", edgecolors="0.35",
                                linewidths=0.3)
    collection.set_clim(0.0, max(magnitude[in_view].max(initial=0.0), 1e-12))
    ax.add_collection(collection)
    figure.colorbar(collection, ax=ax, label="|u| since %s [mm]" % since, shrink=0.8)
    key_ids = {b["id"]: b for b in keyblocks.get("blocks", [])}
    index = {block_id: k for k, block_id in enumerate(ids)}
    outlined = [polygons[index[i]] for i in key_ids if i in index]
    if outlined:
        ax.add_collection(PolyCollection(outlined, facecolors="none", edgecolors="red",
                                         linewidths=1.2))
        for block_id, block in key_ids.items():
            if block_id in index:
                centre = polygons[index[block_id]].mean(axis=0)
                ax.annotate(str(block_id) + (" fell" if block["fell"] else ""), centre,
                            ha="center", va="center", fontsize=6,
                            path_effects=[patheffects.withStroke(linewidth=2,
                                                                 foreground="white")])
    frame_to_scale(ax, (lower, upper) if openings else None)
    ax.set_title("Blocks at t = %.4g s (deformed, to scale), keyblocks in red" % entries[-1][0],
                 fontsize="medium")
    figure.tight_layout()
    figure.savefig(path, dpi=150)
    plt.close(figure)
    zoom = " around the openings" if openings else ""
    return "Blocks at the end%s, coloured by |u| since %s" % (zoom, since)


# ---- report.md -----------------------------------------------------------------------------

def mm(value):
    return "-" if value is None else "%.3g" % (1e3 * value)


def model_lines(summary):
    model = summary.get("model", {})
    lines = ["- blocks: %s, bonded joints left: %s, DOFs: %s"
             % (model.get("blocks", 0), model.get("bonded_joints", 0), model.get("dofs", 0))]
    if "far_field_dofs" in model:
        lines.append("- far field: %s cells, %s DOFs, elements up to %.3g m"
                     % (model["far_field_cells"], model["far_field_dofs"],
                        model.get("element_size_m", float("nan"))))
    if "ties" in model:
        lines.append("- interface: %s ties on %s edges of %s blocks"
                     % (model["ties"], model.get("tied_edges", "?"), model.get("tied_blocks", "?")))
    contacts = summary.get("contacts")
    if contacts:
        lines.append("- contacts at the end: %s open, %s sliding, %s locked; %s joints broke"
                     % (contacts["open"], contacts["slide"], contacts["lock"],
                        contacts["broken_joints"]))
    return lines


def support_lines(bolts):
    """The bolts of summary.json: law, extremes, final state, yield and rupture times."""
    if not bolts:
        return []
    lines = ["End-anchored bolts (docs/support.md): k = E_s A_s / L0, N tension positive.", "",
             "| bolt | head [m] | anchor [m] | L0 [m] | k [N/m] | pretension [N] | "
             "yield force [N] | max force [N] | max elongation [mm] | final state | "
             "yielded at [s] | ruptured at [s] |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]

    def when(t):
        return "-" if t is None else "%.4g" % t
    for b in bolts:
        lines.append("| %s | (%g, %g) | (%g, %g) | %.4g | %.4g | %.4g | %.4g | %.4g | %s | %s | %s | %s |"
                     % (b["name"], *b["head_m"], *b["anchor_m"], b["free_length_m"],
                        b["stiffness_n_per_m"], b["pretension_n"], b["yield_force_n"],
                        b["max_force_n"], mm(b["max_elongation_m"]), b["final_state"],
                        when(b["yield_time_s"]), when(b["rupture_time_s"])))
    return lines


def lining_lines(linings):
    """The linings of summary.json: section, largest utilisation and where, first break, and
    the final forces of the elements between two blocks (the others move with their block)."""
    if not linings:
        return []

    def when(t):
        return "-" if t is None else "%.4g" % t
    lines = ["Linings (docs/support.md, \"Lining\"): frame elements on the blocks' surface; "
             "utilisation = the largest of the extreme-fibre stress N/t +- 6M/t^2 over f_t or f_c "
             "(and 1.5 V/t over f_v if given); an element beyond 1 breaks for good.", "",
             "| lining | t [m] | E [GPa] | f_c [MPa] | f_t [MPa] | elements (between blocks) | "
             "installed at [s] | max utilisation | at [s] | element | broken | first break [s] |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for l in linings:
        installed = "-" if l["install_time_s"] is None else "%.4g" % l["install_time_s"]
        lines.append("| %s | %.4g | %.4g | %.4g | %.4g | %d (%d) | %s | %.4g | %s | %d | %d | %s |"
                     % (l["name"], l["thickness_m"], l["youngs_modulus_pa"] / 1e9,
                        l["compressive_strength_pa"] / 1e6, l["tensile_strength_pa"] / 1e6,
                        l["elements"], len(l["coupling_elements"]), installed,
                        l["max_utilisation"], when(l["max_utilisation_time_s"]),
                        l["max_utilisation_element"], l["broken_elements"],
                        when(l["first_break_time_s"])))
    worst = sorted(((e, l["name"]) for l in linings for e in l["coupling_elements"]),
                   key=lambda p: -p[0]["max_utilisation"])[:10]
    lines += ["", "Elements between two blocks at the end (the 10 most used), N tension "
              "positive, per metre:", "",
              "| lining | element | from [m] | to [m] | blocks | state | N [kN/m] | V [kN/m] | "
              "M_a [kN m/m] | M_b [kN m/m] | utilisation | governing | max utilisation | "
              "broke at [s] |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for e, name in worst:
        lines.append("| %s | %d | (%.4g, %.4g) | (%.4g, %.4g) | %d-%d | %s | %.4g | %.4g | %.4g | "
                     "%.4g | %.4g | %s | %.4g | %s |"
                     % (name, e["index"], *e["from_m"], *e["to_m"], *e["blocks"], e["state"],
                        e["axial_force_n_per_m"] / 1e3, e["shear_force_n_per_m"] / 1e3,
                        e["moment_a_nm_per_m"] / 1e3, e["moment_b_nm_per_m"] / 1e3,
                        e["utilisation"], e["governing"], e["max_utilisation"],
                        when(e["break_time_s"])))
    return lines


def grouted_lines(bolts):
    """The grouted bolts of summary.json: per crossing, its blocks, extremes, final forces and
    state, yield and rupture times."""
    if not bolts:
        return []
    lines = ["Grouted bolts (docs/support.md): at each crossing of a block boundary an axial "
             "spring k_a = E_s A_s / L_d (N tension positive) and a dowel k_s = K / (4 beta) "
             "(S across the bolt).", "",
             "| bolt | crossing | blocks | at [m] | k_a [N/m] | k_s [N/m] | yield force [N] | "
             "shear capacity [N] | max N [N] | max abs S [N] | final N [N] | final S [N] | "
             "max slip [mm] | final state | yielded at [s] | ruptured at [s] |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]

    def when(t):
        return "-" if t is None else "%.4g" % t
    for b in bolts:
        for k, c in enumerate(b["crossings"]):
            lines.append(
                "| %s | %d | %d to %d | (%.4g, %.4g) | %.4g | %.4g | %.4g | %.4g | %.4g | %.4g | "
                "%.4g | %.4g | %s | %s | %s | %s |"
                % (b["name"], k, *c["blocks"], *c["point_m"], b["axial_stiffness_n_per_m"],
                   b["shear_stiffness_n_per_m"], b["yield_force_n"], b["shear_capacity_n"],
                   c["max_axial_force_n"], c["max_shear_force_n"], c["final_axial_force_n"],
                   c["final_shear_force_n"], mm(c["max_slip_m"]), c["final_state"],
                   when(c["yield_time_s"]), when(c["rupture_time_s"])))
    return lines


def stage_lines(summary):
    stages = summary.get("stages", [])
    if not stages:
        return []
    lines = ["| stage | mode | steps | result |", "|---|---|---|---|"]
    for s in stages:
        if s.get("mode") == "static":
            result = "%s: out-of-balance force ratio %.3g (tolerance %.3g)" % (
                "equilibrium" if s.get("converged") else "**no equilibrium**",
                s.get("unbalanced_force_ratio", float("nan")), s.get("tolerance", float("nan")))
            released = s.get("released", [])
            if released:
                result += "; released (%s): %s" % (s.get("release", "fall"), ", ".join(
                    "block %d (%.3g kg)" % (r["block"], r["mass_kg"]) for r in released))
        elif s.get("mode") == "settle":
            result = settle_result(s)
        else:
            end = s.get("end_time_s", float("nan"))
            reached = s.get("time_reached_s", end)
            result = ("to t = %.4g s" % end if reached >= end - 1e-9 * max(abs(end), 1.0) else
                      "**stopped at t = %.4g s** of %.4g s" % (reached, end))
        lines.append("| %s | %s | %s | %s |" % (s.get("name"), s.get("mode"), s.get("steps"),
                                               result))
    return lines


def settle_result(s):
    """A settle stage's outcome: at rest, or still moving at its bound, and what fell."""
    reached = s.get("time_reached_s", float("nan"))
    if s.get("settled"):
        result = ("every block at rest (slower than %.3g m/s for %.3g s) or fallen at t = %.4g s"
                  % (s["rest_speed_m_s"], s["rest_duration_s"], reached))
    elif reached < s.get("end_time_s", reached) - 1e-9:
        result = "**stopped at t = %.4g s**" % reached
    else:
        result = ("**still moving at t = %.4g s** (its bound, %.3g s): %d blocks, the fastest "
                  "at %.3g m/s" % (reached, s["max_duration_s"], len(s.get("moving", [])),
                                   s.get("moving_speed_m_s", float("nan"))))
    fallen = s.get("fallen", [])
    if fallen:
        result += "; fallen: " + ", ".join("block %d (%.3g kg)" % (f["block"], f["mass_kg"])
                                           for f in fallen)
    removed = s.get("removed", [])
    if removed:
        result += "; removed as debris once out of place: " + ", ".join(
            "block %d at t = %.4g s" % (r["block"], r["time_s"]) for r in removed)
    return result


def wave_not_reached(summary):
    """Why keyblock verdicts mean nothing yet: the run stopped before the wave reached the
    near field (summary.tunnel.arrival_time_s), else None."""
    arrival = summary.get("tunnel", {}).get("arrival_time_s")
    reached = summary.get("time_reached_s", 0.0)
    if summary.get("status") == "completed" or arrival is None or reached >= arrival:
        return None
    return ("the run stopped at t = %.4g s, before the wave reached the near field at %.4g s: "
            "no verdict" % (reached, arrival))


def keyblock_lines(keyblocks, not_reached=None):
    if not keyblocks:
        return ["No keyblocks: the blocks enclose no opening."]
    lines = []
    for k, o in enumerate(keyblocks["openings"]):
        lines.append("- opening %d: %.3g m across (%.3g m^2), from (%.3g, %.3g) to (%.3g, %.3g) m;"
                     " a keyblock fell if it ended more than %s mm lower (or detached and still "
                     "falling faster than %.3g m/s, or detached and more than %s mm from its "
                     "place relative to the rock: thrown out); one that did not fall loosened if "
                     "it ended more than %s mm from its place relative to the rock around the "
                     "opening"
                     % (k, o["size_m"], o["area_m2"], o["lower_m"][0], o["lower_m"][1],
                        o["upper_m"][0], o["upper_m"][1], mm(o["fall_threshold_m"]),
                        o["fall_speed_m_s"], mm(o["fall_threshold_m"]),
                        mm(o.get("loosen_threshold_m"))))
        if "fallen_blocks" in o and not not_reached:
            lines.append("  - fallen into it: %d blocks, %.3g m^3 per metre of tunnel%s"
                         % (len(o["fallen_blocks"]), o["fallen_area_m2"],
                            " (blocks %s)" % ", ".join(str(b) for b in o["fallen_blocks"])
                            if o["fallen_blocks"] else ""))
    if not_reached:
        lines.append("- %d keyblocks: **not reached**, %s" % (keyblocks["count"], not_reached))
    else:
        lines.append("- %d keyblocks; largest peak displacement %s mm (block %d), %s mm "
                     "relative to the rock around the opening (block %s); %d detached, %d fell, "
                     "%s loosened"
                     % (keyblocks["count"], mm(keyblocks["keyblock_peak_m"]),
                        keyblocks["keyblock_peak_id"],
                        mm(keyblocks.get("keyblock_peak_relative_m")),
                        keyblocks.get("keyblock_peak_relative_id", "-"), keyblocks["detached"],
                        keyblocks["fell"], keyblocks.get("loosened", "-")))
    verdict = (lambda flag: "not reached") if not_reached else \
        (lambda flag: "**yes**" if flag else "no")
    lines += ["",
              "| block | name | peak \\|u\\| [mm] | at [s] | peak relative [mm] | "
              "residual ux, uy [mm] | residual relative ux, uy [mm] | "
              "max slip [mm] | max opening [mm] | detached | fell | loosened | "
              "a_y horizontal, vertical [m/s^2] |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for b in sorted(keyblocks["blocks"], key=lambda b: -b.get("peak_relative_m",
                                                               b["peak_displacement_m"])):
        ux, uy = b["residual_displacement_m"]
        rx, ry = b.get("residual_relative_displacement_m", [None, None])
        lines.append("| %d | %s | %s | %.4g | %s | %s, %s | %s, %s | %s | %s | %s | %s | %s | %s |"
                     % (b["id"], b.get("name", ""), mm(b["peak_displacement_m"]),
                        b["peak_time_s"], mm(b.get("peak_relative_m")), mm(ux), mm(uy), mm(rx),
                        mm(ry), mm(b["max_slip_m"]), mm(b["max_opening_m"]),
                        verdict(b["detached"]), verdict(b["fell"]),
                        verdict(b.get("loosened", False)), yield_text(b)))
    lines += ["", "a_y: Newmark's yield acceleration of the block at t = 0, rigid on the joints "
              "of its edges with their friction, for a horizontal (SV) and a vertical (P) ground "
              "acceleration; 0: gravity alone moves it; none: that shaking alone cannot move it "
              "without rotating it. No cohesion, tension or clamping by the in-situ stress: a "
              "lower bound of what holds it (`ddafem check` lists them)."]
    return lines


def yield_text(block):
    """'a_h, a_v' of summary.json keyblocks.blocks[i].yield_acceleration."""
    y = block.get("yield_acceleration")
    if not y:
        return "-"
    text = []
    for part in ("horizontal", "vertical"):
        value = y[part]["m_s2"]
        text.append("none" if value is None else "%.3g%s" % (
            value, " (slide)" if y[part]["mode"] == "slide" and value > 0 else ""))
    return ", ".join(text)


def simulated_of(summary):
    """What the time reached is out of: time.end_time, or a settle stage's bound after it."""
    settle = [s for s in summary.get("stages", []) if s.get("mode") == "settle"]
    if settle:
        return ("(the wave's window to %.4g s, then settling, at most to %.4g s)"
                % (summary.get("end_time_s", 0.0), settle[-1].get("end_time_s", float("nan"))))
    return "of %.4g s" % summary.get("end_time_s", 0.0)


def solver_line(solver):
    """The blocks' linear solver and what it did (summary.json's `solver`)."""
    if not solver:
        return "- linear solver: ?"
    line = "- linear solver: %s, %s factorizations" % (solver.get("name", "?"),
                                                     solver.get("factorizations", "?"))
    if solver.get("pcg_solves"):
        line += (", %d conjugate-gradient solves of %.1f iterations each, %d handed to the "
                 "direct solver" % (solver["pcg_solves"],
                                    solver["pcg_iterations"] / solver["pcg_solves"],
                                    solver.get("pcg_fallbacks", 0)))
    elif "solves" in solver:
        line += ", %s solves" % solver["solves"]
    elif "linear_iterations" in solver:
        line += ", %s iterations" % solver["linear_iterations"]
    return line


def record_lines(records):
    """The recorded ground motions (summary.json `records`, docs/ground_motions.md)."""
    lines = []
    for r in records or []:
        b = r["baseline"]
        lines += ["- `%s`: record `%s`, %s motion (the incident wave %.3g x it), %.4g to %.4g s "
                  "of it every %.4g s from t = %.4g s, scale %.4g"
                  % (r["where"], r["file"], r["motion"], r["incident_factor"], r["window_s"][0],
                     r["window_s"][1], r["dt_s"], r["start_s"], r["scale"]),
                  "  - PGA %.3g m/s^2 (%.3g g), PGV %.3g m/s, PGD %.3g m, Arias intensity "
                  "%.3g m/s, D5-95 %.3g s (%.3g to %.3g s), mean frequency %.3g Hz, f99 %.3g Hz"
                  % (r["pga_m_s2"], r["pga_g"], r["pgv_m_s"], r["pgd_m"],
                     r["arias_intensity_m_s"], r["t95_s"] - r["t5_s"], r["t5_s"], r["t95_s"],
                     r["mean_frequency_hz"], r["f99_hz"]),
                  "  - baseline correction: end velocity %.3g -> 0 m/s, end displacement %.3g "
                  "-> %.3g m" % (b["end_velocity_before_m_s"], b["end_displacement_before_m"],
                                 b["end_displacement_after_m"])]
    return lines


def incident_lines(far_field):
    """The wave at the far field's base (the input) and arriving at the near field's base
    (summary.json far_field.free_field_at_base: the free-field column's peak there)."""
    base = (far_field or {}).get("free_field_at_base")
    if not base:
        return []
    lines = ["- input at the far field's base: peak velocity of the upgoing wave %.3g m/s" %
             base["input_pgv_m_s"],
             "- arriving at the near field's base (y = %.4g m, %.4g m above the input; the "
             "free-field column, without the opening): PGV %.3g m/s" %
             (base["height_m"], base["travel_m"], base["pgv_m_s"])]
    if base.get("ratio") is not None:
        lines[-1] += (", %.1f %% of the input's: the rock's damping over the way (a plane wave "
                      "there travels %.3g ms)" % (100 * base["ratio"],
                                                  1e3 * base["travel_m"] / base["wave_speed_m_s"]))
    return lines


def write_report(run_dir, summary, figures, path):
    status = summary.get("status", "?")
    lines = ["# Run report: %s" % summary.get("name", os.path.basename(run_dir)), "",
             "- scene: `%s` (ddafem %s)" % (summary.get("scene", "?"), summary.get("version", "?")),
             "- status: **%s**%s" % (status, ": " + summary["failure"]
                                     if "failure" in summary else ""),
             "- simulated %.4g s %s in %s %s (dt up to %.3g s, smallest %.3g s), integrator %s"
             % (summary.get("time_reached_s", 0.0), simulated_of(summary),
                summary.get("steps", "?"),
                "half steps" if summary.get("integrator") == "bathe" else "steps",
                summary.get("dt_s", float("nan")),
                summary.get("time_step", {}).get("smallest_dt_s", float("nan")),
                summary.get("integrator", "?")),
             "- time steps: %s dt cuts (%s steps cut), %s contact penalties raised, %s "
             "contact flips at almost no force let go, %s steps shortened to end at a slip "
             "reversal, %s open-close iterations"
             % (summary.get("time_step", {}).get("cuts", "?"),
                summary.get("time_step", {}).get("steps_cut", "?"),
                summary.get("time_step", {}).get("penalty_raises", "?"),
                summary.get("time_step", {}).get("flips_ignored", "?"),
                summary.get("time_step", {}).get("slip_reversals", "?"),
                summary.get("contacts", {}).get("open_close_iterations", "?")),
             solver_line(summary.get("solver")),
             "- wall time: %.3g s, peak memory %.0f MB"
             % (summary.get("wall_time_s", 0.0), summary.get("peak_memory_mb", 0.0)), ""]
    lines += ["## Model", ""] + model_lines(summary) + [""]
    incident = incident_lines(summary.get("far_field"))
    if incident:
        lines += ["## Incident wave", ""] + incident + [""]
    if summary.get("records"):
        lines += ["## Ground motion", ""] + record_lines(summary["records"]) + [""]
    stages = stage_lines(summary)
    if stages:
        lines += ["## Stages", ""] + stages + [""]
    if summary.get("bolts") or summary.get("grouted_bolts") or summary.get("linings"):
        lines += ["## Support", ""]
        for part in (support_lines(summary.get("bolts")),
                     grouted_lines(summary.get("grouted_bolts")),
                     lining_lines(summary.get("linings"))):
            lines += part + [""] if part else []
    if summary.get("warnings"):
        lines += ["## Warnings", ""] + ["- " + w for w in summary["warnings"]] + [""]
    lines += ["## Keyblocks", "",
              "Blocks with a point of their boundary on an opening. Displacements of the "
              "centroid from the start of the dynamic stage, absolute and relative to the rock "
              "around the opening (the mean of the blocks 0.75 to 1.5 opening sizes from its "
              "centre, which the wave moves with the opening); slip and opening are the largest "
              "over the run among the block's joints and contacts.", ""]
    lines += keyblock_lines(summary.get("keyblocks"), wave_not_reached(summary)) + [""]
    if figures:
        lines += ["## Pictures", ""]
        for caption, figure in figures:
            lines += ["%s:" % caption, "", "![%s](%s)" % (caption, os.path.basename(figure)), ""]
    outputs = summary.get("outputs", {})
    lines += ["## Files", "",
              "- [summary.json](summary.json): every number above",
              "- [histories.h5](histories.h5): monitor, energy, contact and keyblock histories"]
    if "model" in outputs:
        lines.append("- [%s](%s): the whole model for ParaView (blocks, contacts%s); "
                     "`pvpython tools/paraview_open.py %s` opens it coloured"
                     % (outputs["model"], outputs["model"],
                        ", far field, ties" if "far_field" in outputs else "", run_dir))
    with open(path, "w") as f:
        f.write("\n".join(lines).rstrip() + "\n")


def main(argv):
    parser = argparse.ArgumentParser(description="Write RUN_DIR/report.md with plots of a "
                                     "ddafem run.")
    parser.add_argument("run_dir", help="the directory of `ddafem run -o RUN_DIR`")
    parser.add_argument("--top", type=int, default=10,
                        help="keyblocks drawn in the displacement plot (default 10)")
    args = parser.parse_args(argv)
    run_dir = args.run_dir
    summary_path = os.path.join(run_dir, "summary.json")
    if not os.path.isfile(summary_path):
        fail("no %s: expected the output directory of `ddafem run`" % summary_path)
    with open(summary_path) as f:
        summary = json.load(f)

    figures = []
    histories = os.path.join(run_dir, summary.get("outputs", {}).get("histories", "histories.h5"))
    if os.path.isfile(histories):
        with open_histories(histories) as h5:
            time_ms, _ = plot_histories.scaled(h5["time"], "s")
            time_ms = time_ms.reshape(-1)
            figures += plot_monitor_histories(h5, time_ms, histories, run_dir)
            keyblocks = summary.get("keyblocks")
            if keyblocks and keyblocks.get("blocks"):
                path = os.path.join(run_dir, "report_keyblocks.png")
                plot_keyblocks(time_ms, h5, keyblocks, args.top, path)
                figures.append(("Keyblock displacement", path))
            path = os.path.join(run_dir, "report_bolts.png")
            if plot_bolt_forces(time_ms, h5, path):
                figures.append(("Bolt forces", path))
    map_path = os.path.join(run_dir, "report_map.png")
    caption = plot_map(run_dir, summary, map_path)
    if caption:
        figures.append((caption, map_path))
    report = os.path.join(run_dir, "report.md")
    write_report(run_dir, summary, figures, report)
    print("wrote %s (%d pictures)" % (report, len(figures)))


if __name__ == "__main__":
    main(sys.argv[1:])
