"""Checks of meshes given as solids (the exact check is Rust's, ``check_solid``), their shells and volume."""

from __future__ import annotations

from typing import Any, List, Optional, Tuple

import numpy as np

from .. import _dymsum as _ext


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
    if not np.all(np.isfinite(v)):
        raise ValueError("mesh vertices must be finite")
    # The range is checked in the given dtype, before any conversion: an
    # index beyond int64 (a uint64 2**63) is quoted as given, not wrapped.
    lo, hi = f.min(), f.max()
    if lo < 0 or hi >= len(v):
        raise ValueError(f"mesh faces index vertex {int(hi) if hi >= len(v) else int(lo)}, out of range 0..{len(v) - 1}")
    f = np.ascontiguousarray(f, dtype=np.int64)
    return v, f


def check_closed_mesh(vertices: np.ndarray, faces: np.ndarray) -> Optional[str]:
    """Why ``(vertices, faces)`` is not a closed, oriented 2-manifold triangle
    mesh of positive volume, or ``None`` when it is.

    Tolerance-free: no face repeats a vertex, every directed edge occurs once
    and its reverse once (each edge in exactly two faces, in opposite
    directions), every vertex's faces form one fan (no pinched vertex), and
    the signed volume is positive. The check is the core's
    (``dymsum::solid::closed::check_closed_mesh``), the one Rust's non-convex
    sums pass too.
    """
    return _ext._check_closed_mesh(np.asarray(vertices, dtype=np.float64), np.asarray(faces))


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
