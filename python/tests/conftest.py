"""Shared oracles for the dymsum Python tests.

Every sum is checked against scipy's ConvexHull (Qhull) of all pairwise
vertex sums: the same volume and the same set of face planes (unit normal
and offset), matched both ways.
"""

import os
import zlib
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import ConvexHull
from scipy.spatial.transform import Rotation

CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)


def sphere_points(n, rng, radii=(1.0, 1.0, 1.0)):
    """n random points on an ellipsoid (all are hull vertices)."""
    p = rng.normal(size=(n, 3))
    p /= np.linalg.norm(p, axis=1)[:, None]
    return p * np.asarray(radii)


def random_pose(rng, angle=None, shift=1.0):
    """A random rigid 4×4 pose (uniform rotation, or `angle` about a random axis)."""
    if angle is None:
        r = Rotation.random(random_state=rng)
    else:
        axis = rng.normal(size=3)
        r = Rotation.from_rotvec(axis / np.linalg.norm(axis) * angle)
    m = np.eye(4)
    m[:3, :3] = r.as_matrix()
    m[:3, 3] = rng.uniform(-shift, shift, size=3)
    return m


def apply(pose, points):
    if pose is None:
        return np.asarray(points, dtype=float)
    return points @ pose[:3, :3].T + pose[:3, 3]


def pairwise_sums(a, b):
    return (a[:, None, :] + b[None, :, :]).reshape(-1, 3)


def polygon_planes(vertices, polygons):
    """(unit normal, offset) of each polygon face (Newell normals)."""
    planes = []
    for f in polygons:
        p = vertices[np.asarray(f)]
        q = np.roll(p, -1, axis=0)
        n = np.array(
            [
                np.sum((p[:, 1] - q[:, 1]) * (p[:, 2] + q[:, 2])),
                np.sum((p[:, 2] - q[:, 2]) * (p[:, 0] + q[:, 0])),
                np.sum((p[:, 0] - q[:, 0]) * (p[:, 1] + q[:, 1])),
            ]
        )
        n /= np.linalg.norm(n)
        planes.append(np.append(n, -n @ p.mean(axis=0)))
    return np.array(planes)


def distinct_planes(eq):
    """Distinct planes, (unit normal, offset) rows equal within 1e-9 merged.

    Qhull merges facets coplanar within rounding, and dymsum's merged mesh is
    the exact hull of the *rounded* sum vertices, where a parallelogram
    facet (an edge of each operand) may be split along its diagonal by a
    rounding-level fold: both sides are compared as sets of distinct planes.
    """
    eq = np.asarray(eq, dtype=float)
    keep = np.zeros(len(eq), dtype=bool)
    for i, e in enumerate(eq):
        kept = eq[keep]
        if len(kept) == 0 or np.abs(kept - e).max(axis=1).min() > 1e-9:
            keep[i] = True
    return eq[keep]


def hull_planes(hull):
    """Distinct facet planes of a scipy hull."""
    return distinct_planes(hull.equations)


def assert_same_planes(ours, theirs, scale, tol=1e-8):
    """Each plane of one set is in the other (normals within tol, offsets within tol·scale)."""

    def uncovered(xs, ys):
        # Rows of xs with no row of ys within tol (normal) and tol·scale (offset).
        out = []
        for c in range(0, len(xs), 256):
            x = xs[c : c + 256]
            d = np.abs(x[:, None, :3] - ys[None, :, :3]).max(axis=2)
            d = d + np.abs(x[:, None, 3] - ys[None, :, 3]) / scale
            out.extend(x[d.min(axis=1) > tol])
        return np.array(out)

    assert len(ours) == len(theirs), f"{len(ours)} faces, the hull of pairwise sums has {len(theirs)}"
    extra, missing = uncovered(ours, theirs), uncovered(theirs, ours)
    assert len(extra) == 0, f"face planes {extra} are not faces of the hull of pairwise sums"
    assert len(missing) == 0, f"hull face planes {missing} are missing from the sum"


def check_sum_against_qhull(vertices, polygons, points, tol=1e-8):
    """The sum (vertices, polygon faces) equals the hull of `points`."""
    hull = ConvexHull(points)
    scale = np.abs(points).max()
    ours = distinct_planes(polygon_planes(vertices, polygons))
    assert_same_planes(ours, hull_planes(hull), scale, tol)
    t = np.array([p[[0, i, i + 1]] for p in polygons for i in range(1, len(p) - 1)])
    vol = np.einsum("ij,ij->i", vertices[t[:, 0]], np.cross(vertices[t[:, 1]], vertices[t[:, 2]])).sum() / 6
    assert vol == pytest.approx(hull.volume, rel=1e-9, abs=1e-12 * scale**3)
    # The vertex sets agree too.
    hv = points[hull.vertices]
    assert len(hv) == len(vertices)
    for xs, ys in ((hv, vertices), (vertices, hv)):
        for c in range(0, len(xs), 256):
            d = np.abs(xs[c : c + 256, None, :] - ys[None, :, :]).max(axis=2)
            assert d.min(axis=1).max() <= tol * scale, "the vertex sets differ"


@pytest.fixture
def rng(request):
    # One seed per test, from its name: reproducible and independent.
    seed = zlib.crc32(request.node.name.encode())
    return np.random.default_rng(seed)


def need(module: str, reason: str = ""):
    """The optional module, imported; the test is skipped without it,
    unless DYMSUM_REQUIRE_SCENES=1 (the README's test command installs the
    scene packages, trimesh, pycollada and python-fcl, and sets it), where
    a missing module fails the test instead of hiding it."""
    import importlib
    import os

    import pytest

    if os.environ.get("DYMSUM_REQUIRE_SCENES") == "1":
        return importlib.import_module(module)
    return pytest.importorskip(module, reason=reason or None)


def cli():
    """The dymsum command line the tests run: $DYMSUM_CLI, else the release
    build; skipped when absent, failed when DYMSUM_REQUIRE_CLI=1."""
    exe = os.environ.get("DYMSUM_CLI") or str(Path(__file__).resolve().parents[2] / "target" / "release" / "dymsum")
    if not os.path.isfile(exe):
        if os.environ.get("DYMSUM_REQUIRE_CLI") == "1":
            pytest.fail(f"DYMSUM_REQUIRE_CLI=1 but no CLI at {exe}")
        pytest.skip("the dymsum CLI is not built (cargo build --release -p dymsum-cli)")
    return exe
