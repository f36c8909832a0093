"""minkowski_sum, Polytope and DynamicSum against scipy's hull of pairwise sums."""

import itertools

import numpy as np
import pytest
from conftest import (
    CUBE,
    apply,
    check_sum_against_qhull,
    pairwise_sums,
    random_pose,
    sphere_points,
)

import dymsum


@pytest.mark.parametrize("case", range(12))
def test_random_shapes_posed_match_qhull(case, rng):
    n, m = rng.integers(4, 60, size=2)
    a = sphere_points(n, rng, radii=rng.uniform(0.2, 3.0, size=3))
    b = rng.normal(size=(m, 3)) * rng.uniform(0.1, 2.0)  # interior points too
    pa, pb = random_pose(rng), random_pose(rng)
    method = ["walk", "brute", "hull"][case % 3]
    if method == "hull":
        pa = None  # the hull method needs P unrotated (see SumError::HullMismatch)
    v, polys = dymsum.minkowski_sum(a, b, pose_a=pa, pose_b=pb, method=method, polygons=True)
    check_sum_against_qhull(v, polys, pairwise_sums(apply(pa, a), apply(pb, b)))


@pytest.mark.parametrize("name_a,name_b", [("gs1", "cube"), ("cone", "gs2"), ("tcube:3", "cylinder:12"), ("dd", "t")])
def test_models_match_qhull(name_a, name_b, rng):
    a, b = dymsum.load(name_a), dymsum.load(name_b)
    pa = random_pose(rng)
    v, polys = dymsum.minkowski_sum(a, b, pose_a=pa, polygons=True)
    check_sum_against_qhull(v, polys, pairwise_sums(apply(pa, a.vertices), b.vertices))


def quarter_turns():
    """The 24 rotations of the cube, as exact integer matrices."""
    out = []
    for perm in itertools.permutations(range(3)):
        for signs in itertools.product((1, -1), repeat=3):
            m = np.zeros((3, 3))
            for i, (j, s) in enumerate(zip(perm, signs)):
                m[i, j] = s
            if np.linalg.det(m) > 0:
                out.append(m)
    return out


@pytest.mark.parametrize("k", range(24))
def test_degenerate_boxes_at_quarter_turns(k):
    # Every face of P is exactly parallel to a face of Q: the fully
    # degenerate case, decided by exact predicates and symbolic perturbation.
    a = dymsum.load("box:1,2,3")
    b = dymsum.load("box:0.5,4,1")
    pose = np.eye(4)
    pose[:3, :3] = quarter_turns()[k]
    pose[:3, 3] = [0.25, -1.5, 2.0]
    for method in ("walk", "brute"):
        v, polys = dymsum.minkowski_sum(a, b, pose_a=pose, method=method, polygons=True)
        assert len(polys) == 6 and all(len(p) == 4 for p in polys)
        check_sum_against_qhull(v, polys, pairwise_sums(apply(pose, a.vertices), b.vertices))


def test_cube_with_itself_and_triangles():
    v, f = dymsum.minkowski_sum(CUBE, CUBE)
    assert v.dtype == np.float64 and v.shape == (8, 3)
    assert f.dtype == np.int64 and f.shape == (12, 3)
    assert sorted(map(tuple, v.tolist())) == sorted(map(tuple, (2 * CUBE).tolist()))
    # Triangles are outward: positive signed volume 8.
    vol = np.einsum("ij,ij->i", v[f[:, 0]], np.cross(v[f[:, 1]], v[f[:, 2]])).sum() / 6
    assert vol == 8.0


def test_methods_agree_exactly(rng):
    a, b = sphere_points(40, rng), sphere_points(30, rng, radii=(2, 1, 0.5))
    pb = random_pose(rng)
    results = [dymsum.minkowski_sum(a, b, pose_b=pb, method=m) for m in ("walk", "brute", "hull")]
    for v, f in results[1:]:
        assert np.array_equal(v, results[0][0]) and np.array_equal(f, results[0][1])


def test_polytope_properties(rng):
    pts = sphere_points(50, rng)
    p = dymsum.Polytope(np.vstack([pts, 0.1 * pts]))  # 50 interior points dropped
    from scipy.spatial import ConvexHull

    h = ConvexHull(pts)
    assert p.vertex_count == 50 and p.vertices.shape == (50, 3)
    assert p.volume == pytest.approx(h.volume, rel=1e-12)
    assert p.faces.shape == (2 * 50 - 4, 3) and p.faces.dtype == np.int64
    assert p.vertex_count - p.edge_count + p.face_count == 2
    r = p.convexity_report
    assert r["point_cloud"] and r["input_vertices"] == 100 and r["dropped_vertices"] == 50
    assert sum(len(q) - 2 for q in p.polygons) == len(p.faces)
    v, polys = p.mesh(polygons=True)
    assert np.array_equal(v, p.vertices) and len(polys) == p.face_count


def test_polytope_from_mesh_reports_convexity():
    p = dymsum.Polytope(CUBE)
    # The cube as 12 triangles: merged back into 6 squares, exactly convex.
    q = dymsum.Polytope((p.vertices, p.faces))
    r = q.convexity_report
    assert (r["point_cloud"], r["exactly_convex"], r["replaced_by_hull"]) == (False, True, False)
    assert (r["input_faces"], r["faces"], q.face_count) == (12, 6, 6)
    # A cube with one corner pushed in by 1e-9: convex within tolerance,
    # replaced by its exact hull; refused when strict. By 1e-3: not convex.
    v = p.vertices.copy()
    v[0] -= 1e-9 * (v[0] - 0.5)
    bent = dymsum.Polytope((v, p.faces))
    r = bent.convexity_report
    assert r["replaced_by_hull"] and not r["exactly_convex"]
    assert 0 < r["max_deviation"] < r["tolerance"]
    with pytest.raises(ValueError, match="convex"):
        dymsum.Polytope((v, p.faces), strict=True)
    v[0] -= 1e-3 * (v[0] - 0.5)
    with pytest.raises(ValueError, match="non-convex mesh"):
        dymsum.Polytope((v, p.faces))


@pytest.mark.parametrize("case", range(4))
def test_dynamic_sum_after_many_small_rotations_equals_fresh_sum(case, rng):
    a = sphere_points(int(rng.integers(10, 80)), rng, radii=rng.uniform(0.3, 2, size=3))
    b = sphere_points(int(rng.integers(10, 80)), rng)
    if case == 3:
        a, b = dymsum.load("ellipse"), dymsum.load("gs3")
    pa, pb = random_pose(rng), random_pose(rng)
    s = dymsum.DynamicSum(a, b, pa, pb)
    total_changes = 0
    for step in range(300):
        pa = random_pose(rng, angle=0.02) @ pa
        pa[:3, 3] = rng.uniform(-1, 1, size=3)
        if step % 3 == 0:
            pb = random_pose(rng, angle=0.01) @ pb
        report = s.update(pa, pb)
        assert report["recovered"] is None
        assert report["facets"] == s.facet_count
        total_changes += report["added"]
        if step % 150 == 149:
            v, f = s.mesh()
            v2, f2 = dymsum.minkowski_sum(a, b, pa, pb)
            assert np.array_equal(v, v2) and np.array_equal(f, f2)
            va = apply(pa, a.vertices if isinstance(a, dymsum.Polytope) else a)
            vb = apply(pb, b.vertices if isinstance(b, dymsum.Polytope) else b)
            check_sum_against_qhull(*s.mesh(polygons=True), pairwise_sums(va, vb), tol=1e-7)
    assert total_changes > 0  # the motion really changed the sum
    assert np.allclose(s.pose_a, pa, atol=1e-12) and np.allclose(s.pose_b, pb, atol=1e-12)


def test_dynamic_sum_update_keeps_a_body_whose_pose_is_none(rng):
    a, b = sphere_points(20, rng), sphere_points(20, rng)
    pa, pb = random_pose(rng), random_pose(rng)
    s = dymsum.DynamicSum(a, b, pa, pb)
    pa = random_pose(rng, angle=0.1) @ pa
    s.update(pa)  # B stays
    assert np.allclose(s.pose_b, pb, atol=1e-12) and np.allclose(s.pose_a, pa, atol=1e-12)
    pb = random_pose(rng, angle=0.1) @ pb
    s.update(None, pb)  # A stays
    assert np.allclose(s.pose_b, pb, atol=1e-12) and np.allclose(s.pose_a, pa, atol=1e-12)
    v, f = s.mesh()
    v2, f2 = dymsum.minkowski_sum(a, b, pa, pb)
    assert np.array_equal(v, v2) and np.array_equal(f, f2)


def test_report_counts_changes():
    a, b = dymsum.load("gs2"), dymsum.load("ellipse")
    s = dymsum.DynamicSum(a, b)
    before = s.facet_count
    r = s.update(dymsum.pose([0, 0, np.sin(0.05), np.cos(0.05)]))
    assert r["facets"] == before - r["removed"] + r["added"]
    assert r["removed"] > 0 and r["step_angle"] == pytest.approx(0.1, rel=1e-9)
    assert r["errors"] == r["fv_errors"] + r["ee_errors"]
