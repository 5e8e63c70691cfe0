#!/usr/bin/env bash
# Hardware throughput at the paper configuration (docs/performance.md), from the
# cycle-accurate harness report (stereo_sim report.json): cycles per frame with a
# continuous stream and with camera timing (hblank 80 clocks, vblank 22 lines), the
# minimum clock for 30 frames/s and frames/s at 100 MHz. Cycle counts are exact (no
# medians needed). Usage: bench/throughput.sh [OUT_DIR]   (FRAMES=3)
set -euo pipefail
source "$(dirname "$0")/common.sh"
OUT=${1:-$ROOT/build-bench/throughput}
FRAMES=${FRAMES:-3}
mkdir -p "$OUT"
SIM=$LEAD/sim/stereo_sim
need "$SIM" "cmake --build $LEAD --target stereo_sim"
SCENE=$(pick "$LEAD/scene" "$BENCH/scene")
machine
nice "$SIM" --scene "$SCENE" --frames "$FRAMES" --continuous -q --out "$OUT/continuous" \
  >"$OUT/continuous.log" 2>&1 || die "stereo_sim failed, see $OUT/continuous.log"
nice "$SIM" --scene "$SCENE" --frames "$FRAMES" -q --out "$OUT/camera" \
  >"$OUT/camera.log" 2>&1 || die "stereo_sim failed, see $OUT/camera.log"
python3 - "$OUT/continuous/report.json" "$OUT/camera/report.json" <<'PY' | tee "$OUT/throughput.txt"
import json, sys
c, m = (json.load(open(p)) for p in sys.argv[1:3])
cfg = c["config"]
print(f"paper configuration {cfg['width']}x{cfg['height']}, DISP {cfg['disp']}, census {cfg['census']}, "
      f"SW {cfg['sw']}; {c['frames']} frames back to back; bit-exact vs model: "
      f"{c['bit_exact']} / {m['bit_exact']}")
print("| figure | continuous stream | camera timing (hblank %d, vblank %d lines) |" %
      (m["timing"]["hblank"], m["timing"]["vblank_lines"]))
print("|---|---|---|")
def row(name, key, fmt=str):
    print(f"| {name} | {fmt(c[key])} | {fmt(m[key])} |")
row("cycles per frame, first pixel in -> last pixel out", "cycles_per_frame_sof_to_last_pixel")
row("steady-state frame period (cycles)", "steady_state_frame_period_cycles")
row("latency (cycles)", "latency_cycles")
row("latency (line periods)", "latency_lines", lambda v: f"{v:.2f}")
row("input stall cycles", "input_stall_cycles")
row("minimum clock for 30 frames/s (MHz)", "min_clock_hz_for_30fps", lambda v: f"{v/1e6:.3f}")
print(f"| frames/s at {c['fps_at_clock']['clock_mhz']:g} MHz | {c['fps_at_clock']['fps']:.1f} | "
      f"{m['fps_at_clock']['fps']:.1f} |")
per = lambda r: r["steady_state_frame_period_cycles"] or r["cycles_per_frame_sof_to_last_pixel"]
mhz = c["fps_at_clock"]["clock_mhz"]
print(f"| frames/s at {mhz:g} MHz with this stream's blanking (clock / period) | "
      f"{mhz * 1e6 / per(c):.1f} | {mhz * 1e6 / per(m):.1f} |")
print(f"| camera pixel clock for 30 frames/s (MHz) | {c['timing']['camera_pixel_clock_hz']/1e6:.3f} | "
      f"{m['timing']['camera_pixel_clock_hz']/1e6:.3f} |")
print(f"| 30 frames/s at that clock | {c['meets_30fps_with_camera_at_core_clock']} | {m['meets_30fps_with_camera_at_core_clock']} |")
PY
