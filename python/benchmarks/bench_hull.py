"""dymsum from Python against the hull of all pairwise sums (scipy/Qhull).

    pip install ./python scipy
    python python/benchmarks/bench_hull.py [--repeats R] [--steps S]

For 100, 300 and 1,000 vertices per shape (random points on two spheres,
so every point is a vertex), prints the median wall-clock time of

* ``scipy``: ``ConvexHull`` of the n·m pairwise vertex sums, the way a
  Python user gets a Minkowski sum without dymsum (what manifold3d's
  ``minkowski_sum`` computes internally, too);
* ``minkowski_sum``: ``dymsum.minkowski_sum(A, B, pose_a=R)`` on prebuilt
  Polytopes (walk method; triangle mesh out);
* ``update``: one ``DynamicSum.update(R_k)`` in a loop of small rotations
  (2π/500 per step about a random axis held for the run, the paper's motion
  at 500 steps per turn), without building the mesh;
* ``update+mesh``: the same plus ``DynamicSum.mesh()`` each step (what a
  caller needing the vertices and faces every frame pays).

Each figure is the median over R repeats (minkowski_sum, scipy) or over
the S update steps. Single thread; timings include the Python call
overhead and the NumPy conversions.
"""

import argparse
import platform
import statistics
import time

import numpy as np
from scipy.spatial import ConvexHull

import dymsum


def sphere(n, rng):
    p = rng.normal(size=(n, 3))
    return p / np.linalg.norm(p, axis=1)[:, None]


def pose(axis, angle):
    q = np.append(np.sin(angle / 2) * axis, np.cos(angle / 2))  # (x, y, z, w)
    return dymsum.pose(q)


def median_time(f, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--sizes", type=int, nargs="*", default=[100, 300, 1000])
    args = ap.parse_args()
    rng = np.random.default_rng(2024)
    print(f"dymsum {dymsum.__version__}, numpy {np.__version__}, Python {platform.python_version()}, {platform.machine()}")
    print(f"{'n = m':>6} {'facets':>7} {'scipy hull':>11} {'minkowski_sum':>14} {'ratio':>6} "
          f"{'update':>9} {'ratio':>6} {'update+mesh':>12} {'ratio':>6}")
    for n in args.sizes:
        a_pts, b_pts = sphere(n, rng), 0.5 * sphere(n, rng)
        a, b = dymsum.Polytope(a_pts), dymsum.Polytope(b_pts)
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        r = pose(axis, 0.3)
        rot = r[:3, :3]

        def scipy_sum():
            pts = (a_pts @ rot.T)[:, None, :] + b_pts[None, :, :]
            return ConvexHull(pts.reshape(-1, 3))

        t_scipy = median_time(scipy_sum, args.repeats)
        t_sum = median_time(lambda: dymsum.minkowski_sum(a, b, pose_a=r), args.repeats)

        step = 2 * np.pi / 500
        dyn = dymsum.DynamicSum(a, b, r)
        poses = [pose(axis, 0.3 + step * k) for k in range(1, 2 * args.steps + 1)]
        upd, upd_mesh = [], []
        for k, p in enumerate(poses):
            t0 = time.perf_counter()
            dyn.update(p)
            if k % 2 == 1:
                dyn.mesh()
                upd_mesh.append(time.perf_counter() - t0)
            else:
                upd.append(time.perf_counter() - t0)
        t_upd, t_upd_mesh = statistics.median(upd), statistics.median(upd_mesh)
        # The dynamic sum is still exact after the run.
        v, f = dyn.mesh()
        v2, f2 = dymsum.minkowski_sum(a, b, pose_a=poses[-1])
        assert np.array_equal(v, v2) and np.array_equal(f, f2)
        print(f"{n:>6} {dyn.facet_count:>7} {t_scipy * 1e3:>8.2f} ms {t_sum * 1e3:>11.2f} ms {t_scipy / t_sum:>5.1f}x "
              f"{t_upd * 1e6:>6.0f} µs {t_scipy / t_upd:>5.0f}x {t_upd_mesh * 1e3:>9.2f} ms {t_scipy / t_upd_mesh:>5.1f}x")


if __name__ == "__main__":
    main()
