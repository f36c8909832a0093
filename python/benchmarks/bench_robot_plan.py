"""Planning an arm among a table and shelves: dymsum against pinocchio +
coal (issue 37's targets).

``python python/benchmarks/bench_robot_plan.py [--robots panda ur5] [--runs 10] [--time 30] [--loads 5]``

The scene and the problems are ``python/examples/robot_shelves.py``'s
(Panda from ``python/tests/data/panda``, UR5 from an installed
``example-robot-data``), the obstacles in both tools as the same seven
boxes (coal's ``Box`` in pinocchio's geometry model, every robot geometry
paired with every box; the SRDF's pairs removed from the self pairs).
Three measurements per robot:

1. **Loading**, cold, each in a fresh process (``--loads`` of them, the
   median): dymsum's ``Robot.from_urdf`` + ``RobotChecker(robot)``
   against pinocchio's ``buildModelFromUrdf`` + ``buildGeomFromUrdf`` +
   ``addAllCollisionPairs`` + ``removeCollisionPairs`` + the data
   structures; mesh reading included, the modules' import not.
2. **RRTConnect**, ``--runs`` runs each, the two tools alternating, OMPL's
   generator seeded once (``--seed``), the time limit ``--time`` s: dymsum's validators
   (``dymsum.ompl.setup_joint_validators``: exact states, certified
   motions) against a state checker calling pinocchio's
   ``computeCollisions(..., True)`` with OMPL's own
   ``DiscreteMotionValidator`` at its default resolution (1% of the
   space's extent). Solve rate, median solve time (an unsolved run counts
   at the limit), and the discrete runs whose path has a motion that
   collides (each motion of the path checked by dymsum's certified
   ``check``; such a run is counted as solved in the rate, as a user of the
   discrete check would believe; a motion dymsum leaves undecided, grazing
   within rounding, is counted apart).
3. **The motions RRTConnect asks**: every motion dymsum's validator was
   asked in the runs above (recorded), timed again one call each,
   interleaved: dymsum's ``JointMotionValidator.checkMotion`` (the states
   OMPL would sample checked exactly in one ``collides_many`` call, then,
   unless one collides, the certified ``check(s2, s1, 1/8)``) against the
   discrete check at OMPL's resolution done with pinocchio in a Python
   loop (the end state first, then the intermediate states in order,
   stopping at the first contact: what ``DiscreteMotionValidator`` does,
   without its callback overhead).

Prints Markdown rows for docs/BENCHMARKS.md.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "examples"))

import robot_shelves as rs  # noqa: E402

import dymsum  # noqa: E402
import dymsum.ompl  # noqa: E402


def urdf_paths(name):
    """(urdf, srdf, package_dirs) of a robot of the example; Panda's meshes
    are copied under a temporary package root (the caller removes it)."""
    import shutil
    import tempfile

    if name == "panda":
        root = tempfile.mkdtemp()
        meshes = os.path.join(root, "example-robot-data", "robots", "panda_description", "meshes", "collision")
        os.makedirs(meshes)
        for f in os.listdir(rs.DATA):
            if f.endswith(".stl"):
                shutil.copy(os.path.join(rs.DATA, f), meshes)
        return os.path.join(rs.DATA, "panda.urdf"), os.path.join(rs.DATA, "panda.srdf"), root
    ur = os.path.join(rs.SHARE, "example-robot-data", "robots", "ur_description")
    return os.path.join(ur, "urdf", "ur5_robot.urdf"), os.path.join(ur, "srdf", "ur5.srdf"), rs.SHARE


LOAD_DYMSUM = """
import sys, time, dymsum
urdf, srdf, root = sys.argv[1:4]
t = time.perf_counter()
robot = dymsum.Robot.from_urdf(urdf, srdf=srdf, package_dirs=[root])
checker = dymsum.RobotChecker(robot)
print(time.perf_counter() - t)
"""

LOAD_PINOCCHIO = """
import sys, time, pinocchio as pin
urdf, srdf, root = sys.argv[1:4]
t = time.perf_counter()
model = pin.buildModelFromUrdf(urdf)
geom = pin.buildGeomFromUrdf(model, urdf, pin.GeometryType.COLLISION, package_dirs=[root])
geom.addAllCollisionPairs()
pin.removeCollisionPairs(model, geom, srdf)
data, gdata = model.createData(), pin.GeometryData(geom)
print(time.perf_counter() - t)
"""


def cold_load(code, paths, n):
    """The median of ``n`` fresh processes' load times (s)."""
    times = []
    for _ in range(n):
        out = subprocess.run([sys.executable, "-c", code, *paths], capture_output=True, text=True, check=True)
        times.append(float(out.stdout.strip().splitlines()[-1]))
    return float(np.median(times))


class Pinocchio:
    """pinocchio + coal on the same robot and scene."""

    def __init__(self, name, robot, paths, obstacles=None):
        import coal
        import pinocchio as pin

        urdf, srdf, root = paths
        self.pin = pin
        self.model = pin.buildModelFromUrdf(urdf)
        self.geom = pin.buildGeomFromUrdf(self.model, urdf, pin.GeometryType.COLLISION, package_dirs=[root])
        self.geom.addAllCollisionPairs()
        pin.removeCollisionPairs(self.model, self.geom, srdf)
        robot_geoms = range(self.geom.ngeoms)
        for k, corners in enumerate(rs.scene() if obstacles is None else obstacles):
            lo, hi = corners.min(axis=0), corners.max(axis=0)
            placement = pin.SE3(np.eye(3), (lo + hi) / 2)
            obj = pin.GeometryObject(f"obstacle{k}", 0, 0, placement, coal.Box(*(hi - lo)))
            o = self.geom.addGeometryObject(obj)
            for g in robot_geoms:
                if self.geom.geometryObjects[g].parentJoint != 0:
                    self.geom.addCollisionPair(pin.CollisionPair(g, o))
        self.data, self.gdata = self.model.createData(), pin.GeometryData(self.geom)
        # dymsum's configuration to pinocchio's: a mimic joint is an
        # independent one there (Panda's second finger follows the first).
        names = list(robot.joint_names)
        self.index = [names.index(n) if n in names else names.index("panda_finger_joint1")
                      for n in self.model.names[1:]]

    def q(self, q):
        return np.asarray(q, float)[self.index]

    def collides(self, q):
        return self.pin.computeCollisions(self.model, self.data, self.geom, self.gdata, self.q(q), True)


def plan_once(name, seconds, tool, pinocchio=None, record=None):
    """One RRTConnect run; returns (solved, time, path configurations)."""
    from ompl import geometric as og

    robot, checker, start_q, goal_q = rs.problem(name)
    space = rs.joint_space(robot)
    ss = og.SimpleSetup(space)
    n = robot.dof
    if tool == "dymsum":
        dymsum.ompl.setup_joint_validators(ss, checker)
        if record is not None:

            class Recording(dymsum.ompl.JointMotionValidator):
                def checkMotion(self, s1, s2):  # noqa: N802
                    record.append(([s1[i] for i in range(n)], [s2[i] for i in range(n)]))
                    return super().checkMotion(s1, s2)

            recording = Recording(ss.getSpaceInformation(), checker)
            ss.getSpaceInformation().setMotionValidator(recording)
            plan_once.keep = recording  # alive while OMPL holds it
    else:
        si = ss.getSpaceInformation()
        sat = space.satisfiesBounds

        def valid(s):
            return sat(s) and not pinocchio.collides([s[i] for i in range(n)])

        ss.setStateValidityChecker(valid)
        si.setStateValidityCheckingResolution(0.01)
    start, goal = space.allocState(), space.allocState()
    for state, q in ((start, start_q), (goal, goal_q)):
        for i, x in enumerate(q):
            state[i] = x
    ss.setStartAndGoalStates(start, goal)
    ss.setPlanner(og.RRTConnect(ss.getSpaceInformation()))
    t0 = time.perf_counter()
    solved = bool(ss.solve(seconds)) and ss.haveExactSolutionPath()
    took = time.perf_counter() - t0
    path = [[s[i] for i in range(n)] for s in ss.getSolutionPath().getStates()] if solved else []
    return solved, took, path, checker


def replay_validator(robot, checker):
    """dymsum's joint motion validator on a fresh space with the robot's
    bounds, and the space."""
    from ompl import base as ob

    space = rs.joint_space(robot)
    si = ob.SpaceInformation(space)
    v = dymsum.ompl.setup_joint_validators(si, checker)
    si.setup()
    replay_validator.keep = (si, v)
    return v.motion_validator, space


def discrete(pinocchio, q0, q1, extent):
    """OMPL's DiscreteMotionValidator at resolution 0.01 of ``extent``,
    with pinocchio: free when no state checked collides."""
    q0, q1 = np.asarray(q0), np.asarray(q1)
    nd = int(np.ceil(np.linalg.norm(q1 - q0) / (0.01 * extent)))
    if pinocchio.collides(q1):
        return False
    for k in range(1, nd):
        if pinocchio.collides(q0 + (q1 - q0) * k / nd):
            return False
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--robots", nargs="+", default=["panda", "ur5"], choices=sorted(rs.ROBOTS))
    ap.add_argument("--runs", type=int, default=10)
    ap.add_argument("--time", type=float, default=30.0)
    ap.add_argument("--loads", type=int, default=5)
    ap.add_argument("--motions", type=int, default=400, help="at most this many recorded motions timed")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", help="write the figures here too")
    ap.add_argument("--dump", help="write the recorded motions (s1, s2) to DUMP_robot.json")
    a = ap.parse_args()
    from ompl import util as ou

    ou.RNG.setSeed(a.seed)  # once: OMPL seeds its generators only before their first use
    rows = {}
    for name in a.robots:
        paths = urdf_paths(name)
        try:
            load_d = cold_load(LOAD_DYMSUM, paths, a.loads) if a.loads else float("nan")
            load_p = cold_load(LOAD_PINOCCHIO, paths, a.loads) if a.loads else float("nan")
            robot, _, _, _ = rs.problem(name)
            pino = Pinocchio(name, robot, paths)
        finally:
            if name == "panda":
                import shutil

                shutil.rmtree(paths[2], ignore_errors=True)
        record = []
        runs = {"dymsum": [], "pinocchio": []}
        bad_paths = unsure_paths = 0
        checker = None
        for _ in range(a.runs):
            for tool in ("dymsum", "pinocchio"):
                solved, took, path, checker = plan_once(name, a.time, tool, pino, record if tool == "dymsum" else None)
                runs[tool].append((solved, took if solved else a.time))
                if tool == "pinocchio" and solved:
                    bad = unsure = False
                    for q0, q1 in zip(path, path[1:]):
                        try:
                            bad |= not checker.check(q0, q1).free
                        except dymsum.MotionUndecided:
                            unsure = True
                    bad_paths += bad
                    unsure_paths += unsure and not bad
        if a.dump:
            with open(f"{a.dump}_{name}.json", "w") as f:
                json.dump(record, f)
        limits = np.array(robot.joint_limits)
        extent = float(np.linalg.norm(limits[:, 1] - limits[:, 0]))
        rng = np.random.default_rng(0)
        motions = record if len(record) <= a.motions else [record[i] for i in sorted(rng.choice(len(record), a.motions, replace=False))]
        td, tp, missed, undecided = [], [], 0, 0
        # Replayed through dymsum's validator itself (the sampled states,
        # then the certificate), on a space with the same bounds.
        validator, space = replay_validator(robot, checker)
        st1, st2 = space.allocState(), space.allocState()
        for s1, s2 in motions:
            for state, q in ((st1, s1), (st2, s2)):
                for i, x in enumerate(q):
                    state[i] = x
            before = validator.undecided
            t0 = time.perf_counter()
            free = validator.checkMotion(st1, st2)
            td.append(time.perf_counter() - t0)
            decided = validator.undecided == before
            t0 = time.perf_counter()
            ok = discrete(pino, s1, s2, extent)
            tp.append(time.perf_counter() - t0)
            missed += ok and not free and decided
            undecided += not decided
        td, tp = np.array(td) * 1e6, np.array(tp) * 1e6
        row = {
            "load_ms": (load_d * 1e3, load_p * 1e3),
            "solved": tuple(sum(s for s, _ in runs[t]) for t in ("dymsum", "pinocchio")),
            "median_s": tuple(float(np.median([t for _, t in runs[k]])) for k in ("dymsum", "pinocchio")),
            "bad_paths": bad_paths,
            "undecided_paths": unsure_paths,
            "motions": len(motions),
            "motion_us": (float(np.median(td)), float(np.median(tp)), float(np.percentile(td, 99)), float(np.percentile(tp, 99))),
            "missed": missed,
            "undecided": undecided,
        }
        rows[name] = row
        print(name, json.dumps(row), flush=True)
    print()
    print("| robot | load ms dymsum / pinocchio (ratio) | solved of runs dymsum / pinocchio | median s dymsum / pinocchio (ratio) | discrete paths with a colliding motion (with one undecided) |")
    print("|---|---|---|---|---|")
    for name, r in rows.items():
        (ld, lp), (sd, sp), (md, mp) = r["load_ms"], r["solved"], r["median_s"]
        print(f"| {name} | {ld:.0f} / {lp:.0f} ({ld / lp:.2f}) | {sd} / {sp} of {a.runs} | {md:.2f} / {mp:.2f} ({md / mp:.2f}) | {r['bad_paths']} ({r['undecided_paths']}) |")
    print()
    print("| robot | motions RRTConnect asked | certified µs median (p99) | discrete pinocchio µs median (p99) | ratio of medians | accepted by the discrete check, colliding (undecided by dymsum) |")
    print("|---|---|---|---|---|---|")
    for name, r in rows.items():
        md, mp, qd, qp = r["motion_us"]
        print(f"| {name} | {r['motions']} | {md:.0f} ({qd:.0f}) | {mp:.0f} ({qp:.0f}) | {md / mp:.2f} | {r['missed']} ({r['undecided']}) |")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
