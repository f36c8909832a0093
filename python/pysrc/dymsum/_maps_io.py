"""C-obstacle map files: the validating reader and the atomic writer.

Both are dymsum-io's, in Rust (``dymsum_io::cmap``, ``npz``, ``atomic``),
so a map file is read and written by one implementation whether it comes
from Python or from ``dymsum cobst --format npz``:

* :func:`read_map` validates the whole file before use, with bounded
  memory (docs/LIMITS.md, "Map files"), and returns its arrays;
* :func:`write_map` validates the arrays the same way, then writes them
  atomically: the temporary files of dead writers of ``path`` removed, a
  fresh temporary file ``.STEM.tmp-PID-N.EXT`` beside ``path`` (named with
  this process's id), renamed over ``path`` once complete and synced.
"""

from __future__ import annotations

import os
from typing import IO, Any, Callable, Dict, Mapping, Optional, Tuple, Union

import numpy as np

from ._dymsum import _cobstacle_map_fields, _read_cobstacle_map, _write_cobstacle_map

FORMAT = "dymsum-cobstacle-map"

#: The fields of a map container: name → (NumPy dtype kind, dimensions);
#: kind "i" a signed integer, "f" float64 or float32, "U" unicode.
FIELD_KINDS: Dict[str, Tuple[str, int]] = _cobstacle_map_fields()


def open_temp(fd: int) -> IO[bytes]:
    """The binary file object a map is written through, on the temporary
    file's descriptor ``fd`` (it takes the descriptor over)."""
    return os.fdopen(fd, "wb")


def write_map(
    path: Union[str, "os.PathLike[str]"],
    arrays: Mapping[str, Any],
    opener: Optional[Callable[[int], IO[bytes]]] = None,
) -> None:
    """Writes the container ``arrays`` to ``path`` atomically (module docs),
    through the file object ``opener(fd)`` gives (by default this module's
    ``open_temp``, looked up at each call: the seam the tests replace to
    fail a write after k bytes). Raises
    :class:`ValueError` naming the path and the field for arrays that are
    not a valid map (nothing is written), :class:`OSError` when the file
    cannot be written (``path`` is then as it was, and no temporary file is
    left)."""

    def open_path(temp: Union[str, "os.PathLike[str]"]) -> IO[bytes]:
        fd = os.open(temp, os.O_WRONLY | getattr(os, "O_BINARY", 0) | getattr(os, "O_CLOEXEC", 0))
        try:
            return (opener or open_temp)(fd)
        except BaseException:
            os.close(fd)
            raise

    _write_cobstacle_map(path, arrays, open_path)


def read_map(path: Union[str, "os.PathLike[str]"]) -> Dict[str, np.ndarray]:
    """The arrays of the map container at ``path``, validated whole first
    (module docs). Raises :class:`ValueError` naming the path (and the
    field) for a file that is not a valid map or not a regular file,
    :class:`OSError` naming the path when it cannot be opened or read."""
    return _read_cobstacle_map(path)
