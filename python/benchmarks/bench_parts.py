"""dymsum's state checks against python-fcl on robot part meshes (issue 35).

    pip install ./python trimesh python-fcl scipy
    python python/benchmarks/bench_parts.py DIR [DIR ...] [--pairs N]
        [--states N] [--seed S] [--min-faces F] [--motions M] [--distance D]
        [--pair A,B ...]

Every ``*.stl`` under the folders given (e.g. git checkouts of
``ros-industrial/universal_robot`` and ``ros-industrial/abb``, or
``example-robot-data``'s ``robots`` folder), read by trimesh as it is
(``process=False``: unwelded, as robots ship them). ``--pairs`` seeded
pairs (body, obstacle) of those meshes (or, with ``--pair A,B``, the
first meshes whose paths contain ``A`` and ``B``), each with ``--states`` seeded
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
``collides_many`` on all states at once, per state (the median of five
such calls: one call of a few milliseconds is at the mercy of the
machine), against the fcl loop's mean. Disagreements are counted (fcl
rounds; dymsum is exact and also counts a body inside a solid). With ``--motions M``, short motions
from free near-contact states: turned by 1° to 5° about a random axis
through the body's centre and moved by up to 2% of the obstacle's
diagonal, one call each: dymsum's certified ``check(pose0, pose1)``
(the contact bracketed to 1e-6; and as the OMPL validator's
``checkMotion(s1, s2)`` decides: ``sampled_contact`` on the discrete
check's own states, then ``check`` backwards to
``dymsum.ompl.DECISION_TOLERANCE``) against discrete validation with fcl as OMPL's SE(3) space would make
it (``DiscreteMotionValidator``: states ``0.01 · extent`` apart in OMPL's
SE(3) distance, the translation's length plus the quaternion angle, the
extent the obstacle box's diagonal plus π/2; the end state included, the
start not). With ``--distance D``, up to D free states per pair (the
random ones, then the free ends of the near ones): dymsum's
``distance_at(pose)`` (a certified lower bound within rounding) against
``fcl.distance`` with a default request, one call each, interleaved;
``above`` counts states where dymsum's bound exceeds fcl's distance by
more than 1e-9 relative (fcl's is a float estimate). Prints Markdown
tables.
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


def motions(fcl, checker, oa, ob, va, vb, starts, rng):
    """Short motions from free states (module docs): dymsum's certified check against fcl's discrete one."""
    from scipy.spatial.transform import Rotation

    import dymsum

    extent = np.linalg.norm(np.ptp(vb, 0)) + np.pi / 2
    ca = (va.min(0) + va.max(0)) / 2
    from dymsum.ompl import DECISION_TOLERANCE

    td, tdec, tf, counts, missed = [], [], [], [], 0
    for p0 in starts:
        axis = rng.normal(size=3)
        turn = Rotation.from_rotvec(axis / np.linalg.norm(axis) * np.radians(rng.uniform(1, 5)))
        p1 = np.eye(4)
        centre = p0[:3, :3] @ ca + p0[:3, 3]
        p1[:3, :3] = turn.as_matrix() @ p0[:3, :3]
        p1[:3, 3] = turn.apply(p0[:3, 3] - centre) + centre + rng.normal(size=3) * 0.01 * np.linalg.norm(np.ptp(vb, 0))
        t0 = time.perf_counter()
        try:
            free = checker.check(p0, p1).free
        except Exception:  # noqa: BLE001 - undecided or over budget: counted as not free, timed
            free = False
        td.append(time.perf_counter() - t0)
        q0, q1 = Rotation.from_matrix(p0[:3, :3]), Rotation.from_matrix(p1[:3, :3])
        dist = np.linalg.norm(p1[:3, 3] - p0[:3, 3]) + np.arccos(min(1.0, abs(np.dot(q0.as_quat(), q1.as_quat()))))
        steps = max(1, int(dist / (0.01 * extent)))
        # What the OMPL validator's checkMotion(s1, s2) runs: up to seven of
        # the sampled check's states first (a colliding one refutes), then
        # the same certified answer backwards (the new end first), the
        # contact bracketed only to 1/8.
        t0 = time.perf_counter()
        try:
            if checker.sampled_contact(p1, p0, steps) is None:
                checker.check(p1, p0, DECISION_TOLERANCE)
        except Exception:  # noqa: BLE001 - as above
            pass
        tdec.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        ok = True
        for k in range(1, steps + 1):
            s = k / steps
            r = dymsum.pose(Rotation.from_quat(_slerp(q0.as_quat(), q1.as_quat(), s)), (1 - s) * p0[:3, 3] + s * p1[:3, 3])
            oa.setTransform(fcl.Transform(r[:3, :3], r[:3, 3]))
            if fcl.collide(oa, ob, fcl.CollisionRequest(), fcl.CollisionResult()) > 0:
                ok = False
                break
        tf.append(time.perf_counter() - t0)
        counts.append(steps)
        missed += ok and not free
    td, tdec, tf = np.array(td) * 1e6, np.array(tdec) * 1e6, np.array(tf) * 1e6
    return (
        len(td), np.median(td), np.percentile(td, 99), np.median(tf), np.percentile(tf, 99), np.median(counts), missed,
        np.median(tdec), np.percentile(tdec, 99),
    )


def _slerp(a, b, s):
    if np.dot(a, b) < 0:
        b = -b
    d = min(1.0, float(np.dot(a, b)))
    th = np.arccos(d)
    if th < 1e-12:
        return a
    return (np.sin((1 - s) * th) * a + np.sin(s * th) * b) / np.sin(th)



def interleaved(poses, mine, theirs, oa, fcl):
    """Times `mine(p)` and fcl's `theirs(p)` (after posing `oa` at `p`, which
    counts in fcl's time) pose by pose, interleaved: their times in µs and
    the (mine, theirs) answers."""
    td, tf, answers = [], [], []
    for p in poses:
        t0 = time.perf_counter()
        m = mine(p)
        t1 = time.perf_counter()
        oa.setTransform(fcl.Transform(p[:3, :3], p[:3, 3]))
        t = theirs(p)
        t2 = time.perf_counter()
        td.append(t1 - t0)
        tf.append(t2 - t1)
        answers.append((m, t))
    return np.array(td) * 1e6, np.array(tf) * 1e6, answers

def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--pairs", type=int, default=20)
    ap.add_argument("--states", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--min-faces", type=int, default=0)
    ap.add_argument("--motions", type=int, default=0)
    ap.add_argument("--distance", type=int, default=0, help="free states per pair for distance_at against fcl.distance")
    ap.add_argument("--pair", action="append", default=[], help="A,B: the meshes whose paths contain A and B, instead of seeded pairs (repeatable)")
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
    def named(part):
        found = [k for k, n in enumerate(names) if part in n]
        if not found:
            sys.exit(f"--pair: no mesh's path contains {part!r}")
        return found[0]

    picks = [tuple(named(x) for x in p.split(",", 1)) for p in a.pair] or [rng.choice(len(names), 2) for _ in range(a.pairs)]
    for fa, fb in picks:
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
            td, tf, answers = interleaved(
                poses,
                checker.collides_at,
                lambda p: fcl.collide(oa, ob, fcl.CollisionRequest(), fcl.CollisionResult()) > 0,
                oa,
                fcl,
            )
            disagree = sum(mine != theirs for mine, theirs in answers)
            stack = np.stack(poses)
            runs = []
            for _ in range(5):
                t0 = time.perf_counter()
                checker.collides_many(stack)
                runs.append((time.perf_counter() - t0) / len(poses))
            many = float(np.median(runs))
            row[what] = (len(poses), np.median(td), np.median(tf), np.percentile(td, 99), np.percentile(tf, 99), many * 1e6, tf.mean(), disagree)
        if a.distance:
            free = [p for p in random + near[1::2] if not checker.collides_at(p)][: a.distance]
            tdd, tfd, answers = interleaved(
                free,
                checker.distance_at,
                lambda p: fcl.distance(oa, ob, fcl.DistanceRequest(), fcl.DistanceResult()),
                oa,
                fcl,
            )
            above = sum(mine > theirs * (1 + 1e-9) + 1e-12 for mine, theirs in answers)
            if free:
                row["distance"] = (len(free), np.median(tdd), np.median(tfd), np.percentile(tdd, 99), np.percentile(tfd, 99), above)
        if a.motions and near:
            row["motions"] = motions(fcl, checker, oa, ob, va, vb, near[1::2][: a.motions], rng)
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
    if a.motions:
        print()
        print(
            "| body | obstacle | motions | certified, bracket 1e-6: µs median (p99) | certified, decision (validator): µs median (p99) "
            "| discrete fcl µs median (p99), states | ratio of medians, bracket / decision | discrete misses |"
        )
        print("|---|---|---|---|---|---|---|---|")
        mr, mdec = [], []
        for row in rows:
            if "motions" not in row:
                continue
            n, dm, d99, fm, f99, steps, missed, cm, c99 = row["motions"]
            mr.append(dm / fm)
            mdec.append(cm / fm)
            print(
                f"| {short(row['a'])} | {short(row['b'])} | {n} | {dm:.0f} ({d99:.0f}) | {cm:.0f} ({c99:.0f}) "
                f"| {fm:.0f} ({f99:.0f}), {steps:.0f} | {dm / fm:.2f} / {cm / fm:.2f} | {missed} |"
            )
        print()
        print(
            f"Motions: ratio of medians, bracket 1e-6 gm {gm(mr):.2f} worst {max(mr or [0]):.2f}; "
            f"decision gm {gm(mdec):.2f} worst {max(mdec or [0]):.2f}"
        )
    if a.distance:
        print()
        print("| body | obstacle | free states | distance_at µs median / fcl.distance (ratio) | p99 (ratio) | above fcl |")
        print("|---|---|---|---|---|---|")
        dr = []
        for row in rows:
            if "distance" not in row:
                continue
            n, md, mf, pd, pf, above = row["distance"]
            dr.append(md / mf)
            print(f"| {short(row['a'])} | {short(row['b'])} | {n} | {md:.0f} / {mf:.0f} ({md / mf:.2f}) | {pd:.0f} / {pf:.0f} ({pd / pf:.2f}) | {above} |")
        print()
        print(f"distance_at: ratio of medians gm {gm(dr):.2f} worst {max(dr or [0]):.2f}")
    print()
    print(
        f"Ratios (dymsum / fcl): median random gm {gm(ratios['random']):.2f} worst {max(ratios['random'] or [0]):.2f}; "
        f"median near gm {gm(ratios['near']):.2f} worst {max(ratios['near'] or [0]):.2f}; "
        f"p99 gm {gm(ratios['p99']):.2f} worst {max(ratios['p99'] or [0]):.2f}; "
        f"collides_many gm {gm(ratios['many']):.2f} worst {max(ratios['many'] or [0]):.2f}"
    )


if __name__ == "__main__":
    main()
