"""Obstacles given in their own frame with a pose (issue 34): ``(body,
pose)`` wherever obstacles are taken. Oracle: the same obstacle moved by
hand (its vertices posed with the same float arithmetic is not available
from Python, so poses here are exact: quarter turns and dyadic
translations, under which moving by hand is exact too)."""

import numpy as np
import pytest

import dymsum

scipy_rotation = pytest.importorskip("scipy.spatial.transform").Rotation

QUADS = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]


def box(lo, hi):
    v = np.array([[hi[k] if (i >> k) & 1 else lo[k] for k in range(3)] for i in range(8)], float)
    f = np.array([t for q in QUADS for t in ([q[0], q[1], q[2]], [q[0], q[2], q[3]])])
    return v, f


def two_boxes():
    (va, fa), (vb, fb) = box([0, 0, 0], [1, 1, 1]), box([1, 0, 0], [2, 1, 1])
    return np.vstack([va, vb]), np.vstack([fa, fb + 8])


def moved(mesh, pose):
    v, f = mesh
    return (v @ pose[:3, :3].T + pose[:3, 3], f)


@pytest.mark.parametrize("mesh", [two_boxes(), box([0, 0, 0], [1, 2, 0.5])], ids=["touching boxes", "one box"])
def test_a_placed_obstacle_answers_as_one_moved_by_hand(mesh):
    quarter = scipy_rotation.from_euler("z", 90, degrees=True)
    pose = dymsum.pose(quarter, translation=[3.0, -1.0, 2.5])
    robot = box([-0.25] * 3, [0.25] * 3)
    placed = dymsum.MotionChecker(robot, [(mesh, pose)])
    by_hand = dymsum.MotionChecker(robot, [moved(mesh, pose)])
    single = dymsum.MotionChecker(robot, (mesh, pose))  # one placed obstacle, no list
    rng = np.random.default_rng(34)
    for _ in range(300):
        at = dymsum.pose(translation=rng.integers(-16, 48, 3) / 8.0)
        assert placed.collides_at(at) == by_hand.collides_at(at) == single.collides_at(at)
    start, end = dymsum.pose(translation=[-3.0, 0.5, 2.75]), dymsum.pose(translation=[6.0, 0.5, 2.75])
    a, b = placed.check(start, end), by_hand.check(start, end)
    assert a.free == b.free and a.t_contact == b.t_contact
    # A scipy Rotation is a pose too (a turn about the origin).
    turned = dymsum.MotionChecker(robot, [(mesh, quarter)])
    assert turned.collides_at(dymsum.pose(translation=[-0.5, 0.5, 0.25]))


def test_faces_are_not_taken_for_a_pose():
    # A (vertices, faces) pair of quads: a (4, 4) integer face array is faces.
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    quad = np.array([[0, 1, 2, 3]] * 1 + [[3, 2, 1, 0]] * 3)
    checker = dymsum.MotionChecker(box([-0.1] * 3, [0.1] * 3), [(v, quad)])
    assert checker.info["path"] == "triangles"


def test_a_bad_placed_pose_names_the_obstacle():
    with pytest.raises(ValueError, match=r"obstacles\[0\]\[1\]"):
        dymsum.MotionChecker(box([0] * 3, [1] * 3), [(two_boxes(), np.full((4, 4), np.nan))])
