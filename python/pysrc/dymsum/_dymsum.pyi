"""Type stubs of dymsum's extension module (re-exported by ``dymsum``).

Conventions: shapes are (N, 3) point clouds (their exact hull), ``(vertices,
faces)`` pairs, objects with ``.vertices``/``.faces`` (trimesh),
:class:`Polytope`, or model names and mesh file paths (as :func:`load`);
poses are 4×4 homogeneous rigid transforms (``None`` is the identity) or
rotations about the origin; a rotation is a
``scipy.spatial.transform.Rotation``, a 3×3 matrix, or a quaternion
``(x, y, z, w)``, scalar last, as scipy.

Any memory layout is accepted wherever an array is taken (C- or
Fortran-ordered, transposed, negatively strided, sliced, broadcast,
big-endian, ``np.matrix``, nested lists): arrays are read by their logical
indices, so the answer never depends on the layout. Errors are
``ValueError`` naming the argument: among them an empty face array (a
``(vertices, faces)`` pair with no face is never the hull of its vertices),
a mesh with no triangle left after cleaning, a face index out of range
(quoted as given, unsigned included) and ``None`` where a body or the
obstacles are expected.
"""

import os
from typing import IO, Any, Callable, Dict, Literal, Mapping, Optional, Protocol, Sequence, Tuple, Union, final, overload

import numpy as np
import numpy.typing as npt
from typing_extensions import disjoint_base

__version__: str
__all__ = [
    "read_mesh_bodies",
    "Polytope",
    "Robot",
    "RobotChecker",
    "DynamicSum",
    "Contact",
    "ContactTracker",
    "Contacts",
    "ConvexUnion",
    "MotionCheck",
    "MotionChecks",
    "MotionChecker",
    "MotionUndecided",
    "check_motion",
    "check_motions",
    "Slab",
    "minkowski_sum",
    "collides_many",
    "contact",
    "contact_many",
    "cobstacle_slices",
    "pose",
    "load",
    "save",
    "models",
    "__version__",
    "_rotations_xyzw",
    "_triangle_sums",
    "_uncontained",
    "_check_closed_mesh",
    "_surfaces_touch",
    "_cobstacle_block",
    "_cobstacle_map_fields",
    "_read_cobstacle_map",
    "_write_cobstacle_map",
    "check_solid",
]

class _MeshLike(Protocol):
    @property
    def vertices(self) -> Any: ...
    @property
    def faces(self) -> Any: ...

_Faces = Union[npt.ArrayLike, Sequence[Sequence[int]]]
"""An (M, k) integer array (any integer dtype and memory layout), or a list
of index lists (polygons of any size); at least one face (an empty one is a
``ValueError``)."""

_ShapeLike = Union["Polytope", str, os.PathLike[str], npt.ArrayLike, Tuple[npt.ArrayLike, _Faces], _MeshLike]
"""An (N, 3) point array (its exact convex hull), a ``(vertices, faces)`` pair,
an object with ``.vertices`` and ``.faces`` (a trimesh.Trimesh), a Polytope, or
a built-in model name or mesh file path (as :func:`load`)."""

class _RotationLike(Protocol):
    """A ``scipy.spatial.transform.Rotation`` (scipy is not imported: any
    object with ``as_quat()`` returning ``(x, y, z, w)`` and ``as_matrix()``)."""

    def as_quat(self) -> Any: ...
    def as_matrix(self) -> Any: ...

_Rotation = Union[_RotationLike, npt.ArrayLike]
"""A ``scipy.spatial.transform.Rotation``, a (4,) quaternion ``(x, y, z, w)``
(scalar last, as scipy) or a 3×3 rotation matrix."""

_PoseLike = Optional[_Rotation]
"""A 4×4 homogeneous rigid transform (rotation block, translation in the last
column, last row ``0 0 0 1``); a rotation about the origin (a
``scipy.spatial.transform.Rotation``, a (4,) quaternion ``(x, y, z, w)``,
scalar last as scipy, or a 3×3 rotation matrix); or ``None`` (the identity;
in ``update`` methods: the body stays). Any memory layout: a Fortran-ordered
(column-major, as Eigen-based bindings hand out) or transposed 4×4 reads as
the same matrix C-ordered."""

_Rotations = Union[_RotationLike, npt.ArrayLike]
"""A ``scipy.spatial.transform.Rotation`` (one or a stack), (K, 4) quaternions
``(x, y, z, w)``, (K, 3, 3) rotation matrices, (K, 4, 4) homogeneous
transforms without translation, or one (4,) quaternion or 3×3 matrix."""

_Vertices = npt.NDArray[np.float64]
_Triangles = npt.NDArray[np.int64]
_Polygons = list[npt.NDArray[np.int64]]
_Method = Literal["walk", "brute", "hull"]

@final
class Polytope:
    """A convex polytope: the exact hull of a point cloud, or a validated convex mesh.

    ``strict=True`` refuses meshes that are convex only within tolerance
    (otherwise replaced by the exact hull of their vertices). Raises
    ``ValueError`` for bad input.

    >>> cube = Polytope([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)])
    >>> cube.volume, cube.face_count
    (1.0, 6)
    """

    def __new__(cls, a: _ShapeLike, strict: bool = False) -> Polytope: ...
    def __reduce__(self) -> Tuple[Any, Tuple[_Vertices]]:
        """Pickles as ``Polytope(vertices)`` (the same hull)."""
    @property
    def vertices(self) -> _Vertices:
        """Read-only (n, 3) float64 array (the same array on every access)."""
    @property
    def faces(self) -> _Triangles:
        """Read-only (m, 3) int64 fan triangles, counter-clockwise from outside."""
    @property
    def polygons(self) -> _Polygons:
        """The maximal convex polygon faces."""
    def mesh(self, polygons: bool = False) -> Tuple[_Vertices, Union[_Triangles, _Polygons]]:
        """``(vertices, faces)``: triangles, or polygons with ``polygons=True``."""
    @property
    def volume(self) -> float: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def edge_count(self) -> int: ...
    @property
    def face_count(self) -> int:
        """Number of maximal (polygon) faces."""
    @property
    def source(self) -> str:
        """``"points"``, ``"mesh"``, ``"built-in NAME"`` or ``"file PATH"``."""
    @property
    def convexity_report(self) -> dict[str, Any]:
        """source, point_cloud, input_vertices, input_faces, input_triangles,
        vertices, faces, exactly_convex, replaced_by_hull, max_deviation,
        tolerance, dropped_vertices, inward_oriented (mesh-only entries are
        None for a point cloud)."""

@overload
def minkowski_sum(
    a: _ShapeLike,
    b: _ShapeLike,
    pose_a: _PoseLike = None,
    pose_b: _PoseLike = None,
    method: _Method = "walk",
    polygons: Literal[False] = False,
) -> Tuple[_Vertices, _Triangles]:
    """``(R_a A + t_a) ⊕ (R_b B + t_b)``, exactly, as ``(vertices, faces)``.

    Poses are 4×4 homogeneous rigid transforms, or rotations about the
    origin (a scipy ``Rotation``, a 3×3 matrix, a quaternion ``(x, y, z, w)``).

    >>> v, f = minkowski_sum(load("cube"), load("gs1"), pose_a=pose([0, 0, 0.38268343, 0.92387953]))
    """
@overload
def minkowski_sum(
    a: _ShapeLike,
    b: _ShapeLike,
    pose_a: _PoseLike = None,
    pose_b: _PoseLike = None,
    method: _Method = "walk",
    *,
    polygons: Literal[True],
) -> Tuple[_Vertices, _Polygons]: ...
@overload
def minkowski_sum(
    a: _ShapeLike,
    b: _ShapeLike,
    pose_a: _PoseLike = None,
    pose_b: _PoseLike = None,
    method: _Method = "walk",
    polygons: bool = False,
) -> Tuple[_Vertices, Union[_Triangles, _Polygons]]: ...

@disjoint_base
class DynamicSum:
    """``A ⊕ B`` kept up to date while the bodies move (DYMSUM).

    Poses are 4×4 homogeneous rigid transforms, or rotations about the
    origin (a scipy ``Rotation``, a 3×3 matrix, a quaternion ``(x, y, z, w)``).

    >>> s = DynamicSum(load("ellipse"), load("gs4"))
    >>> report = s.update(pose([0, 0, 0.0087265, 0.9999619]))
    >>> vertices, faces = s.mesh()
    """

    def __new__(cls, a: _ShapeLike, b: _ShapeLike, pose_a: _PoseLike = None, pose_b: _PoseLike = None) -> DynamicSum: ...
    def update(self, pose_a: _PoseLike = None, pose_b: _PoseLike = None) -> dict[str, Any]:
        """Moves A and B (``None`` keeps that body where it is) and repairs the sum. The report:
        fv_errors, ee_errors, errors, removed, added, facets, step_angle,
        recomputed, recovered."""
    @overload
    def mesh(self, polygons: Literal[False] = False) -> Tuple[_Vertices, _Triangles]: ...
    @overload
    def mesh(self, polygons: Literal[True]) -> Tuple[_Vertices, _Polygons]: ...
    @overload
    def mesh(self, polygons: bool = False) -> Tuple[_Vertices, Union[_Triangles, _Polygons]]: ...
    @property
    def facet_count(self) -> int: ...
    @property
    def pose_a(self) -> npt.NDArray[np.float64]: ...
    @property
    def pose_b(self) -> npt.NDArray[np.float64]: ...

@final
class Contact:
    """Depth or distance of A and B.

    ``normal`` is the unit vector from A towards B: when colliding, moving A
    by ``-depth * normal`` separates the bodies, and ``point_a - point_b ==
    depth * normal``; when apart, ``point_a``/``point_b`` are the closest
    points and ``normal`` points from ``point_a`` to ``point_b``.
    """

    @property
    def collides(self) -> bool: ...
    @property
    def depth(self) -> float:
        """Penetration depth (0.0 when apart or touching)."""
    @property
    def distance(self) -> float:
        """Distance (0.0 when colliding)."""
    @property
    def normal(self) -> npt.NDArray[np.float64]:
        """(3,) unit normal from A towards B."""
    @property
    def point_a(self) -> npt.NDArray[np.float64]: ...
    @property
    def point_b(self) -> npt.NDArray[np.float64]: ...

def contact(a: _ShapeLike, b: _ShapeLike, pose_a: _PoseLike = None, pose_b: _PoseLike = None) -> Contact:
    """Exact penetration depth or distance of A and B at 4×4 poses.

    >>> contact(load("cube"), load("cube"), None, pose(translation=[1.0, 0, 0])).depth
    """

@final
class ContactTracker:
    """Contact of A and B over a motion, with the answers of ``contact`` at every frame.

    ``strategy="certified"``: certified support-function queries warm-started
    from the last frame; ``"sum"``: the dynamic sum repaired by DYMSUM, every
    facet evaluated; ``"auto"`` (default): the faster of the two, measured.
    """

    def __new__(
        cls,
        a: _ShapeLike,
        b: _ShapeLike,
        pose_a: _PoseLike = None,
        pose_b: _PoseLike = None,
        strategy: Literal["auto", "certified", "sum"] = "auto",
    ) -> ContactTracker: ...
    def update(self, pose_a: _PoseLike = None, pose_b: _PoseLike = None) -> Contact:
        """Moves A and B to these 4×4 poses (``None`` keeps that body where it is) and answers."""
    @property
    def last(self) -> Contact: ...
    @property
    def last_update(self) -> dict[str, Any]: ...
    @property
    def strategy(self) -> str: ...
    @property
    def active_strategy(self) -> str: ...
    @property
    def stats(self) -> dict[str, int]:
        """queries, exhaustive_decisions, exhaustive_answers, carried_polytopes, carried_restarts."""

@final
class Contacts:
    """The answers of ``contact_many``: one row per pose."""

    @property
    def collides(self) -> npt.NDArray[np.bool_]: ...
    @property
    def depth(self) -> npt.NDArray[np.float64]: ...
    @property
    def distance(self) -> npt.NDArray[np.float64]: ...
    @property
    def normal(self) -> npt.NDArray[np.float64]: ...
    @property
    def point_a(self) -> npt.NDArray[np.float64]: ...
    @property
    def point_b(self) -> npt.NDArray[np.float64]: ...
    def __len__(self) -> int: ...

@final
class Slab:
    """A certified C-obstacle slab (``cobstacle_slices(..., certified=True)``):
    ``{x : normals @ x <= offsets}`` contains every slice for every rotation on
    the shortest path between its two end rotations (with ``cell_radius=rho``:
    within angle ``rho`` of its centre rotation)."""

    @property
    def normals(self) -> npt.NDArray[np.float64]:
        """Read-only (M, 3) unit outward normals."""
    @property
    def offsets(self) -> npt.NDArray[np.float64]:
        """Read-only (M,) offsets, rounded outward."""
    @property
    def margin(self) -> float:
        """How far each plane is pushed beyond the end slices' hull (sagitta, or
        ``r·rho`` for a cell, and rounding)."""
    @property
    def rotations(self) -> npt.NDArray[np.float64]:
        """The end rotations, (2, 4) quaternions ``(x, y, z, w)``; a cell's centre, (1, 4)."""
    @property
    def angle(self) -> float:
        """An upper bound on the angle between the end rotations (radians); a cell's radius."""
    @property
    def cell_radius(self) -> Optional[float]:
        """The cell's radius (radians), ``None`` for a slab between two rotations."""
    @overload
    def contains(self, points: Sequence[float]) -> bool:
        """Exact ``normals @ x <= offsets`` for one (3,) point, or each of (N, 3) points."""
    @overload
    def contains(self, points: npt.ArrayLike) -> Union[bool, npt.NDArray[np.bool_]]: ...
    @overload
    def mesh(self, polygons: Literal[False] = False) -> Tuple[_Vertices, _Triangles]:
        """``(vertices, faces)`` of a checked convex mesh containing the slab."""
    @overload
    def mesh(self, polygons: Literal[True]) -> Tuple[_Vertices, _Polygons]: ...
    @overload
    def mesh(self, polygons: bool = False) -> Tuple[_Vertices, Union[_Triangles, _Polygons]]: ...
    def __len__(self) -> int:
        """The number of half-spaces."""

_PosesLike = Union[None, npt.ArrayLike, _RotationLike]
"""K poses: a (K, 4, 4) array of homogeneous rigid transforms (any memory
layout: a Fortran-ordered, per-pose transposed, sliced or reversed stack is
read by its strides, no copy), (K, 4) quaternions ``(x, y, z, w)``, (K, 3, 3)
rotation matrices, a scipy ``Rotation`` stack; or one pose for all
(``None``: the identity)."""

def contact_many(a: _ShapeLike, b: _ShapeLike, poses_a: _PosesLike = None, poses_b: _PosesLike = None) -> Contacts:
    """``contact`` at K poses ((K, 4, 4) arrays, or one pose for all), in parallel."""

def collides_many(
    a: _ShapeLike, b: _ShapeLike, poses_a: _PosesLike = None, poses_b: _PosesLike = None
) -> npt.NDArray[np.bool_]:
    """Overlap or touch at K poses, as a (K,) bool array (GJK with exact certificates)."""

@overload
def cobstacle_slices(
    robot: _ShapeLike,
    obstacle: _ShapeLike,
    rotations: _Rotations,
    polygons: Literal[False] = False,
    parallel: bool = False,
    certified: Literal[False] = False,
    cell_radius: None = None,
) -> list[Tuple[_Vertices, _Triangles]]:
    """C-obstacle slices ``obstacle ⊕ (−R·robot)``, one per rotation.

    ``rotations``: a scipy ``Rotation`` (one or a stack), (K, 3, 3) rotation
    matrices, (K, 4) quaternions in the order ``(x, y, z, w)`` (scalar last,
    as scipy's ``as_quat()``), (K, 4, 4) transforms without translation, or
    one (4,) quaternion or 3×3 matrix. ``certified=True``: the K − 1
    certified slabs between consecutive rotations instead (:class:`Slab`);
    with ``cell_radius=rho`` (radians, ``0 <= rho < π``) one slab per
    rotation, holding every slice within angle ``rho`` of it.
    """
@overload
def cobstacle_slices(
    robot: _ShapeLike,
    obstacle: _ShapeLike,
    rotations: _Rotations,
    polygons: Literal[True],
    parallel: bool = False,
    certified: Literal[False] = False,
    cell_radius: None = None,
) -> list[Tuple[_Vertices, _Polygons]]: ...
@overload
def cobstacle_slices(
    robot: _ShapeLike,
    obstacle: _ShapeLike,
    rotations: _Rotations,
    polygons: Literal[False] = False,
    parallel: bool = False,
    *,
    certified: Literal[True],
    cell_radius: Optional[float] = None,
) -> list[Slab]: ...
@overload
def cobstacle_slices(
    robot: _ShapeLike,
    obstacle: _ShapeLike,
    rotations: _Rotations,
    polygons: bool = False,
    parallel: bool = False,
    certified: bool = False,
    cell_radius: Optional[float] = None,
) -> Union[list[Tuple[_Vertices, Union[_Triangles, _Polygons]]], list[Slab]]: ...

@final
class ConvexUnion:
    """A union of convex pieces (a convex decomposition; pieces may overlap)."""

    def __new__(cls, pieces: Sequence[_ShapeLike]) -> ConvexUnion: ...
    @property
    def pieces(self) -> list[Polytope]: ...
    def __len__(self) -> int: ...
    def __reduce__(self) -> Tuple[Any, Tuple[list[Polytope]]]:
        """Pickles as ``ConvexUnion(pieces)``."""

_BodyLike = Union[ConvexUnion, _ShapeLike]
_PlacedLike = Tuple[_BodyLike, _PoseLike]
_ObstaclesLike = Union[ConvexUnion, _ShapeLike, _PlacedLike, Sequence[Union[ConvexUnion, _ShapeLike, _PlacedLike]]]

class MotionUndecided(RuntimeError):
    """A motion grazing an obstacle within rounding, or one that used up its
    work budget: neither free nor colliding certified; every ``t <= t_safe``
    is certified free."""

    t_safe: float
    t: Optional[float]
    index: Optional[int]
    budget_exhausted: bool

@final
class MotionCheck:
    """The answer of a certified motion check."""

    @property
    def free(self) -> bool: ...
    @property
    def t_safe(self) -> Optional[float]:
        """Every ``t <= t_safe`` is certified free: ``1.0`` for a free motion;
        ``None`` when the body collides at the start pose (no instant is free)."""
    @property
    def t_contact(self) -> Optional[float]:
        """A time at which the body touches or overlaps an obstacle
        (``t_contact - t_safe <= tolerance``; ``0.0`` when colliding at the start);
        ``None`` for a free motion."""
    def __bool__(self) -> bool: ...

@final
class MotionChecks:
    """The answers of ``check_motions``: one row per motion."""

    @property
    def free(self) -> npt.NDArray[np.bool_]: ...
    @property
    def t_safe(self) -> npt.NDArray[np.float64]:
        """(K,) last times certified free (``nan``: colliding at the start)."""
    @property
    def t_contact(self) -> npt.NDArray[np.float64]:
        """(K,) times of contact (``nan``: free)."""
    def __len__(self) -> int: ...

@final
class Robot:
    """A robot read from a URDF: links, joints and collision geometry."""

    @staticmethod
    def from_urdf(
        path: Union[str, os.PathLike[str]],
        srdf: Optional[Union[str, os.PathLike[str]]] = None,
        package_dirs: Optional[Sequence[Union[str, os.PathLike[str]]]] = None,
    ) -> Robot: ...
    @property
    def joint_names(self) -> list[str]: ...
    @property
    def link_names(self) -> list[str]: ...
    @property
    def dof(self) -> int: ...
    @property
    def joint_limits(self) -> list[Tuple[float, float]]: ...
    @property
    def deviations(self) -> list[Tuple[str, float]]: ...
    @property
    def collision_pairs(self) -> list[Tuple[str, str]]: ...
    @collision_pairs.setter
    def collision_pairs(self, pairs: Sequence[Tuple[str, str]]) -> None: ...
    def forward(self, q: Sequence[float]) -> npt.NDArray[np.float64]: ...

@final
class RobotChecker:
    """Exact configuration checks and certified joint-space motions of a robot."""

    def __new__(cls, robot: Robot, obstacles: Optional[_ObstaclesLike] = None, budget: Optional[int] = None) -> RobotChecker: ...
    @property
    def budget(self) -> int: ...
    @property
    def dof(self) -> int: ...
    def collides_at(self, q: Sequence[float]) -> bool: ...
    def collides_many(self, qs: npt.ArrayLike) -> npt.NDArray[np.bool_]: ...
    def colliding_pairs(self, q: Sequence[float]) -> list[Tuple[str, Optional[str]]]: ...
    def distance_at(self, q: Sequence[float]) -> float: ...
    def check(self, q0: Sequence[float], q1: Sequence[float], tolerance: float = 1e-6) -> MotionCheck: ...
    def sampled_contact(self, q0: Sequence[float], q1: Sequence[float], segments: int, most: int = 7) -> Optional[float]: ...

@final
class MotionChecker:
    """A body and obstacles prepared for many certified motion checks."""

    def __new__(cls, body: _BodyLike, obstacles: _ObstaclesLike, budget: Optional[int] = None) -> MotionChecker: ...
    @property
    def budget(self) -> int: ...
    @property
    def steps(self) -> int: ...
    @property
    def containment_stats(self) -> Optional[dict[str, int]]:
        """How containment tests decided their points (``by_grid``, ``by_segment``, ``by_ray``, ``segment_fallbacks``, ``plane_cull_fallbacks``); ``None`` on the convex path."""
    def check(self, pose0: _PoseLike, pose1: _PoseLike, tolerance: float = 1e-6) -> MotionCheck:
        """The straight motion from ``pose0`` to ``pose1`` (linear translation, slerp rotation)."""
    def check_many(self, poses0: _PosesLike, poses1: _PosesLike, tolerance: float = 1e-6) -> MotionChecks:
        """``check`` for K motions ((K, 4, 4) pose arrays), in parallel."""
    def sampled_contact(self, pose0: _PoseLike, pose1: _PoseLike, segments: int, most: int = 7) -> Optional[float]:
        """The first ``k / segments`` (bisection order, at most ``most``) at which the body collides, or ``None`` (proves nothing)."""
    def collides_at(self, pose: _PoseLike = None) -> bool:
        """Whether the body at ``pose`` touches or overlaps an obstacle (exact)."""
    def distance_at(self, pose: _PoseLike = None) -> float:
        """Clearance at ``pose``: 0 in contact; exact (convex) or a certified lower bound within rounding (triangles)."""
    def collides_many(self, poses: _PosesLike) -> npt.NDArray[np.bool_]:
        """``collides_at`` for K poses ((K, 4, 4)): a (K,) bool array, in parallel."""
    @property
    def info(self) -> Dict[str, Any]:
        """How the bodies were taken: the convex path, or triangles with the cleaning's counts."""

def check_motion(
    body: _BodyLike,
    obstacles: _ObstaclesLike,
    pose0: _PoseLike,
    pose1: _PoseLike,
    tolerance: float = 1e-6,
    budget: Optional[int] = None,
) -> MotionCheck:
    """Certified check of the straight motion from ``pose0`` to ``pose1``: ``free``, ``t_safe``, ``t_contact``."""

def check_motions(
    body: _BodyLike,
    obstacles: _ObstaclesLike,
    poses0: _PosesLike,
    poses1: _PosesLike,
    tolerance: float = 1e-6,
    budget: Optional[int] = None,
) -> MotionChecks:
    """``check_motion`` for K motions ((K, 4, 4) pose arrays), in parallel."""

def pose(quaternion: Optional[_Rotation] = None, translation: Optional[Sequence[float]] = None) -> npt.NDArray[np.float64]:
    """A 4×4 pose from a rotation (a scipy ``Rotation``, a 3×3 matrix, or a
    quaternion ``(x, y, z, w)``, scalar last as scipy) and a translation."""

def load(path_or_model_name: Union[str, os.PathLike[str]], strict: bool = False) -> Polytope:
    """A polytope from a mesh file (.off, .obj, .ply, .stl) or a built-in model name."""

@overload
def save(path: Union[str, os.PathLike[str]], vertices: npt.ArrayLike, faces: _Faces) -> None: ...
@overload
def save(path: Union[str, os.PathLike[str]], vertices: _ShapeLike, faces: None = None) -> None: ...
def read_mesh_bodies(
    path: Union[str, os.PathLike[str]],
) -> list[Tuple[str, npt.NDArray[np.float64], npt.NDArray[np.int64]]]:
    """The bodies of a mesh file as written: ``(name, vertices, faces)``, polygons fan-triangulated."""

def check_solid(vertices: npt.ArrayLike, faces: Any) -> list[npt.NDArray[np.int64]]:
    """The shells (face indices) of a mesh given as a solid; ``ValueError`` saying what is wrong and where otherwise (exact)."""

def _triangle_sums(
    triangles: npt.ArrayLike, points: npt.ArrayLike
) -> list[Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]]:
    """``t ⊕ P`` for every triangle (three rows each): exact hulls of pairwise sums, in parallel."""

def _check_closed_mesh(vertices: npt.ArrayLike, faces: Any) -> Optional[str]:
    """Why the mesh is not a closed, oriented 2-manifold of positive volume, or ``None`` (exact)."""

def _uncontained(meshes: Sequence[Tuple[npt.ArrayLike, npt.ArrayLike]]) -> list[int]:
    """Indices of the convex meshes to keep: every one not certified inside a kept one (exact)."""

def models() -> list[str]:
    """Names of the built-in models and model families."""

def _rotations_xyzw(rotations: _Rotations) -> npt.NDArray[np.float64]:
    """The rotations as (K, 4) quaternions ``(x, y, z, w)``, as dymsum reads them."""

def _cobstacle_block(
    robot: _ShapeLike, obstacle: _ShapeLike, rotations: _Rotations, form: str, certified: bool
) -> Tuple[npt.NDArray[Any], ...]:
    """One task of :func:`dymsum.cobstacle_map`: one piece pair, one block of rotations."""

def _cobstacle_map_fields() -> dict[str, Tuple[str, int]]:
    """The fields of a map container: name → (dtype kind, dimensions)."""

def _read_cobstacle_map(path: Union[str, os.PathLike[str]]) -> dict[str, npt.NDArray[Any]]:
    """The arrays of a map container, validated whole by dymsum-io (``ValueError`` / ``OSError`` naming the path)."""

def _write_cobstacle_map(
    path: Union[str, os.PathLike[str]], arrays: Mapping[str, Any], open_temp: Callable[[os.PathLike[str]], IO[bytes]]
) -> None:
    """Validates a map's arrays and writes them atomically through ``open_temp(temporary path)`` (dymsum-io)."""

def _surfaces_touch(a: Any, pose_a: _PoseLike, b: Any, pose_b: _PoseLike) -> bool:
    """Whether the triangles of two meshes at their poses touch (exact, no containment). Private."""
