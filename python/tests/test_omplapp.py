"""dymsum.omplapp: OMPL.app's problems read as OMPL.app reads them.

The scenes are the folders of ``tests/data/omplapp`` holding a ``.cfg``:
``window`` is made by its ``make_scene.py`` in the layout of OMPL.app's
SketchUp exports (Z_UP, node matrices, ``<instance_node>``, edge
``<lines>``, double-sided faces); its expected numbers below were read with
libassimp 5.2.5, with the flags and the traversal of OMPL.app. Setting
``DYMSUM_OMPLAPP_DIR`` to a copy of OMPL.app's ``resources/3D`` adds its
problems to the path checks.

The ``.cfg``/``.path`` readers need NumPy only; reading the meshes needs
pycollada (``pip install trimesh pycollada``), the path checks python-fcl.
"""

import doctest
import math
import os
import pathlib
import sys

import numpy as np
import pytest
from conftest import need

import dymsum.omplapp as oa

DATA = pathlib.Path(__file__).resolve().parent / "data" / "omplapp"
WINDOW = DATA / "window" / "window.cfg"
SCENES = sorted(DATA.glob("*/*.cfg"))
EXTRA = sorted(pathlib.Path(os.environ["DYMSUM_OMPLAPP_DIR"]).glob("*.cfg")) if os.environ.get("DYMSUM_OMPLAPP_DIR") else []

# libassimp 5.2.5 on window_robot.dae / window_env.dae (float32): the robot
# centre OMPL.app subtracts, and the triangle counts.
ASSIMP_CENTRE = np.array([0.352499604, 0.157499984, 0.0224998482])
ROBOT_TRIANGLES, ENV_TRIANGLES = 36, 96


def collada():
    return need("collada", reason="reading .dae needs pycollada (pip install trimesh pycollada)")


def fcl():
    return need("fcl", reason="the path checks need python-fcl (pip install python-fcl)")


def test_docstring_examples():
    r = doctest.testmod(oa, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert r.failed == 0 and r.attempted >= 3


def rotation_ok(pose):
    r = pose[:3, :3]
    return np.allclose(r @ r.T, np.eye(3), atol=1e-12) and abs(np.linalg.det(r) - 1) < 1e-12 and pose[3].tolist() == [0, 0, 0, 1]


# ---------------------------------------------------------------- no mesh reader


def test_axis_angle_pose_is_ompls_set_axis_angle():
    # The axis need not be unit; the angle is in radians.
    p = oa.axis_angle_pose(1, 2, 3, (0, 0, 5), math.pi / 2)
    assert np.allclose(p, [[0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]], atol=1e-15)
    # A null axis is the identity (OMPL: norm below 1e-9).
    assert np.array_equal(oa.axis_angle_pose(0, 0, 0, (0, 0, 0), 1.0), np.eye(4))
    # theta = pi about x turns y to -y.
    assert np.allclose(oa.axis_angle_pose(0, 0, 0, (1, 0, 0), math.pi)[:3, :3], np.diag([1.0, -1.0, -1.0]), atol=1e-11)


def test_state_pose_normalises_the_quaternion():
    a = oa.state_pose(0, 0, 0, 0, 0, math.sin(0.3), math.cos(0.3))
    b = oa.state_pose(0, 0, 0, 0, 0, 2 * math.sin(0.3), 2 * math.cos(0.3))
    assert np.allclose(a, b, atol=1e-15) and rotation_ok(a)
    assert np.allclose(a[:2, :2], [[math.cos(0.6), -math.sin(0.6)], [math.sin(0.6), math.cos(0.6)]])
    with pytest.raises(ValueError):
        oa.state_pose(0, 0, 0, 0, 0, 0, 0)


def test_read_cfg():
    s = oa.read_cfg(WINDOW)
    assert s["problem.name"] == "window" and s["problem.robot"] == "window_robot.dae"
    assert float(s["benchmark.time_limit"]) == 10.0 and s["planner.rrtconnect"] == ""


def test_read_cfg_comments_and_errors(tmp_path):
    cfg = tmp_path / "a.cfg"
    cfg.write_text("[problem]\n# comment\nname = x # trailing\n\n[planner]\nrrt.range=5\nrrt.range=6\n")
    assert oa.read_cfg(cfg) == {"problem.name": "x", "planner.rrt.range": "6"}
    cfg.write_text("[problem]\nnot a setting\n")
    with pytest.raises(ValueError, match="key = value"):
        oa.read_cfg(cfg)


def test_load_path():
    path = oa.load_path(WINDOW.with_suffix(".path"))
    assert path.shape == (45, 4, 4) and path.dtype == np.float64
    assert all(rotation_ok(p) for p in path)
    # The first line is 'x y z 0 0 0 1'.
    first = WINDOW.with_suffix(".path").read_text().split("\n")[0].split()
    assert np.array_equal(path[0][:3, 3], [float(v) for v in first[:3]]) and np.array_equal(path[0][:3, :3], np.eye(3))


def test_load_path_rejects_other_rows(tmp_path):
    bad = tmp_path / "bad.path"
    bad.write_text("1 2 3 0 0 0 1\n1 2 3\n")
    with pytest.raises(ValueError, match=":2: expected 7 numbers"):
        oa.load_path(bad)
    empty = tmp_path / "empty.path"
    empty.write_text("\n")
    assert oa.load_path(empty).shape == (0, 4, 4)


# ---------------------------------------------------------------- meshes


@pytest.mark.parametrize("cfg", SCENES, ids=[c.stem for c in SCENES])
def test_problem_shapes_and_bounds(cfg):
    collada()
    p = oa.load_problem(cfg)
    for v, f in ((p.robot_vertices, p.robot_faces), (p.env_vertices, p.env_faces)):
        assert v.ndim == 2 and v.shape[1] == 3 and v.dtype == np.float64 and np.isfinite(v).all()
        assert f.ndim == 2 and f.shape[1] == 3 and f.dtype == np.int64 and len(f) > 0
        assert f.min() >= 0 and f.max() < len(v)
        assert len(np.unique(f)) == len(v)  # every vertex is used by a triangle
    low, high = p.bounds
    assert low.shape == high.shape == (3,) and (low < high).all()
    for pose in (p.start, p.goal):
        assert pose.shape == (4, 4) and pose.dtype == np.float64 and rotation_ok(pose)
        assert ((low <= pose[:3, 3]) & (pose[:3, 3] <= high)).all()
    assert p.robot_centre.shape == (3,)
    if p.path_file is not None:
        path = oa.load_path(p.path_file)
        assert ((low <= path[:, :3, 3]) & (path[:, :3, 3] <= high)).all()


def test_window_matches_assimp():
    collada()
    p = oa.load_problem(WINDOW)
    assert p.name == "window" and p.time_limit == 10.0
    assert len(p.robot_faces) == ROBOT_TRIANGLES and len(p.env_faces) == ENV_TRIANGLES
    # Each file vertex once per instance: the rod's 24 faces x 4 corners
    # (double-sided) and the knob's 24 corners; the wall's 4 slabs x 48.
    assert len(p.robot_vertices) == 72 and len(p.env_vertices) == 192
    # OMPL.app's centre: Assimp's joined vertices (edge lines included).
    assert np.allclose(p.robot_centre, ASSIMP_CENTRE, atol=2e-6)
    # The up axis, node matrices and instance nodes put the geometry where
    # make_scene.py designed it (in OMPL.app's frame).
    assert np.allclose(p.env_vertices.min(axis=0), [-5, 0, -5], atol=1e-5)
    assert np.allclose(p.env_vertices.max(axis=0), [5, 0.5, 5], atol=1e-5)
    robot = p.robot_vertices + p.robot_centre
    assert np.allclose(robot.min(axis=0), [-1.5, -0.4, -0.4], atol=1e-5)
    assert np.allclose(robot.max(axis=0), [1.5, 0.65, 0.4], atol=1e-5)
    # The window: no wall vertex strictly inside |x|, |z| < 0.575.
    inside = (np.abs(p.env_vertices[:, 0]) < 0.575 - 1e-5) & (np.abs(p.env_vertices[:, 2]) < 0.575 - 1e-5)
    assert not inside.any()
    # The shipped path runs from the start to the goal.
    path = oa.load_path(p.path_file)
    assert np.allclose(path[0], p.start, atol=1e-8) and np.allclose(path[-1], p.goal, atol=1e-8)


@pytest.mark.parametrize(
    "asset, centre",
    [  # libassimp 5.2.5's centre of window_robot.dae with its <asset> changed so
        ('<unit meter="0.5" name="half"/>\n        <up_axis>Z_UP</up_axis>', [0.176249802, 0.078749992, 0.0112499241]),
        ("<up_axis>X_UP</up_axis>", [0.0224998482, 0.352499604, 0.157499984]),
        ("<up_axis>Y_UP</up_axis>", [0.352499604, -0.0224998482, 0.157499984]),
    ],
    ids=["unit", "x_up", "y_up"],
)
def test_up_axis_and_unit_as_assimp(tmp_path, asset, centre):
    collada()
    text = (DATA / "window" / "window_robot.dae").read_text()
    changed = tmp_path / "robot.dae"
    changed.write_text(text.replace("<up_axis>Z_UP</up_axis>", asset))
    v, f, c = oa.load_mesh(changed)
    assert np.allclose(c, centre, atol=2e-6)
    v0, f0, c0 = oa.load_mesh(DATA / "window" / "window_robot.dae")
    # The same mesh, turned (and scaled) about the origin as the centre is.
    m = np.linalg.lstsq(np.c_[v0, np.ones(len(v0))], v, rcond=None)[0]
    assert np.allclose(c, np.r_[c0, 1.0] @ m, atol=2e-6) and np.array_equal(f, f0)


def test_triangles_keep_the_files_orientation():
    collada()
    v, f, _ = oa.load_mesh(DATA / "window" / "window_robot.dae")
    # The rod is written double-sided (every face twice, opposite ways),
    # the knob once, outward: the signed volume is the knob's alone.
    t = v[f]
    volume = np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6
    assert volume == pytest.approx(0.35 * 0.25 * 0.35, rel=1e-5)


def test_other_formats_through_trimesh(tmp_path):
    collada()
    trimesh = need("trimesh", reason="other mesh formats need trimesh (pip install trimesh)")
    v, f, centre = oa.load_mesh(DATA / "window" / "window_robot.dae")
    mesh = trimesh.Trimesh(v, f, process=False)
    for suffix in ("stl", "ply", "obj"):
        out = tmp_path / f"robot.{suffix}"
        mesh.export(out)
        v2, f2, c2 = oa.load_mesh(out)
        assert len(f2) == len(f)
        assert np.allclose(np.sort(v2[f2].reshape(-1, 9), axis=0), np.sort(v[f].reshape(-1, 9), axis=0), atol=1e-5)
        # libassimp 5.2.5 on these files: 72 joined vertices, this centre.
        assert np.allclose(c2, [0.39166674, 0.175000027, 0.024999762], atol=2e-6), suffix


def test_missing_reader_names_the_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "collada", None)
    with pytest.raises(ImportError, match="pip install trimesh pycollada"):
        oa.load_mesh(DATA / "window" / "window_robot.dae")


def test_missing_mesh_and_settings(tmp_path):
    cfg = tmp_path / "x.cfg"
    cfg.write_text("[problem]\nrobot = nothing.dae\nworld = nothing.dae\n")
    with pytest.raises(FileNotFoundError):
        oa.load_problem(cfg)
    cfg.write_text("[problem]\nworld = nothing.dae\n")
    with pytest.raises(ValueError, match="problem.robot"):
        oa.load_problem(cfg)


# ---------------------------------------------------------------- FCL, as OMPL.app checks


def fcl_checker(problem):
    f = fcl()

    def model(v, faces):
        m = f.BVHModel()
        m.beginModel(len(v), len(faces))
        m.addSubModel(np.ascontiguousarray(v), np.ascontiguousarray(faces))
        m.endModel()
        return m

    env = f.CollisionObject(model(problem.env_vertices, problem.env_faces), f.Transform())

    def colliding(robot_vertices, poses):
        robot = f.CollisionObject(model(robot_vertices, problem.robot_faces), f.Transform())
        hits = []
        for i, pose in enumerate(poses):
            robot.setTransform(f.Transform(pose[:3, :3], pose[:3, 3]))
            if f.collide(robot, env, f.CollisionRequest(), f.CollisionResult()) > 0:
                hits.append(i)
        return hits

    return colliding


@pytest.mark.parametrize("cfg", SCENES + EXTRA, ids=[c.stem for c in SCENES + EXTRA])
def test_shipped_path_is_free(cfg):
    collada()
    try:
        p = oa.load_problem(cfg)
    except FileNotFoundError as e:  # a partial copy of resources/3D
        if cfg in SCENES:
            raise
        pytest.skip(str(e))
    if p.path_file is None:
        pytest.skip(f"{cfg.name} ships no .path")
    colliding = fcl_checker(p)
    path = oa.load_path(p.path_file)
    assert colliding(p.robot_vertices, path) == []
    assert colliding(p.robot_vertices, [p.start]) == []


def test_window_path_needs_omplapps_centre():
    """The window's path passes 0.05 from the window's sides: centred on the
    mean of its distinct vertex positions instead, the robot hits the wall."""
    collada()
    p = oa.load_problem(WINDOW)
    colliding = fcl_checker(p)
    path = oa.load_path(p.path_file)
    world = p.robot_vertices + p.robot_centre
    naive = np.unique(world, axis=0).mean(axis=0)
    assert np.linalg.norm(naive - p.robot_centre) > 0.2
    assert len(colliding(world - naive, path)) > 5
    assert colliding(p.robot_vertices, [p.goal]) == []
