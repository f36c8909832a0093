"""One convention everywhere (issue 19): every argument that takes a
rotation or a pose accepts a scipy ``Rotation``, a 3×3 matrix, an
``(x, y, z, w)`` quaternion and (for poses) a 4×4 transform, all meaning the
same turn; every shape argument also takes a model name or a path; scipy is
never imported by dymsum itself."""

import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest
from conftest import CUBE
from scipy.spatial.transform import Rotation

import dymsum

TURN = Rotation.from_rotvec([0.3, -0.2, 0.9])


class DuckRotation:
    """Not scipy, but quacks like its Rotation (as_quat scalar last)."""

    def __init__(self, r):
        self.r = r

    def as_quat(self):
        return self.r.as_quat()

    def as_matrix(self):
        return self.r.as_matrix()


def rotation_forms(r):
    """The same rotation in every accepted form (name -> value)."""
    h = np.eye(4)
    h[:3, :3] = r.as_matrix()
    return {
        "scipy Rotation": r,
        "duck-typed Rotation": DuckRotation(r),
        "3×3 matrix": r.as_matrix(),
        "3×3 nested list": r.as_matrix().tolist(),
        "(x, y, z, w) quaternion": r.as_quat(),
        "4×4 homogeneous": h,
    }


def close_meshes(x, y, tol=1e-12):
    """The same sum: identical when tol is 0; else the same vertices within
    tol (a rotation from a matrix and from a quaternion differ by an ulp,
    and rounding may then triangulate a bent face the other way)."""
    (v1, f1), (v2, f2) = x, y
    if tol == 0:
        return np.array_equal(v1, v2) and np.array_equal(f1, f2)
    if v1.shape != v2.shape:
        return False
    d = np.abs(v1[:, None, :] - v2[None, :, :]).max(axis=2)
    return d.min(axis=1).max() <= tol and d.min(axis=0).max() <= tol


def test_every_pose_argument_takes_every_rotation_form():
    a, b = dymsum.load("gs1"), dymsum.load("dd")
    ref_sum = dymsum.minkowski_sum(a, b, pose_a=dymsum.pose(TURN.as_quat()))
    ref_contact = dymsum.contact(a, b, dymsum.pose(TURN.as_quat()), dymsum.pose(translation=[0.8, 0, 0]))
    for name, form in rotation_forms(TURN).items():
        assert close_meshes(dymsum.minkowski_sum(a, b, pose_a=form), ref_sum), name
        assert close_meshes(dymsum.minkowski_sum(a, b, pose_b=form), dymsum.minkowski_sum(a, b, pose_b=ref_pose())), name
        assert close_meshes(dymsum.DynamicSum(a, b, pose_a=form).mesh(), ref_sum), name
        s = dymsum.DynamicSum(a, b)
        s.update(form)
        assert close_meshes(s.mesh(), ref_sum), name
        c = dymsum.contact(a, b, form, dymsum.pose(translation=[0.8, 0, 0]))
        assert abs(c.depth - ref_contact.depth) < 1e-12 and np.allclose(c.normal, ref_contact.normal, atol=1e-12), name
        t = dymsum.ContactTracker(a, b, form, dymsum.pose(translation=[0.8, 0, 0]))
        assert abs(t.last.depth - ref_contact.depth) < 1e-12, name
        t = dymsum.ContactTracker(a, b, None, dymsum.pose(translation=[0.8, 0, 0]))
        assert abs(t.update(form).depth - ref_contact.depth) < 1e-12, name
        if name != "4×4 homogeneous":
            assert np.allclose(dymsum.pose(form, [1, 2, 3])[:3, :3], TURN.as_matrix(), atol=1e-14), name
            assert dymsum.pose(form, [1, 2, 3])[:3, 3].tolist() == [1.0, 2.0, 3.0]


def ref_pose():
    return dymsum.pose(TURN.as_quat())


def test_quaternions_are_scalar_last_as_scipy():
    # [1, 0, 0, 0] is (x, y, z, w): a half turn about x, as scipy reads it.
    q = [1.0, 0, 0, 0]
    assert np.allclose(dymsum.pose(q)[:3, :3], Rotation.from_quat(q).as_matrix(), atol=1e-15)
    assert np.allclose(dymsum.pose(q)[:3, :3], np.diag([1.0, -1, -1]), atol=1e-15)


def test_cobstacle_slices_take_every_rotations_form():
    turns = Rotation.from_rotvec(np.outer(np.linspace(0, 1, 5), [0.2, 0.1, 1.0]))
    h = np.tile(np.eye(4), (5, 1, 1))
    h[:, :3, :3] = turns.as_matrix()
    ref = dymsum.cobstacle_slices(CUBE, "box:2,1,1", turns.as_quat())
    forms = {
        "Rotation stack": turns,
        "duck-typed stack": DuckRotation(turns),
        "(K, 3, 3)": turns.as_matrix(),
        "(K, 4, 4)": h,
    }
    for name, form in forms.items():
        got = dymsum.cobstacle_slices(CUBE, "box:2,1,1", form)
        assert len(got) == 5 and all(close_meshes(x, y) for x, y in zip(got, ref)), name
    one = dymsum.cobstacle_slices(CUBE, "box:2,1,1", turns[2].as_quat())
    for name, form in {"Rotation": turns[2], "3×3": turns[2].as_matrix(), "(4,)": turns[2].as_quat()}.items():
        got = dymsum.cobstacle_slices(CUBE, "box:2,1,1", form)
        assert len(got) == 1 and close_meshes(got[0], one[0]), name
    h[3, :3, 3] = [1, 0, 0]
    with pytest.raises(ValueError, match="rotations: transform 3 has the translation"):
        dymsum.cobstacle_slices(CUBE, "box:2,1,1", h)
    with pytest.raises(ValueError, match="rotations: transform 1: not a rigid transform"):
        dymsum.cobstacle_slices(CUBE, "box:2,1,1", np.stack([np.eye(4), 2 * np.eye(4)]))
    with pytest.raises(ValueError, match=r"rotations: expected .* got shape \(3,\)"):
        dymsum.cobstacle_slices(CUBE, "box:2,1,1", np.zeros(3))


@pytest.mark.parametrize(
    "bad,message",
    [
        (Rotation.from_rotvec([[0, 0, 0.1], [0, 0, 0.2]]), "expected one: .* a stack of 2"),
        (np.eye(2), r"got shape \(2, 2\)"),
        (np.zeros((3, 3)), "matrix is not a rotation"),
        ([0, 0, 0, 0], "quaternion .* is zero"),
        ("x", "dtype"),
    ],
)
def test_bad_rotations_say_what_is_accepted(bad, message):
    with pytest.raises(ValueError, match=message):
        dymsum.pose(bad)
    with pytest.raises(ValueError, match=f"pose_a: .*{message}"):
        dymsum.minkowski_sum(CUBE, CUBE, pose_a=bad)


def test_shapes_by_model_name_or_path(tmp_path):
    ref = dymsum.minkowski_sum(dymsum.load("cube"), dymsum.load("gs2"))
    assert close_meshes(dymsum.minkowski_sum("cube", "gs2"), ref, tol=0)
    path = tmp_path / "gs2.off"
    dymsum.save(path, dymsum.load("gs2"))
    assert close_meshes(dymsum.minkowski_sum("cube", path), ref, tol=0)
    assert close_meshes(dymsum.minkowski_sum("cube", str(path)), ref, tol=0)
    assert dymsum.Polytope("gs2").source == "built-in gs2"
    assert dymsum.contact("cube", "cube", None, dymsum.pose(translation=[5, 0, 0])).distance > 0
    with pytest.raises(ValueError, match="b: .*did you mean the model `gs2`"):
        dymsum.minkowski_sum("cube", "gs22")
    with pytest.raises(FileNotFoundError, match="a: .*does not exist"):
        dymsum.minkowski_sum(tmp_path / "missing.off", "cube")
    with pytest.raises(ValueError, match="strict mode"):
        dymsum.Polytope("cube", strict=True)


def test_scipy_is_never_imported_by_dymsum():
    code = (
        "import sys, numpy as np, dymsum\n"
        "dymsum.minkowski_sum('cube', 'gs1', pose_a=np.eye(3))\n"
        "dymsum.cobstacle_slices('cube', 'gs1', np.eye(3)[None])\n"
        "assert 'scipy' not in sys.modules, sorted(m for m in sys.modules if 'scipy' in m)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr


def test_examples_write_only_where_told(tmp_path):
    # The tour writes into the folder it is given (or a fresh temporary one),
    # never into the caller's working directory.
    script = pathlib.Path(__file__).parent.parent / "examples" / "tour.py"
    cwd, tmp = tmp_path / "cwd", tmp_path / "tmp"
    cwd.mkdir()
    tmp.mkdir()
    # Its fresh temporary folder under tmp_path, removed with it (issue 29:
    # the tests leave no dymsum-* folder in the system's temporary folder).
    env = {**os.environ, "TMPDIR": str(tmp), "TEMP": str(tmp), "TMP": str(tmp)}
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=300, cwd=cwd, env=env)
    assert done.returncode == 0, done.stderr
    assert list(cwd.iterdir()) == []
    assert "wrote" in done.stdout
    assert [p.name[: len("dymsum-tour-")] for p in tmp.iterdir()] == ["dymsum-tour-"]
