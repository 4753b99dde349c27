#!/usr/bin/python3
"""Where a run's steps went: its accepted steps by dt level and by phase, and why dt was small.

    /usr/bin/python3 tools/step_anatomy.py RUN_DIR [-o FILE.md] [--json FILE.json]

A run with adaptive time control (`time.control: adaptive`) takes steps of dt_max / 2^k on a
ladder when blocks are tied to a far field. Its wall time is its number of step attempts times
the cost of one, and the first factor is often the larger lever: this tool reads the run's
`histories.h5` (a row per accepted step: `time`, `steps/dt`, `steps/cuts`) and `summary.json`
(the stages, the blocks removed as debris and when) and tells, per phase (each dynamic stage;
the settle stage split where a fallen block was removed):

- the accepted steps at each level k (dt = dt_max / 2^k) and the time they covered;
- the steps that followed a cut (a failed attempt: open-close iteration not converged,
  penetration or step displacement too large);
- the steps shortened without a cut (dt below the previous step's, then back up: a slip
  reversal ahead, localised; or the end of a stage).

Writes markdown to FILE.md (stdout without -o) and the numbers to FILE.json. Exit 0, or 2 on
bad input (no such run directory, a history without the step channels).
"""
import argparse
import json
import math
import os
import sys

import numpy as np


def fail(message):
    sys.stderr.write(f"step_anatomy: {message}\n")
    raise SystemExit(2)


def read_run(run_dir):
    """(time, dt, cuts, summary) of a run directory."""
    summary_path = os.path.join(run_dir, "summary.json")
    history_path = os.path.join(run_dir, "histories.h5")
    for path in (summary_path, history_path):
        if not os.path.isfile(path):
            fail(f"{path}: no such file, expected a run directory written by `ddafem run`")
    with open(summary_path) as f:
        summary = json.load(f)
    import h5py

    try:
        with h5py.File(history_path, "r") as h:
            for key in ("time", "steps/dt", "steps/cuts"):
                if key not in h:
                    fail(f"{history_path}: no dataset `{key}`, expected a dynamic run's step "
                         "history")
            time, dt, cuts = (np.asarray(h[k][:], dtype=float)
                              for k in ("time", "steps/dt", "steps/cuts"))
    except OSError as e:  # not HDF5, or still open for writing by a run
        fail(f"{history_path}: cannot be read ({e}), expected a finished run's histories.h5")
    taken = dt > 0.0  # the row of the initial state took no step
    return time[taken], dt[taken], cuts[taken], summary


def phases(summary, t_end):
    """[(name, start, end)] of the dynamic stages [s], the settle stage split at removals."""
    out, start = [], 0.0
    for stage in summary.get("stages", []):
        if stage.get("mode") == "static":
            continue
        end = stage.get("time_reached_s", stage.get("end_time_s", t_end))
        cuts = sorted(r["time_s"] for r in stage.get("removed", []) if start < r["time_s"] < end)
        bounds = [start] + cuts + [end]
        for i in range(len(bounds) - 1):
            name = stage["name"]
            if len(bounds) > 2:
                name += f" (to a removal at {bounds[i + 1]:.3f} s)" if i < len(cuts) else " (after)"
            out.append((name, bounds[i], bounds[i + 1]))
        start = end
    return out or [("run", 0.0, t_end)]


def anatomy(time, dt, cuts, dt_max, spans):
    """Per phase: rows by level, time by level, steps after cuts, shortened steps."""
    level = np.rint(np.log2(dt_max / dt)).astype(int)
    previous = np.concatenate(([level[0]], level[:-1]))
    following = np.concatenate((level[1:], [level[-1]]))
    shortened = (level > previous) & (cuts == 0) & (following < level)
    result = []
    for name, a, b in spans:
        sel = (time > a + 1e-12) & (time <= b + 1e-12)
        levels = {}
        for k in np.unique(level[sel]):
            at = sel & (level == k)
            levels[int(k)] = {"steps": int(at.sum()), "time_s": float(dt[at].sum())}
        cut = sel & (cuts > 0)
        result.append({"phase": name, "start_s": a, "end_s": b, "steps": int(sel.sum()),
                       "levels": levels, "steps_after_cuts": int(cut.sum()),
                       "cuts": int(cuts[sel].sum()),
                       "shortened_without_cut": int((sel & shortened).sum()),
                       "steps_at_dt_max": math.ceil((b - a) / dt_max - 1e-9)})
    return result


def markdown(result, dt_max, summary):
    top = max((k for r in result for k in r["levels"]), default=0)
    head = "| phase | s | steps | " + " | ".join(f"k={k}" for k in range(top + 1))
    scene = os.path.basename(str(summary.get("scene", "?")))
    lines = [f"Run `{summary.get('name', '?')}`, scene `{scene}`: accepted steps by level k "
             f"(dt = {dt_max:g} s / 2^k) and phase, from `histories.h5`.",
             "", head + " | after cuts | shortened, no cut | at dt_max |",
             "|---|---:|---:|" + "---:|" * (top + 4)]
    for r in result:
        cells = [str(r["levels"].get(k, {}).get("steps", "")) for k in range(top + 1)]
        lines.append(f"| {r['phase']} | {r['start_s']:.3f}-{r['end_s']:.3f} | {r['steps']} | "
                     + " | ".join(cells)
                     + f" | {r['steps_after_cuts']} | {r['shortened_without_cut']} | "
                     f"{r['steps_at_dt_max']} |")
    ts = summary.get("time_step", {})
    said = [f"{label} {ts[key]}" for key, label in
            (("attempts", "attempts"), ("cuts", "cuts"), ("cuts_by_cause", "by cause"),
             ("slip_reversals", "slip reversals localised"), ("smallest_dt_s", "smallest dt [s]"))
            if key in ts]
    if "wall_time_s" in summary:
        said.append(f"wall time {summary['wall_time_s']:.1f} s")
    if said:
        lines += ["", "From summary.json: " + ", ".join(said) + "."]
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run_dir")
    parser.add_argument("-o", "--output", help="markdown file (default: stdout)")
    parser.add_argument("--json", help="the numbers as JSON")
    args = parser.parse_args(argv)
    if not os.path.isdir(args.run_dir):
        fail(f"{args.run_dir}: no such directory, expected a run directory written by `ddafem run`")
    time, dt, cuts, summary = read_run(args.run_dir)
    if len(time) == 0:
        fail(f"{args.run_dir}/histories.h5: no rows, expected a run that took steps")
    dt_max = summary.get("time_step", {}).get("dt_max_s") or float(dt.max())
    result = anatomy(time, dt, cuts, dt_max, phases(summary, float(time[-1])))
    text = markdown(result, dt_max, summary)
    if args.output:
        with open(args.output, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"dt_max_s": dt_max, "phases": result}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
