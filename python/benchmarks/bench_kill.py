"""Nothing lost on a kill (issue 26 §6): SIGKILL experiments, not run in CI.

Each trial replaces an earlier output with a new one and SIGKILLs the
writer at a random moment (uniform over the length of an uninterrupted
run, so some kills land while computing, some while writing, some during
the swap and some after the end). After each kill the output is checked:

* ``cobst-npz``: ``dymsum cobst ... --format npz --force`` over a small
  earlier ``map.npz``: the file must be the earlier map byte for byte or
  the new one (a committed swap still pending in a ``.dymsum-ready-*``
  folder counts as new: the next run finishes it);
* ``cobst-folder``: the same with ``--format halfspaces`` (a folder of
  ``slice_*.json`` files and ``index.json``): every non-temporary file must
  be the earlier set or the new set, with a ``notes.txt`` of the user's
  kept;
* ``save``: ``CObstacleMap.save`` of a 40 MB map in a subprocess over an
  earlier map: ``load_cobstacle_map`` must return the earlier or the new map.

Leftovers (temporary files and staging folders of the killed writers) are
counted after each kill; one more uninterrupted run must remove them all.

    python python/benchmarks/bench_kill.py [--trials 50] [--cli target/release/dymsum]
"""

import argparse
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import numpy as np

import dymsum


def own_files(d):
    """Non-temporary files of `d` with their bytes; whether a ready folder
    (a committed swap) is pending; the number of temporary entries."""
    files, ready, temps = {}, False, 0
    for n in os.listdir(d):
        if n.startswith(".dymsum-ready-"):
            ready = True
        if n.startswith("."):
            temps += 1
        else:
            with open(os.path.join(d, n), "rb") as f:
                files[n] = f.read()
    return files, ready, temps


def timed(cmd):
    t = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True)
    return time.perf_counter() - t


def kill_at(cmd, seconds):
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(seconds)
    finished = p.poll() is not None
    if not finished:
        p.send_signal(signal.SIGKILL)
    p.wait()
    return finished


def cobst_trials(cli, fmt, slices, trials, rng, root):
    out = os.path.join(root, f"out-{fmt}")
    fresh = os.path.join(root, f"fresh-{fmt}")

    def cmd(n, d):
        return [cli, "cobst", "box", "gs1", "--axis", "0,0,1", "--slices", str(n), "--format", fmt, "--out", d, "--force"]

    subprocess.run(cmd(3, out), check=True, capture_output=True)
    with open(os.path.join(out, "notes.txt"), "w") as f:
        f.write("mine")
    old, _, _ = own_files(out)
    full = timed(cmd(slices, fresh))
    new, _, _ = own_files(fresh)
    new["notes.txt"] = b"mine"
    stats = {"old": 0, "new": 0, "pending": 0, "lost": 0, "finished": 0, "leftovers": 0, "max_leftovers": 0}
    for _ in range(trials):
        if own_files(out)[0] == new:
            # Start every trial from the earlier output.
            shutil.rmtree(out)
            subprocess.run(cmd(3, out), check=True, capture_output=True)
            with open(os.path.join(out, "notes.txt"), "w") as f:
                f.write("mine")
        t = rng.uniform(0, 1.2 * full)
        stats["finished"] += kill_at(cmd(slices, out), t)
        files, ready, temps = own_files(out)
        stats["leftovers"] += temps
        stats["max_leftovers"] = max(stats["max_leftovers"], temps)
        if files == old:
            stats["old"] += 1
        elif files == new:
            stats["new"] += 1
        elif ready:
            stats["pending"] += 1
        else:
            stats["lost"] += 1
    subprocess.run(cmd(slices, out), check=True, capture_output=True)
    files, ready, temps = own_files(out)
    stats["after_next_run"] = temps
    stats["final_ok"] = files == new and not ready
    stats["full_run_s"] = full
    return stats


SAVER = """
import sys, numpy as np, dymsum
a = dict(np.load(sys.argv[1], allow_pickle=False))
dymsum.CObstacleMap(a).save(sys.argv[2])
"""


def save_trials(trials, rng, root):
    d = os.path.join(root, "save")
    os.makedirs(d)
    small = dymsum.cobstacle_map("box", "gs1", np.array([[0, 0, 0, 1.0]]))
    path = os.path.join(d, "map.npz")
    small.save(path)
    # A 40 MB map: one pair, 8 slices of 200 000 planes.
    rng_np = np.random.default_rng(26)
    a = {k: np.asarray(v) for k, v in dymsum.cobstacle_map("box", "gs1", np.tile([[0, 0, 0, 1.0]], (8, 1))).arrays.items()}
    n = 200_000
    a["plane_start"] = np.arange(9, dtype=np.int64) * n
    normals = rng_np.normal(size=(8 * n, 3))
    a["normals"] = normals / np.linalg.norm(normals, axis=1)[:, None]
    a["offsets"] = rng_np.uniform(1, 2, size=8 * n)
    src = os.path.join(root, "big-src.npz")
    np.savez(src, **a)
    big = dymsum.CObstacleMap(a)
    cmd = [sys.executable, "-c", SAVER, src, path]
    full = timed(cmd)
    small.save(path)
    stats = {"old": 0, "new": 0, "lost": 0, "finished": 0, "leftovers": 0, "max_leftovers": 0}
    for _ in range(trials):
        small.save(path)
        stats["finished"] += kill_at(cmd, rng.uniform(0, 1.2 * full))
        temps = sum(n.startswith(".") for n in os.listdir(d))
        stats["leftovers"] += temps
        stats["max_leftovers"] = max(stats["max_leftovers"], temps)
        try:
            m = dymsum.load_cobstacle_map(path)
        except ValueError:
            stats["lost"] += 1
            continue
        if len(m.arrays["offsets"]) == len(big.arrays["offsets"]) and np.array_equal(m.arrays["offsets"], big.arrays["offsets"]):
            stats["new"] += 1
        elif np.array_equal(m.arrays["offsets"], small.arrays["offsets"]):
            stats["old"] += 1
        else:
            stats["lost"] += 1
    small.save(path)
    stats["after_next_run"] = sum(n.startswith(".") for n in os.listdir(d))
    stats["full_run_s"] = full
    return stats


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--trials", type=int, default=50)
    ap.add_argument("--cli", default=os.path.join(os.path.dirname(__file__), "..", "..", "target", "release", "dymsum"))
    ap.add_argument("--seed", type=int, default=26)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    root = tempfile.mkdtemp(prefix="dymsum-kill-")
    try:
        rows = [
            ("cobst --format npz (6,000 slices)", cobst_trials(args.cli, "npz", 6000, args.trials, rng, root)),
            ("cobst --format halfspaces (1,500 slice files)", cobst_trials(args.cli, "halfspaces", 1500, args.trials, rng, root)),
            ("CObstacleMap.save (40 MB)", save_trials(args.trials, rng, root)),
        ]
    finally:
        shutil.rmtree(root, ignore_errors=True)
    print(f"| writer | uninterrupted run | kills | finished before the kill | earlier output intact | new output complete | swap pending (finished by the next run) | lost | temporary entries left per kill (mean / max) | left after the next run |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, s in rows:
        print(
            f"| {name} | {s['full_run_s']:.2f} s | {args.trials} | {s['finished']} | {s['old']} | {s['new']} | "
            f"{s.get('pending', 0)} | {s['lost']} | {s['leftovers'] / args.trials:.2f} / {s['max_leftovers']} | {s['after_next_run']} |"
        )


if __name__ == "__main__":
    main()
