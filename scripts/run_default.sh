#!/usr/bin/env bash
# Quick start 1: install what is missing, build, run the default scene.
# Until the tunnel scene exists (issue 7) the default scene is the P-wave bar of Bao et al. 2012
# as a hybrid: 60 DDA blocks tied to a deal.II far-field bar with a Lysmer end.
set -euo pipefail
top="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$top/scripts/setup.sh"
"$top/scripts/build.sh"
cd "$top"
scene="${1:-examples/coupled/p_wave_bar_hybrid.yaml}"
out="${2:-results/p_wave_bar_hybrid}"
./build/ddafem check "$scene"
./build/ddafem run "$scene" -o "$out"
/usr/bin/python3 tools/plot_histories.py "$out/histories.h5" -o "$out/histories.png" --quantity stress --component xx
echo "plots: $out/histories.png, $out/histories_energy.png"
