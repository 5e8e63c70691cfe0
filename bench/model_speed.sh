#!/usr/bin/env bash
# Model speed (docs/performance.md): the reference model (per stage) on 1 thread and on
# THREADS (default 2) against OpenCV StereoSGBM and StereoBinarySGBM on 1 thread,
# 320x240, 128 levels, interleaved in the same run, medians of RUNS (default 7).
# Usage: bench/model_speed.sh [SCENE_DIR] [OUT_DIR]
set -euo pipefail
RUNS=${RUNS:-7}
THREADS=${THREADS:-2}
source "$(dirname "$0")/common.sh"
bench_build bench_model_speed sm_default_scene
SCENE=${1:-$BENCH/scene}
OUT=${2:-$ROOT/build-bench/model_speed}
mkdir -p "$OUT"
machine
nice "$BENCH/bench/bench_model_speed" --scene "$SCENE" --runs "$RUNS" --threads "$THREADS" --json "$OUT/model_speed.json" |
  tee "$OUT/model_speed.txt"
