"""The sum as one mesh: exact piece-pair sums, culled, merged by Manifold and validated; the boundary method for a bare mesh."""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from .. import _dymsum as _ext
from ._types import MeshUnionError, UnionSum, _NeedsDecomposition, _convex_sum, _manifold3d, _pose_matrix
from ._checks import _components, _submesh, check_closed_mesh, signed_volume
from ._decompose import _to_manifold, convex_pieces


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
    """Drop pair sums certified inside another kept one: Rust's rule
    (``dymsum::sum::contained::uncontained``: every vertex strictly inside
    every face plane of the other by exact ``orient3d``; bounding boxes
    first, larger kept first), the same as for Rust's non-convex sums."""
    keep = _ext._uncontained([(v, f) for _, _, v, f in sums])
    return [sums[k] for k in keep]
