"""Plan an L-shaped body through two thin walls with OMPL, in SE(2).

The walls (0.02 thick) are far thinner than the step at which OMPL's
default ``DiscreteMotionValidator`` samples motions (1% of the space's
extent: 0.157 here), and the body's thin arm can be carried across a wall
between two samples. dymsum's validators check states exactly and motions
with a certificate, so the path found never crosses a wall.

    python python/examples/ompl_se2.py [--discrete] [--seed N] [--time SECONDS]

``--discrete`` plans with OMPL's DiscreteMotionValidator (and dymsum's exact
state check) instead, for comparison. Prints whether a path was found, its
length, the planning time, and whether every motion of the path is
certified free. Needs OMPL (``pip install ompl``).
"""

from __future__ import annotations

import argparse
import math

import numpy as np

import dymsum
import dymsum.ompl


def box(lo, hi):
    """The 8 corners of an axis-aligned box."""
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])], float)


#: The workspace: x and y in [-5, 5].
BOUNDS = (-5.0, 5.0)
#: Start and goal: (x, y, yaw).
START = (-4.0, -3.0, math.pi / 2)
GOAL = (4.0, 3.0, -math.pi / 2)


def scene():
    """``(robot, obstacles)``: an L of two boxes (a bar 1.0 long, 0.08
    wide, and an arm 0.3 long), and two walls 0.02 thick across the
    workspace, each with a gap 0.6 wide (at y = 2 and y = -2)."""
    robot = dymsum.ConvexUnion([box([-0.5, -0.04, -0.1], [0.5, 0.04, 0.1]), box([0.42, 0.04, -0.1], [0.5, 0.3, 0.1])])
    obstacles = []
    for x, gap in ((-1.5, 2.0), (1.5, -2.0)):
        lo, hi = x - 0.01, x + 0.01
        obstacles.append(box([lo, -5.0, -1.0], [hi, gap - 0.3, 1.0]))
        obstacles.append(box([lo, gap + 0.3, -1.0], [hi, 5.0, 1.0]))
    return robot, obstacles


def simple_setup(discrete=False):
    """An OMPL ``SimpleSetup`` of the scene with RRTConnect, and the
    validators dymsum installed (``dymsum.ompl.Validators``)."""
    from ompl import base as ob
    from ompl import geometric as og

    space = ob.SE2StateSpace()
    bounds = ob.RealVectorBounds(2)
    bounds.setLow(BOUNDS[0])
    bounds.setHigh(BOUNDS[1])
    space.setBounds(bounds)
    ss = og.SimpleSetup(space)
    robot, obstacles = scene()
    if discrete:
        validators = dymsum.ompl.setup_state_checker(ss, robot, obstacles)
    else:
        validators = dymsum.ompl.setup_validators(ss, robot, obstacles)
    start, goal = space.allocState(), space.allocState()
    for state, (x, y, yaw) in ((start, START), (goal, GOAL)):
        state.setXY(x, y)
        state.setYaw(yaw)
    ss.setStartAndGoalStates(start, goal)
    ss.setPlanner(og.RRTConnect(ss.getSpaceInformation()))
    ss.setup()
    return ss, validators


def plan(discrete=False, seconds=10.0, simplify=True):
    """Plans once: a dict with ``found`` (an exact solution), ``length``,
    ``time`` (OMPL's planning time, s), ``simplify_time``, ``states``,
    ``certified`` (every motion of the path certified free by dymsum) and
    ``validators``."""
    ss, validators = simple_setup(discrete)
    out = dymsum.ompl.solve_and_certify(ss, validators.checker, seconds, simplify)
    out["validators"] = validators
    return out


def main():
    from ompl import util as ou

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--discrete", action="store_true", help="OMPL's DiscreteMotionValidator instead")
    parser.add_argument("--seed", type=int, default=1, help="OMPL's random seed (default 1)")
    parser.add_argument("--time", type=float, default=10.0, help="planning time limit in seconds")
    args = parser.parse_args()
    ou.setLogLevel(ou.LOG_WARN)
    ou.RNG.setSeed(args.seed)
    r = plan(args.discrete, args.time)
    which = "OMPL's DiscreteMotionValidator" if args.discrete else "dymsum's certified validator"
    print(f"SE(2), L-shaped body through two walls 0.02 thick; motions checked by {which}")
    if not r["found"]:
        print(f"no path found in {r['time']:.3f} s")
        return 1
    print(f"path found: length {r['length']:.3f} ({r['states']} states) in {r['time']:.3f} s of planning")
    verdict = "yes" if r["certified"] else f"NO: {r['uncertified_motions']} of its motions touch a wall"
    print(f"every motion of the path certified free by dymsum: {verdict}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
