"""Exact state validity and certified motion validation for OMPL.

`OMPL <https://ompl.kavrakilab.org>`_ (2.x, ``pip install ompl``) plans
with two callbacks: a *state validity checker* (is the body free at this
state?) and a *motion validator* (is it free along the straight motion
between two states?). OMPL's default motion validator, the
``DiscreteMotionValidator``, checks interpolated states a fixed resolution
apart (1% of the space's extent), so it steps over walls thinner than a
step and corners that a turning body grazes between two samples. This
module installs validators built on dymsum instead:

* the state checker asks the exact query (``MotionChecker.collides_at``:
  touching counts) and the space's bounds;
* the motion validator asks the certified motion check
  (``MotionChecker.check``): a motion is accepted only when dymsum proves
  that no instant of it touches an obstacle, never by sampling. A motion
  that grazes an obstacle within rounding (``MotionUndecided``) is
  rejected.

Robots with joints plan in a ``RealVectorStateSpace`` of one dimension
per degree of freedom (``Robot.joint_names`` order; set the bounds to the
joint limits): ``setup_joint_validators`` installs the same two callbacks
on a ``dymsum.RobotChecker``, OMPL's linear interpolation being the
joint-space motion ``RobotChecker.check`` certifies.

For rigid bodies only ``SE2StateSpace`` and ``SE3StateSpace`` are accepted, because their
interpolation is the motion dymsum certifies: the translation linear, the
rotation at a constant rate about a fixed axis along the shorter arc
(SE(2): OMPL's ``SO2StateSpace.interpolate`` moves the yaw the shorter way;
SE(3): ``SO3StateSpace.interpolate`` is slerp, negating the second
quaternion when their dot product is negative). Two cases at the edges are
handled so that the certified set of states contains every state OMPL's
interpolation gives:

* a rotation of (nearly) half a turn, where "the shorter arc" is decided by
  rounding (SE(2): ``|Δyaw|`` within 1e-6 of π; SE(3): ``|q₁·q₂| < 1e-6``):
  the motion is checked as its two halves, split at OMPL's own interpolated
  state at ``t = 0.5``, so it turns the way OMPL turns;
* a tiny SE(3) rotation (``|q₁·q₂| > 1 − 1e-9``): OMPL's
  ``SO3StateSpace.interpolate`` then returns the *first* state's rotation
  for every ``t`` (it treats the arc as empty), while the body really turns
  by up to 9e-5 rad; both motions, the slerp and the translation at the
  first rotation, must be certified free.

In SE(2) the body turns about the z axis and moves in the plane ``z = 0``
of its own frame: give 3-D shapes (prisms for a planar problem).

Poses are built from the states with plain float arithmetic into reused
per-thread buffers (no scipy, no new arrays per call). OMPL's Python
bindings do not forward ``checkMotion(s1, s2, lastValid)`` to a Python
validator: OMPL's C++ planners always get the yes/no answer, and planners
that *rely* on ``lastValid`` being filled (``PDST``, and the
``ObstacleBasedValidStateSampler``) must not be used with any Python motion
validator (docs/PYTHON.md, "OMPL"). Python code can call
``validator.checkMotion(s1, s2, last_valid)`` with a ``[state, 0.0]`` list,
or ``validator.check(s1, s2)``.

Importing this module does not import OMPL; the functions and classes that
need it import it when first used. The pose helpers need only NumPy:

>>> import math
>>> from dymsum.ompl import se2_pose, se3_pose
>>> se2_pose(1.0, 2.0, math.pi / 2).round(12).tolist()[:2]
[[0.0, -1.0, 0.0, 1.0], [1.0, 0.0, 0.0, 2.0]]
>>> se3_pose(1.0, 2.0, 3.0, 0.0, 0.0, math.sin(math.pi / 4), math.cos(math.pi / 4)).round(12)[:3].tolist()
[[0.0, -1.0, 0.0, 1.0], [1.0, 0.0, 0.0, 2.0], [0.0, 0.0, 1.0, 3.0]]
"""

from __future__ import annotations

import math
import threading
from typing import Any, List, NamedTuple, Optional, Tuple

import numpy as np

from ._dymsum import MotionChecker, MotionUndecided, RobotChecker

__all__ = [
    "CertifiedMotionValidator",
    "JointStateChecker",
    "MotionResult",
    "StateChecker",
    "Validators",
    "certified_path",
    "se2_pose",
    "se3_pose",
    "setup_joint_validators",
    "setup_state_checker",
    "setup_validators",
    "solve_and_certify",
]

#: SE(2): a yaw change within this of π is checked as two halves.
NEAR_HALF_TURN_YAW = 1e-6
#: SE(3): a quaternion dot product below this (in absolute value) is
#: checked as two halves.
NEAR_HALF_TURN_DOT = 1e-6
#: OMPL's ``MAX_QUATERNION_NORM_ERROR``: above ``1 - this``, OMPL's SO(3)
#: arc length is 0 and its interpolation returns the first rotation.
OMPL_SO3_FLAT = 1e-9
#: The bracket used by the yes/no ``checkMotion(s1, s2)``, which reports no
#: bracket: the answer (certified free or not) does not depend on it, only
#: the time spent locating a contact does.
DECISION_TOLERANCE = 2.0**-3

_TWO_PI = 2.0 * math.pi


def se2_pose(x: float, y: float, yaw: float) -> np.ndarray:
    """The 4×4 pose of an SE(2) state: a turn by ``yaw`` about z, then the
    translation ``(x, y, 0)``."""
    c, s = math.cos(yaw), math.sin(yaw)
    return np.array([[c, -s, 0.0, x], [s, c, 0.0, y], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])


def _quat_rows(qx: float, qy: float, qz: float, qw: float) -> Tuple[float, ...]:
    """The rotation matrix of a (not necessarily unit) quaternion, row-major."""
    n = qx * qx + qy * qy + qz * qz + qw * qw
    s = 2.0 / n
    xx, yy, zz = qx * qx * s, qy * qy * s, qz * qz * s
    xy, xz, yz = qx * qy * s, qx * qz * s, qy * qz * s
    wx, wy, wz = qw * qx * s, qw * qy * s, qw * qz * s
    return (
        1.0 - yy - zz, xy - wz, xz + wy,
        xy + wz, 1.0 - xx - zz, yz - wx,
        xz - wy, yz + wx, 1.0 - xx - yy,
    )


def se3_pose(x: float, y: float, z: float, qx: float, qy: float, qz: float, qw: float) -> np.ndarray:
    """The 4×4 pose of an SE(3) state: the rotation of the quaternion
    ``(qx, qy, qz, qw)`` (scalar last, as OMPL's ``SO3State`` and scipy;
    normalised), then the translation ``(x, y, z)``."""
    r = _quat_rows(qx, qy, qz, qw)
    return np.array([[r[0], r[1], r[2], x], [r[3], r[4], r[5], y], [r[6], r[7], r[8], z], [0.0, 0.0, 0.0, 1.0]])


class MotionResult(NamedTuple):
    """A certified motion check in OMPL's parametrisation of the motion
    ``s1 → s2`` (``t`` as in ``StateSpace.interpolate(s1, s2, t, out)``).

    * ``free``: certified: no state of the motion touches an obstacle, and
      both ends are within the space's bounds;
    * ``t_safe``: every ``t ≤ t_safe`` is certified free (``1.0`` when
      free; ``None`` when ``s1`` itself is invalid);
    * ``t_contact``: a ``t`` at which the body touches or overlaps an
      obstacle, ``t_contact - t_safe`` at most the tolerance (``None`` when
      free, when an end is out of bounds, or when undecided). For an SE(3)
      turn below OMPL's threshold (``|q₁·q₂| > 1 − 1e-9``), where OMPL's
      interpolation holds the first rotation, the contact may be on that
      motion or on the true (slerp) motion: both are certified;
    * ``undecided``: the motion grazes an obstacle within rounding
      (``MotionUndecided``): not free, certified free up to ``t_safe``.
    """

    free: bool
    t_safe: Optional[float]
    t_contact: Optional[float]
    undecided: bool = False


def _ompl_base() -> Any:
    try:
        from ompl import base as ob
    except ImportError as e:  # pragma: no cover - exercised without OMPL
        raise ImportError(
            "dymsum.ompl needs OMPL's Python bindings (OMPL >= 2.0): pip install ompl"
        ) from e
    return ob


def _space_information(si: Any) -> Any:
    """A ``SpaceInformation`` from itself or a ``SimpleSetup``."""
    if hasattr(si, "getSpaceInformation") and not hasattr(si, "setMotionValidator"):
        si = si.getSpaceInformation()
    if not hasattr(si, "setMotionValidator") or not hasattr(si, "getStateSpace"):
        raise TypeError(
            f"expected an OMPL SpaceInformation (or SimpleSetup), got {type(si).__name__}"
        )
    return si


def _space_kind(space: Any) -> str:
    """``"SE2"`` or ``"SE3"``; a ``TypeError`` for any other space."""
    ob = _ompl_base()
    kind = space.getType()
    if kind == 4 and isinstance(space, ob.SE2StateSpace):
        return "SE2"
    if kind == 5 and isinstance(space, ob.SE3StateSpace):
        return "SE3"
    raise TypeError(
        f"dymsum.ompl supports OMPL's SE2StateSpace and SE3StateSpace (whose interpolation is "
        f"the motion dymsum certifies); got {type(space).__name__} (type {kind}, "
        f"{space.getName()!r}). Dubins, Reeds-Shepp and other curved or compound spaces "
        f"interpolate differently and are refused."
    )


def _checker(robot: Any, obstacles: Any) -> MotionChecker:
    if isinstance(robot, MotionChecker):
        if obstacles is not None:
            raise ValueError("give obstacles only with a robot shape, not with a MotionChecker")
        return robot
    if obstacles is None:
        raise ValueError("obstacles are required (a sequence of shapes or ConvexUnions)")
    return MotionChecker(robot, obstacles)


class _Buffers(threading.local):
    """Per-thread 4×4 pose buffers, written through flat memoryviews."""

    def __init__(self) -> None:
        self.a = np.eye(4)
        self.b = np.eye(4)
        self.va = self.a.data.cast("B").cast("d")
        self.vb = self.b.data.cast("B").cast("d")


class _Poser:
    """Reads OMPL states of one space kind into 4×4 poses."""

    def __init__(self, kind: str) -> None:
        self.kind = kind
        self._buf = _Buffers()

    def fresh(self, s: Any) -> np.ndarray:
        """A new 4×4 array for state ``s``."""
        if self.kind == "SE2":
            return se2_pose(s.getX(), s.getY(), s.getYaw())
        q = s.rotation()
        return se3_pose(s.getX(), s.getY(), s.getZ(), q.x, q.y, q.z, q.w)

    def pair(self, s1: Any, s2: Any) -> Optional[Tuple[np.ndarray, np.ndarray]]:
        """The poses of ``s1`` and ``s2`` in this thread's buffers, or
        ``None`` when the motion must be split (a near half turn) or, in
        SE(3), OMPL's interpolation holds the first rotation."""
        b = self._buf
        va, vb = b.va, b.vb
        if self.kind == "SE2":
            a1, a2 = s1.getYaw(), s2.getYaw()
            if abs(_se2_turn(a1, a2)) > math.pi - NEAR_HALF_TURN_YAW:
                return None
            c, s = math.cos(a1), math.sin(a1)
            va[0] = c; va[1] = -s; va[4] = s; va[5] = c
            va[3] = s1.getX(); va[7] = s1.getY()
            c, s = math.cos(a2), math.sin(a2)
            vb[0] = c; vb[1] = -s; vb[4] = s; vb[5] = c
            vb[3] = s2.getX(); vb[7] = s2.getY()
            return b.a, b.b
        q1, q2 = s1.rotation(), s2.rotation()
        x1, y1, z1, w1 = q1.x, q1.y, q1.z, q1.w
        x2, y2, z2, w2 = q2.x, q2.y, q2.z, q2.w
        dq = abs(x1 * x2 + y1 * y2 + z1 * z2 + w1 * w2)
        if dq < NEAR_HALF_TURN_DOT or dq > 1.0 - OMPL_SO3_FLAT:
            return None
        for v, s, r in ((va, s1, _quat_rows(x1, y1, z1, w1)), (vb, s2, _quat_rows(x2, y2, z2, w2))):
            v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10] = r
            v[3] = s.getX(); v[7] = s.getY(); v[11] = s.getZ()
        return b.a, b.b

    def segments(self, s1: Any, s2: Any) -> List[Tuple[np.ndarray, np.ndarray, float, float]]:
        """The motion ``s1 → s2`` as motions dymsum checks, each
        ``(pose_a, pose_b, t_a, t_b)`` covering ``[t_a, t_b]`` of OMPL's
        interpolation; a held-rotation SE(3) motion has ``t_a = t_b = -1``
        (checked in addition, over the whole ``[0, 1]``)."""
        p1, p2 = self.fresh(s1), self.fresh(s2)
        if self.kind == "SE2":
            a1, a2 = s1.getYaw(), s2.getYaw()
            d = _se2_turn(a1, a2)
            if abs(d) <= math.pi - NEAR_HALF_TURN_YAW:
                return [(p1, p2, 0.0, 1.0)]
            x1, y1, x2, y2 = s1.getX(), s1.getY(), s2.getX(), s2.getY()
            mid = se2_pose(x1 + (x2 - x1) * 0.5, y1 + (y2 - y1) * 0.5, a1 + d * 0.5)
            return [(p1, mid, 0.0, 0.5), (mid, p2, 0.5, 1.0)]
        q1, q2 = s1.rotation(), s2.rotation()
        x1, y1, z1, w1 = q1.x, q1.y, q1.z, q1.w
        x2, y2, z2, w2 = q2.x, q2.y, q2.z, q2.w
        dot = x1 * x2 + y1 * y2 + z1 * z2 + w1 * w2
        dq = abs(dot)
        if dq > 1.0 - OMPL_SO3_FLAT:
            held = se3_pose(s2.getX(), s2.getY(), s2.getZ(), x1, y1, z1, w1)
            out = [(p1, p2, 0.0, 1.0)]
            if (x1, y1, z1, w1) != (x2, y2, z2, w2):
                out.append((p1, held, -1.0, -1.0))
            return out
        if dq >= NEAR_HALF_TURN_DOT:
            return [(p1, p2, 0.0, 1.0)]
        # OMPL's SO3StateSpace.interpolate at t = 0.5, as it computes it.
        theta = math.acos(dq)
        d = 1.0 / math.sin(theta)
        w_a = math.sin(0.5 * theta)
        w_b = -w_a if dot < 0 else w_a
        qm = ((x1 * w_a + x2 * w_b) * d, (y1 * w_a + y2 * w_b) * d, (z1 * w_a + z2 * w_b) * d, (w1 * w_a + w2 * w_b) * d)
        t1x, t1y, t1z = s1.getX(), s1.getY(), s1.getZ()
        mid = se3_pose(
            t1x + (s2.getX() - t1x) * 0.5, t1y + (s2.getY() - t1y) * 0.5, t1z + (s2.getZ() - t1z) * 0.5, *qm
        )
        return [(p1, mid, 0.0, 0.5), (mid, p2, 0.5, 1.0)]


def _se2_turn(a1: float, a2: float) -> float:
    """The signed yaw change OMPL's ``SO2StateSpace.interpolate`` makes
    from ``a1`` to ``a2`` (the shorter way; a difference of exactly π is
    kept as it is)."""
    diff = a2 - a1
    if abs(diff) <= math.pi:
        return diff
    # OMPL: v = from - diff' * t with diff' = ±2π - diff.
    return -((_TWO_PI - diff) if diff > 0.0 else (-_TWO_PI - diff))


class StateChecker:
    """An OMPL state validity checker: the state is within the space's
    bounds and the robot there touches no obstacle (exact query; touching
    counts as a collision).

    ``StateChecker(space_information, checker)`` with ``checker`` a
    ``dymsum.MotionChecker``; install it with
    ``si.setStateValidityChecker(state_checker)`` (``setup_validators``
    and ``setup_state_checker`` do). ``checked`` and ``invalid`` count the
    calls.
    """

    def __init__(self, space_information: Any, checker: MotionChecker) -> None:
        si = _space_information(space_information)
        self.kind = _space_kind(si.getStateSpace())
        self.checker = checker
        self.checked = 0
        self.invalid = 0
        self._poser = _Poser(self.kind)
        # The space's method, not the space information's: a reference to
        # the space information would make a cycle through C++ (it holds
        # this checker) that Python's collector cannot see.
        self._satisfies_bounds = si.getStateSpace().satisfiesBounds
        self._collides_at = checker.collides_at
        se2 = self.kind == "SE2"
        buffers = self._poser._buf

        def is_valid(s: Any) -> bool:
            self.checked += 1
            if self._satisfies_bounds(s):
                v = buffers.va
                if se2:
                    yaw = s.getYaw()
                    c, sn = math.cos(yaw), math.sin(yaw)
                    v[0] = c; v[1] = -sn; v[4] = sn; v[5] = c
                    v[3] = s.getX(); v[7] = s.getY()
                else:
                    q = s.rotation()
                    v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10] = _quat_rows(q.x, q.y, q.z, q.w)
                    v[3] = s.getX(); v[7] = s.getY(); v[11] = s.getZ()
                if not self._collides_at(buffers.a):
                    return True
            self.invalid += 1
            return False

        self._is_valid = is_valid

    def __call__(self, state: Any) -> bool:
        """Whether ``state`` is valid (in bounds and collision-free)."""
        return self._is_valid(state)

    def pose(self, state: Any) -> np.ndarray:
        """The robot's 4×4 pose at an OMPL state (a new array)."""
        return self._poser.fresh(state)

    def __repr__(self) -> str:
        return f"dymsum.ompl.StateChecker({self.kind}, checked={self.checked}, invalid={self.invalid})"


_VALIDATOR_CLASS: Optional[type] = None


def _validator_class() -> type:
    """``CertifiedMotionValidator``, defined on first use (it subclasses
    OMPL's ``MotionValidator``)."""
    global _VALIDATOR_CLASS
    if _VALIDATOR_CLASS is not None:
        return _VALIDATOR_CLASS
    ob = _ompl_base()

    class CertifiedMotionValidator(ob.MotionValidator):  # type: ignore[misc, name-defined]
        """An OMPL motion validator that accepts a motion only when dymsum
        certifies it free (``MotionChecker.check``), with both ends within
        the space's bounds; never by sampling. ``MotionUndecided`` (a motion
        grazing an obstacle within rounding) counts as invalid. The yes/no
        ``checkMotion(s1, s2)`` first checks up to seven of the states OMPL's
        own ``DiscreteMotionValidator`` would sample (the space's
        ``validSegmentCount``, in bisection order) exactly
        (``MotionChecker.sampled_contact``): a contact at one of them
        refutes the motion at the sampled check's price (a colliding state
        is a colliding motion); only a motion none of them refutes is
        certified.

        ``CertifiedMotionValidator(space_information, checker,
        tolerance=1e-6)``: ``checker`` a ``dymsum.MotionChecker``;
        ``tolerance`` bounds ``t_contact - t_safe`` (in OMPL's ``t``) where
        a bracket is returned (``check``, ``checkMotion`` with
        ``last_valid``). Install it with ``si.setMotionValidator(v)``
        (``setup_validators`` does). Counters: ``checked``, ``rejected``,
        ``undecided``, ``sampled`` (rejected by a sampled state).
        """

        def __init__(self, space_information: Any, checker: MotionChecker, tolerance: float = 1e-6) -> None:
            si = _space_information(space_information)
            super().__init__(si)
            if not (0.0 < tolerance < 1.0):
                raise ValueError(f"tolerance must be a finite number in (0, 1), got {tolerance}")
            self.kind = _space_kind(si.getStateSpace())
            self.checker = checker
            self.tolerance = float(tolerance)
            self.decision_tolerance = max(self.tolerance, DECISION_TOLERANCE)
            self.checked = 0
            self.rejected = 0
            self.undecided = 0
            self.sampled = 0
            self._space = si.getStateSpace()
            self._satisfies_bounds = self._space.satisfiesBounds  # no reference to si: no cycle
            self._poser = _Poser(self.kind)
            self._check = checker.check
            self._sampled_contact = checker.sampled_contact
            self._state_checker = StateChecker(si, checker)

        def checkMotion(self, s1: Any, s2: Any, last_valid: Optional[list] = None) -> bool:  # noqa: N802
            """Whether the motion ``s1 → s2`` is certified free. With
            ``last_valid``, a list ``[state or None, float]`` (OMPL's
            ``std::pair<State*, double>``), a rejected motion also sets
            ``last_valid[1]`` to the last certified-free ``t`` and
            interpolates that state into ``last_valid[0]`` (OMPL calls only
            the two-argument form: its bindings do not forward the
            three-argument one)."""
            if last_valid is not None:
                return self._check_last_valid(s1, s2, last_valid)
            self.checked += 1
            if not (self._satisfies_bounds(s2) and self._satisfies_bounds(s1)):
                self.rejected += 1
                return False
            pair = self._poser.pair(s1, s2)
            try:
                if pair is not None:
                    # Up to seven of the states OMPL's sampled check would
                    # visit first: a colliding one refutes the motion.
                    segments = int(self._space.validSegmentCount(s1, s2))
                    if self._sampled_contact(pair[1], pair[0], segments) is not None:
                        self.sampled += 1
                        self.rejected += 1
                        return False
                    # The motion backwards: the same states, and s2 (the new,
                    # unchecked end in a tree planner) is queried first.
                    free = self._check(pair[1], pair[0], self.decision_tolerance).free
                else:
                    free = all(
                        self._check(pb, pa, self.decision_tolerance).free
                        for pa, pb, _, _ in reversed(self._poser.segments(s1, s2))
                    )
            except MotionUndecided:
                self.undecided += 1
                free = False
            if not free:
                self.rejected += 1
            return free

        def check(self, s1: Any, s2: Any) -> MotionResult:
            """The certified check of ``s1 → s2`` with its bracket: a
            ``MotionResult`` (``free``, ``t_safe``, ``t_contact``,
            ``undecided``) in OMPL's ``t``."""
            self.checked += 1
            result = self._result(s1, s2)
            if not result.free:
                self.rejected += 1
            return result

        def _result(self, s1: Any, s2: Any) -> MotionResult:
            if not self._satisfies_bounds(s1):
                return MotionResult(False, None, None)
            safe: Optional[float] = 1.0
            contact: Optional[float] = None
            for pa, pb, ta, tb in self._poser.segments(s1, s2):
                held = ta < 0.0
                if held:
                    ta, tb = 0.0, 1.0
                if not held and safe is not None and ta >= safe:
                    break
                try:
                    c = self._check(pa, pb, self.tolerance)
                except MotionUndecided as e:
                    self.undecided += 1
                    t = ta + (tb - ta) * e.t_safe
                    return MotionResult(False, t if safe is None else min(safe, t), None, True)
                if c.free:
                    continue
                seg_safe = None if c.t_safe is None else ta + (tb - ta) * c.t_safe
                assert c.t_contact is not None  # not free: a contact
                seg_contact = ta + (tb - ta) * c.t_contact
                if seg_safe is None and ta > 0.0:
                    seg_safe = ta  # the segment's start was certified by the one before
                if contact is None or seg_contact < contact:
                    contact = seg_contact
                safe = seg_safe if safe is None or seg_safe is None else min(safe, seg_safe)
                if safe is None:
                    break
            if contact is not None:
                return MotionResult(False, safe, contact)
            if not self._satisfies_bounds(s2):
                return MotionResult(False, 1.0, None)
            return MotionResult(True, 1.0, None)

        def _check_last_valid(self, s1: Any, s2: Any, last_valid: list) -> bool:
            result = self.check(s1, s2)
            if result.free:
                return True
            t = 0.0 if result.t_safe is None else result.t_safe
            out = last_valid[0]
            if out is not None:
                self._space.interpolate(s1, s2, t, out)
                if t > 0.0 and not self._state_checker(out):
                    # OMPL's float interpolation left the certified path by
                    # rounding into contact: fall back to the start.
                    t = 0.0
                    self._space.interpolate(s1, s2, 0.0, out)
            last_valid[1] = t
            return False

        def check_path(self, path: Any) -> List[MotionResult]:
            """``check`` for each motion of an OMPL ``PathGeometric`` (or a
            sequence of states), in order."""
            states = path.getStates() if hasattr(path, "getStates") else list(path)
            return [self._result(a, b) for a, b in zip(states, states[1:])]

        def __repr__(self) -> str:
            return (
                f"dymsum.ompl.CertifiedMotionValidator({self.kind}, tolerance={self.tolerance}, "
                f"checked={self.checked}, rejected={self.rejected}, undecided={self.undecided}, "
                f"sampled={self.sampled})"
            )

    CertifiedMotionValidator.__module__ = __name__
    CertifiedMotionValidator.__qualname__ = "CertifiedMotionValidator"
    _VALIDATOR_CLASS = CertifiedMotionValidator
    return CertifiedMotionValidator


def __getattr__(name: str) -> Any:
    # ``dymsum.ompl.CertifiedMotionValidator`` imports OMPL on first use.
    if name == "CertifiedMotionValidator":
        return _validator_class()
    if name == "JointMotionValidator":
        return _joint_validator_class()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


class Validators(NamedTuple):
    """What ``setup_validators`` installed: the ``MotionChecker``, the
    ``StateChecker`` and the ``CertifiedMotionValidator`` (``None`` from
    ``setup_state_checker``). Keep it (or the space information) alive while
    planning; the space information holds references to both callbacks."""

    checker: MotionChecker
    state_checker: StateChecker
    motion_validator: Any


def setup_validators(
    space_information: Any, robot: Any, obstacles: Any = None, tolerance: float = 1e-6
) -> Validators:
    """Installs dymsum's exact state validity checker and certified motion
    validator on an OMPL ``SpaceInformation`` (or a ``SimpleSetup``'s) of an
    ``SE2StateSpace`` or ``SE3StateSpace``.

    ``robot`` is a ``ConvexUnion`` or one shape, in its own frame (SE(2):
    it turns about z and moves in the plane ``z = 0``); ``obstacles`` a
    sequence of ``ConvexUnion``s or shapes, in the world frame (or give a
    prepared ``dymsum.MotionChecker`` as ``robot`` and no obstacles).
    ``tolerance`` bounds the bracket of ``check`` and ``last_valid``.
    Returns ``Validators(checker, state_checker, motion_validator)``.
    """
    si = _space_information(space_information)
    _space_kind(si.getStateSpace())
    checker = _checker(robot, obstacles)
    state_checker = StateChecker(si, checker)
    validator = _validator_class()(si, checker, tolerance)
    si.setStateValidityChecker(state_checker)
    si.setMotionValidator(validator)
    return Validators(checker, state_checker, validator)


def setup_state_checker(space_information: Any, robot: Any, obstacles: Any = None) -> Validators:
    """Installs only dymsum's exact state validity checker, leaving the
    motion validator as it is: on a fresh ``SpaceInformation``, OMPL's own
    ``DiscreteMotionValidator`` (which checks states ``resolution × extent``
    apart, ``si.setStateValidityCheckingResolution``; 1% by default), for
    comparisons. Refuses a space information that already has dymsum's
    motion validator (OMPL's bindings cannot put the default one back).
    Returns ``Validators(checker, state_checker, None)``.
    """
    si = _space_information(space_information)
    _space_kind(si.getStateSpace())
    if isinstance(si.getMotionValidator(), _validator_class()):
        raise ValueError(
            "this SpaceInformation already uses dymsum's CertifiedMotionValidator; "
            "use a fresh one for OMPL's DiscreteMotionValidator"
        )
    checker = _checker(robot, obstacles)
    state_checker = StateChecker(si, checker)
    si.setStateValidityChecker(state_checker)
    return Validators(checker, state_checker, None)


def certified_path(
    space_information: Any, path: Any, robot: Any, obstacles: Any = None, tolerance: float = 1e-6
) -> List[MotionResult]:
    """Checks every motion of a solution path (an OMPL ``PathGeometric`` or
    a sequence of states) with the certified check, whatever validator
    planned it: one ``MotionResult`` per motion. ``all(r.free for r in
    ...)`` says the whole path is certified free."""
    si = _space_information(space_information)
    validator = _validator_class()(si, _checker(robot, obstacles), tolerance)
    return validator.check_path(path)


def solve_and_certify(simple_setup: Any, checker: MotionChecker, seconds: float = 10.0, simplify: bool = True) -> dict:
    """Plans once with an OMPL ``SimpleSetup`` whatever its validators, then
    checks every motion of the path found with the certified check.

    Returns a dict: ``found`` (an exact solution), ``time`` (OMPL's planning
    time, s) and, when found, ``length``, ``states``, ``simplify_time`` (s,
    0 without ``simplify``), ``certified`` (every motion certified free)
    and ``uncertified_motions`` (how many are not)."""
    import time

    ss = simple_setup
    solved = ss.solve(seconds)
    found = bool(solved) and ss.haveExactSolutionPath()
    out: dict = {"found": found, "time": ss.getLastPlanComputationTime()}
    if not found:
        return out
    simplify_time = 0.0
    if simplify:
        t0 = time.perf_counter()
        ss.simplifySolution()
        simplify_time = time.perf_counter() - t0
    path = ss.getSolutionPath()
    checks = certified_path(ss, path, checker)
    out.update(
        length=path.length(),
        states=path.getStateCount(),
        simplify_time=simplify_time,
        certified=all(c.free for c in checks),
        uncertified_motions=sum(not c.free for c in checks),
    )
    return out


def _joint_space(si: Any, checker: RobotChecker) -> int:
    """The dimension of a ``RealVectorStateSpace`` matching the robot's
    degrees of freedom; a ``TypeError`` or ``ValueError`` otherwise."""
    ob = _ompl_base()
    space = si.getStateSpace()
    if not isinstance(space, ob.RealVectorStateSpace):
        raise TypeError(
            f"joint-space validators need OMPL's RealVectorStateSpace (linear interpolation is the "
            f"motion dymsum certifies); got {type(space).__name__}"
        )
    n = space.getDimension()
    if n != checker.dof:
        raise ValueError(f"the space has {n} dimensions, the robot {checker.dof} degrees of freedom")
    return n


class JointStateChecker:
    """An OMPL state validity checker for a robot in joint space: the state
    is within the space's bounds (and the joint limits) and the robot there
    touches neither itself nor an obstacle (``RobotChecker.collides_at``,
    exact). ``checked`` and ``invalid`` count the calls."""

    def __init__(self, space_information: Any, checker: RobotChecker) -> None:
        si = _space_information(space_information)
        self.n = _joint_space(si, checker)
        self.checker = checker
        self.checked = 0
        self.invalid = 0
        self._satisfies_bounds = si.getStateSpace().satisfiesBounds

    def q(self, state: Any) -> List[float]:
        """The configuration of an OMPL state."""
        return [state[i] for i in range(self.n)]

    def __call__(self, state: Any) -> bool:
        """Whether ``state`` is valid."""
        self.checked += 1
        if self._satisfies_bounds(state):
            try:
                if not self.checker.collides_at(self.q(state)):
                    return True
            except ValueError:
                pass  # outside a joint's limits
        self.invalid += 1
        return False

    def __repr__(self) -> str:
        return f"dymsum.ompl.JointStateChecker(checked={self.checked}, invalid={self.invalid})"


_JOINT_VALIDATOR_CLASS: Optional[type] = None


def _joint_validator_class() -> type:
    """``JointMotionValidator``, defined on first use (it subclasses OMPL's
    ``MotionValidator``)."""
    global _JOINT_VALIDATOR_CLASS
    if _JOINT_VALIDATOR_CLASS is not None:
        return _JOINT_VALIDATOR_CLASS
    ob = _ompl_base()

    class JointMotionValidator(ob.MotionValidator):  # type: ignore[misc, name-defined]
        """An OMPL motion validator for a robot in joint space: a motion is
        accepted only when ``RobotChecker.check`` certifies it free, both
        ends in bounds; ``MotionUndecided`` and configurations outside the
        joint limits count as invalid. Up to seven of the states OMPL's own
        ``DiscreteMotionValidator`` would sample (the space's
        ``validSegmentCount``, in bisection order) are checked exactly
        first (``RobotChecker.sampled_contact``): a contact at one of them
        refutes the motion at the sampled check's price (a colliding state
        is a colliding motion); only a motion none of them refutes is
        certified.
        Counters: ``checked``, ``rejected``, ``undecided``, ``sampled``
        (rejected by a sampled state)."""

        def __init__(self, space_information: Any, checker: RobotChecker, tolerance: float = 1e-6) -> None:
            si = _space_information(space_information)
            super().__init__(si)
            if not (0.0 < tolerance < 1.0):
                raise ValueError(f"tolerance must be a finite number in (0, 1), got {tolerance}")
            self.n = _joint_space(si, checker)
            self.checker = checker
            self.tolerance = float(tolerance)
            self.decision_tolerance = max(self.tolerance, DECISION_TOLERANCE)
            self.checked = 0
            self.rejected = 0
            self.undecided = 0
            self.sampled = 0
            self._space = si.getStateSpace()
            self._satisfies_bounds = self._space.satisfiesBounds

        def checkMotion(self, s1: Any, s2: Any) -> bool:  # noqa: N802
            """Whether the motion ``s1 → s2`` is certified free."""
            self.checked += 1
            free = False
            if self._satisfies_bounds(s1) and self._satisfies_bounds(s2):
                q1 = [s1[i] for i in range(self.n)]
                q2 = [s2[i] for i in range(self.n)]
                try:
                    segments = int(self._space.validSegmentCount(s1, s2))
                    if self.checker.sampled_contact(q1, q2, segments) is not None:
                        self.sampled += 1
                        self.rejected += 1
                        return False
                    # Backwards: s2 (the new end in a tree planner) first.
                    free = self.checker.check(q2, q1, self.decision_tolerance).free
                except MotionUndecided:
                    self.undecided += 1
                except ValueError:
                    pass  # outside a joint's limits
            if not free:
                self.rejected += 1
            return free

        def __repr__(self) -> str:
            return (
                f"dymsum.ompl.JointMotionValidator(checked={self.checked}, rejected={self.rejected}, "
                f"undecided={self.undecided}, sampled={self.sampled})"
            )

    JointMotionValidator.__module__ = __name__
    JointMotionValidator.__qualname__ = "JointMotionValidator"
    _JOINT_VALIDATOR_CLASS = JointMotionValidator
    return JointMotionValidator


def setup_joint_validators(space_information: Any, checker: RobotChecker, tolerance: float = 1e-6) -> Validators:
    """Installs dymsum's exact state validity checker and certified motion
    validator for a robot in joint space on an OMPL ``SpaceInformation``
    (or a ``SimpleSetup``'s) of a ``RealVectorStateSpace`` with one
    dimension per degree of freedom. Returns ``Validators(checker,
    state_checker, motion_validator)``."""
    si = _space_information(space_information)
    state_checker = JointStateChecker(si, checker)
    validator = _joint_validator_class()(si, checker, tolerance)
    si.setStateValidityChecker(state_checker)
    si.setMotionValidator(validator)
    return Validators(checker, state_checker, validator)

