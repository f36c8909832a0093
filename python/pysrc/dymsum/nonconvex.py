"""Minkowski sums of non-convex bodies as one closed mesh.

``A ⊕ B`` of two unions of convex pieces is the union, over every pair of
pieces, of the exact convex sums ``a_i ⊕ b_j`` (dymsum's own, as for convex
bodies). That union is merged into one closed, oriented 2-manifold by the
Manifold library (the optional ``manifold3d`` package: never a hand-written
boolean), and the result is validated before it is returned.

What is exact, and what is not:

* each piece-pair sum is exact (every decision an exact predicate), its
  vertices rounded to ``float64`` as for any convex sum;
* the union is Manifold's float boolean (robust, with its own
  rounding-level tolerance), so the merged mesh is the true union up to that
  rounding;
* a non-convex mesh given as ``(vertices, faces)`` is split into connected
  components; components that are exactly convex (and outward) are taken as
  they are; anything else needs a decomposition (``decomposition="coacd"`` or
  ``"vhacd"``, optional extras), which is approximate: its kind and its
  volume error against the input are recorded in the result's ``info``.

The optional packages (manifold3d, coacd, vhacdx) are imported only when
used; without them a clear ``ImportError`` names the package to install.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Dict, List, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from . import _dymsum as _ext

__all__ = [
    "UnionSum",
    "UnionContact",
    "MeshUnionError",
    "DynamicSum",
    "DynamicUnionSum",
    "minkowski_sum",
    "contact",
    "cobstacle_slices",
    "convex_pieces",
    "check_closed_mesh",
    "check_solid",
    "closest_boundary_point",
]

DECOMPOSITIONS = ("coacd", "vhacd")

# The convex sum (typed by _dymsum.pyi's overloads; called here with
# arguments passed through from the caller).
_convex_sum: Any = _ext.minkowski_sum


class _NeedsDecomposition(ValueError):
    """A non-convex mesh that is not a union of exactly convex components,
    given with no decomposition; carries the mesh."""

    def __init__(self, message: str, vertices: np.ndarray, faces: np.ndarray, shells: List[np.ndarray]) -> None:
        super().__init__(message)
        self.mesh = (vertices, faces)
        self.shells = shells


class MeshUnionError(RuntimeError):
    """The union of the piece-pair sums failed: Manifold rejected a mesh, or the
    merged mesh failed validation (never returned)."""


if TYPE_CHECKING:
    from ._dymsum import _Method, _Polygons, _PoseLike, _ShapeLike, _Triangles, _Vertices


class UnionSum(Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]):
    """``(vertices, faces)`` of a non-convex Minkowski sum, with ``info``.

    Unpacks like the convex result (``vertices, faces = minkowski_sum(...)``);
    ``info`` says how it was made: ``pieces`` (per operand), ``pairs``,
    ``pairs_culled``, ``decomposition`` (per operand: ``method`` and, for an
    approximate decomposition, ``volume_error`` against the input),
    ``volume``, ``genus``, ``shells``.
    """

    info: Dict[str, Any]

    def __new__(cls, vertices: npt.NDArray[np.float64], faces: npt.NDArray[np.int64], info: Dict[str, Any]) -> "UnionSum":
        self = super().__new__(cls, (vertices, faces))
        self.info = info
        return self

    @property
    def vertices(self) -> npt.NDArray[np.float64]:
        return self[0]

    @property
    def faces(self) -> npt.NDArray[np.int64]:
        return self[1]

    @property
    def volume(self) -> float:
        return float(self.info["volume"])

    def __repr__(self) -> str:
        return f"UnionSum({len(self[0])} vertices, {len(self[1])} triangles, volume {self.volume:.9g})"


def _manifold3d():
    try:
        import manifold3d
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError(
            "the Minkowski sum of non-convex bodies merges the piece sums with the Manifold library: "
            "pip install manifold3d (or dymsum[nonconvex])"
        ) from e
    return manifold3d


# ---------------------------------------------------------------- mesh checks


def _as_mesh(vertices: Any, faces: Any) -> Tuple[np.ndarray, np.ndarray]:
    v = np.ascontiguousarray(vertices, dtype=np.float64)
    f = np.asarray(faces)
    if v.ndim != 2 or v.shape[1] != 3 or len(v) == 0:
        raise ValueError(f"mesh vertices must be a non-empty (n, 3) array, got shape {v.shape}")
    if f.ndim != 2 or f.shape[1] != 3 or len(f) == 0:
        raise ValueError(f"mesh faces must be a non-empty (m, 3) array of triangles, got shape {f.shape}")
    if not np.issubdtype(f.dtype, np.integer):
        if not np.all(np.asarray(f, dtype=np.float64) == np.round(np.asarray(f, dtype=np.float64))):
            raise ValueError("mesh faces must be integer vertex indices")
    f = np.ascontiguousarray(f, dtype=np.int64)
    if not np.all(np.isfinite(v)):
        raise ValueError("mesh vertices must be finite")
    if f.min() < 0 or f.max() >= len(v):
        raise ValueError(f"mesh faces index vertex {int(f.max()) if f.max() >= len(v) else int(f.min())}, out of range 0..{len(v) - 1}")
    return v, f


def check_closed_mesh(vertices: np.ndarray, faces: np.ndarray) -> Optional[str]:
    """Why ``(vertices, faces)`` is not a closed, oriented 2-manifold triangle
    mesh of positive volume, or ``None`` when it is.

    Tolerance-free: no face repeats a vertex, every directed edge occurs once
    and its reverse once (each edge in exactly two faces, in opposite
    directions), every vertex's faces form one fan (no pinched vertex), and
    the signed volume is positive.
    """
    f = np.asarray(faces, dtype=np.int64)
    v = np.asarray(vertices, dtype=np.float64)
    bad = (f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 0] == f[:, 2])
    if bad.any():
        return f"face {int(np.argmax(bad))} repeats a vertex"
    n = len(v)
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    key = e[:, 0] * n + e[:, 1]
    uniq, counts = np.unique(key, return_counts=True)
    if (counts > 1).any():
        k = int(uniq[np.argmax(counts > 1)])
        return f"directed edge ({k // n}, {k % n}) occurs {int(counts.max())} times (non-manifold or inconsistently oriented)"
    rev = e[:, 1] * n + e[:, 0]
    has_rev = np.isin(rev, uniq)
    if not has_rev.all():
        i = int(np.argmin(has_rev))
        return f"edge ({int(e[i, 0])}, {int(e[i, 1])}) has no opposite half-edge (the mesh is open or inconsistently oriented)"
    # Pinched vertices: the half-edges around each vertex must form one cycle.
    # Each face corner (face t, vertex a, next b, previous c) links the
    # outgoing half-edge a->b to the outgoing half-edge a->c of the face
    # across edge c->a. One cycle per used vertex.
    m = len(f)
    order = np.argsort(key)
    skey = key[order]
    # outgoing half-edge index h = t + m*k for corner k of face t: edge (f[t,k], f[t,k+1]).
    nxt = np.empty(3 * m, dtype=np.int64)
    for k in range(3):
        a, c = f[:, k], f[:, (k + 2) % 3]
        # the half-edge a->c (in the neighbouring face): its index
        pos = order[np.searchsorted(skey, a * n + c)]
        nxt[k * m + np.arange(m)] = pos
    # The cycles of the permutation nxt are the fans: label each half-edge
    # with the smallest index on its cycle by pointer doubling, and count.
    label = np.arange(3 * m)
    jump = nxt.copy()
    for _ in range(int(np.ceil(np.log2(3 * m + 1))) + 1):
        label = np.minimum(label, label[jump])
        jump = jump[jump]
    cycles = len(np.unique(label))
    used = len(np.unique(f))
    if cycles != used:
        return f"{cycles - used} pinched vertex fan(s): a vertex where the surface touches itself"
    t = v[f]
    vol = np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6.0
    if not vol > 0:
        return f"signed volume {vol:.6g} is not positive (inward or empty)"
    return None


def signed_volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    t = np.asarray(vertices, dtype=np.float64)[np.asarray(faces, dtype=np.int64)]
    return float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6.0)


def _components(n: int, faces: np.ndarray) -> List[np.ndarray]:
    """Face index sets of the edge-connected components."""
    m = len(faces)
    # Faces sharing an edge are connected: label propagation over vertices.
    label = np.arange(n)
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]]])
    while True:
        lo = np.minimum(label[e[:, 0]], label[e[:, 1]])
        new = label.copy()
        np.minimum.at(new, e[:, 0], lo)
        np.minimum.at(new, e[:, 1], lo)
        new = new[new]
        if np.array_equal(new, label):
            break
        label = new
    face_label = label[faces[:, 0]]
    out = []
    for lab in np.unique(face_label):
        out.append(np.nonzero(face_label == lab)[0])
    assert sum(len(c) for c in out) == m
    return out


def _submesh(vertices: np.ndarray, faces: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    used, inv = np.unique(faces, return_inverse=True)
    return vertices[used], inv.reshape(faces.shape).astype(np.int64)


# --------------------------------------------------------------- decompositions


def _to_manifold(m3d: Any, vertices: np.ndarray, faces: np.ndarray, what: str) -> Any:
    mesh = m3d.Mesh64(
        vert_properties=np.array(vertices, dtype=np.float64, order="C"),  # a writable copy
        tri_verts=np.array(faces, dtype=np.uint64, order="C"),
    )
    man = m3d.Manifold(mesh)
    if man.status() != m3d.Error.NoError:
        raise MeshUnionError(f"Manifold refused {what}: {man.status()}")
    return man


def _decompose(vertices: np.ndarray, faces: np.ndarray, method: str, options: Dict[str, Any]) -> List[np.ndarray]:
    """Convex parts (point arrays) of a closed mesh by an optional library."""
    if method == "coacd":
        try:
            import coacd
        except ImportError as e:
            raise ImportError("decomposition='coacd' needs the coacd package: pip install coacd") from e
        coacd.set_log_level("error")
        parts = coacd.run_coacd(coacd.Mesh(vertices, faces.astype(np.int32)), **options)
        return [np.asarray(p[0], dtype=np.float64) for p in parts]
    if method == "vhacd":
        try:
            import vhacdx
        except ImportError as e:
            raise ImportError("decomposition='vhacd' needs the vhacdx package: pip install vhacdx") from e
        parts = vhacdx.compute_vhacd(vertices, faces.astype(np.uint32), **options)
        return [np.asarray(p[0], dtype=np.float64) for p in parts]
    raise ValueError(f"unknown decomposition {method!r}: use one of {', '.join(map(repr, DECOMPOSITIONS))}")


def _volume_error(pieces: Sequence[Any], vertices: np.ndarray, faces: np.ndarray, shells: Sequence[np.ndarray]) -> Dict[str, float]:
    """How far the union of the pieces is from the input mesh, the union of
    its ``shells`` (by Manifold)."""
    m3d = _manifold3d()
    union = m3d.Manifold.batch_boolean(
        [_to_manifold(m3d, p.vertices, p.faces, f"decomposition piece {i}") for i, p in enumerate(pieces)], m3d.OpType.Add
    )
    vin = signed_volume(vertices, faces)
    out: Dict[str, float] = {"input_volume": vin, "union_volume": union.volume()}
    try:
        if len(shells) == 1:
            inp = _to_manifold(m3d, vertices, faces, "the input mesh")
        else:
            # Overlapping shells: the input is their union.
            inp = m3d.Manifold.batch_boolean(
                [_to_manifold(m3d, *_submesh(vertices, faces[s]), f"shell {k} of the input") for k, s in enumerate(shells)],
                m3d.OpType.Add,
            )
            vin = out["input_volume"] = inp.volume()
    except MeshUnionError:
        # The input is not a valid manifold for Manifold: the volumes only.
        out["volume_error"] = abs(union.volume() - vin) / vin
        return out
    extra = (union - inp).volume()
    missing = (inp - union).volume()
    out["added_volume"] = extra
    out["missing_volume"] = missing
    out["volume_error"] = (extra + missing) / vin
    return out


def check_solid(vertices: Any, faces: Any) -> Optional[str]:
    """Why the triangle mesh ``(vertices, faces)`` is not a solid, or
    ``None`` when it is (dymsum's exact check, in Rust: each shell closed,
    consistently oriented, edge- and vertex-manifold, crossing itself
    nowhere, of positive volume; no zero-area triangle; no face listed twice
    or back to back; shells may overlap each other)."""
    try:
        _ext.check_solid(vertices, faces)
    except ValueError as e:
        return str(e)
    return None


def _solid_shells(vertices: np.ndarray, faces: np.ndarray, name: Optional[str]) -> List[np.ndarray]:
    """The shells (face indices) of a mesh given as a solid; ``ValueError``
    naming the argument when it is not one."""
    try:
        return list(_ext.check_solid(vertices, faces))
    except ValueError as e:
        prefix = f"{name}: " if name else ""
        raise ValueError(
            f"{prefix}not a solid: {e}; a non-convex body must be a closed mesh whose shells each bound a "
            "region (repair the mesh, or give its convex pieces as dymsum.ConvexUnion([...]))"
        ) from None


def convex_pieces(
    shape: Any,
    decomposition: Optional[str] = None,
    options: Optional[Dict[str, Any]] = None,
    *,
    name: Optional[str] = None,
) -> Tuple[List[Any], Dict[str, Any]]:
    """The convex pieces of a body, and how they were obtained.

    A :class:`ConvexUnion` gives its pieces; a convex shape (anything
    :class:`Polytope` accepts) is one piece; a mesh ``(vertices, faces)``
    (or an object with ``.vertices`` and ``.faces``) that is not convex is
    first checked exactly to be a solid (:func:`check_solid`; else
    ``ValueError``, prefixed by ``name``, the argument's name): the body is
    the union of its shells. The shells are taken as pieces when every one
    is exactly convex; otherwise the non-convex shells are decomposed, one
    by one, by ``decomposition`` (``"coacd"`` or ``"vhacd"``), and the
    volume error of the union of the parts against the input is reported.
    """
    opts = dict(options or {})
    if isinstance(shape, _ext.ConvexUnion):
        return list(shape.pieces), {"method": "given", "exact": True}
    if isinstance(shape, _ext.Polytope):
        return [shape], {"method": "convex", "exact": True}
    path = _path_of(shape)
    if path is not None:
        try:
            return [_ext.Polytope(path)], {"method": "convex", "exact": True}
        except ValueError:
            return _path_pieces(path, decomposition, opts, name)
    mesh = _mesh_of(shape)
    if mesh is None:
        return [_ext.Polytope(shape)], {"method": "convex", "exact": True}
    try:
        return [_ext.Polytope(shape)], {"method": "convex", "exact": True}
    except ValueError as convex_error:
        refusal = str(convex_error)
    try:
        vertices, faces = _as_mesh(*mesh)
    except ValueError:
        raise ValueError(f"{name}: {refusal}" if name else refusal) from None
    # Exactly a solid, or refused: nothing from an invalid mesh goes on.
    shells = _solid_shells(vertices, faces, name)
    pieces: List[Any] = []
    rest: List[np.ndarray] = []
    for shell in shells:
        cv, cf = _submesh(vertices, faces[shell])
        try:
            pieces.append(_ext.Polytope((cv, cf), strict=True))
        except ValueError:
            rest.append(shell)
    if not rest:
        return pieces, {"method": "components", "exact": True, "components": len(pieces)}
    if decomposition is None or decomposition == "boundary":
        raise _NeedsDecomposition(
            f"a non-convex mesh ({refusal}) needs a convex decomposition: pass decomposition='coacd' "
            "or decomposition='vhacd' (optional packages coacd / vhacdx), or give its convex pieces "
            "as dymsum.ConvexUnion([...]); minkowski_sum also takes decomposition='boundary' "
            "(exact, when the other body is convex or in convex pieces)",
            vertices,
            faces,
            shells,
        )
    if decomposition not in DECOMPOSITIONS:
        raise ValueError(f"unknown decomposition {decomposition!r}: use one of {', '.join(map(repr, DECOMPOSITIONS))}")
    parts = []
    for shell in rest:
        dv, df = _submesh(vertices, faces[shell])
        parts.extend(_decompose(dv, df, decomposition, opts))
    decomposed = []
    flat = 0
    for p in parts:
        try:
            decomposed.append(_ext.Polytope(p))
        except ValueError as e:
            # A flat (zero-volume) part adds nothing to the union; any
            # other refusal is an error.
            if "degenerate input" not in str(e):
                raise
            flat += 1
    if not decomposed:
        raise ValueError(f"the {decomposition} decomposition returned no solid part")
    info: Dict[str, Any] = {
        "method": decomposition,
        "exact": False,
        "options": opts,
        "convex_components": len(pieces),
        "parts": len(decomposed),
        "flat_parts_dropped": flat,
    }
    pieces = pieces + decomposed
    info.update(_volume_error(pieces, vertices, faces, shells))
    return pieces, info


def _mesh_of(shape: Any) -> Optional[Tuple[Any, Any]]:
    """``(vertices, faces)`` when ``shape`` is given as a mesh, else ``None``."""
    if hasattr(shape, "vertices") and hasattr(shape, "faces"):
        return shape.vertices, shape.faces
    if isinstance(shape, (tuple, list)) and len(shape) == 2:
        f = np.asarray(shape[1]) if not isinstance(shape[1], (str, bytes)) else None
        v = np.asarray(shape[0]) if not isinstance(shape[0], (str, bytes)) else None
        if f is not None and v is not None and f.ndim == 2 and f.shape[1] == 3 and v.ndim == 2 and v.shape[1] == 3:
            if np.issubdtype(f.dtype, np.integer):
                return shape[0], shape[1]
    return None


def _is_nonconvex_solid(shape: Any) -> bool:
    """A closed triangle mesh that dymsum refuses as a polytope."""
    if isinstance(shape, (_ext.ConvexUnion, _ext.Polytope)):
        return False
    mesh = _mesh_of(shape)
    if mesh is None:
        return False
    try:
        vertices, faces = _as_mesh(*mesh)
    except ValueError:
        return False
    try:
        _ext.Polytope((vertices, faces))
        return False
    except ValueError:
        pass
    # A closed mesh (every edge paired, however badly) goes on as a
    # non-convex body, where the exact solid check says what is wrong with
    # it; an open one keeps the convex loader's refusal.
    why = check_closed_mesh(vertices, faces)
    return why is None or "no opposite half-edge" not in why


# ---------------------------------------------------------------------- the sum


def _union_sum(
    a: Any,
    b: Any,
    pose_a: Any,
    pose_b: Any,
    method: str,
    decomposition: Optional[str],
    decomposition_options: Optional[Dict[str, Any]],
    cull: bool,
) -> UnionSum:
    m3d = _manifold3d()
    if decomposition == "boundary":
        return _boundary_sum(m3d, a, b, pose_a, pose_b, decomposition_options, cull)
    pa, info_a = convex_pieces(a, decomposition, decomposition_options, name="a")
    pb, info_b = convex_pieces(b, decomposition, decomposition_options, name="b")
    sums = []
    for i, p in enumerate(pa):
        for j, q in enumerate(pb):
            v, f = _convex_sum(p, q, pose_a, pose_b, method)
            sums.append((i, j, np.asarray(v), np.asarray(f)))
    culled = 0
    if cull and len(sums) > 1:
        keep = _cull(sums)
        culled = len(sums) - len(keep)
        sums = keep
    return _merge(m3d, sums, culled, len(pa), len(pb), {"a": info_a, "b": info_b})


def _merge(
    m3d: Any,
    sums: list,
    culled: int,
    na: int,
    nb: int,
    decomposition: Dict[str, Any],
    extra: Sequence[Tuple[str, np.ndarray, np.ndarray]] = (),
) -> UnionSum:
    """Manifold's union of the pair sums ``(i, j, vertices, faces)`` (and of
    the ``extra`` closed meshes ``(what, vertices, faces)``), validated."""
    mans = [_to_manifold(m3d, v, f, f"the sum of pieces {i} and {j}") for i, j, v, f in sums]
    mans += [_to_manifold(m3d, v, f, what) for what, v, f in extra]
    union = m3d.Manifold.batch_boolean(mans, m3d.OpType.Add) if len(mans) > 1 else mans[0]
    if union.status() != m3d.Error.NoError:
        raise MeshUnionError(f"Manifold's union of the piece sums failed: {union.status()}")
    mesh = union.to_mesh64()
    vertices = np.array(mesh.vert_properties[:, :3], dtype=np.float64)
    faces = np.array(mesh.tri_verts, dtype=np.int64)
    if len(faces) == 0:
        raise MeshUnionError("Manifold's union of the piece sums is empty")
    why = check_closed_mesh(vertices, faces)
    if why is not None:
        raise MeshUnionError(f"the merged sum is not a valid closed mesh: {why}")
    volume = signed_volume(vertices, faces)
    if abs(volume - union.volume()) > 1e-9 * abs(volume):
        raise MeshUnionError(f"the merged mesh's volume {volume!r} differs from Manifold's {union.volume()!r}")
    genus = int(union.genus())
    comps = _components(len(vertices), faces)
    # Every connected part of the true union contains a whole piece, so an
    # outward shell smaller than the smallest piece is the union's rounding
    # (Manifold can leave a flat sliver tetrahedron): certified, dropped and
    # counted. Inward shells (cavities) are kept whatever their size.
    dropped = 0
    if len(comps) > 1:
        floor = 0.5 * min(signed_volume(np.asarray(v), np.asarray(f)) for v, f in [(x[2], x[3]) for x in sums] + [(x[1], x[2]) for x in extra])
        keep = [c for c in comps if not 0.0 <= signed_volume(vertices, faces[c]) < floor]
        dropped = len(comps) - len(keep)
        if dropped:
            vertices, faces = _submesh(vertices, faces[np.concatenate(keep)])
            comps = _components(len(vertices), faces)
            volume = signed_volume(vertices, faces)
            edges = len({(min(a, b), max(a, b)) for t in faces.tolist() for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))})
            genus = 1 - (len(vertices) - edges + len(faces)) // 2
    info: Dict[str, Any] = {
        "pieces": (na, nb),
        "pairs": na * nb,
        "pairs_culled": culled,
        "decomposition": decomposition,
        "volume": volume,
        "genus": genus,
        "shells": len(comps),
        "slivers_dropped": dropped,
    }
    vertices.setflags(write=False)
    faces.setflags(write=False)
    return UnionSum(vertices, faces, info)


def _boundary_mesh(shape: Any, name: str) -> Optional[Tuple[np.ndarray, np.ndarray, List[np.ndarray], Dict[str, Any]]]:
    """``(vertices, faces, shells, info)`` of a body that is not a union of
    exactly convex shells (it needs a decomposition), else ``None``."""
    try:
        convex_pieces(shape, "boundary", name=name)
    except _NeedsDecomposition as e:
        v, f = e.mesh
        return v, f, e.shells, {"method": "boundary", "exact": True, "triangles": len(f)}
    return None


def _posed_points(points: np.ndarray, pose: np.ndarray) -> np.ndarray:
    return points @ pose[:3, :3].T + pose[:3, 3]


def _boundary_sum(
    m3d: Any, a: Any, b: Any, pose_a: Any, pose_b: Any, options: Optional[Dict[str, Any]], cull: bool
) -> UnionSum:
    """``A ⊕ B`` for a closed non-convex mesh A and B convex or in convex
    pieces ``B_j``, with no decomposition of A:

        A ⊕ B_j = (A + b_j) ∪ ⋃_{triangles t of ∂A} (t ⊕ B_j)   for any b_j ∈ B_j.

    Proof: for x = a + b (a ∈ A, b ∈ B_j), follow ``y(s) = x − b(s)`` with
    ``b(s)`` on the segment from b_j to b (in B_j, which is convex): y(1) = a
    is in A; either y(0) = x − b_j is in A (x ∈ A + b_j), or y crosses ∂A at
    some s, where y(s) lies on a triangle t and x = y(s) + b(s) ∈ t ⊕ B_j.
    Both sides are in A ⊕ B_j, so they are equal. Each ``t ⊕ B_j`` is the
    exact hull of the pairwise vertex sums; no approximation enters before
    Manifold's union. (manifold3d's own ``minkowski_sum`` takes A itself for
    A + b_j, which is wrong when B does not contain the origin.)
    """
    if options:
        raise ValueError("decomposition='boundary' takes no decomposition_options")
    ma, mb = _boundary_mesh(a, "a"), _boundary_mesh(b, "b")
    if ma is not None and mb is not None:
        raise ValueError(
            "decomposition='boundary' sums a non-convex mesh with a convex body or convex pieces; "
            "both bodies here need a decomposition: give one as dymsum.ConvexUnion([...]) or use "
            "decomposition='coacd' / 'vhacd'"
        )
    if ma is None and mb is None:
        return _union_sum(a, b, pose_a, pose_b, "walk", None, None, cull)
    swap = ma is None
    mesh = mb if swap else ma
    assert mesh is not None
    v, f, shells, info_mesh = mesh
    other, pose_mesh, pose_other = (a, pose_b, pose_a) if swap else (b, pose_a, pose_b)
    pieces, info_other = convex_pieces(other, name="a" if swap else "b")
    tm, to = _pose_matrix(pose_mesh), _pose_matrix(pose_other)
    mesh_v = _posed_points(np.asarray(v, dtype=np.float64), tm)
    tris = mesh_v[np.asarray(f)]
    sums = []
    copies = []
    flat = np.ascontiguousarray(tris.reshape(-1, 3))
    for j, piece in enumerate(pieces):
        pv = _posed_points(np.asarray(_ext.Polytope(piece).vertices, dtype=np.float64), to)
        # One copy per shell: the body is the union of its shells, which
        # may overlap (Manifold takes no self-overlapping input).
        for k, shell in enumerate(shells):
            sv, sf = _submesh(mesh_v, np.asarray(f)[shell])
            copies.append((f"shell {k} of the mesh moved by a vertex of piece {j}", sv + pv[0], sf))
        for k, (hv, hf) in enumerate(_ext._triangle_sums(flat, np.ascontiguousarray(pv))):
            sums.append((k, j, hv, hf))
    # No culling: a triangle's sum straddles the mesh's boundary, so one
    # inside another is rare and the test would cost more than it saves.
    culled = 0
    decomposition = {"a": info_other, "b": info_mesh} if swap else {"a": info_mesh, "b": info_other}
    na, nb = (len(pieces), len(f)) if swap else (len(f), len(pieces))
    if swap:
        sums = [(j, k, sv, sf) for k, j, sv, sf in sums]
    out = _merge(m3d, sums, culled, na, nb, decomposition, copies)
    out.info["copies"] = len(copies)
    return out


def _planes(v: np.ndarray, f: np.ndarray) -> np.ndarray:
    t = v[f]
    n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    return np.hstack([n, -np.einsum("ij,ij->i", n, t[:, 0])[:, None]])


def _cull(sums: list) -> list:
    """Drop pair sums certified inside another kept one.

    A convex sum lies inside a convex sum ``S`` when all its vertices do:
    tested against the planes of ``S``'s triangles with a margin of 1e-9 of
    the size, far above the rounding of the planes, so a pair is dropped
    only when it is clearly inside. Bounding boxes filter first (one
    vectorised test against every kept box).
    """
    lo = np.array([v.min(axis=0) for _, _, v, _ in sums])
    hi = np.array([v.max(axis=0) for _, _, v, _ in sums])
    size = max(float(np.abs(np.concatenate([lo, hi])).max()), 1e-300)
    margin = 1e-9 * size
    order = np.argsort(-np.prod(hi - lo, axis=1), kind="stable")
    kept = np.empty(len(sums), dtype=np.int64)
    n_kept = 0
    planes: Dict[int, np.ndarray] = {}
    for k in order:
        k = int(k)
        ks = kept[:n_kept]
        boxed = ks[np.all(lo[k] >= lo[ks], axis=1) & np.all(hi[k] <= hi[ks], axis=1)]
        inside = False
        for o in boxed.tolist():
            if o not in planes:
                planes[o] = _planes(sums[o][2], sums[o][3])
            pl = planes[o]
            if (sums[k][2] @ pl[:, :3].T + pl[:, 3]).max() < -margin:
                inside = True
                break
        if not inside:
            kept[n_kept] = k
            n_kept += 1
    return [sums[k] for k in sorted(kept[:n_kept].tolist())]


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
    except ValueError:
        if not any(_is_union_operand(x) for x in operands):
            raise
    return _NOT_CONVEX


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


# ------------------------------------------------- bodies given by file path


def _path_of(shape: Any) -> Optional[str]:
    """The file path ``shape`` names, if it names an existing file."""
    if isinstance(shape, (str, os.PathLike)):
        path = os.fspath(shape)
        if isinstance(path, str) and os.path.isfile(path):
            return path
    return None


def _path_pieces(
    path: str, decomposition: Optional[str], options: Optional[Dict[str, Any]], name: Optional[str] = None
) -> Tuple[List[Any], Dict[str, Any]]:
    """Convex pieces of a mesh file that ``Polytope`` refuses: the bodies of
    the file (OBJ objects), each convex or split as :func:`convex_pieces`
    splits a mesh."""
    bodies = _ext.read_mesh_bodies(path)
    if len(bodies) == 1:
        _, v, f = bodies[0]
        return convex_pieces((v, f), decomposition, options, name=name)
    pieces: List[Any] = []
    objects = []
    for obj, v, f in bodies:
        got, how = convex_pieces((v, f) if len(f) else v, decomposition, options, name=f"{name or path} (object {obj!r})")
        pieces.extend(got)
        objects.append({"name": obj, **how})
    info: Dict[str, Any] = {"method": "objects", "exact": all(o["exact"] for o in objects), "objects": objects}
    return pieces, info


def _is_union_operand(shape: Any) -> bool:
    """A body that is not one convex polytope: a :class:`ConvexUnion`, a
    closed non-convex mesh, or a mesh file holding either."""
    if isinstance(shape, _ext.ConvexUnion):
        return True
    path = _path_of(shape)
    if path is not None:
        try:
            _ext.Polytope(path)
            return False
        except ValueError:
            pass
        try:
            bodies = _ext.read_mesh_bodies(path)
        except (ValueError, OSError):
            return False
        if len(bodies) > 1:
            return True
        return _is_nonconvex_solid((bodies[0][1], bodies[0][2]))
    return _is_nonconvex_solid(shape)


# ------------------------------------------------------------------ poses


def _pose_matrix(pose: Any) -> np.ndarray:
    """Any accepted pose as a 4×4 ``float64`` rigid transform."""
    if pose is None:
        return np.eye(4)
    if not hasattr(pose, "as_quat"):
        m = np.asarray(pose, dtype=np.float64)
        if m.shape == (4, 4):
            return m
    return np.array(_ext.pose(pose), dtype=np.float64)


def _reflected(piece: Any) -> Any:
    """``−piece`` (exact: negation is exact in floats)."""
    return _ext.Polytope(-np.asarray(_ext.Polytope(piece).vertices))


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
    pa, info_a = convex_pieces(a, decomposition, decomposition_options, name="a")
    pb, info_b = convex_pieces(b, decomposition, decomposition_options, name="b")
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
