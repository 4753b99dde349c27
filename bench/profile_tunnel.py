#!/usr/bin/python3
"""Where the time of the default tunnel scene goes, per phase, before and after the fix of its
largest avoidable cost, in the same run: writes docs/performance/profile_tunnel.{json,md,png}.

The scene (examples/tunnel/stable_sv.yaml, hybrid truncation) is run one at a time (nothing
else of this script runs beside it), with `output.vtu_compression` at

  before  best_compression  deal.II DataOut's default zlib level, what ddafem wrote until issue 8
  after   best_speed        the default now

and every phase is read from summary.json (docs/outputs.md): the DDA's broad and narrow phase,
assembly, solve (its factorizations and back-substitutions) and update; the ties' terms added to
the blocks' matrix; the far field's set-up (mesh, matrices, factorization) and
condensation G; its per-step right-hand side, solves and update; the tie algebra; the output
(histories, block files, far-field VTU files). The rest of the wall time (scene reading, rock-mass
generation, writing the summary) is "other".

usage: /usr/bin/python3 bench/profile_tunnel.py [--build build] [--repeat 2] [--out docs/performance]

Not a test: timings depend on the machine and its load.
"""
import argparse
import json
import os
import platform
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(TOP, "examples/tunnel/stable_sv.yaml")
VARIANTS = [("before", "best_compression"), ("after", "best_speed")]


def run(ddafem, compression):
    """summary.json of one run of the default tunnel with the given VTU compression, and the
    size of its far-field VTU files [MB]."""
    with tempfile.TemporaryDirectory() as out:
        cmd = [ddafem, "run", SCENE, "-o", out, "--quiet",
               "--set", f"output.vtu_compression={compression}"]
        proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if proc.returncode != 0:
            raise SystemExit(f"failed: {' '.join(cmd)}\n{proc.stderr}")
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        size = sum(os.path.getsize(os.path.join(out, name)) for name in os.listdir(out)
                   if name.startswith("far_field_") and name.endswith(".vtu"))
    summary["far_field_vtu_mb"] = size / 1e6
    return summary


def phases(summary):
    """Seconds per phase: the top-level timers (they add up to the wall time, with "other" the
    rest) and, indented, the parts of some of them."""
    t = summary["timings_s"]
    ff = summary["far_field"]["timings_s"]
    ties = summary["interface"]["timings_s"]
    # ff["setup"] holds the far field's mesh and matrices (built before the first step), its
    # factorization and the condensation G; the factorization and G are paid inside tied_body
    # at the first dynamic step, in interface.timings_s.condensation.
    p = {
        "DDA broad phase": t["broad_phase"],
        "DDA narrow phase": t["narrow_phase"],
        "DDA assembly": t["assemble"],
        "DDA solve with the open-close iteration": t["solve"],
        "  of which tie terms added to the blocks' matrix": t["tie_terms"],
        "far field and ties (tied body)": t["tied_body"],
        "  of which factorization and condensation G (once per dt)": ties["condensation"],
        "  of which far-field rhs, 2 solves and update per step":
            ff["assemble"] + ff["solve"] + ff["update"],
        "DDA update": t["update"],
        "output": t["output"],
        "  of which far-field VTU": summary["timings_detail_s"]["output_far_field_vtu"],
    }
    top = sum(v for k, v in p.items() if not k.startswith(" "))
    p["other (reading, rock mass, far-field mesh and matrices, summary)"] = \
        summary["wall_time_s"] - top
    return p


def best_of(ddafem, compression, repeat):
    """The run with the smallest wall time of `repeat` runs."""
    return min((run(ddafem, compression) for _ in range(repeat)), key=lambda s: s["wall_time_s"])


def bar_segments(phases_s):
    """The top-level phases for the chart, with output split into the far-field VTU and the
    rest."""
    segments = {}
    for name, seconds in phases_s.items():
        if name == "output":
            far = phases_s["  of which far-field VTU"]
            segments["output: far-field VTU"] = far
            segments["output: histories and block files"] = seconds - far
        elif not name.startswith(" "):
            segments[name] = seconds
    return segments


def figure(records, path):
    fig, ax = plt.subplots(figsize=(9, 4.5))
    colors = plt.cm.tab20.colors
    for row, r in enumerate(records):
        left = 0.0
        for k, (name, width) in enumerate(bar_segments(r["phases_s"]).items()):
            ax.barh(row, width, left=left, color=colors[k % len(colors)],
                    label=name if row == 0 else None)
            left += width
    ax.set_yticks(range(len(records)))
    ax.set_yticklabels([f"{r['variant']}\n({r['vtu_compression']})" for r in records])
    ax.set_xlabel("wall time [s]")
    ax.set_title("default tunnel scene (hybrid): where the time goes")
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.0, 0.5))
    ax.grid(alpha=0.3, axis="x")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    fig.savefig(path.replace(".png", ".svg"))
    plt.close(fig)


def markdown_section(records, heading="##"):
    """The profile as markdown (also included in docs/performance.md)."""
    before, after = records
    steps = after["steps"]
    lines = [
        f"{heading} Profile of the default tunnel scene",
        "",
        f"`{os.path.relpath(SCENE, TOP)}` (hybrid: {after['model']['blocks']} blocks, "
        f"{after['model']['far_field_dofs']} far-field DOFs, {after['model']['ties']} ties), "
        f"{steps} steps ({after['stages'][0]['steps']} static, "
        f"{after['stages'][1]['steps']} dynamic), {after['outputs']['snapshots']} snapshots; "
        "best of the repeats, run one at a time. Generated by "
        "`/usr/bin/python3 bench/profile_tunnel.py`.",
        "",
        "| phase | before [s] | after [s] | after [ms/step] | after [% of wall] |",
        "|---|---:|---:|---:|---:|",
    ]
    for name in after["phases_s"]:
        b, a = before["phases_s"][name], after["phases_s"][name]
        label = name if not name.startswith(" ") else "&nbsp;&nbsp;" + name.strip()
        lines.append(f"| {label} | {b:.3f} | {a:.3f} | {1e3 * a / steps:.2f} | "
                     f"{100 * a / after['wall_time_s']:.1f} |")
    lines.append(f"| **wall time** | **{before['wall_time_s']:.2f}** | "
                 f"**{after['wall_time_s']:.2f}** | {1e3 * after['wall_time_s'] / steps:.2f} | 100 |")
    lines += [
        "",
        f"Counts (after): {after['contacts']['open_close_iterations']} open-close iterations "
        f"({after['contacts']['open_close_iterations'] / steps:.2f} per step), "
        f"{after['solver']['factorizations']} factorizations and {after['solver']['solves']} "
        f"solves of the blocks' matrix ({after['solver']['name']}), far-field VTU files "
        f"{before['far_field_vtu_mb']:.1f} MB before, {after['far_field_vtu_mb']:.1f} MB after.",
        "",
        "**The fix.** The far field's VTU files were written at deal.II's default zlib level, "
        "`best_compression`: "
        f"{before['phases_s']['  of which far-field VTU']:.2f} s of a "
        f"{before['wall_time_s']:.2f} s run, the largest single cost and an avoidable one. "
        "`output.vtu_compression: best_speed` (now the default) writes them in "
        f"{after['phases_s']['  of which far-field VTU']:.2f} s; the run takes "
        f"{after['wall_time_s']:.2f} s ({before['wall_time_s'] / after['wall_time_s']:.2f}x "
        "faster), and the results are the same (keyblock peak "
        f"{1e3 * before['keyblocks']['keyblock_peak_m']:.4f} mm before, "
        f"{1e3 * after['keyblocks']['keyblock_peak_m']:.4f} mm after).",
        "",
        "![profile](performance/profile_tunnel.png)",
        "",
    ]
    return "\n".join(lines)


def profile(ddafem, out_dir, repeat):
    """Runs the profile; writes profile_tunnel.{json,png} in out_dir and returns the records."""
    records = []
    for variant, compression in VARIANTS:
        s = best_of(ddafem, compression, repeat)
        records.append({"variant": variant, "vtu_compression": compression,
                        "wall_time_s": s["wall_time_s"], "steps": s["steps"],
                        "phases_s": phases(s), "model": s["model"], "stages": s["stages"],
                        "outputs": s["outputs"], "contacts": s["contacts"],
                        "solver": s["solver"], "keyblocks": s["keyblocks"],
                        "far_field_vtu_mb": s["far_field_vtu_mb"]})
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "profile_tunnel.json"), "w") as f:
        json.dump({"machine": platform.platform(), "records": records}, f, indent=1)
    figure(records, os.path.join(out_dir, "profile_tunnel.png"))
    return records


def write_markdown(records, out_dir):
    """OUT_DIR/profile_tunnel.md: the section as a page of its own."""
    with open(os.path.join(out_dir, "profile_tunnel.md"), "w") as f:
        f.write(markdown_section(records, "#").replace("](performance/", "]("))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "performance"))
    args = parser.parse_args()
    records = profile(os.path.join(args.build, "ddafem"), args.out, args.repeat)
    write_markdown(records, args.out)
    print(markdown_section(records))


if __name__ == "__main__":
    main()
