#!/usr/bin/env bash
# Model speed (docs/performance.md): the reference model (per stage) against OpenCV
# StereoSGBM and StereoBinarySGBM, 320x240, 128 levels, one thread, interleaved in the
# same run, medians of RUNS (default 7). Usage: bench/model_speed.sh [SCENE_DIR] [OUT_DIR]
set -euo pipefail
RUNS=${RUNS:-7}
source "$(dirname "$0")/common.sh"
bench_build bench_model_speed sm_default_scene
SCENE=${1:-$BENCH/scene}
OUT=${2:-$ROOT/build-bench/model_speed}
mkdir -p "$OUT"
machine
nice "$BENCH/bench/bench_model_speed" --scene "$SCENE" --runs "$RUNS" --json "$OUT/model_speed.json" |
  tee "$OUT/model_speed.txt"
