"""dymsum: exact static and dynamic Minkowski sums of convex polytopes.

Exact ``A ⊕ B`` of convex polytopes (every combinatorial decision an exact
predicate), kept up to date while the bodies rotate (the DYMSUM algorithm),
penetration depth and distance, contact tracking and configuration-space
obstacle slices and certified slabs between them, from NumPy arrays.

Conventions, everywhere:

* shapes: an (N, 3) array of points (its exact convex hull), a
  ``(vertices, faces)`` pair, any object with ``.vertices`` and ``.faces``
  (a ``trimesh.Trimesh``), a :class:`Polytope` (parse and hull once), or a
  built-in model name or mesh file path (as :func:`load`);
* rotations, wherever one is taken: a ``scipy.spatial.transform.Rotation``
  (scipy itself is never imported), a 3×3 rotation matrix, or a (4,)
  quaternion, always ``(x, y, z, w)``, scalar last, as scipy;
* poses: 4×4 homogeneous rigid transforms (``None`` is the identity), or
  any rotation form for a rotation about the origin (:func:`pose` adds a
  translation);
* outputs: vertices ``float64`` (n, 3) and faces ``int64`` (m, 3) fan
  triangles, or with ``polygons=True`` the merged convex faces as a list of
  ``int64`` arrays;
* invalid input raises ``ValueError`` with dymsum's message.

>>> import numpy as np, dymsum
>>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
>>> vertices, faces = dymsum.minkowski_sum(cube, "tcube:4")
"""

from ._dymsum import (
    Contact as Contact,
    ContactTracker as ContactTracker,
    Contacts as Contacts,
    ConvexUnion as ConvexUnion,
    MotionCheck as MotionCheck,
    MotionChecker as MotionChecker,
    MotionChecks as MotionChecks,
    MotionUndecided as MotionUndecided,
    Polytope as Polytope,
    Robot as Robot,
    RobotChecker as RobotChecker,
    Slab as Slab,
    __version__ as __version__,
    check_motion as check_motion,
    check_motions as check_motions,
    collides_many as collides_many,
    contact_many as contact_many,
    load as load,
    models as models,
    pose as pose,
    read_mesh_bodies as read_mesh_bodies,
    save as save,
)
from .nonconvex import (
    DynamicSum as DynamicSum,
    DynamicUnionSum as DynamicUnionSum,
    UnionContact as UnionContact,
    closest_boundary_point as closest_boundary_point,
    cobstacle_slices as cobstacle_slices,
    contact as contact,
    MeshUnionError as MeshUnionError,
    NeedsDecompositionError as NeedsDecompositionError,
    UnionSum as UnionSum,
    check_solid as check_solid,
    convex_pieces as convex_pieces,
    minkowski_sum as minkowski_sum,
)
from ._maps import (
    CObstacleMap as CObstacleMap,
    CObstacleMapError as CObstacleMapError,
    cobstacle_map as cobstacle_map,
    load_cobstacle_map as load_cobstacle_map,
)

__all__ = [
    "Contact",
    "ContactTracker",
    "Contacts",
    "ConvexUnion",
    "DynamicSum",
    "DynamicUnionSum",
    "MeshUnionError",
    "NeedsDecompositionError",
    "MotionCheck",
    "MotionChecker",
    "MotionChecks",
    "MotionUndecided",
    "Polytope",
    "Robot",
    "RobotChecker",
    "Slab",
    "UnionContact",
    "UnionSum",
    "check_motion",
    "check_motions",
    "check_solid",
    "closest_boundary_point",
    "cobstacle_slices",
    "collides_many",
    "contact",
    "contact_many",
    "convex_pieces",
    "load",
    "minkowski_sum",
    "models",
    "pose",
    "read_mesh_bodies",
    "save",
    "CObstacleMap",
    "CObstacleMapError",
    "cobstacle_map",
    "load_cobstacle_map",
]
