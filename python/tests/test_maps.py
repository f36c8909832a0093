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
from pathlib import Path

import numpy as np
import pytest
from conftest import CUBE
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


def cli():
    exe = os.environ.get("DYMSUM_CLI") or str(Path(__file__).resolve().parents[2] / "target" / "release" / "dymsum")
    if not os.path.isfile(exe):
        if os.environ.get("DYMSUM_REQUIRE_CLI") == "1":
            pytest.fail(f"DYMSUM_REQUIRE_CLI=1 but no CLI at {exe}")
        pytest.skip("the dymsum CLI is not built (cargo build --release -p dymsum-cli)")
    return exe


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
