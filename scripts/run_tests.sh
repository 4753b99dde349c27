#!/usr/bin/env bash
# Quick start 2: install what is missing, build, check formatting, run the whole test suite.
set -euo pipefail
top="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$top/scripts/setup.sh"
"$top/scripts/check_format.sh"
"$top/scripts/build.sh"
cd "$top/build"
ctest --output-on-failure -j "${DDAFEM_JOBS:-$(nproc)}"
