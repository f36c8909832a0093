"""Certified C-obstacle slabs of orientation cells in SO(3)
(``cobstacle_slices(..., certified=True, cell_radius=rho)``): how far a slab
reaches beyond the slices of its cell, against the radius, and what it
costs against the slices.

    pip install ./python scipy
    python python/benchmarks/bench_cell_slabs.py [--robot gs2] [--obstacle box:1,2,0.5] [--radii 0.4 0.2 0.1 0.05 0.025] [--cells 16] [--samples 4000]

For each radius ``rho``: ``--cells`` random centre rotations (seeded), one
slab each (the centre's slice, every plane pushed out by ``r·rho`` and the
rounding terms, ``r`` the robot's radius). The tightness, over every plane
of every slab: how far it reaches beyond the cell's slices in its own
direction, ``d − max_R h(n, R)``, with ``h(n, R) = h_O(n) + h_A(−Rᵀ n)``
the slice's support function, maximised over ``--samples`` rotations
within angle ``rho`` of the centre (random axes; half of them on the rim,
at angle ``rho``), as a fraction of the margin (the part of the margin no
sampled slice uses): the smallest, the median and the largest over the
planes. Sampling can only under-estimate the maximum, so it
over-estimates the excess slightly. Times (median of ``--repeats``, one
thread): the slices at the centres, and the cell slabs (``parallel=False``).
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


def cell_samples(centre, rho, count, rng):
    """``count`` rotations within angle ``rho`` of ``centre``, half on the rim."""
    axes = rng.normal(size=(count, 3))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    angles = rng.uniform(0.0, rho, size=count)
    angles[::2] = rho
    return Rotation.from_rotvec(axes * angles[:, None]) * centre


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--robot", default="gs2")
    ap.add_argument("--obstacle", default="box:1,2,0.5")
    ap.add_argument("--radii", type=float, nargs="+", default=[0.4, 0.2, 0.1, 0.05, 0.025])
    ap.add_argument("--cells", type=int, default=16)
    ap.add_argument("--samples", type=int, default=4000)
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    rng = np.random.default_rng(20)
    robot, obstacle = dymsum.load(a.robot), dymsum.load(a.obstacle)
    radius = np.linalg.norm(robot.vertices, axis=1).max()
    centres = Rotation.random(a.cells, random_state=rng)
    print(
        f"{a.robot} (r = {radius:.4f}) against {a.obstacle}; {a.cells} random cells, "
        f"{a.samples} sampled rotations each; median of {a.repeats}; "
        f"Python {platform.python_version()}, dymsum {dymsum.__version__}"
    )
    print(
        "| ρ | slices | cell slabs | ratio | planes per slab | margin ÷ r "
        "| excess ÷ margin: smallest | median | largest |"
    )
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for rho in a.radii:
        t_slices, _ = median_time(lambda: dymsum.cobstacle_slices(robot, obstacle, centres), a.repeats)
        t_slabs, slabs = median_time(
            lambda: dymsum.cobstacle_slices(robot, obstacle, centres, certified=True, cell_radius=rho),
            a.repeats,
        )
        fractions = []
        for k, s in enumerate(slabs):
            h_o = (s.normals @ obstacle.vertices.T).max(axis=1)
            samples = cell_samples(centres[k], rho, a.samples, rng).as_matrix()
            # h_A(−Rᵀ n) = max over the robot's vertices a of −n·(R a).
            h_a = np.full(len(s), -np.inf)
            for chunk in np.array_split(samples, max(1, len(samples) // 100)):
                turned = np.einsum("kij,vj->kvi", chunk, robot.vertices)  # (K, V, 3)
                h_a = np.maximum(h_a, np.einsum("mi,kvi->mkv", -s.normals, turned).max(axis=(1, 2)))
            excess = s.offsets - (h_o + h_a)
            assert (excess >= 0).all(), "a sampled slice outside its slab"
            fractions.extend(excess / s.margin)
        print(
            f"| {rho:g} | {t_slices * 1e3:.2f} ms | {t_slabs * 1e3:.2f} ms | {t_slabs / t_slices:.2f} "
            f"| {np.mean([len(s) for s in slabs]):.0f} | {max(s.margin for s in slabs) / radius:.2e} "
            f"| {min(fractions):.3f} | {np.median(fractions):.3f} | {max(fractions):.3f} |"
        )


if __name__ == "__main__":
    main()
