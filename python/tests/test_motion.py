"""Certified motion checks from Python, against a dense sampling oracle.

The oracle interpolates each motion exactly as documented (translation
linear, rotation by slerp along the shorter arc, scipy's ``Slerp``) at many
instants and asks the exact static query at each: a certified ``free``
must have no colliding sample; a ``t_safe`` must have no colliding sample
before it; ``t_contact`` must collide (exact query).
"""

import numpy as np
import pytest
from scipy.spatial import ConvexHull
from scipy.spatial.transform import Rotation, Slerp

import dymsum

from conftest import CUBE


def cuboid(lo, hi):
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])], float)


def pose_of(rotation, translation):
    m = np.eye(4)
    m[:3, :3] = rotation.as_matrix()
    m[:3, 3] = translation
    return m


def interpolate(p0, p1, ts):
    """The poses of the straight motion p0 → p1 at the instants ts, (K, 4, 4)."""
    rots = Rotation.from_matrix(np.stack([p0[:3, :3], p1[:3, :3]]))
    r = Slerp([0.0, 1.0], rots)(ts)
    out = np.tile(np.eye(4), (len(ts), 1, 1))
    out[:, :3, :3] = r.as_matrix()
    out[:, :3, 3] = p0[:3, 3] + np.outer(ts, p1[:3, 3] - p0[:3, 3])
    return out


def sampled_collisions(body, obstacles, poses):
    """(K,) bool: the body at each pose meets some obstacle (exact queries)."""
    hit = np.zeros(len(poses), bool)
    for piece in body:
        for o in obstacles:
            hit |= dymsum.collides_many(piece, o, poses, None)
    return hit


def assert_agrees_with_sampling(body, obstacles, p0, p1, answer, samples=2000):
    ts = np.linspace(0.0, 1.0, samples)
    hit = sampled_collisions(body, obstacles, interpolate(p0, p1, ts))
    if answer.free:
        assert not hit.any(), f"certified free, but t = {ts[hit][0]} collides"
        return
    if answer.t_safe is not None:
        assert not hit[ts <= answer.t_safe].any(), "a sample before t_safe collides"
    contact = interpolate(p0, p1, np.array([answer.t_contact]))
    assert sampled_collisions(body, obstacles, contact)[0], "no contact at t_contact"


BAR = cuboid([-2, -0.05, -0.05], [2, 0.05, 0.05])
BLOCK = cuboid([1.7, 0.6, -1], [1.9, 0.8, 1])
WALL = cuboid([4.999, -5, -5], [5.001, 5, 5])
BOX = CUBE - 0.5


def turn(deg):
    return pose_of(Rotation.from_euler("z", deg, degrees=True), [0, 0, 0])


def test_thin_wall_is_not_stepped_over():
    # A small box slides 10 units through a wall 0.002 thick: sampled at 1%
    # steps of the motion (0.1 apart, as OMPL's default resolution), every
    # sampled pose is free.
    small = BOX * 0.05
    wall = cuboid([5.049, -5, -5], [5.051, 5, 5])
    end = dymsum.pose(translation=[10, 0, 0])
    ts = np.linspace(0, 1, 101)
    assert not sampled_collisions([small], [wall], interpolate(np.eye(4), end, ts)).any()
    c = dymsum.check_motion(small, [wall], None, end, tolerance=1e-9)
    assert not c.free and not c
    assert c.t_contact - c.t_safe <= 1e-9
    # The box first touches the wall when its face x = 0.025 reaches 5.049.
    assert abs(c.t_contact - 0.5024) <= 1e-9
    assert_agrees_with_sampling([small], [wall], np.eye(4), end, c, samples=20001)


def test_bar_turning_past_a_corner_collides_between_free_samples():
    checker = dymsum.MotionChecker(BAR, [BLOCK])
    assert not any(checker.collides_at(turn(d)) for d in (0, 45, 90))
    c = checker.check(turn(0), turn(90), 1e-6)
    assert not c.free and 0 < c.t_safe < c.t_contact <= c.t_safe + 1e-6
    assert checker.collides_at(turn(90 * c.t_contact))
    assert_agrees_with_sampling([BAR], [BLOCK], turn(0), turn(90), c)
    # Turning the other way misses the block.
    free = checker.check(turn(0), turn(-90))
    assert free.free and free.t_safe == 1.0 and free.t_contact is None
    assert repr(free) == "MotionCheck(free=True, t_safe=1.0, t_contact=None)"


@pytest.mark.parametrize("triangles", [False, True])
def test_sampled_contact_refutes_only_with_a_colliding_sample(triangles):
    """``MotionChecker.sampled_contact``: the first colliding sample in
    bisection order, at the pose ``check`` checks at that ``t``; ``None``
    when none of the samples collides, even on a motion that does (only
    ``check`` decides). On the convex path and on triangles alike."""
    faces = ConvexHull(BLOCK).simplices
    # Without its top: an open surface, taken as triangles.
    open_block = (BLOCK, faces[BLOCK[faces].mean(axis=1)[:, 2] < 1])
    checker = dymsum.MotionChecker(BAR, [open_block if triangles else BLOCK, WALL])
    assert checker.info["path"] == ("triangles" if triangles else "convex")
    rng = np.random.default_rng(5)
    hits = misses = 0
    while hits < 10 or misses < 10:
        p0 = pose_of(Rotation.random(random_state=rng), rng.uniform(-2, 6, 3) * [1, 0.3, 0.3])
        p1 = pose_of(Rotation.random(random_state=rng), rng.uniform(-2, 6, 3) * [1, 0.3, 0.3])
        t = checker.sampled_contact(p0, p1, 16)
        if t is None:
            misses += 1
            samples = interpolate(p0, p1, np.array([8, 4, 12, 2, 6, 10, 14]) / 16)
            assert not checker.collides_many(samples).any()
        else:
            hits += 1
            assert t * 16 == round(t * 16) and 0 < t < 1
            assert checker.collides_at(interpolate(p0, p1, np.array([t]))[0])
            assert not checker.check(p0, p1).free
    # The bar turning past the block's corner collides between 0° and 45°.
    assert checker.sampled_contact(turn(0), turn(90), 2) is None
    assert not checker.check(turn(0), turn(90)).free
    assert checker.sampled_contact(turn(0), turn(90), 1) is None
    assert checker.sampled_contact(turn(0), turn(0), 16) is None
    with pytest.raises(ValueError):
        checker.sampled_contact(turn(0), np.full((4, 4), np.nan), 16)


def test_colliding_at_the_start_has_no_safe_time():
    c = dymsum.check_motion(BOX, BOX, None, dymsum.pose(translation=[5, 0, 0]))
    assert not c.free and c.t_safe is None and c.t_contact == 0.0


def test_shorter_arc_like_ompl():
    # 350° of yaw is the 10° turn the other way: the bar does not sweep
    # through the block at 45°.
    block = cuboid([1.2, 1.2, -1], [1.4, 1.4, 1])
    checker = dymsum.MotionChecker(BAR, [block])
    assert checker.check(turn(0), turn(-10)).free
    assert checker.check(turn(0), turn(350)).free
    assert not checker.check(turn(0), turn(90)).free


def test_unions_as_body_and_obstacles():
    ell = dymsum.ConvexUnion([BOX, BOX + [1, 0, 0], BOX + [0, 1, 0]])
    assert len(ell) == 3 and len(ell.pieces) == 3
    assert isinstance(ell.pieces[0], dymsum.Polytope)
    posts = dymsum.ConvexUnion([cuboid([3, -3, -1], [3.2, -2.8, 1]), cuboid([3, 1.9, -1], [3.2, 2.1, 1])])
    p0, p1 = dymsum.pose(translation=[0, 0, 0]), dymsum.pose(translation=[6, 0, 0])
    c = dymsum.check_motion(ell, [posts, WALL], p0, p1)
    # The L's arm (y up to 1.5) misses the post at y ≥ 1.9; the wall stops it.
    assert not c.free and abs(c.t_contact - (4.999 - 1.5) / 6) <= 1e-6
    assert_agrees_with_sampling(ell.pieces, [posts.pieces[0], posts.pieces[1], WALL], p0, p1, c)
    up = dymsum.pose(translation=[6, 1.0, 0])
    c2 = dymsum.check_motion(ell, [posts], p0, up)
    assert_agrees_with_sampling(ell.pieces, posts.pieces, p0, up, c2)


@pytest.mark.parametrize("seed", range(4))
def test_random_motions_agree_with_dense_sampling(seed):
    rng = np.random.default_rng(seed)
    body = dymsum.Polytope(rng.normal(size=(12, 3)) * [1.0, 0.3, 0.3])
    obstacles = [dymsum.Polytope(rng.normal(size=(10, 3)) * 0.4 + rng.uniform(-3, 3, 3)) for _ in range(3)]
    checker = dymsum.MotionChecker(body, obstacles)
    results = {True: 0, False: 0}
    for _ in range(15):
        p0 = pose_of(Rotation.random(random_state=rng), rng.uniform(-4, 4, 3))
        p1 = pose_of(Rotation.random(random_state=rng), rng.uniform(-4, 4, 3))
        c = checker.check(p0, p1, 1e-7)
        results[c.free] += 1
        assert_agrees_with_sampling([body], obstacles, p0, p1, c, samples=1500)
    assert results[False] > 0


def test_batch_is_the_single_check_row_by_row():
    rng = np.random.default_rng(7)
    poses0 = np.stack([pose_of(Rotation.random(random_state=rng), rng.uniform(-3, 3, 3)) for _ in range(40)])
    poses1 = np.stack([pose_of(Rotation.random(random_state=rng), rng.uniform(-3, 3, 3)) for _ in range(40)])
    obstacles = [BLOCK, WALL, cuboid([-1, -1, -1], [-0.5, -0.5, 1])]
    batch = dymsum.check_motions(BAR, obstacles, poses0, poses1, tolerance=1e-5)
    assert len(batch) == 40 and batch.free.dtype == bool
    checker = dymsum.MotionChecker(BAR, obstacles)
    for k in range(40):
        c = checker.check(poses0[k], poses1[k], 1e-5)
        assert c.free == batch.free[k]
        if c.free:
            assert batch.t_safe[k] == 1.0 and np.isnan(batch.t_contact[k])
        else:
            assert batch.t_contact[k] == c.t_contact
            assert (np.isnan(batch.t_safe[k]) and c.t_safe is None) or batch.t_safe[k] == c.t_safe
    same = checker.check_many(poses0, poses1, 1e-5)
    assert np.array_equal(same.free, batch.free)
    assert not batch.free.all() and batch.free.any()
    # One pose stands for all.
    assert len(dymsum.check_motions(BAR, obstacles, None, poses1)) == 40


def test_bad_arguments_raise_value_error():
    with pytest.raises(ValueError, match="tolerance"):
        dymsum.check_motion(BOX, [WALL], None, None, tolerance=0.0)
    with pytest.raises(ValueError, match="tolerance"):
        dymsum.MotionChecker(BOX, [WALL]).check(None, None, tolerance=2.0)
    with pytest.raises(ValueError, match="obstacles\\[1\\]"):
        dymsum.check_motion(BOX, [WALL, np.zeros((2, 3))], None, None)
    with pytest.raises(ValueError, match="empty"):
        dymsum.ConvexUnion([])
    with pytest.raises(ValueError, match="single shape"):
        dymsum.ConvexUnion(BOX)
    with pytest.raises(ValueError, match="poses0 and poses1"):
        dymsum.check_motions(BOX, WALL, np.stack([np.eye(4)] * 3), np.stack([np.eye(4)] * 2))
    assert issubclass(dymsum.MotionUndecided, RuntimeError)


def test_obstacle_forms():
    # One shape, a (vertices, faces) pair, and two point clouds in a pair.
    box = dymsum.Polytope(BOX)
    end = dymsum.pose(translation=[10, 0, 0])
    wall = dymsum.Polytope(WALL)
    mesh = (wall.vertices, wall.faces)
    for obstacles in (WALL, wall, mesh, [mesh], (WALL, BLOCK), [dymsum.ConvexUnion([WALL])]):
        c = dymsum.check_motion(box, obstacles, None, end)
        assert not c.free and abs(c.t_contact - 0.4499) <= 1e-6, obstacles
    assert dymsum.check_motion(box, (BLOCK + [0, 5, 0], BLOCK - [0, 5, 0]), None, end).free


def box_triangles(lo, hi, outward=True):
    """The box ``[lo, hi]`` as 12 triangles, outward (or inward: a cavity's
    wall), its corners numbered as ``cuboid``'s."""
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    tris = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))])
    return cuboid(lo, hi), tris if outward else tris[:, ::-1].copy()


def joined(*meshes):
    vs, fs, base = [], [], 0
    for v, f in meshes:
        vs.append(v)
        fs.append(f + base)
        base += len(v)
    return np.vstack(vs), np.vstack(fs)


def test_containment_stats_count_how_points_were_decided():
    """Five specks in a box's cavity, close to one wall (one grid cell that
    meets the wall): no wall comes near their box, so the first speck's
    point, decided by a ray, decides the state (``bodies_by_region``). With
    an open sheet between two of them (which meets their box, not them),
    the first is decided by a ray, the next four by segments from the point
    before. The convex path has no such tests."""
    shell = joined(box_triangles([0] * 3, [10] * 3), box_triangles([1] * 3, [9] * 3, outward=False))
    specks = joined(*(box_triangles(lo, lo + 1e-4) for lo in (np.array([1.001, 5 + 3e-4 * i, 5.0]) for i in range(5))))
    zero = {"by_grid": 0, "by_segment": 0, "by_ray": 0, "segment_fallbacks": 0, "plane_cull_fallbacks": 0, "bodies_by_grid": 0, "bodies_by_region": 0}
    checker = dymsum.MotionChecker(specks, [shell])
    assert checker.info["path"] == "triangles"
    assert checker.containment_stats == zero
    assert not checker.collides_at(np.eye(4))
    assert checker.containment_stats == {**zero, "by_ray": 1, "bodies_by_region": 1}
    y = 5 + 3e-4 * 2.5
    sheet = (np.array([[1.0005, y, 4.5], [1.5, y, 4.5], [1.5, y, 5.5], [1.0005, y, 5.5]]), np.array([[0, 1, 2], [0, 2, 3]]))
    checker = dymsum.MotionChecker(specks, [shell, sheet])
    assert not checker.collides_at(np.eye(4))
    assert checker.containment_stats == {**zero, "by_segment": 4, "by_ray": 1}
    assert dymsum.MotionChecker(CUBE, [CUBE + 5]).containment_stats is None
