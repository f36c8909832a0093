"""C-obstacle maps (issue 22): ``dymsum.cobstacle_map`` against the slices
and slabs of ``cobstacle_slices`` (every mesh vertex inside every
half-space, as floats, no tolerance; the meshes equal), the container
round trip (``save`` / ``load_cobstacle_map``, ``np.load(...,
allow_pickle=False)``), the CLI's ``--format npz`` container, identical
results bit for bit with ``client=None`` and Dask LocalClusters of threads
and of processes, pickling, and a failing task."""

import os
import pickle
import subprocess

import numpy as np
import pytest
from conftest import CUBE, cli
from scipy.spatial.transform import Rotation

import dymsum

ROBOT = dymsum.ConvexUnion(["gs1", "box:1,0.5,0.5"])
OBSTACLES = {"block": "box:2,1,1", "ball": dymsum.load("gs1").vertices + [3.0, 0.0, 0.0]}
TURN = Rotation.from_rotvec(np.outer(np.linspace(0, 2 * np.pi, 21)[:-1], [1, 2, 3]) / np.sqrt(14))


def same_arrays(a, b):
    assert sorted(a.arrays) == sorted(b.arrays)
    for k in a.arrays:
        x, y = np.asarray(a.arrays[k]), np.asarray(b.arrays[k])
        assert x.dtype == y.dtype and x.shape == y.shape, k
        if x.dtype.kind == "f":
            assert np.array_equal(x.view(np.int64), y.view(np.int64)), k
        else:
            assert np.array_equal(x, y), k


def test_halfspaces_hold_every_slice_and_touch_it():
    m = dymsum.cobstacle_map(ROBOT, OBSTACLES, TURN, block=7)
    assert (m.robot_pieces, m.obstacle_pieces) == (["r0", "r1"], ["block", "ball"])
    assert m.form == "halfspaces" and not m.certified and len(m) == 4 * 20
    q = TURN.as_quat()
    np.testing.assert_allclose(np.abs((m.orientations * q).sum(axis=1)), 1.0, rtol=1e-14)
    for i, piece in enumerate(ROBOT.pieces):
        for j, name in enumerate(["block", "ball"]):
            slices = dymsum.cobstacle_slices(piece, OBSTACLES[name], TURN)
            for k, (v, _) in enumerate(slices):
                n, d = m[i, name, k]
                assert n.shape == (len(d), 3)
                np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0, rtol=1e-12)
                dots = v @ n.T
                assert (dots <= d).all(), (i, j, k)
                # Each plane touches the slice within rounding.
                scale = np.abs(v).max()
                assert (d - dots.max(axis=0) <= 64 * np.finfo(float).eps * scale).all()
    with pytest.raises(KeyError):
        m[0, "nothing", 0]
    with pytest.raises(IndexError):
        m[0, 0, 20]


def test_meshes_equal_the_slices_and_the_container_round_trips(tmp_path):
    m = dymsum.cobstacle_map(ROBOT, OBSTACLES, TURN[:5], form="mesh", block=2)
    for i, piece in enumerate(ROBOT.pieces):
        for j, name in enumerate(["block", "ball"]):
            slices = dymsum.cobstacle_slices(piece, OBSTACLES[name], TURN[:5], polygons=True)
            for k, (v, faces) in enumerate(slices):
                mv, mf = m[i, j, k]
                np.testing.assert_array_equal(mv, v)
                assert [f.tolist() for f in mf] == [f.tolist() for f in faces]
    path = tmp_path / "map.npz"
    m.save(path)
    assert os.listdir(tmp_path) == ["map.npz"]
    with np.load(path, allow_pickle=False) as z:
        assert str(z["format"]) == "dymsum-cobstacle-map" and str(z["form"]) == "mesh"
        assert z["orientations_xyzw"].shape == (5, 4)
    same_arrays(dymsum.load_cobstacle_map(path), m)


def test_certified_slabs_match_cobstacle_slices():
    closed = Rotation.from_rotvec(np.outer(np.linspace(0, 2 * np.pi, 17), [0, 0, 1]))
    m = dymsum.cobstacle_map("box:4,0.2,0.2", ["box"], closed, certified=True, block=5)
    assert m.certified and m.slices_per_pair == 16
    slabs = dymsum.cobstacle_slices("box:4,0.2,0.2", "box", closed, certified=True)
    for k, s in enumerate(slabs):
        n, d = m[0, 0, k]
        np.testing.assert_array_equal(n, s.normals)
        np.testing.assert_array_equal(d, s.offsets)
    with pytest.raises(ValueError, match="half-spaces only"):
        dymsum.cobstacle_map("box", "box", closed, form="mesh", certified=True)


def test_blocks_and_workers_do_not_change_the_result():
    a = dymsum.cobstacle_map(ROBOT, OBSTACLES, TURN, block=1)
    b = dymsum.cobstacle_map(ROBOT, OBSTACLES, TURN, block=256, workers=1)
    same_arrays(a, b)


def test_polytopes_and_unions_pickle():
    p = dymsum.Polytope(CUBE * [1, 2, 3])
    q = pickle.loads(pickle.dumps(p))
    assert isinstance(q, dymsum.Polytope)
    assert sorted(map(tuple, q.vertices)) == sorted(map(tuple, p.vertices))
    assert q.volume == p.volume == 6.0
    u = pickle.loads(pickle.dumps(ROBOT))
    assert isinstance(u, dymsum.ConvexUnion) and len(u) == 2
    assert u.pieces[1].volume == ROBOT.pieces[1].volume


def test_a_failing_task_names_its_pair_and_block_and_writes_nothing(tmp_path):
    # A piece far beyond f64's range for its offsets: the half-spaces overflow.
    huge = CUBE * 1e308
    with pytest.raises(dymsum.CObstacleMapError, match=r"pair \(r0, o1\), block 0 \(orientations 0\.\.8\)") as e:
        dymsum.cobstacle_map(CUBE, [CUBE, huge], TURN, block=8)
    assert e.value.__cause__ is not None
    m = dymsum.cobstacle_map(CUBE, CUBE, TURN[:3])
    with pytest.raises(OSError):
        m.save(tmp_path / "missing" / "map.npz")
    assert os.listdir(tmp_path) == []


def test_the_cli_container_loads_with_numpy_and_matches_the_library(tmp_path):
    out = tmp_path / "m"
    subprocess.run(
        [cli(), "cobst", "gs1+box:1,0.5,0.5", "box:2,1,1", "--axis", "0,0,1", "--slices", "12", "--format", "npz", "--out", str(out)],
        check=True,
        capture_output=True,
    )
    with np.load(out / "map.npz", allow_pickle=False) as z:
        assert z["orientations_xyzw"].shape == (12, 4)
        assert z["pairs"].tolist() == [[0, 0], [1, 0]]
        assert z["robot_pieces"].tolist() == ["r0", "r1"]
    m = dymsum.load_cobstacle_map(out / "map.npz")
    turn = Rotation.from_quat(m.orientations)
    mine = dymsum.cobstacle_map(["gs1", "box:1,0.5,0.5"], ["box:2,1,1"], turn)
    for i in range(2):
        for k in range(12):
            n, d = m[i, 0, k]
            v, _ = dymsum.cobstacle_slices(["gs1", "box:1,0.5,0.5"][i], "box:2,1,1", turn[k])[0]
            assert (v @ n.T <= d).all()
            # The same planes as the library's (the pieces are the same
            # hulls; their vertex order, and so the last bits, may differ).
            np.testing.assert_allclose(np.sort(d), np.sort(mine[i, 0, k][1]), rtol=1e-12, atol=1e-12)


def dask_or_skip():
    try:
        import distributed
    except ImportError:
        if os.environ.get("DYMSUM_REQUIRE_DASK") == "1":
            pytest.fail("DYMSUM_REQUIRE_DASK=1 but dask.distributed is not installed")
        pytest.skip("dask.distributed is not installed (pip install ./python[dask])")
    return distributed


@pytest.mark.parametrize("processes", [False, True])
def test_dask_gives_the_same_map_bit_for_bit(processes):
    distributed = dask_or_skip()
    local = dymsum.cobstacle_map(ROBOT, OBSTACLES, TURN, block=6)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=processes, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            remote = dymsum.cobstacle_map(ROBOT, OBSTACLES, TURN, client=client, block=6)
            same_arrays(local, remote)
            # Maps one after the other on one client (the same pieces
            # scattered again while the first map's are released).
            for _ in range(3):
                same_arrays(local, dymsum.cobstacle_map(ROBOT, OBSTACLES, TURN, client=client, block=6))
            with pytest.raises(dymsum.CObstacleMapError, match=r"pair \(r0, o1\), block 0"):
                dymsum.cobstacle_map(CUBE, [CUBE, CUBE * 1e308], TURN, client=client, block=16)


@pytest.mark.parametrize("shared", ["tmp", False])
def test_dask_blocks_come_back_as_files_or_in_memory_and_nothing_is_left(tmp_path, shared):
    distributed = dask_or_skip()
    local = dymsum.cobstacle_map(ROBOT, OBSTACLES, TURN, block=3)
    shared_dir = tmp_path if shared == "tmp" else False
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            same_arrays(local, dymsum.cobstacle_map(ROBOT, OBSTACLES, TURN, client=client, block=3, shared_dir=shared_dir))
            assert os.listdir(tmp_path) == []
            with pytest.raises(dymsum.CObstacleMapError, match=r"pair \(r0, o1\), block 0 \(orientations 0\.\.8\)"):
                dymsum.cobstacle_map(CUBE, [CUBE, CUBE * 1e308], TURN, client=client, block=8, shared_dir=shared_dir)
    assert os.listdir(tmp_path) == []


def test_a_worker_that_does_not_see_the_folder_sends_its_blocks_through_dask(tmp_path):
    from dymsum import _maps

    _, rv = _maps._pieces(ROBOT, "r")
    _, ov = _maps._pieces(OBSTACLES, "o")
    q = np.asarray(_maps._rotations_xyzw(TURN))
    units = [(0, 1, 0, 5), (1, 0, 5, 9)]
    (tmp_path / "token").write_text("abc", encoding="ascii")
    kind, blocks = _maps._remote_task(rv, ov, q, units, "halfspaces", False, str(tmp_path), "xyz", "t.npy")
    assert kind == "arrays" and os.listdir(tmp_path) == ["token"]
    kind, name = _maps._remote_task(rv, ov, q, units, "halfspaces", False, str(tmp_path), "abc", "t.npy")
    assert (kind, name) == ("file", "t.npy")
    read = _maps._read_blocks(str(tmp_path), name, len(units), 3)
    assert os.listdir(tmp_path) == ["token"]
    for x, y in zip(blocks, read):
        for a, b in zip(x, y):
            assert a.dtype == b.dtype and np.array_equal(a.view(np.int64) if a.dtype.kind == "f" else a, b.view(np.int64) if b.dtype.kind == "f" else b)


# --- Issue 26 §5: map files are validated whole, with bounded memory -------


def small_arrays(form="halfspaces", certified=False):
    """The arrays of a small valid map (two pairs, three slices)."""
    turn = TURN[:4] if certified else TURN[:3]
    return {k: np.asarray(v) for k, v in dymsum.cobstacle_map(ROBOT, ["box"], turn, form=form, certified=certified).arrays.items()}


def write_zip(path, entries, compression=None):
    """An .npz of `entries` [(name, array or raw bytes)], names repeated or
    not, as given."""
    import io
    import warnings
    import zipfile

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # zipfile warns on duplicate names
        with zipfile.ZipFile(path, "w", compression or zipfile.ZIP_STORED) as z:
            for name, a in entries:
                if isinstance(a, bytes):
                    z.writestr(name + ".npy", a)
                else:
                    buf = io.BytesIO()
                    np.lib.format.write_array(buf, np.asanyarray(a), allow_pickle=False)
                    z.writestr(name + ".npy", buf.getvalue())
    return path


def with_field(tmp_path, name, value, form="halfspaces"):
    arrays = small_arrays(form)
    if value is None:
        del arrays[name]
    else:
        arrays[name] = value
    return write_zip(tmp_path / "map.npz", list(arrays.items()))


def refused(path, *needles, kind=ValueError):
    with pytest.raises(kind) as e:
        dymsum.load_cobstacle_map(path)
    msg = str(e.value)
    assert str(path) in msg, msg
    for n in needles:
        assert n in msg, msg
    assert "pickle" not in msg, msg
    return msg


def test_a_valid_map_of_either_form_round_trips_through_the_validating_reader(tmp_path):
    for form, certified in [("halfspaces", False), ("halfspaces", True), ("mesh", False)]:
        m = dymsum.CObstacleMap(small_arrays(form, certified))
        m.save(tmp_path / f"{form}{certified}.npz")
        same_arrays(dymsum.load_cobstacle_map(tmp_path / f"{form}{certified}.npz"), m)
    # An archive of deflated entries and big-endian arrays is as good.
    arrays = small_arrays()
    arrays["normals"] = arrays["normals"].astype(">f8")
    import zipfile

    path = write_zip(tmp_path / "deflated.npz", list(arrays.items()), zipfile.ZIP_DEFLATED)
    m = dymsum.load_cobstacle_map(path)
    np.testing.assert_array_equal(m.arrays["normals"], small_arrays()["normals"])


def test_a_reversed_plane_start_is_refused(tmp_path):
    # Before issue 26 it loaded and answered empty slices flagged certified.
    a = small_arrays()
    ps = a["plane_start"].copy()
    ps[1:-1] = ps[1:-1][::-1]
    refused(with_field(tmp_path, "plane_start", ps), "'plane_start'", "non-decreasing")


def test_offsets_shorter_than_normals_are_refused(tmp_path):
    refused(with_field(tmp_path, "offsets", small_arrays()["offsets"][:-1]), "'offsets'", "normals")


def test_nan_normals_are_refused(tmp_path):
    n = small_arrays()["normals"].copy()
    n[3, 1] = np.nan
    refused(with_field(tmp_path, "normals", n), "'normals'", "not finite")


def test_string_normals_are_refused(tmp_path):
    n = small_arrays()["normals"].astype(str)
    refused(with_field(tmp_path, "normals", n), "'normals'", "dtype")


def test_version_99_is_refused(tmp_path):
    refused(with_field(tmp_path, "version", np.array(99)), "'version'", "99", "version 1")


def test_duplicate_zip_entries_are_refused(tmp_path):
    arrays = small_arrays()
    entries = list(arrays.items()) + [("offsets", arrays["offsets"] * 2)]
    refused(write_zip(tmp_path / "map.npz", entries), "'offsets'", "twice")


def test_a_zip_bomb_is_refused_without_inflating_it(tmp_path):
    import tracemalloc
    import zipfile

    # `offsets` claims its true shape but the entry inflates to 64 MiB more
    # (zeros deflate about 1000:1: a 64 KiB entry).
    arrays = small_arrays()
    head = io_npy(arrays["offsets"])
    entries = [(k, v) for k, v in arrays.items() if k != "offsets"]
    entries.append(("offsets", head + bytes(64 << 20)))
    path = write_zip(tmp_path / "bomb.npz", entries, zipfile.ZIP_DEFLATED)
    assert path.stat().st_size < 1 << 20
    tracemalloc.start()
    try:
        refused(path, "'offsets'", "more data")
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 8 << 20, peak
    # A header that lies about the shape (normals and offsets agreeing,
    # plane_start not) is refused before its data is read.
    n = 1 << 26
    entries = [(k, v) for k, v in arrays.items() if k not in ("offsets", "normals")]
    entries.append(("normals", npy_header(np.float64, (n, 3)) + bytes(1 << 16)))
    entries.append(("offsets", npy_header(np.float64, (n,)) + bytes(1 << 16)))
    path = write_zip(tmp_path / "bomb2.npz", entries, zipfile.ZIP_DEFLATED)
    tracemalloc.start()
    try:
        refused(path, "'plane_start'")
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 8 << 20, peak


def io_npy(a):
    import io

    buf = io.BytesIO()
    np.lib.format.write_array(buf, a, allow_pickle=False)
    return buf.getvalue()[: len(buf.getvalue()) - a.nbytes]


def npy_header(dtype, shape):
    import io

    buf = io.BytesIO()
    np.lib.format.write_array_header_1_0(buf, {"descr": np.dtype(dtype).str, "fortran_order": False, "shape": shape})
    return buf.getvalue()


def test_a_fifo_is_refused_without_blocking(tmp_path):
    import threading

    fifo = tmp_path / "map.npz"
    os.mkfifo(fifo)
    box = {}

    def load():
        try:
            dymsum.load_cobstacle_map(fifo)
        except BaseException as e:  # noqa: BLE001 - reported below
            box["e"] = e

    t = threading.Thread(target=load, daemon=True)
    t.start()
    t.join(10)
    if t.is_alive():
        # Unblock the reader before failing.
        os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
        pytest.fail("load_cobstacle_map blocked on a FIFO")
    assert isinstance(box.get("e"), ValueError), box
    assert str(fifo) in str(box["e"]) and "not a regular file" in str(box["e"])


def test_a_truncated_zip_is_a_value_error_naming_the_path(tmp_path):
    dymsum.CObstacleMap(small_arrays()).save(tmp_path / "m.npz")
    data = (tmp_path / "m.npz").read_bytes()
    for cut in (len(data) // 2, len(data) - 30, 10):
        p = tmp_path / f"cut{cut}.npz"
        p.write_bytes(data[:cut])
        refused(p)


def test_an_empty_file_is_a_value_error_naming_the_path(tmp_path):
    (tmp_path / "empty.npz").write_bytes(b"")
    refused(tmp_path / "empty.npz", "not a dymsum C-obstacle map")


def test_a_missing_field_is_a_value_error_naming_the_path_and_field(tmp_path):
    refused(with_field(tmp_path, "offsets", None), "'offsets'", "missing")
    refused(with_field(tmp_path, "corners", None, form="mesh"), "'corners'", "missing")


def test_a_text_file_is_not_a_map_and_gets_no_pickle_advice(tmp_path):
    (tmp_path / "notes.npz").write_text("just some text\n" * 50)
    refused(tmp_path / "notes.npz", "not a dymsum C-obstacle map")
    # A plain .npy (numpy would offer pickle for it too), another program's
    # .npz, a directory and a missing file.
    np.save(tmp_path / "a.npy", np.arange(3))
    refused(tmp_path / "a.npy", "not a dymsum C-obstacle map")
    np.savez(tmp_path / "other.npz", x=np.arange(3))
    refused(tmp_path / "other.npz", "not a dymsum C-obstacle map")
    refused(tmp_path, "not a regular file")
    with pytest.raises(OSError, match="nothing.npz"):
        dymsum.load_cobstacle_map(tmp_path / "nothing.npz")


def test_object_arrays_pairs_corners_and_flags_are_checked(tmp_path):
    import io

    buf = io.BytesIO()
    np.lib.format.write_array(buf, np.array([{"a": 1}], dtype=object), allow_pickle=True)
    arrays = small_arrays()
    entries = [(k, v) for k, v in arrays.items() if k != "robot_pieces"] + [("robot_pieces", buf.getvalue())]
    refused(write_zip(tmp_path / "obj.npz", entries), "'robot_pieces'", "object")
    pairs = small_arrays()["pairs"].copy()
    pairs[1, 0] = 7
    refused(with_field(tmp_path, "pairs", pairs), "'pairs'", "out of range")
    pairs[1] = pairs[0]
    refused(with_field(tmp_path, "pairs", pairs), "'pairs'", "twice")
    corners = small_arrays("mesh")["corners"].copy()
    corners[5] = 10**6
    refused(with_field(tmp_path, "corners", corners, form="mesh"), "'corners'")
    refused(with_field(tmp_path, "form", np.array("voxels")), "'form'")
    refused(with_field(tmp_path, "certified", np.array(2)), "'certified'")
    refused(with_field(tmp_path, "slices_per_pair", np.array(2)), "'slices_per_pair'")
    refused(with_field(tmp_path, "format", np.array("something else")), "not a dymsum C-obstacle map")
    fs = small_arrays("mesh")["face_start"].copy()
    fs[0] = 1
    refused(with_field(tmp_path, "face_start", fs, form="mesh"), "'face_start'", "not 0")


def test_a_large_genuine_map_still_loads(tmp_path):
    # 200 000 planes per pair: about 40 MB of arrays.
    n = 100_000
    a = small_arrays()
    per = int(a["slices_per_pair"])
    slices = len(a["pairs"]) * per
    a["plane_start"] = np.linspace(0, n * slices, slices + 1).astype(np.int64)
    rng = np.random.default_rng(1)
    normals = rng.normal(size=(n * slices, 3))
    a["normals"] = normals / np.linalg.norm(normals, axis=1)[:, None]
    a["offsets"] = rng.uniform(1, 2, size=n * slices)
    dymsum.CObstacleMap(a).save(tmp_path / "big.npz")
    same_arrays(dymsum.load_cobstacle_map(tmp_path / "big.npz"), dymsum.CObstacleMap(a))


# --- Issue 26 §6: CObstacleMap.save loses nothing on a kill -----------------


class FailAfter:
    """A file object that fails (as a full disk or a kill would stop it)
    once `left` more bytes have been written."""

    def __init__(self, f, left):
        self._f, self._left = f, left

    def write(self, b):
        b = bytes(b)
        if len(b) > self._left:
            self._f.write(b[: self._left])
            self._left = 0
            raise OSError(28, "injected failure: no space left")
        self._left -= len(b)
        return self._f.write(b)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self._f.close()

    def __getattr__(self, name):
        return getattr(self._f, name)


def test_save_failing_after_k_bytes_for_every_k_keeps_the_old_map_and_leaves_no_temp(tmp_path, monkeypatch):
    from dymsum import _maps_io

    path = tmp_path / "map.npz"
    old = dymsum.CObstacleMap(small_arrays())
    old.save(path)
    before = path.read_bytes()
    new = dymsum.CObstacleMap({k: np.asarray(v) for k, v in dymsum.cobstacle_map("box", "box", TURN[:1]).arrays.items()})
    new.save(tmp_path / "new.npz")
    size = (tmp_path / "new.npz").stat().st_size
    os.unlink(tmp_path / "new.npz")
    real = _maps_io.open_temp
    for k in range(size):
        monkeypatch.setattr(_maps_io, "open_temp", lambda fd, k=k: FailAfter(real(fd), k))
        with pytest.raises(OSError):
            new.save(path)
        assert path.read_bytes() == before, k
        assert os.listdir(tmp_path) == ["map.npz"], k
    monkeypatch.setattr(_maps_io, "open_temp", real)
    new.save(path)
    same_arrays(dymsum.load_cobstacle_map(path), new)
    assert os.listdir(tmp_path) == ["map.npz"]


def test_save_names_its_temp_file_with_its_pid_and_removes_only_dead_owners(tmp_path, monkeypatch):
    from dymsum import _maps_io

    child = subprocess.Popen(["true"])
    child.wait()
    dead, live = child.pid, os.getpid()
    stale = tmp_path / f".map.tmp-{dead}-ab12_x.npz"
    mine = tmp_path / f".map.tmp-{live}-0.npz"
    other = tmp_path / f".other.tmp-{dead}-0.npz"
    for p in (stale, mine, other):
        p.write_bytes(b"partial")
    seen = []
    real = _maps_io.open_temp

    def spy(fd):
        seen.append(os.readlink(f"/proc/self/fd/{fd}") if os.path.exists("/proc/self/fd") else "")
        return real(fd)

    monkeypatch.setattr(_maps_io, "open_temp", spy)
    dymsum.CObstacleMap(small_arrays()).save(tmp_path / "map.npz")
    if seen[0]:
        assert os.path.basename(seen[0]).startswith(f".map.tmp-{live}-") and seen[0].endswith(".npz"), seen
    left = sorted(os.listdir(tmp_path))
    if not os.path.exists(f"/proc/{dead}"):
        assert left == sorted(["map.npz", mine.name, other.name]), left
    assert mine.exists() and other.exists()


# --- Issue 26 §7: every Dask worker dying is said so, with the pair/block ---


class _LostFuture:
    def __init__(self, exc):
        self.exc = exc

    def result(self):
        raise self.exc


class _LosingClient:
    """A stand-in for a Dask client whose cluster lost every task with
    `exc` (what `distributed` raises when the workers died)."""

    def __init__(self, exc):
        self.exc = exc

    def scatter(self, x, **_):
        return x

    def nthreads(self):
        return {"w": 1}

    def submit(self, *_, **__):
        return _LostFuture(self.exc)

    def cancel(self, _):
        pass


def test_a_task_the_cluster_forgot_or_whose_workers_died_says_so():
    from concurrent.futures import CancelledError

    class FutureCancelledError(CancelledError):
        def __str__(self):
            return "task-1 cancelled for reason: already forgotten."

    class KilledWorker(Exception):
        pass

    for exc, words in [
        (FutureCancelledError(), "workers died"),
        (KilledWorker("task-1", None, 3), "workers running this task died"),
    ]:
        with pytest.raises(dymsum.CObstacleMapError) as e:
            dymsum.cobstacle_map(ROBOT, OBSTACLES, TURN, client=_LosingClient(exc), block=8, shared_dir=False)
        msg = str(e.value)
        assert words in msg and "pair (r0, block), block 0 (orientations 0..8)" in msg, msg
        assert e.value.__cause__ is exc


def test_dask_every_worker_killed_mid_map_says_the_workers_died():
    distributed = dask_or_skip()
    import signal

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:

            class KillAfterScatter:
                """The client, with every worker process SIGKILLed once the
                pieces are scattered (before any task runs)."""

                def __getattr__(self, name):
                    return getattr(client, name)

                def nthreads(self):
                    for pid in client.run(os.getpid).values():
                        os.kill(pid, signal.SIGKILL)
                    return client.nthreads()

            with pytest.raises(dymsum.CObstacleMapError) as e:
                dymsum.cobstacle_map(ROBOT, OBSTACLES, TURN, client=KillAfterScatter(), block=8)
            msg = str(e.value)
            assert "lost this task: its workers died" in msg and "pair (r0, block), block 0" in msg, msg


# --- Issue 34: map files are read and written by dymsum-io (Rust) ----------


def test_a_map_numpy_saved_zip64_headers_fortran_order_loads_the_same(tmp_path):
    # np.savez writes ZIP64 local headers (as CObstacleMap.save did before
    # issue 34); a Fortran-ordered and a narrower integer array read in C
    # order as int64/float64.
    for form in ("halfspaces", "mesh"):
        m = dymsum.CObstacleMap(small_arrays(form))
        np.savez(tmp_path / f"{form}.npz", **m.arrays)
        same_arrays(dymsum.load_cobstacle_map(tmp_path / f"{form}.npz"), m)
    arrays = small_arrays()
    arrays["normals"] = np.asfortranarray(arrays["normals"])
    arrays["pairs"] = np.asfortranarray(arrays["pairs"].astype(np.int16))
    assert not arrays["normals"].flags.c_contiguous
    path = write_zip(tmp_path / "fortran.npz", list(arrays.items()))
    same_arrays(dymsum.load_cobstacle_map(path), dymsum.CObstacleMap(small_arrays()))


def test_save_refuses_a_map_that_load_would_refuse_and_writes_nothing(tmp_path):
    for field, value, needles in [
        ("plane_start", small_arrays()["plane_start"][::-1].copy(), ["'plane_start'"]),
        ("normals", np.full_like(small_arrays()["normals"], np.nan), ["'normals'", "not finite"]),
        ("pairs", small_arrays()["pairs"].astype(np.uint64), ["'pairs'", "dtype <u8"]),
        ("extra", np.arange(3), ["unexpected entry 'extra.npy'"]),
    ]:
        arrays = small_arrays()
        arrays[field] = value
        with pytest.raises(ValueError) as e:
            dymsum.CObstacleMap(arrays).save(tmp_path / "map.npz")
        for n in [str(tmp_path / "map.npz")] + needles:
            assert n in str(e.value), str(e.value)
        assert os.listdir(tmp_path) == []


def test_the_map_readers_fields_are_dymsum_ios():
    from dymsum import _maps

    assert _maps._KINDS["normals"] == ("f", 2) and _maps._KINDS["format"] == ("U", 0)
    assert len(_maps._KINDS) == 17
