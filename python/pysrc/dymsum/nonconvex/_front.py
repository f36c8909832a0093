"""The front doors: ``minkowski_sum``, ``DynamicSum``/``DynamicUnionSum``, ``contact`` and ``cobstacle_slices`` on non-convex bodies (files, unions, meshes)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Dict, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from .. import _dymsum as _ext
from ._types import NeedsDecompositionError, UnionSum, _convex_sum, _manifold3d, _pose_matrix, _reflected
from ._decompose import _is_union_operand, convex_pieces
from ._union import _cull, _merge, _planes, _union_sum

if TYPE_CHECKING:
    from .._dymsum import _Method, _Polygons, _PoseLike, _ShapeLike, _Triangles, _Vertices


_NOT_CONVEX = object()


def _convex_path(call: Any, operands: Sequence[Any], union_asked: bool) -> Any:
    """``call()`` (the convex path) unless an operand is not one convex
    body: ``_NOT_CONVEX`` when ``union_asked`` (a decomposition or other
    union option was given), an operand is a :class:`ConvexUnion`, or the
    convex path refuses an operand that is a closed non-convex solid
    (:func:`_is_union_operand`). dymsum's own refusal stands otherwise."""
    if union_asked or any(isinstance(x, _ext.ConvexUnion) for x in operands):
        return _NOT_CONVEX
    try:
        return call()
    except ValueError as e:
        if not any(_is_union_operand(x) for x in operands):
            raise _what_the_mesh_is(e, operands) from e
    return _NOT_CONVEX


def _what_the_mesh_is(error: ValueError, operands: Sequence[Any]) -> ValueError:
    """The convex loader's refusal, said of the operand it concerns: a mesh
    of several closed shells is named as such (not "not a topological
    sphere"), with what to do."""
    text = str(error)
    for name, x in zip("ab", operands):
        if not text.startswith(f"{name}: ") or "topological sphere" not in text:
            continue
        mesh = _mesh_parts(x)
        if mesh is None:
            continue
        try:
            shells = _ext.check_solid(*mesh)
        except ValueError:
            continue
        if len(shells) > 1:
            return ValueError(
                f"{name}: a mesh of {len(shells)} closed shells, not one convex body; give them as "
                "dymsum.ConvexUnion([...]) of their meshes (or as one triangle mesh to the "
                "non-convex path), or check one shell at a time"
            )
    return error


def _mesh_parts(x: Any) -> Any:
    """``(vertices, faces)`` of a mesh operand (a pair, or an object with
    ``.vertices`` and ``.faces``), else ``None``."""
    if hasattr(x, "vertices") and hasattr(x, "faces"):
        return x.vertices, x.faces
    if isinstance(x, (tuple, list)) and len(x) == 2 and not isinstance(x[0], (str, bytes)):
        return x[0], x[1]
    return None


def _pieces_of_both(a: Any, b: Any, decomposition: Optional[str], options: Optional[Dict[str, Any]]) -> Any:
    """The convex pieces of both operands. When A needs a decomposition and
    B cannot be read at all (a misspelt path), B's error is the one raised:
    each error comes from the body it concerns."""
    try:
        pa, info_a = convex_pieces(a, decomposition, options, name="a")
    except NeedsDecompositionError:
        convex_pieces(b, decomposition, options, name="b")  # B's own error, if any
        raise
    pb, info_b = convex_pieces(b, decomposition, options, name="b")
    return pa, info_a, pb, info_b


@overload
def minkowski_sum(
    a: "_ext.ConvexUnion",
    b: "Union[_ext.ConvexUnion, _ShapeLike]",
    pose_a: "_PoseLike" = None,
    pose_b: "_PoseLike" = None,
    method: "_Method" = "walk",
    polygons: Literal[False] = False,
    *,
    decomposition: Optional[Literal["coacd", "vhacd", "boundary"]] = None,
    decomposition_options: Optional[Dict[str, Any]] = None,
    cull: bool = True,
) -> UnionSum: ...
@overload
def minkowski_sum(
    a: "_ShapeLike",
    b: "_ext.ConvexUnion",
    pose_a: "_PoseLike" = None,
    pose_b: "_PoseLike" = None,
    method: "_Method" = "walk",
    polygons: Literal[False] = False,
    *,
    decomposition: Optional[Literal["coacd", "vhacd", "boundary"]] = None,
    decomposition_options: Optional[Dict[str, Any]] = None,
    cull: bool = True,
) -> UnionSum: ...
@overload
def minkowski_sum(
    a: "_ShapeLike",
    b: "_ShapeLike",
    pose_a: "_PoseLike" = None,
    pose_b: "_PoseLike" = None,
    method: "_Method" = "walk",
    *,
    polygons: Literal[True],
) -> "Tuple[_Vertices, _Polygons]": ...
@overload
def minkowski_sum(
    a: "_ShapeLike",
    b: "_ShapeLike",
    pose_a: "_PoseLike" = None,
    pose_b: "_PoseLike" = None,
    method: "_Method" = "walk",
    polygons: Literal[False] = False,
    *,
    decomposition: Optional[Literal["coacd", "vhacd", "boundary"]] = None,
    decomposition_options: Optional[Dict[str, Any]] = None,
    cull: bool = True,
) -> "Tuple[_Vertices, _Triangles]": ...
def minkowski_sum(
    a: Any,
    b: Any,
    pose_a: Any = None,
    pose_b: Any = None,
    method: str = "walk",
    polygons: bool = False,
    *,
    decomposition: Optional[str] = None,
    decomposition_options: Optional[Dict[str, Any]] = None,
    cull: bool = True,
) -> Any:
    """``(R_a A + t_a) ⊕ (R_b B + t_b)`` as ``(vertices, faces)``.

    Convex operands: the exact convex sum (as ``dymsum._dymsum.minkowski_sum``).
    A :class:`ConvexUnion` or a non-convex closed mesh: the union over piece
    pairs of the exact convex sums, merged by Manifold (``manifold3d``) into
    one closed, oriented, validated mesh, returned as a :class:`UnionSum`
    (``vertices, faces`` plus ``.info``). A non-convex mesh whose components
    are not all exactly convex needs ``decomposition="coacd"`` or
    ``"vhacd"`` (``decomposition_options`` go to that library), or
    ``"boundary"`` when the other body is convex or in convex pieces (exact:
    one piece per triangle of the mesh, see :func:`_boundary_sum`). ``cull``
    drops pair sums certified inside another one.
    """
    out = _convex_path(lambda: _convex_sum(a, b, pose_a, pose_b, method, polygons), (a, b), decomposition is not None)
    if out is not _NOT_CONVEX:
        return out
    if polygons:
        raise ValueError("polygons=True is for convex sums; the sum of non-convex bodies is a triangle mesh")
    return _union_sum(a, b, pose_a, pose_b, method, decomposition, decomposition_options, cull)


class DynamicUnionSum:
    """``A ⊕ B`` of non-convex bodies kept up to date while they move.

    One :class:`DynamicSum` per pair of convex pieces, each repaired by
    DYMSUM on :meth:`update` (exact, as for convex bodies); :meth:`mesh`
    merges the current pair sums with Manifold into one validated closed
    mesh (a :class:`UnionSum`), redone on each call. Bodies as
    :func:`minkowski_sum` takes them (``decomposition`` for a non-convex
    mesh).
    """

    def __init__(
        self,
        a: Any,
        b: Any,
        pose_a: Any = None,
        pose_b: Any = None,
        *,
        decomposition: Optional[str] = None,
        decomposition_options: Optional[Dict[str, Any]] = None,
        cull: bool = True,
    ) -> None:
        self._pa, info_a = convex_pieces(a, decomposition, decomposition_options, name="a")
        self._pb, info_b = convex_pieces(b, decomposition, decomposition_options, name="b")
        self._decomposition = {"a": info_a, "b": info_b}
        self._cull = cull
        self._sums = [
            (i, j, _ext.DynamicSum(p, q, pose_a, pose_b)) for i, p in enumerate(self._pa) for j, q in enumerate(self._pb)
        ]

    def __len__(self) -> int:
        """The number of piece pairs."""
        return len(self._sums)

    def update(self, pose_a: Any = None, pose_b: Any = None) -> Dict[str, Any]:
        """Moves A and B (``None`` keeps that body where it is) and repairs
        every pair sum. The report sums the pairs' reports (``facets``,
        ``errors``, ``removed``, ``added``, ``recomputed``: pairs recomputed
        from scratch)."""
        total: Dict[str, Any] = {"pairs": len(self._sums), "facets": 0, "errors": 0, "removed": 0, "added": 0, "recomputed": 0}
        for _, _, s in self._sums:
            r = s.update(pose_a, pose_b)
            for k in ("facets", "errors", "removed", "added"):
                total[k] += int(r[k])
            total["recomputed"] += int(bool(r["recomputed"]))
        return total

    def mesh(self) -> UnionSum:
        """The current sum as one closed mesh (Manifold's union, validated)."""
        m3d = _manifold3d()
        sums = []
        for i, j, s in self._sums:
            v, f = s.mesh()
            sums.append((i, j, np.asarray(v), np.asarray(f)))
        culled = 0
        if self._cull and len(sums) > 1:
            keep = _cull(sums)
            culled = len(sums) - len(keep)
            sums = keep
        return _merge(m3d, sums, culled, len(self._pa), len(self._pb), self._decomposition)


# ---------------------------------------------------------------- contact


class UnionContact:
    """The contact of two bodies at least one of which is non-convex.

    The same attributes as :class:`Contact` — ``collides``, ``depth``,
    ``distance``, ``normal`` (from A towards B), ``point_a``, ``point_b`` —
    plus ``pair``, the indices ``(i, j)`` of the pieces that decide the
    answer, and ``info`` (``pieces``, ``decomposition`` per body, and for a
    depth ``cobstacle``: the merged C-obstacle's info).

    ``collides`` and ``distance`` are exact (the pair answers are exact; the
    distance is their minimum). ``depth`` is the distance from the origin to
    the boundary of the merged C-obstacle ``A ⊕ (−B)``: the union, by
    Manifold, of the exact piece-pair sums, so it is exact up to that
    union's float construction; ``normal`` and the witness points come from
    the closest boundary point ``p = depth · normal`` (translating A by
    ``−p`` leaves the bodies touching).
    """

    __slots__ = ("collides", "depth", "distance", "_normal", "_point_a", "_point_b", "pair", "info")

    def __init__(
        self,
        collides: bool,
        depth: float,
        distance: float,
        normal: np.ndarray,
        point_a: np.ndarray,
        point_b: np.ndarray,
        pair: Tuple[int, int],
        info: Dict[str, Any],
    ) -> None:
        self.collides = bool(collides)
        self.depth = float(depth)
        self.distance = float(distance)
        self._normal = np.array(normal, dtype=np.float64)
        self._point_a = np.array(point_a, dtype=np.float64)
        self._point_b = np.array(point_b, dtype=np.float64)
        self.pair = pair
        self.info = info

    @property
    def normal(self) -> npt.NDArray[np.float64]:
        return self._normal.copy()

    @property
    def point_a(self) -> npt.NDArray[np.float64]:
        return self._point_a.copy()

    @property
    def point_b(self) -> npt.NDArray[np.float64]:
        return self._point_b.copy()

    def __repr__(self) -> str:
        if self.collides:
            return f"UnionContact(collides=True, depth={self.depth}, normal={self._normal.tolist()}, pair={self.pair})"
        return f"UnionContact(collides=False, distance={self.distance}, normal={self._normal.tolist()}, pair={self.pair})"


def closest_boundary_point(vertices: np.ndarray, faces: np.ndarray, point: Any) -> Tuple[np.ndarray, int]:
    """The point of the triangle mesh closest to ``point``, and its triangle.

    Vectorised closest point on each triangle (Ericson's region tests);
    degenerate triangles are skipped (their edges belong to neighbours).
    """
    p = np.asarray(point, dtype=np.float64)
    t = np.asarray(vertices, dtype=np.float64)[np.asarray(faces)]
    a, b, c = t[:, 0], t[:, 1], t[:, 2]
    ab, ac = b - a, c - a
    ap, bp, cp = p - a, p - b, p - c
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        out = a + ab * (vb / denom)[:, None] + ac * (vc / denom)[:, None]
        # Regions in reverse priority: each later assignment wins.
        m = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        out[m] = (b + (c - b) * w[:, None])[m]
        m = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        w = d2 / (d2 - d6)
        out[m] = (a + ac * w[:, None])[m]
        m = (d6 >= 0) & (d5 <= d6)
        out[m] = c[m]
        m = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        w = d1 / (d1 - d3)
        out[m] = (a + ab * w[:, None])[m]
        m = (d3 >= 0) & (d4 <= d3)
        out[m] = b[m]
        m = (d1 <= 0) & (d2 <= 0)
        out[m] = a[m]
    dist = np.linalg.norm(out - p, axis=1)
    dist[~np.isfinite(dist)] = np.inf
    k = int(np.argmin(dist))
    return out[k], k


def _union_contact(
    a: Any,
    b: Any,
    pose_a: Any,
    pose_b: Any,
    decomposition: Optional[str],
    decomposition_options: Optional[Dict[str, Any]],
) -> UnionContact:
    pa, info_a, pb, info_b = _pieces_of_both(a, b, decomposition, decomposition_options)
    ta, tb = _pose_matrix(pose_a), _pose_matrix(pose_b)
    info: Dict[str, Any] = {"pieces": (len(pa), len(pb)), "decomposition": {"a": info_a, "b": info_b}}
    best = None
    hits = []
    for i, p in enumerate(pa):
        for j, q in enumerate(pb):
            c = _ext.contact(p, q, ta, tb)
            if c.collides:
                hits.append((c.depth, i, j, c))
            elif best is None or c.distance < best[0]:
                best = (c.distance, i, j, c)
    if not hits:
        assert best is not None
        _, i, j, c = best
        return UnionContact(False, 0.0, c.distance, c.normal, c.point_a, c.point_b, (i, j), info)
    # The C-obstacle A ⊕ (−B): −(R q + t) = R (−q) − t.
    neg_b = [_reflected(q) for q in pb]
    tneg = tb.copy()
    tneg[:3, 3] = -tb[:3, 3]
    sums = []
    for i, p in enumerate(pa):
        for j, q in enumerate(neg_b):
            v, f = _convex_sum(p, q, ta, tneg)
            sums.append((i, j, np.asarray(v), np.asarray(f)))
    keep = _cull(sums) if len(sums) > 1 else sums
    cobstacle = _merge(_manifold3d(), keep, len(sums) - len(keep), len(pa), len(pb), info["decomposition"])
    info["cobstacle"] = cobstacle.info
    point, _ = closest_boundary_point(cobstacle.vertices, cobstacle.faces, np.zeros(3))
    depth = float(np.linalg.norm(point))
    _, i, j, deepest = max(hits, key=lambda h: h[0])
    if not depth > 0:
        return UnionContact(True, 0.0, 0.0, deepest.normal, deepest.point_a, deepest.point_b, (i, j), info)
    normal = point / depth
    # The pair whose sum holds p most deeply decides the witnesses: A moved
    # by −p touches B there.
    inside = [float((pl[:, :3] @ point + pl[:, 3]).max()) for pl in (_planes(v, f) for _, _, v, f in sums)]
    k = int(np.argmin(inside))
    i, j = sums[k][0], sums[k][1]
    moved = ta.copy()
    moved[:3, 3] -= point
    w = _ext.contact(pa[i], pb[j], moved, tb)
    return UnionContact(True, depth, 0.0, normal, w.point_a + point, w.point_b, (i, j), info)


def contact(
    a: Any,
    b: Any,
    pose_a: Any = None,
    pose_b: Any = None,
    *,
    decomposition: Optional[str] = None,
    decomposition_options: Optional[Dict[str, Any]] = None,
) -> Any:
    """Penetration depth or distance of A and B at their poses.

    Convex bodies: the exact :class:`Contact` (``dymsum._dymsum.contact``).
    A :class:`ConvexUnion`, a closed non-convex mesh or a mesh file of
    several objects: a :class:`UnionContact` with the same attributes
    (collision and distance exact; depth from the merged C-obstacle, exact
    up to Manifold's union; needs ``manifold3d`` when the bodies collide).
    ``decomposition`` as for :func:`minkowski_sum`.

    >>> import dymsum
    >>> L = dymsum.ConvexUnion(["box:3,1,1", dymsum.Polytope([[x, y, z] for x in (-1.5, -0.5) for y in (0.5, 2) for z in (-0.5, 0.5)])])
    >>> c = dymsum.contact(L, "box:1,1,1", None, dymsum.pose(translation=[0.0, 3.0, 0.0]))
    >>> c.collides, c.distance
    (False, 0.5)
    """
    out = _convex_path(lambda: _ext.contact(a, b, pose_a, pose_b), (a, b), decomposition is not None)
    if out is not _NOT_CONVEX:
        return out
    return _union_contact(a, b, pose_a, pose_b, decomposition, decomposition_options)


# ------------------------------------------------------------- C-obstacles


def cobstacle_slices(
    robot: Any,
    obstacle: Any,
    rotations: Any,
    polygons: bool = False,
    parallel: bool = False,
    certified: bool = False,
    cell_radius: Optional[float] = None,
    *,
    decomposition: Optional[str] = None,
    decomposition_options: Optional[Dict[str, Any]] = None,
    cull: bool = True,
) -> Any:
    """C-obstacle slices ``obstacle ⊕ (−R·robot)``, one per rotation.

    Convex bodies: as ``dymsum._dymsum.cobstacle_slices`` (meshes, or
    certified :class:`Slab` s). A :class:`ConvexUnion`, a closed non-convex
    mesh or a mesh file of several objects: each piece pair's slices are
    kept by DYMSUM across the rotations, and each slice is the union of the
    pair slices merged by Manifold into one validated :class:`UnionSum`;
    with ``certified=True`` each step is a list of the piece pairs'
    :class:`Slab` s (robot piece major), whose union holds every slice
    between the two rotations.
    """
    out = _convex_path(
        lambda: _ext.cobstacle_slices(robot, obstacle, rotations, polygons, parallel, certified, cell_radius),
        (robot, obstacle),
        decomposition is not None,
    )
    if out is not _NOT_CONVEX:
        return out
    if polygons:
        raise ValueError("polygons=True is for convex bodies; a non-convex C-obstacle slice is a triangle mesh")
    pr, info_r = convex_pieces(robot, decomposition, decomposition_options, name="robot")
    po, info_o = convex_pieces(obstacle, decomposition, decomposition_options, name="obstacle")
    pairs = [(i, j) for i in range(len(pr)) for j in range(len(po))]
    per_pair = [_ext.cobstacle_slices(pr[i], po[j], rotations, False, parallel, certified, cell_radius) for i, j in pairs]
    steps = len(per_pair[0])
    if certified:
        return [[slabs[k] for slabs in per_pair] for k in range(steps)]
    m3d = _manifold3d()
    decomposition_info = {"robot": info_r, "obstacle": info_o}
    out = []
    for k in range(steps):
        sums = [(i, j, np.asarray(s[k][0]), np.asarray(s[k][1])) for (i, j), s in zip(pairs, per_pair)]
        culled = 0
        if cull and len(sums) > 1:
            keep = _cull(sums)
            culled = len(sums) - len(keep)
            sums = keep
        out.append(_merge(m3d, sums, culled, len(pr), len(po), decomposition_info))
    return out


# ------------------------------------------------------------ DynamicSum


class DynamicSum(_ext.DynamicSum):
    """``A ⊕ B`` kept up to date while the bodies move (DYMSUM).

    Convex bodies: the extension's dynamic sum (``update``, ``mesh``, ...).
    Given a :class:`ConvexUnion`, a closed non-convex mesh or a mesh file of
    several objects (or a ``decomposition``), the constructor returns a
    :class:`DynamicUnionSum` instead: one dynamic sum per piece pair, merged
    on ``mesh()``.
    """

    def __new__(cls, a: Any, b: Any, pose_a: Any = None, pose_b: Any = None, **kwargs: Any) -> Any:
        out = _convex_path(lambda: super(DynamicSum, cls).__new__(cls, a, b, pose_a, pose_b), (a, b), bool(kwargs))
        if out is not _NOT_CONVEX:
            return out
        return DynamicUnionSum(a, b, pose_a, pose_b, **kwargs)
