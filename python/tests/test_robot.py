"""Robots with joints from Python (issue 37): ``dymsum.Robot`` and
``dymsum.RobotChecker`` on Panda (example-robot-data's URDF, SRDF and
collision meshes, Apache-2.0, in ``data/panda``).

Oracles: python-fcl on the link meshes placed by ``Robot.forward`` (a
contact of surfaces fcl finds is never missed; fcl does not count a link
inside another); pinocchio + coal (``pin.buildGeomFromUrdf``,
``computeCollisions``) where installed; dense sampling for motions.
"""

import os
import shutil

import numpy as np
import pytest
from conftest import need

import dymsum

DATA = os.path.join(os.path.dirname(__file__), "data", "panda")


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    """A package root laid out as the URDF's ``package://`` paths expect."""
    base = tmp_path_factory.mktemp("pkg")
    meshes = base / "example-robot-data" / "robots" / "panda_description" / "meshes" / "collision"
    meshes.mkdir(parents=True)
    for name in os.listdir(DATA):
        if name.endswith(".stl"):
            shutil.copy(os.path.join(DATA, name), meshes / name)
    return base


@pytest.fixture(scope="module")
def panda(root):
    return dymsum.Robot.from_urdf(
        os.path.join(DATA, "panda.urdf"), srdf=os.path.join(DATA, "panda.srdf"), package_dirs=[root]
    )


def _random_q(rng, n, robot):
    limits = np.array(robot.joint_limits)
    return limits[:, 0] + (limits[:, 1] - limits[:, 0]) * rng.random((n, len(limits)))


def test_the_front_door(panda):
    assert panda.dof == 8
    assert panda.joint_names[:2] == ["panda_joint1", "panda_joint2"]
    assert panda.joint_limits[3] == (-3.0718, -0.0698) and panda.joint_limits[7] == (0.0, 0.04)
    assert "panda_hand" in panda.link_names
    poses = panda.forward([0, 0, 0, -1.5, 0, 1.5, 0, 0.02])
    assert poses.shape == (len(panda.link_names), 4, 4)
    assert np.allclose(poses[:, 3], [0, 0, 0, 1])
    pairs = panda.collision_pairs
    assert pairs and all(isinstance(a, str) and isinstance(b, str) for a, b in pairs)
    with pytest.raises(ValueError, match="panda_joint4"):
        panda.forward([0, 0, 0, 0.5, 0, 1.5, 0, 0.02])
    with pytest.raises(ValueError):
        panda.forward([0.0] * 7)
    with pytest.raises(ValueError, match="nowhere"):
        panda.collision_pairs = [("panda_link0", "nowhere")]


def test_configurations_against_fcl(panda):
    fcl = need("fcl")
    trimesh = need("trimesh")
    checker = dymsum.RobotChecker(panda)
    names = panda.link_names
    meshes = {}
    for link in ("link0", "link1", "link2", "link3", "link4", "link5", "link6", "link7", "hand"):
        m = trimesh.load(os.path.join(DATA, link + ".stl"), process=False, force="mesh")
        model = fcl.BVHModel()
        model.beginModel(len(m.vertices), len(m.faces))
        model.addSubModel(np.asarray(m.vertices, float), np.asarray(m.faces, np.int64))
        model.endModel()
        meshes["panda_" + link] = model
    pairs = [(a, b) for a, b in panda.collision_pairs if a in meshes and b in meshes]
    rng = np.random.default_rng(7)
    qs = _random_q(rng, 300, panda)
    found = 0
    for q in qs:
        poses = panda.forward(q)
        ours = {(a, b) for a, b in checker.colliding_pairs(q)}
        for a, b in pairs:
            pa, pb = poses[names.index(a)], poses[names.index(b)]
            oa = fcl.CollisionObject(meshes[a], fcl.Transform(pa[:3, :3], pa[:3, 3]))
            ob = fcl.CollisionObject(meshes[b], fcl.Transform(pb[:3, :3], pb[:3, 3]))
            if fcl.collide(oa, ob, fcl.CollisionRequest(), fcl.CollisionResult()) > 0:
                found += 1
                assert (a, b) in ours or (b, a) in ours, (q, a, b)
        assert checker.collides_at(q) == bool(ours)
    assert found > 5
    many = checker.collides_many(qs[:40])
    assert list(many) == [checker.collides_at(q) for q in qs[:40]]
    # Any array-like, any layout: lists, Fortran order, a strided view.
    assert list(checker.collides_many(qs[:40].tolist())) == list(many)
    assert list(checker.collides_many(np.asfortranarray(qs[:40]))) == list(many)
    assert list(checker.collides_many(qs[:80:2])) == [checker.collides_at(q) for q in qs[:80:2]]
    with pytest.raises(ValueError, match=r"\(K, 8\)"):
        checker.collides_many(qs[:4, :7])


def test_against_pinocchio_and_coal(root, panda):
    if os.environ.get("DYMSUM_REQUIRE_PINOCCHIO") == "1":
        import pinocchio as pin
    else:
        pin = pytest.importorskip("pinocchio")
    urdf = os.path.join(DATA, "panda.urdf")
    model = pin.buildModelFromUrdf(urdf)
    geom = pin.buildGeomFromUrdf(model, urdf, pin.GeometryType.COLLISION, package_dirs=[str(root)])
    geom.addAllCollisionPairs()
    pin.removeCollisionPairs(model, geom, os.path.join(DATA, "panda.srdf"))
    data, gdata = model.createData(), pin.GeometryData(geom)
    checker = dymsum.RobotChecker(panda)
    ours_pairs = {frozenset(p) for p in panda.collision_pairs}
    rng = np.random.default_rng(3)
    found = 0
    for q in _random_q(rng, 200, panda):
        pq = np.concatenate([q, [q[7]]])[: model.nq]  # the mimic finger, when pinocchio has it
        pin.computeCollisions(model, data, geom, gdata, pq, False)
        ours = {frozenset((a, b)) for a, b in checker.colliding_pairs(q)}
        for k, cp in enumerate(geom.collisionPairs):
            if not gdata.collisionResults[k].isCollision():
                continue
            a = model.frames[geom.geometryObjects[cp.first].parentFrame].name
            b = model.frames[geom.geometryObjects[cp.second].parentFrame].name
            if frozenset((a, b)) in ours_pairs:
                found += 1
                # No contact coal finds is missed (our spheres and
                # cylinders contain coal's exact ones).
                assert frozenset((a, b)) in ours, (q, a, b)
    assert found > 0


def test_sampled_contact_refutes_only_with_a_colliding_sample(panda):
    """``RobotChecker.sampled_contact``: the first colliding sample in
    bisection order (exact), ``None`` when no sample collides; every ``t``
    it gives is a colliding configuration."""
    corners = np.array([[x, y, z] for x in (0.37, 0.53) for y in (-0.3, 0.3) for z in (0.0, 0.8)], float)
    checker = dymsum.RobotChecker(panda, [corners])
    rng = np.random.default_rng(2)
    hits = misses = 0
    while hits < 10 or misses < 10:
        q0, q1 = _random_q(rng, 2, panda)
        t = checker.sampled_contact(q0, q1, 16)
        if t is None:
            misses += 1
            for k in (8, 4, 12, 2, 6, 10, 14):
                assert not checker.collides_at(q0 + k / 16 * (q1 - q0))
        else:
            hits += 1
            assert t * 16 == round(t * 16) and 0 < t < 1
            assert checker.collides_at(np.clip(q0 + t * (q1 - q0), np.minimum(q0, q1), np.maximum(q0, q1)))
    assert checker.sampled_contact(q0, q0, 16) is None and checker.sampled_contact(q0, q1, 1) is None
    with pytest.raises(ValueError, match="outside its limits"):
        checker.sampled_contact(q0 + 10.0, q1, 16)


def test_motions_against_dense_sampling(panda):
    corners = np.array([[x, y, z] for x in (0.37, 0.53) for y in (-0.3, 0.3) for z in (0.0, 0.8)], float)
    checker = dymsum.RobotChecker(panda, [corners])
    rng = np.random.default_rng(11)
    free = hit = 0
    while free + hit < 12:
        q0 = _random_q(rng, 1, panda)[0]
        if checker.collides_at(q0):
            continue
        q1 = q0 + 0.25 * (_random_q(rng, 1, panda)[0] - q0)
        try:
            c = checker.check(q0, q1)
        except dymsum.MotionUndecided:
            continue
        at = lambda t: np.clip(q0 + t * (q1 - q0), np.minimum(q0, q1), np.maximum(q0, q1))  # noqa: E731
        if c.free:
            free += 1
            assert not any(checker.collides_at(at(t)) for t in np.linspace(0, 1, 101))
        else:
            hit += 1
            assert checker.collides_at(at(c.t_contact))
            assert c.t_contact - c.t_safe <= 1e-6
    assert free and hit


def test_planning_in_joint_space_with_ompl(panda):
    """RRTConnect plans Panda around a block with dymsum's joint-space
    validators; every motion of the path found is certified free."""
    if os.environ.get("DYMSUM_REQUIRE_OMPL") == "1":
        from ompl import base as ob
    else:
        ob = pytest.importorskip("ompl.base")
    from ompl import geometric as og

    import dymsum.ompl as dom

    block = np.array([[x, y, z] for x in (0.35, 0.45) for y in (-0.15, 0.15) for z in (0.0, 0.9)], float)
    checker = dymsum.RobotChecker(panda, [block])
    space = ob.RealVectorStateSpace(8)
    bounds = ob.RealVectorBounds(8)
    for i, (lo, hi) in enumerate(panda.joint_limits):
        bounds.setLow(i, lo)
        bounds.setHigh(i, hi)
    space.setBounds(bounds)
    ss = og.SimpleSetup(space)
    v = dom.setup_joint_validators(ss, checker)
    start, goal = space.allocState(), space.allocState()
    # Reaching to one side of the block, then to the other.
    for st, q in ((start, [0.9, 0.3, 0, -1.8, 0, 2.1, 0.8, 0.02]), (goal, [-0.9, 0.3, 0, -1.8, 0, 2.1, 0.8, 0.02])):
        for i, x in enumerate(q):
            st[i] = x
        assert v.state_checker(st)
    # The straight motion between them passes through the block.
    assert not checker.check(v.state_checker.q(start), v.state_checker.q(goal)).free
    ss.setStartAndGoalStates(start, goal)
    ss.setPlanner(og.RRTConnect(ss.getSpaceInformation()))
    assert ss.solve(20.0) and ss.haveExactSolutionPath()
    states = ss.getSolutionPath().getStates()
    qs = [v.state_checker.q(s) for s in states]
    assert all(checker.check(a, b).free for a, b in zip(qs, qs[1:]))
    assert v.motion_validator.checked > 0 and "JointMotionValidator" in repr(v.motion_validator)
    assert 0 <= v.motion_validator.sampled <= v.motion_validator.rejected
    with pytest.raises(ValueError, match="degrees of freedom"):
        dom.setup_joint_validators(ob.SpaceInformation(ob.RealVectorStateSpace(3)), checker)


def _shelves():
    """python/examples/robot_shelves.py as a module."""
    import importlib.util
    import pathlib

    path = pathlib.Path(__file__).parent.parent / "examples" / "robot_shelves.py"
    spec = importlib.util.spec_from_file_location("robot_shelves", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.parametrize("robot_name", ["panda", "ur5"])
def test_near_contact_configurations_against_pinocchio_and_coal(root, robot_name):
    """Both arms among the table and the shelf, 600 random configurations
    and 1,200 within 1e-9 (in joint space) of contact, found by bisecting
    between a free and a colliding one: no contact coal finds (link
    against link, or link against a box) is missed, beyond what coal's own
    distance can tell (a contact it reports within 1e-9 m of touching, by
    its own distance, is counted, not a failure)."""
    if os.environ.get("DYMSUM_REQUIRE_PINOCCHIO") == "1":
        import pinocchio as pin
    else:
        pin = pytest.importorskip("pinocchio")
    import coal

    mod = _shelves()
    if robot_name == "panda":
        urdf, srdf, package = os.path.join(DATA, "panda.urdf"), os.path.join(DATA, "panda.srdf"), str(root)
    else:
        ur = os.path.join(mod.SHARE, "example-robot-data", "robots", "ur_description")
        if not os.path.isdir(ur):
            assert os.environ.get("DYMSUM_REQUIRE_PINOCCHIO") != "1", "example-robot-data is not installed"
            pytest.skip("example-robot-data is not installed")
        urdf, srdf, package = os.path.join(ur, "urdf", "ur5_robot.urdf"), os.path.join(ur, "srdf", "ur5.srdf"), mod.SHARE
    robot, checker, _, _ = mod.problem(robot_name)
    model = pin.buildModelFromUrdf(urdf)
    geom = pin.buildGeomFromUrdf(model, urdf, pin.GeometryType.COLLISION, package_dirs=[package])
    geom.addAllCollisionPairs()
    pin.removeCollisionPairs(model, geom, srdf)
    links = range(geom.ngeoms)
    for k, corners in enumerate(mod.scene()):
        lo, hi = corners.min(axis=0), corners.max(axis=0)
        box = pin.GeometryObject(f"box{k}", 0, 0, pin.SE3(np.eye(3), (lo + hi) / 2), coal.Box(*(hi - lo)))
        o = geom.addGeometryObject(box)
        for g in links:
            if geom.geometryObjects[g].parentJoint != 0:
                geom.addCollisionPair(pin.CollisionPair(g, o))
    data, gdata = model.createData(), pin.GeometryData(geom)
    names = list(robot.joint_names)
    # Pinocchio's configuration: a mimic joint is an independent one there
    # (Panda's second finger follows the first).
    index = [names.index(n) if n in names else names.index("panda_finger_joint1") for n in model.names[1:]]
    checked = {frozenset(p) for p in robot.collision_pairs}
    rng = np.random.default_rng(17)
    configurations = list(_random_q(rng, 600, robot))
    while len(configurations) < 1800:
        q0, q1 = _random_q(rng, 2, robot)
        if checker.collides_at(q0) or not checker.collides_at(q1):
            continue
        a, b = 0.0, 1.0
        while b - a > 1e-9:
            t = 0.5 * (a + b)
            if checker.collides_at(q0 + t * (q1 - q0)):
                b = t
            else:
                a = t
        configurations += [q0 + a * (q1 - q0), q0 + b * (q1 - q0)]
    found = settled = 0

    def frame(g):
        obj = geom.geometryObjects[g]
        return None if obj.parentJoint == 0 else model.frames[obj.parentFrame].name

    for q in configurations:
        ours = {frozenset(p) for p in checker.colliding_pairs(q)}
        pin.computeCollisions(model, data, geom, gdata, np.asarray(q)[index], False)
        for k, cp in enumerate(geom.collisionPairs):
            if not gdata.collisionResults[k].isCollision():
                continue
            a, b = frame(cp.first), frame(cp.second)
            if a == b or (b is not None and frozenset((a, b)) not in checked):
                continue
            pair = frozenset((a, b)) if b is not None else frozenset((a, None))
            found += 1
            if pair not in ours:
                # coal's collide() reports contacts within its own margin
                # (its distance then says apart, up to 4e-10 here) and its
                # EPA depths are floats: a disagreement within 1e-9 m of
                # touching by coal's own distance is within what coal can
                # tell, counted apart; anything deeper fails.
                d = pin.computeDistance(geom, gdata, k).min_distance
                assert d > -1e-9, (robot_name, list(q), a, b, d)
                settled += 1
    assert found > 300 and settled <= found // 10, (found, settled)


@pytest.mark.parametrize("robot_name", ["panda", "ur5"])
def test_long_motions_among_shelves_against_dense_sampling(robot_name):
    """Motions as a planner asks them (anywhere in the joint limits, up to
    the whole range), among the table and the shelf: a motion certified
    free has no colliding state among 1,500 evenly spaced ones (including
    the moments its links pass closest, which the separating planes of
    ``robot::motion`` certify over long stretches), and a contact
    bracketed is a contact, with no contact sampled before it."""
    mod = _shelves()
    if robot_name == "ur5" and not os.path.isdir(os.path.join(mod.SHARE, "example-robot-data")):
        assert os.environ.get("DYMSUM_REQUIRE_PINOCCHIO") != "1", "example-robot-data is not installed"
        pytest.skip("example-robot-data is not installed")
    robot, checker, _, _ = mod.problem(robot_name)
    rng = np.random.default_rng(5)
    limits = np.array(robot.joint_limits)
    free = hit = 0
    ts = np.linspace(0.0, 1.0, 1501)
    while free + hit < 40:
        q0, q1 = _random_q(rng, 2, robot)
        if checker.collides_at(q0):
            continue
        q1 = q0 + rng.choice([0.05, 0.3, 1.0]) * (q1 - q0)
        try:
            c = checker.check(q0, q1, 1e-3)
        except dymsum.MotionUndecided:
            continue
        states = np.clip(q0 + ts[:, None] * (q1 - q0), np.minimum(q0, q1), np.maximum(q0, q1))
        states = np.clip(states, limits[:, 0], limits[:, 1])
        hits = checker.collides_many(states)
        if c.free:
            free += 1
            assert not hits.any(), (q0.tolist(), q1.tolist(), ts[hits.argmax()])
        else:
            hit += 1
            at = np.clip(q0 + c.t_contact * (q1 - q0), np.minimum(q0, q1), np.maximum(q0, q1))
            assert checker.collides_at(at)
            assert not hits[ts <= c.t_safe].any()
            assert c.t_contact - c.t_safe <= 1e-3
    assert free >= 5 and hit >= 5, (free, hit)


@pytest.mark.parametrize("robot_name", ["panda", "ur5"])
def test_the_shelves_example_plans_and_certifies(robot_name):
    """python/examples/robot_shelves.py: Panda and UR5 (example-robot-data's,
    Collada meshes) into the middle compartment of a shelf on a table, with
    RRTConnect and dymsum's validators, every motion of the path certified."""
    if os.environ.get("DYMSUM_REQUIRE_OMPL") != "1":
        pytest.importorskip("ompl.base")
    mod = _shelves()
    if robot_name == "ur5" and not os.path.isdir(os.path.join(mod.SHARE, "example-robot-data")):
        assert os.environ.get("DYMSUM_REQUIRE_PINOCCHIO") != "1", "example-robot-data is not installed"
        pytest.skip("example-robot-data is not installed")
    r = mod.plan(seconds=30.0, seed=1, robot_name=robot_name)
    assert r["found"] and r["path_certified"], r
    assert 0 < r["motions_certified"] <= r["motions_checked"]
