"""Checks of meshes given as solids (the exact check is Rust's, ``check_solid``), their shells and volume."""

from __future__ import annotations

from typing import Any, List, Optional, Tuple

import numpy as np


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
