#!/usr/bin/env bash
# Quick start 1: install what is missing, build, run the default scene and write its report.
# The default scene is the tunnel of examples/tunnel/circular_sv.yaml: a circular tunnel in rock
# cut by two joint sets, excavated (static stage), hit by an SV pulse (dynamic stage), then left
# to settle (settle stage).
#   bash scripts/run_default.sh [SCENE [OUTPUT_DIR]]
set -euo pipefail
top="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$top/scripts/setup.sh"
"$top/scripts/build.sh"
cd "$top"
scene="${1:-examples/tunnel/circular_sv.yaml}"
out="${2:-results/$(basename "$scene" .yaml)}"
./build/ddafem check "$scene"
./build/ddafem run "$scene" -o "$out"
/usr/bin/python3 tools/report.py "$out"
echo "report: $out/report.md (ParaView: $out/model.pvd, or pvpython tools/paraview_open.py $out)"
