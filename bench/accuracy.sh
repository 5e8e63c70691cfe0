#!/usr/bin/env bash
# Accuracy tables (docs/performance.md): (1) bad-1.0 of the model and the OpenCV peers on
# the evaluation dataset at full size, 128 levels; (2) the model after each stage of the
# post-processing chain; (3) the same scenes at the IP's 320x240, scored from the model
# and from the cycle-accurate RTL simulation (stereo_sim, paper configuration), which
# must agree pixel for pixel. Usage: bench/accuracy.sh [OUT_DIR]   (DATASETS=... to override)
set -euo pipefail
source "$(dirname "$0")/common.sh"
OUT=${1:-$ROOT/build-bench/accuracy}
mkdir -p "$OUT"
[ -d "$DATASETS" ] || die "$DATASETS: no such folder (set DATASETS=)"
bench_build sm_evaluate bench_stage_accuracy bench_scale_dataset sm_default_scene
SIM=$LEAD/sim/stereo_sim
need "$SIM" "cmake --build $LEAD --target stereo_sim"
machine

echo "## 1. full size, 128 levels: bad-1.0 % (invalid %), model vs OpenCV"
nice "$BENCH/tools/sm_evaluate" "$DATASETS" --peer-levels 128 --json "$OUT/full.json" -q | tee "$OUT/full.txt"

echo
echo "## 2. model per stage, full size, 128 levels: bad-1.0 %"
nice "$BENCH/bench/bench_stage_accuracy" "$DATASETS" --json "$OUT/stages.json" | tee "$OUT/stages.txt"

echo
echo "## 3. at 320x240 (the paper configuration): model vs RTL simulation"
"$BENCH/bench/bench_scale_dataset" "$DATASETS" --out "$OUT/ds320" >/dev/null
nice "$BENCH/tools/sm_evaluate" "$OUT/ds320" --methods model --json "$OUT/model320.json" -q >/dev/null
# The RTL's output is the checked word (docs/algorithm.md 9.4: invalid pixels count as
# bad), so it is scored against the model's checked output (model_checked).
python3 - "$OUT/full.json" "$OUT/model320.json" >"$OUT/model_by_scene.txt" <<'PY'
import json, sys
full = {s["name"]: s["methods"]["model_checked"]["bad1_pct"] for s in json.load(open(sys.argv[1]))["scenes"]}
m320 = {s["name"]: s["methods"]["model_checked"]["bad1_pct"] for s in json.load(open(sys.argv[2]))["scenes"]}
for n in sorted(m320):
    print(n, full.get(n, float("nan")), m320[n])
PY
echo "| scene | model (checked), full size | model (checked), 320x240 | RTL (stereo_sim), 320x240 | RTL bit-exact vs model |"
echo "|---|---|---|---|---|"
all_same=1
while read -r name full m320; do
  d="$OUT/rtl_$name"
  nice "$SIM" --scene "$OUT/ds320/$name" --frames 1 -q --out "$d" >"$d.log" 2>&1 ||
    die "stereo_sim failed on $name, see $d.log"
  rtl=$(jget "$d/report.json" bad1_percent)
  exact=$(jget "$d/report.json" bit_exact)
  same=$(python3 -c "print('yes' if abs($rtl - $m320) < 1e-9 and '$exact' == 'True' else 'NO')")
  [ "$same" = yes ] || all_same=0
  printf "| %s | %.2f | %.2f | %.2f | %s |\n" "$name" "$full" "$m320" "$rtl" \
    "$([ "$exact" = True ] && echo yes || echo NO)"
done <"$OUT/model_by_scene.txt" | tee "$OUT/rtl320.txt"
# The built-in synthetic scene is already 320x240.
d="$OUT/rtl_builtin"
nice "$SIM" --scene "$BENCH/scene" --frames 1 -q --out "$d" >"$d.log" 2>&1 || die "stereo_sim failed, see $d.log"
m=$(nice "$BENCH/tools/sm_evaluate" "$BENCH/scene" --methods model --json "$OUT/model_builtin.json" -q >/dev/null &&
    python3 -c "import json; print(json.load(open('$OUT/model_builtin.json'))['scenes'][0]['methods']['model_checked']['bad1_pct'])")
printf "| built-in synthetic scene | - | %.2f | %.2f | %s |\n" "$m" "$(jget "$d/report.json" bad1_percent)" \
  "$([ "$(jget "$d/report.json" bit_exact)" = True ] && echo yes || echo NO)" | tee -a "$OUT/rtl320.txt"
[ "$all_same" = 1 ] && echo "RTL and model scores identical on every scene" || die "RTL and model differ"
