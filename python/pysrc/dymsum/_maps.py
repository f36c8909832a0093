"""C-obstacle maps: every robot piece against every obstacle piece over many
orientations, split into tasks (one piece pair × one block of consecutive
orientations, DYMSUM inside a block) on a local thread pool or a Dask
cluster, and one NumPy container for the whole map (issue 22 §2).

The container is the one ``dymsum cobst --format npz`` writes: plain arrays
only (``np.load(path, allow_pickle=False)``), the layout documented in
docs/PYTHON.md and in the Rust crate ``dymsum_io::cmap``.

This module is the front door: :func:`cobstacle_map` (arguments, the
pieces, the blocks, the container assembled) and
:func:`load_cobstacle_map`. The jobs behind it, one module each:

* ``_maps_tasks``: running the tasks (threads or Dask),
  :class:`CObstacleMapError`;
* ``_maps_container``: the container, :class:`CObstacleMap`;
* ``_maps_io``: reading (validating) and writing map files, both done by
  dymsum-io in Rust.
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ._dymsum import ConvexUnion, Polytope
from ._dymsum import _rotations_xyzw as _rotations_xyzw
from ._maps_container import CObstacleMap as CObstacleMap
from ._maps_io import FIELD_KINDS, read_map
from ._maps_io import FORMAT as FORMAT
# The seam CObstacleMap.save writes through, looked up here at each call
# (the tests replace it to fail a write after k bytes).
from ._maps_tasks import CObstacleMapError as CObstacleMapError
from ._maps_tasks import _read_blocks as _read_blocks
from ._maps_tasks import _remote_task as _remote_task
from ._maps_tasks import run_blocks

#: The map's fields (name → dtype kind, dimensions), as dymsum-io checks them.
_KINDS = FIELD_KINDS


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


def load_cobstacle_map(path: Union[str, "os.PathLike[str]"]) -> CObstacleMap:
    """Reads a map container written by :meth:`CObstacleMap.save` or
    ``dymsum cobst --format npz|npz-mesh`` (plain arrays, never a pickle),
    validated whole before use by dymsum-io (docs/LIMITS.md): a regular
    file (a FIFO or device is refused before it is opened), a ZIP of
    ``.npy`` entries, each name once, each field of the map present with
    its dtype and shape, lengths that agree, starts arrays that begin at 0,
    never decrease and end at their array's length, finite values, unit
    quaternions, pairs of existing pieces, version 1, form ``halfspaces``
    or ``mesh``, certified 0 or 1. Memory is bounded by the arrays the
    headers describe: an entry is inflated only up to the bytes its shape
    and dtype need, so a lying archive (a zip bomb) is refused without
    inflating the rest.

    Raises :class:`ValueError` naming the path (and the field) for a file
    that is not a valid map (text, empty, truncated or not a map at all:
    "not a dymsum C-obstacle map"), :class:`OSError` naming the path when
    the file cannot be opened or read."""
    return CObstacleMap(read_map(path))


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

    results = run_blocks(rverts, overts, quats, specs, form, certified, label, client, workers, shared_dir)

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
