"""dymsum's exact contact queries from Python against coal's GJK/EPA.

    pip install ./python scipy coal
    python python/benchmarks/bench_contact.py [--poses K] [--repeats R]

coal is a peer for this benchmark only (install it into the benchmark's
environment; dymsum never imports it). For each pair of shapes, body A
turns about (1, 2, 3) at 500 steps per turn while it slides through B along
x (between ±1.1 (r_A + r_B)), B turns slowly the other way: the workload
of the Rust ``tracker_vs_parry`` bench, K poses. Prints the median over R
repeats of the time per pose of

* ``coal distance``: ``coal.distance`` (GJK, EPA when overlapping; signed
  distance, witness points, normal), one call per pose;
* ``contact``: ``dymsum.contact`` on prepared ``Polytope`` objects, one call
  per pose (certified support-function query);
* ``contact_many``: one ``dymsum.contact_many`` call for all K poses
  (the GIL released, parallel chunks), per pose;
* ``tracker``: ``ContactTracker.update`` per frame (strategy "auto");
* ``collides_many``: the yes/no alone for all K poses, per pose;

and the largest difference between coal's signed distance and ours
(``distance − depth``) over the poses, with the number of poses where they
disagree on contact.
"""

import argparse
import platform
import statistics
import time

import coal
import numpy as np
from scipy.spatial.transform import Rotation

import dymsum


def sphere(n, seed):
    p = np.random.default_rng(seed).normal(size=(n, 3))
    return p / np.linalg.norm(p, axis=1)[:, None]


def shapes():
    return [
        ("box+box", dymsum.load("box:1,2,3"), dymsum.load("box:2,1,1")),
        ("box+hull20", dymsum.load("box:1,2,3"), dymsum.Polytope(sphere(20, 1))),
        ("box+hull60", dymsum.load("box:1,2,3"), dymsum.Polytope(sphere(60, 2))),
        ("hull40+hull40", dymsum.Polytope(sphere(40, 3)), dymsum.Polytope(1.5 * sphere(40, 4))),
        ("round200+round200", dymsum.Polytope(sphere(200, 5)), dymsum.Polytope(sphere(200, 6))),
        ("capsule+capsule", dymsum.load("capsule:8:4"), dymsum.load("capsule:8:4")),
    ]


def motion(a, b, k, steps_per_turn=500.0):
    """K poses (4×4) of A and of B (dymsum_bench::contact::contact_motion)."""
    reach = 1.1 * (np.linalg.norm(a.vertices, axis=1).max() + np.linalg.norm(b.vertices, axis=1).max())
    step = 2 * np.pi / steps_per_turn
    axis_a = np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0)
    axis_b = np.array([-2.0, 0.5, 1.0]) / np.linalg.norm([-2.0, 0.5, 1.0])
    pa, pb = np.zeros((k, 4, 4)), np.zeros((k, 4, 4))
    for i in range(k):
        s = i * step
        slide = 2 * np.pi * i / 1000.0
        pa[i] = dymsum.pose(Rotation.from_rotvec(axis_a * s), [reach * np.cos(slide), 0.3, 0.1])
        pb[i] = dymsum.pose(Rotation.from_rotvec(axis_b * (-0.7 * s)), [0.0, 0.0, 0.0])
    return pa, pb


def coal_shape(p):
    v = coal.StdVec_Vec3s()
    for x in p.vertices:
        v.append(np.asarray(x, dtype=float))
    return coal.Convex.convexHull(v, False, "")


def coal_tf(m):
    t = coal.Transform3s()
    t.setRotation(np.ascontiguousarray(m[:3, :3]))
    t.setTranslation(np.ascontiguousarray(m[:3, 3]))
    return t


def per_pose(f, k, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        f()
        times.append((time.perf_counter() - t0) / k)
    return statistics.median(times) * 1e6


def run(label, a, b, k, repeats):
    pa, pb = motion(a, b, k)
    ca, cb = coal_shape(a), coal_shape(b)
    tfa, tfb = [coal_tf(m) for m in pa], [coal_tf(m) for m in pb]
    req = coal.DistanceRequest()

    def coal_all():
        out = np.empty(k)
        for i in range(k):
            res = coal.DistanceResult()
            out[i] = coal.distance(ca, tfa[i], cb, tfb[i], req, res)
        return out

    def contact_all():
        return [dymsum.contact(a, b, pa[i], pb[i]) for i in range(k)]

    def tracker_all():
        t = dymsum.ContactTracker(a, b, pa[0], pb[0])
        return [t.update(pa[i], pb[i]) for i in range(k)]

    signed_coal = coal_all()
    many = dymsum.contact_many(a, b, pa, pb)
    ours = many.distance - many.depth
    single = contact_all()
    assert all(c.depth == many.depth[i] and c.distance == many.distance[i] for i, c in enumerate(single))
    disagree = int(np.sum((signed_coal <= 0) != many.collides))
    diff = float(np.max(np.abs(signed_coal - ours)))
    row = {
        "coal distance": per_pose(coal_all, k, repeats),
        "contact": per_pose(contact_all, k, repeats),
        "contact_many": per_pose(lambda: dymsum.contact_many(a, b, pa, pb), k, repeats),
        "tracker": per_pose(tracker_all, k, repeats),
        "collides_many": per_pose(lambda: dymsum.collides_many(a, b, pa, pb), k, repeats),
    }
    hits = int(many.collides.sum())
    cells = " | ".join(f"{row[c]:.2f}" for c in row)
    ratio = row["contact"] / row["coal distance"]
    print(
        f"| {label} | {len(a.vertices)}+{len(b.vertices)} | {hits}/{k} | {cells} | {ratio:.2f} | "
        f"{diff:.1e} | {disagree} |"
    )


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--poses", type=int, default=500)
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    print(f"# {platform.node()} {platform.processor()} python {platform.python_version()} coal {coal.__version__}")
    print(
        "| pair | vertices | in contact | coal distance µs | contact µs | contact_many µs | tracker µs | "
        "collides_many µs | contact ÷ coal | max |coal − ours| | contact verdicts differing |"
    )
    print("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for label, a, b in shapes():
        run(label, a, b, args.poses, args.repeats)


if __name__ == "__main__":
    main()
