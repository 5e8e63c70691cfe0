#!/usr/bin/env bash
# Lints every RTL module on its own with verilator --lint-only -Wall, at its default
# parameters. Usage: lint_rtl.sh <rtl dir> [generated dir]
# VERILATOR= the Verilator to run (default: verilator on PATH); its version is printed.
set -u
verilator=${VERILATOR:-verilator}
rtl=${1:?usage: lint_rtl.sh <rtl dir> [generated dir]}
gen=${2:-}
inc=(-y "$rtl")
[ -n "$gen" ] && inc+=(-y "$gen" -I"$gen")
echo "$("$verilator" --version)"
fail=0; n=0
for f in "$rtl"/*.v; do
  m=$(basename "$f" .v)
  n=$((n + 1))
  if ! out=$("$verilator" --lint-only -Wall "${inc[@]}" --top-module "$m" "$f" 2>&1); then
    echo "LINT FAIL $m"; echo "$out"; fail=$((fail + 1))
  fi
done
echo "lint: $((n - fail)) passed, $fail failed"
[ "$fail" -eq 0 ]
