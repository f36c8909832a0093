"""The example ``examples/ompl_app.py`` plans the ``window`` test scene
(``tests/data/omplapp/window``) with dymsum's validators; the path it
returns is checked independently: every state free under python-fcl (as
OMPL.app checks states) and every motion certified free by
``MotionChecker.check``.

OMPL is installed by ``scripts/test.sh``, which sets
``DYMSUM_REQUIRE_OMPL=1``: there a missing OMPL fails these tests;
elsewhere they are skipped. pycollada and python-fcl: ``conftest.need``.
"""

import importlib.util
import os
import pathlib

import pytest
from conftest import need

import dymsum
import dymsum.omplapp

if os.environ.get("DYMSUM_REQUIRE_OMPL") == "1":
    import ompl.base  # noqa: F401  (fail, not skip, where OMPL is required)
else:
    pytest.importorskip("ompl.base", reason="OMPL is not installed (pip install ompl); scripts/test.sh installs it")

HERE = pathlib.Path(__file__).resolve().parent
WINDOW = HERE / "data" / "omplapp" / "window" / "window.cfg"
EXAMPLE = HERE.parent / "examples" / "ompl_app.py"


def example():
    spec = importlib.util.spec_from_file_location("ompl_app", EXAMPLE)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_ompl_app_example_plans_the_window_scene(capsys):
    need("collada", reason="reading .dae needs pycollada (pip install trimesh pycollada)")
    fcl = need("fcl", reason="the path check needs python-fcl (pip install python-fcl)")
    mod = example()
    results = mod.main([str(WINDOW), "--checker", "dymsum", "--time", "10", "--runs", "2"])
    out = capsys.readouterr().out
    assert "window:" in out and "solved 2 of 2" in out, out
    assert len(results) == 2

    problem = dymsum.omplapp.load_problem(WINDOW)
    robot = mod.fcl_object(problem.robot_vertices, problem.robot_faces)
    env = mod.fcl_object(problem.env_vertices, problem.env_faces)
    checker = dymsum.MotionChecker((problem.robot_vertices, problem.robot_faces), [(problem.env_vertices, problem.env_faces)])
    low, high = problem.bounds
    for r in results:
        assert r["solved"] and r["time"] < 10.0 and r["length"] > 0.0
        assert r["motion_checks"] >= r["certified"] >= len(r["path"]) - 1 > 0
        path = r["path"]
        assert path.shape[1:] == (4, 4) and len(path) >= 2
        assert abs(path[0] - problem.start).max() < 1e-9 and abs(path[-1] - problem.goal).max() < 1e-9
        for pose in path:
            assert (pose[:3, 3] >= low).all() and (pose[:3, 3] <= high).all()
            robot.setTransform(fcl.Transform(pose[:3, :3], pose[:3, 3]))
            assert fcl.collide(robot, env, fcl.CollisionRequest(), fcl.CollisionResult()) == 0
        for a, b in zip(path, path[1:]):
            assert checker.check(a, b, tolerance=1e-6).free


def test_ompl_app_example_with_fcl(capsys):
    need("collada", reason="reading .dae needs pycollada (pip install trimesh pycollada)")
    need("fcl", reason="--checker fcl needs python-fcl (pip install python-fcl)")
    (r,) = example().main([str(WINDOW), "--checker", "fcl", "--time", "10"])
    assert r["solved"] and r["certified"] is None and r["state_checks"] > r["motion_checks"] > 0
    assert "run 1: solved" in capsys.readouterr().out
