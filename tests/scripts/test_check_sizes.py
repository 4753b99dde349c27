#!/usr/bin/python3
"""The size gate checked on made-up sources (issue 55): every function is measured, the first
after a namespace's opening included, and 80 lines pass where 81 fail.

    /usr/bin/python3 tests/scripts/test_check_sizes.py
"""
import os
import subprocess
import sys
import tempfile

TOP = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CHECKER = os.path.join(TOP, "scripts", "check_sizes.py")


def function(name, lines):
    """A definition of `lines` lines in our style: signature, `{` alone, body, `}`."""
    body = ["  int x%d = %d;" % (i, i) for i in range(lines - 3)]
    return ["int %s()" % name, "{"] + body + ["}"]


def check(sources):
    """Run the checker on a tree holding `sources` ({path: lines}); (exit code, output)."""
    with tempfile.TemporaryDirectory() as root:
        for path, lines in sources.items():
            os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
            with open(os.path.join(root, path), "w", encoding="utf-8") as f:
                f.write("\n".join(lines) + "\n")
        run = subprocess.run([sys.executable, CHECKER, "--root", root], capture_output=True,
                             text=True, check=False)
        return run.returncode, run.stdout


def expect(what, sources, code, flagged, passed=()):
    got, out = check(sources)
    problems = []
    if got != code:
        problems.append("exit %d, expected %d" % (got, code))
    problems += ["%s not flagged" % name for name in flagged
                 if " %s is " % name not in out and name not in out]
    problems += ["%s flagged" % name for name in passed if " %s is " % name in out]
    print("%-52s %s" % (what, "ok" if not problems else "FAILED: " + "; ".join(problems)))
    if problems:
        print(out)
    return not problems


def main():
    namespace = ["namespace ddafem::dda", "{"]
    anonymous = ["namespace", "{"]
    close = ["} // namespace ddafem::dda"]
    cases = [
        ("81 lines after a namespace's opening fail",
         {"dda/a.cc": namespace + function("first", 81) + close}, 1, ["first"]),
        ("81 lines after an anonymous namespace fail",
         {"app/b.cc": namespace + anonymous + function("hidden", 81) + ["}"] + close}, 1,
         ["hidden"]),
        ("the second function is measured as before",
         {"fem/c.cc": namespace + function("short", 10) + [""] + function("second", 90) + close},
         1, ["second"], ["short"]),
        ("80 lines pass",
         {"common/d.cc": namespace + function("exact", 80) + close}, 0, [], ["exact"]),
        ("a struct's body is not a function",
         {"coupling/e.h": namespace + ["struct Big", "{"] + ["  int m%d;" % i for i in range(90)]
          + ["};"] + function("after_struct", 81) + close}, 1, ["after_struct"], ["Big"]),
        ("a file over 800 lines fails",
         {"dda/f.cc": namespace + sum((function("f%d" % i, 20) for i in range(41)), []) + close},
         1, ["dda/f.cc: 823 lines"]),
    ]
    ok = all([expect(*case) for case in cases])
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
