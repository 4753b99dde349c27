#!/usr/bin/env bash
# Issue 20 (docs/testing.md): ddafem built with clang, AddressSanitizer and UndefinedBehaviorSanitizer
# in build-sanitize/, with the libFuzzer harnesses of tests/fuzz.
#
#   scripts/sanitize.sh                # CI: the tests labelled `sanitize`, then each harness 60 s
#   scripts/sanitize.sh fuzz SECONDS   # only the harnesses, SECONDS each (the long run: 600)
#
# The harnesses run side by side, each from its corpus in tests/fuzz/corpus (read only; what they
# add goes to build-sanitize/fuzz/HARNESS). A finding stops the script with exit 1 and names the
# input libFuzzer kept, in build-sanitize/fuzz/.
set -euo pipefail
top="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$top/build-sanitize"
jobs="${DDAFEM_JOBS:-$(nproc)}"
harnesses=(scene overrides)
mode="${1:-all}"
seconds=60
if [ "$mode" = fuzz ]; then
  seconds="${2:?usage: scripts/sanitize.sh fuzz SECONDS}"
elif [ "$mode" != all ]; then
  echo "usage: scripts/sanitize.sh [fuzz SECONDS]" >&2
  exit 2
fi

# -O1 with line tables only: the sanitizers' reports give files and lines, and the build stays
# short; asserts stay on.
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$top" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" -DDDAFEM_SANITIZE=ON \
    -DDDAFEM_FUZZ=ON >/dev/null
fi
# Stop at the first report, with its stack; leaks are reported too.
export ASAN_OPTIONS=detect_leaks=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1

if [ "$mode" = all ]; then
  cmake --build "$build" -j "$jobs" --target ddafem test_common test_dda test_fem test_coupling \
    test_app "${harnesses[@]/#/fuzz_}"
  (cd "$build" && ctest --output-on-failure -j "$jobs" -L sanitize)
else
  cmake --build "$build" -j "$jobs" --target "${harnesses[@]/#/fuzz_}"
fi

mkdir -p "$build/fuzz"
# An input taking over 30 s is a finding: the slowest scenes within the harnesses' 200 MB (6,600
# blocks, 35,000 short traces) read in 6.4 s and 5.1 s here (0.6 s and 1.5 s in Release), and two
# harnesses share CI's two cores.
pids=()
for h in "${harnesses[@]}"; do
  mkdir -p "$build/fuzz/$h"
  "$build/tests/fuzz/fuzz_$h" "$build/fuzz/$h" "$top/tests/fuzz/corpus/$h" \
    -max_total_time="$seconds" -timeout=30 -max_len=8192 -print_final_stats=1 \
    -artifact_prefix="$build/fuzz/$h-" >"$build/fuzz/$h.log" 2>&1 &
  pids+=($!)
done
status=0
for i in "${!harnesses[@]}"; do
  h="${harnesses[$i]}"
  if wait "${pids[$i]}"; then
    echo "fuzz $h: $(grep -m1 -o 'Done [0-9]* runs in [0-9]* second(s)' "$build/fuzz/$h.log")"
  else
    echo "fuzz $h: a finding ($build/fuzz/$h.log):" >&2
    tail -n 40 "$build/fuzz/$h.log" >&2
    status=1
  fi
done
exit "$status"
