"""Every array layout gives the C-ordered answer, or a clear error (issue 33 §2).

A pose, a pose stack, a rotation, a vertex or a face array is read by its
logical indices, never by its raw memory: a Fortran-ordered 4×4 (as Eigen
based bindings hand out), a transposed view, a negatively strided, sliced,
broadcast, big-endian or ``np.matrix`` array gives exactly the answer of the
same values C-ordered. The scene makes a layout bug visible: a stick turned
by ``R`` hits a block that it misses turned by ``Rᵀ`` (a rotation matrix
read transposed is its inverse), and the poses are pure rotations, so a
transposed read is still a valid rigid transform.

And the errors: an empty face array, a mesh with no triangle left after
cleaning, a face index out of range (quoted as given, unsigned included)
and ``None`` where a body is expected are ``ValueError``s naming the
argument.
"""

import os
import tempfile
import tracemalloc

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import dymsum


def cuboid(lo, hi):
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])], float)


def unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


# A stick from the origin along +x, and a block at its tip turned by R.
STICK = cuboid([0, -0.05, -0.05], [2, 0.05, 0.05])
ROT = Rotation.from_rotvec(np.deg2rad(70) * unit([0.3, 0.2, 1.0]))
R = ROT.as_matrix()
TIP = R @ [1.9, 0.0, 0.0]
BLOCK = cuboid(TIP - 0.15, TIP + 0.15)


def rotation_pose(m):
    p = np.eye(4)
    p[:3, :3] = m
    return p


POSE_R = rotation_pose(R)  # the stick hits the block
POSE_RT = rotation_pose(R.T)  # the stick misses it
# Pure rotations (no translation: a transposed read stays a rigid transform).
OTHERS = [rotation_pose(m) for m in Rotation.from_rotvec(np.array([[0.3, -0.5, 0.9], [-1.2, 0.4, 0.2], [0.1, 0.1, -2.0]])).as_matrix()]
STACK = np.stack([POSE_R, POSE_RT, np.eye(4), POSE_R, *OTHERS, POSE_RT])

# A triangle mesh: the block's hull without one triangle (an open surface,
# on the triangle path of the motion checks), and a closed convex one.
_HULL = dymsum.Polytope(BLOCK)
BLOCK_V, BLOCK_F = np.asarray(_HULL.vertices), np.asarray(_HULL.faces)
OPEN_F = BLOCK_F[1:]


def _sliced_last(a):
    big = np.zeros(a.shape[:-1] + (2 * a.shape[-1],), a.dtype)
    big[..., 1::2] = a
    return big[..., 1::2]


def _sliced_first(a):
    big = np.zeros((2 * a.shape[0],) + a.shape[1:], a.dtype)
    big[::2] = a
    return big[::2]


def _swapped(a):
    # Each trailing matrix column-major in memory (a stack of Eigen matrices).
    return np.ascontiguousarray(np.swapaxes(a, -1, -2)).swapaxes(-1, -2)


def _readonly_f(a):
    f = np.asfortranarray(a)
    f.flags.writeable = False
    return f


LAYOUTS = {
    "C": np.ascontiguousarray,
    "F": np.asfortranarray,
    "transposed": lambda a: np.ascontiguousarray(a.T).T,
    "swapped": _swapped,
    "reversed": lambda a: np.flip(np.flip(a).copy()),
    "sliced": _sliced_last,
    "rows sliced": _sliced_first,
    "big-endian": lambda a: a.astype(a.dtype.newbyteorder(">")),
    "readonly F": _readonly_f,
    "list": lambda a: a.tolist(),
}


def laid(a, layout):
    """``a``'s values in the given memory layout (asserted equal)."""
    a = np.ascontiguousarray(a)
    if layout == "swapped" and a.ndim < 2:
        layout = "reversed"
    out = LAYOUTS[layout](a)
    if layout != "list":
        assert np.array_equal(out, a) and out.shape == a.shape
        if a.ndim >= 2 and min(a.shape[-2:]) > 1 and layout in ("F", "transposed", "swapped"):
            assert not out.flags.c_contiguous, layout
    return out


layouts = pytest.mark.parametrize("layout", list(LAYOUTS))


def same_check(a, b):
    assert (a.free, a.t_safe, a.t_contact) == (b.free, b.t_safe, b.t_contact)


def same_checks(a, b):
    np.testing.assert_array_equal(a.free, b.free)
    np.testing.assert_array_equal(a.t_safe, b.t_safe)
    np.testing.assert_array_equal(a.t_contact, b.t_contact)


def same_contact(a, b):
    assert (a.collides, a.depth, a.distance) == (b.collides, b.depth, b.distance)
    for k in ("normal", "point_a", "point_b"):
        np.testing.assert_array_equal(getattr(a, k), getattr(b, k))


def same_contacts(a, b):
    for k in ("collides", "depth", "distance", "normal", "point_a", "point_b"):
        np.testing.assert_array_equal(getattr(a, k), getattr(b, k))


def same_mesh(a, b):
    assert len(a) == len(b)
    for x, y in zip(a, b):
        if isinstance(x, list):
            assert len(x) == len(y) and all(np.array_equal(p, q) for p, q in zip(x, y))
        else:
            np.testing.assert_array_equal(x, y)


@pytest.fixture(scope="module")
def checker():
    return dymsum.MotionChecker(STICK, [BLOCK])


@pytest.fixture(scope="module")
def mesh_checker():
    return dymsum.MotionChecker(STICK, [(BLOCK_V, OPEN_F)])


def test_the_scene_tells_a_rotation_from_its_inverse(checker, mesh_checker):
    assert mesh_checker.info["path"] == "triangles"
    for c in (checker, mesh_checker):
        assert c.collides_at(POSE_R) and not c.collides_at(POSE_RT)
        assert not c.collides_at(np.eye(4))
        assert not c.check(None, POSE_R).free and c.check(None, POSE_RT).free
        assert c.distance_at(POSE_R) == 0.0 < c.distance_at(POSE_RT)
    # The transposed 4×4 is the inverse rotation: the bug the layouts catch.
    assert checker.collides_at(np.ascontiguousarray(POSE_R.T)) is False


# ------------------------------------------------------------------ poses


@layouts
@pytest.mark.parametrize("which", ["checker", "mesh_checker"])
def test_motion_checker_single_poses(layout, which, request):
    c = request.getfixturevalue(which)
    for pose in (POSE_R, POSE_RT, *OTHERS):
        p = laid(pose, layout)
        assert c.collides_at(p) == c.collides_at(pose)
        assert c.distance_at(p) == c.distance_at(pose)
        same_check(c.check(None, p), c.check(None, pose))
        same_check(c.check(p, None), c.check(pose, None))
        q = laid(OTHERS[0], layout)
        same_check(c.check(q, p), c.check(OTHERS[0], pose))
    # A rotation as a 3×3 matrix or a (4,) quaternion, in every layout.
    for rot in (R, R.T):
        assert c.collides_at(laid(rot, layout)) == c.collides_at(rot)
        assert c.distance_at(laid(rot, layout)) == c.distance_at(rot)
    for quat in (ROT.as_quat(), ROT.inv().as_quat()):
        assert c.collides_at(laid(quat, layout)) == c.collides_at(quat)
    # A scipy Rotation made from a matrix in that layout.
    if layout != "list":
        assert c.collides_at(Rotation.from_matrix(laid(R, layout))) is True


@layouts
def test_pose_with_translation(layout, checker):
    shifted = POSE_R.copy()
    shifted[:3, 3] = [0.02, -0.01, 0.03]
    p = laid(shifted, layout)
    assert checker.collides_at(p) == checker.collides_at(shifted)
    assert checker.distance_at(p) == checker.distance_at(shifted)
    same_check(checker.check(None, p), checker.check(None, shifted))


@pytest.mark.parametrize("layout", ["F", "transposed", "readonly F"])
def test_eigen_style_pose_is_not_read_transposed(layout, checker):
    # The case: a column-major pose read as row-major turned the
    # rotation into its inverse, silently.
    assert checker.collides_at(laid(POSE_R, layout)) is True
    assert checker.collides_at(laid(POSE_RT, layout)) is False


@pytest.mark.filterwarnings("ignore::PendingDeprecationWarning")
def test_np_matrix_poses(checker):
    for pose in (POSE_R, POSE_RT):
        m = np.asmatrix(np.asfortranarray(pose))
        assert checker.collides_at(m) == checker.collides_at(pose)
        assert checker.collides_at(np.asmatrix(np.asfortranarray(pose[:3, :3]))) == checker.collides_at(pose)


@layouts
@pytest.mark.parametrize("which", ["checker", "mesh_checker"])
def test_pose_stacks(layout, which, request):
    c = request.getfixturevalue(which)
    for stack in (STACK, STACK[:1], STACK[1:2]):
        s = laid(stack, layout)
        want = c.collides_many(stack)
        np.testing.assert_array_equal(c.collides_many(s), want)
        same_checks(c.check_many(None, s), c.check_many(None, stack))
        same_checks(c.check_many(s, None), c.check_many(stack, None))
        same_checks(c.check_many(s, s[::-1] if layout != "list" else stack[::-1]), c.check_many(stack, stack[::-1]))
    np.testing.assert_array_equal(c.collides_many(laid(STACK, layout)), [c.collides_at(p) for p in STACK])


@layouts
def test_rotation_stacks(layout, checker):
    rots = Rotation.from_matrix(STACK[:, :3, :3])
    want = checker.collides_many(STACK)
    np.testing.assert_array_equal(checker.collides_many(laid(STACK[:, :3, :3], layout)), want)
    np.testing.assert_array_equal(checker.collides_many(laid(rots.as_quat(), layout)), want)


def test_reversed_and_strided_stacks_answer_in_their_order(checker):
    want = checker.collides_many(STACK)
    np.testing.assert_array_equal(checker.collides_many(STACK[::-1]), want[::-1])
    np.testing.assert_array_equal(checker.collides_many(STACK[::2]), want[::2])
    np.testing.assert_array_equal(checker.collides_many(STACK[::-3]), want[::-3])
    pair = np.stack([POSE_R, POSE_RT])
    broadcast = np.broadcast_to(pair[:1], (5, 4, 4))
    assert broadcast.strides[0] == 0
    np.testing.assert_array_equal(checker.collides_many(broadcast), [True] * 5)
    np.testing.assert_array_equal(checker.collides_many(pair.transpose(0, 2, 1)), [False, True])


@layouts
def test_check_motion_and_check_motions(layout):
    for p0, p1 in ((None, POSE_R), (OTHERS[0], POSE_RT), (POSE_RT, OTHERS[1])):
        a0 = None if p0 is None else laid(p0, layout)
        same_check(dymsum.check_motion(STICK, [BLOCK], a0, laid(p1, layout)), dymsum.check_motion(STICK, [BLOCK], p0, p1))
    same_checks(
        dymsum.check_motions(STICK, [BLOCK], None, laid(STACK, layout)),
        dymsum.check_motions(STICK, [BLOCK], None, STACK),
    )
    same_checks(
        dymsum.check_motions(STICK, [(BLOCK_V, OPEN_F)], laid(STACK, layout), None),
        dymsum.check_motions(STICK, [(BLOCK_V, OPEN_F)], STACK, None),
    )


@layouts
def test_contact_functions(layout):
    for pa, pb in ((POSE_R, None), (POSE_RT, None), (POSE_R, OTHERS[0])):
        la, lb = laid(pa, layout), None if pb is None else laid(pb, layout)
        same_contact(dymsum.contact(STICK, BLOCK, la, lb), dymsum.contact(STICK, BLOCK, pa, pb))
        # The body moved is b: its pose as well.
        same_contact(dymsum.contact(BLOCK, STICK, lb, la), dymsum.contact(BLOCK, STICK, pb, pa))
    same_contacts(dymsum.contact_many(STICK, BLOCK, laid(STACK, layout)), dymsum.contact_many(STICK, BLOCK, STACK))
    same_contacts(dymsum.contact_many(BLOCK, STICK, None, laid(STACK, layout)), dymsum.contact_many(BLOCK, STICK, None, STACK))
    np.testing.assert_array_equal(
        dymsum.collides_many(STICK, BLOCK, laid(STACK, layout)), dymsum.collides_many(STICK, BLOCK, STACK)
    )
    assert dymsum.collides_many(STICK, BLOCK, laid(STACK, layout))[0]


@layouts
def test_contact_tracker(layout):
    t = dymsum.ContactTracker(STICK, BLOCK, laid(POSE_R, layout))
    u = dymsum.ContactTracker(STICK, BLOCK, POSE_R)
    same_contact(t.last, u.last)
    assert t.last.collides
    for pose in (POSE_RT, OTHERS[0], POSE_R):
        same_contact(t.update(laid(pose, layout)), u.update(pose))
        same_contact(t.update(None, laid(OTHERS[1], layout)), u.update(None, OTHERS[1]))


@layouts
def test_minkowski_sum_and_dynamic_sum(layout):
    for pa, pb in ((POSE_R, None), (POSE_RT, OTHERS[0])):
        la, lb = laid(pa, layout), None if pb is None else laid(pb, layout)
        same_mesh(dymsum.minkowski_sum(STICK, BLOCK, la, lb), dymsum.minkowski_sum(STICK, BLOCK, pa, pb))
        same_mesh(
            dymsum.minkowski_sum(STICK, BLOCK, la, lb, polygons=True),
            dymsum.minkowski_sum(STICK, BLOCK, pa, pb, polygons=True),
        )
    d = dymsum.DynamicSum(STICK, BLOCK, laid(POSE_R, layout))
    e = dymsum.DynamicSum(STICK, BLOCK, POSE_R)
    np.testing.assert_array_equal(d.pose_a, e.pose_a)
    assert np.allclose(d.pose_a, POSE_R, atol=1e-12)
    same_mesh(d.mesh(), e.mesh())
    d.update(laid(POSE_RT, layout), laid(OTHERS[2], layout))
    e.update(POSE_RT, OTHERS[2])
    np.testing.assert_array_equal(d.pose_a, e.pose_a)
    np.testing.assert_array_equal(d.pose_b, e.pose_b)
    same_mesh(d.mesh(), e.mesh())


@layouts
def test_pose_function(layout):
    t = [1.0, -2.0, 0.5]
    for q in (ROT.as_quat(), ROT.inv().as_quat()):
        np.testing.assert_array_equal(dymsum.pose(laid(q, layout), t), dymsum.pose(q, t))
    for m in (R, R.T):
        np.testing.assert_array_equal(dymsum.pose(laid(m, layout), t), dymsum.pose(m, t))
    assert np.allclose(dymsum.pose(laid(R, layout))[:3, :3], R, atol=1e-12)


@layouts
def test_cobstacle_slices_rotations(layout):
    quats = Rotation.from_matrix(STACK[:5, :3, :3]).as_quat()
    for rotations in (STACK[:5], STACK[:5, :3, :3], quats):
        want = dymsum.cobstacle_slices(STICK, BLOCK, rotations)
        got = dymsum.cobstacle_slices(STICK, BLOCK, laid(rotations, layout))
        assert len(got) == len(want)
        for g, w in zip(got, want):
            same_mesh(g, w)
    slabs = dymsum.cobstacle_slices(STICK, BLOCK, laid(STACK[:3, :3, :3], layout), certified=True)
    ref = dymsum.cobstacle_slices(STICK, BLOCK, STACK[:3, :3, :3], certified=True)
    for s, r in zip(slabs, ref):
        np.testing.assert_array_equal(s.normals, r.normals)
        np.testing.assert_array_equal(s.offsets, r.offsets)
    # Slab.contains: points in every layout.
    pts = np.array([[0.0, 0.0, 0.0], [5.0, 5.0, 5.0], list(TIP), [-1.0, 0.5, 0.2]])
    np.testing.assert_array_equal(slabs[0].contains(laid(pts, layout)), slabs[0].contains(pts))


@layouts
def test_cobstacle_map_rotations(layout):
    quats = Rotation.from_matrix(STACK[:4, :3, :3]).as_quat()
    for rotations in (quats, STACK[:4, :3, :3]):
        want = dymsum.cobstacle_map(STICK, [BLOCK], rotations, workers=1)
        got = dymsum.cobstacle_map([laid(STICK, layout)], [laid(BLOCK, layout)], laid(rotations, layout), workers=1)
        assert got.arrays.keys() == want.arrays.keys()
        for k in want.arrays:
            np.testing.assert_array_equal(got.arrays[k], want.arrays[k])


# -------------------------------------------------------- vertices, faces


@layouts
def test_vertex_and_face_arrays(layout):
    p = dymsum.Polytope(laid(BLOCK, layout))
    q = dymsum.Polytope(BLOCK)
    np.testing.assert_array_equal(p.vertices, q.vertices)
    np.testing.assert_array_equal(p.faces, q.faces)
    for dtype in (np.int64, np.int32, np.uint32, np.uint64):
        f = laid(BLOCK_F.astype(dtype), layout)
        m = dymsum.Polytope((laid(BLOCK_V, layout), f))
        n = dymsum.Polytope((BLOCK_V, BLOCK_F))
        np.testing.assert_array_equal(m.vertices, n.vertices)
        np.testing.assert_array_equal(m.faces, n.faces)
        c = dymsum.MotionChecker(STICK, [(laid(BLOCK_V, layout), laid(OPEN_F.astype(dtype), layout))])
        assert c.info == dymsum.MotionChecker(STICK, [(BLOCK_V, OPEN_F)]).info
        np.testing.assert_array_equal(c.collides_many(STACK), [c.collides_at(x) for x in STACK])
        assert c.collides_at(POSE_R) and not c.collides_at(POSE_RT)
    u = dymsum.ConvexUnion([laid(STICK, layout), (laid(BLOCK_V, layout), laid(BLOCK_F, layout))])
    for a, b in zip(u.pieces, dymsum.ConvexUnion([STICK, (BLOCK_V, BLOCK_F)]).pieces):
        np.testing.assert_array_equal(a.vertices, b.vertices)
    # The body in any layout, moved by a pose in any layout.
    c = dymsum.MotionChecker(laid(STICK, layout), [laid(BLOCK, layout)])
    np.testing.assert_array_equal(c.collides_many(laid(STACK, layout)), dymsum.MotionChecker(STICK, BLOCK).collides_many(STACK))


@layouts
def test_save_and_check_solid(layout):
    with tempfile.TemporaryDirectory() as d:
        a, b = os.path.join(d, "a.off"), os.path.join(d, "b.off")
        dymsum.save(a, laid(BLOCK_V, layout), laid(BLOCK_F, layout))
        dymsum.save(b, BLOCK_V, BLOCK_F)
        with open(a, "rb") as fa, open(b, "rb") as fb:
            assert fa.read() == fb.read()
    assert dymsum.check_solid(laid(BLOCK_V, layout), laid(BLOCK_F, layout)) is None
    assert dymsum.check_solid(laid(BLOCK_V, layout), laid(OPEN_F, layout)) == dymsum.check_solid(BLOCK_V, OPEN_F)


# ------------------------------------------------------------ large stacks


def _traced_peak(call):
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        base = tracemalloc.get_traced_memory()[0]
        out = call()
        return out, tracemalloc.get_traced_memory()[1] - base
    finally:
        tracemalloc.stop()


def test_large_non_contiguous_stacks_are_not_read_through_lists():
    # A (K, 4, 4) stack is read by its strides (float64) or copied once to
    # C order (other dtypes), never converted through a Python list (which
    # took 5.6 s and 1.75 GB for 2 million poses).
    k = 50_000
    rng = np.random.default_rng(7)
    stack = np.zeros((k, 4, 4))
    stack[:, :3, :3] = Rotation.random(k, random_state=rng).as_matrix()
    stack[:, 3, 3] = 1.0
    want = dymsum.collides_many(STICK, BLOCK, stack)
    assert want.any() and not want.all()
    for name, s in (("F", np.asfortranarray(stack)), ("swapped", _swapped(stack)), ("sliced", _sliced_first(stack))):
        got, peak = _traced_peak(lambda: dymsum.collides_many(STICK, BLOCK, s))
        np.testing.assert_array_equal(got, want)
        assert peak < stack.nbytes / 4, (name, peak)
    s32 = np.asfortranarray(stack.astype(np.float32))
    got, peak = _traced_peak(lambda: dymsum.collides_many(STICK, BLOCK, s32))
    np.testing.assert_array_equal(got, dymsum.collides_many(STICK, BLOCK, np.ascontiguousarray(s32)))
    assert peak < 1.5 * stack.nbytes, peak  # one float64 copy at most


# ------------------------------------------------------------------ errors


class _Mesh:
    def __init__(self, vertices, faces):
        self.vertices, self.faces = vertices, faces


EMPTIES = {
    "(0, 3) int64": np.zeros((0, 3), np.int64),
    "(0, 3) uint32 F": np.asfortranarray(np.zeros((0, 3), np.uint32)),
    "(0, 3) float": np.zeros((0, 3)),
    "empty list": [],
}

BOX = cuboid([-1, -1, -1], [1, 1, 1]) * 5


def _body_calls(shape):
    """(the argument's name, a call taking ``shape`` as it)."""
    return [
        ("a", lambda: dymsum.Polytope(shape)),
        ("body", lambda: dymsum.MotionChecker(shape, [BLOCK])),
        (r"obstacles\[0\]", lambda: dymsum.MotionChecker(STICK, [shape])),
        ("obstacles", lambda: dymsum.MotionChecker(STICK, shape)),
        ("body", lambda: dymsum.check_motion(shape, [BLOCK], None, None)),
        (r"obstacles\[1\]", lambda: dymsum.check_motions(STICK, [BLOCK, shape], None, STACK)),
        (r"pieces\[1\]", lambda: dymsum.ConvexUnion([STICK, shape])),
        ("a", lambda: dymsum.contact(shape, BLOCK)),
        ("b", lambda: dymsum.contact(STICK, shape)),
        ("a", lambda: dymsum.contact_many(shape, BLOCK, STACK)),
        ("b", lambda: dymsum.collides_many(STICK, shape, STACK)),
        ("b", lambda: dymsum.minkowski_sum(STICK, shape)),
        ("a", lambda: dymsum.DynamicSum(shape, BLOCK)),
        ("b", lambda: dymsum.ContactTracker(STICK, shape)),
        ("robot", lambda: dymsum.cobstacle_slices(shape, BLOCK, STACK[:2])),
        ("obstacle", lambda: dymsum.cobstacle_slices(STICK, shape, STACK[:2])),
    ]


@pytest.mark.parametrize("empty", list(EMPTIES))
def test_empty_face_array_is_an_error(empty):
    faces = EMPTIES[empty]
    for shape in ((BOX, faces), _Mesh(BOX, faces)):
        for name, call in _body_calls(shape):
            with pytest.raises(ValueError, match=rf"^{name} faces: the face array is empty"):
                call()


def test_robot_inside_a_faceless_box_is_refused():
    # It was the hull of the box's corners: a solid the robot is inside.
    robot = cuboid([-0.1] * 3, [0.1] * 3)
    with pytest.raises(ValueError, match=r"obstacles\[0\] faces: the face array is empty \(shape \(0, 3\)\)"):
        dymsum.MotionChecker(robot, [(BOX, np.zeros((0, 3), np.int64))])
    with pytest.raises(ValueError, match=r"obstacles faces: the face array is empty"):
        dymsum.check_motion(robot, (BOX, np.zeros((0, 3), np.int64)), None, None)


def test_no_triangle_left_after_cleaning_is_an_error():
    v = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0]], float)
    degenerate = np.array([[0, 0, 1], [0, 1, 2], [3, 3, 3]])  # repeated corners, collinear
    with pytest.raises(ValueError, match=r"^obstacles\[0\]: no triangle is left after cleaning"):
        dymsum.MotionChecker(STICK, [(v, degenerate)])
    with pytest.raises(ValueError, match=r"^body: no triangle is left after cleaning"):
        dymsum.MotionChecker((v, degenerate), [BLOCK])
    with pytest.raises(ValueError, match=r"^obstacles: no triangle is left after cleaning"):
        dymsum.check_motion(STICK, (v, degenerate), None, None)
    with pytest.raises(ValueError, match=r"^a: "):
        dymsum.Polytope((v, degenerate))


BIG = 2**63


@pytest.mark.parametrize(
    "faces, quoted",
    [
        (np.array([[0, 1, BIG]], np.uint64), str(BIG)),
        (np.asfortranarray(np.array([[0, 1, 2], [3, BIG, 2]], np.uint64)), str(BIG)),
        (np.array([[0, 1, 2**64 - 1]], np.uint64), str(2**64 - 1)),
        (np.array([[0, 1, 8]], np.uint8), "8"),
        (np.array([[0, -1, 2]], np.int64), "-1"),
        (np.array([[0, 1, -(2**63)]], np.int64), str(-(2**63))),
        ([[0, 1, BIG]], str(BIG)),
        ([np.array([0, 1, BIG], np.uint64)], str(BIG)),
        ([[0, 1, 2, 3, 2**70]], str(2**70)),
    ],
    ids=["uint64 2**63", "F uint64", "uint64 max", "uint8", "-1", "int64 min", "list", "list of arrays", "list 2**70"],
)
def test_index_out_of_range_is_quoted_as_given(faces, quoted):
    cases = [
        ("a faces", lambda: dymsum.Polytope((BOX, faces))),
        (r"obstacles\[0\] faces", lambda: dymsum.MotionChecker(STICK, [(BOX, faces)])),
        ("body faces", lambda: dymsum.check_motion((BOX, faces), [BLOCK], None, None)),
        ("b faces", lambda: dymsum.contact(STICK, (BOX, faces))),
    ]
    for name, call in cases:
        with pytest.raises(ValueError, match=rf"^{name}: face \d: vertex index {quoted} out of range") as e:
            call()
        if not quoted.startswith("-"):
            assert f"-{quoted}" not in str(e.value) and "-9223372036854775808" not in str(e.value)
    why = dymsum.check_solid(BOX, faces)
    assert why is not None and f"vertex index {quoted} out of range" in why


def test_convex_pieces_quotes_an_unsigned_index_as_given():
    from dymsum.nonconvex._checks import _as_mesh

    faces = np.array([[0, 1, 2], [0, 2, BIG]], np.uint64)
    with pytest.raises(ValueError, match=f"vertex index {BIG} out of range") as e:
        dymsum.convex_pieces((BOX, faces), name="body")
    assert "-9223372036854775808" not in str(e.value)
    with pytest.raises(ValueError, match=f"mesh faces index vertex {BIG}, out of range") as e:
        _as_mesh(BOX, faces)
    with pytest.raises(ValueError, match=f"mesh faces index vertex {2**64 - 1}, out of range") as e:
        _as_mesh(BOX, np.asfortranarray(np.array([[0, 1, 2], [0, 2, 2**64 - 1]], np.uint64)))


def test_none_where_a_body_is_expected():
    for name, call in _body_calls(None):
        with pytest.raises(ValueError, match=rf"^{name}: expected .*got None"):
            call()
    checks = [
        ("obstacles", lambda: dymsum.MotionChecker(STICK, obstacles=None)),
        ("obstacles", lambda: dymsum.check_motion(STICK, None, None, None)),
        ("obstacles", lambda: dymsum.check_motions(STICK, None, None, STACK)),
        ("body", lambda: dymsum.check_motions(None, [BLOCK], None, STACK)),
        (r"obstacles\[1\]", lambda: dymsum.check_motions(STICK, [BLOCK, None], None, STACK)),
        ("ConvexUnion: pieces", lambda: dymsum.ConvexUnion(None)),
    ]
    for name, call in checks:
        with pytest.raises(ValueError, match=rf"^{name}.*None"):
            call()
    with pytest.raises(ValueError, match="obstacles: .*got None"):
        dymsum.cobstacle_map(STICK, None, ROT.as_quat()[None], workers=1)
    with pytest.raises(ValueError, match="robot: .*got None"):
        dymsum.cobstacle_map(None, [BLOCK], ROT.as_quat()[None], workers=1)


def test_not_a_sequence_of_obstacles():
    with pytest.raises(ValueError, match="^obstacles: expected a sequence of ConvexUnions or shapes, or one; got int"):
        dymsum.MotionChecker(STICK, 3)
    with pytest.raises(ValueError, match="^ConvexUnion: pieces must be a sequence of shapes, got float"):
        dymsum.ConvexUnion(1.5)
