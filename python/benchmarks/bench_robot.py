"""Robot configuration checks against pinocchio + coal (issue 37).

``python python/benchmarks/bench_robot.py [--states N] [--motions M] [--robot panda|ur5] [--shelves]``

Panda (example-robot-data's URDF, SRDF and collision meshes, shipped in
``python/tests/data/panda``) or UR5 (an installed ``example-robot-data``),
self-collision, the SRDF's pairs removed in both tools; with
``--shelves`` also against ``python/examples/robot_shelves.py``'s table
and shelf (seven boxes, coal's ``Box`` in pinocchio, every robot geometry
paired with every box). Per random configuration within the limits, one
call each, timed interleaved in one process: dymsum's
``RobotChecker.collides_at(q)`` against pinocchio's
``computeCollisions(model, data, geom, gdata, q, True)`` (forward
kinematics, geometry placements and the pairs, stopping at the first
contact). ``collides_many`` on all configurations at once, per
configuration. Motions: from free configurations, a tenth of the way to
another random one: dymsum's certified ``check(q0, q1)`` (the contact
bracketed to 1/8, as a planner's yes/no asks) against pinocchio at
joint-space steps of 0.01 rad (the largest joint change over the step
count, OMPL's ``DiscreteMotionValidator`` at that resolution).
Medians and 99th percentiles in µs and their ratios (dymsum / pinocchio).
"""

import argparse
import os
import shutil
import sys
import time

import numpy as np

import dymsum

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--states", type=int, default=2000)
    ap.add_argument("--motions", type=int, default=100)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--robot", choices=["panda", "ur5"], default="panda")
    ap.add_argument("--shelves", action="store_true")
    a = ap.parse_args()
    from bench_robot_plan import Pinocchio, rs, urdf_paths

    paths = urdf_paths(a.robot)
    try:
        urdf, srdf, root = paths
        obstacles = rs.scene() if a.shelves else []
        t0 = time.perf_counter()
        robot = dymsum.Robot.from_urdf(urdf, srdf=srdf, package_dirs=[root])
        checker = dymsum.RobotChecker(robot, obstacles)
        build_d = time.perf_counter() - t0
        t0 = time.perf_counter()
        pino = Pinocchio(a.robot, robot, paths, obstacles)
        build_p = time.perf_counter() - t0
    finally:
        if a.robot == "panda":
            shutil.rmtree(paths[2], ignore_errors=True)
    pin = pino.pin
    model, data, geom, gdata = pino.model, pino.data, pino.geom, pino.gdata
    pq = pino.q
    limits = np.array(robot.joint_limits)
    rng = np.random.default_rng(a.seed)
    qs = limits[:, 0] + (limits[:, 1] - limits[:, 0]) * rng.random((a.states, robot.dof))
    td, tp, hits = [], [], 0
    for q in qs:
        t0 = time.perf_counter()
        ours = checker.collides_at(q)
        td.append(time.perf_counter() - t0)
        p = pq(q)
        t0 = time.perf_counter()
        pin.computeCollisions(model, data, geom, gdata, p, True)
        tp.append(time.perf_counter() - t0)
        hits += ours
    t0 = time.perf_counter()
    checker.collides_many(qs)
    many = (time.perf_counter() - t0) / len(qs)
    td, tp = np.array(td) * 1e6, np.array(tp) * 1e6
    print(f"{a.robot}{' among the shelves' if a.shelves else ''}: {len(robot.collision_pairs)} link pairs (dymsum), {len(geom.collisionPairs)} geometry pairs (pinocchio); build {build_d * 1e3:.0f} ms / {build_p * 1e3:.0f} ms")
    print("| states | colliding | median µs dymsum / pinocchio (ratio) | p99 µs (ratio) | collides_many µs per state (ratio to pinocchio's median) |")
    print("|---|---|---|---|---|")
    md, mp = np.median(td), np.median(tp)
    qd, qp = np.percentile(td, 99), np.percentile(tp, 99)
    print(f"| {len(qs)} | {hits} | {md:.1f} / {mp:.1f} ({md / mp:.2f}) | {qd:.0f} / {qp:.0f} ({qd / qp:.2f}) | {many * 1e6:.1f} ({many * 1e6 / mp:.2f}) |")
    if a.motions:
        from dymsum.ompl import DECISION_TOLERANCE

        tm, tdisc, missed, n = [], [], 0, 0
        while n < a.motions:
            q0 = limits[:, 0] + (limits[:, 1] - limits[:, 0]) * rng.random(robot.dof)
            if checker.collides_at(q0):
                continue
            q1 = q0 + 0.1 * (limits[:, 0] + (limits[:, 1] - limits[:, 0]) * rng.random(robot.dof) - q0)
            n += 1
            t0 = time.perf_counter()
            try:
                free = checker.check(q0, q1, DECISION_TOLERANCE).free
            except dymsum.MotionUndecided:
                free = False
            tm.append(time.perf_counter() - t0)
            steps = max(1, int(np.ceil(np.max(np.abs(q1 - q0)) / 0.01)))
            t0 = time.perf_counter()
            ok = True
            for k in range(1, steps + 1):
                if pin.computeCollisions(model, data, geom, gdata, pq(q0 + (q1 - q0) * k / steps), True):
                    ok = False
                    break
            tdisc.append(time.perf_counter() - t0)
            missed += ok and not free
        tm, tdisc = np.array(tm) * 1e6, np.array(tdisc) * 1e6
        print()
        print("| motions | certified µs median (p99) | discrete pinocchio µs median (p99) | ratio of medians | accepted by the discrete check, colliding |")
        print("|---|---|---|---|---|")
        print(f"| {n} | {np.median(tm):.0f} ({np.percentile(tm, 99):.0f}) | {np.median(tdisc):.0f} ({np.percentile(tdisc, 99):.0f}) | {np.median(tm) / np.median(tdisc):.2f} | {missed} |")


if __name__ == "__main__":
    main()
