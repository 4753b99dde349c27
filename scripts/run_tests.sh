#!/usr/bin/env bash
# Quick start 2: install what is missing, build, check formatting and sizes (files of at most 800
# lines, functions of at most 80), run the whole test suite, then the sanitizer build's tests and
# a short fuzz run (scripts/sanitize.sh, docs/testing.md).
set -euo pipefail
top="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$top/scripts/setup.sh"
"$top/scripts/check_format.sh"
/usr/bin/python3 "$top/scripts/check_sizes.py"
"$top/scripts/build.sh"
(cd "$top/build" && ctest --output-on-failure -j "${DDAFEM_JOBS:-$(nproc)}")
"$top/scripts/sanitize.sh"
