"""Scaling of ``dymsum.cobstacle_map`` (issue 22 §3): an arm-like robot of
4 convex pieces (two bars, a ball and a gripper-like ellipsoid) against a scene of 12 convex obstacles, 4,000 orientations
about one axis and 4,000 random orientations, half-spaces, on 1 and 2
local workers: the thread pool (``client=None, workers=n``) and a Dask
``LocalCluster`` of ``n`` single-threaded worker processes; the container's
size. One run each (the maps are also checked equal, bit for bit). Dask
twice on the same cluster: blocks handed back as files in a shared
temporary folder (the default, ``shared_dir=None``) and through Dask
itself (``shared_dir=False``).

    pip install "./python[dask]" scipy
    python python/benchmarks/bench_maps.py [--orientations 4000] [--block 256]
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
    a = ap.parse_args()
    from distributed import Client, LocalCluster

    arm, obstacles = scene()
    k = a.orientations
    axis = Rotation.from_rotvec(np.outer(np.linspace(0, 2 * np.pi, k, endpoint=False), [0.2, 0.3, 0.93]))
    rand = Rotation.random(k, random_state=22)
    print(f"# {platform.node()}, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}; 4 pieces × 12 obstacles, {k} orientations, block {a.block}")
    print("| orientations | 1 worker | 2 workers | speed-up | Dask 1 | Dask 2 | Dask overhead (1 / 2) | Dask in memory 1 / 2 | overhead in memory | container |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for name, rots in (("about one axis", axis), ("random", rand)):
        t1, m1 = timed(lambda: dymsum.cobstacle_map(arm, obstacles, rots, block=a.block, workers=1))
        t2, m2 = timed(lambda: dymsum.cobstacle_map(arm, obstacles, rots, block=a.block, workers=2))
        dt, dm = [], []
        for n in (1, 2):
            with LocalCluster(n_workers=n, threads_per_worker=1, dashboard_address=None) as cluster, Client(cluster) as client:
                dymsum.cobstacle_map(arm, obstacles, rots[:8], client=client)  # warm the workers
                t, md = timed(lambda: dymsum.cobstacle_map(arm, obstacles, rots, client=client, block=a.block))
                dt.append(t)
                assert all(np.array_equal(md.arrays[x], m1.arrays[x]) for x in m1.arrays)
                del md
                t, md = timed(lambda: dymsum.cobstacle_map(arm, obstacles, rots, client=client, block=a.block, shared_dir=False))
                dm.append(t)
                assert all(np.array_equal(md.arrays[x], m1.arrays[x]) for x in m1.arrays)
                del md
        assert all(np.array_equal(m2.arrays[x], m1.arrays[x]) for x in m1.arrays)
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "map.npz")
            m1.save(path)
            size = os.path.getsize(path)
        print(
            f"| {name} | {t1:.2f} s | {t2:.2f} s | {t1 / t2:.2f}× | {dt[0]:.2f} s | {dt[1]:.2f} s "
            f"| {100 * (dt[0] / t1 - 1):+.0f}% / {100 * (dt[1] / t2 - 1):+.0f}% "
            f"| {dm[0]:.2f} s / {dm[1]:.2f} s | {100 * (dm[0] / t1 - 1):+.0f}% / {100 * (dm[1] / t2 - 1):+.0f}% "
            f"| {size / 2**20:.1f} MiB |",
            flush=True,
        )


if __name__ == "__main__":
    main()
