"""dymsum's state checks against python-fcl on robot part meshes (issue 35).

    pip install ./python trimesh python-fcl scipy
    python python/benchmarks/bench_parts.py DIR [DIR ...] [--pairs N]
        [--states N] [--seed S] [--min-faces F]

Every ``*.stl`` under the folders given (e.g. git checkouts of
``ros-industrial/universal_robot`` and ``ros-industrial/abb``, or
``example-robot-data``'s ``robots`` folder), read by trimesh as it is
(``process=False``: unwelded, as robots ship them). ``--pairs`` seeded
pairs (body, obstacle) of those meshes, each with ``--states`` seeded
rotations and directions: the body's box centre put on the obstacle's,
turned, and moved along the direction by a fraction of the two
diagonals: *random* states a uniform fraction in [0, 0.6], *near*
states the two ends of a 40-step bisection between colliding and free
(both ends kept: within 2⁻⁴⁰ of the diagonals of contact).

Per pair: the build (``dymsum.MotionChecker(body, [obstacle])`` against
two fcl ``BVHModel``s, OBBRSS, and their ``CollisionObject``s), then
one call per state, both tools timed interleaved in one process:
dymsum's ``collides_at(pose)`` against ``setTransform`` +
``fcl.collide`` with a fresh request and result; medians and 99th
percentiles in µs, and their ratios (dymsum / fcl: below 1 is faster);
``collides_many`` on all states at once, per state, against the fcl
loop's mean. Disagreements are counted (fcl rounds; dymsum is exact and
also counts a body inside a solid). Prints a Markdown table.
"""

import argparse
import glob
import os
import sys
import time

import numpy as np


def load(path):
    import trimesh

    m = trimesh.load(path, process=False, force="mesh")
    return np.asarray(m.vertices, float), np.asarray(m.faces, np.int64)


def fcl_object(fcl, v, f):
    b = fcl.BVHModel()
    b.beginModel(len(v), len(f))
    b.addSubModel(v, f)
    b.endModel()
    return fcl.CollisionObject(b)


def states(checker, va, vb, n, rng):
    from scipy.spatial.transform import Rotation

    ca = (va.min(0) + va.max(0)) / 2
    cb = (vb.min(0) + vb.max(0)) / 2
    reach = np.linalg.norm(np.ptp(va, 0)) + np.linalg.norm(np.ptp(vb, 0))
    random, near = [], []
    for k in range(n):
        m = Rotation.random(random_state=int(rng.integers(1 << 31))).as_matrix()
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)

        def at(s):
            p = np.eye(4)
            p[:3, :3] = m
            p[:3, 3] = cb - m @ ca + d * (s * reach)
            return p

        random.append(at(rng.uniform(0, 0.6)))
        lo, hi = 0.0, 1.0
        if not checker.collides_at(at(lo)) or checker.collides_at(at(hi)):
            continue
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            if checker.collides_at(at(mid)):
                lo = mid
            else:
                hi = mid
        near += [at(lo), at(hi)]
    return random, near


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--pairs", type=int, default=20)
    ap.add_argument("--states", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--min-faces", type=int, default=0)
    a = ap.parse_args()
    import fcl

    import dymsum

    files = sorted({f for d in a.dirs for f in glob.glob(os.path.join(d, "**", "*.stl"), recursive=True)} | {f for d in a.dirs for f in glob.glob(os.path.join(d, "**", "*.STL"), recursive=True)})
    meshes = {}
    for f in files:
        try:
            v, t = load(f)
        except Exception as e:  # noqa: BLE001 - a file trimesh cannot read is reported and skipped
            print(f"skipped {f}: {e}", file=sys.stderr)
            continue
        if len(t) >= max(1, a.min_faces):
            meshes[f] = (v, t)
    names = sorted(meshes)
    print(f"{len(names)} meshes from {', '.join(a.dirs)}", file=sys.stderr)
    rng = np.random.default_rng(a.seed)
    rows = []
    for _ in range(a.pairs):
        fa, fb = rng.choice(len(names), 2)
        (va, ta), (vb, tb) = meshes[names[fa]], meshes[names[fb]]
        t0 = time.perf_counter()
        checker = dymsum.MotionChecker((va, ta), [(vb, tb)])
        build_d = time.perf_counter() - t0
        t0 = time.perf_counter()
        oa, ob = fcl_object(fcl, va, ta), fcl_object(fcl, vb, tb)
        build_f = time.perf_counter() - t0
        random, near = states(checker, va, vb, a.states, rng)
        row = {"a": names[fa], "b": names[fb], "fa": len(ta), "fb": len(tb), "build": (build_d, build_f)}
        for what, poses in (("random", random), ("near", near)):
            if not poses:
                continue
            td, tf, disagree = [], [], 0
            for p in poses:
                t0 = time.perf_counter()
                mine = checker.collides_at(p)
                t1 = time.perf_counter()
                oa.setTransform(fcl.Transform(p[:3, :3], p[:3, 3]))
                theirs = fcl.collide(oa, ob, fcl.CollisionRequest(), fcl.CollisionResult()) > 0
                t2 = time.perf_counter()
                td.append(t1 - t0)
                tf.append(t2 - t1)
                disagree += mine != theirs
            stack = np.stack(poses)
            t0 = time.perf_counter()
            checker.collides_many(stack)
            many = (time.perf_counter() - t0) / len(poses)
            td, tf = np.array(td) * 1e6, np.array(tf) * 1e6
            row[what] = (len(poses), np.median(td), np.median(tf), np.percentile(td, 99), np.percentile(tf, 99), many * 1e6, tf.mean(), disagree)
        rows.append(row)
        short = lambda s: os.path.basename(s)[:-4]
        r = row.get("near", row.get("random"))
        print(f"{short(row['a'])} ({row['fa']}) vs {short(row['b'])} ({row['fb']}): near median {r[1]:.1f} µs vs fcl {r[2]:.1f}", file=sys.stderr, flush=True)
    short = lambda s: "/".join(s.split("/")[-3:])[:-4]
    print("| body (faces) | obstacle (faces) | build ms dymsum / fcl | states | median µs dymsum / fcl (ratio) | p99 µs dymsum / fcl (ratio) | collides_many per state / fcl loop (ratio) | disagree |")
    print("|---|---|---|---|---|---|---|---|")
    ratios = {"random": [], "near": [], "p99": [], "many": []}
    for row in rows:
        for what in ("random", "near"):
            if what not in row:
                continue
            n, md, mf, pd, pf, many, meanf, dis = row[what]
            ratios[what].append(md / mf)
            ratios["p99"].append(pd / pf)
            ratios["many"].append(many / meanf)
            bd, bf = row["build"]
            print(
                f"| {short(row['a'])} ({row['fa']}) | {short(row['b'])} ({row['fb']}) | {bd * 1e3:.0f} / {bf * 1e3:.0f} | {what} {n} "
                f"| {md:.1f} / {mf:.1f} ({md / mf:.2f}) | {pd:.0f} / {pf:.0f} ({pd / pf:.2f}) | {many:.1f} / {meanf:.1f} ({many / meanf:.2f}) | {dis} |"
            )
    gm = lambda v: float(np.exp(np.mean(np.log(v)))) if v else float("nan")
    print()
    print(
        f"Ratios (dymsum / fcl): median random gm {gm(ratios['random']):.2f} worst {max(ratios['random'] or [0]):.2f}; "
        f"median near gm {gm(ratios['near']):.2f} worst {max(ratios['near'] or [0]):.2f}; "
        f"p99 gm {gm(ratios['p99']):.2f} worst {max(ratios['p99'] or [0]):.2f}; "
        f"collides_many gm {gm(ratios['many']):.2f} worst {max(ratios['many'] or [0]):.2f}"
    )


if __name__ == "__main__":
    main()
