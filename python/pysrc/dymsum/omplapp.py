"""OMPL.app's 3-D rigid-body problems, read as OMPL.app reads them.

`OMPL.app <https://github.com/ompl/omplapp>`_ ships its benchmark problems
(``resources/3D``: cubicles, Twistycool, Easy, Home, Abstract, Apartment,
bugtrap, alpha-1.x, escape, spirelli, ...) as a ``.cfg`` file naming a robot
mesh and an environment mesh (COLLADA ``.dae`` files exported from
SketchUp), the start and goal states and the bounds of the translation, and
several with a solution ``.path`` next to it. :func:`load_problem` turns one
into arrays; :func:`load_path` reads a ``.path``. The meshes themselves are
not part of dymsum (OMPL.app's licence does not allow passing them on):
get them from OMPL.app's repository.

What OMPL.app does, and this module does alike, so that the shipped
solution paths come out collision-free (every state of every shipped path
was checked with FCL, as OMPL.app checks, by
``python/benchmarks/omplapp_check.py``):

* **Meshes.** OMPL.app reads them with Assimp (flags ``Triangulate |
  JoinIdenticalVertices | GenNormals | SortByPType | OptimizeGraph``) and
  takes every triangle of every mesh of every node, each moved by the
  product of the node transforms from the root. Here COLLADA files are read
  with pycollada and walked the same way (``<instance_node>`` included);
  every triangle is kept, none is merged, dropped or reoriented (a polygon
  of a ``<polylist>`` is split as a fan from its first corner; Assimp
  splits a quad the same way and cuts larger polygons by ear clipping, the
  same region for convex polygons). Vertices are those the triangles use,
  each vertex of the file once per instance of its geometry (no merging by
  position: the dymsum core cleans its input itself). Other formats (STL,
  OBJ, PLY, ...) are read with trimesh (``process=False``: nothing merged
  either).
* **Up axis and unit.** Assimp turns a COLLADA file to Y up: it applies
  ``(x, y, z) -> (x, z, -y)`` to a ``Z_UP`` file and ``(x, y, z) -> (-y, x,
  z)`` to an ``X_UP`` one, and scales by ``<unit meter="...">``. OMPL.app's
  ``.cfg`` coordinates are in that frame (all its 3-D files are ``Z_UP``),
  so this is done here too. trimesh's own COLLADA reader does not do it,
  which is why it is not used for ``.dae`` files.
* **Robot frame.** OMPL.app moves the robot by ``p -> R (p - c) + t`` where
  ``(R, t)`` is the state and ``c`` the mean of the robot's vertices as
  Assimp holds them after ``JoinIdenticalVertices``: every vertex of every
  mesh (the line meshes of SketchUp's edges included), each mesh joined on
  its own and each counted once per node that instances it; two corners
  are one vertex when their positions are equal and their normals (and
  first texture coordinates, tangents) differ by at most 1e-5. The same
  vertices are counted here, and their mean is taken in float64 (Assimp
  sums in float32: its centre differs from this one by up to about 1e-6
  of the coordinates, far below the 3 decimals the ``.path`` files print
  positions with). For other formats the centre is the mean of the
  distinct vertices trimesh reads (in an STL file: the distinct pairs of
  position and facet normal, as Assimp joins them); trimesh tells OBJ
  vertices apart by their index triples where Assimp compares values, so
  there it can differ. ``Problem.robot_vertices`` are the robot's vertices with
  ``c`` already subtracted, and ``Problem.robot_centre`` is ``c``, so a
  state's 4x4 pose moves ``robot_vertices`` to the world.
* **States.** ``start.x/y/z`` and ``start.axis.x/y/z`` + ``start.theta``
  (radians; the axis need not be of unit length), alike for ``goal``, as
  OMPL's ``SO3StateSpace::StateType::setAxisAngle``. A ``.path`` line is
  one SE(3) state as OMPL's ``PathGeometric::printAsMatrix`` writes it:
  ``x y z qx qy qz qw``.
* **Bounds.** ``volume.min.x`` ... ``volume.max.z``; where a ``.cfg`` has
  none, OMPL.app takes the bounding box of the environment's vertices, and
  so does :func:`load_problem`.

pycollada (and trimesh for other mesh formats) are optional: ``pip install
trimesh pycollada`` (the ``scenes`` extra). :func:`load_path` and
:func:`read_cfg` need NumPy only:

>>> import io, math
>>> from dymsum.omplapp import axis_angle_pose, state_pose
>>> axis_angle_pose(1.0, 2.0, 3.0, (0.0, 0.0, 2.0), math.pi / 2).round(12)[:3].tolist()
[[0.0, -1.0, 0.0, 1.0], [1.0, 0.0, 0.0, 2.0], [0.0, 0.0, 1.0, 3.0]]
>>> bool(np.allclose(state_pose(1, 2, 3, 0, 0, math.sin(math.pi / 4), math.cos(math.pi / 4)), axis_angle_pose(1, 2, 3, (0, 0, 1), math.pi / 2)))
True
"""

from __future__ import annotations

import dataclasses
import math
import os
import pathlib
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple, Union

import numpy as np

__all__ = [
    "Problem",
    "axis_angle_pose",
    "load_mesh",
    "load_path",
    "load_problem",
    "read_cfg",
    "state_pose",
]

PathLike = Union[str, "os.PathLike[str]"]

_INSTALL = "pip install trimesh pycollada"

# Assimp's ColladaLoader turns the scene to Y up (root transform, applied
# after every node transform).
_UP_AXIS = {
    "Z_UP": np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]]),
    "X_UP": np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]),
    "Y_UP": np.eye(3),
}

# JoinVerticesProcess: attributes within this (squared) distance are equal.
_JOIN_EPS2 = np.float32(1e-5) * np.float32(1e-5)


@dataclasses.dataclass
class Problem:
    """One OMPL.app problem (:func:`load_problem`).

    Attributes:
        name: ``problem.name`` of the ``.cfg`` (its file name without
            ``.cfg`` where it has none).
        robot_vertices: ``(N, 3)`` float64, the robot in its own frame: its
            vertices less :attr:`robot_centre`, as OMPL.app moves them.
        robot_faces: ``(M, 3)`` int64 rows into ``robot_vertices``, every
            triangle of the robot file, as the file orients it.
        env_vertices: ``(P, 3)`` float64, the environment in the world frame.
        env_faces: ``(Q, 3)`` int64, every triangle of the environment file.
        start: 4x4 float64 pose of the start state (moves ``robot_vertices``).
        goal: 4x4 float64 pose of the goal state.
        bounds: ``(low, high)``, each ``(3,)`` float64: the box the robot's
            frame origin (the translation of a state) stays in.
        time_limit: ``benchmark.time_limit`` in seconds, ``None`` if absent.
        robot_centre: ``(3,)`` float64, what was subtracted from the robot
            file's vertices (OMPL.app's robot centre).
        cfg_file, robot_file, env_file: the files read.
        path_file: the solution ``<cfg name>.path`` beside the ``.cfg``, or
            ``None`` where there is none (read it with :func:`load_path`).
    """

    name: str
    robot_vertices: np.ndarray
    robot_faces: np.ndarray
    env_vertices: np.ndarray
    env_faces: np.ndarray
    start: np.ndarray
    goal: np.ndarray
    bounds: Tuple[np.ndarray, np.ndarray]
    time_limit: Optional[float]
    robot_centre: np.ndarray
    cfg_file: pathlib.Path
    robot_file: pathlib.Path
    env_file: pathlib.Path
    path_file: Optional[pathlib.Path] = None

    def robot_at(self, pose: np.ndarray) -> np.ndarray:
        """The robot's vertices in the world at a 4x4 ``pose`` (a state)."""
        pose = np.asarray(pose, dtype=float)
        return self.robot_vertices @ pose[:3, :3].T + pose[:3, 3]


# --------------------------------------------------------------------------
# Poses


def state_pose(x: float, y: float, z: float, qx: float, qy: float, qz: float, qw: float) -> np.ndarray:
    """The 4x4 pose of an SE(3) state: translation and quaternion (x, y, z, w).

    The quaternion is normalised first (a ``.path`` prints it rounded).
    """
    q = np.array([qx, qy, qz, qw], dtype=float)
    n = float(np.linalg.norm(q))
    if not math.isfinite(n) or n == 0.0:
        raise ValueError(f"not a rotation quaternion: {q.tolist()}")
    x_, y_, z_, w_ = q / n
    m = np.eye(4)
    m[:3, :3] = [
        [1 - 2 * (y_ * y_ + z_ * z_), 2 * (x_ * y_ - z_ * w_), 2 * (x_ * z_ + y_ * w_)],
        [2 * (x_ * y_ + z_ * w_), 1 - 2 * (x_ * x_ + z_ * z_), 2 * (y_ * z_ - x_ * w_)],
        [2 * (x_ * z_ - y_ * w_), 2 * (y_ * z_ + x_ * w_), 1 - 2 * (x_ * x_ + y_ * y_)],
    ]
    m[:3, 3] = (x, y, z)
    return m


def axis_angle_pose(x: float, y: float, z: float, axis: Sequence[float], theta: float) -> np.ndarray:
    """The 4x4 pose of a ``.cfg`` state: OMPL's ``setAxisAngle(ax, ay, az, theta)``.

    The axis is normalised; an axis shorter than 1e-9 gives the identity
    rotation, as in OMPL.
    """
    ax, ay, az = (float(a) for a in axis)
    norm = math.sqrt(ax * ax + ay * ay + az * az)
    if norm < 1e-9:  # OMPL's MAX_QUATERNION_NORM_ERROR
        return state_pose(x, y, z, 0.0, 0.0, 0.0, 1.0)
    s = math.sin(float(theta) / 2.0) / norm
    return state_pose(x, y, z, s * ax, s * ay, s * az, math.cos(float(theta) / 2.0))


def load_path(path_file: PathLike) -> np.ndarray:
    """The states of an OMPL ``.path`` file as ``(K, 4, 4)`` float64 poses.

    Each non-blank line is one SE(3) state, ``x y z qx qy qz qw``, as OMPL's
    ``PathGeometric::printAsMatrix`` prints it (translation, then the
    quaternion with the scalar last). The poses move
    :attr:`Problem.robot_vertices`.
    """
    poses = []
    with open(path_file, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            words = line.split()
            if not words:
                continue
            if len(words) != 7:
                raise ValueError(f"{path_file}:{number}: expected 7 numbers (x y z qx qy qz qw), got {len(words)}")
            poses.append(state_pose(*(float(w) for w in words)))
    return np.array(poses, dtype=float).reshape(-1, 4, 4)


# --------------------------------------------------------------------------
# .cfg


def read_cfg(cfg_file: PathLike) -> Dict[str, str]:
    """The settings of an OMPL.app ``.cfg`` as ``{"section.key": "value"}``.

    The INI-like format Boost.Program_options reads: ``[section]`` lines,
    ``key = value`` lines, ``#`` starting a comment. A key given twice keeps
    its last value (only ``[planner]`` entries repeat, and they are not
    used here).
    """
    settings: Dict[str, str] = {}
    section = ""
    with open(cfg_file, encoding="utf-8") as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            if line.startswith("[") and line.endswith("]"):
                section = line[1:-1].strip()
                continue
            if "=" not in line:
                raise ValueError(f"{cfg_file}: not a 'key = value' line: {line!r}")
            key, value = (s.strip() for s in line.split("=", 1))
            settings[f"{section}.{key}" if section else key] = value
    return settings


def _number(settings: Dict[str, str], key: str, cfg_file: PathLike) -> float:
    try:
        return float(settings[key])
    except KeyError:
        raise ValueError(f"{cfg_file}: no {key}") from None
    except ValueError:
        raise ValueError(f"{cfg_file}: {key} = {settings[key]!r} is not a number") from None


def _cfg_pose(settings: Dict[str, str], which: str, cfg_file: PathLike) -> np.ndarray:
    n = lambda k: _number(settings, f"problem.{which}.{k}", cfg_file)  # noqa: E731
    return axis_angle_pose(n("x"), n("y"), n("z"), (n("axis.x"), n("axis.y"), n("axis.z")), n("theta"))


# --------------------------------------------------------------------------
# Meshes


@dataclasses.dataclass
class _Mesh:
    vertices: np.ndarray  # (N, 3) float64, world frame of the file
    faces: np.ndarray  # (M, 3) int64
    centre_sum: np.ndarray  # sum of Assimp's vertices (after JoinIdenticalVertices)
    centre_count: int


def load_mesh(mesh_file: PathLike) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A mesh file as OMPL.app sees it: ``(vertices, faces, centre)``.

    ``vertices`` ``(N, 3)`` float64 in the file's world frame turned as
    Assimp turns it (module docstring), ``faces`` ``(M, 3)`` int64, every
    triangle, and ``centre`` the mean of Assimp's vertices (OMPL.app's
    robot centre; not subtracted here). COLLADA files need pycollada, other
    formats trimesh (``pip install trimesh pycollada``).
    """
    m = _load_mesh(pathlib.Path(mesh_file))
    return m.vertices, m.faces, m.centre_sum / max(m.centre_count, 1)


def _load_mesh(mesh_file: pathlib.Path) -> _Mesh:
    if not mesh_file.is_file():
        raise FileNotFoundError(f"no mesh file {mesh_file}")
    if mesh_file.suffix.lower() == ".dae":
        return _load_collada(mesh_file)
    return _load_trimesh(mesh_file)


def _unique_first(rows: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Indices of the first occurrence of each distinct row (in order) and
    for each row the position of its class in that list."""
    if len(rows) == 0:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    rows = np.ascontiguousarray(rows)
    _, first, inverse = np.unique(rows, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    return first[order], rank[np.asarray(inverse).reshape(-1)]


def _joined_vertices(positions: np.ndarray, attributes: List[np.ndarray]) -> np.ndarray:
    """Assimp's JoinIdenticalVertices on one mesh: the indices of the corners
    it keeps. ``positions`` ``(n, 3)`` float32 per corner, ``attributes``
    per-corner float32 arrays (normals, texture coordinates, ...)."""
    # +0.0 turns -0.0 into 0.0: Assimp compares values, not bits.
    pos = positions.astype(np.float32) + np.float32(0.0)
    if not attributes:
        return _unique_first(pos)[0]
    attrs = [a.astype(np.float32) + np.float32(0.0) for a in attributes]
    candidates, _ = _unique_first(np.concatenate([pos, *attrs], axis=1))
    # Corners that differ only by attributes within 1e-5 are joined too:
    # look at the positions holding more than one candidate.
    _, group = _unique_first(pos[candidates])
    counts = np.bincount(group)
    if counts.max(initial=0) <= 1:
        return candidates
    keep = np.ones(len(candidates), dtype=bool)
    for g in np.flatnonzero(counts > 1):
        members = np.flatnonzero(group == g)  # in order of first occurrence
        kept: List[int] = []
        for i in members:
            ci = candidates[i]
            for k in kept:
                ck = candidates[k]
                if all(float(np.sum(np.square(a[ci] - a[ck], dtype=np.float32), dtype=np.float32)) <= _JOIN_EPS2 for a in attrs):
                    keep[i] = False
                    break
            else:
                kept.append(int(i))
    return candidates[keep]


def _face_normals(corners: np.ndarray) -> np.ndarray:
    """GenNormals (flat) for a mesh without normals: ``(t, 3, 3)`` corners ->
    ``(3t, 3)`` per-corner normals."""
    c = corners.astype(np.float32)
    n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    n = np.divide(n, length, out=np.zeros_like(n), where=length > 0)
    return np.repeat(n, 3, axis=0)


def _collada_instances(node: Any, matrix: np.ndarray, collada: Any) -> Iterator[Tuple[Any, np.ndarray]]:
    """(geometry, world matrix) for every geometry instance below ``node``,
    depth first as Assimp walks them."""
    if isinstance(node, collada.scene.GeometryNode):
        yield node.geometry, matrix
    elif isinstance(node, collada.scene.ControllerNode):
        raise ValueError("COLLADA controllers (skinned or morphed meshes) are not supported")
    elif isinstance(node, collada.scene.Node):  # NodeNode (<instance_node>) too
        local = np.eye(4)
        defined = node.node if isinstance(node, collada.scene.NodeNode) else node
        for t in defined.transforms:
            local = local @ np.asarray(t.matrix, dtype=float)
        for child in node.children or ():
            yield from _collada_instances(child, matrix @ local, collada)


def _load_collada(mesh_file: pathlib.Path) -> _Mesh:
    try:
        import collada
    except ImportError as e:
        raise ImportError(f"reading COLLADA (.dae) files needs pycollada: {_INSTALL}") from e

    doc = collada.Collada(str(mesh_file))
    scene = doc.scene if doc.scene is not None else (doc.scenes[0] if doc.scenes else None)
    if scene is None:
        raise ValueError(f"{mesh_file}: no visual scene")
    root = np.eye(4)
    up = doc.assetInfo.upaxis if doc.assetInfo is not None else None
    up = getattr(up, "value", up)  # an enum in some pycollada versions
    root[:3, :3] = _UP_AXIS.get(str(up) if up is not None else "Y_UP", np.eye(3))
    unit = doc.assetInfo.unitmeter if doc.assetInfo is not None else None
    if unit is not None:
        root[:3, :3] *= float(unit)

    vertices: List[np.ndarray] = []
    faces: List[np.ndarray] = []
    offset = 0
    centre_sum = np.zeros(3)
    centre_count = 0
    for node in scene.nodes:
        for geometry, matrix in _collada_instances(node, root, collada):
            # This instance's triangles, as rows into its position array
            # (one per primitive's VERTEX source; in a <mesh> they all share
            # its <vertices>): each file vertex once per instance.
            triangles: Dict[int, Tuple[np.ndarray, List[np.ndarray]]] = {}
            for prim in geometry.primitives:
                if isinstance(prim, collada.lineset.LineSet):
                    kind = "lines"
                elif isinstance(prim, collada.polylist.Polylist):  # <polygons> too
                    kind = "polygons"
                elif isinstance(prim, collada.triangleset.TriangleSet):
                    kind = "triangles"
                else:
                    raise ValueError(f"{mesh_file}: unsupported COLLADA primitive {type(prim).__name__}")
                sources = prim.sources
                if not sources.get("VERTEX") or len(prim.index) == 0:
                    continue
                width = prim.index.shape[-1]
                index = np.asarray(prim.index).reshape(-1, width)  # one row per corner
                voff, _, _, _, vsrc = sources["VERTEX"][0]
                positions = np.asarray(vsrc.data, dtype=np.float32).reshape(-1, 3)
                corner_v = index[:, voff]
                if kind != "lines":
                    tri = corner_v if kind == "triangles" else np.asarray(prim.triangleset().vertex_index)
                    triangles.setdefault(id(vsrc), (positions, []))[1].append(tri.reshape(-1, 3))

                # Assimp's vertices of this primitive's mesh (for the centre).
                attributes = []
                for semantic in ("NORMAL", "TEXCOORD", "TEXTANGENT", "TEXBINORMAL"):
                    if sources.get(semantic):
                        off, _, _, _, src = sources[semantic][0]
                        data = np.asarray(src.data, dtype=np.float32)
                        attributes.append(data.reshape(len(data), -1)[index[:, off]])
                if kind != "lines" and not sources.get("NORMAL"):  # GenNormals: flat normals
                    if kind == "triangles":
                        attributes.insert(0, _face_normals(positions[corner_v].reshape(-1, 3, 3)))
                    else:  # a (planar) polygon's normal from its first three corners
                        counts = np.asarray(prim.vcounts, dtype=np.int64)
                        starts = np.cumsum(counts) - counts
                        firsts = np.stack([corner_v[np.minimum(starts + k, len(corner_v) - 1)] for k in range(3)], axis=1)
                        attributes.insert(0, np.repeat(_face_normals(positions[firsts])[::3], counts, axis=0))
                kept = corner_v[_joined_vertices(positions[corner_v], attributes)]
                world = positions[kept].astype(float) @ matrix[:3, :3].T + matrix[:3, 3]
                centre_sum += world.sum(axis=0)
                centre_count += len(world)

            for positions, tris in triangles.values():
                rows = np.concatenate(tris)
                used, remap = np.unique(rows, return_inverse=True)
                vertices.append(positions[used].astype(float) @ matrix[:3, :3].T + matrix[:3, 3])
                faces.append(np.asarray(remap).reshape(-1, 3).astype(np.int64) + offset)
                offset += len(used)
    return _Mesh(
        vertices=np.concatenate(vertices) if vertices else np.zeros((0, 3)),
        faces=np.concatenate(faces) if faces else np.zeros((0, 3), dtype=np.int64),
        centre_sum=centre_sum,
        centre_count=centre_count,
    )


def _load_trimesh(mesh_file: pathlib.Path) -> _Mesh:
    try:
        import trimesh
    except ImportError as e:
        raise ImportError(f"reading {mesh_file.suffix} meshes needs trimesh: {_INSTALL}") from e

    loaded: Any = trimesh.load(str(mesh_file), process=False, force="scene")
    vertices: List[np.ndarray] = []
    faces: List[np.ndarray] = []
    offset = 0
    centre_sum = np.zeros(3)
    centre_count = 0
    stl = mesh_file.suffix.lower() == ".stl"
    for node in loaded.graph.nodes_geometry:
        transform, name = loaded.graph[node]
        geom = loaded.geometry[name]
        if not isinstance(geom, trimesh.Trimesh):
            continue  # point clouds, paths: no triangles
        v = np.asarray(geom.vertices, dtype=float) @ np.asarray(transform, float)[:3, :3].T + np.asarray(transform, float)[:3, 3]
        f = np.asarray(geom.faces, dtype=np.int64)
        vertices.append(v)
        faces.append(f + offset)
        offset += len(v)
        # Assimp's vertices: an STL file gives each corner its facet normal.
        corners = f.reshape(-1)
        attrs = [np.repeat(np.asarray(geom.face_normals, dtype=np.float32), 3, axis=0)] if stl else []
        kept = corners[_joined_vertices(v[corners].astype(np.float32), attrs)] if stl else np.unique(corners)
        centre_sum += v[kept].sum(axis=0)
        centre_count += len(kept)
    return _Mesh(
        vertices=np.concatenate(vertices) if vertices else np.zeros((0, 3)),
        faces=np.concatenate(faces) if faces else np.zeros((0, 3), dtype=np.int64),
        centre_sum=centre_sum,
        centre_count=centre_count,
    )


# --------------------------------------------------------------------------
# Problems


def load_problem(cfg_path: PathLike) -> Problem:
    """Read an OMPL.app 3-D problem (a ``.cfg`` and the meshes it names).

    The ``.cfg``'s ``problem.robot`` and ``problem.world`` are found beside
    it. Returns a :class:`Problem`: the robot in its own frame (OMPL.app's
    centre subtracted), the environment, start and goal as 4x4 poses, the
    translation bounds and the time limit; the module docstring says how
    each follows OMPL.app. Needs pycollada for ``.dae`` meshes and trimesh
    for other formats (``pip install trimesh pycollada``).
    """
    cfg_file = pathlib.Path(cfg_path)
    settings = read_cfg(cfg_file)
    base = cfg_file.parent

    def mesh_path(key: str) -> pathlib.Path:
        if f"problem.{key}" not in settings:
            raise ValueError(f"{cfg_file}: no problem.{key}")
        return base / settings[f"problem.{key}"]

    robot_file, env_file = mesh_path("robot"), mesh_path("world")
    robot = _load_mesh(robot_file)
    env = _load_mesh(env_file)
    if robot.centre_count == 0:
        raise ValueError(f"{robot_file}: no vertices")
    centre = robot.centre_sum / robot.centre_count

    keys = [f"problem.volume.{e}.{a}" for e in ("min", "max") for a in "xyz"]
    if all(k in settings for k in keys):
        low = np.array([_number(settings, k, cfg_file) for k in keys[:3]])
        high = np.array([_number(settings, k, cfg_file) for k in keys[3:]])
    elif len(env.vertices):
        # OMPL.app's inferEnvironmentBounds (factor 1, add 0).
        low, high = env.vertices.min(axis=0), env.vertices.max(axis=0)
    else:
        raise ValueError(f"{cfg_file}: no volume.min/max and an empty environment")

    time_limit = _number(settings, "benchmark.time_limit", cfg_file) if "benchmark.time_limit" in settings else None
    path_file = cfg_file.with_suffix(".path")
    return Problem(
        name=settings.get("problem.name", cfg_file.stem),
        robot_vertices=robot.vertices - centre,
        robot_faces=robot.faces,
        env_vertices=env.vertices,
        env_faces=env.faces,
        start=_cfg_pose(settings, "start", cfg_file),
        goal=_cfg_pose(settings, "goal", cfg_file),
        bounds=(low, high),
        time_limit=time_limit,
        robot_centre=centre,
        cfg_file=cfg_file,
        robot_file=robot_file,
        env_file=env_file,
        path_file=path_file if path_file.is_file() else None,
    )
