"""C-obstacle maps: every robot piece against every obstacle piece over many
orientations, split into tasks (one piece pair × one block of consecutive
orientations, DYMSUM inside a block) on a local thread pool or a Dask
cluster, and one NumPy container for the whole map (issue 22 §2).

The container is the one ``dymsum cobst --format npz`` writes: plain arrays
only (``np.load(path, allow_pickle=False)``), the layout documented in
docs/PYTHON.md and in the Rust crate ``dymsum_io::cmap``.
"""

from __future__ import annotations

import os
import secrets
import shutil
import tempfile
from concurrent.futures import ThreadPoolExecutor
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ._dymsum import ConvexUnion, Polytope, _cobstacle_block, _rotations_xyzw

FORMAT = "dymsum-cobstacle-map"


class CObstacleMapError(RuntimeError):
    """A task of :func:`cobstacle_map` failed; the message names its piece
    pair and block of orientations, and the cause is chained."""


def _pieces(body: Any, prefix: str) -> Tuple[List[str], List[np.ndarray]]:
    """Piece names and vertex arrays of a body: a ``ConvexUnion``, a mapping
    name → shape, a list of shapes, or one shape."""
    if isinstance(body, Mapping):
        names = [str(k) for k in body]
        shapes = list(body.values())
    elif isinstance(body, ConvexUnion):
        shapes = list(body.pieces)
        names = [f"{prefix}{i}" for i in range(len(shapes))]
    elif isinstance(body, (list, tuple)) and not _is_vertices_faces(body):
        shapes = list(body)
        names = [f"{prefix}{i}" for i in range(len(shapes))]
    else:
        shapes = [body]
        names = [f"{prefix}0"]
    if not shapes:
        raise ValueError("cobstacle_map: a body has no pieces")
    # Every task gets the pieces' hull vertices: the same input whether it
    # runs here or in another process, so the results are identical.
    verts = [np.array(Polytope(s).vertices) for s in shapes]
    return names, verts


def _is_vertices_faces(obj: Sequence[Any]) -> bool:
    return (
        len(obj) == 2
        and isinstance(obj[0], np.ndarray)
        and isinstance(obj[1], np.ndarray)
        and obj[1].dtype.kind in "iu"
    )


def _task(robot: np.ndarray, obstacle: np.ndarray, quats: np.ndarray, form: str, certified: bool) -> Tuple[np.ndarray, ...]:
    # Arrays deserialized on a worker may be misaligned views of a message
    # buffer: aligned copies (the values are unchanged).
    robot, obstacle, quats = (np.array(a, dtype=np.float64, order="C", copy=True) for a in (robot, obstacle, quats))
    return tuple(_cobstacle_block(robot, obstacle, quats, form, certified))


#: The name of the token file in a transfer folder (see :func:`_remote_task`).
_TOKEN = "token"


def _sees(folder: str, token: str) -> bool:
    """Whether this process sees the client's transfer folder: the token
    file the client wrote there holds ``token`` (a random name: a folder of
    the same path on another machine's own disk does not)."""
    try:
        with open(os.path.join(folder, _TOKEN), encoding="ascii") as f:
            return f.read() == token
    except OSError:
        return False


def _remote_task(
    robots: List[np.ndarray],
    obstacles: List[np.ndarray],
    quats: np.ndarray,
    units: List[Tuple[int, int, int, int]],
    form: str,
    certified: bool,
    folder: Optional[str],
    token: str,
    name: str,
) -> Tuple[Any, ...]:
    """One Dask task: the blocks ``units`` (robot piece, obstacle piece,
    first and end orientation) one after the other, each as
    :func:`_task`. Returns ``("error", u, exc)`` for the first failing
    unit ``u`` (the client names its pair and block); else, when the
    worker sees the client's transfer folder (:func:`_sees`), the blocks'
    arrays written there as one file of consecutive ``.npy`` records (raw
    float64/int64, bit for bit; a temporary name renamed once complete),
    ``("file", name)``; else ``("arrays", blocks)`` through Dask."""
    c = int(certified)
    out = []
    for u, (i, j, s, e) in enumerate(units):
        try:
            out.append(_task(robots[i], obstacles[j], quats[s : e + c], form, certified))
        except Exception as exc:  # named by the client
            return ("error", u, exc)
    if folder is None or not _sees(folder, token):
        return ("arrays", out)
    path = os.path.join(folder, name)
    tmp = f"{path}.{secrets.token_hex(4)}.tmp"
    try:
        with open(tmp, "wb") as f:
            for block in out:
                for x in block:
                    np.save(f, x, allow_pickle=False)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    return ("file", name)


def _read_blocks(folder: str, name: str, blocks: int, count: int) -> List[Tuple[np.ndarray, ...]]:
    """The ``blocks`` × ``count`` arrays a worker wrote to ``folder/name``;
    the file is removed once read."""
    path = os.path.join(folder, name)
    with open(path, "rb") as f:
        out = [tuple(np.load(f, allow_pickle=False) for _ in range(count)) for _ in range(blocks)]
    os.unlink(path)
    return out


class CObstacleMap:
    """The slices (or certified slabs) of every (robot piece, obstacle piece)
    pair over ``orientations``: ``m[i, j, k]`` is slice ``k`` of robot piece
    ``i`` (an index or a name) against obstacle piece ``j``, as
    ``(normals (M, 3), offsets (M,))`` (the region ``{x : normals @ x <=
    offsets}``) or as ``(vertices (V, 3), faces)`` with ``faces`` a list of
    ``int64`` arrays (convex polygons, counter-clockwise from outside)."""

    def __init__(self, arrays: Dict[str, np.ndarray]):
        self._a = arrays
        self.form: str = str(arrays["form"])
        self.certified: bool = bool(arrays["certified"])
        self.orientations: np.ndarray = arrays["orientations_xyzw"]
        self.robot_pieces: List[str] = [str(s) for s in arrays["robot_pieces"]]
        self.obstacle_pieces: List[str] = [str(s) for s in arrays["obstacle_pieces"]]
        self.pairs: np.ndarray = arrays["pairs"]
        self.slices_per_pair: int = int(arrays["slices_per_pair"])
        self._pair = {(int(r), int(o)): p for p, (r, o) in enumerate(self.pairs)}

    @property
    def arrays(self) -> Dict[str, np.ndarray]:
        """The container's arrays (read them, do not modify them)."""
        return self._a

    def __len__(self) -> int:
        return len(self.pairs) * self.slices_per_pair

    def _index(self, key: Any, names: List[str], what: str) -> int:
        if isinstance(key, str):
            try:
                return names.index(key)
            except ValueError:
                raise KeyError(f"no {what} piece named {key!r} (pieces: {names})") from None
        i = int(key)
        if not 0 <= i < len(names):
            raise IndexError(f"{what} piece {i} out of range (0..{len(names)})")
        return i

    def __getitem__(self, key: Tuple[Any, Any, int]) -> Tuple[Any, Any]:
        r, o, k = key
        i = self._index(r, self.robot_pieces, "robot")
        j = self._index(o, self.obstacle_pieces, "obstacle")
        k = int(k)
        if k < 0:
            k += self.slices_per_pair
        if not 0 <= k < self.slices_per_pair:
            raise IndexError(f"slice {k} out of range (0..{self.slices_per_pair})")
        s = self._pair[(i, j)] * self.slices_per_pair + k
        a = self._a
        if self.form == "halfspaces":
            lo, hi = a["plane_start"][s], a["plane_start"][s + 1]
            return a["normals"][lo:hi], a["offsets"][lo:hi]
        v0, v1 = a["vertex_start"][s], a["vertex_start"][s + 1]
        f0, f1 = a["face_start"][s], a["face_start"][s + 1]
        cs, c = a["corner_start"], a["corners"]
        faces = [c[cs[f] : cs[f + 1]] for f in range(f0, f1)]
        return a["vertices"][v0:v1], faces

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the container to ``path`` (``.npz``), atomically: a
        temporary file in the same folder renamed over ``path`` once
        complete; on an error nothing is left behind."""
        path = os.fspath(path)
        folder = os.path.dirname(os.path.abspath(path))
        fd, tmp = tempfile.mkstemp(prefix=".map-", suffix=".npz.tmp", dir=folder)
        try:
            with os.fdopen(fd, "wb") as f:
                savez: Any = np.savez  # its keyword `allow_pickle` is no array name here
                savez(f, **self._a)
                f.flush()
                os.fsync(f.fileno())
            os.replace(tmp, path)
        except BaseException:
            try:
                os.unlink(tmp)
            except OSError:
                pass
            raise

    def __repr__(self) -> str:
        return (
            f"CObstacleMap({len(self.robot_pieces)} robot × {len(self.obstacle_pieces)} obstacle "
            f"pieces, {self.slices_per_pair} {'slabs' if self.certified else 'slices'} per pair, "
            f"{self.form})"
        )


def load_cobstacle_map(path: Union[str, "os.PathLike[str]"]) -> CObstacleMap:
    """Reads a map container written by :meth:`CObstacleMap.save` or
    ``dymsum cobst --format npz|npz-mesh`` (plain arrays, no pickle)."""
    with np.load(os.fspath(path), allow_pickle=False) as z:
        arrays = {k: z[k] for k in z.files}
    if str(arrays.get("format", "")) != FORMAT:
        raise ValueError(f"{os.fspath(path)}: not a dymsum C-obstacle map (no format {FORMAT!r})")
    return CObstacleMap(arrays)


def cobstacle_map(
    robot: Any,
    obstacles: Any,
    rotations: Any,
    form: str = "halfspaces",
    certified: bool = False,
    client: Any = None,
    block: int = 256,
    workers: Optional[int] = None,
    shared_dir: Union[None, bool, str, "os.PathLike[str]"] = None,
) -> CObstacleMap:
    """The C-obstacle slices of every robot piece against every obstacle
    piece at every rotation (see the module docs and docs/PYTHON.md).
    ``workers``: the local thread pool's size (``client=None``; default:
    the CPU count). ``shared_dir`` (with a Dask ``client``): where workers
    hand their blocks back as files, in a fresh temporary folder removed
    before returning: ``None`` the system's temporary directory (right for
    a ``LocalCluster``), a path on a filesystem every worker mounts at the
    same path for a cluster of several machines, ``False`` never (every
    block travels through Dask). A worker that does not see the folder
    sends its block through Dask instead."""
    if form not in ("halfspaces", "mesh"):
        raise ValueError(f'cobstacle_map: form must be "halfspaces" or "mesh", got {form!r}')
    if certified and form != "halfspaces":
        raise ValueError('cobstacle_map: certified slabs come as half-spaces only (form="halfspaces")')
    if int(block) < 1 + int(certified):
        raise ValueError(f"cobstacle_map: block must be at least {1 + int(certified)}, got {block}")
    block = int(block)
    quats = np.asarray(_rotations_xyzw(rotations))
    k = len(quats)
    if certified and k < 2:
        raise ValueError("cobstacle_map: certified slabs need at least two rotations")
    rnames, rverts = _pieces(robot, "r")
    onames, overts = _pieces(obstacles, "o")
    per_pair = k - 1 if certified else k
    # Blocks of orientations; certified blocks share their end orientation
    # with the next block's first, so the slabs tile the turn.
    bounds = [(s, min(s + block, per_pair)) for s in range(0, per_pair, block)]
    pairs = [(i, j) for i in range(len(rverts)) for j in range(len(overts))]
    specs = [
        (p, b, i, j, s, e)
        for p, (i, j) in enumerate(pairs)
        for b, (s, e) in enumerate(bounds)
    ]

    def label(i: int, j: int, b: int, s: int, e: int) -> str:
        return f"pair ({rnames[i]}, {onames[j]}), block {b} (orientations {s}..{e + int(certified)})"

    results: List[Any] = [None] * len(specs)
    if client is None:
        with ThreadPoolExecutor(max_workers=workers or os.cpu_count() or 1) as pool:
            futures = [
                pool.submit(_task, rverts[i], overts[j], quats[s : e + int(certified)], form, certified)
                for (_, _, i, j, s, e) in specs
            ]
            for n, (fut, (_, b, i, j, s, e)) in enumerate(zip(futures, specs)):
                try:
                    results[n] = fut.result()
                except Exception as exc:
                    for f in futures:
                        f.cancel()
                    raise CObstacleMapError(f"cobstacle_map: {label(i, j, b, s, e)}: {exc}") from exc
    else:
        counts = {"halfspaces": 3, "mesh": 5}[form]
        folder: Optional[str] = None
        token = secrets.token_hex(16)
        if shared_dir is not False:
            base = None if shared_dir is None or shared_dir is True else os.fspath(shared_dir)
            folder = tempfile.mkdtemp(prefix="dymsum-map-", dir=base)
        try:
            if folder is not None:
                with open(os.path.join(folder, _TOKEN), "w", encoding="ascii") as tf:
                    tf.write(token)
            # Fresh keys (hash=False): an earlier map's scattered pieces with
            # the same content may be being released, and would take these
            # with them.
            rv = client.scatter(rverts, broadcast=True, hash=False)
            ov = client.scatter(overts, broadcast=True, hash=False)
            qv = client.scatter(quats, broadcast=True, hash=False)
            # Several blocks per Dask task: each task costs the scheduler a
            # few milliseconds, about 20% of a 256-orientation block here;
            # 16 tasks per worker thread keep the load balanced.
            threads = max(1, sum(client.nthreads().values()))
            per = max(1, -(-len(specs) // (16 * threads)))
            groups = [list(range(g, min(g + per, len(specs)))) for g in range(0, len(specs), per)]
            futures = [
                client.submit(
                    _remote_task,
                    rv,
                    ov,
                    qv,
                    [specs[n][2:] for n in g],
                    form,
                    certified,
                    folder,
                    token,
                    f"task-{t}.npy",
                    pure=False,
                )
                for t, g in enumerate(groups)
            ]
            for fut, g in zip(futures, groups):
                try:
                    r: Tuple[Any, ...] = fut.result()
                except Exception as exc:
                    client.cancel(futures)
                    _, b, i, j, s, e = specs[g[0]]
                    last = specs[g[-1]]
                    raise CObstacleMapError(
                        f"cobstacle_map: a task of {label(i, j, b, s, e)} to {label(*last[2:4], last[1], *last[4:])}: {exc}"
                    ) from exc
                if r[0] == "error":
                    client.cancel(futures)
                    _, b, i, j, s, e = specs[g[r[1]]]
                    raise CObstacleMapError(f"cobstacle_map: {label(i, j, b, s, e)}: {r[2]}") from r[2]
                got = _read_blocks(folder, r[1], len(g), counts) if r[0] == "file" and folder else r[1]
                for n, x in zip(g, got):
                    results[n] = x
        finally:
            if folder is not None:
                shutil.rmtree(folder, ignore_errors=True)

    arrays: Dict[str, np.ndarray] = {
        "format": np.array(FORMAT),
        "version": np.array(1, dtype=np.int64),
        "form": np.array(form),
        "certified": np.array(int(certified), dtype=np.int64),
        "orientations_xyzw": quats,
        "robot_pieces": np.array(rnames, dtype=str),
        "obstacle_pieces": np.array(onames, dtype=str),
        "pairs": np.array(pairs, dtype=np.int64).reshape(-1, 2),
        "slices_per_pair": np.array(per_pair, dtype=np.int64),
    }

    def starts(counts: List[np.ndarray]) -> np.ndarray:
        c = np.concatenate([np.zeros(1, np.int64)] + [np.asarray(x, np.int64) for x in counts])
        return np.cumsum(c)

    if form == "halfspaces":
        arrays["plane_start"] = starts([r[0] for r in results])
        arrays["normals"] = np.concatenate([r[1] for r in results]).reshape(-1, 3)
        arrays["offsets"] = np.concatenate([r[2] for r in results])
    else:
        arrays["vertex_start"] = starts([r[0] for r in results])
        arrays["vertices"] = np.concatenate([r[1] for r in results]).reshape(-1, 3)
        arrays["face_start"] = starts([r[2] for r in results])
        arrays["corner_start"] = starts([r[3] for r in results])
        arrays["corners"] = np.concatenate([r[4] for r in results]).astype(np.int64)
    return CObstacleMap(arrays)
