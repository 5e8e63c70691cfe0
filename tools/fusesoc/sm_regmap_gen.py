#!/usr/bin/env python3
"""FuseSoC generator of sm_stereo.core: the generated Verilog includes.

rtl/sm_axil_regs.v includes sm_regmap.vh, which tools/sm_regmap_gen writes from
rtl/regmap.json (the single source of truth, also used by the CMake build); most RTL
files include sm_defs.vh and sm_top includes sm_defs_check.vh, written from
rtl/defs.json (sideband layout, parameter limits, grid geometry). This
generator runs that same C++ generator, so nothing generated is committed:

- the executable named by the environment variable SM_REGMAP_GEN (the CMake build's
  build/tools/sm_regmap_gen; the ctest lint_fusesoc passes it), or else
- tools/sm_regmap_gen.cpp compiled here with c++ (the Debian packages of
  scripts/deps.sh: libfmt-dev, libcli11-dev, nlohmann-json3-dev; about 12 s), with the
  repository as its include root, as the CMake build has it (the generator includes
  header-only parts of model/ and toolio/).

A failure is one line on stderr and exit status 1 (FuseSoC then stops the setup).

It writes sm_regmap.vh and a core (sm_regmap.core) that lists it as an include file
into its working directory. FuseSoC caches the result by the contents of regmap.json
and sm_regmap_gen.cpp (cache_type input in sm_stereo.core).
"""
import os
import shutil
import subprocess
import sys


DEFAULTS = {"regmap_json": "rtl/regmap.json", "defs_json": "rtl/defs.json",
            "regmap_gen_src": "tools/sm_regmap_gen.cpp"}


def read_input(path):
    """The generator input (FuseSoC GAPI 1.0 YAML): files_root, vlnv, parameters."""
    try:
        import yaml  # fusesoc's own dependency
    except ImportError:  # a python3 without PyYAML: the top-level keys are plain scalars
        data = {}
        with open(path) as f:
            for line in f:
                k, _, v = line.partition(":")
                if k in ("files_root", "vlnv"):
                    data[k] = v.strip().strip("'\"")
    else:
        with open(path) as f:
            data = yaml.safe_load(f)
    params = dict(DEFAULTS, **(data.get("parameters") or {}))
    return data["files_root"], data["vlnv"], params


def run(cmd, what):
    """Runs cmd; a failure ends the generator with one line naming what failed."""
    try:
        subprocess.run(cmd, check=True)
    except (OSError, subprocess.CalledProcessError) as e:
        code = getattr(e, "returncode", None)
        sys.exit(f"sm_regmap_gen.py: error: {what} failed"
                 + (f" (exit status {code})" if code is not None else f": {e}"))


def generator_exe(files_root, src):
    exe = os.environ.get("SM_REGMAP_GEN")
    if exe:
        if not os.access(exe, os.X_OK):
            sys.exit(f"sm_regmap_gen.py: error: SM_REGMAP_GEN={exe} is not an executable")
        return exe
    cxx = os.environ.get("CXX") or shutil.which("c++") or shutil.which("g++")
    if not cxx:
        sys.exit("sm_regmap_gen.py: error: no C++ compiler (set SM_REGMAP_GEN to a built sm_regmap_gen)")
    exe = os.path.abspath("sm_regmap_gen")
    run([cxx, "-std=c++17", "-O1", "-I", files_root, src, "-o", exe, "-lfmt"],
        f"compiling {src} (scripts/deps.sh installs its libraries; or set SM_REGMAP_GEN)")
    return exe


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: sm_regmap_gen.py <generator input yml>")
    files_root, vlnv, params = read_input(sys.argv[1])
    exe = generator_exe(files_root, os.path.join(files_root, params["regmap_gen_src"]))
    run([exe, os.path.join(files_root, params["regmap_json"]), ".", "--defs",
         os.path.join(files_root, params["defs_json"])], f"{exe} on {params['regmap_json']}")
    # only the Verilog includes are part of the core; the C++ headers and the doc stay here
    with open("sm_regmap.core", "w") as f:
        f.write(
            "CAPI=2:\n"
            f"name: {vlnv}\n"
            "description: sm_regmap.vh, sm_defs.vh, sm_defs_check.vh generated from rtl/regmap.json, rtl/defs.json\n"
            "filesets:\n"
            "  rtl:\n"
            "    files:\n"
            "      - sm_regmap.vh: {is_include_file: true}\n"
            "      - sm_defs.vh: {is_include_file: true}\n"
            "      - sm_defs_check.vh: {is_include_file: true}\n"
            "    file_type: verilogSource\n"
            "targets:\n"
            "  default:\n"
            "    filesets: [rtl]\n"
        )


if __name__ == "__main__":
    main()
