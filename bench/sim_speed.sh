#!/usr/bin/env bash
# RTL simulation speed (docs/performance.md): Verilator at the paper configuration
# (320x240, 128 levels) with one and, if built, two threads; then Verilator against
# Icarus Verilog on the same RTL at the small configuration (64x48, 16 levels), in the
# same run. Medians over RUNS (default 3) runs. Usage: bench/sim_speed.sh [OUT_DIR]
#   FRAMES=3 frames per Verilator paper run, IV_FRAMES=2 frames per Icarus run;
#   LEAD= build of the one-thread stereo_sim (and stereo_sim_small, generated headers),
#   SIM_MT= two-thread stereo_sim (default build-bench-mt/sim/stereo_sim), see common.sh.
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

# vl_runs <sim> <label> <frames> [args...]: prints "label cycles/s frames/s" medians
vl_runs() {
  local sim=$1 label=$2 frames=$3; shift 3
  local cps="" fps=""
  for k in $(seq "$RUNS"); do
    local d="$OUT/$label.$k"
    nice "$sim" --frames "$frames" --continuous --no-check -q --out "$d" "$@" >"$d.log" 2>&1 ||
      die "$sim failed, see $d.log"
    cps+=" $(jget "$d/report.json" sim_cycles_per_second)"
    fps+=" $(jget "$d/report.json" sim_frames_per_second)"
  done
  echo "$label $(echo $cps | median) $(echo $fps | median)"
}

echo "## paper configuration 320x240, DISP 128, CENSUS 15, SW 5; $FRAMES frames per run, continuous stream"
{
  vl_runs "$SIM" verilator_1thread "$FRAMES"
  if [ -x "$SIM_MT" ]; then vl_runs "$SIM_MT" verilator_2threads "$FRAMES"; fi
} | tee "$OUT/paper.txt" | awk '{printf "%-20s %12.0f cycles/s %8.3f frames/s\n", $1, $2, $3}'
if [ -x "$SIM_MT" ]; then
  awk 'NR==1{v=$2} NR==2{printf "2 threads / 1 thread (cycles/s): %.2fx\n", $2/v}' "$OUT/paper.txt"
else
  echo "(no two-thread build at $SIM_MT: cmake -S . -B build-bench-mt -DSM_SIM_THREADS=2 && cmake --build build-bench-mt --target stereo_sim)"
fi

# ---- small configuration: Verilator vs Icarus on the same RTL
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
