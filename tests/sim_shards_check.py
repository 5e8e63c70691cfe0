#!/usr/bin/env python3
"""Frame-parallel stereo_sim runs give the serial run's per-frame results (issue 41).

A 12-frame sequence of three small synthetic scenes (one with a rotated right camera and
its calibration) with a register schedule whose changes fall on both sides of the shard
boundary at frame 6 (frames 5, 6 and 7: new values, new rectification grids, a grid bank
switch) is simulated serially, then in two shards (--mode jobs: stereo_sim --jobs 2;
--mode farm: tools/sm_farm.py shards on a 2-worker LocalCluster). The per-frame parts of
report.json (registers, what the host changed, object packet, bit-exactness) and every
per-frame disparity file must be identical; the merged report covers all 12 frames and
takes its timing figures from the first shard. --mode jobs also checks all-or-nothing: a
sequence whose frame 9 cannot be read fails in the second shard with one error line, a
non-zero exit and no merged output. --mode farm also kills the second shard's first
stereo_sim (then, with --worker-processes, its worker process): the run is retried and
equals the serial one; with --retries 0 it fails with one error line and no output, and
no Dask log line follows a closed cluster. --mode farm-cli checks sm_farm.py's command
line on a 4-frame sequence: an --out that is or holds an input, a --scheduler address
without a port or with one outside 1..65535 and a register given twice in --grid are each
refused with one error line and exit 2 before any stereo_sim runs, the inputs untouched;
a run into a folder holding other files keeps them and writes what stereo_sim --jobs 2
writes there.
"""
import argparse
import filecmp
import hashlib
import json
import os
import shutil
import subprocess
import sys
import time

FAILS = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        FAILS.append(what)


def run(args, ok=(0,)):
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode not in ok:
        print(" ".join(args), "\n", p.stdout, p.stderr)
        sys.exit(f"exit {p.returncode}")
    return p


def make_inputs(sm_scene, tmp):
    scenes = {}
    for name, extra in (("plain", []), ("raw", ["--rot-deg", "1.5", "--vshift", "1.5"]), ("many", [])):
        d = os.path.join(tmp, name)
        seed = "2" if name == "many" else "3"
        run([sm_scene, "--out", d, "--width", "64", "--height", "48", "--levels", "16", "--seed", seed, "--objects",
             "3", *extra])
        scenes[name] = d
    seq = os.path.join(tmp, "seq12")
    os.makedirs(seq)
    order = ["plain", "raw", "many"]
    for i in range(12):
        s = scenes[order[i % 3]]
        shutil.copy(os.path.join(s, "left.png"), os.path.join(seq, f"left_{i:03d}.png"))
        shutil.copy(os.path.join(s, "right.png"), os.path.join(seq, f"right_{i:03d}.png"))
    regs = {5: {"occ": 20, "offset_r": -3},
            6: {"calib": os.path.join(scenes["raw"], "calib.json"), "obj_near": 6, "obj_min_pixels": 8},
            7: {"calib": os.path.join(scenes["plain"], "calib.json"), "filter_enable": 5}}
    args = ["--sequence", seq, "--disp-each-frame"]
    for f, r in regs.items():
        p = os.path.join(tmp, f"regs_{f}.json")
        with open(p, "w") as fh:
            json.dump(r, fh)
        args += ["--regs-at", f"{f}={p}"]
    return seq, args


def compare(serial, par, label):
    a = json.load(open(os.path.join(serial, "report.json")))
    b = json.load(open(os.path.join(par, "report.json")))
    check(a["frames"] == 12 and b["frames"] == 12, f"{label}: 12 frames in both reports")
    check(a["bit_exact"] is True and b["bit_exact"] is True, f"{label}: both bit-exact against the model")
    # a shard counts cycles from its own reset: frame cycles match the serial run's in
    # the first shard only, every other per-frame field in all of them
    n0 = b["shards"][0]["count"]
    strip = [{k: v for k, v in fr.items() if k != "cycles" or fr["frame"] < n0} for fr in b["frame_results"]]
    want = [{k: v for k, v in fr.items() if k != "cycles" or fr["frame"] < n0} for fr in a["frame_results"]]
    check(len(a["frame_results"]) == 12 and want == strip,
          f"{label}: per-frame results (registers, changes, object packets and notes, bit-exactness) identical")
    check(all("cycles" in fr for fr in b["frame_results"]) and "frame_cycles_note" in b,
          f"{label}: every frame's cycles, with the note on their clock")
    for pic in ("disparity.png", "disparity_color.png", "panel.png"):
        check(filecmp.cmp(os.path.join(serial, pic), os.path.join(par, pic), shallow=False),
              f"{label}: {pic} identical")
    changed = [fr["frame"] for fr in b["frame_results"] if fr["changed"]]
    check(changed == [5, 6, 7], f"{label}: register changes at frames 5, 6, 7 across the boundary ({changed})")
    check([s["first"] for s in b["shards"]] == [0, 6], f"{label}: two shards, frames 0..5 and 6..11")
    check(b["timing_frames"]["count"] == 6 and b["cycles_per_frame_sof_to_last_pixel"] ==
          a["cycles_per_frame_sof_to_last_pixel"], f"{label}: timing figures from the first shard")
    same = all(filecmp.cmp(os.path.join(serial, f"disparity_{f:03d}.pfm"), os.path.join(par, f"disparity_{f:03d}.pfm"),
                           shallow=False) for f in range(12))
    check(same, f"{label}: the 12 per-frame disparity files identical")
    check(filecmp.cmp(os.path.join(serial, "disparity.pfm"), os.path.join(par, "disparity.pfm"), shallow=False),
          f"{label}: last frame's disparity identical")


def failing_shard(sim, seq, tmp):
    bad = os.path.join(tmp, "seq_bad")
    shutil.copytree(seq, bad)
    with open(os.path.join(bad, "left_009.png"), "wb") as f:
        f.write(b"not a png")
    out = os.path.join(tmp, "bad_out")
    p = subprocess.run([sim, "--sequence", bad, "--jobs", "2", "--out", out, "-q"], capture_output=True, text=True)
    lines = [ln for ln in p.stderr.splitlines() if ln.strip()]
    check(p.returncode == 2, f"a failing shard: exit 2 ({p.returncode})")
    check(len(lines) == 1 and lines[0].startswith("stereo_sim: error: shard 1 (frames 6..11)"),
          f"a failing shard: one error line naming it ({lines})")
    check(not os.path.exists(os.path.join(out, "report.json")), "a failing shard: no merged report")
    left = [n for n in os.listdir(tmp) if ".jobs" in n]
    check(not left, f"a failing shard: no shard folders left ({left})")


def farm_scenes(o, tmp):
    """sm_farm.py accuracy on two scenes equals stereo_sim run on each; a refused register
    value in a sweep is one error line, exit 2 and no output."""
    ds = os.path.join(tmp, "dataset")
    os.makedirs(ds)
    for name in ("plain", "many"):
        shutil.copytree(os.path.join(tmp, name), os.path.join(ds, name))
    acc = os.path.join(tmp, "acc")
    run([sys.executable, o.farm, "--workers", "2", "-q", "accuracy", ds, "--stereo-sim", o.stereo_sim, "--out", acc])
    got = {s["name"]: s for s in json.load(open(os.path.join(acc, "summary.json")))["scenes"]}
    for name in ("plain", "many"):
        d = os.path.join(tmp, f"direct_{name}")
        run([o.stereo_sim, "--scene", os.path.join(ds, name), "--frames", "1", "-q", "--out", d])
        want = json.load(open(os.path.join(d, "report.json")))
        check(got[name]["bad1_percent"] == want["bad1_percent"] and got[name]["bit_exact"] is True,
              f"sm_farm.py accuracy, scene {name}: bad-1.0 {got[name]['bad1_percent']} as stereo_sim's")
    bad = os.path.join(tmp, "sweep_bad")
    p = subprocess.run([sys.executable, o.farm, "--workers", "2", "-q", "sweep", ds, "--rtl", o.stereo_sim, "--grid",
                        "occ=8,999", "--out", bad], capture_output=True, text=True)
    lines = [ln for ln in p.stderr.splitlines() if ln.strip()]
    check(p.returncode == 2 and len(lines) == 1 and "'occ' = 999" in lines[0],
          f"sm_farm.py sweep with occ=999: exit 2, one error line ({p.returncode}, {lines})")
    check(not os.path.exists(bad), "sm_farm.py sweep with occ=999: no output folder")
    # a --regs after --: the base of every point, the grid's values on top
    base = os.path.join(tmp, "base.json")
    json.dump({"filter_enable": 5, "occ": 3}, open(base, "w"))
    sw = os.path.join(tmp, "sweep_base")
    run([sys.executable, o.farm, "--workers", "2", "-q", "sweep", ds, "--rtl", o.stereo_sim, "--grid", "occ=9",
         "--out", sw, "--", "--regs", base])
    point = json.load(open(os.path.join(sw, "summary.json")))["points"][0]
    merged = os.path.join(tmp, "base_occ9.json")
    json.dump({"filter_enable": 5, "occ": 9}, open(merged, "w"))
    want = []
    for name in ("plain", "many"):
        d = os.path.join(tmp, f"direct_base_{name}")
        run([o.stereo_sim, "--scene", os.path.join(ds, name), "--frames", "1", "-q", "--regs", merged, "--out", d])
        want.append(json.load(open(os.path.join(d, "report.json")))["bad1_percent"])
    check(point["rtl_bit_exact"] is True and abs(point["mean_bad1_percent"] - sum(want) / 2) < 1e-9,
          f"sm_farm.py sweep on a --regs base: {point['mean_bad1_percent']} as stereo_sim with the merged file")


def killing_sim(o, tmp, target):
    """A stereo_sim wrapper whose first run of the second shard (frames 6..11) is killed with
    SIGKILL: itself (target "$$", as the kernel's OOM killer would) or the worker process
    that started it (target "$PPID"); later runs are stereo_sim's. Returns (wrapper, mark):
    `mark` exists once the kill happened."""
    mark = os.path.join(tmp, f"killed_{'worker' if target == '$PPID' else 'sim'}")
    path = mark + ".sh"
    with open(path, "w") as f:
        f.write("#!/bin/sh\n"
                f'if [ ! -e "{mark}" ]; then\n'
                '  prev=""\n'
                '  for a in "$@"; do\n'
                f'    if [ "$prev" = "--frame-range" ] && [ "$a" = "6:12" ]; then touch "{mark}"; kill -9 {target}; '
                'kill -9 $$; fi\n'
                '    prev="$a"\n'
                '  done\n'
                'fi\n'
                f'exec "{o.stereo_sim}" "$@"\n')
    os.chmod(path, 0o755)
    return path, mark


def farm_retries(o, tmp, serial, args):
    """A shard whose stereo_sim is killed is run again (--retries), with the LocalCluster's
    worker threads and, when the worker process itself dies, with --worker-processes; with
    --retries 0 the killed shard fails the run: exit 2, one error line, no output."""
    sim, mark = killing_sim(o, tmp, "$$")
    out = os.path.join(tmp, "farm_killed")
    run([sys.executable, o.farm, "--workers", "2", "-q", "shards", "--stereo-sim", sim, "--shards", "2", "--out", out,
         "--", *args])
    check(os.path.exists(mark), "sm_farm.py shards: the second shard's first stereo_sim was killed")
    compare(serial, out, "sm_farm.py shards, a killed shard run again")
    os.remove(mark)
    out0 = os.path.join(tmp, "farm_killed_noretry")
    p = subprocess.run([sys.executable, o.farm, "--workers", "2", "-q", "--retries", "0", "shards", "--stereo-sim", sim,
                        "--shards", "2", "--out", out0, "--", *args], capture_output=True, text=True)
    lines = [ln for ln in p.stderr.splitlines() if ln.strip()]
    check(p.returncode == 2 and len(lines) == 1 and lines[0].startswith("sm_farm: error: task shard1 failed:") and
          "killed by signal 9" in lines[0], f"sm_farm.py --retries 0, a killed shard: exit 2, one error line "
          f"({p.returncode}, {lines})")
    check(not os.path.exists(out0), "sm_farm.py --retries 0, a killed shard: no output folder")
    sim, mark = killing_sim(o, tmp, "$PPID")
    out = os.path.join(tmp, "farm_worker_died")
    # --retries 0: only Dask's rescheduling of a lost worker's task can complete the run
    run([sys.executable, o.farm, "--workers", "2", "--worker-processes", "--retries", "0", "-q", "shards",
         "--stereo-sim", sim, "--shards", "2", "--out", out, "--", *args])
    check(os.path.exists(mark), "sm_farm.py --worker-processes: the worker running the second shard was killed")
    compare(serial, out, "sm_farm.py --worker-processes --retries 0 shards, a worker killed mid-shard")


LATE_LOG = """
import logging, sys
sys.path.insert(0, sys.argv[1])
import sm_farm
class Opts:
    scheduler, workers, worker_processes = None, 1, False
client, cluster = sm_farm.make_client(Opts())
client.close()
cluster.close()
logging.getLogger("distributed.batched").info("a comm closing after the cluster")
logging.getLogger("distributed.client").warning("a client warning after the cluster")
"""


def farm_late_logs(o):
    """Dask's log lines stay off after the LocalCluster closed: a comm that a killed task
    left closing logged an INFO line and a traceback after the error line (a CI run of
    the --retries 0 case above, a race that the case itself does not reproduce)."""
    p = subprocess.run([sys.executable, "-c", LATE_LOG, os.path.dirname(os.path.abspath(o.farm))],
                       capture_output=True, text=True)
    check(p.returncode == 0 and not p.stderr.strip(),
          f"sm_farm.py: no Dask log line after its cluster closed ({p.returncode}, {p.stderr.strip()[:200]!r})")


def tree(root):
    """Every file and folder under `root`: relative path -> sha256 of its bytes (None: a folder)."""
    t = {}
    for d, dirs, names in os.walk(root):
        for n in dirs:
            t[os.path.relpath(os.path.join(d, n), root)] = None
        for n in names:
            with open(os.path.join(d, n), "rb") as f:
                t[os.path.relpath(os.path.join(d, n), root)] = hashlib.sha256(f.read()).hexdigest()
    return t


def farm_refusals(o, tmp, inputs, seq, scene):
    """Bad sm_farm.py command lines: exit 2 and one error line, before any work (no
    stereo_sim run, not even --list-shards: a wrapper logs its runs) and with every
    file under `inputs` as it was. `inputs` is made again before each case, so that each
    checks its own refusal even where the tool destroyed them."""
    log = os.path.join(tmp, "sim_runs.log")
    sim = os.path.join(tmp, "logging_sim.sh")
    with open(sim, "w") as f:
        f.write(f'#!/bin/sh\necho "$@" >> "{log}"\nexec "{o.stereo_sim}" "$@"\n')
    os.chmod(sim, 0o755)
    regs = os.path.join(inputs, "notes", "regs.json")
    ds = os.path.join(inputs, "dataset")
    farm = [sys.executable, o.farm, "--workers", "2", "-q"]
    shards = ["shards", "--stereo-sim", sim, "--shards", "2"]
    cases = [
        ("--out the --sequence folder (the audit's run: all inputs deleted)",
         farm + shards + ["--out", seq, "--", "--sequence", seq], f"--out {seq}: is the input --sequence {seq}"),
        ("--out the folder holding the --sequence folder",
         farm + shards + ["--out", inputs, "--", f"--sequence={seq}"],
         f"--out {inputs}: contains the input --sequence"),
        ("--out holding a --regs-at file", farm + shards + ["--out", os.path.dirname(regs), "--", "--sequence", seq,
                                                           "--regs-at", f"1={regs}", f"2={regs}"],
         "contains the input --regs-at"),
        ("--out the folder of --left/--right", farm + shards + ["--out", scene, "--", "--left",
                                                               os.path.join(scene, "left.png"), "--right",
                                                               os.path.join(scene, "right.png")],
         f"--out {scene}: contains the input --left"),
        ("accuracy, --out a scene of the dataset", farm + ["accuracy", ds, "--stereo-sim", sim, "--out",
                                                          os.path.join(ds, "s1")], "is the input scene"),
        ("--scheduler notanaddress", [sys.executable, o.farm, "--scheduler", "notanaddress", "-q"] + shards +
         ["--out", os.path.join(tmp, "out_sched"), "--", "--sequence", seq], "--scheduler notanaddress: "),
        ("--scheduler tcp://127.0.0.1:99999", [sys.executable, o.farm, "--scheduler", "tcp://127.0.0.1:99999", "-q"] +
         shards + ["--out", os.path.join(tmp, "out_sched"), "--", "--sequence", seq],
         "--scheduler tcp://127.0.0.1:99999: port 99999 is outside 1..65535"),
        ("sweep --grid occ=8 --grid occ=11", farm + ["sweep", ds, "--rtl", sim, "--grid", "occ=8", "--grid", "occ=11",
                                                    "--out", os.path.join(tmp, "out_sweep")],
         "--grid occ=11: register occ given twice"),
        ("sweep --grid OCC=8 --grid occ=11", farm + ["sweep", ds, "--rtl", sim, "--grid", "OCC=8", "--grid", "occ=11",
                                                    "--out", os.path.join(tmp, "out_sweep")], "given twice"),
    ]
    pristine = inputs + ".pristine"
    shutil.copytree(inputs, pristine)
    for what, args, want in cases:
        shutil.rmtree(inputs)
        shutil.copytree(pristine, inputs)
        before = tree(inputs)
        t0 = time.monotonic()
        p = subprocess.run(args, capture_output=True, text=True, timeout=120)
        el = time.monotonic() - t0
        lines = [ln for ln in p.stderr.splitlines() if ln.strip()]
        check(p.returncode == 2 and len(lines) == 1 and lines[0].startswith("sm_farm: error: ") and want in lines[0]
              and not p.stdout, f"sm_farm.py {what}: exit 2, one error line with '{want}' "
              f"({p.returncode}, {lines[:3]}, stdout {p.stdout[:80]!r})")
        check(el < 15, f"sm_farm.py {what}: refused at once ({el:.1f} s)")
        check(not os.path.exists(log), f"sm_farm.py {what}: no stereo_sim run before the refusal")
        check(tree(inputs) == before, f"sm_farm.py {what}: every input file and folder as it was")
        check(not any(os.path.exists(os.path.join(tmp, n)) for n in ("out_sched", "out_sweep")),
              f"sm_farm.py {what}: no output folder")
        if os.path.exists(log):
            os.remove(log)
    shutil.rmtree(inputs)
    shutil.copytree(pristine, inputs)


def farm_out_kept(o, tmp, seq):
    """sm_farm.py shards into a folder holding other files (notes, a subfolder, an old
    run's report and per-frame disparity) against stereo_sim --jobs 2 into a copy of it:
    the same files with the same bytes (report.json: the same per-frame results), the
    other files kept."""
    outs = {}
    for name in ("jobs_out", "farm_out"):
        d = os.path.join(tmp, name)
        os.makedirs(os.path.join(d, "sub"))
        for rel, text in (("notes.txt", "notes\n"), ("sub/keep.txt", "keep\n"), ("report.json", "{}\n"),
                          ("disparity_009.pfm", "an old run's\n")):
            with open(os.path.join(d, rel), "w") as f:
                f.write(text)
        outs[name] = d
    args = ["--sequence", seq, "--disp-each-frame"]
    run([o.stereo_sim, *args, "--jobs", "2", "--out", outs["jobs_out"], "-q"])
    run([sys.executable, o.farm, "--workers", "2", "-q", "shards", "--stereo-sim", o.stereo_sim, "--shards", "2",
         "--out", outs["farm_out"], "--", *args])
    a, b = tree(outs["jobs_out"]), tree(outs["farm_out"])
    check(sorted(a) == sorted(b), f"sm_farm.py shards into a used folder: the files of stereo_sim --jobs 2 "
          f"({sorted(set(a) ^ set(b))} differ)")
    for rel, text in (("notes.txt", "notes\n"), ("sub/keep.txt", "keep\n"), ("disparity_009.pfm", "an old run's\n")):
        p = os.path.join(outs["farm_out"], rel)
        check(os.path.isfile(p) and open(p).read() == text, f"sm_farm.py shards into a used folder: {rel} kept")
    same = [r for r in a if r != "report.json" and a[r] is not None and a[r] == b.get(r)]
    check(len(same) == len(a) - 2, f"sm_farm.py shards into a used folder: every output but report.json identical "
          f"to stereo_sim --jobs 2's ({len(same)} of {len(a) - 2})")
    ra, rb = (json.load(open(os.path.join(outs[n], "report.json"))) for n in ("jobs_out", "farm_out"))
    check(rb.get("frames") == 4 and ra.get("frame_results") == rb.get("frame_results"),
          "sm_farm.py shards into a used folder: the new report.json, per-frame results as stereo_sim --jobs 2's")
    left = [n for n in os.listdir(tmp) if ".farm" in n]
    check(not left, f"sm_farm.py shards into a used folder: no temporary folder left ({left})")


def farm_cli(o, tmp):
    inputs = os.path.join(tmp, "in")
    scene = os.path.join(inputs, "scene")
    run([o.sm_scene, "--out", scene, "--width", "64", "--height", "48", "--levels", "16"])
    seq = os.path.join(inputs, "seq")
    os.makedirs(seq)
    for i in range(1, 5):
        for side in ("left", "right"):
            shutil.copy(os.path.join(scene, f"{side}.png"), os.path.join(seq, f"{side}{i}.png"))
    os.makedirs(os.path.join(inputs, "notes"))
    with open(os.path.join(inputs, "notes", "regs.json"), "w") as f:
        f.write('{"occ": 12}\n')
    with open(os.path.join(inputs, "notes", "notes.txt"), "w") as f:
        f.write("notes\n")
    shutil.copytree(scene, os.path.join(inputs, "dataset", "s1"))
    farm_refusals(o, tmp, inputs, seq, scene)
    farm_out_kept(o, tmp, seq)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--mode", choices=["jobs", "farm", "farm-cli"], required=True)
    ap.add_argument("--stereo-sim", required=True)
    ap.add_argument("--sm-scene", required=True)
    ap.add_argument("--farm", help="tools/sm_farm.py (modes farm, farm-cli)")
    ap.add_argument("--tmp", required=True)
    o = ap.parse_args()
    shutil.rmtree(o.tmp, ignore_errors=True)
    os.makedirs(o.tmp)
    if o.mode == "farm-cli":
        farm_cli(o, o.tmp)
        if FAILS:
            sys.exit(f"{len(FAILS)} check(s) failed")
        return
    seq, args = make_inputs(o.sm_scene, o.tmp)
    serial = os.path.join(o.tmp, "serial")
    run([o.stereo_sim, *args, "--out", serial, "-q"])
    par = os.path.join(o.tmp, o.mode)
    if o.mode == "jobs":
        run([o.stereo_sim, *args, "--jobs", "2", "--out", par, "-q"])
        compare(serial, par, "--jobs 2")
        failing_shard(o.stereo_sim, seq, o.tmp)
    else:
        run([sys.executable, o.farm, "--workers", "2", "-q", "shards", "--stereo-sim", o.stereo_sim, "--shards", "2",
             "--out", par, "--", *args])
        compare(serial, par, "sm_farm.py shards, 2 workers")
        farm_retries(o, o.tmp, serial, args)
        farm_late_logs(o)
        farm_scenes(o, o.tmp)
        left = [n for n in os.listdir(o.tmp) if ".farm" in n]
        check(not left, f"no temporary folders left ({left})")
    if FAILS:
        sys.exit(f"{len(FAILS)} check(s) failed")


if __name__ == "__main__":
    main()
