#!/usr/bin/env python3
"""stereo_model's point cloud read back by an independent reader (plyfile, PyPI).

Renders a synthetic scene with a known camera (sm_scene --focal-px --baseline-m), runs
stereo_model --depth-file (float PFM) --cloud (binary PLY), with and without
--cloud-max-depth, and checks with plyfile that the cloud is a binary little-endian PLY
with float x, y, z and uchar intensity, one vertex per pixel of finite depth (within the
cut), in raster order, each at ((x - cx) Z / f, (y - cy) Z / f, Z) of the depth file.
Exit 0 when all checks pass; otherwise the failed checks are printed and the exit is 1.
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import plyfile


def read_pfm(path):
    """A one-channel PFM ("Pf"), rows stored bottom to top; returns rows top to bottom."""
    with open(path, "rb") as f:
        if f.readline().strip() != b"Pf":
            raise ValueError(f"{path}: not a one-channel PFM")
        w, h = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(w * h * 4), dtype="<f4" if scale < 0 else ">f4")
    return np.flipud(data.reshape(h, w))


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--scene-exe", required=True)
    ap.add_argument("--model-exe", required=True)
    ap.add_argument("--work", required=True, type=pathlib.Path)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    a.work.mkdir(parents=True)
    scene = a.work / "scene"
    subprocess.run([a.scene_exe, "--out", str(scene), "--width", "96", "--height", "64", "--levels", "32",
                    "--seed", "4", "--focal-px", "120", "--baseline-m", "0.2"], check=True)
    cam = json.loads((scene / "calib.json").read_text())["camera"]
    base = [a.model_exe, str(scene / "left.png"), str(scene / "right.png"), "--disp", "32",
            "--calib", str(scene / "calib.json"), "--depth-file", str(a.work / "z.pfm")]
    subprocess.run(base + ["--cloud", str(a.work / "all.ply")], check=True)
    subprocess.run(base + ["--cloud", str(a.work / "near.ply"), "--cloud-max-depth", "1.5"], check=True)
    z = read_pfm(a.work / "z.pfm")
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    for name, cut in (("all.ply", np.inf), ("near.ply", 1.5)):
        ply = plyfile.PlyData.read(str(a.work / name))
        check(not ply.text and ply.byte_order == "<", f"{name}: not binary little-endian")
        check([e.name for e in ply.elements] == ["vertex"], f"{name}: elements {[e.name for e in ply.elements]}")
        v = ply["vertex"].data
        check(v.dtype.names == ("x", "y", "z", "intensity"), f"{name}: properties {v.dtype.names}")
        check([v.dtype[k].kind + str(v.dtype[k].itemsize) for k in v.dtype.names] == ["f4", "f4", "f4", "u1"],
              f"{name}: property types {v.dtype}")
        keep = np.isfinite(z) & (z <= cut)
        ys, xs = np.nonzero(keep)  # raster order
        check(len(v) == keep.sum(), f"{name}: {len(v)} vertices, {keep.sum()} pixels of finite depth <= {cut}")
        if len(v) != keep.sum():
            continue
        zz = z[keep].astype(np.float64)
        f, cx, cy = cam["f_px"], cam["cx"], cam["cy"]
        for k, want in (("x", (xs - cx) * zz / f), ("y", (ys - cy) * zz / f), ("z", zz)):
            err = np.max(np.abs(v[k] - want)) if len(v) else 0.0
            check(err <= 1e-5 * max(1.0, np.max(np.abs(want), initial=0)), f"{name}: {k} off by up to {err}")
        print(f"{name}: {len(v)} vertices of {z.size} pixels, Z {zz.min():.3f}..{zz.max():.3f} m")
    check(len(plyfile.PlyData.read(str(a.work / "near.ply"))["vertex"]) <
          len(plyfile.PlyData.read(str(a.work / "all.ply"))["vertex"]), "the depth cut removed no vertex")
    for msg in failures:
        print("FAILED:", msg)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
