"""Bodies as they come (issue 28): meshes of any topology in
``MotionChecker``, ``check_motion(s)`` and ``collides_many``.

Oracles: python-fcl's BVH mesh-mesh ``collide`` (FCL's surface
semantics; every disagreement settled by dymsum's exact surface test,
``_dymsum._surfaces_touch``, whose own oracle is the brute force in the Rust
tests, and a contact only dymsum finds must be a body inside a solid);
dense sampling for motions; known answers for open and double-sided
meshes.
"""

import numpy as np
import pytest
from conftest import need

import dymsum
from dymsum import _dymsum

trimesh = need("trimesh")


def _box(lo, hi):
    m = trimesh.creation.box(bounds=[lo, hi])
    return np.asarray(m.vertices, float), np.asarray(m.faces, np.int64)


def _double_sided(v, f):
    return v, np.vstack([f, f[:, ::-1]])


def _open_box(lo, hi):
    v, f = _box(lo, hi)
    centres = v[f].mean(axis=1)
    return v, f[centres[:, 2] < hi[2]]


def _t(x, y, z):
    return dymsum.pose(translation=[x, y, z])


def test_open_and_double_sided_meshes_are_taken_as_they_come():
    robot = _double_sided(*_box([-0.5] * 3, [0.5] * 3))
    room = _open_box([0, 0, 0], [10, 10, 10])
    c = dymsum.MotionChecker(robot, [room])
    info = c.info
    assert info["path"] == "triangles"
    assert info["body"]["dropped_back_to_back"] == 12
    assert (info["body"]["solids"], info["obstacles"]["surfaces"]) == (1, 1)
    assert not c.collides_at(_t(5, 5, 5))
    assert c.collides_at(_t(5, 5, 0.5))  # on the floor, exactly
    assert not c.collides_at(_t(5, 5, 0.5 + 1e-12))
    assert c.check(_t(5, 5, 5), _t(5, 5, 30)).free  # out through the top
    side = c.check(_t(5, 5, 5), _t(30, 5, 5))
    assert not side.free and side.t_contact - side.t_safe <= 1e-6
    assert abs(side.t_contact - 4.5 / 25) <= 1e-6
    # Clearance: 4.5 from the floor (and walls) at the centre, 0 in contact.
    assert c.distance_at(_t(5, 5, 5)) == pytest.approx(4.5, rel=1e-12)
    assert c.distance_at(_t(5, 5, 0.5)) == 0.0
    assert c.distance_at(_t(5, 5, 2)) == pytest.approx(1.5, rel=1e-12)
    # A solid scene: inside it is a contact.
    solid = dymsum.MotionChecker(robot, [_double_sided(*_box([0, 0, 0], [10, 10, 10]))])
    assert solid.collides_at(_t(5, 5, 5))
    assert not solid.collides_at(_t(-1, 5, 5))


def test_convex_meshes_keep_the_convex_path():
    cube = _box([-0.5] * 3, [0.5] * 3)
    c = dymsum.MotionChecker(cube, [_box([2, -1, -1], [3, 1, 1])])
    assert c.info == {"path": "convex"}
    assert c.distance_at(_t(0, 0, 0)) == pytest.approx(1.5, rel=1e-12)
    assert c.collides_at(_t(1.5, 0, 0)) and not c.collides_at(_t(1.4, 0, 0))
    poses = np.stack([_t(x, 0, 0) for x in np.linspace(0, 3, 31)])
    assert c.collides_many(poses).tolist() == [c.collides_at(p) for p in poses]


def test_files_trimesh_objects_and_the_functions(tmp_path):
    room = trimesh.Trimesh(*_open_box([0, 0, 0], [10, 10, 10]), process=False)
    path = tmp_path / "room.stl"
    room.export(path)  # STL: unwelded triangles
    robot = trimesh.creation.icosphere(subdivisions=2, radius=0.5)
    for obstacle in (room, str(path), path):
        c = dymsum.MotionChecker(robot, obstacle)
        assert not c.collides_at(_t(5, 5, 5)) and c.collides_at(_t(5, 5, 0.4))
    assert dymsum.MotionChecker(robot, str(path)).info["obstacles"]["triangles"] == 10
    free = dymsum.check_motion(robot, [room], _t(5, 5, 5), _t(5, 5, 40))
    assert free.free
    ends = np.stack([_t(5, 5, 40), _t(40, 5, 5)])
    assert dymsum.check_motions(robot, [room], _t(5, 5, 5), ends).free.tolist() == [True, False]


def _random_soup(rng, n, spread):
    """n random triangles of size about 1 with corners on a grid of step
    1/4 and centres within ``spread`` (an open, non-manifold soup; shared
    coordinates and coplanar triangles common)."""
    centres = rng.integers(-spread, spread + 1, size=(n, 1, 3))
    corners = rng.integers(-2, 3, size=(n, 3, 3)) / 4
    v = (centres + corners).reshape(-1, 3).astype(float)
    f = np.arange(3 * n).reshape(n, 3)
    # Flat triangles (collinear corners, exact here: small integers over
    # 4) are dropped by the cleaning, so the referee must not see them.
    t = v[f]
    return v, f[np.abs(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])).sum(axis=1) > 0]


def test_collides_many_is_collides_at_on_random_soups():
    rng = np.random.default_rng(7)
    body = _random_soup(rng, 8, 1)
    scene = _random_soup(rng, 60, 4)
    c = dymsum.MotionChecker(body, [scene])
    from scipy.spatial.transform import Rotation

    rots = Rotation.random(300, random_state=3)
    poses = np.stack([dymsum.pose(r, rng.uniform(-3, 3, 3)) for r in rots])
    hits = c.collides_many(poses)
    assert hits.dtype == bool and hits.shape == (300,)
    assert hits.tolist() == [c.collides_at(p) for p in poses]
    # Surfaces only: contact is exactly the surface test.
    assert hits.tolist() == [_dymsum._surfaces_touch(body, p, scene, None) for p in poses]
    assert 0.05 < hits.mean() < 0.95


def test_motions_on_soups_are_never_free_through_a_contact():
    rng = np.random.default_rng(11)
    body = _random_soup(rng, 5, 1)
    scene = _random_soup(rng, 30, 5)
    c = dymsum.MotionChecker(body, [scene], budget=100_000)
    from scipy.spatial.transform import Rotation, Slerp

    frees = 0
    for k in range(40):
        r = Rotation.random(2, random_state=k)
        t = rng.uniform(-3, 3, (2, 3))
        p0, p1 = dymsum.pose(r[0], t[0]), dymsum.pose(r[1], t[1])
        if c.collides_at(p0):
            continue
        try:
            out = c.check(p0, p1)
        except dymsum.MotionUndecided:
            continue
        if out.free:
            frees += 1
            slerp = Slerp([0, 1], r)
            for s in np.linspace(0, 1, 301):
                p = dymsum.pose(slerp([s])[0], (1 - s) * t[0] + s * t[1])
                assert not c.collides_at(p), (k, s)
        else:
            assert out.t_contact - out.t_safe <= 1e-6
    assert frees > 0


def _near_contact(checker, poses, translation, steps):
    """States near contact: from each free pose towards a colliding one
    with the same rotation (its translation drawn by ``translation()``),
    bisected ``steps`` times on the translation; both ends kept."""
    near = []
    for free in poses:
        if checker.collides_at(free):
            continue
        hit = free.copy()
        hit[:3, 3] = translation()
        if not checker.collides_at(hit):
            continue
        for _ in range(steps):
            mid = free.copy()
            mid[:3, 3] = (free[:3, 3] + hit[:3, 3]) / 2
            if checker.collides_at(mid):
                hit = mid
            else:
                free = mid
        near += [free, hit]
    return near


def _fcl_model(fcl_mod, v, f):
    m = fcl_mod.BVHModel()
    m.beginModel(len(v), len(f))
    m.addSubModel(np.asarray(v, float), np.asarray(f, np.int32))
    m.endModel()
    return m


def test_agrees_with_fcl_on_random_and_near_contact_states():
    """Every state, random or within 2^-30 of contact, against python-fcl.

    The robot (two overlapping boxes, each a solid) is longer than any
    box of the scene is wide, so it can never lie inside one: here
    dymsum's contact is exactly the surface test, and every disagreement
    with fcl (which rounds) must be a pair the exact surface test decides
    dymsum's way.
    """
    fcl_mod = need("fcl")
    from scipy.spatial.transform import Rotation

    rng = np.random.default_rng(5)
    l1, l2 = _box([0, 0, 0], [2, 0.5, 0.5]), _box([0, 0, 0], [0.5, 2, 0.5])
    rv = np.vstack([l1[0], l2[0]]) - [0.6, 0.6, 0.25]
    rf = np.vstack([l1[1], l2[1] + len(l1[0])])
    parts = [_open_box([-6, -6, -1], [6, 6, 4])]
    for _ in range(6):
        c = rng.uniform(-4, 4, 3) * [1, 1, 0.3] + [0, 0, 1.5]
        parts.append(_double_sided(*_box(c - 0.6, c + 0.6)))
    offsets = np.cumsum([0] + [len(p[0]) for p in parts[:-1]])
    sv = np.vstack([p[0] for p in parts])
    sf = np.vstack([p[1] + o for p, o in zip(parts, offsets)])
    checker = dymsum.MotionChecker((rv, rf), [(sv, sf)])
    assert checker.info["path"] == "triangles"
    rm, sm = _fcl_model(fcl_mod, rv, rf), _fcl_model(fcl_mod, sv, sf)
    scene_obj = fcl_mod.CollisionObject(sm, fcl_mod.Transform())

    def fcl_hit(p):
        robot_obj = fcl_mod.CollisionObject(rm, fcl_mod.Transform(p[:3, :3], p[:3, 3]))
        req, res = fcl_mod.CollisionRequest(), fcl_mod.CollisionResult()
        return fcl_mod.collide(robot_obj, scene_obj, req, res) > 0

    rots = Rotation.random(400, random_state=1)
    poses = [dymsum.pose(r, rng.uniform([-5, -5, -0.5], [5, 5, 3.5])) for r in rots]
    # Near contact: bisect the translation from a free pose towards a
    # colliding one (the rotation kept) down to 2^-30.
    near = _near_contact(checker, poses[:80], lambda: rng.uniform([-5, -5, -0.5], [5, 5, 3.5]), 30)
    assert len(near) >= 20
    poses += near
    ours = checker.collides_many(np.stack(poses))
    disagree = 0
    for p, mine in zip(poses, ours):
        if mine == fcl_hit(p):
            continue
        disagree += 1
        assert mine == _dymsum._surfaces_touch((rv, rf), p, (sv, sf), None)
    assert 0.05 < ours.mean() < 0.95
    assert disagree <= len(near) // 4


def test_the_window_scene_against_fcl():
    """The shipped OMPL.app-style scene (python/tests/data/omplapp/window,
    double-sided SketchUp COLLADA as OMPL.app's problems come): random and
    near-contact states against python-fcl. A contact fcl finds is never
    missed; a contact only dymsum finds is one where the surfaces do not
    touch exactly and the robot lies inside a solid, which the test checks
    by moving it: along each axis, both ways, out of the scene's box, the
    robot's triangles meet the scene's somewhere (it crosses the solid's
    boundary; sampled finer than the robot is small)."""
    fcl_mod = need("fcl")
    need("collada")
    import pathlib

    from scipy.spatial.transform import Rotation

    from dymsum import omplapp

    cfg = pathlib.Path(__file__).resolve().parent / "data" / "omplapp" / "window" / "window.cfg"
    p = omplapp.load_problem(cfg)
    robot, env = (p.robot_vertices, p.robot_faces), (p.env_vertices, p.env_faces)
    checker = dymsum.MotionChecker(robot, [env])
    assert checker.info["path"] == "triangles"
    rm, em = _fcl_model(fcl_mod, *robot), _fcl_model(fcl_mod, *env)
    env_obj = fcl_mod.CollisionObject(em, fcl_mod.Transform())

    def fcl_hit(q):
        robot_obj = fcl_mod.CollisionObject(rm, fcl_mod.Transform(q[:3, :3], q[:3, 3]))
        return fcl_mod.collide(robot_obj, env_obj, fcl_mod.CollisionRequest(), fcl_mod.CollisionResult()) > 0

    rng = np.random.default_rng(2)
    lo, hi = np.asarray(p.bounds[0], float), np.asarray(p.bounds[1], float)
    poses = [dymsum.pose(r, rng.uniform(lo, hi)) for r in Rotation.random(1500, random_state=4)]
    near = _near_contact(checker, poses[:200], lambda: rng.uniform(lo, hi), 40)
    assert len(near) >= 40
    poses += near
    ours = checker.collides_many(np.stack(poses))
    only_ours = 0
    for q, mine in zip(poses, ours):
        theirs = fcl_hit(q)
        if mine == theirs:
            continue
        surfaces = _dymsum._surfaces_touch(robot, q, env, None)
        if theirs:
            # fcl's float contact: the exact test says apart, by rounding.
            assert not surfaces and not mine
            continue
        if surfaces:
            continue  # fcl missed an exact touch (a near-contact pose)
        only_ours += 1
        span = 2 * (hi - lo).max()
        for d in np.vstack([np.eye(3), -np.eye(3)]):
            crossed = False
            for s in np.linspace(0, 1, 2001):
                out = q.copy()
                out[:3, 3] = q[:3, 3] + d * span * s
                if _dymsum._surfaces_touch(robot, out, env, None):
                    crossed = True
                    break
            assert crossed, (q, d)
    assert 0.05 < ours.mean() < 0.95
    assert only_ours <= len(poses) // 20
