#!/usr/bin/env bash
# Configures (once) and builds ddafem in build/ (Release). Incremental when nothing changed.
set -euo pipefail
top="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="${DDAFEM_JOBS:-$(nproc)}"
if [ ! -f "$top/build/CMakeCache.txt" ]; then
  cmake -S "$top" -B "$top/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$top/build" -j "$jobs"
