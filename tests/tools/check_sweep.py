#!/usr/bin/python3
"""`ddafem sweep` end to end (CI test cli.sweep): the roof-wedge tunnel (VB I, no settle stage)
swept over the incident wave's amplitude from 0.1 to 0.8 m/s, two runs at a time, for the
smallest amplitude at which a keyblock's residual displacement relative to the rock exceeds
1 mm, to within 50 %. Checks that the search ended bracketed and narrow enough, that every case's
verdict is what its own summary.json says, that the outcome is monotonic, that sweep.md states
the bracket, that each run stopped as no longer needed lay outside the bracket of the runs judged
before it or the search had concluded by then, and that bad input is refused with exit code 2 before any run.

    check_sweep.py DDAFEM SOURCE_DIR WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys


def main():
    ddafem, source, work = sys.argv[1:4]
    scene = os.path.join(source, "examples/tunnel/roof_wedge_sv.yaml")
    out = os.path.join(work, "sweep")
    shutil.rmtree(out, ignore_errors=True)
    key = "tunnel.wave.velocity.amplitude"

    def sweep(swept, *extra):
        return [ddafem, "sweep", scene, "--key", swept, "--find", "displacement", "--threshold",
                "0.001", "--set", "tunnel.settle.enabled=false", "-j", "2", "-o", out, *extra]

    common = sweep(key)
    subprocess.run(common + ["--low", "0.1", "--high", "0.8", "--tolerance", "0.5"], check=True)
    result = json.load(open(os.path.join(out, "sweep.json")))
    low, high = result["highest_holding"], result["lowest_exceeding"]
    assert result["conclusion"] == "bracketed", result["conclusion"]
    assert 0.1 <= low < high <= 0.8 and high - low <= 0.5 * high, (low, high)
    assert result["non_monotonic"] == [], result["non_monotonic"]
    def ended(c):
        return c["started_s"] + c["wall_s"]

    for case in result["cases"]:
        if case["cancelled"]:  # stopped once it could no longer narrow the bracket:
            # by the runs judged before it was stopped, its value lay outside their bracket
            # or that bracket was already narrow enough (the search had concluded).
            before = [c for c in result["cases"]
                      if not c["cancelled"] and ended(c) < ended(case)]
            a = max([c["value"] for c in before if not c["exceeded"]], default=None)
            b = min([c["value"] for c in before if c["exceeded"]], default=None)
            assert a is not None and b is not None, (case, before)
            inside = a < case["value"] < b
            assert not inside or b - a <= 0.5 * b * (1 + 1e-12), (case, a, b)
            continue
        summary = json.load(open(os.path.join(out, case["directory"], "summary.json")))
        relative = max([b["residual_relative_m"] for b in summary["keyblocks"]["blocks"]
                        if not b["released"]] + [0.0])
        assert abs(relative - case["max_relative_residual_m"]) < 1e-12, case
        assert case["exceeded"] == (relative > 0.001 or summary["status"] == "failed"), case
        assert (case["value"] > low) == case["exceeded"], case
    text = open(os.path.join(out, "sweep.md")).read()
    assert "The critical value lies above %g and at most %g" % (low, high) in text, text

    # Bad input: an unknown key, a value the scene refuses, --low without --high.
    for args, expected in ((sweep("tunnel.wave.amplitude", "--low", "0.1", "--high", "0.8"),
                            "unknown key"),
                           (sweep(key, "--low", "-1", "--high", "1"), "0 < --low < --high"),
                           (sweep(key, "--low", "0.1"), "both --low and --high")):
        r = subprocess.run(args, capture_output=True, text=True)
        assert r.returncode == 2 and expected in r.stderr, (args, r.returncode, r.stderr)
    print("sweep bracketed the critical amplitude in (%g, %g] m/s over %d runs"
          % (low, high, len(result["cases"])))


if __name__ == "__main__":
    main()
