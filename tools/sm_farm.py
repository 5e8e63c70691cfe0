#!/usr/bin/env python3
"""sm_farm: stereo_sim and model runs as Dask tasks, on this machine or a cluster (issue 41).

Subcommands (docs/farm.md):
  shards    one stereo_sim run of a sequence or video, its frames split into contiguous
            shards (stereo_sim --frame-range), merged by stereo_sim --merge-shards
  accuracy  the RTL on every scene of a dataset folder (stereo_sim --scene, one frame
            each): bad-1.0 and bit-exactness per scene, like bench/accuracy.sh
  sweep     a grid of register values over a dataset: the model (sm_evaluate --regs) or
            the RTL (stereo_sim --regs per scene)

A LocalCluster of --workers single-threaded workers in this process by default (each task
is an external program, so a thread waiting on it is enough; --worker-processes: worker
processes under a nanny, as on a cluster); --scheduler ADDRESS uses a running cluster
(dask scheduler / dask worker, dask-jobqueue), whose workers must see the same file
system. A task whose program is killed or whose worker dies is retried (--retries);
results are written all or nothing (staged in a temporary folder, moved into --out when
complete, replacing only files of the same names, as stereo_sim --jobs; an --out that is
or holds an input is refused); progress shows tasks done and the time left. Run it with
the project's .venv python.
"""
import argparse
import itertools
import json
import logging
import os
import shutil
import subprocess
import sys
import tempfile
import time

TOOL = "sm_farm"


class FarmError(Exception):
    pass


# A run's tasks write into one temporary folder; this file in it says the run has failed:
# a task still running kills its program and ends, so that nothing writes into the
# folder after it is removed (the workers, local or not, see the same file system).
CANCEL = ".cancel"


class TaskError(Exception):
    """A program that ran and refused its input (the same on any worker, so not retried),
    or a task ended because the run had failed."""


def run_task(args, log):
    """One program run on a worker: its output in `log`; (exit code, last line). The
    program is killed, and TaskError raised, when CANCEL appears beside `log`."""
    cancel = os.path.join(os.path.dirname(log), CANCEL)
    with open(log, "w") as f:
        if os.path.exists(cancel):
            raise TaskError("not run: the run had failed")
        p = subprocess.Popen(args, stdout=f, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
        while True:
            try:
                rc = p.wait(timeout=0.5)
                break
            except subprocess.TimeoutExpired:
                if os.path.exists(cancel):
                    p.kill()
                    p.wait()
                    raise TaskError("stopped: the run had failed")
    last = ""
    with open(log, errors="replace") as f:
        for line in f:
            line = line.rstrip("\n").split("\r")[-1]
            if line.strip():
                last = line
    return rc, last


def run_checked(args, log, ok_codes=(0, 1)):
    """run_task; an exit code outside ok_codes is a TaskError, a signal (the process was
    killed, e.g. with its worker) an exception that Dask retries."""
    rc, last = run_task(args, log)
    if rc < 0:
        raise RuntimeError(f"{os.path.basename(args[0])} killed by signal {-rc}")
    if rc not in ok_codes:
        raise TaskError(f"{os.path.basename(args[0])} exit {rc}: {last}")
    return rc


def no_retry(fn):
    """Runs fn on a worker; a TaskError comes back as a value (Dask retries only exceptions)."""
    def task(*args):
        try:
            return fn(*args)
        except TaskError as e:
            return TaskError(str(e))
    return task


def quiet_dask_logs():
    """Dask's own log lines off for the whole run: the tool reports a failure in one line
    of its own. LocalCluster's silence_logs lowers the handlers only while the cluster
    starts and restores them when it closes, so a comm that a killed task left closing
    could still print an INFO line and its traceback after the error line (seen in CI)."""
    for name in ["distributed"] + [n for n in logging.root.manager.loggerDict if n.startswith("distributed.")]:
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)


def make_client(opts):
    """A client of the --scheduler cluster or of a new LocalCluster (docs/farm.md). The
    LocalCluster's workers are threads of this process unless --worker-processes: a task
    only waits on its external program, and worker processes would cost a Python start
    and a dask import each before the first task and a nanny to stop them (0.7-1.2 s of
    wall on this 2-core machine)."""
    # sm_farm moves no arrays: without numpy Dask allocates its message buffers as bytearrays
    # (distributed/protocol/utils.py) and its import takes 0.1 s less CPU (0.25 s instead of 0.35)
    sys.modules.setdefault("numpy", None)
    import dask
    from distributed import Client, LocalCluster

    quiet_dask_logs()

    if opts.scheduler:
        return Client(opts.scheduler), None
    # the workers share two cores with the programs they run: no statistical profiler, event
    # loop check or system monitor for a dashboard (0.36 s of this process's CPU in an 8 s
    # run of two tasks, 0.08 s without them)
    dask.config.set({"distributed.worker.profile.enabled": False, "distributed.admin.tick.interval": "1s",
                     "distributed.admin.system-monitor.interval": "5s",
                     "distributed.worker.memory.monitor-interval": "5s"})
    cluster = LocalCluster(n_workers=opts.workers, threads_per_worker=1, processes=opts.worker_processes,
                           dashboard_address=None, silence_logs=logging.CRITICAL)
    return Client(cluster), cluster


class Farm:
    """A Dask client for the run, closed with its LocalCluster on leaving the `with`."""

    def __init__(self, opts):
        self.opts = opts
        self.client, self.cluster = make_client(opts)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()

    def run(self, tasks, noun, tmp):
        """tasks: list of (name, function, args), writing into the folder `tmp`. Runs them as
        Dask tasks; results by name. Progress: one line of `noun` done and the time left.
        A task that fails (after its retries) stops the others (CANCEL in `tmp`): they
        have ended when the FarmError is raised."""
        from distributed import as_completed, wait

        opts, futures = self.opts, {}
        for name, fn, args in tasks:
            fut = self.client.submit(no_retry(fn), *args, retries=opts.retries, pure=False,
                                     key=f"{TOOL}-{name}-{os.getpid()}")
            futures[fut] = name
        results, t0, done = {}, time.monotonic(), 0
        try:
            for fut in as_completed(list(futures)):
                name = futures[fut]
                try:
                    results[name] = fut.result()
                    if isinstance(results[name], TaskError):
                        raise results[name]
                except Exception as e:  # refused, or failed after its retries: no output
                    raise FarmError(f"task {name} failed: {e}")
                done += 1
                if not opts.quiet:
                    el = time.monotonic() - t0
                    left = el / done * (len(tasks) - done)
                    end = "\n" if done == len(tasks) else ""
                    print(f"\r{noun} done {done}/{len(tasks)} ({el:.1f} s, about {left:.0f} s left)", end=end,
                          file=sys.stderr, flush=True)
        except BaseException:
            open(os.path.join(tmp, CANCEL), "w").close()
            try:
                wait(list(futures), timeout=60)
            except Exception:  # a worker that does not answer: the run fails all the same
                pass
            raise
        return results


def run_all(opts, tasks, noun, tmp):
    """Farm(opts).run(tasks, noun, tmp) on a client of its own."""
    with Farm(opts) as farm:
        return farm.run(tasks, noun, tmp)


def publish(staged, out, last):
    """Moves every file of the complete folder `staged` to the same name under `out` (made
    when missing), as `stereo_sim --jobs` writes its outputs: a file of that name is
    replaced, nothing else in `out` is touched (docs/farm.md). Every target is checked
    first; `last` (report.json, summary.json: what says the output is complete) is removed
    from `out` before the first move and moved last, so that `out` never looks complete
    with only part of the new files."""
    files = []
    for root, dirs, names in os.walk(staged):
        dirs.sort()
        files += sorted(os.path.relpath(os.path.join(root, n), staged) for n in names)
    files.sort(key=lambda rel: rel == last)
    if os.path.lexists(out) and not os.path.isdir(out):
        raise FarmError(f"--out {out}: cannot write: not a folder")
    for rel in files:
        parts = rel.split(os.sep)
        for k in range(1, len(parts)):
            d = os.path.join(out, *parts[:k])
            if os.path.lexists(d) and not os.path.isdir(d):
                raise FarmError(f"--out {out}: cannot write {os.path.join(out, rel)}: {d} is not a folder")
        target = os.path.join(out, rel)
        if os.path.isdir(target):
            raise FarmError(f"--out {out}: cannot write {target}: is a folder")
    os.makedirs(out, exist_ok=True)
    if os.path.lexists(os.path.join(out, last)):
        os.remove(os.path.join(out, last))
    for rel in files:
        target = os.path.join(out, rel)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        os.replace(os.path.join(staged, rel), target)


def temp_beside(out):
    """The run's temporary folder, hidden beside --out (beside the folder it names when
    --out is a symbolic link): on its file system, so that publish() only renames."""
    parent = os.path.dirname(os.path.realpath(out))
    os.makedirs(parent, exist_ok=True)
    return tempfile.mkdtemp(prefix=f".{os.path.basename(os.path.abspath(out))}.farm", dir=parent)


# stereo_sim's options that name a file or folder it reads (sim/sm_sim_preflight.cpp,
# run_inputs)
SIM_INPUTS = ("--sequence", "--scene", "--left", "--right", "--video", "--regs", "--regs-at", "--calib",
              "--synth-json")


def sim_inputs(args):
    """The files and folders that the stereo_sim options `args` read, as (option, path)."""
    found, i = [], 0
    while i < len(args):
        name, eq, val = args[i].partition("=")
        i += 1
        if name not in SIM_INPUTS:
            continue
        vals = [val] if eq else []
        # CLI11: a repeatable option (--regs-at) takes every value up to the next option
        while not eq and i < len(args) and not args[i].startswith("-") and (not vals or name == "--regs-at"):
            vals.append(args[i])
            i += 1
        for v in vals:
            path = v.partition("=")[2] if name == "--regs-at" else v
            if path:
                found.append((name, path))
    return found


def check_out(out, inputs):
    """Refuses an --out that is or contains one of the run's inputs, (option, path): the
    outputs would go among them (docs/farm.md)."""
    o = os.path.realpath(out)
    inside = o.rstrip(os.sep) + os.sep
    for opt, path in inputs:
        r = os.path.realpath(path)
        if r == o:
            raise FarmError(f"--out {out}: is the input {opt} {path}")
        if r.startswith(inside):
            raise FarmError(f"--out {out}: contains the input {opt} {path}")


def check_scheduler(address):
    """Refuses a --scheduler address that Dask cannot connect to by its form, before any
    work: no port, a port outside 1..65535, an unknown scheme."""
    sys.modules.setdefault("numpy", None)  # as in make_client
    from distributed.comm import registry
    from distributed.comm.addressing import parse_address

    scheme, loc = parse_address(address)
    try:
        _, port = registry.get_backend(scheme).get_address_host_port(loc)
    except NotImplementedError:  # a scheme without host and port (ucx, inproc)
        return
    except ValueError as e:
        msg = str(e)
        if msg.startswith("invalid literal for int()"):
            msg = f"the port {loc.rpartition(':')[2]!r} is not a number"
        raise FarmError(f"--scheduler {address}: {msg} (expected tcp://HOST:PORT)")
    if not 1 <= port <= 65535:
        raise FarmError(f"--scheduler {address}: port {port} is outside 1..65535")


def need_file(path, what):
    if not os.path.isfile(path) or not os.access(path, os.X_OK):
        raise FarmError(f"{path}: {what} is not an executable file")


# ---- shards ----

def list_shards(lister):
    """The ranges `A:B` that `stereo_sim --list-shards` printed (it checked the inputs)."""
    out, err = lister.communicate()
    if lister.returncode != 0:
        raise FarmError(err.strip().splitlines()[-1] if err.strip() else f"stereo_sim exit {lister.returncode}")
    return out.split()


def merge_shards(opts, tmp, n):
    """stereo_sim --merge-shards into <tmp>/merged; its report names the final --out."""
    merged = os.path.join(tmp, "merged")
    dirs = [os.path.join(tmp, f"shard_{i:03d}") for i in range(n)]
    m = subprocess.run([opts.stereo_sim, "--merge-shards", *dirs, "--out", merged], capture_output=True, text=True)
    if m.returncode not in (0, 1):
        raise FarmError(f"merge: {m.stderr.strip()}")
    # the merged report names its disparity file in the temporary folder: the final one
    rep_path = os.path.join(merged, "report.json")
    with open(rep_path) as f:
        rep = json.load(f)
    rep["disparity_file"] = os.path.join(opts.out, os.path.basename(rep["disparity_file"]))
    for s in rep.get("shards", []):
        s["folder"] = os.path.basename(s["folder"])
    with open(rep_path, "w") as f:
        json.dump(rep, f, indent=2)
        f.write("\n")
    return merged, m


def cmd_shards(opts):
    need_file(opts.stereo_sim, "--stereo-sim")
    sim_args = opts.sim_args
    if not sim_args:
        raise FarmError("shards: no stereo_sim input after -- (e.g. -- --sequence FOLDER)")
    check_out(opts.out, sim_inputs(sim_args))
    # stereo_sim checks the inputs, registers and output files in --out and prints the
    # shards' ranges while this process imports Dask and starts the cluster
    with subprocess.Popen([opts.stereo_sim, *sim_args, "--out", opts.out, "--list-shards", str(opts.shards)],
                          stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, text=True) as lister, Farm(opts) as farm:
        ranges = list_shards(lister)
        tmp = temp_beside(opts.out)
        try:
            tasks = []
            for i, r in enumerate(ranges):
                d = os.path.join(tmp, f"shard_{i:03d}")
                args = [opts.stereo_sim, *sim_args, "--frame-range", r, "--out", d, "-q"]
                tasks.append((f"shard{i}", run_checked, (args, d + ".log")))
            if not opts.quiet:
                print(f"{TOOL}: {len(ranges)} shards ({' '.join(ranges)})", file=sys.stderr)
            farm.run(tasks, "shards", tmp)
            merged, m = merge_shards(opts, tmp, len(ranges))
            publish(merged, opts.out, "report.json")
            sys.stdout.write(m.stdout.replace(merged, opts.out))
            return m.returncode
        finally:
            shutil.rmtree(tmp, ignore_errors=True)


# ---- accuracy ----

def list_scenes(dataset):
    if not os.path.isdir(dataset):
        raise FarmError(f"{dataset}: not a folder")
    scenes = sorted(d for d in os.listdir(dataset)
                    if os.path.isfile(os.path.join(dataset, d, "left.png")) and
                    os.path.isfile(os.path.join(dataset, d, "right.png")))
    if not scenes:
        raise FarmError(f"{dataset}: no scene folders (left.png, right.png)")
    return scenes


def sim_scene(stereo_sim, scene_dir, out, extra):
    """stereo_sim on one scene: its bad-1.0 and whether it was bit-exact."""
    run_checked([stereo_sim, "--scene", scene_dir, "--frames", "1", "-q", "--out", out, *extra], out + ".log")
    with open(os.path.join(out, "report.json")) as f:
        r = json.load(f)
    return {"bad1_percent": r.get("bad1_percent"), "bit_exact": r.get("bit_exact")}


def write_summary(opts, tmp, summary, lines):
    with open(os.path.join(tmp, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")
    with open(os.path.join(tmp, "summary.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    publish(tmp, opts.out, "summary.json")
    print("\n".join(lines))


def cmd_accuracy(opts):
    need_file(opts.stereo_sim, "--stereo-sim")
    scenes = list_scenes(opts.dataset)
    if opts.scenes:
        want = opts.scenes.split(",")
        missing = [s for s in want if s not in scenes]
        if missing:
            raise FarmError(f"{opts.dataset}: no scene {missing[0]}")
        scenes = want
    check_out(opts.out, [("DATASET", opts.dataset), *[("scene", os.path.join(opts.dataset, s)) for s in scenes],
                         *sim_inputs(opts.sim_args)])
    tmp = temp_beside(opts.out)
    try:
        tasks = [(s, sim_scene, (opts.stereo_sim, os.path.join(opts.dataset, s), os.path.join(tmp, f"rtl_{s}"),
                                 opts.sim_args)) for s in scenes]
        res = run_all(opts, tasks, "scenes", tmp)
        lines = ["| scene | RTL bad-1.0 % | bit-exact vs model |", "|---|---|---|"]
        for s in scenes:
            r = res[s]
            lines.append(f"| {s} | {r['bad1_percent']:.2f} | {'yes' if r['bit_exact'] else 'NO'} |")
        mean = sum(res[s]["bad1_percent"] for s in scenes) / len(scenes)
        lines.append(f"| mean of {len(scenes)} | {mean:.2f} | "
                     f"{'yes' if all(res[s]['bit_exact'] for s in scenes) else 'NO'} |")
        write_summary(opts, tmp, {"scenes": [{"name": s, **res[s]} for s in scenes], "mean_bad1_percent": mean},
                      lines)
        return 0 if all(res[s]["bit_exact"] for s in scenes) else 1
    finally:  # published (its files moved to --out) or not
        shutil.rmtree(tmp, ignore_errors=True)


# ---- sweep ----

def parse_grid(items):
    grid = []
    for it in items:
        key, eq, vals = it.partition("=")
        try:
            values = [int(v) for v in vals.split(",")]
        except ValueError:
            values = None
        if not eq or not key or not values:
            raise FarmError(f"--grid {it}: expected REGISTER=V1,V2,... with integer values")
        if key.lower() in [k for k, _ in grid]:
            raise FarmError(f"--grid {it}: register {key} given twice (one --grid {key}=V1,V2,... per register)")
        grid.append((key.lower(), values))
    return grid


def model_point(sm_evaluate, dataset, regs, json_out, extra):
    """sm_evaluate's model over the dataset with these registers: mean bad-1.0."""
    run_checked([sm_evaluate, dataset, "--methods", "model", "--regs", regs, "--json", json_out, "-q", *extra],
                json_out + ".log", ok_codes=(0,))
    with open(json_out) as f:
        r = json.load(f)
    vals = [s["methods"]["model"]["bad1_pct"] for s in r["scenes"]]
    return sum(vals) / len(vals)


def base_registers(tool_args):
    """A --regs FILE among the options after --: its registers (the grid's values go on top)
    and the options without it, since each point passes its own --regs."""
    rest, base = [], {}
    i = 0
    while i < len(tool_args):
        a = tool_args[i]
        if a == "--regs" or a.startswith("--regs="):
            path = a.partition("=")[2] if "=" in a else (tool_args[i + 1] if i + 1 < len(tool_args) else "")
            i += 1 if "=" in a else 2
            if not os.path.isfile(path):
                raise FarmError(f"--regs {path}: no such file")
            with open(path) as f:
                base = json.load(f)
            if not isinstance(base, dict):
                raise FarmError(f"--regs {path}: not a JSON object of registers")
            continue
        rest.append(a)
        i += 1
    return base, rest


def cmd_sweep(opts):
    grid = parse_grid(opts.grid)
    base, opts.tool_args = base_registers(opts.tool_args)
    if opts.rtl:
        need_file(opts.rtl, "--rtl")
        scenes = list_scenes(opts.dataset)
    else:
        need_file(opts.sm_evaluate, "--sm-evaluate")
        if not os.path.isdir(opts.dataset):
            raise FarmError(f"{opts.dataset}: not a folder")
    check_out(opts.out, [("DATASET", opts.dataset), *([("scene", os.path.join(opts.dataset, s)) for s in scenes] +
                                                      sim_inputs(opts.tool_args) if opts.rtl else [])])
    points = [dict(zip([k for k, _ in grid], vals)) for vals in itertools.product(*[v for _, v in grid])]
    files = [{**{k: v for k, v in base.items() if k.lower() not in p}, **p} for p in points]
    tmp = temp_beside(opts.out)
    try:
        tasks = []
        for i, p in enumerate(points):
            regs = os.path.join(tmp, f"point_{i:03d}.json")
            with open(regs, "w") as f:
                json.dump(files[i], f)
            if opts.rtl:
                for s in scenes:
                    tasks.append((f"p{i}-{s}", sim_scene, (opts.rtl, os.path.join(opts.dataset, s),
                                                            os.path.join(tmp, f"rtl_{i:03d}_{s}"),
                                                            ["--regs", regs, *opts.tool_args])))
            else:
                tasks.append((f"p{i}", model_point, (opts.sm_evaluate, opts.dataset, regs,
                                                      os.path.join(tmp, f"model_{i:03d}.json"), opts.tool_args)))
        res = run_all(opts, tasks, "runs", tmp)
        rows, lines = [], ["| " + " | ".join(k for k, _ in grid) + " | mean bad-1.0 % |",
                           "|" + "---|" * (len(grid) + 1)]
        for i, p in enumerate(points):
            if opts.rtl:
                vals = [res[f"p{i}-{s}"]["bad1_percent"] for s in scenes]
                mean = sum(vals) / len(vals)
                exact = all(res[f"p{i}-{s}"]["bit_exact"] for s in scenes)
            else:
                mean, exact = res[f"p{i}"], None
            rows.append({"registers": p, "mean_bad1_percent": mean, "rtl_bit_exact": exact})
            lines.append("| " + " | ".join(str(p[k]) for k, _ in grid) + f" | {mean:.2f} |")
        best = min(rows, key=lambda r: r["mean_bad1_percent"])
        lines.append(f"best: {best['registers']} ({best['mean_bad1_percent']:.2f} %)")
        write_summary(opts, tmp, {"dataset": opts.dataset, "tool": "rtl" if opts.rtl else "model", "points": rows},
                      lines)
        return 0
    finally:  # published (its files moved to --out) or not
        shutil.rmtree(tmp, ignore_errors=True)


def parser():
    ap = argparse.ArgumentParser(prog=TOOL, description=__doc__.split("\n\n")[0],
                                 epilog="Options after -- go to stereo_sim (shards: its input and register options; "
                                        "accuracy and sweep --rtl: more options) or sm_evaluate (sweep).")
    ap.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster workers, one thread each (default 2)")
    ap.add_argument("--worker-processes", action="store_true",
                    help="LocalCluster workers as processes under a nanny (restarted when one dies) instead of "
                         "threads of this process")
    ap.add_argument("--retries", type=int, default=2, help="retries of a task whose worker died or that failed")
    ap.add_argument("-q", "--quiet", action="store_true", help="no progress line")
    sub = ap.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("shards", help="one stereo_sim run in shards, merged")
    s.add_argument("--stereo-sim", required=True, help="the stereo_sim executable")
    s.add_argument("--shards", type=int, default=2, help="contiguous frame ranges (default 2)")
    s.add_argument("--out", required=True, help="output folder of the merged run")
    a = sub.add_parser("accuracy", help="the RTL on every scene of a dataset")
    a.add_argument("dataset", help="dataset folder of scene folders")
    a.add_argument("--stereo-sim", required=True, help="the stereo_sim executable")
    a.add_argument("--scenes", help="comma-separated scene names (default: all)")
    a.add_argument("--out", required=True, help="output folder (summary.json, summary.txt, rtl_<scene>/)")
    w = sub.add_parser("sweep", help="a grid of register values over a dataset, model or RTL")
    w.add_argument("dataset", help="dataset folder of scene folders")
    w.add_argument("--grid", action="append", required=True, help="REGISTER=V1,V2,... (repeatable: the product)")
    w.add_argument("--sm-evaluate", help="the model: sm_evaluate executable")
    w.add_argument("--rtl", metavar="STEREO_SIM", help="the RTL instead: stereo_sim executable, one run per scene")
    w.add_argument("--out", required=True, help="output folder (summary.json, summary.txt)")
    return ap


def main(argv=None):
    # after "--": the options handed to stereo_sim (shards: its input and registers) or sm_evaluate
    argv = sys.argv[1:] if argv is None else argv
    cut = argv.index("--") if "--" in argv else len(argv)
    opts = parser().parse_args(argv[:cut])
    opts.sim_args = opts.tool_args = argv[cut + 1:]
    try:
        if opts.workers < 1 or opts.retries < 0 or getattr(opts, "shards", 1) < 1:
            raise FarmError("--workers and --shards must be at least 1, --retries at least 0")
        if opts.cmd == "sweep" and bool(opts.rtl) == bool(opts.sm_evaluate):
            raise FarmError("sweep needs one of --sm-evaluate (the model) and --rtl (stereo_sim)")
        if opts.scheduler:
            check_scheduler(opts.scheduler)
        return {"shards": cmd_shards, "accuracy": cmd_accuracy, "sweep": cmd_sweep}[opts.cmd](opts)
    except (FarmError, OSError, json.JSONDecodeError, KeyError) as e:
        print(f"{TOOL}: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    rc = main()
    # everything is closed and written: skip the interpreter's teardown of the Dask modules
    # (0.1 s of wall and CPU)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(rc)
