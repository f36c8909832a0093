"""C-obstacle maps: every robot piece against every obstacle piece over many
orientations, split into tasks (one piece pair × one block of consecutive
orientations, DYMSUM inside a block) on a local thread pool or a Dask
cluster, and one NumPy container for the whole map (issue 22 §2).

The container is the one ``dymsum cobst --format npz`` writes: plain arrays
only (``np.load(path, allow_pickle=False)``), the layout documented in
docs/PYTHON.md and in the Rust crate ``dymsum_io::cmap``.
"""

from __future__ import annotations

import errno
import io
import os
import re
import secrets
import shutil
import stat
import struct
import tempfile
import zipfile
import zlib
from concurrent.futures import CancelledError, ThreadPoolExecutor
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ._dymsum import ConvexUnion, Polytope, _cobstacle_block, _rotations_xyzw

FORMAT = "dymsum-cobstacle-map"


class CObstacleMapError(RuntimeError):
    """A task of :func:`cobstacle_map` failed; the message names its piece
    pair and block of orientations, and the cause is chained."""


def _pieces(body: Any, prefix: str, what: str = "body") -> Tuple[List[str], List[np.ndarray]]:
    """Piece names and vertex arrays of a body: a ``ConvexUnion``, a mapping
    name → shape, a list of shapes, or one shape (``None``: a ``ValueError``
    naming ``what``, the argument)."""
    if body is None:
        raise ValueError(f"cobstacle_map: {what}: expected a ConvexUnion, a mapping name → shape, a list of shapes or one shape, got None")
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


def _lost(exc: BaseException) -> str:
    """What a Dask error means for a map task, when the cluster lost it
    rather than the task failing: its workers died (a ``KilledWorker``: the
    workers running it died, several times over), or the task was cancelled
    or forgotten (every worker holding the pieces scattered to the cluster
    died, so the task can never run). Empty otherwise."""
    name = type(exc).__name__
    if name == "KilledWorker":
        return "the Dask workers running this task died (each time it was tried); "
    if isinstance(exc, CancelledError) or name in ("FutureCancelledError", "CancelledError"):
        return (
            "the Dask cluster lost this task: its workers died (with them the pieces "
            "scattered to the cluster) or the task was cancelled; "
        )
    return ""


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
        temporary file in the same folder (``.STEM.tmp-PID-XXXX.EXT``, named
        with this process's id) renamed over ``path`` once complete; on an
        error nothing is left behind, and a kill leaves ``path`` as it was.
        The temporary files that killed writers of ``path`` left (their
        owner process is dead) are removed first; a running writer's are
        kept."""
        path = os.fspath(path)
        folder = os.path.dirname(os.path.abspath(path))
        stem, ext = os.path.splitext(os.path.basename(path))
        _remove_stale_temps(folder, stem, ext)
        fd, tmp = tempfile.mkstemp(prefix=f".{stem}.tmp-{os.getpid()}-", suffix=ext, dir=folder)
        try:
            with _open_temp(fd) as f:
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


def _open_temp(fd: int) -> Any:
    """The file object :meth:`CObstacleMap.save` writes through (a seam
    for the tests that make it fail after k bytes)."""
    return os.fdopen(fd, "wb")


#: A temporary file of a writer: ``.STEM.tmp-PID-TOKEN`` then nothing or
#: ``.EXT`` (the names ``dymsum_io::atomic`` and :meth:`CObstacleMap.save`
#: give their temporary files).
_TEMP = re.compile(r"\A\.(?P<stem>.+)\.tmp-(?P<pid>[0-9]+)-[A-Za-z0-9_]+(?P<ext>\.[^.]*)?\Z")


def _owner_alive(pid: int) -> bool:
    """Whether process ``pid`` may be running: this one, or one that
    ``os.kill(pid, 0)`` finds (a process of another user counts as alive).
    A dead owner's id reused by another process keeps its file until a
    later run."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, OSError):
        return True
    return True


def _remove_stale_temps(folder: str, stem: str, ext: str) -> None:
    """Removes the temporary files of ``STEM.EXT`` in ``folder`` whose
    owner process is dead; best effort (a folder that cannot be listed is
    reported by the write)."""
    try:
        names = os.listdir(folder)
    except OSError:
        return
    for name in names:
        m = _TEMP.match(name)
        if not m or m["stem"] != stem or (m["ext"] or "") != ext or _owner_alive(int(m["pid"])):
            continue
        try:
            full = os.path.join(folder, name)
            if stat.S_ISREG(os.lstat(full).st_mode):
                os.unlink(full)
        except OSError:
            pass


class _MapError(Exception):
    """A map file fails validation: ``field`` (or None) and the reason."""

    def __init__(self, field: Optional[str], reason: str):
        super().__init__(reason)
        self.field = field
        self.reason = reason


_COMMON = (
    "format",
    "version",
    "form",
    "certified",
    "orientations_xyzw",
    "robot_pieces",
    "obstacle_pieces",
    "pairs",
    "slices_per_pair",
)
_FORM_FIELDS = {
    "halfspaces": ("plane_start", "normals", "offsets"),
    "mesh": ("vertex_start", "vertices", "face_start", "corner_start", "corners"),
}
#: Each field's dtype kind ("i" int64 or narrower signed ints, "f" float64
#: or float32, "U" unicode strings) and number of dimensions.
_KINDS = {
    "format": ("U", 0),
    "version": ("i", 0),
    "form": ("U", 0),
    "certified": ("i", 0),
    "orientations_xyzw": ("f", 2),
    "robot_pieces": ("U", 1),
    "obstacle_pieces": ("U", 1),
    "pairs": ("i", 2),
    "slices_per_pair": ("i", 0),
    "plane_start": ("i", 1),
    "normals": ("f", 2),
    "offsets": ("f", 1),
    "vertex_start": ("i", 1),
    "vertices": ("f", 2),
    "face_start": ("i", 1),
    "corner_start": ("i", 1),
    "corners": ("i", 1),
}
#: The largest ``.npy`` header read (numpy's own limit for safe loading).
_MAX_HEADER = 10000
_CHUNK = 1 << 20


class _Member:
    """One ``.npy`` entry of the archive: its header, read without reading
    the data."""

    def __init__(self, zf: zipfile.ZipFile, info: zipfile.ZipInfo, field: str):
        self.zf, self.info, self.field = zf, info, field
        with zf.open(info) as f:
            self.shape, self.fortran, self.dtype, self.offset = _npy_header(f, field)
        self.count = 1
        for n in self.shape:
            self.count *= n
        self.nbytes = self.count * self.dtype.itemsize

    def read(self) -> np.ndarray:
        """The array, reading at most the bytes its header's shape and dtype
        need (and one more, to refuse an entry that holds more)."""
        with self.zf.open(self.info) as f:
            _exact(f, self.offset, self.field, "header")
            buf = bytearray()
            while len(buf) < self.nbytes:
                chunk = f.read(min(_CHUNK, self.nbytes - len(buf)))
                if not chunk:
                    raise _MapError(
                        self.field,
                        f"truncated: {len(buf)} of the {self.nbytes} data bytes its shape "
                        f"{self.shape} of {self.dtype.str} needs",
                    )
                buf += chunk
            if f.read(1):
                raise _MapError(
                    self.field, f"holds more data than its shape {self.shape} of {self.dtype.str} needs"
                )
        a = np.frombuffer(buf, dtype=self.dtype, count=self.count)
        a = a.reshape(self.shape, order="F" if self.fortran else "C")
        return np.asarray(a.astype(self.dtype.newbyteorder("="), copy=False), order="C")


def _exact(f: Any, n: int, field: str, what: str) -> bytes:
    b = f.read(n)
    if len(b) != n:
        raise _MapError(field, f"truncated {what} (an .npy entry)")
    return bytes(b)


def _npy_header(f: Any, field: str) -> Tuple[Tuple[int, ...], bool, np.dtype, int]:
    """Shape, Fortran order, dtype and data offset of an ``.npy`` stream,
    the header length checked before the header is read."""
    from numpy.lib import format as npformat

    magic = _exact(f, 8, field, "magic")
    if magic[:6] != b"\x93NUMPY":
        raise _MapError(field, "not an .npy array (bad magic)")
    version = (magic[6], magic[7])
    if version == (1, 0):
        lenbytes = _exact(f, 2, field, "header length")
        (hlen,) = struct.unpack("<H", lenbytes)
        reader = npformat.read_array_header_1_0
    elif version == (2, 0):
        lenbytes = _exact(f, 4, field, "header length")
        (hlen,) = struct.unpack("<I", lenbytes)
        reader = npformat.read_array_header_2_0
    else:
        raise _MapError(field, f".npy format version {version[0]}.{version[1]} is not supported (1.0 or 2.0)")
    if hlen > _MAX_HEADER:
        raise _MapError(field, f".npy header of {hlen} bytes (at most {_MAX_HEADER})")
    header = _exact(f, hlen, field, "header")
    try:
        shape, fortran, dtype = reader(io.BytesIO(lenbytes + header), max_header_size=_MAX_HEADER)
    except (ValueError, TypeError, SyntaxError, MemoryError, RecursionError) as e:
        raise _MapError(field, f"bad .npy header ({e})") from None
    if not isinstance(dtype, np.dtype) or dtype.hasobject or dtype.fields is not None or dtype.subdtype is not None:
        raise _MapError(field, f"dtype {dtype!r} is not a plain number or string (object arrays are never read)")
    if not all(isinstance(n, int) and n >= 0 for n in shape):
        raise _MapError(field, f"bad shape {shape!r}")
    return tuple(int(n) for n in shape), bool(fortran), dtype, len(magic) + len(lenbytes) + hlen


def _check_kind(m: _Member) -> None:
    kind, ndim = _KINDS[m.field]
    dt = m.dtype
    ok = (
        (kind == "i" and dt.kind == "i")
        or (kind == "f" and dt.kind == "f" and dt.itemsize in (4, 8))
        or (kind == "U" and dt.kind == "U")
    )
    if not ok:
        want = {"i": "a signed integer (int64)", "f": "float64", "U": "a unicode string"}[kind]
        raise _MapError(m.field, f"dtype {dt.str} where {want} is expected")
    if len(m.shape) != ndim:
        raise _MapError(m.field, f"shape {m.shape}: expected {ndim} dimension{'s' if ndim != 1 else ''}")


def _scalar_str(m: _Member) -> str:
    return str(m.read()[()])


def _scalar_int(m: _Member) -> int:
    return int(m.read()[()])


def _starts(m: _Member, length: int, end: Optional[int], what: str) -> np.ndarray:
    """A starts array: ``length`` entries, first 0, non-decreasing, last
    ``end`` (when known)."""
    if m.shape != (length,):
        raise _MapError(m.field, f"shape {m.shape}: expected ({length},) ({what} + 1)")
    a = m.read().astype(np.int64)
    if a[0] != 0:
        raise _MapError(m.field, f"starts at {a[0]}, not 0")
    d = np.diff(a)
    if (d < 0).any():
        k = int(np.argmax(d < 0))
        raise _MapError(m.field, f"decreases at entry {k + 1} ({a[k + 1]} after {a[k]}): starts must be non-decreasing")
    if end is not None and a[-1] != end:
        raise _MapError(m.field, f"ends at {a[-1]}, but {end} entries are there")
    return a


def _finite(m: _Member) -> np.ndarray:
    a = m.read().astype(np.float64)
    bad = ~np.isfinite(a)
    if bad.any():
        k = np.unravel_index(int(np.argmax(bad)), a.shape)
        raise _MapError(m.field, f"holds a value that is not finite ({a[k]} at {tuple(int(i) for i in k)})")
    return a


def _read_map(f: Any) -> Dict[str, np.ndarray]:
    """The validated arrays of a map archive open as ``f`` (module docs,
    :func:`load_cobstacle_map`); raises :class:`_MapError`."""
    try:
        zf = zipfile.ZipFile(f)
    except (zipfile.BadZipFile, zipfile.LargeZipFile, EOFError) as e:
        raise _MapError(None, f"not a dymsum C-obstacle map (not a NumPy .npz archive: {e})") from None
    with zf:
        infos = zf.infolist()
        names = [i.filename for i in infos]
        if "format.npy" not in names:
            raise _MapError(None, "not a dymsum C-obstacle map (no 'format' entry)")
        seen = set()
        for n in names:
            if n in seen:
                raise _MapError(n[:-4] if n.endswith(".npy") else n, f"the archive holds the entry {n!r} twice")
            seen.add(n)
        by = {}
        for i in infos:
            field = i.filename[:-4] if i.filename.endswith(".npy") else i.filename
            if not i.filename.endswith(".npy") or field not in _KINDS:
                raise _MapError(None, f"unexpected entry {i.filename!r} (not a field of a map)")
            if i.flag_bits & 0x1:
                raise _MapError(field, "the entry is encrypted")
            if i.compress_type not in (zipfile.ZIP_STORED, zipfile.ZIP_DEFLATED):
                raise _MapError(field, f"unsupported compression method {i.compress_type}")
            by[field] = i
        members: Dict[str, _Member] = {}

        def member(field: str) -> _Member:
            if field not in members:
                if field not in by:
                    raise _MapError(field, "missing")
                m = _Member(zf, by[field], field)
                _check_kind(m)
                members[field] = m
            return members[field]

        fmt = member("format")
        if fmt.shape != () or _scalar_str(fmt) != FORMAT:
            raise _MapError(None, f"not a dymsum C-obstacle map (its format is not {FORMAT!r})")
        v = member("version")
        if v.shape != ():
            raise _MapError("version", f"shape {v.shape}: expected a scalar")
        version = _scalar_int(v)
        if version != 1:
            raise _MapError("version", f"version {version} is not supported (this dymsum reads version 1)")
        form = _scalar_str(member("form"))
        if form not in _FORM_FIELDS:
            raise _MapError("form", f"{form!r}: expected 'halfspaces' or 'mesh'")
        wanted = set(_COMMON + _FORM_FIELDS[form])
        for field in sorted(set(by) - wanted):
            raise _MapError(field, f"not a field of a {form} map")
        for field in _COMMON + _FORM_FIELDS[form]:
            member(field)
        certified = _scalar_int(members["certified"])
        if certified not in (0, 1):
            raise _MapError("certified", f"{certified}: expected 0 or 1")
        if certified and form != "halfspaces":
            raise _MapError("certified", "certified slabs come as half-spaces only, not in a mesh map")
        per = _scalar_int(members["slices_per_pair"])
        quats_m = members["orientations_xyzw"]
        k = quats_m.shape[0]
        if quats_m.shape[1] != 4:
            raise _MapError("orientations_xyzw", f"shape {quats_m.shape}: expected (K, 4)")
        if (certified and per not in (k - 1, k)) or (not certified and per != k) or per < 0:
            raise _MapError(
                "slices_per_pair",
                f"{per} with {k} orientations (expected {k - 1 if certified else k}{' or ' + str(k) if certified else ''})",
            )
        quats = _finite(quats_m)
        norms = np.linalg.norm(quats, axis=1)
        if (np.abs(norms - 1.0) > 1e-6).any():
            raise _MapError("orientations_xyzw", f"not unit quaternions (norm {norms[np.argmax(np.abs(norms - 1.0))]})")
        robot = members["robot_pieces"].read()
        obstacle = members["obstacle_pieces"].read()
        pairs_m = members["pairs"]
        if pairs_m.shape[1] != 2:
            raise _MapError("pairs", f"shape {pairs_m.shape}: expected (P, 2)")
        pairs = pairs_m.read().astype(np.int64)
        if len(pairs) and (
            (pairs < 0).any() or (pairs[:, 0] >= len(robot)).any() or (pairs[:, 1] >= len(obstacle)).any()
        ):
            raise _MapError(
                "pairs", f"a piece index out of range ({len(robot)} robot, {len(obstacle)} obstacle pieces)"
            )
        if len({(int(r), int(o)) for r, o in pairs}) != len(pairs):
            raise _MapError("pairs", "a piece pair is listed twice")
        slices = len(pairs) * per
        arrays: Dict[str, np.ndarray] = {
            "format": np.array(FORMAT),
            "version": np.array(1, dtype=np.int64),
            "form": np.array(form),
            "certified": np.array(certified, dtype=np.int64),
            "orientations_xyzw": quats,
            "robot_pieces": robot,
            "obstacle_pieces": obstacle,
            "pairs": pairs.reshape(-1, 2),
            "slices_per_pair": np.array(per, dtype=np.int64),
        }
        if form == "halfspaces":
            n_m, d_m = members["normals"], members["offsets"]
            if n_m.shape[1] != 3:
                raise _MapError("normals", f"shape {n_m.shape}: expected (N, 3)")
            if d_m.shape != (n_m.shape[0],):
                raise _MapError("offsets", f"shape {d_m.shape}, but normals has {n_m.shape[0]} rows")
            arrays["plane_start"] = _starts(members["plane_start"], slices + 1, n_m.shape[0], "slices")
            arrays["normals"] = _finite(n_m)
            arrays["offsets"] = _finite(d_m)
        else:
            v_m, c_m = members["vertices"], members["corners"]
            if v_m.shape[1] != 3:
                raise _MapError("vertices", f"shape {v_m.shape}: expected (V, 3)")
            vs = _starts(members["vertex_start"], slices + 1, v_m.shape[0], "slices")
            fs = _starts(members["face_start"], slices + 1, None, "slices")
            cs = _starts(members["corner_start"], int(fs[-1]) + 1, c_m.shape[0], "faces")
            corners = c_m.read().astype(np.int64)
            # Each corner indexes a vertex of its own slice.
            face_slice = np.repeat(np.arange(slices), np.diff(fs))
            corner_face = np.repeat(np.arange(len(cs) - 1), np.diff(cs))
            limit = np.diff(vs)[face_slice[corner_face]] if len(corners) else np.zeros(0, np.int64)
            if ((corners < 0) | (corners >= limit)).any():
                c = int(np.argmax((corners < 0) | (corners >= limit)))
                raise _MapError("corners", f"corner {c} indexes vertex {corners[c]} of a slice of {limit[c]} vertices")
            arrays.update(vertex_start=vs, vertices=_finite(v_m), face_start=fs, corner_start=cs, corners=corners)
        return arrays


def load_cobstacle_map(path: Union[str, "os.PathLike[str]"]) -> CObstacleMap:
    """Reads a map container written by :meth:`CObstacleMap.save` or
    ``dymsum cobst --format npz|npz-mesh`` (plain arrays, never a pickle),
    validated whole before use (docs/LIMITS.md): a regular file (a FIFO or
    device is refused before it is opened), a ZIP of ``.npy`` entries, each
    name once, each field of the map present with its dtype and shape,
    lengths that agree, starts arrays that begin at 0, never decrease and
    end at their array's length, finite values, unit quaternions, pairs of
    existing pieces, version 1, form ``halfspaces`` or ``mesh``, certified
    0 or 1. Memory is bounded by the arrays the headers describe: an entry
    is inflated only up to the bytes its shape and dtype need, so a lying
    archive (a zip bomb) is refused without inflating the rest.

    Raises :class:`ValueError` naming the path (and the field) for a file
    that is not a valid map (text, empty, truncated or not a map at all:
    "not a dymsum C-obstacle map"), :class:`OSError` naming the path when
    the file cannot be opened or read."""
    p = os.fspath(path)
    st = os.stat(p)
    if not stat.S_ISREG(st.st_mode):
        what = "a directory" if stat.S_ISDIR(st.st_mode) else "a FIFO, socket or device"
        raise ValueError(f"{p}: not a regular file ({what}); give a map file")
    # Non-blocking: a FIFO swapped in after the check cannot hang the open.
    fd = os.open(p, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise ValueError(f"{p}: not a regular file; give a map file")
        if hasattr(os, "set_blocking"):
            os.set_blocking(fd, True)
        f = os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise
    with f:
        try:
            return CObstacleMap(_read_map(f))
        except _MapError as e:
            where = f"field {e.field!r}: " if e.field else ""
            raise ValueError(f"{p}: {where}{e.reason}") from None
        except OSError as e:
            if e.errno in (None, errno.EINVAL):
                # zipfile's seeks to offsets a corrupt directory gives.
                raise ValueError(f"{p}: not a valid dymsum C-obstacle map (corrupt archive: {e})") from None
            raise OSError(e.errno, f"{p}: {e.strerror or e}") from e
        except (
            zipfile.BadZipFile,
            zipfile.LargeZipFile,
            EOFError,
            zlib.error,
            struct.error,
            NotImplementedError,
            RuntimeError,
            UnicodeError,
            ValueError,
            TypeError,
            IndexError,
            KeyError,
            OverflowError,
            MemoryError,
        ) as e:
            raise ValueError(f"{p}: not a valid dymsum C-obstacle map (corrupt archive: {type(e).__name__}: {e})") from None


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
    rnames, rverts = _pieces(robot, "r", "robot")
    onames, overts = _pieces(obstacles, "o", "obstacles")
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
                    what = (
                        f"the task of {label(i, j, b, s, e)}"
                        if len(g) == 1
                        else f"a task of {label(i, j, b, s, e)} to {label(*last[2:4], last[1], *last[4:])}"
                    )
                    raise CObstacleMapError(f"cobstacle_map: {what}: {_lost(exc)}{exc}") from exc
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
