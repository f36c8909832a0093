//! `Polytope::from_mesh` at any position and size, and on large meshes
//! (issue 8 §3 first bullet, §4).

use dymsum::polytope::{MeshPolicy, PolytopeError};
use dymsum::{PolygonMesh, Polytope};
use dymsum_testkit::sphere_mesh;
use proptest::prelude::*;

use dymsum_testkit::CUBE_QUADS as QUADS;

/// An axis-aligned box with corner `at` and edge `size`, as quads or triangles.
fn box_mesh(at: [f64; 3], size: f64, triangulated: bool) -> PolygonMesh {
    let v = (0..8)
        .map(|i| {
            [
                at[0] + (i & 1) as f64 * size,
                at[1] + ((i >> 1) & 1) as f64 * size,
                at[2] + ((i >> 2) & 1) as f64 * size,
            ]
        })
        .collect();
    let faces = if triangulated {
        QUADS
            .iter()
            .flat_map(|q| [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]])
            .collect()
    } else {
        QUADS.iter().map(|q| q.to_vec()).collect()
    };
    PolygonMesh::new(v, faces)
}

fn assert_exact_box(mesh: &PolygonMesh, label: &str) {
    for policy in [MeshPolicy::default(), MeshPolicy::strict()] {
        let (p, r) =
            Polytope::from_mesh(mesh, policy).unwrap_or_else(|e| panic!("{label}: refused: {e}"));
        assert_eq!((p.vertex_count(), p.face_count()), (8, 6), "{label}");
        assert!(r.exactly_convex && !r.replaced_by_hull, "{label}: {r:?}");
        assert!(!r.inward_oriented, "{label}");
        // Exactly convex: exactly no deviation (not float noise).
        assert_eq!(r.max_deviation, 0.0, "{label}: {r:?}");
    }
}

#[test]
fn boxes_far_from_the_origin_load_exactly() {
    for (size, off) in [(0.01, 1e4), (1.0, 1e8), (1e-8, 1e6)] {
        for tri in [false, true] {
            let m = box_mesh([off, off, off], size, tri);
            assert_exact_box(&m, &format!("box {size} at {off}, triangulated {tri}"));
        }
    }
}

/// A box whose top face is dented by `depth` at its centre (4 triangles).
fn dented_box(at: [f64; 3], size: f64, depth: f64) -> PolygonMesh {
    let mut m = box_mesh(at, size, false);
    let c = m.vertices.len();
    m.vertices
        .push([at[0] + 0.5 * size, at[1] + 0.5 * size, at[2] + size - depth]);
    // The top face is QUADS[1] = [4, 5, 7, 6].
    m.faces.remove(1);
    for (a, b) in [(4, 5), (5, 7), (7, 6), (6, 4)] {
        m.faces.push(vec![a, b, c]);
    }
    m
}

#[test]
fn dented_box_far_away_is_refused_with_a_sane_distance() {
    for off in [0.0, 1e4, 1e8, -3e12] {
        let m = dented_box([off, off, off], 1.0, 0.3);
        match Polytope::from_mesh(&m, MeshPolicy::default()) {
            Err(e @ PolytopeError::NonConvex { .. }) => {
                let PolytopeError::NonConvex { what, distance, .. } = &e else {
                    unreachable!()
                };
                assert_eq!(what, "vertex 8", "offset {off}");
                assert!((distance - 0.3).abs() < 1e-3, "offset {off}: {e}");
                assert!(e.to_string().len() < 120, "offset {off}: {e}");
            }
            other => panic!("offset {off}: expected non-convex, got {other:?}"),
        }
    }
}

/// A minimal OFF reader for the embedded Fogel models.
fn parse_off(text: &str) -> PolygonMesh {
    let mut it = text
        .lines()
        .map(|l| l.split('#').next().unwrap().trim())
        .filter(|l| !l.is_empty())
        .skip(1);
    let counts: Vec<usize> = it
        .next()
        .unwrap()
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect();
    let v = (0..counts[0])
        .map(|_| {
            let c: Vec<f64> = it
                .next()
                .unwrap()
                .split_whitespace()
                .map(|t| t.parse().unwrap())
                .collect();
            [c[0], c[1], c[2]]
        })
        .collect();
    let f = (0..counts[1])
        .map(|_| {
            let c: Vec<usize> = it
                .next()
                .unwrap()
                .split_whitespace()
                .map(|t| t.parse().unwrap())
                .collect();
            c[1..=c[0]].to_vec()
        })
        .collect();
    PolygonMesh::new(v, f)
}

macro_rules! fogel {
    ($($name:literal),*) => {
        [$(($name, include_str!(concat!("../../dymsum-io/models/fogel/", $name, ".off")))),*]
    };
}

#[test]
fn fogel_models_translated_far_away_still_load() {
    let models = fogel!(
        "cube",
        "dioctagonal_dipyramid",
        "ellipsoid",
        "ellipsoid_1.0_0.5_0.5",
        "geodesic_sphere1",
        "geodesic_sphere2",
        "geodesic_sphere3",
        "geodesic_sphere4",
        "hexagonal_pyramid",
        "triakis_icosahedron",
        "truncated_icosidodecahedron"
    );
    for (name, text) in models {
        let m = parse_off(text);
        let (p0, _) = Polytope::from_mesh(&m, MeshPolicy::default())
            .unwrap_or_else(|e| panic!("{name} at the origin: {e}"));
        for off in [[1e4, -2e4, 3e4], [1e8, 1e8, -1e8], [-5e9, 2e9, 7e9]] {
            let mut t = m.clone();
            for v in &mut t.vertices {
                for k in 0..3 {
                    v[k] += off[k];
                }
            }
            let (p, r) = Polytope::from_mesh(&t, MeshPolicy::default())
                .unwrap_or_else(|e| panic!("{name} at {off:?}: {e}"));
            let rel = (p.volume() - p0.volume()).abs() / p0.volume();
            // The volume is a float construction from origin-relative
            // coordinates; only a coarse check at 1e9.
            assert!(rel < 1e-2, "{name} at {off:?}: volume {rel}");
            assert!(r.max_deviation <= r.tolerance, "{name} at {off:?}");
            assert!(p.vertex_count() <= p0.vertex_count() + 2, "{name}");
        }
    }
}

#[test]
fn large_sphere_mesh_loads_as_its_hull() {
    let m = sphere_mesh(20_000);
    let (p, r) = Polytope::from_mesh(&m, MeshPolicy::strict()).unwrap();
    let q = Polytope::from_points(&m.vertices).unwrap();
    assert!(r.exactly_convex);
    assert_eq!(
        (p.vertex_count(), p.face_count()),
        (q.vertex_count(), q.face_count())
    );
}

/// A tessellated cube: `k × k` quads per face, most with no hull corner.
fn tessellated_cube(k: usize, at: f64, size: f64) -> PolygonMesh {
    let mut verts = Vec::new();
    let mut index = std::collections::HashMap::new();
    let mut id = |p: [i64; 3], verts: &mut Vec<[f64; 3]>| -> usize {
        *index.entry(p).or_insert_with(|| {
            verts.push(p.map(|c| at + c as f64 * size / k as f64));
            verts.len() - 1
        })
    };
    let k = k as i64;
    let mut faces = Vec::new();
    for axis in 0..3 {
        for side in [0, k] {
            for a in 0..k {
                for b in 0..k {
                    let mut q = [[0i64; 3]; 4];
                    for (n, (da, db)) in [(0, 0), (1, 0), (1, 1), (0, 1)].iter().enumerate() {
                        q[n][axis] = side;
                        q[n][(axis + 1) % 3] = a + da;
                        q[n][(axis + 2) % 3] = b + db;
                    }
                    let mut f: Vec<usize> = q.iter().map(|&p| id(p, &mut verts)).collect();
                    if side == 0 {
                        f.reverse();
                    }
                    faces.push(f);
                }
            }
        }
    }
    PolygonMesh::new(verts, faces)
}

#[test]
fn tessellated_cube_far_away_is_exactly_convex() {
    for (at, size) in [(0.0, 1.0), (1e7, 3.0), (-2.5e11, 0.125)] {
        let m = tessellated_cube(12, at, size);
        let (p, r) = Polytope::from_mesh(&m, MeshPolicy::strict())
            .unwrap_or_else(|e| panic!("at {at}: {e}"));
        assert_eq!((p.vertex_count(), p.face_count()), (8, 6), "at {at}");
        assert!(r.exactly_convex, "at {at}");
        assert_eq!(r.dropped_vertices, m.vertices.len() - 8);
    }
}

#[test]
fn dented_tessellated_cube_is_refused() {
    let mut m = tessellated_cube(6, 1e6, 1.0);
    // Push the centre vertex of the bottom face inwards (its nearest hull
    // plane is then the bottom one, 0.25 away; the sides are 0.5 away).
    let i = m
        .vertices
        .iter()
        .position(|v| *v == [1e6 + 0.5, 1e6 + 0.5, 1e6])
        .unwrap();
    m.vertices[i][2] += 0.25;
    match Polytope::from_mesh(&m, MeshPolicy::default()) {
        Err(PolytopeError::NonConvex { what, distance, .. }) => {
            assert_eq!(what, format!("vertex {i}"));
            assert!((distance - 0.25).abs() < 1e-6, "{distance}");
        }
        other => panic!("expected non-convex, got {other:?}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Exact boxes at offsets up to 1e12 with sizes down to 1e-6 of the
    /// offset load as exactly convex 8-vertex, 6-face polytopes.
    #[test]
    fn boxes_at_any_offset_and_size(
        mant in prop::array::uniform3(-1.0f64..1.0),
        exp in 0i32..=12,
        rel in -6.0f64..0.0,
        tri in any::<bool>(),
    ) {
        let off = 10f64.powi(exp);
        let at = mant.map(|m| m * off);
        let size = off * 10f64.powf(rel);
        let m = box_mesh(at, size, tri);
        // The rounded corners still form an exact box; skip the rare case
        // where rounding collapsed it.
        prop_assume!(m.vertices[0] != m.vertices[7]);
        let (p, r) = Polytope::from_mesh(&m, MeshPolicy::strict()).unwrap();
        prop_assert_eq!((p.vertex_count(), p.face_count()), (8, 6));
        prop_assert!(r.exactly_convex);
    }

    /// A random convex hull, triangulated and translated far away (rounding
    /// the coordinates), still loads: exactly, or within tolerance.
    #[test]
    fn translated_hulls_load(
        seed_pts in prop::collection::vec(prop::array::uniform3(-1.0f64..1.0), 8..60),
        exp in 0i32..=12,
        rel in -6.0f64..0.0,
    ) {
        let off = 10f64.powi(exp);
        let size = off * 10f64.powf(rel);
        let Ok(p0) = Polytope::from_points(&seed_pts) else { return Ok(()) };
        let m0 = p0.to_mesh();
        let faces: Vec<Vec<usize>> = m0
            .faces
            .iter()
            .flat_map(|f| (1..f.len() - 1).map(move |k| vec![f[0], f[k], f[k + 1]]))
            .collect();
        let verts: Vec<[f64; 3]> = m0.vertices.iter().map(|v| v.map(|c| off + c * size)).collect();
        let m = PolygonMesh::new(verts, faces);
        let r = Polytope::from_mesh(&m, MeshPolicy::default());
        prop_assert!(r.is_ok(), "{:?}", r.err());
        let (_, rep) = r.unwrap();
        prop_assert!(rep.max_deviation <= rep.tolerance);
    }
}
