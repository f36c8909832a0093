"""Input forms, array ownership (no copies), file I/O and error cases."""

import os
import threading
import time
import tracemalloc

import numpy as np
import pytest
from conftest import CUBE, check_sum_against_qhull, pairwise_sums, random_pose, sphere_points

import dymsum


class FakeTrimesh:
    """Duck-typed like trimesh.Trimesh: only .vertices and .faces."""

    def __init__(self, vertices, faces):
        self.vertices = vertices
        self.faces = faces


def same_sum(x, y):
    return all(np.array_equal(p, q) for p, q in zip(x, y))


def test_every_input_form_gives_the_same_sum(rng):
    pts = sphere_points(30, rng)
    p = dymsum.Polytope(pts)
    ref = dymsum.minkowski_sum(p, CUBE)
    v, f = p.vertices, p.faces
    polys = [list(map(int, q)) for q in p.polygons]
    forms = {
        "points list": pts.tolist(),
        "points Fortran order": np.asfortranarray(pts),
        "points strided": np.hstack([pts, pts])[:, :3],
        "points read-only": np.require(pts, requirements="C").copy(),
        "(v, triangles)": (v, f),
        "[v, triangles list]": [v, f.tolist()],
        "(v, polygon lists)": (v, polys),
        "(v, polygon arrays)": (v, p.polygons),
        "(v, int32 triangles)": (v, f.astype(np.int32)),
        "trimesh-like": FakeTrimesh(v, f),
        "polytope": p,
    }
    forms["points read-only"].setflags(write=False)
    for name, a in forms.items():
        assert same_sum(dymsum.minkowski_sum(a, CUBE), ref), name
    # float32 and integer point arrays are converted (exactly) to float64.
    pts32 = pts.astype(np.float32)
    assert same_sum(dymsum.minkowski_sum(pts32, CUBE), dymsum.minkowski_sum(pts32.astype(np.float64), CUBE))
    assert same_sum(dymsum.minkowski_sum(CUBE.astype(np.int64), CUBE), dymsum.minkowski_sum(CUBE, CUBE))


def test_point_cloud_objects_and_quaternion_poses(rng):
    class FakePointCloud:  # like trimesh.PointCloud: .vertices only
        def __init__(self, vertices):
            self.vertices = vertices

    pts = sphere_points(20, rng)
    assert same_sum(dymsum.minkowski_sum(FakePointCloud(pts), CUBE), dymsum.minkowski_sum(pts, CUBE))
    # A (4,) pose is a quaternion (x, y, z, w): the same as its 4×4 pose (up
    # to rounding: the matrix is turned back into a quaternion).
    q = np.array([0.1, -0.4, 0.3, 0.8])
    (v1, f1), (v2, f2) = (dymsum.minkowski_sum(pts, CUBE, pose_a=p) for p in (q, dymsum.pose(q)))
    assert np.allclose(v1, v2, rtol=0, atol=1e-14) and np.array_equal(f1, f2)
    c1, c2 = dymsum.contact(pts, CUBE, None, q), dymsum.contact(pts, CUBE, None, dymsum.pose(q))
    assert c1.collides == c2.collides and abs(c1.depth - c2.depth) + abs(c1.distance - c2.distance) < 1e-14
    # ... and rotates about the origin as scipy's Rotation.from_quat does.
    from scipy.spatial.transform import Rotation

    _, polys = dymsum.minkowski_sum(pts, CUBE, pose_a=q, polygons=True)
    check_sum_against_qhull(v1, polys, pairwise_sums(Rotation.from_quat(q).apply(pts), CUBE))
    with pytest.raises(ValueError, match="quaternion .* is zero"):
        dymsum.minkowski_sum(pts, CUBE, pose_a=[0, 0, 0, 0])


def test_inputs_are_not_modified_and_not_kept(rng):
    pts = sphere_points(20, rng)
    keep = pts.copy()
    p = dymsum.Polytope(pts)
    assert np.array_equal(pts, keep)
    pts[:] = 0.0  # the polytope does not alias its input
    assert p.vertex_count == 20 and p.volume > 1.0


def numpy_peak_bytes(f):
    """Peak bytes allocated through Python and NumPy while f runs (NumPy
    reports its data buffers to tracemalloc; Rust's own allocations are not
    traced)."""
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        f()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_float64_c_contiguous_input_is_read_in_place(rng):
    pts = rng.uniform(-1, 1, size=(100_000, 3))  # 2.4 MB
    # float64 C-contiguous: read in place, no NumPy copy.
    assert numpy_peak_bytes(lambda: dymsum.Polytope(pts)) < 0.05 * pts.nbytes
    ball = dymsum.Polytope(sphere_points(20_000, rng))
    v, f = ball.vertices, ball.faces  # float64 and int64, C-contiguous
    assert numpy_peak_bytes(lambda: dymsum.Polytope((v, f))) < 0.05 * v.nbytes
    # Other layouts and dtypes are converted once (a copy the size of the array).
    for other in (np.asfortranarray(pts), pts.astype(np.float32), pts[::-1]):
        peak = numpy_peak_bytes(lambda: dymsum.Polytope(other))
        assert pts.nbytes <= peak < 3 * pts.nbytes


def test_outputs_are_not_copied():
    p = dymsum.Polytope(CUBE)
    # Polytope arrays: built once, the same read-only array on every access.
    assert p.vertices is p.vertices and p.faces is p.faces
    assert not p.vertices.flags.writeable and not p.faces.flags.writeable
    with pytest.raises(ValueError):
        p.vertices[0, 0] = 5.0
    # Sum outputs take over the Rust buffers: numpy did not allocate (and so
    # did not copy) them; they are ordinary writeable C-contiguous arrays.
    v, f = dymsum.minkowski_sum(p, p)
    for arr in (v, f):
        assert not arr.flags.owndata and arr.base is not None
        assert type(arr.base).__name__ == "PySliceContainer"
        assert arr.flags.c_contiguous and arr.flags.writeable


def test_poses_and_quaternions():
    r = dymsum.pose([0, 0, np.sin(np.pi / 4), np.cos(np.pi / 4)], [1, 2, 3])  # (x, y, z, w)
    assert r.shape == (4, 4) and r.dtype == np.float64
    assert np.allclose(r[:3, :3], [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-15)
    assert r[:3, 3].tolist() == [1, 2, 3] and r[3].tolist() == [0, 0, 0, 1]
    assert np.array_equal(dymsum.pose(), np.eye(4))
    # Poses as nested lists work, and the rotation turns A about the origin.
    v, _ = dymsum.minkowski_sum(CUBE, CUBE, pose_a=r.tolist())
    assert np.allclose(v.min(axis=0), [0, 2, 3]) and np.allclose(v.max(axis=0), [2, 4, 5])


def test_load_save_round_trip(tmp_path, rng):
    a = dymsum.load("gs1")
    b = dymsum.Polytope(sphere_points(25, rng))
    v, f = dymsum.minkowski_sum(a, b, pose_a=random_pose(rng))
    vol = dymsum.Polytope((v, f)).volume
    for ext in ("off", "obj", "ply", "stl"):
        path = tmp_path / f"sum.{ext}"
        dymsum.save(path, v, f)
        back = dymsum.load(path)  # path-like objects work
        assert back.source == f"file {path}"
        tol = 1e-6 if ext == "stl" else 1e-12  # STL stores float32
        assert back.volume == pytest.approx(vol, rel=tol)
    # save(path, shape) forms.
    dymsum.save(str(tmp_path / "poly.off"), a)
    assert dymsum.load(str(tmp_path / "poly.off")).face_count == a.face_count
    dymsum.save(tmp_path / "pair.obj", (v, f))
    assert dymsum.load(tmp_path / "pair.obj").vertex_count == len(v)
    # A point cloud file (no faces) loads as its hull.
    (tmp_path / "cloud.off").write_text("OFF\n8 0 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in CUBE))
    c = dymsum.load(tmp_path / "cloud.off")
    assert c.convexity_report["point_cloud"] and c.volume == 1.0


def test_models_are_listed_and_load():
    names = dymsum.models()
    assert {"cube", "ellipse", "gs4", "tcube:K"} <= set(names)
    e = dymsum.load("ellipse")
    assert e.convexity_report["input_triangles"] == 960 and e.source == "built-in ellipse"


BAD_SHAPES = [
    (np.zeros((3, 3)), "too few points"),
    (np.zeros((5, 2)), r"expected an \(N, 3\) array, got shape \(5, 2\)"),
    (np.zeros((2, 4, 3)), "got shape"),
    (np.array([[np.nan, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]), "non-finite"),
    (np.array([[np.inf, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]), "non-finite"),
    (np.ones((4, 3), dtype=complex), "complex128"),
    (np.array([["a", "b", "c"]] * 4), "dtype"),
    ([[0, 0, 0], [1, 0]], "expected an \\(N, 3\\) array"),
    (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], float), "flat|coplanar"),
    ((CUBE, [[0, 1, 9]]), "out of range"),
    ((CUBE, [[0, 1, -1]]), "out of range"),
    ((CUBE, [[0, 1]]), "face"),
    ((CUBE, np.zeros((2, 3))), "integer"),
    ((CUBE, [[0.0, 1.0, 2.0]]), "integer"),
    ((CUBE, [[0, 1, 3], [0, 3, 2]]), "open|edge"),
    (FakeTrimesh(np.zeros((4, 3)), [[0, 1, 2]]), "open mesh"),
]


@pytest.mark.parametrize("bad,message", BAD_SHAPES)
def test_bad_shapes_raise_value_error(bad, message):
    for call in (dymsum.Polytope, lambda x: dymsum.minkowski_sum(x, CUBE), lambda x: dymsum.contact(x, CUBE)):
        with pytest.raises(ValueError, match=message):
            call(bad)
    with pytest.raises(ValueError, match="^b"):  # the message names the operand
        dymsum.minkowski_sum(CUBE, bad)


def test_non_convex_mesh_raises_value_error():
    p = dymsum.Polytope(CUBE)
    v = p.vertices.copy()
    corner = np.flatnonzero((v == 0).all(axis=1))[0]
    v[corner] = [0.4, 0.4, 0.4]  # a dent: the corner at the origin pushed in
    with pytest.raises(ValueError, match="non-convex"):
        dymsum.Polytope((v, p.faces))


ROT = np.eye(4)
BAD_POSES = [
    (2 * np.eye(3), "not a rotation"),
    (np.eye(4)[:3], r"4×4 .*shape \(3, 4\)"),
    (np.zeros(3), r"got shape \(3,\)"),
    (np.tile([0, 0, 0, 1.0], (3, 1)), "a stack of 3"),
    (2 * np.eye(4), "last row"),
    (np.diag([2.0, 1, 1, 1]), "orthonormal"),
    (np.diag([1.0, 1, -1, 1]), "det"),
    (np.array([[1, 0.5, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]), "orthonormal"),
    (np.where(np.eye(4) == 1, np.nan, 0), "NaN"),
    ("identity", "dtype"),
]


@pytest.mark.parametrize("bad,message", BAD_POSES)
def test_bad_poses_raise_value_error(bad, message):
    with pytest.raises(ValueError, match=f"pose_a: .*{message}"):
        dymsum.minkowski_sum(CUBE, CUBE, pose_a=bad)
    with pytest.raises(ValueError, match=f"pose_b: .*{message}"):
        dymsum.contact(CUBE, CUBE, None, bad)
    s = dymsum.DynamicSum(CUBE, CUBE)
    with pytest.raises(ValueError, match=message):
        s.update(bad)
    t = dymsum.ContactTracker(CUBE, CUBE)
    with pytest.raises(ValueError, match=message):
        t.update(None, bad)


def test_other_errors():
    with pytest.raises(ValueError, match="unknown method `fast`"):
        dymsum.minkowski_sum(CUBE, CUBE, method="fast")
    with pytest.raises(ValueError, match="did you mean the model `ellipse`"):
        dymsum.load("elipse")
    with pytest.raises(FileNotFoundError, match="does not exist"):
        dymsum.load("no/such/file.off")
    with pytest.raises(ValueError, match="unknown mesh file extension"):
        dymsum.save("out.xyz", CUBE, [[0, 1, 2]])
    with pytest.raises(FileNotFoundError):
        dymsum.save("/no/such/dir/out.off", CUBE, [[0, 1, 2]])
    with pytest.raises(ValueError, match="faces are missing"):
        dymsum.save("out.off", CUBE)
    with pytest.raises(ValueError, match="zero"):
        dymsum.pose([0, 0, 0, 0])
    with pytest.raises(ValueError, match="quaternion 1"):
        dymsum.cobstacle_slices(CUBE, CUBE, np.array([[0, 0, 0, 1.0], [0, 0, 0, 0]]))
    with pytest.raises(ValueError, match="matrix 0 is not a rotation"):
        dymsum.cobstacle_slices(CUBE, CUBE, 2 * np.eye(3)[None])
    with pytest.raises(ValueError, match=r"\(K, 4\) quaternions .* got shape \(2, 3\)"):
        dymsum.cobstacle_slices(CUBE, CUBE, np.zeros((2, 3)))


def test_long_calls_release_the_gil():
    # While one thread computes many C-obstacle slices in Rust, another
    # thread keeps running Python: impossible if the GIL were held.
    a, b = dymsum.load("ellipse"), dymsum.load("gs4")
    quats = np.array([[0, 0, np.sin(t), np.cos(t)] for t in np.linspace(0, 0.5, 40)])
    span = {}

    def work():
        span["start"] = time.perf_counter()
        dymsum.cobstacle_slices(a, b, quats)
        span["end"] = time.perf_counter()

    worker = threading.Thread(target=work)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    # Python ran in this thread while the worker was inside the Rust call
    # (with the GIL held, no tick could fall strictly inside it, whatever
    # the load on the machine).
    inside = [t for t in ticks if span["start"] < t < span["end"]]
    assert span["end"] - span["start"] > 0.05
    assert len(inside) >= 10
