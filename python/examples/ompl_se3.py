"""Plan an L-shaped body through the windows of two thin plates with OMPL,
in SE(3).

The plates (0.02 thick) are far thinner than the step at which OMPL's
default ``DiscreteMotionValidator`` samples motions (1% of the space's
extent: 0.12 here), so a body can be carried across a plate between two
samples. dymsum's validators check states exactly and motions with a
certificate, so the path found passes through the windows.

    python python/examples/ompl_se3.py [--discrete] [--seed N] [--time SECONDS]

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


#: The workspace: x, y and z in [-3, 3].
BOUNDS = (-3.0, 3.0)
#: Start and goal: (x, y, z) and a quaternion (x, y, z, w): the bar upright
#: at the start (a quarter turn about y), across at the goal (about z).
_H = math.sqrt(0.5)
START = ((-2.2, 0.0, 0.0), (0.0, _H, 0.0, _H))
GOAL = ((2.2, 0.0, 0.0), (0.0, 0.0, _H, _H))


def plate(x, window_y, window_z, half=0.45):
    """A plate 0.02 thick across the workspace at ``x``, with a square
    window (side ``2 * half``) centred at ``(window_y, window_z)``: four
    boxes."""
    lo, hi = x - 0.01, x + 0.01
    y0, y1, z0, z1 = window_y - half, window_y + half, window_z - half, window_z + half
    return [
        box([lo, -3.0, -3.0], [hi, y0, 3.0]),
        box([lo, y1, -3.0], [hi, 3.0, 3.0]),
        box([lo, y0, -3.0], [hi, y1, z0]),
        box([lo, y0, z1], [hi, y1, 3.0]),
    ]


def scene():
    """``(robot, obstacles)``: an L of two boxes (a bar 1.0 long, 0.08
    thick, and an arm 0.3 long), and two plates 0.02 thick with windows
    0.9 wide, at x = -0.8 (window at the centre) and x = 0.8 (window at
    y = 0.5, z = -0.5)."""
    robot = dymsum.ConvexUnion(
        [box([-0.5, -0.04, -0.04], [0.5, 0.04, 0.04]), box([0.42, 0.04, -0.04], [0.5, 0.3, 0.04])]
    )
    return robot, plate(-0.8, 0.0, 0.0) + plate(0.8, 0.5, -0.5)


def simple_setup(discrete=False):
    """An OMPL ``SimpleSetup`` of the scene with RRTConnect, and the
    validators dymsum installed (``dymsum.ompl.Validators``)."""
    from ompl import base as ob
    from ompl import geometric as og

    space = ob.SE3StateSpace()
    bounds = ob.RealVectorBounds(3)
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
    for state, ((x, y, z), (qx, qy, qz, qw)) in ((start, START), (goal, GOAL)):
        state.setXYZ(x, y, z)
        r = state.rotation()
        r.x, r.y, r.z, r.w = qx, qy, qz, qw
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
    print(f"SE(3), L-shaped body through the windows of two plates 0.02 thick; motions checked by {which}")
    if not r["found"]:
        print(f"no path found in {r['time']:.3f} s")
        return 1
    print(f"path found: length {r['length']:.3f} ({r['states']} states) in {r['time']:.3f} s of planning")
    verdict = "yes" if r["certified"] else f"NO: {r['uncertified_motions']} of its motions touch a plate"
    print(f"every motion of the path certified free by dymsum: {verdict}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
