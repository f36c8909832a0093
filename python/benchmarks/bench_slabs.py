"""Certified C-obstacle slabs against the slices they are built from, and
how tight they are.

    pip install ./python scipy
    python python/benchmarks/bench_slabs.py [--robot gs2] [--obstacle box:1,2,0.5] [--counts 16 64 256 1024] [--repeats 5]

The robot turns a full turn about (0.31, -0.57, 0.76) in N equal steps
(N + 1 rotations, the last equal to the first). For each N, the median over
the repeats of

* ``slices``: ``cobstacle_slices(robot, obstacle, turns)`` (N + 1 slices,
  DYMSUM from slice to slice, meshes out);
* ``slabs``: ``cobstacle_slices(..., certified=True)`` (the N slabs as
  half-spaces: the hull of the two end slices, its planes pushed out);
* ``slabs + mesh``: the same plus every ``Slab.mesh()``;

and the tightness: over every plane of every slab, how far it reaches
beyond the swept C-obstacle in its own direction, ``d − max_θ h(n, θ)``
with ``h(n, θ) = h_O(n) + h_A(−R(θ)ᵀ n)`` the slice's support function,
sampled at 64 angles per slab (the swept set's true support can only be
larger, so this over-estimates the excess slightly), as a fraction of the
robot's radius, next to the margin ``r·(1 − cos(δ/2))``.
"""

import argparse
import platform
import statistics
import time

import numpy as np
from scipy.spatial.transform import Rotation

import dymsum


def median_time(f, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--robot", default="gs2")
    ap.add_argument("--obstacle", default="box:1,2,0.5")
    ap.add_argument("--counts", type=int, nargs="+", default=[16, 64, 256, 1024])
    ap.add_argument("--repeats", type=int, default=5)
    a = ap.parse_args()
    robot, obstacle = dymsum.load(a.robot), dymsum.load(a.obstacle)
    axis = np.array([0.31, -0.57, 0.76])
    axis /= np.linalg.norm(axis)
    radius = np.linalg.norm(robot.vertices, axis=1).max()
    print(
        f"{a.robot} turning about {axis.round(3).tolist()} against {a.obstacle}; "
        f"median of {a.repeats}; Python {platform.python_version()}, dymsum {dymsum.__version__}"
    )
    print(
        "| N | slices | slabs (half-spaces) | ratio | slabs + mesh | ratio | planes per slab "
        "| margin ÷ r | largest excess ÷ r |"
    )
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for n in a.counts:
        angles = np.linspace(0.0, 2.0 * np.pi, n + 1)
        turns = Rotation.from_rotvec(np.outer(angles, axis))
        t_slices, _ = median_time(lambda: dymsum.cobstacle_slices(robot, obstacle, turns), a.repeats)
        t_slabs, slabs = median_time(
            lambda: dymsum.cobstacle_slices(robot, obstacle, turns, certified=True), a.repeats
        )
        t_mesh, _ = median_time(
            lambda: [s.mesh() for s in dymsum.cobstacle_slices(robot, obstacle, turns, certified=True)],
            a.repeats,
        )
        excess = 0.0
        for k, s in enumerate(slabs):
            dense = Rotation.from_rotvec(np.outer(np.linspace(angles[k], angles[k + 1], 64), axis))
            # h(n, θ) for every plane and angle: the obstacle's support plus
            # the turned robot's support in −n.
            h_o = (s.normals @ obstacle.vertices.T).max(axis=1)
            h_a = np.stack([(-(s.normals @ r.as_matrix()) @ robot.vertices.T).max(axis=1) for r in dense])
            excess = max(excess, (s.offsets - (h_o + h_a.max(axis=0))).max())
        planes = np.mean([len(s) for s in slabs])
        print(
            f"| {n} | {t_slices * 1e3:.2f} ms | {t_slabs * 1e3:.2f} ms | {t_slabs / t_slices:.2f} "
            f"| {t_mesh * 1e3:.2f} ms | {t_mesh / t_slices:.2f} | {planes:.0f} "
            f"| {max(s.margin for s in slabs) / radius:.2e} | {excess / radius:.2e} |"
        )


if __name__ == "__main__":
    main()
