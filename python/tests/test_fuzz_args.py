"""Fuzzing the motion functions' arguments and the mesh readers (issue 26).

``dymsum.check_motion``, ``check_motions``, ``MotionChecker(...).check /
check_many / collides_at`` and ``dymsum.pose`` get arbitrary poses (numpy
arrays of any shape and dtype, NaN, infinities, huge values, lists, None,
scipy Rotations, strings, objects), tolerances and budgets of any type and
value: each call succeeds or raises ValueError, TypeError or
dymsum.MotionUndecided; nothing else, never a crash. ``dymsum.load`` and
``dymsum.read_mesh_bodies`` on random and mutated mesh files succeed or
raise ValueError or OSError.

A small budget (``max_examples=100`` per test) keeps CI fast; for a long
run, ``DYMSUM_HYPOTHESIS_EXAMPLES=5000 pytest python/tests/test_fuzz_args.py``.
"""

import math
import os

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import dymsum

pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from hypothesis.extra import numpy as hnp  # noqa: E402

FUZZ = settings(
    max_examples=int(os.environ.get("DYMSUM_HYPOTHESIS_EXAMPLES", "100")),
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)

# The exceptions the motion functions may raise for bad arguments.
ALLOWED = (ValueError, TypeError, dymsum.MotionUndecided)

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float) - 0.5
BAR = np.array([[x, y, z] for x in (0, 2) for y in (-0.05, 0.05) for z in (-0.05, 0.05)], dtype=float)
OBSTACLES = [CUBE * 0.5 + [1.5, 0.5, 0.0], CUBE + [0.0, -2.0, 0.0]]

# ---------------------------------------------------------------------------
# Strategies

EXTREME = [0.0, -0.0, 1e-300, -1e-300, 5e-324, 1.0, -1.0, 1e300, -1e300, math.nan, math.inf, -math.inf, 1.7976931348623157e308]

floats = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(-10, 10),
    st.sampled_from(EXTREME),
)


def valid_pose(quat, translation):
    """A 4×4 rigid pose from a quaternion (x, y, z, w) and a translation."""
    q = np.asarray(quat, float)
    with np.errstate(over="ignore", invalid="ignore"):
        n = np.linalg.norm(q)
    q = q / n if np.isfinite(n) and n > 1e-150 else np.array([0.0, 0.0, 0.0, 1.0])
    m = np.eye(4)
    m[:3, :3] = Rotation.from_quat(q).as_matrix()
    m[:3, 3] = translation
    return m


quaternions = st.lists(st.one_of(st.floats(-1, 1), st.sampled_from(EXTREME)), min_size=4, max_size=4)
modest = st.lists(st.floats(-3, 3), min_size=3, max_size=3)

shapes = st.sampled_from([(4, 4), (3, 3), (4,), (3,), (7,), (2, 4, 4), (1, 4, 4), (0,), (4, 4, 1), (), (3, 4), (4, 3), (0, 4, 4)])
dtypes = st.sampled_from([np.float64, np.float32, np.float16, np.int64, np.int8, np.uint8, np.bool_, np.complex128])


@st.composite
def numeric_arrays(draw):
    shape = draw(shapes)
    dtype = draw(dtypes)
    if dtype == np.complex128:
        elements = st.complex_numbers(allow_nan=True, allow_infinity=True)
    elif dtype in (np.float64,):
        elements = floats
    elif dtype in (np.float32, np.float16):
        elements = st.floats(width=np.finfo(dtype).bits, allow_nan=True, allow_infinity=True)
    else:
        elements = None
    a = draw(hnp.arrays(dtype, shape, elements=elements))
    layout = draw(st.sampled_from(["c", "f", "strided", "readonly"]))
    if layout == "f":
        a = np.asfortranarray(a)
    elif layout == "strided" and a.ndim >= 1:
        a = np.repeat(a, 2, axis=-1)[..., ::2]
    elif layout == "readonly":
        a = a.copy()
        a.setflags(write=False)
    return a


@st.composite
def perturbed_poses(draw):
    """A valid pose with one entry replaced, or a reflection, or scaled."""
    m = valid_pose(draw(quaternions), draw(modest))
    kind = draw(st.sampled_from(["entry", "reflect", "scale", "last_row", "none"]))
    if kind == "entry":
        i, j = draw(st.integers(0, 3)), draw(st.integers(0, 3))
        m[i, j] = draw(floats)
    elif kind == "reflect":
        m[:3, 0] *= -1
    elif kind == "scale":
        with np.errstate(invalid="ignore", over="ignore"):
            m[:3, :3] *= draw(floats)
    elif kind == "last_row":
        m[3, draw(st.integers(0, 3))] = draw(floats)
    return m


def scipy_rotation(q):
    """scipy's Rotation of the quaternion (x, y, z, w), identity where scipy
    cannot normalise it."""
    with np.errstate(over="ignore", invalid="ignore"):
        ok = np.all(np.isfinite(q)) and 1e-150 < np.linalg.norm(q) < 1e150
    return Rotation.from_quat(q) if ok else Rotation.identity()


def scipy_rotations():
    return st.one_of(
        quaternions.map(scipy_rotation),
        st.integers(0, 3).map(lambda k: Rotation.random(k, random_state=k) if k else Rotation.random(random_state=1)),
        st.just(Rotation.from_euler("z", 180.0 + 1e-12, degrees=True)),
        st.just(Rotation.identity(2)),
    )


def junk():
    return st.one_of(
        st.none(),
        st.text(max_size=5),
        st.binary(max_size=5),
        st.integers(min_value=-(2**80), max_value=2**80),
        floats,
        st.booleans(),
        st.just(object()),
        st.just({"a": 1}),
        st.just(np.array("abc")),
        st.just(np.full((4, 4), "x")),
        st.just(np.full((4, 4), None, dtype=object)),
        st.just(np.eye(4, dtype=object)),
        st.just(np.eye(4).astype("U8")),
        st.just(np.ma.masked_array(np.eye(4), mask=np.eye(4))),
        st.just(np.datetime64("2020-01-01")),
    )


poses = st.one_of(
    st.none(),
    st.builds(valid_pose, quaternions, modest),
    st.builds(valid_pose, quaternions, st.lists(floats, min_size=3, max_size=3)),
    perturbed_poses(),
    numeric_arrays(),
    perturbed_poses().map(lambda m: m.tolist()),
    st.lists(floats, min_size=0, max_size=5),
    st.lists(st.lists(floats, min_size=4, max_size=4), min_size=4, max_size=4),
    scipy_rotations(),
    junk(),
)

tolerances = st.one_of(
    st.sampled_from([1e-6, 1e-3, 0.5, 0.999, 1.0, 0.0, -0.0, -1e-6, 1e-300, 2.0**-38, 2.0**-39, math.nan, math.inf, -math.inf]),
    floats,
    st.integers(min_value=-(2**70), max_value=2**70),
    st.just(10**400),
    st.just(np.float32(1e-3)),
    st.just(np.float64(1e-4)),
    st.just(np.int64(0)),
    st.just(np.array(1e-3)),
    st.just(np.array([1e-3])),
    junk(),
)

budgets = st.one_of(
    st.none(),
    st.sampled_from([0, 1, 2, 3, 17, 4096, 2**20, 2**63 - 1, 2**64 - 1, -1, -(2**70), 2**64, 2**70]),
    st.integers(min_value=0, max_value=100),
    st.just(np.int64(5)),
    st.just(np.uint8(3)),
    st.just(True),
    floats,
    st.text(max_size=3),
)


def budget_is_valid(budget):
    """Whether ``budget`` is one the docs accept: None or an integer in
    [1, 2**64) (``True`` is Python's integer 1)."""
    if budget is None:
        return True
    try:
        b = int(budget) if isinstance(budget, (int, np.integer)) else None
    except (TypeError, ValueError):
        return False
    return b is not None and 1 <= b < 2**64


def call(f, *args, **kwargs):
    """Calls ``f``: its result, or None when it raised an allowed
    exception. Any other exception fails the test with the arguments."""
    try:
        return f(*args, **kwargs)
    except ALLOWED as e:
        str(e)  # the message renders
        return None
    except BaseException as e:  # noqa: BLE001 - the point of the test
        pytest.fail(f"{f.__qualname__} raised {type(e).__name__}: {e} for args={args!r} kwargs={kwargs!r}")


def check_answer(r):
    """A MotionCheck that is consistent: free, or a bracket in [0, 1]."""
    if r is None:
        return
    assert isinstance(r, dymsum.MotionCheck)
    if r.free:
        assert r.t_contact is None and bool(r)
    else:
        assert 0.0 <= r.t_contact <= 1.0 and not bool(r)
        assert r.t_safe is None or 0.0 <= r.t_safe < r.t_contact


_CHECKERS = {}


def checker(budget=None):
    key = budget
    if key not in _CHECKERS:
        _CHECKERS[key] = dymsum.MotionChecker(BAR, OBSTACLES, budget=budget)
    return _CHECKERS[key]


# ---------------------------------------------------------------------------
# Motion functions


@FUZZ
@given(p0=poses, p1=poses, tol=tolerances)
def test_fuzz_checker_check_and_collides_at(p0, p1, tol):
    c = checker()
    check_answer(call(c.check, p0, p1, tol))
    check_answer(call(c.check, p0, p1))
    r = call(c.collides_at, p0)
    assert r is None or isinstance(r, bool)


@FUZZ
@given(p0=poses, p1=poses, tol=tolerances, budget=budgets)
def test_fuzz_check_motion_arguments(p0, p1, tol, budget):
    r = call(dymsum.check_motion, BAR, OBSTACLES, p0, p1, tol, budget=budget)
    check_answer(r)
    if r is not None:
        assert budget_is_valid(budget), f"budget {budget!r} accepted"


@FUZZ
@given(budget=budgets)
def test_fuzz_motion_checker_budget(budget):
    c = call(dymsum.MotionChecker, BAR, OBSTACLES, budget=budget)
    if c is not None:
        assert budget_is_valid(budget), f"budget {budget!r} accepted"
        assert c.budget == (4096 if budget is None else int(budget))


@st.composite
def pose_batches(draw):
    """(K, 4, 4) batches, valid or not, of matching or mismatched K."""
    k = draw(st.integers(0, 3))
    kind = draw(st.sampled_from(["valid", "one bad", "array", "list", "junk"]))
    if kind == "valid":
        return np.stack([valid_pose(draw(quaternions), draw(modest)) for _ in range(k)]) if k else np.zeros((0, 4, 4))
    if kind == "one bad":
        ps = [valid_pose(draw(quaternions), draw(modest)) for _ in range(k)] + [draw(perturbed_poses())]
        return np.stack(ps)
    if kind == "array":
        return draw(numeric_arrays())
    if kind == "list":
        return [draw(poses) for _ in range(k)]
    return draw(junk())


@FUZZ
@given(p0=pose_batches(), p1=pose_batches(), tol=tolerances, budget=budgets)
def test_fuzz_check_many_and_check_motions(p0, p1, tol, budget):
    for r in (
        call(checker().check_many, p0, p1, tol),
        call(dymsum.check_motions, BAR, OBSTACLES, p0, p1, tol, budget=budget),
    ):
        if r is None:
            continue
        assert isinstance(r, dymsum.MotionChecks)
        free = np.asarray(r.free)
        assert len(r) == len(free)
        t_contact = np.asarray(r.t_contact)
        hits = t_contact[~free]
        assert np.all((hits >= 0.0) & (hits <= 1.0))


@FUZZ
@given(q=poses, t=st.one_of(modest, st.lists(floats, min_size=0, max_size=4), numeric_arrays(), junk()))
def test_fuzz_pose(q, t):
    m = call(dymsum.pose, q, t)
    if m is not None:
        m = np.asarray(m)
        assert m.shape == (4, 4) and m.dtype == np.float64
        assert np.all(np.isfinite(m)), m
        assert np.array_equal(m[3], [0.0, 0.0, 0.0, 1.0])
        r = m[:3, :3]
        assert np.allclose(r.T @ r, np.eye(3), atol=1e-6)
    m = call(dymsum.pose, q)
    m = call(dymsum.pose, translation=t)


@FUZZ
@given(q=quaternions, t=modest, budget=st.sampled_from([None, 1, 2, 5, 50]))
def test_fuzz_modest_motions_through_pose_are_answered(q, t, budget):
    """Valid poses built by ``dymsum.pose`` from extreme quaternion
    components: an answer, or MotionUndecided (grazing or budget), never
    another error."""
    p0 = call(dymsum.pose, np.asarray(q, float), [0.0, 0.0, 0.0])
    if p0 is None:
        # Only a zero or non-finite quaternion is refused.
        assert not (np.all(np.isfinite(q)) and np.any(np.asarray(q) != 0.0)), q
        return
    p1 = dymsum.pose(Rotation.from_euler("z", 90, degrees=True), t)
    try:
        r = dymsum.check_motion(BAR, OBSTACLES, p0, p1, 1e-6, budget=budget)
    except dymsum.MotionUndecided as e:
        assert 0.0 <= e.t_safe <= 1.0
        assert e.budget_exhausted or e.t is not None
        return
    check_answer(r)


# ---------------------------------------------------------------------------
# Mesh readers

_FILES = {}


def written(ext):
    """A small mesh written by ``dymsum.save`` in each format."""
    if ext not in _FILES:
        import tempfile

        verts = np.array([[0, 0, 0], [1.5, -0.0, 1e-300], [0, 2, 5e-324], [0.25, 0.25, -3.0], [1e30, -1e30, 7.0]], float)
        faces = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]]
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "m." + ext)
            dymsum.save(path, verts, np.array(faces))
            with open(path, "rb") as f:
                _FILES[ext] = f.read()
    return _FILES[ext]


TOKENS = [b"999999999", b"18446744073709551616", b"-1", b"nan", b"inf", b"1e400", b"0", b"2", b"\n", b"#", b"\\", b"/", b"f 1 2", b"v", b"OFF", b"end_header", b"solid", b"\xff", b"\x00"]


@st.composite
def mesh_files(draw):
    ext = draw(st.sampled_from(["off", "obj", "ply", "stl", "xyz", "OFF"]))
    if draw(st.booleans()):
        return ext, draw(st.binary(max_size=512))
    data = bytearray(written(ext.lower() if ext.lower() != "xyz" else "off"))
    for _ in range(draw(st.integers(1, 4))):
        op = draw(st.sampled_from(["flip", "cut", "insert", "overwrite"]))
        pos = draw(st.integers(0, len(data)))
        if op == "flip" and data:
            data[min(pos, len(data) - 1)] ^= 1 << draw(st.integers(0, 7))
        elif op == "cut":
            del data[pos:]
        elif op == "insert":
            data[pos:pos] = b" " + draw(st.sampled_from(TOKENS)) + b" "
        elif op == "overwrite":
            w = draw(st.sampled_from([b"\xff\xff\xff\xff", b"\x00\x00\xc0\x7f", b"\x00\x00\x80\x7f", b"\x02"]))
            data[pos : pos + len(w)] = w
    return ext, bytes(data)


@FUZZ
@given(f=mesh_files())
def test_fuzz_mesh_files_load_or_raise_value_or_os_error(tmp_path, f):
    ext, data = f
    path = tmp_path / ("m." + ext)
    path.write_bytes(data)
    for reader in (dymsum.load, dymsum.read_mesh_bodies):
        for arg in (str(path), path):
            try:
                r = reader(arg)
            except (ValueError, OSError) as e:
                assert "m." in str(e) or ext.lower() == "xyz", e
                continue
            except BaseException as e:  # noqa: BLE001 - the point of the test
                pytest.fail(f"{reader.__name__} raised {type(e).__name__}: {e} on {data!r}")
            if reader is dymsum.read_mesh_bodies:
                for name, v, faces in r:
                    v, faces = np.asarray(v), np.asarray(faces)
                    assert v.ndim == 2 and v.shape[1] == 3 and np.all(np.isfinite(v))
                    assert faces.size == 0 or (faces.min() >= 0 and faces.max() < len(v))
            else:
                assert np.all(np.isfinite(r.vertices))


@FUZZ
@given(arg=junk())
def test_fuzz_mesh_reader_path_arguments(arg):
    for reader in (dymsum.load, dymsum.read_mesh_bodies):
        try:
            reader(arg)
        except (ValueError, TypeError, OSError):
            pass
        except BaseException as e:  # noqa: BLE001 - the point of the test
            pytest.fail(f"{reader.__name__}({arg!r}) raised {type(e).__name__}: {e}")


# ---------------------------------------------------------------------------
# Found by this fuzz: integers beyond what the Rust side extracts (a budget
# below 0 or from 2**64, a tolerance or translation beyond float range)
# raised PyO3's OverflowError instead of a ValueError naming the argument.


@pytest.mark.parametrize("budget", [-1, -(2**70), 2**64, 2**70])
def test_regression_budget_out_of_u64_range_is_value_error(budget):
    with pytest.raises(ValueError, match="budget"):
        dymsum.MotionChecker(BAR, OBSTACLES, budget=budget)
    with pytest.raises(ValueError, match="budget"):
        dymsum.check_motion(BAR, OBSTACLES, None, None, 1e-6, budget=budget)


def test_regression_integer_tolerance_beyond_float_is_value_error():
    with pytest.raises(ValueError, match="tolerance"):
        checker().check(None, None, 10**400)


def test_regression_integer_translation_beyond_float_is_value_error():
    with pytest.raises(ValueError, match="translation"):
        dymsum.pose(None, [10**400, 0, 0])
