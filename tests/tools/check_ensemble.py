#!/usr/bin/python3
"""`ddafem ensemble` end to end (CI test cli.ensemble): four members of the roof-wedge tunnel
(VB I, no settle stage), two at a time, the clean joints' friction angle drawn from
truncnormal(35, 3, 25, 45) and the wave's amplitude perturbed by k 1e-12. Checks the member
directories, that each member.json holds the values drawn for it and
that ensemble.json's values, verdicts and probabilities are those of the members' own
summary.json, recounted here; that the scene's seed warning is printed once; that `ddafem
resume` of an interrupted ensemble runs only the member missing and gives the same report, a
larger -n into the same directory runs only the members added, a smaller one exits 2; that bad --vary texts exit 2 naming them, before
any member runs; that members failing numerically give exit 1, listed and not counted, and
one stopped at its budget exit 3.

    check_ensemble.py DDAFEM SOURCE_DIR WORK_DIR
"""
import json
import math
import os
import shutil
import subprocess
import sys


def wilson(k, n, z=1.96):
    p = k / n
    centre, half = p + z * z / (2 * n), z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return [max(0.0, (centre - half) / (1 + z * z / n)), min(1.0, (centre + half) / (1 + z * z / n))]


def check_members(out, result):
    counted = []
    for m in result["members"]:
        member = json.load(open(os.path.join(out, m["directory"], "member.json")))
        assert member["index"] == m["index"] and member["seed"] == m["seed"], (member, m)
        assert member["values"] == m["values"], (member, m)
        friction = member["values"]["joint_materials.clean.friction_angle"]
        assert 25 <= friction <= 45, friction
        amplitude = member["values"]["tunnel.wave.velocity.amplitude"]
        assert amplitude == 0.1 * (1 + m["index"] * 1e-12), amplitude
        summary = json.load(open(os.path.join(out, m["directory"], "summary.json")))
        assert summary["status"] == m["status"], (summary["status"], m)
        blocks = summary["keyblocks"]["blocks"]
        assert m["fell"] == [b["id"] for b in blocks if b["fell"]], m
        assert m["loosened"] == [b["id"] for b in blocks if b["loosened"]], m
        if summary["status"] == "completed":
            counted.append(blocks)
    assert len(counted) == result["n_counted"], result["n_counted"]
    return counted


def check_probabilities(result, counted):
    for k in result["keyblocks"]:
        verdicts = [b for blocks in counted for b in blocks if b["id"] == k["id"]]
        assert k["n"] == len(verdicts), k
        for what in ("fell", "loosened"):
            count = sum(1 for b in verdicts if b[what])
            assert k[what]["count"] == count, (k, what)
            assert all(abs(a - b) < 1e-12 for a, b in zip(k[what]["wilson_95"], wilson(count, len(verdicts)))), k
        residuals = sorted(b["residual_relative_m"] for b in verdicts)
        median = (residuals[1] + residuals[2]) / 2 if len(residuals) == 4 else None
        if median is not None:
            assert abs(k["residual_relative_m"]["median"] - median) < 1e-15, k


def main():
    ddafem, source, work = sys.argv[1:4]
    scene = os.path.join(source, "examples/tunnel/roof_wedge_sv.yaml")
    out = os.path.join(work, "ensemble")
    shutil.rmtree(out, ignore_errors=True)
    friction = "joint_materials.clean.friction_angle"

    def ensemble(*extra, n=4):
        return [ddafem, "ensemble", scene, "-n", str(n), "-j", "2", "-o", out,
                "--set", "tunnel.settle.enabled=false", *extra]

    r = subprocess.run(ensemble("--vary", friction + "=truncnormal(35,3,25,45)", "--roundoff"),
                       capture_output=True, text=True)
    assert r.returncode in (0, 1), (r.returncode, r.stderr)
    assert r.stderr.count("warning: no joint set has a random perturbation") == 1, r.stderr
    assert r.stderr.count("ensemble: member_") == 4, r.stderr
    result = json.load(open(os.path.join(out, "ensemble.json")))
    assert sorted(os.listdir(out)) == sorted(
        ["ensemble.json", "ensemble.md"] + ["member_%03d" % k for k in range(4)]
        + ["member_%03d.log" % k for k in range(4)]), os.listdir(out)
    assert result["n_finished"] == 4 and (r.returncode == 1) == bool(result["failed"]), result
    check_probabilities(result, check_members(out, result))
    text = open(os.path.join(out, "ensemble.md")).read()
    assert text.split("\n")[2] == "**" + result["answer"] + "**", text[:300]

    # An interrupted ensemble: member 3 as if it had not run. `ddafem resume` runs it alone and
    # ends with the same report; the same -o with another -n is refused.
    ensemble_json = os.path.join(out, "ensemble.json")
    interrupted = json.load(open(ensemble_json))
    interrupted["members"][3]["finished"] = False
    json.dump(interrupted, open(ensemble_json, "w"))
    shutil.rmtree(os.path.join(out, "member_003"))
    r = subprocess.run([ddafem, "resume", out], capture_output=True, text=True)
    assert r.returncode in (0, 1), (r.returncode, r.stderr)
    assert "3 of 4 members finished earlier" in r.stderr, r.stderr
    assert r.stderr.count("ensemble: member_") == 1 and "member_003" in r.stderr, r.stderr
    resumed = json.load(open(ensemble_json))
    assert resumed["keyblocks"] == result["keyblocks"], "the resumed ensemble differs"
    assert [m["values"] for m in resumed["members"]] == [m["values"] for m in result["members"]]
    # A larger -n extends it: only member 4 runs, the first four stand with their values; a
    # smaller -n is refused.
    r = subprocess.run(ensemble("--vary", friction + "=truncnormal(35,3,25,45)", "--roundoff", n=5),
                       capture_output=True, text=True)
    assert r.returncode in (0, 1), (r.returncode, r.stderr)
    assert "4 of 5 members finished earlier" in r.stderr, r.stderr
    assert r.stderr.count("ensemble: member_") == 1 and "member_004" in r.stderr, r.stderr
    extended = json.load(open(ensemble_json))
    assert extended["members_requested"] == 5 and extended["n_finished"] == 5, extended
    assert [m["values"] for m in extended["members"][:4]] == [m["values"] for m in result["members"]]
    check_probabilities(extended, check_members(out, extended))
    # Its report's time: this call's, and the members' of both calls summed.
    summed = sum(m["wall_s"] for m in extended["members"] if m["finished"])
    assert abs(extended["members_wall_s"] - summed) < 1e-9 * summed, (extended["members_wall_s"], summed)
    assert extended["members_wall_s"] > extended["wall_s"] > 0, extended
    r = subprocess.run(ensemble("--vary", friction + "=truncnormal(35,3,25,45)", "--roundoff", n=3),
                       capture_output=True, text=True)
    assert r.returncode == 2 and "members_requested = 5, not 3" in r.stderr, r.stderr

    # Bad --vary texts: exit 2 naming the text and what was expected; nothing run.
    shutil.rmtree(out)
    for vary, expected in ((friction + "=normal(35,3)", "leave the range of key"),
                           (friction + "=gauss(35,3)", "unknown distribution 'gauss'"),
                           (friction + "=normal(35,-3)", "expected a standard deviation sd > 0"),
                           ("joint_materials.clean.friction=normal(35,3)", "friction"),
                           ("joint_materials.clean.bonded=uniform(0,1)", "expected a numeric key")):
        r = subprocess.run(ensemble("--vary", vary), capture_output=True, text=True)
        assert r.returncode == 2 and "--vary " + vary in r.stderr and expected in r.stderr, (
            vary, r.returncode, r.stderr)
        assert not os.path.exists(out), vary
    # Members that fail numerically (the block stack's static stage given one step): exit 1,
    # listed, not counted, the report written. --roundoff without a key needs a tunnel.
    stack = os.path.join(source, "examples/block_stack/stack.yaml")
    r = subprocess.run([ddafem, "ensemble", stack, "-n", "2", "-o", out, "--set",
                        "stages.0.max_steps=1"], capture_output=True, text=True)
    assert r.returncode == 1, (r.returncode, r.stderr)
    failed = json.load(open(os.path.join(out, "ensemble.json")))
    assert failed["failed"] == [0, 1] and failed["n_counted"] == 0, failed
    assert failed["answer"].startswith("None of the 2 runs that ended (of 2) completed"), failed
    assert "Failed (not counted): members [0,1]" in open(os.path.join(out, "ensemble.md")).read()
    shutil.rmtree(out)
    # A member stopped at its budget: exit 3, not counted either.
    r = subprocess.run([ddafem, "ensemble", scene, "-n", "1", "-o", out, "--max-wall-time",
                        "0.01"], capture_output=True, text=True)
    assert r.returncode == 3, (r.returncode, r.stderr)
    stopped = json.load(open(os.path.join(out, "ensemble.json")))
    assert stopped["stopped"] == [0] and stopped["n_counted"] == 0, stopped
    assert "1 stopped at a budget" in stopped["answer"], stopped["answer"]
    shutil.rmtree(out)
    r = subprocess.run([ddafem, "ensemble", stack, "-n", "2", "-o", out, "--roundoff"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "--roundoff: the scene has no tunnel section" in r.stderr, r.stderr
    assert not os.path.exists(out)
    print("ensemble of 4: %s" % result["answer"])


if __name__ == "__main__":
    main()
