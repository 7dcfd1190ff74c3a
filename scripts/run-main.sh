#!/usr/bin/env bash
# The main job: install what is missing, build, and run the S1 circle
# experiment (Table 3) on the emulated I/O board, writing its plots.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target tnv-hil
./build/release/tools/tnv-hil table3 --plot-dir out/plots "$@"
echo "plots: $(pwd)/out/plots/circle-*.svg"
