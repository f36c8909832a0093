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


def _batch(rng, k, spread):
    """K poses of A (random turns near the origin) and of B (moved)."""
    rots = Rotation.random(k, random_state=rng.integers(1 << 30))
    poses_a = np.stack([dymsum.pose(r, rng.normal(size=3) * 0.1) for r in rots])
    poses_b = np.stack(
        [dymsum.pose(Rotation.random(random_state=rng.integers(1 << 30)), rng.normal(size=3) * spread) for _ in range(k)]
    )
    return poses_a, poses_b


def test_contact_many_is_contact_row_by_row():
    """Every row of contact_many equals contact at that pose, bit for bit
    (boxes, a round hull, apart and overlapping), and collides_many agrees."""
    rng = np.random.default_rng(18)
    a = dymsum.Polytope(sphere_points(40, np.random.default_rng(5)))
    b = dymsum.load("box:1,2,3")
    poses_a, poses_b = _batch(rng, 300, 1.2)
    many = dymsum.contact_many(a, b, poses_a, poses_b)
    assert len(many) == 300 and many.normal.shape == (300, 3)
    yes = dymsum.collides_many(a, b, poses_a, poses_b)
    assert yes.dtype == np.bool_ and yes.tolist() == many.collides.tolist()
    assert 30 < many.collides.sum() < 270
    for k in range(300):
        c = dymsum.contact(a, b, poses_a[k], poses_b[k])
        assert (c.collides, c.depth, c.distance) == (many.collides[k], many.depth[k], many.distance[k])
        assert c.normal.tolist() == many.normal[k].tolist()
        assert c.point_a.tolist() == many.point_a[k].tolist()
        assert c.point_b.tolist() == many.point_b[k].tolist()


def test_contact_many_broadcasts_one_pose_and_checks_lengths():
    cube = CUBE - 0.5
    xs = np.linspace(0.0, 2.0, 9)
    poses_b = np.stack([dymsum.pose(translation=[x, 0, 0]) for x in xs])
    many = dymsum.contact_many(cube, cube, None, poses_b)
    assert many.depth.tolist() == [max(0.0, 1.0 - x) for x in xs]
    assert many.distance.tolist() == [max(0.0, x - 1.0) for x in xs]
    # One pose of A for all, given as a quaternion; B as a scipy stack.
    turned = dymsum.contact_many(cube, cube, [0, 0, 0, 1], Rotation.from_rotvec(np.zeros((4, 3))))
    assert len(turned) == 4 and turned.collides.all()
    with pytest.raises(ValueError, match="same number"):
        dymsum.contact_many(cube, cube, poses_b[:3], poses_b[:5])
    with pytest.raises(ValueError, match="poses_b"):
        dymsum.contact_many(cube, cube, None, np.zeros((3, 2, 2)))


def test_tracker_strategies_give_the_static_answers():
    """Both tracker strategies answer exactly what contact answers, frame
    by frame, and the certified one needs no exhaustive fallback here."""
    a = dymsum.load("gs2")
    b = dymsum.load("cylinder")
    for strategy in ("certified", "sum", "auto"):
        t = dymsum.ContactTracker(a, b, strategy=strategy)
        assert t.strategy == strategy
        assert t.active_strategy in ("certified", "sum")
        for k in range(60):
            turn = Rotation.from_rotvec([0.0, 0.0, 0.02 * k])
            pa = dymsum.pose(turn, [2.5 - 0.06 * k, 0.1, 0.0])
            got = t.update(pa, None)
            want = dymsum.contact(a, b, pa, None)
            assert (got.collides, got.depth, got.distance) == (want.collides, want.depth, want.distance)
            assert got.normal.tolist() == want.normal.tolist()
        if strategy == "sum":
            assert t.last_update["facets"] > 0
        elif strategy == "certified":
            assert t.last_update["facets"] == 0
            assert t.stats["queries"] >= 61 and t.stats["exhaustive_answers"] == 0
            # The frames in contact re-pose the last frame's EPA polytope.
            assert t.stats["carried_polytopes"] > 0
            assert 0 <= t.stats["carried_restarts"] <= t.stats["carried_polytopes"]
    with pytest.raises(ValueError, match="strategy"):
        dymsum.ContactTracker(a, b, strategy="fast")
