"""Running the tasks of a C-obstacle map: one task is one (robot piece,
obstacle piece) pair × one block of consecutive orientations (DYMSUM
inside a block, in Rust with the GIL released), run on a local thread pool
or a Dask cluster; :func:`run_blocks` returns every block's arrays, in the
order of the tasks, or raises :class:`CObstacleMapError` naming the
failing pair and block."""

from __future__ import annotations

import os
import secrets
import shutil
import tempfile
from concurrent.futures import CancelledError, ThreadPoolExecutor
from typing import Any, Callable, List, Optional, Sequence, Tuple, Union

import numpy as np

from ._dymsum import _cobstacle_block

#: A task: (pair, block, robot piece, obstacle piece, first orientation,
#: end orientation).
Spec = Tuple[int, int, int, int, int, int]


class CObstacleMapError(RuntimeError):
    """A task of :func:`cobstacle_map` failed; the message names its piece
    pair and block of orientations, and the cause is chained."""


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
    # The transfer folder is private to this map (a fresh random folder the
    # client removes): a partial file only needs a name the client never
    # reads.
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


def run_blocks(
    robots: List[np.ndarray],
    obstacles: List[np.ndarray],
    quats: np.ndarray,
    specs: Sequence[Spec],
    form: str,
    certified: bool,
    label: Callable[[int, int, int, int, int], str],
    client: Any = None,
    workers: Optional[int] = None,
    shared_dir: Union[None, bool, str, "os.PathLike[str]"] = None,
) -> List[Tuple[np.ndarray, ...]]:
    """The arrays of every task of ``specs`` (as ``_cobstacle_block`` gives
    them), in order: on a thread pool of ``workers`` threads (``client``
    None), or on the Dask ``client``, handing blocks back as files under
    ``shared_dir`` (see :func:`dymsum.cobstacle_map`). ``label(i, j, b, s,
    e)`` names a task in a :class:`CObstacleMapError`."""
    if client is None:
        return _run_local(robots, obstacles, quats, specs, form, certified, label, workers)
    return _run_dask(robots, obstacles, quats, specs, form, certified, label, client, shared_dir)


def _run_local(
    robots: List[np.ndarray],
    obstacles: List[np.ndarray],
    quats: np.ndarray,
    specs: Sequence[Spec],
    form: str,
    certified: bool,
    label: Callable[[int, int, int, int, int], str],
    workers: Optional[int],
) -> List[Tuple[np.ndarray, ...]]:
    results: List[Any] = [None] * len(specs)
    with ThreadPoolExecutor(max_workers=workers or os.cpu_count() or 1) as pool:
        futures = [
            pool.submit(_task, robots[i], obstacles[j], quats[s : e + int(certified)], form, certified)
            for (_, _, i, j, s, e) in specs
        ]
        for n, (fut, (_, b, i, j, s, e)) in enumerate(zip(futures, specs)):
            try:
                results[n] = fut.result()
            except Exception as exc:
                for f in futures:
                    f.cancel()
                raise CObstacleMapError(f"cobstacle_map: {label(i, j, b, s, e)}: {exc}") from exc
    return results


def _run_dask(
    robots: List[np.ndarray],
    obstacles: List[np.ndarray],
    quats: np.ndarray,
    specs: Sequence[Spec],
    form: str,
    certified: bool,
    label: Callable[[int, int, int, int, int], str],
    client: Any,
    shared_dir: Union[None, bool, str, "os.PathLike[str]"],
) -> List[Tuple[np.ndarray, ...]]:
    results: List[Any] = [None] * len(specs)
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
        rv = client.scatter(robots, broadcast=True, hash=False)
        ov = client.scatter(obstacles, broadcast=True, hash=False)
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
                    else f"a task of {label(i, j, b, s, e)} to {label(last[2], last[3], last[1], last[4], last[5])}"
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
    return results
