#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs (only what is missing).
set -euo pipefail
pkgs=(build-essential cmake verilator yosys iverilog libopencv-dev libopencv-contrib-dev
      catch2 libfmt-dev libcli11-dev nlohmann-json3-dev clang-format)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}"
fi
