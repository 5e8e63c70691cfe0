#!/usr/bin/env bash
# RTL simulation speed (docs/performance.md): Verilator at the paper configuration
# (320x240, 128 levels) with one and, if built, two threads and the profile-guided build
# (bench/pgo_build.sh), interleaved; then Verilator against
# Icarus Verilog on the same RTL at the small configuration (64x48, 16 levels), in the
# same run. Medians over RUNS (default 3) runs. Usage: bench/sim_speed.sh [OUT_DIR]
#   FRAMES=3 frames per Verilator paper run, IV_FRAMES=2 frames per Icarus run, SMALL=0
#   skips the small configuration (Icarus);
#   LEAD= build of the one-thread stereo_sim (and stereo_sim_small, generated headers),
#   SIM_MT= two-thread stereo_sim (default build-bench-mt/sim/stereo_sim), SIM_PGO=
#   profile-guided one-thread stereo_sim (default build-bench-pgo/sim/stereo_sim, built by
#   bench/pgo_build.sh); SIM_DEB=, SIM_DEB_MT=, SIM_DEB_PGO= the same three built with
#   Debian's Verilator 5.006 (-DSM_VERILATOR=debian), timed in the same interleaved
#   rounds when they exist; see common.sh.
set -euo pipefail
source "$(dirname "$0")/common.sh"
OUT=${1:-$ROOT/build-bench/sim_speed}
FRAMES=${FRAMES:-3}
IV_FRAMES=${IV_FRAMES:-2}
mkdir -p "$OUT"
SIM=$LEAD/sim/stereo_sim
need "$SIM" "cmake --build $LEAD --target stereo_sim"
machine
build_info "$LEAD"
[ -x "$SIM_MT" ] && build_info "$(cd "$(dirname "$SIM_MT")/.." && pwd)"
for s in "$SIM_PGO" "$SIM_DEB" "$SIM_DEB_MT" "$SIM_DEB_PGO"; do
  [ -x "$s" ] && build_info "$(cd "$(dirname "$s")/.." && pwd)"
done

# vl_run <sim> <label> <k> <frames> [args...]: one run, prints "cycles/s frames/s"
vl_run() {
  local sim=$1 label=$2 k=$3 frames=$4; shift 4
  local d="$OUT/$label.$k"
  nice "$sim" --frames "$frames" --continuous --no-check -q --out "$d" "$@" >"$d.log" 2>&1 ||
    die "$sim failed, see $d.log"
  echo "$(jget "$d/report.json" sim_cycles_per_second) $(jget "$d/report.json" sim_frames_per_second)"
}
# vl_runs <sim> <label> <frames> [args...]: prints "label cycles/s frames/s" medians
vl_runs() {
  local sim=$1 label=$2 frames=$3; shift 3
  local cps="" fps="" r
  for k in $(seq "$RUNS"); do
    r=$(vl_run "$sim" "$label" "$k" "$frames" "$@")
    cps+=" ${r% *}" fps+=" ${r#* }"
  done
  echo "$label $(echo $cps | median) $(echo $fps | median)"
}

# The paper-configuration builds run interleaved (plain, two threads, PGO, plain, ...):
# this machine's speed drifts within minutes, and interleaving spreads the drift evenly.
labels=(verilator_1thread) sims=("$SIM")
if [ -x "$SIM_MT" ]; then labels+=(verilator_2threads) sims+=("$SIM_MT"); fi
if [ -x "$SIM_PGO" ]; then labels+=(verilator_1thread_pgo) sims+=("$SIM_PGO"); fi
if [ -x "$SIM_DEB" ]; then labels+=(debian5006_1thread) sims+=("$SIM_DEB"); fi
if [ -x "$SIM_DEB_MT" ]; then labels+=(debian5006_2threads) sims+=("$SIM_DEB_MT"); fi
if [ -x "$SIM_DEB_PGO" ]; then labels+=(debian5006_1thread_pgo) sims+=("$SIM_DEB_PGO"); fi
echo "## paper configuration 320x240, DISP 128, CENSUS 15, SW 5; $FRAMES frames per run, continuous stream"
declare -A CPS FPS
for k in $(seq "$RUNS"); do
  for i in "${!labels[@]}"; do
    r=$(vl_run "${sims[$i]}" "${labels[$i]}" "$k" "$FRAMES")
    CPS[$i]+=" ${r% *}" FPS[$i]+=" ${r#* }"
  done
done
{
  for i in "${!labels[@]}"; do
    echo "${labels[$i]} $(echo ${CPS[$i]} | median) $(echo ${FPS[$i]} | median) runs:$(printf '%.0f,' ${CPS[$i]} | sed 's/,$//')"
  done
} | tee "$OUT/paper.txt" | awk '{printf "%-24s %12.0f cycles/s %8.3f frames/s  (%s)\n", $1, $2, $3, $4}'
ratio() { # ratio <label> <base label> <text>: label's cycles/s over the base's
  awk -v l="$1" -v b="$2" -v t="$3" '$1==b{v=$2} $1==l{w=$2} END{if (w && v) printf "%s (cycles/s): %.2fx\n", t, w/v}' "$OUT/paper.txt"
}
ratio verilator_2threads verilator_1thread "2 threads / 1 thread"
ratio verilator_1thread_pgo verilator_1thread "1 thread PGO / 1 thread"
ratio verilator_1thread debian5006_1thread "Verilator 5.48 / 5.006, 1 thread"
ratio verilator_2threads debian5006_2threads "Verilator 5.48 / 5.006, 2 threads"
ratio verilator_1thread_pgo debian5006_1thread_pgo "Verilator 5.48 / 5.006, 1 thread PGO"
[ -x "$SIM_MT" ] ||
  echo "(no two-thread build at $SIM_MT: cmake -S . -B build-bench-mt -DSM_SIM_THREADS=2 && cmake --build build-bench-mt --target stereo_sim)"
[ -x "$SIM_PGO" ] || echo "(no profile-guided build at $SIM_PGO: bench/pgo_build.sh)"
[ -x "$SIM_DEB" ] ||
  echo "(no Debian-Verilator build at $SIM_DEB: cmake -S . -B build-bench-deb -DSM_VERILATOR=debian && cmake --build build-bench-deb --target stereo_sim)"

# ---- small configuration: Verilator vs Icarus on the same RTL (about 25 minutes: Icarus
# runs 16 cycles/s; SMALL=0 stops after the paper configuration)
[ "${SMALL:-1}" = 0 ] && { echo "(SMALL=0: small configuration and Icarus skipped)"; exit 0; }
SMALL=$(pick "$LEAD/sim/stereo_sim_small" "$ROOT/build-bench-top/sim/stereo_sim_small")
need "$SMALL" "cmake --build $LEAD --target stereo_sim_small"
command -v iverilog >/dev/null || die "iverilog not installed (apt-get install iverilog)"
bench_build bench_icarus_vectors sm_default_scene
SCENE=$BENCH/scene_small
IV=$OUT/icarus
mkdir -p "$IV"
"$BENCH/bench/bench_icarus_vectors" --scene "$SCENE" --out "$IV" --frames "$IV_FRAMES" \
  --max-width 64 --max-height 48 --disp 16 --census 7 --sw 3 --rect-radius 4 >/dev/null
# The Icarus run reads the RTL as Verilator does; sm_top.v is copied so a declaration
# Icarus refuses (a net declared twice) can be patched without touching rtl/.
mkdir -p "$IV/rtl"
cp "$ROOT"/rtl/*.v "$IV/rtl/"
if ! iverilog -g2012 -I "$LEAD/generated" -y "$IV/rtl" -o "$IV/tb.vvp" \
    -P sm_bench_tb.FRAMES="$IV_FRAMES" -P sm_bench_tb.IN_HEX="\"$IV/in.hex\"" \
    -P sm_bench_tb.OUT_HEX="\"$IV/out.hex\"" "$ROOT/bench/sm_bench_tb.v" 2>"$IV/iverilog.log"; then
  if grep -q "'rst_n' has already been declared" "$IV/iverilog.log"; then
    # sm_top declares rst_n twice (= aresetn, then = the soft-reset register); keep the
    # second, the one its comment describes.
    awk '/^  wire rst_n = aresetn;$/ {next} {print}' "$ROOT/rtl/sm_top.v" >"$IV/rtl/sm_top.v"
    echo "note: rtl/sm_top.v declares rst_n twice; Icarus runs a copy without 'wire rst_n = aresetn;'"
    iverilog -g2012 -I "$LEAD/generated" -y "$IV/rtl" -o "$IV/tb.vvp" \
      -P sm_bench_tb.FRAMES="$IV_FRAMES" -P sm_bench_tb.IN_HEX="\"$IV/in.hex\"" \
      -P sm_bench_tb.OUT_HEX="\"$IV/out.hex\"" "$ROOT/bench/sm_bench_tb.v" 2>"$IV/iverilog.log" ||
      die "iverilog failed, see $IV/iverilog.log"
  else
    die "iverilog failed, see $IV/iverilog.log"
  fi
fi

echo "## small configuration 64x48, DISP 16, CENSUS 7, SW 3 (same RTL, same run)"
{
  vl_runs "$SMALL" verilator_small "$((IV_FRAMES * 50))" --scene "$SCENE"
  cps="" fps=""
  for k in $(seq "$RUNS"); do
    t0=$(date +%s.%N)
    nice vvp -n "$IV/tb.vvp" >"$IV/run$k.log" 2>&1 || die "vvp failed, see $IV/run$k.log"
    t1=$(date +%s.%N)
    cycles=$(sed -n 's/.* out, \([0-9]*\) cycles$/\1/p' "$IV/run$k.log")
    [ -n "$cycles" ] || die "no cycle count in $IV/run$k.log"
    cmp -s "$IV/out.hex" "$IV/expected.hex" || die "Icarus output differs from the model ($IV/out.hex vs expected.hex)"
    cps+=" $(python3 -c "print($cycles / ($t1 - $t0))")"
    fps+=" $(python3 -c "print($IV_FRAMES / ($t1 - $t0))")"
  done
  echo "icarus_small $(echo $cps | median) $(echo $fps | median)"
} | tee "$OUT/small.txt" | awk '{printf "%-20s %12.0f cycles/s %8.3f frames/s\n", $1, $2, $3}'
echo "Icarus output identical to the model: yes ($IV_FRAMES frames, every pixel)"
awk 'NR==1{v=$2} NR==2{printf "Verilator / Icarus (cycles/s): %.0fx\n", v/$2}' "$OUT/small.txt"
echo "load at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
