#!/usr/bin/python3
"""`ddafem fragility` end to end (CI test cli.fragility): the roof-wedge tunnel (VB I, no settle
stage) at two levels of the wave's amplitude, two members each with round-off, two at a time.
Checks the level and member directories, that fragility.json's counts per level and damage state
are those of the members' own summary.json, recounted here, with their Wilson intervals; the
intensity measure (outcrop PGV = 2 x the incident amplitude, PGA = 2 pi f PGV of the 25 Hz sine
pulse); the fit's status and bracket (a fall at one level and none at the other separate
perfectly: beta unresolved); fragility.md opening with the answer; and that bad input exits 2
naming the option before any member runs.

    check_fragility.py DDAFEM SOURCE_DIR WORK_DIR
"""
import json
import math
import os
import shutil
import subprocess
import sys

from check_ensemble import wilson  # the same Wilson interval


def recount(out, level):
    """Per damage state (any loosened, any fell not released, block 50 fell) the members that
    reached it, from their summary.json; and the members counted (completed)."""
    counts, n = [0, 0, 0], 0
    for m in sorted(os.listdir(os.path.join(out, level["directory"]))):
        path = os.path.join(out, level["directory"], m, "summary.json")
        if not m.startswith("member_") or m.endswith(".log") or not os.path.exists(path):
            continue
        summary = json.load(open(path))
        if summary["status"] != "completed":
            continue
        n += 1
        blocks = summary["keyblocks"]["blocks"]
        counts[0] += any(b["loosened"] for b in blocks)
        counts[1] += any(b["fell"] and not b["released"] for b in blocks)
        counts[2] += any(b["id"] == 50 and b["fell"] and not b["released"] for b in blocks)
    return counts, n


def main():
    ddafem, source, work = sys.argv[1:4]
    scene = os.path.join(source, "examples/tunnel/roof_wedge_sv.yaml")
    out = os.path.join(work, "fragility")
    shutil.rmtree(out, ignore_errors=True)
    key = "tunnel.wave.velocity.amplitude"

    def fragility(*extra):
        return [ddafem, "fragility", scene, "--key", key, "--members", "2", "-j", "2", "-o", out,
                "--set", "tunnel.settle.enabled=false", "--roundoff", "--state", "block:50:fell",
                *extra]

    r = subprocess.run(fragility("--levels", "0.2,1"), capture_output=True, text=True)
    assert r.returncode == 0, (r.returncode, r.stderr)
    assert r.stderr.count("ensemble: member_") == 4, r.stderr
    result = json.load(open(os.path.join(out, "fragility.json")))
    assert sorted(os.listdir(out)) == ["fragility.json", "fragility.md", "level_01", "level_02"]
    im = result["intensity_measure"]
    assert im["name"] == "PGV (outcrop)" and im["factor"] == 2, im
    assert abs(im["pga_g_per_im"] - 2 * math.pi * 25 / 9.80665) < 1e-12, im
    assert [l["value"] for l in result["levels"]] == [0.2, 1.0], result["levels"]
    assert [l["im"] for l in result["levels"]] == [0.4, 2.0], result["levels"]
    assert [s["name"] for s in result["states"]] == ["a keyblock loosened", "a keyblock fell",
                                                     "block 50 fell"], result["states"]
    fractions = []
    for level in result["levels"]:
        counts, n = recount(out, level)
        assert level["n_counted"] == n == 2, (level, n)
        for state, count in zip(level["states"], counts):
            assert state["count"] == count, (level, counts)
            assert all(abs(a - b) < 1e-12 for a, b in zip(state["wilson_95"], wilson(count, n)))
        fractions.append(counts[1] / n)
    fit = result["states"][1]["fit"]
    if fractions == [0.0, 1.0]:
        assert fit["status"] == "separated", fit
        assert fit["highest_none"] == 0.4 and fit["lowest_all"] == 2.0, fit
        assert "beta is unresolved" in result["answer"], result["answer"]
    text = open(os.path.join(out, "fragility.md")).read()
    assert text.split("\n")[2] == "**" + result["answer"] + "**", text[:300]
    assert "HAZUS" in text and "0.6 g" in text, text

    # Bad input: exit 2 naming the option, before any member runs.
    shutil.rmtree(out)
    for extra, expected in ((["--levels", "0.2,-1"], "--levels -1: expected intensity levels > 0"),
                            (["--levels", "0.2", "--state", "block:x:fell"],
                             "--state block:x:fell: expected block:ID:fell"),
                            (["--low", "0.2"], "expected both --low and --high"),
                            (["--levels", "0.2", "--vary", "joint_materials.clean.friction_angle"
                              "=gauss(35,3)"], "unknown distribution 'gauss'"),
                            (["--levels", "0.2", "--fallen-area", "0"], "--fallen-area 0")):
        r = subprocess.run(fragility(*extra), capture_output=True, text=True)
        assert r.returncode == 2 and expected in r.stderr, (extra, r.returncode, r.stderr)
        assert not os.path.exists(out), extra
    print("fragility of 2 x 2: %s" % result["answer"])


if __name__ == "__main__":
    main()
