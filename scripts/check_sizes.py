#!/usr/bin/python3
"""Source files of at most 800 lines and functions of at most 80 (issue 18, docs/style.md).

    /usr/bin/python3 scripts/check_sizes.py            # exit 1 and a list if any is over
    /usr/bin/python3 scripts/check_sizes.py --report   # every file and function over, no exit 1

Reads the C++ sources of the library folders and app/ (tests, bench and generated files aside).
A function is a definition whose body opens with a `{` alone at the start of a line (our
clang-format style: Allman braces, namespaces not indented) and ends at the next `}` there; its
length counts from the first line of its signature to the closing brace. Class, struct, enum and
namespace bodies and initialiser lists are not functions; a namespace's body is searched, so the
first function after `namespace x {` is measured too (it was not before issue 55).
tests/scripts/test_check_sizes.py checks the checker.
"""
import argparse
import os
import re
import sys

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FOLDERS = ["app", "common", "coupling", "dda", "fem"]
MAX_FILE_LINES = 800
MAX_FUNCTION_LINES = 80
OPENS_A_SCOPE = re.compile(r'^\s*(inline\s+)?namespace\b|^\s*extern\s+"C"')
NOT_A_FUNCTION = re.compile(r"^\s*(template\s*<.*>\s*)?(class|struct|enum|namespace|union)\b|=\s*$")


def sources(top):
    for folder in FOLDERS:
        for root, _, files in os.walk(os.path.join(top, folder)):
            for name in sorted(files):
                if name.endswith((".cc", ".h")):
                    yield os.path.join(root, name)


def signature_start(lines, brace):
    """Index of the first line of the signature ending just above line `brace`."""
    i = brace - 1
    while i > 0:
        above = lines[i - 1].rstrip()
        if (not above or above.endswith((";", "}", "{")) or above.startswith(("//", "#"))
                or above.lstrip().startswith("//")):
            break
        i -= 1
    return i


def functions(lines):
    """(name line, first line, length) of each function definition at namespace scope."""
    found = []
    i = 0
    while i < len(lines):
        if lines[i].rstrip() == "{" and i > 0:
            start = signature_start(lines, i)
            head = " ".join(l.strip() for l in lines[start:i])
            if OPENS_A_SCOPE.search(lines[start]) or not head:
                i += 1  # a namespace's body holds functions: look inside it
                continue
            end = i + 1
            while end < len(lines) and not re.match(r"^\}", lines[end]):
                end += 1
            if head and "(" in head and not NOT_A_FUNCTION.search(lines[start]) and \
                    not NOT_A_FUNCTION.search(lines[i - 1]):
                found.append((head, start + 1, end - start + 1))
            i = end
        i += 1
    return found


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--report", action="store_true", help="list, but do not fail")
    parser.add_argument("--root", default=TOP, help="the source tree (default: this checkout)")
    args = parser.parse_args(argv)
    over = []
    for path in sources(args.root):
        with open(path, encoding="utf-8") as f:
            lines = f.read().split("\n")
        if lines and lines[-1] == "":
            lines.pop()
        rel = os.path.relpath(path, args.root)
        if len(lines) > MAX_FILE_LINES:
            over.append("%s: %d lines (at most %d)" % (rel, len(lines), MAX_FILE_LINES))
        for head, first, length in functions(lines):
            if length > MAX_FUNCTION_LINES:
                name = head.split("(")[0].split()[-1] if head.split("(")[0].split() else head
                over.append("%s:%d: %s is %d lines (at most %d)" %
                            (rel, first, name, length, MAX_FUNCTION_LINES))
    for line in over:
        print(line)
    if over:
        print("%d files or functions over the limits" % len(over))
    else:
        print("every file at most %d lines, every function at most %d" %
              (MAX_FILE_LINES, MAX_FUNCTION_LINES))
    return 1 if over and not args.report else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
