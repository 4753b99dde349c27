#!/usr/bin/python3
"""Do two builds give the same bits? Every example scene run by both, their determinism hashes
compared (issue 55: a restructuring must leave every example's history hash unchanged).

    /usr/bin/python3 tools/same_bits.py OLD_BINARY NEW_BINARY [CASE ...] [--jobs N] [--out DIR]

A CASE is an example's path under examples/ without `.yaml` (default: every scene there). The hash
is tests/tools/example_reference.py's: summary.json without timings, and every history's bytes.
Both binaries run on this machine, so unlike the stored references the hash is always compared.
Exit 1 if any case differs or fails to run; the table names each case, its two hashes' heads and
the wall time of each run.
"""
import argparse
import concurrent.futures
import glob
import os
import sys
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(TOP, "tests", "tools"))
import example_reference  # noqa: E402  (the fingerprint and the way a case is run)


def every_case():
    scenes = glob.glob(os.path.join(TOP, "examples", "**", "*.yaml"), recursive=True)
    return sorted(os.path.relpath(s, os.path.join(TOP, "examples"))[:-5] for s in scenes)


def run(binary, case, out):
    start = time.monotonic()
    example_reference.run_case(binary, case, out)
    return example_reference.fingerprint(out)["hash"], time.monotonic() - start


def compare(case, binaries, out):
    results = []
    for label, binary in zip(("old", "new"), binaries):
        try:
            results.append(run(binary, case, os.path.join(out, case.replace("/", "."), label)))
        except SystemExit as failure:  # run_case exits with the command and its output
            return case, None, str(failure)
    return case, results, ""


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("cases", nargs="*")
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--out", default="same_bits_runs")
    args = parser.parse_args(argv)
    binaries = [os.path.abspath(args.old), os.path.abspath(args.new)]
    cases = args.cases or every_case()
    differ = 0
    print("| case | old hash | new hash | same | old s | new s |")
    print("|---|---|---|---|---|---|")
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for case, results, failure in pool.map(lambda c: compare(c, binaries, args.out), cases):
            if results is None:
                differ += 1
                print("| %s | failed: %s |" % (case, failure.splitlines()[0]))
                continue
            (old, t_old), (new, t_new) = results
            differ += old != new
            print("| %s | %s | %s | %s | %.1f | %.1f |" %
                  (case, old[:12], new[:12], "yes" if old == new else "**no**", t_old, t_new),
                  flush=True)
    print("%d of %d cases differ or failed" % (differ, len(cases)))
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
