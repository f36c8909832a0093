"""Plan an OMPL.app 3-D rigid-body problem with OMPL, checking collisions
with dymsum or with FCL.

OMPL.app ships its problems (cubicles, Twistycool, Home, Apartment, ...)
as a ``.cfg`` naming a robot mesh and an environment mesh; dymsum does not
ship them (OMPL.app's licence), get them from OMPL.app's ``resources/3D``.

    python python/examples/ompl_app.py PATH/TO/problem.cfg [--planner RRTConnect]
        [--time SECONDS] [--checker dymsum|fcl] [--runs N] [--seed S]

``--checker dymsum`` (the default) plans with dymsum's validators: the
state validity check is the exact ``MotionChecker.collides_at`` and every
motion is accepted only when ``MotionChecker.check`` certifies it free
(``dymsum.ompl.setup_validators``). ``--checker fcl`` plans as OMPL.app
does: python-fcl's ``collide`` on the two BVH models as the state validity
check, and OMPL's default ``DiscreteMotionValidator`` (states 1% of the
space's extent apart) for motions. The time limit is the ``.cfg``'s, at
most 60 s, unless ``--time`` is given. Prints, per run, whether an exact
solution was found, the planning time, the path's length, how many state
and motion checks the planner asked and, with dymsum, how many motions were
certified free. Needs OMPL (``pip install ompl``), pycollada for the
``.dae`` meshes and, for ``--checker fcl``, python-fcl.

``main(argv)`` returns each run's result, the path as 4×4 poses included:
the tests run it on the small ``window`` scene of
``python/tests/data/omplapp`` (which is dymsum's own) and check its path.
"""

from __future__ import annotations

import argparse
import statistics

import numpy as np

import dymsum
import dymsum.ompl
from dymsum.omplapp import load_problem, read_cfg


def state_pose(s):
    """The 4×4 pose of an OMPL SE(3) state."""
    q = s.rotation()
    return dymsum.ompl.se3_pose(s.getX(), s.getY(), s.getZ(), q.x, q.y, q.z, q.w)


def fcl_object(vertices, faces):
    """A python-fcl collision object of a triangle mesh (a BVHModel, OBBRSS,
    as OMPL.app's FCL checker builds it)."""
    import fcl

    model = fcl.BVHModel()
    model.beginModel(len(vertices), len(faces))
    model.addSubModel(np.ascontiguousarray(vertices, float), np.ascontiguousarray(faces, np.int64))
    model.endModel()
    return fcl.CollisionObject(model, fcl.Transform())


class FclStateChecker:
    """OMPL state validity with python-fcl: within the bounds and no
    ``fcl.collide`` between the robot, moved to the state, and the
    environment. ``checked`` counts the calls."""

    def __init__(self, space, problem):
        import fcl

        self.fcl = fcl
        self.robot = fcl_object(problem.robot_vertices, problem.robot_faces)
        self.env = fcl_object(problem.env_vertices, problem.env_faces)
        self.satisfies_bounds = space.satisfiesBounds  # not the space information: no cycle
        self.checked = 0

    def collides(self, pose):
        fcl = self.fcl
        self.robot.setTransform(fcl.Transform(pose[:3, :3], pose[:3, 3]))
        return fcl.collide(self.robot, self.env, fcl.CollisionRequest(), fcl.CollisionResult()) > 0

    def __call__(self, s):
        self.checked += 1
        if not self.satisfies_bounds(s):
            return False
        return not self.collides(state_pose(s))


def simple_setup(problem, checker="dymsum", planner="RRTConnect", motion_checker=None):
    """An OMPL ``SimpleSetup`` of the problem (SE(3), the ``.cfg``'s bounds,
    start and goal) with the chosen checker and planner. Returns ``(ss,
    counters)``: ``counters()`` gives ``(state checks, motion checks,
    motions certified free or None)``. ``motion_checker``: a prepared
    ``dymsum.MotionChecker`` of the problem, to build it once for many runs."""
    from ompl import base as ob
    from ompl import geometric as og

    space = ob.SE3StateSpace()
    bounds = ob.RealVectorBounds(3)
    for i in range(3):
        bounds.setLow(i, float(problem.bounds[0][i]))
        bounds.setHigh(i, float(problem.bounds[1][i]))
    space.setBounds(bounds)
    ss = og.SimpleSetup(space)
    si = ss.getSpaceInformation()
    if checker == "dymsum":
        if motion_checker is None:
            motion_checker = dymsum.MotionChecker((problem.robot_vertices, problem.robot_faces), [(problem.env_vertices, problem.env_faces)])
        v = dymsum.ompl.setup_validators(si, motion_checker)
        state_checker, validator = v.state_checker, v.motion_validator

        def counters():
            return state_checker.checked, validator.checked, validator.checked - validator.rejected
    elif checker == "fcl":
        state_checker = FclStateChecker(space, problem)
        si.setStateValidityChecker(state_checker)  # motions: OMPL's DiscreteMotionValidator

        def counters():
            return state_checker.checked, si.getMotionValidator().getCheckedMotionCount(), None
    else:
        raise ValueError(f"unknown checker {checker!r} (dymsum or fcl)")
    # Start and goal as OMPL.app sets them: a position and an axis and angle.
    cfg = read_cfg(problem.cfg_file)
    start, goal = space.allocState(), space.allocState()
    for state, which in ((start, "start"), (goal, "goal")):
        v = {key: float(cfg[f"problem.{which}.{key}"]) for key in ("x", "y", "z", "axis.x", "axis.y", "axis.z", "theta")}
        state.setXYZ(v["x"], v["y"], v["z"])
        state.rotation().setAxisAngle(v["axis.x"], v["axis.y"], v["axis.z"], v["theta"])
    ss.setStartAndGoalStates(start, goal)
    ss.setPlanner(getattr(og, planner)(si))
    ss.setup()
    return ss, counters


def plan(problem, checker="dymsum", planner="RRTConnect", seconds=10.0, motion_checker=None):
    """Plans once. Returns a dict: ``solved`` (an exact solution), ``time``
    (OMPL's planning time, s), ``state_checks``, ``motion_checks``,
    ``certified`` (motions certified free; ``None`` with fcl) and, when
    solved, ``length`` and ``path`` (the path's states as (K, 4, 4) poses)."""
    ss, counters = simple_setup(problem, checker, planner, motion_checker)
    solved = bool(ss.solve(seconds)) and ss.haveExactSolutionPath()
    states, motions, certified = counters()
    out = dict(solved=solved, time=ss.getLastPlanComputationTime(), state_checks=states, motion_checks=motions, certified=certified)
    if solved:
        path = ss.getSolutionPath()
        out.update(length=path.length(), path=np.array([state_pose(s) for s in path.getStates()]))
    return out


def main(argv=None):
    """Runs the command line; returns the list of ``plan`` results."""
    from ompl import util as ou

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cfg", help="an OMPL.app problem (.cfg) with its meshes beside it")
    parser.add_argument("--planner", default="RRTConnect", help="an OMPL geometric planner (default RRTConnect)")
    parser.add_argument("--time", type=float, help="time limit per run, s (default: the .cfg's, at most 60)")
    parser.add_argument("--checker", choices=("dymsum", "fcl"), default="dymsum")
    parser.add_argument("--runs", type=int, default=1, help="planning runs (default 1)")
    parser.add_argument("--seed", type=int, help="OMPL's random seed")
    args = parser.parse_args(argv)
    ou.setLogLevel(ou.LOG_WARN)
    if args.seed is not None:
        ou.RNG.setSeed(args.seed)
    problem = load_problem(args.cfg)
    seconds = args.time if args.time is not None else min(problem.time_limit or 60.0, 60.0)
    motion_checker = None
    if args.checker == "dymsum":
        motion_checker = dymsum.MotionChecker((problem.robot_vertices, problem.robot_faces), [(problem.env_vertices, problem.env_faces)])
    print(
        f"{problem.name}: robot {len(problem.robot_faces)} triangles, environment {len(problem.env_faces)};"
        f" {args.planner}, {args.checker}, up to {seconds:g} s per run"
    )
    results = []
    for run in range(args.runs):
        r = plan(problem, args.checker, args.planner, seconds, motion_checker)
        results.append(r)
        found = f"solved, path length {r['length']:.2f}" if r["solved"] else "NOT solved"
        certified = "" if r["certified"] is None else f", {r['certified']} motions certified free"
        print(f"run {run + 1}: {found} in {r['time']:.3f} s; {r['state_checks']} state checks, {r['motion_checks']} motion checks{certified}")
    if args.runs > 1:
        solved = [r["time"] for r in results if r["solved"]]
        median = f", median time of those {statistics.median(solved):.3f} s" if solved else ""
        print(f"solved {len(solved)} of {args.runs}{median}")
    return results


if __name__ == "__main__":
    raise SystemExit(0 if all(r["solved"] for r in main()) else 1)
