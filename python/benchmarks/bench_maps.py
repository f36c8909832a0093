"""Scaling of ``dymsum.cobstacle_map`` (issue 22 §3): an arm-like robot of
4 convex pieces (two bars, a ball and a gripper-like ellipsoid) against a scene of 12 convex obstacles, 4,000 orientations
about one axis and 4,000 random orientations, half-spaces, on 1 and 2
local workers: the thread pool (``client=None, workers=n``) and a Dask
``LocalCluster`` of ``n`` single-threaded worker processes; the container's
size. The best of ``--repeats`` runs of each, interleaved (the machine is
shared: the least disturbed run of each); every map checked equal, bit for
bit. Dask twice on the same cluster: blocks handed back as files in a shared
temporary folder (the default, ``shared_dir=None``) and through Dask
itself (``shared_dir=False``).

    pip install "./python[dask]" scipy
    python python/benchmarks/bench_maps.py [--orientations 4000] [--block 256] [--repeats 3] [--malloc dask|tuned]
"""

import argparse
import os
import platform
import tempfile
import time

import numpy as np
from scipy.spatial.transform import Rotation

import dymsum


def scene():
    rng = np.random.default_rng(22)
    arm = [
        "box:1.2,0.2,0.2",
        dymsum.load("box:0.8,0.15,0.15").vertices + [1.0, 0, 0],
        dymsum.load("gs1").vertices * 0.15 + [1.45, 0, 0],
        dymsum.load("gs1").vertices * [0.25, 0.1, 0.1] + [1.75, 0, 0],
    ]
    obstacles = {}
    for i in range(12):
        kind = ["box:0.3,0.3,1", "gs1", "box:1,0.2,0.2"][i % 3]
        v = dymsum.load(kind).vertices * rng.uniform(0.3, 1.0)
        obstacles[f"o{i}"] = v + rng.uniform(-3, 3, size=3) * [1, 1, 0.2]
    return arm, obstacles


def timed(f):
    t = time.perf_counter()
    out = f()
    return time.perf_counter() - t, out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--orientations", type=int, default=4000)
    ap.add_argument("--block", type=int, default=256)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument(
        "--malloc",
        choices=["dask", "tuned"],
        default="dask",
        help="the workers' glibc malloc settings: Dask's (MALLOC_TRIM_THRESHOLD_=65536) or "
        "MALLOC_TRIM_THRESHOLD_=268435456 MALLOC_MMAP_THRESHOLD_=33554432 (docs/BENCHMARKS.md)",
    )
    a = ap.parse_args()
    import dask
    from distributed import Client, LocalCluster

    if a.malloc == "tuned":
        dask.config.set(
            {
                "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": 268435456,
                "distributed.nanny.pre-spawn-environ.MALLOC_MMAP_THRESHOLD_": 33554432,
            }
        )

    arm, obstacles = scene()
    k = a.orientations
    axis = Rotation.from_rotvec(np.outer(np.linspace(0, 2 * np.pi, k, endpoint=False), [0.2, 0.3, 0.93]))
    rand = Rotation.random(k, random_state=22)
    print(
        f"# {platform.node()}, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}; {len(arm)} pieces × {len(obstacles)} obstacles, "
        f"{k} orientations, block {a.block}; best of {a.repeats} interleaved runs; workers' malloc: {a.malloc}",
        flush=True,
    )
    clusters = {n: LocalCluster(n_workers=n, threads_per_worker=1, dashboard_address=None) for n in (1, 2)}
    clients = {n: Client(c) for n, c in clusters.items()}
    try:
        for c in clients.values():
            dymsum.cobstacle_map(arm, obstacles, axis[:8], client=c)  # warm the workers
        print("| orientations | 1 worker | 2 workers | speed-up | Dask 1 | Dask 2 | Dask overhead (1 / 2) | Dask in memory 1 / 2 | overhead in memory | container |")
        print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for name, rots in (("about one axis", axis), ("random", rand)):
            best: dict = {}
            ref = None
            for _ in range(a.repeats):
                for n in (1, 2):
                    runs = (
                        ("pool", lambda: dymsum.cobstacle_map(arm, obstacles, rots, block=a.block, workers=n)),
                        ("files", lambda: dymsum.cobstacle_map(arm, obstacles, rots, client=clients[n], block=a.block)),
                        ("memory", lambda: dymsum.cobstacle_map(arm, obstacles, rots, client=clients[n], block=a.block, shared_dir=False)),
                    )
                    for kind, f in runs:
                        t, m = timed(f)
                        best[kind, n] = min(t, best.get((kind, n), np.inf))
                        if ref is None:
                            ref = m
                        else:
                            assert all(np.array_equal(m.arrays[x], ref.arrays[x]) for x in ref.arrays)
                        del m
            with tempfile.TemporaryDirectory() as d:
                path = os.path.join(d, "map.npz")
                ref.save(path)
                size = os.path.getsize(path)
            del ref
            p1, p2 = best["pool", 1], best["pool", 2]
            f1, f2 = best["files", 1], best["files", 2]
            m1, m2 = best["memory", 1], best["memory", 2]
            print(
                f"| {name} | {p1:.2f} s | {p2:.2f} s | {p1 / p2:.2f}× | {f1:.2f} s | {f2:.2f} s "
                f"| {100 * (f1 / p1 - 1):+.0f}% / {100 * (f2 / p2 - 1):+.0f}% "
                f"| {m1:.2f} s / {m2:.2f} s | {100 * (m1 / p1 - 1):+.0f}% / {100 * (m2 / p2 - 1):+.0f}% "
                f"| {size / 2**20:.1f} MiB |",
                flush=True,
            )
    finally:
        for c in clients.values():
            c.close()
        for c in clusters.values():
            c.close()
    print(f"# load at the end {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
