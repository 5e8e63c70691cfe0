#!/usr/bin/env bash
# Lints every RTL module on its own with verilator --lint-only -Wall, at its default
# parameters, and checks the house rules a linter does not: the first line is
# `default_nettype none, the last is `default_nettype wire, and the module is named after
# its file; then the modules again at the parameters listed in lint_params.txt beside this
# script (limits where a construct behaves differently). Usage: lint_rtl.sh <rtl dir> [generated dir]
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
  if [ "$(head -n1 "$f")" != '`default_nettype none' ] || [ "$(tail -n1 "$f")" != '`default_nettype wire' ]; then
    echo "RULE FAIL $m: the file must open with \`default_nettype none and close with \`default_nettype wire"
    fail=$((fail + 1)); continue
  fi
  if ! grep -q "^module $m\b" "$f"; then
    echo "RULE FAIL $m: no module named after the file"; fail=$((fail + 1)); continue
  fi
  if ! out=$("$verilator" --lint-only -Wall "${inc[@]}" --top-module "$m" "$f" 2>&1); then
    echo "LINT FAIL $m"; echo "$out"; fail=$((fail + 1))
  fi
done
while read -r m params; do
  case "$m" in '' | '#'*) continue ;; esac
  n=$((n + 1))
  # shellcheck disable=SC2086  # the -G overrides are separate words
  if ! out=$("$verilator" --lint-only -Wall "${inc[@]}" --top-module "$m" $params "$rtl/$m.v" 2>&1); then
    echo "LINT FAIL $m $params"; echo "$out"; fail=$((fail + 1))
  fi
done < "$(dirname "$0")/lint_params.txt"
echo "lint: $((n - fail)) passed, $fail failed"
[ "$fail" -eq 0 ]
