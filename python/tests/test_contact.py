"""contact, ContactTracker and cobstacle_slices against brute-force oracles."""

import numpy as np
import pytest
from conftest import (
    CUBE,
    apply,
    check_sum_against_qhull,
    pairwise_sums,
    random_pose,
    sphere_points,
)
from scipy.optimize import linprog
from scipy.spatial import ConvexHull
from scipy.spatial.transform import Rotation

import dymsum


def in_hull(points, x, tol):
    """x is in the convex hull of points (within tol), by an LP."""
    n = len(points)
    res = linprog(
        np.zeros(n),
        A_eq=np.vstack([points.T, np.ones(n)]),
        b_eq=np.append(x, 1.0),
        bounds=[(0, None)] * n,
        method="highs",
    )
    if res.status == 0:
        return True
    # Infeasible at the LP's own tolerance: measure the distance instead.
    h = ConvexHull(points)
    return (h.equations[:, :3] @ x + h.equations[:, 3]).max() <= tol


def check_contact(c, a, b, pa, pb):
    """c is the exact depth/distance of A and B (brute-force oracles)."""
    va, vb = apply(pa, a), apply(pb, b)
    scale = max(np.abs(va).max(), np.abs(vb).max())
    tol = 1e-9 * scale
    # D = A ⊕ (−B): the hull of all pairwise differences.
    h = ConvexHull(pairwise_sums(va, -vb))
    offsets = h.equations[:, 3]  # n·0 + d: negative when the origin is inside
    assert np.allclose(np.linalg.norm(c.normal), 1.0, atol=1e-12)
    assert c.normal.dtype == np.float64 and c.normal.shape == (3,)
    if offsets.max() < -tol:
        assert c.collides and c.distance == 0.0
        # Depth: the origin's distance to the boundary of D, the minimum over
        # D's face planes.
        k = np.argmin(-offsets)
        assert c.depth == pytest.approx(-offsets[k], rel=1e-9, abs=tol)
        # The normal is that face's outward normal when the minimum is clear.
        second = np.sort(-offsets[np.abs(h.equations[:, :3] - h.equations[k, :3]).max(axis=1) > 1e-6])
        if len(second) and second[0] > -offsets[k] + 1e-6 * scale:
            assert np.abs(c.normal - h.equations[k, :3]).max() < 1e-7
        assert np.allclose(c.point_a - c.point_b, c.depth * c.normal, atol=tol)
    elif offsets.max() > tol:
        assert not c.collides and c.depth == 0.0
        # The witnesses are in A and B, at the reported distance, and the
        # normal separates A and B by exactly that distance (which certifies
        # the minimum: no pair of points is closer).
        assert np.linalg.norm(c.point_b - c.point_a) == pytest.approx(c.distance, rel=1e-9, abs=tol)
        gap = (vb @ c.normal).min() - (va @ c.normal).max()
        assert gap == pytest.approx(c.distance, rel=1e-9, abs=tol)
        assert in_hull(va, c.point_a, tol) and in_hull(vb, c.point_b, tol)
        assert c.distance >= offsets.max() - tol
    else:
        assert abs(c.depth) <= tol and abs(c.distance) <= tol  # touching


@pytest.mark.parametrize("case", range(30))
def test_contact_matches_brute_force(case, rng):
    a = sphere_points(int(rng.integers(4, 40)), rng, radii=rng.uniform(0.3, 2, size=3))
    b = rng.normal(size=(int(rng.integers(4, 40)), 3))
    pa, pb = random_pose(rng, shift=1.5), random_pose(rng, shift=1.5)
    c = dymsum.contact(a, b, pa, pb)
    check_contact(c, a, b, pa, pb)


def test_contact_both_ways_and_both_states():
    p = dymsum.Polytope(CUBE - 0.5)
    hit = dymsum.contact(p, p, None, dymsum.pose(translation=[0.75, 0.1, 0]))
    assert hit.collides and hit.depth == 0.25 and hit.normal.tolist() == [1.0, 0.0, 0.0]
    swapped = dymsum.contact(p, p, dymsum.pose(translation=[0.75, 0.1, 0]), None)
    assert swapped.depth == 0.25 and swapped.normal.tolist() == [-1.0, 0.0, 0.0]
    apart = dymsum.contact(p, p, None, dymsum.pose(translation=[1.5, 0, 0]))
    assert (apart.collides, apart.depth, apart.distance) == (False, 0.0, 0.5)
    touching = dymsum.contact(p, p, None, dymsum.pose(translation=[1.0, 0, 0]))
    assert touching.collides and touching.depth == 0.0


def test_tracker_update_keeps_a_body_whose_pose_is_none(rng):
    a, b = sphere_points(15, rng), sphere_points(15, rng)
    pa, pb = random_pose(rng, shift=0.5), random_pose(rng, shift=0.5)
    t = dymsum.ContactTracker(a, b, pa, pb)
    pa2 = random_pose(rng, angle=0.05) @ pa
    c = t.update(pa2)  # B stays at pb
    assert c.depth == dymsum.contact(a, b, pa2, pb).depth
    pb2 = random_pose(rng, angle=0.05) @ pb
    c = t.update(None, pb2)  # A stays at pa2
    fresh = dymsum.contact(a, b, pa2, pb2)
    assert (c.depth, c.distance) == (fresh.depth, fresh.distance)
    assert np.array_equal(c.normal, fresh.normal)


def test_tracker_equals_contact_every_frame(rng):
    a, b = dymsum.load("gs2"), dymsum.load("ellipse")
    tracker = dymsum.ContactTracker(a, b)
    axis = np.array([0.3, 1.0, -0.4]) / np.linalg.norm([0.3, 1.0, -0.4])
    collided = apart = 0
    for k in range(120):
        pa = np.eye(4)
        pa[:3, :3] = Rotation.from_rotvec(axis * 0.02 * k).as_matrix()
        pa[:3, 3] = [3.0 * np.cos(0.05 * k), 0.5, 0.0]
        pb = dymsum.pose(Rotation.from_rotvec([0, 0, -0.01 * k]).as_quat())
        c = tracker.update(pa, pb)
        fresh = dymsum.contact(a, b, pa, pb)
        assert (c.collides, c.depth, c.distance) == (fresh.collides, fresh.depth, fresh.distance)
        assert np.array_equal(c.normal, fresh.normal)
        assert np.array_equal(c.point_a, fresh.point_a) and np.array_equal(c.point_b, fresh.point_b)
        assert tracker.last_update["recovered"] is None
        collided += c.collides
        apart += not c.collides
        if k % 40 == 0:
            check_contact(c, a.vertices, b.vertices, pa, pb)
    assert collided > 10 and apart > 10  # the motion crosses contact both ways
    assert tracker.last.depth == c.depth


@pytest.mark.parametrize("form", ["quaternions", "matrices"])
def test_cobstacle_slices_match_qhull(form, rng):
    robot = sphere_points(12, rng, radii=(0.5, 1.0, 0.2))
    obstacle = dymsum.load("box:2,1,1")
    rots = Rotation.from_rotvec(np.outer(np.linspace(0, np.pi, 24), [0.2, 0.1, 1.0]))
    arg = rots.as_quat() if form == "quaternions" else rots.as_matrix()
    slices = dymsum.cobstacle_slices(robot, obstacle, arg, polygons=True)
    assert len(slices) == 24
    for (v, polys), r in zip(slices[::5], list(rots)[::5]):
        # The slice is obstacle ⊕ (−R·robot).
        check_sum_against_qhull(v, polys, pairwise_sums(obstacle.vertices, -r.apply(robot)))
    par = dymsum.cobstacle_slices(robot, obstacle, arg, polygons=True, parallel=True)
    for (v, polys), (v2, polys2) in zip(slices, par):
        assert np.array_equal(v, v2) and all(np.array_equal(p, q) for p, q in zip(polys, polys2))
    tri = dymsum.cobstacle_slices(robot, obstacle, arg)
    assert all(f.shape[1] == 3 and f.dtype == np.int64 for _, f in tri)


def test_cobstacle_slices_no_rotations():
    assert dymsum.cobstacle_slices(CUBE, CUBE, np.zeros((0, 4))) == []
