"""The C-obstacle map container, :class:`CObstacleMap`: the arrays of
``dymsum cobst --format npz`` (plain arrays only, the layout documented in
docs/PYTHON.md and in the Rust crate ``dymsum_io::cmap``), indexed by
(robot piece, obstacle piece, orientation)."""

from __future__ import annotations

import os
from typing import Any, Dict, List, Tuple, Union

import numpy as np

from ._maps_io import write_map


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
        """Writes the container to ``path`` (``.npz``), validated first as
        :func:`dymsum.load_cobstacle_map` validates a file (a
        :class:`ValueError` naming the field, and nothing written), then
        atomically: a temporary file in the same folder
        (``.STEM.tmp-PID-N.EXT``, named with this process's id) renamed
        over ``path`` once complete; on an error nothing is left behind,
        and a kill leaves ``path`` as it was. The temporary files that
        killed writers of ``path`` left (their owner process is dead) are
        removed first; a running writer's are kept. The writing is
        dymsum-io's (``dymsum._maps_io``)."""
        write_map(path, self._a)

    def __repr__(self) -> str:
        return (
            f"CObstacleMap({len(self.robot_pieces)} robot × {len(self.obstacle_pieces)} obstacle "
            f"pieces, {self.slices_per_pair} {'slabs' if self.certified else 'slices'} per pair, "
            f"{self.form})"
        )
