"""Which way a motion to a nearly opposite orientation turns, from every
Python entry point (issue 26 §1), and the motion check's work budget and
tolerance floor (§4).

The scene of the finding: a bar ``[0, 2] × [−.05, .05]²`` turning about z
from the identity to ``180° ± ε``, and a block at ``y ∈ [−1.6, −1.4]`` that
only the clockwise arc sweeps. The shorter arc (OMPL's rule: negate the
second quaternion when the dot product is negative) is clockwise for
``+ε`` and counter-clockwise for ``−ε``; at an exact half turn (dot product
exactly zero) the second quaternion is kept as given.
"""

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import dymsum


def cuboid(lo, hi):
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])], float)


BAR = cuboid([0, -0.05, -0.05], [2, 0.05, 0.05])
BLOCK = cuboid([-0.1, -1.6, -1], [0.1, -1.4, 1])


def half_turn_plus(eps):
    """The quaternion (x, y, z, w) of a turn by π + eps about +z, built
    exactly: w = −sin(eps/2), z = cos(eps/2)."""
    return np.array([0.0, 0.0, math.cos(eps / 2), -math.sin(eps / 2)])


def sweeps(total):
    """Oracle independent of dymsum's interpolation: the bar turning by
    ``total`` radians about z (negative: clockwise) at 2,001 instants, each
    checked by the exact query."""
    angles = np.linspace(0.0, total, 2001)
    poses = np.stack([dymsum.pose(Rotation.from_euler("z", a)) for a in angles])
    return bool(dymsum.collides_many(BAR, BLOCK, poses, None).any())


def test_oracle_clockwise_half_turn_sweeps_the_block():
    assert sweeps(-math.pi) and not sweeps(math.pi)


EPS = math.radians(1e-12)
# (label, rotation as given, clockwise expected)
CASES = [
    ("+1e-12°", half_turn_plus(EPS), True),
    ("−1e-12°", half_turn_plus(-EPS), False),
    ("+1e-300", np.array([0.0, 0.0, 1.0, -5e-301]), True),
    ("−1e-300", np.array([0.0, 0.0, 1.0, 5e-301]), False),
    ("w = +0, z = 1", np.array([0.0, 0.0, 1.0, 0.0]), False),
    ("w = −0, z = 1", np.array([0.0, 0.0, 1.0, -0.0]), False),
    ("w = +0, z = −1", np.array([0.0, 0.0, -1.0, 0.0]), True),
    ("w = −0, z = −1", np.array([0.0, 0.0, -1.0, -0.0]), True),
]


@pytest.mark.parametrize("label,quat,clockwise", CASES, ids=[c[0] for c in CASES])
@pytest.mark.parametrize("form", ["quaternion", "pose", "scipy", "matrix", "check_motions", "MotionChecker"])
def test_regression_half_turn_takes_the_arc_of_the_rotations_as_given(label, quat, clockwise, form):
    """The motion from the identity to 180° ± ε: clockwise (through the
    block) exactly when the dot product of the quaternions as given is
    negative, from a quaternion, ``dymsum.pose``, a scipy ``Rotation``, a
    3×3 matrix, ``check_motions`` and a ``MotionChecker``."""
    if form in ("pose", "matrix") and quat[3] == 0.0:
        pytest.skip("a matrix has no sign: an exact half turn's arc is given by quaternions only")
    if form == "pose":
        end = dymsum.pose(quat)
    elif form == "scipy":
        # scipy keeps the quaternion it is given (as_quat, not canonical).
        end = Rotation.from_quat(quat)
    elif form == "matrix":
        end = Rotation.from_quat(quat).as_matrix()
    else:
        end = quat
    if form == "check_motions":
        free = bool(dymsum.check_motions(BAR, [BLOCK], np.array([[0.0, 0, 0, 1]]), end[None]).free[0])
    elif form == "MotionChecker":
        free = dymsum.MotionChecker(BAR, [BLOCK]).check(None, end).free
    else:
        free = dymsum.check_motion(BAR, [BLOCK], None, end).free
    assert free == (not clockwise), f"{label} from {form}: free={free}"


def test_pose_keeps_the_side_of_the_half_turn_and_exact_quarter_turns():
    """``dymsum.pose`` hands out the unsnapped matrix where snapping would
    erase the tiny turn, and the exact matrix of a quarter turn."""
    m = dymsum.pose(half_turn_plus(EPS))
    assert m[1, 0] < 0.0 < m[0, 1]  # sin(π + ε) < 0
    quarter = dymsum.pose([0, 0, math.sqrt(0.5), math.sqrt(0.5)])
    assert quarter[:3, :3].tolist() == [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]


def test_the_start_quaternions_sign_keeps_the_shorter_arc():
    minus_identity = np.array([0.0, 0.0, 0.0, -1.0])
    assert not dymsum.check_motion(BAR, [BLOCK], minus_identity, half_turn_plus(EPS)).free
    assert dymsum.check_motion(BAR, [BLOCK], minus_identity, half_turn_plus(-EPS)).free


def grazing_plate(gap):
    x = math.sqrt(4.0025) + gap
    return cuboid([x, -1, -1], [x + 0.01, 1, 1])


def test_regression_grazing_plate_is_decided_quickly():
    turn = lambda deg: dymsum.pose(Rotation.from_euler("z", deg, degrees=True))
    for gap in (1e-9, 1e-10, 1e-12):
        checker = dymsum.MotionChecker(BAR, [grazing_plate(gap)])
        assert checker.check(turn(-45), turn(45)).free, gap
        assert checker.steps <= 1000, (gap, checker.steps)
    # Touching: undecided (never free) within the budget.
    checker = dymsum.MotionChecker(BAR, [grazing_plate(0.0)])
    try:
        c = checker.check(turn(-45), turn(45))
        assert not c.free
    except dymsum.MotionUndecided as e:
        assert e.t_safe < 1.0
    assert checker.steps <= checker.budget == 4096


def test_budget_raises_undecided_with_a_certified_prefix():
    turn = lambda deg: dymsum.pose(Rotation.from_euler("z", deg, degrees=True))
    block = cuboid([1.7, -0.5, -1], [1.9, -0.3, 1])
    checker = dymsum.MotionChecker(BAR, [block], budget=2)
    assert checker.budget == 2
    with pytest.raises(dymsum.MotionUndecided, match="budget of 2 intervals") as info:
        checker.check(turn(45), turn(-45), 1e-9)
    e = info.value
    assert e.budget_exhausted and e.t is None and 0.0 <= e.t_safe < 1.0
    # The prefix [0, t_safe] is free (dense exact sampling along the turn).
    angles = np.linspace(45.0, 45.0 - 90.0 * e.t_safe, 500)
    poses = np.stack([turn(a) for a in angles])
    assert not dymsum.collides_many(BAR, block, poses, None).any()
    # Deterministic: the same answer again, and from check_motion.
    with pytest.raises(dymsum.MotionUndecided) as again:
        dymsum.check_motion(BAR, [block], turn(45), turn(-45), 1e-9, budget=2)
    assert again.value.t_safe == e.t_safe
    assert not dymsum.check_motion(BAR, [block], turn(45), turn(-45), 1e-9).free
    with pytest.raises(ValueError, match="budget"):
        dymsum.MotionChecker(BAR, [block], budget=0)


def test_regression_tolerance_below_what_the_search_can_bracket_is_refused():
    box = cuboid([-0.5, -0.5, -0.5], [0.5, 0.5, 0.5])
    for bad in (1e-300, 1e-13):
        with pytest.raises(ValueError, match=r"3\.637978807091713e-12"):
            dymsum.check_motion(box, [box], dymsum.pose(translation=[3, 0, 0]), None, tolerance=bad)
    c = dymsum.check_motion(box, [box], dymsum.pose(translation=[3, 0, 0]), None, tolerance=2.0**-38)
    assert not c.free and abs(c.t_contact - 2 / 3) <= 2.0**-38
