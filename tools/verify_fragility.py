#!/usr/bin/python3
"""The default tunnel's answer as statistics (issue 53's acceptance); regenerates
docs/verification/fragility.md and docs/verification/fragility/ (each ensemble's and the
fragility curve's report, json and picture).

Runs, each resumed where an earlier call stopped (the runs stay in --work):
1. `friction`: an ensemble of examples/tunnel/circular_sv.yaml, 32 members, the joints' friction
   angle drawn from truncnormal(35, 2, 25, 45) (normal(35, 2) cut at 5 sd: the key's range must
   hold the support) and the incident amplitude x (1 + k 1e-12) (`--roundoff`);
2. `joint_sets`: 32 members differing by the seed of the joint sets' random perturbations
   (spacing +-10 % uniform on both sets, the traces of the non-persistent set shifted by up to
   1/4 of their period), reported by 10 deg sector of the perimeter;
3. `fragility`: `ddafem fragility --key tunnel.wave.velocity.amplitude`, the levels chosen (a
   bracketing sweep, then 6 levels across the estimated 10-90 % band, and levels added beyond
   them until that band of falls is covered) x 16 members, the members drawn as in 1;
4. `mpirun`: 1's first 4 members by `mpirun -np 2 ddafem ensemble` and by `-j 2`: the same
   member values, verdicts and histories.h5 bit for bit.

    /usr/bin/python3 tools/verify_fragility.py [--build build] [--jobs 2]
        [--work build/verification_fragility] [--out docs/verification]
        [--no-fragility | --mpirun-only | --page-only]
Not part of CI: about 160 tunnel runs, some 2 hours on 2 cores.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

import numpy as np

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(TOP, "tests", "tools"))
from check_crash_safety import datasets  # noqa: E402  (every dataset of an HDF5 file)

SCENE = os.path.join(TOP, "examples", "tunnel", "circular_sv.yaml")
FRICTION = ["--vary", "joint_materials.joint.friction_angle=truncnormal(35,2,25,45)",
            "--roundoff"]
JOINT_SETS = ["--set", "tunnel.joint_sets.0.perturbation.spacing=0.1",
              "--set", "tunnel.joint_sets.1.perturbation.spacing=0.1",
              "--set", "tunnel.joint_sets.1.perturbation.position=0.25", "--sector", "10"]
MPI_MEMBERS = 4


def run(name, command, log):
    """Run a ddafem command, its output to log; exit 1 (a member failed) is a result. Open MPI
    refuses root unless told (as the tests' MPIEXEC is: containers run as root)."""
    print("verify_fragility: %s: %s" % (name, " ".join(command[1:])), flush=True)
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}
    start = time.monotonic()
    with open(log, "w") as f:
        code = subprocess.run(command, stdout=f, stderr=subprocess.STDOUT, env=env).returncode
    if code not in (0, 1):
        sys.exit("verify_fragility: %s exited %d (see %s)" % (name, code, log))
    return time.monotonic() - start


def compare_mpirun(ddafem, work):
    """The friction ensemble's first members under mpirun -np 2 and with -j 2 (the same binary):
    the same values, verdicts and histories, bit for bit."""
    out = {way: os.path.join(work, "mpirun_" + way) for way in ("np2", "j2")}
    common = [ddafem, "ensemble", SCENE, "-n", str(MPI_MEMBERS)] + FRICTION
    walls = {}
    for way, command in (("np2", ["mpirun", "-np", "2", "--oversubscribe", "--bind-to", "none"] +
                          common + ["-o", out["np2"]]),
                         ("j2", common + ["-j", "2", "-o", out["j2"]])):
        wall_file = out[way] + ".wall_s"
        if os.path.isfile(wall_file):  # an earlier call finished this way: resumed
            with open(wall_file) as f:
                walls[way] = float(f.read())
            continue
        shutil.rmtree(out[way], ignore_errors=True)
        walls[way] = run("mpirun " + way, command, out[way] + ".log")
        with open(wall_file, "w") as f:
            f.write(repr(walls[way]))
    rows = []
    for k in range(MPI_MEMBERS):
        a, b = (os.path.join(out[way], "member_%03d" % k) for way in ("np2", "j2"))
        same_values = (json.load(open(os.path.join(a, "member.json")))["values"] ==
                       json.load(open(os.path.join(b, "member.json")))["values"])
        sa, sb = (json.load(open(os.path.join(d, "summary.json"))) for d in (a, b))
        ha, hb = datasets(os.path.join(a, "histories.h5")), datasets(os.path.join(b, "histories.h5"))
        same = sorted(ha) == sorted(hb) and all(np.array_equal(ha[n], hb[n]) for n in ha)
        rows.append({"member": k, "values_equal": same_values,
                     "keyblocks_equal": sa.get("keyblocks") == sb.get("keyblocks"),
                     "histories_bit_for_bit": same, "datasets": len(ha)})
    return {"wall_s": walls["np2"] + walls["j2"], "wall_np2_s": walls["np2"],
            "wall_j2_s": walls["j2"], "members": rows}


def member_seconds(directory):
    """The members' wall times summed over every ensemble.json under directory (a resumed
    ensemble's call times only what it ran; this counts every member once)."""
    total = 0.0
    for root, _, files in os.walk(directory):
        if "ensemble.json" in files and os.path.basename(root) != "bracket":
            with open(os.path.join(root, "ensemble.json")) as f:
                total += sum(m.get("wall_s", 0.0) for m in json.load(f)["members"])
    return total


def copy_report(source, target, names):
    os.makedirs(target, exist_ok=True)
    for name in names:
        if os.path.isfile(os.path.join(source, name)):
            shutil.copy(os.path.join(source, name), os.path.join(target, name))


def answer(path):
    """The sentence a report opens with (its first bold line)."""
    for line in open(path):
        if line.startswith("**"):
            return line.strip().strip("*")
    return "(no answer line)"


def bracket_rows(directory):
    """The bracketing sweep's runs so far (sweep.json's cases), [] if none."""
    try:
        with open(os.path.join(directory, "sweep.json")) as f:
            cases = json.load(f).get("cases", [])
    except (OSError, ValueError):
        return []
    return [{"value": c.get("value"),
             "verdict": "cancelled" if c.get("cancelled") else
             "a keyblock fell %s" % c.get("fallen_keyblocks") if c.get("exceeded") else "held",
             "status": c.get("status"), "wall_s": c.get("wall_s")} for c in cases]


def fragility_lines(data):
    if data["answers"]["fragility"] is not None:
        return ["**%s**" % data["answers"]["fragility"], "",
                "Members drawn as in the friction ensemble at every level. Report: "
                "[fragility/fragility/fragility.md](fragility/fragility/fragility.md).", "",
                "![](fragility/fragility/fragility.png)", ""]
    lines = ["**Not run in this regeneration** (`--no-fragility`): at the present speed a "
             "tunnel run at the shaking that drops keyblocks takes minutes, and 6 x 16 of them "
             "hours on 2 cores (issue 54). What the bracketing sweep (single runs, no "
             "perturbation) had found when it was stopped:", "",
             "| incident amplitude [m/s] | verdict | status | wall [s] |", "|---|---|---|---|"]
    lines += ["| %s | %s | %s | %s |" % (r["value"], r["verdict"], r["status"],
                                         "-" if r["wall_s"] is None else "%.0f" % r["wall_s"])
              for r in data["fragility_bracket"]]
    return lines + [""]


def write_page(path, data):
    walls = data["walls_s"]
    lines = [
        "# The default tunnel's answer as statistics: ensembles and a fragility curve", "",
        "Regenerated by `/usr/bin/python3 tools/verify_fragility.py` (the runs: %.0f min of "
        "members' wall time, %d at a time; this call %.0f min, resuming what earlier calls ran; "
        "load average %s at the end); the runs' reports are in [fragility/](fragility/). "
        "Scene: `examples/tunnel/circular_sv.yaml` with its default damping (2 %% at 25 Hz, "
        "docs/damping.md)." % (sum(data["member_s"].values()) / 60, data["jobs"],
                               sum(walls.values()) / 60, data["load_average"]), "",
        "## Friction angle and round-off: 32 members", "",
        "**%s**" % data["answers"]["friction"], "",
        "Friction angle truncnormal(35, 2, 25, 45) deg; incident amplitude 0.5 m/s x (1 + k "
        "1e-12). Report: [fragility/friction/ensemble.md](fragility/friction/ensemble.md).", "",
        "![](fragility/friction/ensemble.png)", "",
        "## Joint-set geometry by seed: 32 members, by sector", "",
        "**%s**" % data["answers"]["joint_sets"], "",
        "Each member's seed draws the joint spacing (+-10 %, both sets) and the traces' "
        "positions of the non-persistent set (+-1/4 period): the blocks differ between members, "
        "so the statistics are by 10 deg sector of the perimeter (from the crown clockwise). "
        "Report: [fragility/joint_sets/ensemble.md](fragility/joint_sets/ensemble.md).", "",
        "![](fragility/joint_sets/ensemble.png)", "",
        "## Fragility in the incident wave's amplitude", ""] + fragility_lines(data) + [
        "## mpirun against -j 2", "",
        "The friction ensemble's first %d members, `mpirun -np 2 ddafem ensemble` (%.0f s) "
        "against `ddafem ensemble -j 2` (%.0f s):" % (
            MPI_MEMBERS, data["mpirun"]["wall_np2_s"], data["mpirun"]["wall_j2_s"]), "",
        "| member | values drawn equal | keyblock verdicts equal | histories.h5 bit for bit "
        "(datasets) |", "|---|---|---|---|"]
    for r in data["mpirun"]["members"]:
        lines.append("| %d | %s | %s | %s (%d) |" % (
            r["member"], r["values_equal"], r["keyblocks_equal"], r["histories_bit_for_bit"],
            r["datasets"]))
    lines += ["", "## Time taken", "",
              "The call's wall time (a call that resumed counts only what it ran) and the members' "
              "wall times summed over every member (each at one thread, %d at a time)." %
              data["jobs"], "", "| run | this call's wall [min] | members' wall, summed [min] |",
              "|---|---|---|"]
    lines += ["| %s | %.1f | %s |" % (name, wall / 60, "%.1f" % (data["member_s"][name] / 60)
                                      if name in data["member_s"] else "-")
              for name, wall in walls.items()]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def rewrite_page(out, update):
    """fragility.json changed by update(data) and fragility.md written again from it."""
    with open(os.path.join(out, "fragility.json")) as f:
        data = json.load(f)
    update(data)
    with open(os.path.join(out, "fragility.json"), "w") as f:
        json.dump(data, f, indent=1)
    write_page(os.path.join(out, "fragility.md"), data)


def page_only(out, work):
    """Rewrites fragility.md from fragility.json (the page's layout changed, not the runs), the
    answers and the copied reports taken again from the runs' own reports in work (rewritten by
    `ddafem resume` of a finished ensemble, which runs nothing)."""
    def update(data):
        for name in ("friction", "joint_sets"):
            source = os.path.join(work, "ensemble_" + name)
            data["answers"][name] = answer(os.path.join(source, "ensemble.md"))
            copy_report(source, os.path.join(out, "fragility", name),
                        ["ensemble.md", "ensemble.json", "ensemble.png"])
    rewrite_page(out, update)


def mpirun_only(ddafem, work, out):
    """Runs the mpirun check again (a new binary) and rewrites fragility.json's entry and the
    page, the ensembles and the curve as they are."""
    for way in ("np2", "j2"):
        wall_file = os.path.join(work, "mpirun_" + way + ".wall_s")
        if os.path.isfile(wall_file):
            os.remove(wall_file)
    rewrite_page(out, lambda data: data.update(mpirun=compare_mpirun(ddafem, work)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(TOP, "build"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--work", default=os.path.join(TOP, "build", "verification_fragility"))
    parser.add_argument("--out", default=os.path.join(TOP, "docs", "verification"))
    parser.add_argument("--mpirun-only", action="store_true",
                        help="only the mpirun check again (e.g. with a new binary), the page "
                             "rewritten with it")
    parser.add_argument("--no-fragility", action="store_true",
                        help="the ensembles and the mpirun check only; the page says the curve "
                             "was not run and gives what its bracketing sweep found, if any")
    parser.add_argument("--page-only", action="store_true",
                        help="rewrite fragility.md from fragility.json, running nothing")
    args = parser.parse_args()
    if args.page_only:
        return page_only(args.out, os.path.abspath(args.work)) or 0
    ddafem = os.path.join(os.path.abspath(args.build), "ddafem")
    work = os.path.abspath(args.work)
    if args.mpirun_only:
        return mpirun_only(ddafem, work, args.out) or 0
    os.makedirs(work, exist_ok=True)
    jobs = ["-j", str(args.jobs), "--quiet"]
    dirs = {name: os.path.join(work, "ensemble_" + name) for name in ("friction", "joint_sets")}
    dirs["fragility"] = os.path.join(work, "fragility")
    walls = {}
    walls["friction ensemble (32)"] = run(
        "friction", [ddafem, "ensemble", SCENE, "-n", "32", "-o", dirs["friction"]] + FRICTION +
        jobs, os.path.join(work, "friction.log"))
    walls["joint-set ensemble (32)"] = run(
        "joint_sets", [ddafem, "ensemble", SCENE, "-n", "32", "-o", dirs["joint_sets"]] +
        JOINT_SETS + jobs, os.path.join(work, "joint_sets.log"))
    if not args.no_fragility:
        wall = run("fragility", [ddafem, "fragility", SCENE, "--key",
                                 "tunnel.wave.velocity.amplitude", "-o", dirs["fragility"]] +
                   FRICTION + jobs, os.path.join(work, "fragility.log"))
        with open(os.path.join(dirs["fragility"], "fragility.json")) as f:
            n_levels = len(json.load(f)["levels"])
        walls["fragility (sweep + %d x 16)" % n_levels] = wall
    mpirun = compare_mpirun(ddafem, work)
    walls["mpirun check (2 x %d)" % MPI_MEMBERS] = mpirun["wall_s"]
    python = sys.executable
    for name in ("friction", "joint_sets"):
        subprocess.run([python, os.path.join(TOP, "tools", "plot_ensemble.py"), dirs[name]],
                       check=True)
    if not args.no_fragility:
        subprocess.run([python, os.path.join(TOP, "tools", "plot_fragility.py"),
                        dirs["fragility"]], check=True)
    target = os.path.join(args.out, "fragility")
    for name in ("friction", "joint_sets"):
        copy_report(dirs[name], os.path.join(target, name),
                    ["ensemble.md", "ensemble.json", "ensemble.png"])
    if not args.no_fragility:
        copy_report(dirs["fragility"], os.path.join(target, "fragility"),
                    ["fragility.md", "fragility.json", "fragility.png"])
    names = dict(zip(walls, ("friction", "joint_sets") + (() if args.no_fragility else
                                                          ("fragility",))))
    data = {"jobs": args.jobs, "walls_s": walls, "mpirun": mpirun,
            "member_s": {label: member_seconds(dirs[name]) for label, name in names.items()},
            "load_average": "%.2f %.2f %.2f" % os.getloadavg(),
            "answers": {"friction": answer(os.path.join(dirs["friction"], "ensemble.md")),
                        "joint_sets": answer(os.path.join(dirs["joint_sets"], "ensemble.md")),
                        "fragility": None if args.no_fragility else
                        answer(os.path.join(dirs["fragility"], "fragility.md"))},
            "fragility_bracket": bracket_rows(os.path.join(dirs["fragility"], "bracket"))}
    with open(os.path.join(args.out, "fragility.json"), "w") as f:
        json.dump(data, f, indent=1)
    write_page(os.path.join(args.out, "fragility.md"), data)
    print("verify_fragility: %s" % os.path.join(args.out, "fragility.md"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
