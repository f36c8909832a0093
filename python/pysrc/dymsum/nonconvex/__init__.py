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


from ._types import UnionSum as UnionSum, MeshUnionError as MeshUnionError, NeedsDecompositionError as NeedsDecompositionError, DECOMPOSITIONS as DECOMPOSITIONS
from ._checks import check_closed_mesh as check_closed_mesh, signed_volume as signed_volume, _components as _components
from ._decompose import convex_pieces as convex_pieces, check_solid as check_solid
from ._front import UnionContact as UnionContact, DynamicSum as DynamicSum, DynamicUnionSum as DynamicUnionSum, minkowski_sum as minkowski_sum, contact as contact, cobstacle_slices as cobstacle_slices, closest_boundary_point as closest_boundary_point

__all__ = [
    "UnionSum",
    "UnionContact",
    "MeshUnionError",
    "NeedsDecompositionError",
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
