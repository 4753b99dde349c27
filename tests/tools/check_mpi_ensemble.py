#!/usr/bin/python3
"""`mpirun -np 2 ddafem ensemble` against `ddafem ensemble -j 2` (CI test cli.ensemble_mpi):
three members of the roof-wedge tunnel (VB I, no settle stage) with round-off, members 0 and 2 on
rank 0 and member 1 on rank 1, each a child run whose environment has none of mpirun's variables.
The same seeds give the same members: member.json's values, summary.json's status and keyblock
verdicts, and every dataset of histories.h5 bit for bit; rank 0's ensemble.json counts all
three, and no rank marker is left.

    check_mpi_ensemble.py DDAFEM MPIEXEC SOURCE_DIR WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

import numpy as np

from check_crash_safety import datasets  # every dataset of an HDF5 file by path


def main():
    ddafem, mpiexec, source, work = sys.argv[1:5]
    scene = os.path.join(source, "examples/tunnel/roof_wedge_sv.yaml")
    common = ["ensemble", scene, "-n", "3", "--roundoff", "--set", "tunnel.settle.enabled=false"]
    out = {way: os.path.join(work, way) for way in ("mpi", "jobs")}
    for way, command in (("mpi", [mpiexec, "-np", "2", "--oversubscribe", "--bind-to", "none",
                                  ddafem] + common + ["-o", out["mpi"]]),
                         ("jobs", [ddafem] + common + ["-j", "2", "-o", out["jobs"]])):
        shutil.rmtree(out[way], ignore_errors=True)
        r = subprocess.run(command, capture_output=True, text=True)
        assert r.returncode == 0, (way, r.returncode, r.stderr)
        # One whole progress line per member: the ranks' lines must not interleave.
        lines = [line for line in r.stderr.splitlines() if line.startswith("ensemble: member_")]
        assert len(lines) == 3 and all(line.endswith(" done") for line in lines), (way, r.stderr)
    assert not [f for f in os.listdir(out["mpi"]) if f.startswith("rank_")], os.listdir(out["mpi"])
    reports = {way: json.load(open(os.path.join(d, "ensemble.json"))) for way, d in out.items()}
    assert reports["mpi"]["n_counted"] == 3, reports["mpi"]
    assert reports["mpi"]["keyblocks"] == reports["jobs"]["keyblocks"]
    for k in range(3):
        member = "member_%03d" % k
        a, b = (os.path.join(out[way], member) for way in ("mpi", "jobs"))
        assert json.load(open(os.path.join(a, "member.json"))) == json.load(
            open(os.path.join(b, "member.json"))), member
        sa, sb = (json.load(open(os.path.join(d, "summary.json"))) for d in (a, b))
        assert sa["status"] == sb["status"] == "completed", member
        assert sa["keyblocks"] == sb["keyblocks"], member
        ha, hb = datasets(os.path.join(a, "histories.h5")), datasets(os.path.join(b, "histories.h5"))
        assert sorted(ha) == sorted(hb) and ha, member
        for name in ha:
            assert np.array_equal(ha[name], hb[name]), (member, name)
    print("mpirun -np 2 and -j 2: 3 members, histories bit for bit")


if __name__ == "__main__":
    main()
