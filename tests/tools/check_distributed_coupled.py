#!/usr/bin/python3
"""`mpirun -np N ddafem run` of coupled scenes (issue 22; CTest cli.distributed_coupled): the
blocks run on every rank, the far field is distributed. Runs the hybrid P-wave bar and S-wave
column of examples/coupled serially and under mpirun with 1 and 2 ranks and checks that every run
gives the serial histories at every monitor (blocks' and far field's displacement, velocity and
stress) within three times the round-off floor of the scene: the difference the serial run makes
when only the blocks' direct solver changes (block_ldlt to KLU), measured here in the same run.
Both sides are direct (CHOLMOD or MUMPS for the far field; the blocks' LDL^T with refinement),
but bonded joints of 50 E per metre make the coupled steps ill-conditioned enough that round-off
reaches 1e-9 (column) to 3e-8 (bar) of the peaks whatever the solver. Also checks that rank 0
wrote summary.json with mpi.ranks and a .vtu piece per rank of each far-field snapshot, and that
a wall-time budget stops both ranks after the same step (exit 3, status stopped, no hang), and
that an error on one rank alone ends every rank with its exit code.

    check_distributed_coupled.py DDAFEM SOURCE_DIR WORK_DIR
"""
import glob
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

# Ranks that wait yield their core: the blocks' threads and the other rank need it (busy-polling
# ranks made a coupled run 300 times slower on a loaded 2-core machine).
ENVIRONMENT = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_mpi_yield_when_idle="1")
MPIRUN = ["mpirun", "--oversubscribe", "--bind-to", "none"]
# The column to t = 0.04 s: the pulse has crossed the interface and reached M2 (y = 49.5 m).
SCENES = (("examples/coupled/p_wave_bar_hybrid.yaml", []),
          ("examples/coupled/s_wave_column_hybrid.yaml", ["--set", "time.end_time=0.04"]))


def monitors(directory):
    with h5py.File(os.path.join(directory, "histories.h5"), "r") as f:
        return f["time"][:], {f"{name}/{q}": f[f"monitors/{name}/{q}"][:]
                              for name in f["monitors"]
                              for q in ("displacement", "velocity", "stress")}


def difference(a, b):
    """The largest difference of two runs' monitors, relative to each quantity's peak."""
    (ta, xa), (tb, xb) = a, b
    assert np.array_equal(ta, tb), (len(ta), len(tb))
    return max(np.max(np.abs(xb[k] - x)) / max(np.max(np.abs(x)), 1e-300) for k, x in xa.items())


def run(ddafem, scene, out, extra, ranks=None):
    shutil.rmtree(out, ignore_errors=True)
    command = [ddafem, "run", scene, "-o", out, "-q"] + extra
    if ranks:
        command = MPIRUN + ["-np", str(ranks)] + command
    subprocess.run(command, check=True, env=ENVIRONMENT)
    return monitors(out)


def main():
    ddafem, source, work = sys.argv[1:4]
    for scene, extra in SCENES:
        name = os.path.splitext(os.path.basename(scene))[0]
        path = os.path.join(source, scene)
        serial = run(ddafem, path, os.path.join(work, name, "serial"), extra)
        klu = run(ddafem, path, os.path.join(work, name, "klu"),
                  extra + ["--set", "solver.type=klu"])
        floor = difference(serial, klu)
        assert 0.0 < floor < 1e-7, (name, floor)
        for ranks in (1, 2):
            out = os.path.join(work, name, f"np{ranks}")
            got = run(ddafem, path, out, extra, ranks)
            d = difference(serial, got)
            assert d <= 3.0 * floor, (name, ranks, d, floor)
            summary = json.load(open(os.path.join(out, "summary.json")))
            assert summary["status"] == "completed" and summary["mpi"]["ranks"] == ranks, summary
            records = glob.glob(os.path.join(out, "far_field_*.pvtu"))
            pieces = glob.glob(os.path.join(out, "far_field_*.*.vtu"))
            assert records and len(pieces) == ranks * len(records), (len(records), len(pieces))
            print(f"{name}, {ranks} rank(s): the serial monitors within {d:.2g} of their peaks "
                  f"(round-off floor {floor:.2g})")
    # A budget: rank 0 and rank 1 reach it at different steps; both stop after the same one.
    out = os.path.join(work, "budget")
    shutil.rmtree(out, ignore_errors=True)
    r = subprocess.run(MPIRUN + ["-np", "2", ddafem, "run", os.path.join(source, SCENES[1][0]),
                                 "-o", out, "-q", "--max-wall-time", "2"],
                       env=ENVIRONMENT, timeout=120)
    summary = json.load(open(os.path.join(out, "summary.json")))
    assert r.returncode == 3 and summary["status"] == "stopped", (r.returncode, summary["status"])
    steps = [json.load(open(os.path.join(out, "ranks", "rank_1", "summary.json")))["steps"],
             summary["steps"]]
    assert steps[0] == steps[1], steps
    print(f"a 2 s budget stopped both ranks after step {steps[1]}")
    # An error on one rank only, after MPI has started: rank 1 cannot make its directory (DIR/ranks
    # is a file) while rank 0 goes on into the run's collective calls. Every rank must end, with
    # the error's exit code, instead of waiting for the other (a hang until mpirun is killed).
    out = os.path.join(work, "one_rank_fails")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    open(os.path.join(out, "ranks"), "w").close()
    r = subprocess.run(MPIRUN + ["-np", "2", ddafem, "run", os.path.join(source, SCENES[1][0]),
                                 "-o", out, "-q"], env=ENVIRONMENT, timeout=120,
                       capture_output=True, text=True)
    assert r.returncode == 2 and "ranks/rank_1" in r.stderr, (r.returncode, r.stderr)
    print("an error on rank 1 alone ended both ranks, exit code 2")


if __name__ == "__main__":
    main()
