"""The types and errors of non-convex sums, and the optional Manifold import."""

from __future__ import annotations

from typing import Any, Dict, List, Tuple

import numpy as np
import numpy.typing as npt

from .. import _dymsum as _ext


DECOMPOSITIONS = ("coacd", "vhacd")

# The convex sum (typed by _dymsum.pyi's overloads; called here with
# arguments passed through from the caller).
_convex_sum: Any = _ext.minkowski_sum


class NeedsDecompositionError(ValueError):
    """A non-convex mesh that is not a union of exactly convex components,
    given with no decomposition (its message names the argument and the
    fix); carries the mesh (``.mesh``) and its shells (``.shells``)."""

    def __init__(self, message: str, vertices: np.ndarray, faces: np.ndarray, shells: List[np.ndarray]) -> None:
        super().__init__(message)
        self.mesh = (vertices, faces)
        self.shells = shells


# The name it had before it was public.
_NeedsDecomposition = NeedsDecompositionError


class MeshUnionError(RuntimeError):
    """The union of the piece-pair sums failed: Manifold rejected a mesh, or the
    merged mesh failed validation (never returned)."""


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
