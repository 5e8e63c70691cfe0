#!/usr/bin/env bash
# Installs what is missing, builds the simulator of the IP at the paper configuration
# (320x240, 128 levels, 15x15 census, 5x5 support weight) and runs it on the built-in
# synthetic stereo scene: two frames at 30 frames/s camera timing, every pixel checked
# against the reference model. Extra arguments go to stereo_sim (see --help).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target stereo_sim sm_default_scene
exec build/sim/stereo_sim --scene build/scene --out out --vcd waves/top.vcd --vcd-line 120 --vcd-cycles 200 "$@"
