#!/usr/bin/env bash
# Checks that every C++ source of the project follows .clang-format; changes nothing.
# Usage: check_format.sh [clang-format executable]. To fix: the same files, clang-format -i.
set -euo pipefail
cf=${1:-clang-format}
cd "$(dirname "$0")/.."
mapfile -t files < <(find model sim tests tools toolio bench \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \) | sort)
[ ${#files[@]} -gt 0 ] || { echo "check_format: no C++ files found" >&2; exit 1; }
"$cf" --dry-run --Werror --style=file "${files[@]}"
echo "format: ${#files[@]} files follow .clang-format"
