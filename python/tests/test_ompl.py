"""dymsum's OMPL validators against OMPL's own DiscreteMotionValidator and
a dense oracle of OMPL's interpolation.

OMPL (``pip install ompl``) is installed by ``scripts/test.sh``, which sets
``DYMSUM_REQUIRE_OMPL=1``: there a missing OMPL fails these tests;
elsewhere they are skipped.

The oracle: OMPL's ``SE2StateSpace`` / ``SE3StateSpace`` interpolation
written in NumPy (``ompl_poses``, checked against OMPL's ``interpolate``
below), evaluated at 10⁵ instants of a motion; each pose is asked the exact
static query (``dymsum.collides_many``) unless a conservative box test
proves it free, and runs of instants are skipped at once where a box grown
by the farthest the body moves over the run proves them all free (checked
against asking every pose, below). The random-motion test keeps the whole
file to about half a minute on two cores.
"""

import importlib.util
import math
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import dymsum

if os.environ.get("DYMSUM_REQUIRE_OMPL") == "1":
    from ompl import base as ob  # noqa: E402  (fail, not skip, where OMPL is required)
else:
    ob = pytest.importorskip("ompl.base", reason="OMPL is not installed (pip install ompl); scripts/test.sh installs it")

import dymsum.ompl as dom  # noqa: E402

EXAMPLES = pathlib.Path(__file__).resolve().parent.parent / "examples"


def box(lo, hi):
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])], float)


def example(name):
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def se2_space(lo=-5.0, hi=5.0):
    space = ob.SE2StateSpace()
    bounds = ob.RealVectorBounds(2)
    bounds.setLow(lo)
    bounds.setHigh(hi)
    space.setBounds(bounds)
    return space


def se3_space(lo=-3.0, hi=3.0):
    space = ob.SE3StateSpace()
    bounds = ob.RealVectorBounds(3)
    bounds.setLow(lo)
    bounds.setHigh(hi)
    space.setBounds(bounds)
    return space


def set_state(state, values):
    """SE(2): (x, y, yaw); SE(3): (x, y, z, qx, qy, qz, qw)."""
    if len(values) == 3:
        state.setXY(values[0], values[1])
        state.setYaw(values[2])
    else:
        state.setXYZ(*values[:3])
        r = state.rotation()
        r.x, r.y, r.z, r.w = values[3:]
    return state


def values_of(state):
    if hasattr(state, "getYaw"):
        return (state.getX(), state.getY(), state.getYaw())
    r = state.rotation()
    return (state.getX(), state.getY(), state.getZ(), r.x, r.y, r.z, r.w)


def state(space, *values):
    return set_state(space.allocState(), values)


def discrete_si(space, robot, obstacles):
    """A SpaceInformation with dymsum's exact state check and OMPL's own
    DiscreteMotionValidator at its default resolution."""
    si = ob.SpaceInformation(space)
    dom.setup_state_checker(si, robot, obstacles)
    si.setup()
    assert si.getStateValidityCheckingResolution() == 0.01
    return si


def certified_si(space, robot, obstacles, tolerance=1e-6):
    si = ob.SpaceInformation(space)
    v = dom.setup_validators(si, robot, obstacles, tolerance)
    si.setup()
    return si, v


# --- the oracle: OMPL's interpolation in NumPy -------------------------------


def quat_matrices(q):
    """(K, 3, 3) rotation matrices of (K, 4) quaternions (x, y, z, w), normalised."""
    q = q / np.linalg.norm(q, axis=1)[:, None]
    x, y, z, w = q.T
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], 1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], 1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], 1),
        ],
        1,
    )


def ompl_poses(v1, v2, ts):
    """(K, 4, 4): OMPL's interpolate(s1, s2, t) at each t, as poses
    (SO2StateSpace::interpolate, SO3StateSpace::interpolate with its arc
    length, and RealVectorStateSpace::interpolate, as in OMPL 2.0.1)."""
    ts = np.asarray(ts, float)
    out = np.tile(np.eye(4), (len(ts), 1, 1))
    if len(v1) == 3:
        diff = v2[2] - v1[2]
        if abs(diff) <= math.pi:
            yaw = v1[2] + diff * ts
        else:
            d = 2.0 * math.pi - diff if diff > 0 else -2.0 * math.pi - diff
            yaw = v1[2] - d * ts
        c, s = np.cos(yaw), np.sin(yaw)
        out[:, 0, 0], out[:, 0, 1], out[:, 1, 0], out[:, 1, 1] = c, -s, s, c
        out[:, 0, 3] = v1[0] + (v2[0] - v1[0]) * ts
        out[:, 1, 3] = v1[1] + (v2[1] - v1[1]) * ts
        return out
    q1, q2 = np.array(v1[3:]), np.array(v2[3:])
    dot = float(q1 @ q2)
    dq = abs(dot)
    theta = 0.0 if dq > 1.0 - 1e-9 else math.acos(dq)
    if theta > np.finfo(float).eps:
        s0 = np.sin((1.0 - ts) * theta)
        s1 = np.sin(ts * theta)
        if dot < 0:
            s1 = -s1
        q = (np.outer(s0, q1) + np.outer(s1, q2)) / math.sin(theta)
    else:
        q = np.tile(q1, (len(ts), 1))
    out[:, :3, :3] = quat_matrices(q)
    for k in range(3):
        out[:, k, 3] = v1[k] + (v2[k] - v1[k]) * ts
    return out


class Oracle:
    """Exact static queries (``dymsum.collides_many``) at many poses.

    Both methods ask the exact query only where a box test cannot rule a
    contact out: each robot piece lies in its bounding box (centre ``c``,
    half extents ``e``), whose copy at pose ``(R, x)`` lies in the world box
    ``R·c + x ± |R|·e``; that box must meet the obstacle's bounding box,
    and the piece's box, in the piece's frame, the obstacle box's there
    (no separating axis among the six; with a margin far above rounding),
    for a contact to be possible.

    ``motion_hits(v1, v2)`` evaluates OMPL's interpolation at 10⁵ instants
    without computing 10⁵ poses for the instants far from every obstacle
    (the prefilter): a run of consecutive instants ``[t_a, t_b]`` is
    skipped when the world box of each piece at the run's middle, grown by
    the farthest any point of the piece moves over half the run, meets no
    obstacle box. That distance is at most ``(|c| + |e|)·Θ·h + |Δx|·h``:
    OMPL turns at a constant rate ``Θ`` about a fixed axis through the
    body's origin and translates at the constant velocity ``Δx``; ``h`` is
    half the run's length in t. Runs that are not skipped are split 32
    ways, down to single instants, which get the exact query for each
    (piece, obstacle) pair whose boxes meet."""

    MARGIN = 1e-7

    def __init__(self, robot, obstacles):
        self.pieces = list(robot.pieces) if isinstance(robot, dymsum.ConvexUnion) else [dymsum.Polytope(robot)]
        self.obstacles = [dymsum.Polytope(o) for o in obstacles]
        lo = np.array([p.vertices.min(0) for p in self.pieces])
        hi = np.array([p.vertices.max(0) for p in self.pieces])
        self.centres, self.halves = (hi + lo) / 2, (hi - lo) / 2  # (P, 3)
        self.reach = np.linalg.norm(self.centres, axis=1) + np.linalg.norm(self.halves, axis=1)  # (P,)
        lo = np.array([o.vertices.min(0) for o in self.obstacles])
        hi = np.array([o.vertices.max(0) for o in self.obstacles])
        self.obstacle_centres, self.obstacle_halves = (hi + lo) / 2, (hi - lo) / 2  # (O, 3)
        self.exact_queries = 0

    def near(self, poses, grow):
        """(K, P, O) bool: piece p's box at poses[k], grown by ``grow[k, p]``
        on every side, meets obstacle o's box: no separating axis among the
        world's three and the piece's three."""
        rot, trans = poses[:, :3, :3], poses[:, :3, 3]
        grow = np.asarray(grow)[..., None]  # (K, P, 1)
        centre = np.matmul(self.centres[None], rot.transpose(0, 2, 1)) + trans[:, None]  # (K, P, 3)
        oc, oh = self.obstacle_centres, self.obstacle_halves
        slack = self.MARGIN * (1 + np.abs(oc).max())
        gap = oc[None, None] - centre[:, :, None]  # (K, P, O, 3)
        abs_rot = np.abs(rot)
        half = np.matmul(self.halves[None], abs_rot.transpose(0, 2, 1)) + grow  # (K, P, 3)
        near = np.all(np.abs(gap) <= (half[:, :, None] + oh[None, None] + slack), axis=3)
        # In the piece's frame (only where the world's axes do not separate):
        # the obstacle's centre, and its half extents.
        k, p, o = np.nonzero(near)
        local = np.abs(np.einsum("nji,nj->ni", rot[k], gap[k, p, o]))
        ohl = np.einsum("nji,nj->ni", abs_rot[k], oh[o])
        near[k, p, o] = np.all(local <= self.halves[p] + grow[k, p] + ohl + slack, axis=1)
        return near

    def collisions(self, poses, near=None):
        """(K,) bool: the robot at each pose touches or overlaps an obstacle."""
        poses = np.ascontiguousarray(poses, float)
        if near is None:
            near = self.near(poses, np.zeros((len(poses), len(self.pieces))))
        hit = np.zeros(len(poses), bool)
        for p, o in zip(*np.nonzero(near.any(axis=0))):
            idx = np.flatnonzero(near[:, p, o] & ~hit)
            if len(idx):
                self.exact_queries += len(idx)
                hit[idx] |= dymsum.collides_many(self.pieces[p], self.obstacles[o], np.ascontiguousarray(poses[idx]), None)
        return hit

    def motion_hits(self, v1, v2, samples=100_000, t_max=1.0):
        """``(ts, hit)``: ``ts`` the ``samples`` instants ``linspace(0, 1)``
        and ``hit[i]`` whether the body at OMPL's interpolated state at
        ``ts[i]`` touches or overlaps an obstacle (exact queries; instants
        the prefilter proves free are free), for the instants up to
        ``t_max`` (``hit`` is False after it)."""
        ts = np.linspace(0.0, 1.0, samples)
        hit = np.zeros(samples, bool)
        rate = turn_rate(v1, v2)
        n = 2 if len(v1) == 3 else 3
        speed = math.dist(v1[:n], v2[:n]) * (1 + 1e-9)
        lo, hi = np.array([0]), np.array([np.searchsorted(ts, t_max, side="right") - 1])
        while len(lo):
            ta, tb = ts[lo], ts[hi]
            h = (tb - ta) / 2
            poses = ompl_poses(v1, v2, (ta + tb) / 2)
            near = self.near(poses, np.outer(h, speed + rate * self.reach))
            keep = near.any(axis=(1, 2))
            if (hi == lo).all():
                hit[lo[keep]] = self.collisions(poses[keep], near[keep])
                break
            lo, hi = lo[keep], hi[keep]
            size = hi - lo + 1
            cuts = lo[:, None] + (size[:, None] * np.arange(33)[None]) // 32
            lo, hi = cuts[:, :-1].ravel(), cuts[:, 1:].ravel() - 1
            keep = hi >= lo
            lo, hi = lo[keep], hi[keep]
        return ts, hit


def turn_rate(v1, v2):
    """The angle OMPL's interpolation turns through from v1 to v2 (the rate
    in rad per unit t), with a relative margin for rounding."""
    if len(v1) == 3:
        diff = abs(v2[2] - v1[2])
        angle = diff if diff <= math.pi else 2.0 * math.pi - diff
    else:
        dq = abs(float(np.dot(v1[3:], v2[3:])))
        angle = 0.0 if dq > 1.0 - 1e-9 else 2.0 * math.acos(min(dq, 1.0))
    return angle * (1 + 1e-9) + 1e-12


def sampled_hits(oracle, v1, v2, samples=100_000):
    """``(ts, hit)`` at ``samples`` instants, every pose asked (no
    prefilter but the box test)."""
    ts = np.linspace(0.0, 1.0, samples)
    return ts, oracle.collisions(ompl_poses(v1, v2, ts))


# --- the interpolation dymsum certifies is OMPL's -----------------------------


def test_the_oracle_is_ompl_interpolation():
    rng = np.random.default_rng(3)
    for space in (se2_space(), se3_space()):
        a, b, out = space.allocState(), space.allocState(), space.allocState()
        sampler = space.allocDefaultStateSampler()
        cases = []
        for _ in range(200):
            sampler.sampleUniform(a)
            sampler.sampleUniform(b)
            cases.append((values_of(a), values_of(b)))
        if isinstance(space, ob.SE3StateSpace):
            h = math.sqrt(0.5)
            cases += [
                ((0, 0, 0, 0, 0, 0, 1), (1, 0, 0, 0, 0, 1, 0)),  # half a turn, dot 0
                ((0, 0, 0, 0, 0, 0, 1), (1, 0, 0, 0, 0, -1, 0)),  # the same rotation, the other sign
                ((0, 0, 0, 0, 0, 0, 1), (1, 0, 0, 0, 0, math.sin(2e-5), math.cos(2e-5))),  # tiny: held
                ((0, 0, 0, 0, h, 0, h), (1, 2, 0, 0, 0, -h, -h)),
            ]
        else:
            cases += [((0, 0, -math.pi / 2), (1, 0, math.pi / 2)), ((0, 0, math.pi / 2), (1, 0, -math.pi / 2)), ((0, 0, 3.0), (0, 1, -3.0))]
        for v1, v2 in cases:
            set_state(a, v1)
            set_state(b, v2)
            ts = rng.uniform(0, 1, 5)
            ours = ompl_poses(v1, v2, ts)
            for t, p in zip(ts, ours):
                space.interpolate(a, b, t, out)
                np.testing.assert_allclose(p, pose_of(out), atol=1e-12)


def pose_of(s):
    v = values_of(s)
    return dom.se2_pose(*v) if len(v) == 3 else dom.se3_pose(*v)


def test_ompl_so3_interpolation_holds_the_first_rotation_for_tiny_turns():
    # What dymsum.ompl handles: below OMPL's arc-length threshold (|q1·q2| >
    # 1 - 1e-9, turns under about 9e-5 rad) OMPL's SO3StateSpace.interpolate
    # returns the first rotation for every t, even t = 1.
    space = se3_space()
    a = state(space, 0, 0, 0, 0, 0, 0, 1)
    b = state(space, 1, 0, 0, 0, 0, math.sin(2e-5), math.cos(2e-5))
    out = space.allocState()
    space.interpolate(a, b, 1.0, out)
    assert values_of(out)[3:] == (0.0, 0.0, 0.0, 1.0) and values_of(out)[0] == 1.0


# --- (a) a wall thinner than OMPL's step ----------------------------------------


def test_thin_wall_discrete_validator_accepts_dymsum_rejects():
    space = se2_space()
    robot = box([-0.025, -0.025, -0.1], [0.025, 0.025, 0.1])
    wall = box([-0.01, -5, -1], [0.01, 5, 1])
    s1, s2 = state(space, -1.0, 0.3, 0.0), state(space, 1.0, 0.3, 0.0)
    discrete = discrete_si(space, robot, [wall])
    # OMPL's step: 1% of the extent (14.14 + 0.5·π); the robot and the wall
    # together are 0.07 wide along the motion.
    assert space.getLongestValidSegmentLength() > 0.15
    assert discrete.isValid(s1) and discrete.isValid(s2)
    assert discrete.checkMotion(s1, s2), "OMPL's DiscreteMotionValidator steps over the wall"
    ts, hit = sampled_hits(Oracle(robot, [wall]), values_of(s1), values_of(s2))
    assert hit.any(), "the motion crosses the wall"
    si, v = certified_si(space, robot, [wall])
    assert not si.checkMotion(s1, s2) and not v.motion_validator.checkMotion(s1, s2)
    assert v.motion_validator.checked == 2 and v.motion_validator.rejected == 2
    # The bracket: the robot's face x = 0.025 meets the wall at x = -0.01.
    r = v.motion_validator.check(s1, s2)
    assert not r.free and not r.undecided
    t_first = ((-0.01 - 0.025) - (-1.0)) / 2.0
    assert r.t_safe < r.t_contact <= r.t_safe + 1e-6 and abs(r.t_contact - t_first) <= 1e-6
    assert not hit[ts <= r.t_safe].any() and hit[ts >= r.t_contact + 1e-5][0]
    # OMPL's lastValid: the state at t_safe, valid.
    last = [space.allocState(), 0.0]
    assert not v.motion_validator.checkMotion(s1, s2, last)
    assert last[1] == r.t_safe and si.isValid(last[0])
    assert abs(last[0].getX() - (-1.0 + 2.0 * r.t_safe)) <= 1e-12
    end = space.allocState()
    space.interpolate(s1, s2, r.t_contact, end)
    assert not si.isValid(end)


# --- (b) a long bar turning about its centre past a box corner -----------------


# A long thin bar (4 by 0.02), and a box whose corner pokes 0.01 into the
# disc the bar's ends sweep, at 27.9° from the x axis: between two of the
# states OMPL checks on a quarter turn (1% of SO(2)'s extent π apart: 1.8°).
THIN_BAR = box([-2, -0.01, -0.01], [2, 0.01, 0.01])
_CORNER = 1.99 * np.array([math.cos(math.radians(27.9)), math.sin(math.radians(27.9))])
CORNER_BOX = box([_CORNER[0], _CORNER[1], -1], [_CORNER[0] + 1, _CORNER[1] + 1, 1])


def test_bar_turning_past_a_corner_discrete_accepts_dymsum_rejects():
    space = se2_space()
    s1, s2 = state(space, 0, 0, 0.0), state(space, 0, 0, math.pi / 2)
    discrete = discrete_si(space, THIN_BAR, [CORNER_BOX])
    mid = state(space, 0, 0, math.pi / 4)
    assert discrete.isValid(s1) and discrete.isValid(mid) and discrete.isValid(s2)
    # OMPL checks the quarter turn at 50 states, 1.8° apart: all free.
    assert space.validSegmentCount(s1, s2) == 50
    assert discrete.checkMotion(s1, s2), "OMPL's DiscreteMotionValidator misses the corner"
    oracle = Oracle(THIN_BAR, [CORNER_BOX])
    ts, hit = sampled_hits(oracle, values_of(s1), values_of(s2))
    assert hit.any() and not hit[::2000].any() and not hit[-1]
    si, v = certified_si(space, THIN_BAR, [CORNER_BOX])
    assert not si.checkMotion(s1, s2)
    r = v.motion_validator.check(s1, s2)
    assert not r.free and r.t_safe < r.t_contact <= r.t_safe + 1e-6
    assert not hit[ts <= r.t_safe].any()
    assert oracle.collisions(ompl_poses(values_of(s1), values_of(s2), [r.t_contact]))[0]
    # Turning the other way round misses the box.
    assert si.checkMotion(s1, state(space, 0, 0, -math.pi / 2))


# --- half turns: the way OMPL turns --------------------------------------------

ARM = box([0, -0.05, -0.05], [2, 0.05, 0.05])


def test_half_turn_follows_ompl_direction_se2():
    # From -90° to +90° OMPL turns through 0 (the difference is exactly π and
    # |π| ≤ π); from +90° to -90° also through 0. An arm (a bar from the
    # origin out to x = 2) and a block in its path through 0, or through 180°.
    space = se2_space()
    block_at_0 = box([1.6, -0.5, -1], [1.7, -0.4, 1])  # -16°: passed through 0, not through 180°
    block_at_180 = box([-1.7, -0.5, -1], [-1.6, -0.4, 1])
    for v1, v2 in (((0, 0, -math.pi / 2), (0, 0, math.pi / 2)), ((0, 0, math.pi / 2), (0, 0, -math.pi / 2))):
        for block, free in ((block_at_0, False), (block_at_180, True)):
            si, v = certified_si(space, ARM, [block])
            s1, s2 = state(space, *v1), state(space, *v2)
            assert si.isValid(s1) and si.isValid(s2)
            ts, hit = sampled_hits(Oracle(ARM, [block]), v1, v2, 20_000)
            assert hit.any() != free
            assert si.checkMotion(s1, s2) == free and v.motion_validator.check(s1, s2).free == free


def test_half_turn_follows_ompl_direction_se3():
    # The same end rotation, half a turn about z, as two quaternions of
    # opposite signs: OMPL turns one way for each (their dot with the start
    # is ±0, never negative), and so must the validator.
    space = se3_space()
    block = box([1.6, 0.4, -1], [1.7, 0.5, 1])  # at about +15°
    start = (0, 0, 0, 0, 0, 0, 1)
    oracle = Oracle(ARM, [block])
    verdicts = []
    for qz in (1.0, -1.0):
        end = (0, 0, 0, 0, 0, qz, 0.0)
        ts, hit = sampled_hits(oracle, start, end, 20_000)
        si, v = certified_si(space, ARM, [block])
        ok = si.checkMotion(state(space, *start), state(space, *end))
        assert ok == (not hit.any())
        verdicts.append(ok)
    assert verdicts == [False, True]


@pytest.mark.parametrize("qw", [-8.598507252118853e-15, 8.598507252118853e-15, -5e-301, 5e-301])
def test_regression_half_turn_plus_epsilon_follows_ompl_se3(qw):
    # Issue 26 §1: 180° ± 1e-12° (or ± 1e-300) about z. OMPL's float dot
    # product with the identity is qw: negative → the second quaternion is
    # negated and the arm turns clockwise through a block at y ≈ −1.5.
    space = se3_space()
    block = box([-0.1, -1.6, -1], [0.1, -1.4, 1])
    start, end = (0, 0, 0, 0, 0, 0, 1), (0, 0, 0, 0, 0, 1.0, qw)
    ts, hit = sampled_hits(Oracle(ARM, [block]), start, end, 20_000)
    assert hit.any() == (qw < 0)
    si, v = certified_si(space, ARM, [block])
    assert si.checkMotion(state(space, *start), state(space, *end)) == (qw > 0)
    # And dymsum's own check of the same quaternions, outside OMPL.
    c = dymsum.check_motion(ARM, [block], None, np.array([0.0, 0.0, 1.0, qw]))
    assert c.free == (qw > 0)


def test_tiny_se3_turn_checks_ompl_held_rotation_too():
    # A bar 10 long turning by 8e-5 rad about z while moving down 5e-4: the
    # real motion lifts the tip, but OMPL's interpolation keeps the first
    # rotation (the turn is below its arc-length threshold) and lowers the
    # tip into a block 3e-4 below it. OMPL's own interpolated states collide,
    # so the motion is rejected; without the turn it is the same as OMPL's.
    space = se3_space(-20, 20)
    bar = box([0, -0.01, -0.01], [10, 0.01, 0.01])
    block = box([9.5, -1, -1], [10.5, -0.0103, 1])
    a = (0, 0, 0, 0, 0, 0, 1)
    b = (0, -5e-4, 0, 0, 0, math.sin(4e-5), math.cos(4e-5))
    oracle = Oracle(bar, [block])
    ts, hit = sampled_hits(oracle, a, b, 20_000)
    assert hit.any(), "OMPL's interpolated states touch the block"
    checker = dymsum.MotionChecker(bar, [block])
    assert checker.check(dom.se3_pose(*a), dom.se3_pose(*b)).free, "the slerp motion is free"
    si, v = certified_si(space, bar, [block])
    s1, s2 = state(space, *a), state(space, *b)
    assert si.isValid(s1) and si.isValid(s2)
    assert not si.checkMotion(s1, s2)
    r = v.motion_validator.check(s1, s2)
    assert not r.free and not hit[ts <= r.t_safe].any() and r.t_contact - r.t_safe <= 1e-6
    discrete = discrete_si(space, bar, [block])
    assert discrete.checkMotion(s1, s2), "OMPL's validator checks only the end state here"


# --- (c) never accepts what the dense oracle finds colliding --------------------


def random_motions(kind, rng, n, bounds, obstacles=()):
    """``n`` random motions ``(v1, v2)`` within ``bounds``: long ones (steps
    up to 3 in SE(2), 2 in SE(3), any turn), every 50th a half turn and, in
    SE(3), every 50th (offset 25) a turn below OMPL's arc-length threshold;
    with ``obstacles``, every third motion crosses one of them along its
    thinnest axis (steps up to 0.6 and small turns: the motions that graze
    walls and slip past OMPL's sampling)."""
    lo, hi = bounds
    dims = 2 if kind == "SE2" else 3
    out = []
    for k in range(n):
        if obstacles and k % 3 == 1:
            o = np.asarray(obstacles[rng.integers(len(obstacles))])[:, :dims]
            olo, ohi = o.min(0), o.max(0)
            axis = int(np.argmin(ohi - olo))
            p = rng.uniform(np.maximum(olo - 0.6, lo), np.minimum(ohi + 0.6, hi))
            p[axis] = (olo[axis] + ohi[axis]) / 2
            step = rng.normal(size=dims) * 0.05
            step[axis] = rng.uniform(0.05, 0.6) * rng.choice([-1.0, 1.0])
            u = rng.uniform()
            p1, p2 = p - u * step, p + (1 - u) * step
            angle = abs(rng.normal()) * 0.3
        else:
            p1 = rng.uniform(lo, hi, dims)
            reach = 3.0 if dims == 2 else 2.0
            p2 = p1 + rng.uniform(0.05, reach) * rng.normal(size=dims) / math.sqrt(dims)
            angle = rng.uniform(0, math.pi) * rng.uniform(0, 1) ** (2 if dims == 2 else 1)
        if k % 50 == 0:
            angle = math.pi  # half turns
        elif k % 50 == 25 and dims == 3:
            angle = 1e-5  # below OMPL's arc-length threshold
        p1, p2 = np.clip(p1, lo, hi), np.clip(p2, lo, hi)
        if dims == 2:
            yaw1 = rng.uniform(-math.pi, math.pi)
            yaw2 = yaw1 + angle * (1 if k % 100 else -1) * (1 if angle == math.pi else rng.choice([-1, 1]))
            yaw2 = (yaw2 + math.pi) % (2 * math.pi) - math.pi
            v1, v2 = (*p1, yaw1), (*p2, yaw2)
        else:
            q1 = rng.normal(size=4)
            q1 /= np.linalg.norm(q1)
            axis = rng.normal(size=3)
            axis /= np.linalg.norm(axis)
            x, y, z, w = (*axis * math.sin(angle / 2), math.cos(angle / 2))
            a, b, c, d = q1
            # The turn, then q1 (Hamilton product, scalar last).
            q2 = np.array([w * a + x * d + y * c - z * b, w * b - x * c + y * d + z * a, w * c + x * b - y * a + z * d, w * d - x * a - y * b - z * c])
            q2 /= np.linalg.norm(q2)
            if rng.uniform() < 0.5:
                q2 = -q2
            v1, v2 = (*p1, *q1), (*p2, *q2)
        out.append((tuple(map(float, v1)), tuple(map(float, v2))))
    return out


def slerp_pose(v1, v2, t):
    """The pose at ``t`` of the true SE(3) motion (slerp on the shorter arc,
    the translation linear), which OMPL's interpolation replaces by the
    first rotation for turns below its threshold."""
    from scipy.spatial.transform import Rotation

    r1, r2 = Rotation.from_quat(v1[3:]), Rotation.from_quat(v2[3:])
    pose = np.eye(4)
    pose[:3, :3] = (r1 * Rotation.from_rotvec(t * (r1.inv() * r2).as_rotvec())).as_matrix()
    pose[:3, 3] = np.array(v1[:3]) + (np.array(v2[:3]) - np.array(v1[:3])) * t
    return pose


def test_prefiltered_oracle_equals_every_pose_asked():
    # The prefiltered oracle against the same poses all asked, on the
    # SE(2) example's scene: motions that cross a wall, graze it, miss it.
    mod = example("ompl_se2")
    robot, obstacles = mod.scene()
    oracle = Oracle(robot, obstacles)
    rng = np.random.default_rng(5)
    motions = [((-2.0, 0.0, 0.3), (-1.0, 0.2, 2.0)), ((-1.2, 2.0, 0.0), (-1.2, 2.0, math.pi / 2)), ((-3, -3, 0), (3, 3, 1.0))]
    motions += random_motions("SE2", rng, 9, mod.BOUNDS)
    some_hit = some_free = 0
    for v1, v2 in motions:
        ts, fast = oracle.motion_hits(v1, v2, 20_000)
        before = oracle.exact_queries
        _, every = sampled_hits(oracle, v1, v2, 20_000)
        np.testing.assert_array_equal(fast, every)
        assert oracle.exact_queries - before > 0 or not every.any()
        some_hit += every.any()
        some_free += not every.any()
    assert some_hit >= 3 and some_free >= 3, (some_hit, some_free)


MOTIONS_PER_SPACE = 1500


@pytest.mark.parametrize("name", ["ompl_se2", "ompl_se3"])
def test_never_accepts_what_dense_sampling_finds_colliding(name):
    # Random motions in the examples' scenes (half turns and, in SE(3),
    # turns below OMPL's arc-length threshold among them). Each accepted
    # motion is free at all 10⁵ instants of OMPL's interpolation; each
    # rejected one is free at every one of those instants up to t_safe,
    # touches an obstacle at t_contact (exact query), and last_valid is the
    # state at t_safe. OMPL's DiscreteMotionValidator accepts some of the
    # motions that touch.
    mod = example(name)
    robot, obstacles = mod.scene()
    se2 = name == "ompl_se2"
    space = se2_space(*mod.BOUNDS) if se2 else se3_space(*mod.BOUNDS)
    si, v = certified_si(space, robot, obstacles)
    discrete = discrete_si(space, robot, obstacles)
    mv = v.motion_validator
    oracle = Oracle(robot, obstacles)
    rng = np.random.default_rng(20 if se2 else 21)
    a, b, last, at = space.allocState(), space.allocState(), space.allocState(), space.allocState()
    motions = [(v1, v2) for v1, v2 in random_motions(v.state_checker.kind, rng, 2 * MOTIONS_PER_SPACE, mod.BOUNDS, obstacles) if si.isValid(set_state(a, v1))]
    motions = motions[:MOTIONS_PER_SPACE]
    assert len(motions) == MOTIONS_PER_SPACE
    accepted = touching = missed_by_discrete = 0
    for v1, v2 in motions:
        set_state(a, v1)
        set_state(b, v2)
        ok = si.checkMotion(a, b)
        r = mv.check(a, b)
        assert ok == r.free, (v1, v2)
        assert not r.undecided, (v1, v2)
        # Certified free up to t_safe (1 when free): the oracle agrees.
        ts, hit = oracle.motion_hits(v1, v2, t_max=r.t_safe)
        assert not hit.any(), f"certified free, but OMPL's state at t = {ts[hit][0]} collides: {v1} -> {v2}, {r}"
        if ok:
            accepted += 1
            assert r.t_safe == 1.0 and r.t_contact is None
            continue
        last_valid = [last, -1.0]
        assert not mv.checkMotion(a, b, last_valid)
        if r.t_contact is None:  # free, but the end state is out of bounds
            assert r.t_safe == 1.0 and not si.satisfiesBounds(b)
            continue
        touching += 1
        assert 0.0 <= r.t_safe < r.t_contact <= r.t_safe + 1e-6, (v1, v2, r)
        touches = oracle.collisions(ompl_poses(v1, v2, [r.t_contact]))[0]
        if not touches and not se2 and abs(np.dot(v1[3:], v2[3:])) > 1 - 1e-9:
            # A turn below OMPL's threshold: t_contact may be on the true
            # (slerp) motion, which dymsum.ompl certifies too.
            touches = oracle.collisions(slerp_pose(v1, v2, r.t_contact)[None])[0]
        assert touches, (v1, v2, r)
        missed_by_discrete += discrete.checkMotion(a, b)
        # last_valid: the state at t_safe, valid (or the start, where OMPL's
        # rounding of that state touches).
        assert last_valid[1] in (r.t_safe, 0.0) and si.isValid(last), (v1, v2, r, last_valid[1])
        space.interpolate(a, b, last_valid[1], at)
        assert space.distance(at, last) == 0.0
    rejected = MOTIONS_PER_SPACE - accepted
    assert accepted >= 300 and touching >= 300, (accepted, rejected, touching)
    assert mv.checked == 2 * MOTIONS_PER_SPACE + rejected and mv.undecided == 0
    print(f"{name}: {accepted} accepted, {touching} touching ({missed_by_discrete} accepted by OMPL's DiscreteMotionValidator), {rejected - touching} ending out of bounds; {oracle.exact_queries} exact oracle queries")


# --- (d) planning ----------------------------------------------------------------


@pytest.mark.parametrize("name", ["ompl_se2", "ompl_se3"])
def test_examples_plan_certified_paths(name):
    done = subprocess.run([sys.executable, str(EXAMPLES / f"{name}.py"), "--seed", "3"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "path found: length" in done.stdout and "certified free by dymsum: yes" in done.stdout, done.stdout
    assert "leaked" not in done.stderr, done.stderr  # no reference cycle through OMPL


@pytest.mark.parametrize("name", ["ompl_se2", "ompl_se3"])
def test_plan_with_the_scene_builders(name):
    mod = example(name)
    r = mod.plan(discrete=False, seconds=30.0)
    assert r["found"] and r["certified"] and r["uncertified_motions"] == 0
    v = r["validators"]
    assert v.motion_validator.checked > 0 and v.state_checker.checked > 0
    assert r["length"] > 0


@pytest.mark.parametrize("name", ["ompl_se2", "ompl_se3"])
def test_planned_paths_are_free_by_the_dense_oracle(name):
    # The simplified path (long shortcuts past the walls' openings), every
    # motion asked at 10⁵ instants, independently of dymsum's motion check.
    mod = example(name)
    ss, v = mod.simple_setup(discrete=False)
    assert ss.solve(30.0) and ss.haveExactSolutionPath()
    ss.simplifySolution()
    values = [values_of(s) for s in ss.getSolutionPath().getStates()]
    assert values[0][0] < -2 and values[-1][0] > 2  # from one side of the walls to the other
    oracle = Oracle(*mod.scene())
    for v1, v2 in zip(values, values[1:]):
        ts, hit = oracle.motion_hits(v1, v2)
        assert not hit.any(), (v1, v2, ts[hit][:3])


# --- the API ----------------------------------------------------------------------


def test_other_spaces_are_refused():
    robot, wall = box([0, 0, 0], [1, 1, 1]), box([3, 0, 0], [4, 1, 1])
    for space in (ob.RealVectorStateSpace(2), ob.SO3StateSpace(), ob.DubinsStateSpace(), ob.ReedsSheppStateSpace()):
        if isinstance(space, ob.RealVectorStateSpace):
            b = ob.RealVectorBounds(2)
            b.setLow(0)
            b.setHigh(1)
            space.setBounds(b)
        si = ob.SpaceInformation(space)
        with pytest.raises(TypeError, match="SE2StateSpace and SE3StateSpace"):
            dom.setup_validators(si, robot, [wall])
    with pytest.raises(TypeError, match="SpaceInformation"):
        dom.setup_validators(se2_space(), robot, [wall])


def test_bounds_and_arguments():
    space = se2_space()
    robot, wall = box([-0.1, -0.1, -0.1], [0.1, 0.1, 0.1]), box([3, 0, -1], [4, 1, 1])
    si, v = certified_si(space, robot, [wall])
    inside, outside = state(space, 4.5, -4, 0), state(space, 5.5, -4, 0)
    assert si.isValid(inside) and not si.isValid(outside)
    assert not si.checkMotion(inside, outside) and not si.checkMotion(outside, inside)
    r = v.motion_validator.check(inside, outside)
    assert not r.free and r.t_contact is None
    assert v.state_checker.checked == 2 and v.state_checker.invalid == 1
    assert "StateChecker(SE2, checked=2, invalid=1)" in repr(v.state_checker)
    with pytest.raises(ValueError, match="tolerance"):
        dom.setup_validators(ob.SpaceInformation(space), robot, [wall], tolerance=0.0)
    with pytest.raises(ValueError, match="obstacles"):
        dom.setup_validators(ob.SpaceInformation(space), robot)
    # A prepared MotionChecker, and a SimpleSetup.
    from ompl import geometric as og

    ss = og.SimpleSetup(space)
    checker = dymsum.MotionChecker(robot, [wall])
    got = dom.setup_validators(ss, checker)
    assert got.checker is checker
    with pytest.raises(ValueError, match="fresh"):
        dom.setup_state_checker(ss, checker)


def test_validators_outlive_their_python_references():
    import gc

    space = se2_space()
    robot, wall = box([-0.1, -0.1, -0.1], [0.1, 0.1, 0.1]), box([-0.01, -5, -1], [0.01, 5, 1])
    si = ob.SpaceInformation(space)
    dom.setup_validators(si, robot, [wall])
    gc.collect()
    s1, s2 = state(space, -1, 0, 0), state(space, 1, 0, 0)
    assert si.isValid(s1) and not si.checkMotion(s1, s2)
    mv = si.getMotionValidator()
    assert isinstance(mv, dom.CertifiedMotionValidator) and mv.checked == 1 and mv.rejected == 1


def test_importing_dymsum_does_not_import_ompl():
    code = "import sys, dymsum, dymsum.ompl; assert 'ompl' not in sys.modules; print(dymsum.ompl.se2_pose(0, 0, 0)[0, 0])"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and done.stdout.strip() == "1.0", done.stderr


def test_module_docstring_examples():
    import doctest

    r = doctest.testmod(dom, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert r.failed == 0 and r.attempted >= 3
