"""Plan an arm (Panda or UR5) into a shelf with OMPL's RRTConnect in joint
space, every motion certified (issue 37).

The scene, in the robot base's frame (metres; x in front of the robot):

* a table top 0.8 × 1.2 × 0.04 whose upper face is level with the base
  (z = 0), its near edge 0.3 in front of it (x from 0.3 to 1.1, y from
  −0.6 to 0.6);
* a shelf 0.3 deep on the table's far half (x from 0.7 to 1.0), boards
  (0.02 thick) every 0.3 up to 0.9, side walls and a back.

The start holds the arm raised above the table; the goal puts the hand in
the middle compartment (between the boards at 0.3 and 0.6): Panda's tool
point at about (0.88, −0.03, 0.39), UR5's flange (``ee_link``, no gripper)
at (0.76, 0, 0.42) pointing into the shelf. Both are checked free.
dymsum's joint-space validators (``dymsum.ompl.setup_joint_validators``)
check states exactly and accept a motion only with a certificate. Prints
whether a path was found, how many motions the validator certified, and
whether every motion of the path found is certified free again.

    python python/examples/robot_shelves.py [--robot panda|ur5] [--time SECONDS] [--seed N]

Needs OMPL (``pip install ompl``); reads Panda from
``python/tests/data/panda`` (example-robot-data, Apache-2.0) and UR5 from
an installed ``example-robot-data`` (``pip install example-robot-data``).
"""

from __future__ import annotations

import argparse
import os
import shutil
import sysconfig
import tempfile

import numpy as np

import dymsum
import dymsum.ompl

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "panda")
#: Where ``pip install example-robot-data`` puts its robots' packages.
SHARE = os.path.join(sysconfig.get_paths()["purelib"], "cmeel.prefix", "share")


def box(lo, hi):
    """The 8 corners of an axis-aligned box."""
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])], float)


def scene():
    """The table and the shelf (module docs), as convex boxes."""
    t = 0.02
    x0, x1 = 0.7, 1.0
    parts = [box([0.3, -0.6, -0.04], [1.1, 0.6, 0.0])]
    parts += [box([x0, -0.6, z - t / 2], [x1, 0.6, z + t / 2]) for z in (0.3, 0.6, 0.9)]
    parts += [
        box([x0, -0.6 - t, 0.0], [x1, -0.6, 0.9 + t / 2]),
        box([x0, 0.6, 0.0], [x1, 0.6 + t, 0.9 + t / 2]),
        box([x1, -0.6 - t, 0.0], [x1 + t, 0.6 + t, 0.9 + t / 2]),
    ]
    return parts


def panda() -> dymsum.Robot:
    """Panda, its ``package://`` meshes found under a temporary root."""
    root = tempfile.mkdtemp()
    try:
        meshes = os.path.join(root, "example-robot-data", "robots", "panda_description", "meshes", "collision")
        os.makedirs(meshes)
        for name in os.listdir(DATA):
            if name.endswith(".stl"):
                shutil.copy(os.path.join(DATA, name), meshes)
        return dymsum.Robot.from_urdf(
            os.path.join(DATA, "panda.urdf"), srdf=os.path.join(DATA, "panda.srdf"), package_dirs=[root]
        )
    finally:
        shutil.rmtree(root, ignore_errors=True)


def ur5() -> dymsum.Robot:
    """UR5 as example-robot-data ships it (Collada meshes, its SRDF)."""
    ur = os.path.join(SHARE, "example-robot-data", "robots", "ur_description")
    if not os.path.isdir(ur):
        raise FileNotFoundError(f"example-robot-data is not installed ({ur}): pip install example-robot-data")
    return dymsum.Robot.from_urdf(
        os.path.join(ur, "urdf", "ur5_robot.urdf"), srdf=os.path.join(ur, "srdf", "ur5.srdf"), package_dirs=[SHARE]
    )


#: Per robot: its loader, the start (the arm raised above the table), the
#: goal (the hand in the middle compartment) and the link that must be
#: there.
ROBOTS = {
    "panda": (panda, [0.0, -0.3, 0.0, -1.2, 0.0, 1.5, 0.8, 0.02],
              [-2.519, -1.079, 2.049, -1.139, 1.713, 2.747, 2.762, 0.026], "panda_hand_tcp"),
    "ur5": (ur5, [0.0, -1.571, 0.0, -1.571, 0.0, 0.0],
            [-0.162, -0.331, -0.492, 0.822, 1.409, 0.206], "ee_link"),
}


def problem(name: str = "panda"):
    """The robot, the checker against the scene, the start and the goal."""
    load, start, goal, hand = ROBOTS[name]
    robot = load()
    tcp = robot.forward(goal)[robot.link_names.index(hand)][:3, 3]
    assert 0.7 < tcp[0] < 1.0 and 0.3 < tcp[2] < 0.6, tcp  # in the middle compartment
    return robot, dymsum.RobotChecker(robot, scene()), start, goal


def joint_space(robot: dymsum.Robot):
    """OMPL's ``RealVectorStateSpace`` of the robot's degrees of freedom,
    bounded by its joint limits."""
    from ompl import base as ob

    space = ob.RealVectorStateSpace(robot.dof)
    bounds = ob.RealVectorBounds(robot.dof)
    for i, (lo, hi) in enumerate(robot.joint_limits):
        bounds.setLow(i, lo)
        bounds.setHigh(i, hi)
    space.setBounds(bounds)
    return space


def plan(seconds: float = 30.0, seed: int = 1, robot_name: str = "panda") -> dict:
    from ompl import geometric as og
    from ompl import util as ou

    ou.RNG.setSeed(seed)
    robot, checker, start_q, goal_q = problem(robot_name)
    space = joint_space(robot)
    ss = og.SimpleSetup(space)
    v = dymsum.ompl.setup_joint_validators(ss, checker)
    start, goal = space.allocState(), space.allocState()
    for state, q in ((start, start_q), (goal, goal_q)):
        for i, x in enumerate(q):
            state[i] = x
        assert v.state_checker(state), f"{q} is not free"
    ss.setStartAndGoalStates(start, goal)
    ss.setPlanner(og.RRTConnect(ss.getSpaceInformation()))
    solved = bool(ss.solve(seconds)) and ss.haveExactSolutionPath()
    out = {
        "found": solved,
        "time": ss.getLastPlanComputationTime(),
        "motions_checked": v.motion_validator.checked,
        "motions_certified": v.motion_validator.checked - v.motion_validator.rejected,
    }
    if solved:
        ss.simplifySolution()
        qs = [v.state_checker.q(s) for s in ss.getSolutionPath().getStates()]
        out["path_motions"] = len(qs) - 1
        out["path_certified"] = all(checker.check(a, b).free for a, b in zip(qs, qs[1:]))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--robot", choices=sorted(ROBOTS), default="panda")
    ap.add_argument("--time", type=float, default=30.0)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    r = plan(a.time, a.seed, a.robot)
    print(f"found: {r['found']} in {r['time']:.2f} s")
    print(f"motions certified by the validator: {r['motions_certified']} of {r['motions_checked']} checked")
    if r["found"]:
        print(f"path: {r['path_motions']} motions, every one certified free again: {r['path_certified']}")


if __name__ == "__main__":
    main()
