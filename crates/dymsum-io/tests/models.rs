//! Tests of the built-in model library (`dymsum_io::models`).

use std::collections::HashMap;

use dymsum::PolygonMesh;
use dymsum_io::models::{catalogue, model, ModelError};

type P3 = [f64; 3];

fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: P3, b: P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The paper's 13 models and their fan-triangulated triangle counts.
const PAPER: &[(&str, usize)] = &[
    ("cone", 78),
    ("cube", 12),
    ("cylinder", 140),
    ("dd", 32),
    ("ellipse", 960),
    ("gs1", 80),
    ("gs2", 180),
    ("gs3", 320),
    ("gs4", 500),
    ("hp", 10),
    ("t", 60),
    ("ti", 236),
    ("vrod", 324),
];

/// Checks that `mesh` is a closed, manifold, genus-0, outward-oriented convex
/// polytope. `planarity` is the allowed distance (relative to the model's
/// size) of a face's own vertices from the face's plane: the Fogel files are
/// printed with few digits, so their polygons are only approximately planar.
/// Every other vertex must lie below each face's plane within 1e-9 relative.
fn check_convex_polytope(label: &str, mesh: &PolygonMesh, planarity: f64) {
    assert!(!mesh.faces.is_empty(), "{label}: no faces");
    let size = mesh
        .vertices
        .iter()
        .map(|v| dot(*v, *v).sqrt())
        .fold(0.0, f64::max);
    assert!(size > 0.0, "{label}: degenerate");

    // Closed and manifold: each directed edge exactly once, reverse present.
    let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
    for (fi, f) in mesh.faces.iter().enumerate() {
        assert!(f.len() >= 3, "{label}: face {fi} has {} vertices", f.len());
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            assert!(a < mesh.vertices.len(), "{label}: index out of range");
            assert_ne!(a, b, "{label}: face {fi} repeats a vertex");
            *directed.entry((a, b)).or_default() += 1;
        }
    }
    for (&(a, b), &count) in &directed {
        assert_eq!(
            count, 1,
            "{label}: directed edge {a}->{b} used {count} times"
        );
        assert_eq!(
            directed.get(&(b, a)),
            Some(&1),
            "{label}: edge {a}->{b} has no reverse (open or non-manifold)"
        );
    }
    // Every vertex is used.
    let mut used = vec![false; mesh.vertices.len()];
    for f in &mesh.faces {
        for &v in f {
            used[v] = true;
        }
    }
    assert!(used.iter().all(|&u| u), "{label}: unused vertex");

    // Euler characteristic 2 (sphere).
    let (v, e, f) = (
        mesh.vertices.len() as i64,
        mesh.edge_count() as i64,
        mesh.faces.len() as i64,
    );
    assert_eq!(v - e + f, 2, "{label}: V - E + F = {v} - {e} + {f}");
    assert_eq!(e as usize * 2, directed.len());

    assert!(
        mesh.signed_volume() > 0.0,
        "{label}: signed volume {} not positive",
        mesh.signed_volume()
    );

    for (fi, face) in mesh.faces.iter().enumerate() {
        // Newell normal and centroid.
        let mut n = [0.0; 3];
        let mut c = [0.0; 3];
        for i in 0..face.len() {
            let a = mesh.vertices[face[i]];
            let b = mesh.vertices[face[(i + 1) % face.len()]];
            n[0] += (a[1] - b[1]) * (a[2] + b[2]);
            n[1] += (a[2] - b[2]) * (a[0] + b[0]);
            n[2] += (a[0] - b[0]) * (a[1] + b[1]);
            for k in 0..3 {
                c[k] += a[k] / face.len() as f64;
            }
        }
        let len = dot(n, n).sqrt();
        assert!(len > 0.0, "{label}: face {fi} degenerate");
        let n = [n[0] / len, n[1] / len, n[2] / len];
        // Planar.
        for &q in face {
            let d = dot(sub(mesh.vertices[q], c), n).abs();
            assert!(
                d <= planarity * size,
                "{label}: face {fi} not planar ({d:e})"
            );
        }
        // Convex polygon, counter-clockwise about the outward normal.
        for i in 0..face.len() {
            let a = mesh.vertices[face[i]];
            let b = mesh.vertices[face[(i + 1) % face.len()]];
            let c2 = mesh.vertices[face[(i + 2) % face.len()]];
            let turn = dot(cross(sub(b, a), sub(c2, b)), n);
            assert!(
                turn > 0.0,
                "{label}: face {fi} not strictly convex at corner {i} ({turn:e})"
            );
        }
        // Outward and supporting: everything else on or below the plane.
        for (q, &p) in mesh.vertices.iter().enumerate() {
            if face.contains(&q) {
                continue;
            }
            let d = dot(sub(p, c), n);
            assert!(
                d <= 1e-9 * size,
                "{label}: vertex {q} is {d:e} above face {fi} (not convex/outward)"
            );
        }
    }
}

/// Strict convexity at every vertex: no vertex lies in the middle of a flat
/// region, i.e. the faces around each vertex have at least three distinct
/// normal directions.
fn check_strictly_convex_vertices(label: &str, mesh: &PolygonMesh) {
    let normals: Vec<P3> = mesh
        .faces
        .iter()
        .map(|f| {
            let a = mesh.vertices[f[0]];
            let n = cross(sub(mesh.vertices[f[1]], a), sub(mesh.vertices[f[2]], a));
            let l = dot(n, n).sqrt();
            [n[0] / l, n[1] / l, n[2] / l]
        })
        .collect();
    for v in 0..mesh.vertices.len() {
        let mut distinct: Vec<P3> = Vec::new();
        for (fi, f) in mesh.faces.iter().enumerate() {
            if f.contains(&v) && !distinct.iter().any(|d| dot(*d, normals[fi]) > 1.0 - 1e-12) {
                distinct.push(normals[fi]);
            }
        }
        assert!(
            distinct.len() >= 3,
            "{label}: vertex {v} is not strictly convex ({} face directions)",
            distinct.len()
        );
    }
}

#[test]
fn every_catalogue_entry_resolves() {
    let cat = catalogue();
    assert!(cat.len() >= 13);
    for info in &cat {
        let mesh =
            model(info.example).unwrap_or_else(|e| panic!("{} ({}): {e}", info.name, info.example));
        assert!(!mesh.vertices.is_empty(), "{}", info.name);
        assert!(!info.description.is_empty() && !info.source.is_empty());
        if !info.name.contains(':') {
            assert_eq!(info.name, info.example);
        }
    }
    // The paper's 13 are listed with their triangle counts.
    for &(name, tris) in PAPER {
        let info = cat
            .iter()
            .find(|i| i.name == name)
            .unwrap_or_else(|| panic!("{name} missing from the catalogue"));
        assert_eq!(info.paper_triangles, Some(tris), "{name}");
    }
}

#[test]
fn paper_models_have_the_papers_triangle_counts() {
    for &(name, tris) in PAPER {
        let mesh = model(name).unwrap();
        assert_eq!(mesh.triangle_count(), tris, "{name}");
        assert_eq!(mesh.triangulated().faces.len(), tris, "{name}");
    }
}

#[test]
fn paper_models_are_convex_polytopes() {
    for &(name, _) in PAPER {
        let mesh = model(name).unwrap();
        check_convex_polytope(name, &mesh, 1e-6);
    }
    check_convex_polytope(
        "ellipsoid_1.0_0.5_0.5",
        &model("ellipsoid_1.0_0.5_0.5").unwrap(),
        1e-6,
    );
}

#[test]
fn generated_paper_models_are_exactly_planar_and_strictly_convex() {
    for name in ["cone", "cylinder", "vrod"] {
        let mesh = model(name).unwrap();
        check_convex_polytope(name, &mesh, 1e-12);
        check_strictly_convex_vertices(name, &mesh);
    }
}

#[test]
fn aliases_and_case() {
    let pairs = [
        ("v-rod", "vrod"),
        ("V-Rod", "vrod"),
        ("DD", "dd"),
        ("GS1", "gs1"),
        ("Gs4", "gs4"),
        ("HP", "hp"),
        ("T", "t"),
        ("TI", "ti"),
        ("ellipsoid-fogel", "ellipse"),
        ("  Cube  ", "cube"),
        ("cone:40", "cone"),
        ("cylinder:36:1,2", "cylinder"),
        ("capsule:27:3:0.5,4", "vrod"),
        ("box", "box:1,1,1"),
        ("box:2", "box:2,2,2"),
        ("tetrahedron", "tetra"),
        ("geodesic_sphere2", "gs2"),
    ];
    for (a, b) in pairs {
        assert_eq!(model(a).unwrap(), model(b).unwrap(), "{a} vs {b}");
    }
    let flat = model("ellipsoid_1.0_0.5_0.5").unwrap();
    let round = model("ellipse").unwrap();
    assert_eq!(flat.triangle_count(), 960);
    assert!(flat.signed_volume() < round.signed_volume() * 0.3);
}

#[test]
fn tessellated_cubes() {
    for k in [1, 2, 3, 5, 10] {
        let mesh = model(&format!("tcube:{k}")).unwrap();
        assert_eq!(mesh.triangle_count(), 12 * k * k, "tcube:{k}");
        assert_eq!(mesh.faces.len(), 12 * k * k);
        assert_eq!(mesh.vertices.len(), 6 * k * k + 2);
        check_convex_polytope(&format!("tcube:{k}"), &mesh, 1e-12);
        assert!((mesh.signed_volume() - 1000.0).abs() < 1e-9);
        for v in &mesh.vertices {
            assert!(v.iter().all(|c| c.abs() <= 5.0));
        }
    }
    assert_eq!(model("tcube:100").unwrap().triangle_count(), 120_000);
    assert_eq!(model("tcube").unwrap().triangle_count(), 12);
}

#[test]
fn parametric_primitives_are_convex_polytopes() {
    let cases: &[(&str, Option<usize>)] = &[
        ("box", Some(12)),
        ("box:1,2,3", Some(12)),
        ("box:0.001,1000,1", Some(12)),
        ("sphere", Some(320)),
        ("sphere:1", Some(20)),
        ("sphere:2", Some(80)),
        ("sphere:7", Some(980)),
        ("ellipsoid:3,2,1", Some(320)),
        ("ellipsoid:3,2,1:5", Some(500)),
        ("cylinder:3", Some(8)),
        ("cylinder:12:1,3", Some(2 * 10 + 24)),
        ("cylinder:100:0.5,10", Some(2 * 98 + 200)),
        ("cone:3", Some(4)),
        ("cone:12:1,3", Some(10 + 12)),
        ("capsule:16:4", Some(4 * 16 * 4)),
        ("capsule:3:1", Some(12)),
        ("capsule:8:2:1,0", Some(4 * 8 * 2 - 2 * 8)),
        ("tetra", Some(4)),
        ("octa", Some(8)),
        ("dodeca", Some(36)),
        ("icosa", Some(20)),
    ];
    for &(name, tris) in cases {
        let mesh = model(name).unwrap_or_else(|e| panic!("{name}: {e}"));
        if let Some(t) = tris {
            assert_eq!(mesh.triangle_count(), t, "{name}");
        }
        check_convex_polytope(name, &mesh, 1e-12);
        check_strictly_convex_vertices(name, &mesh);
    }
    assert_eq!(model("dodeca").unwrap().faces.len(), 12);
    assert!(model("dodeca").unwrap().faces.iter().all(|f| f.len() == 5));
    let b = model("box:1,2,3").unwrap();
    assert!((b.signed_volume() - 6.0).abs() < 1e-12);
}

#[test]
fn geodesic_spheres_lie_on_the_sphere() {
    let mesh = model("sphere:6").unwrap();
    assert_eq!(mesh.vertices.len(), 10 * 36 + 2);
    for v in &mesh.vertices {
        assert!((dot(*v, *v).sqrt() - 1.0).abs() < 1e-14);
    }
}

#[test]
fn random_is_a_deterministic_point_cloud() {
    let a = model("random:1000:42").unwrap();
    let b = model("random:1000:42").unwrap();
    let c = model("random:1000:43").unwrap();
    assert_eq!(a, b);
    assert_ne!(a.vertices, c.vertices);
    assert_eq!(a.vertices.len(), 1000);
    assert!(a.faces.is_empty(), "random models are point clouds");
    for v in &a.vertices {
        assert!(dot(*v, *v) <= 1.0);
    }
    // Spread over the ball, not clustered.
    let mean: f64 = a.vertices.iter().map(|v| dot(*v, *v).sqrt()).sum::<f64>() / 1000.0;
    assert!((mean - 0.75).abs() < 0.03, "mean radius {mean}");
    // Default seed is 0; the generator is pinned (ChaCha8 from seed_from_u64).
    assert_eq!(model("random:5").unwrap(), model("random:5:0").unwrap());
    // Golden values (bit patterns): the same seed must give the same points
    // on every platform and with every build.
    let first = model("random:4:0").unwrap().vertices;
    let bits: Vec<[u64; 3]> = first.iter().map(|v| v.map(f64::to_bits)).collect();
    assert_eq!(
        bits,
        vec![
            [
                4601204355621965084,
                13812947654919474816,
                4600846511385932112
            ],
            [
                4587094206236142848,
                13822419661879392428,
                4602940805391533494
            ],
            [
                4598811159838717796,
                13827138344816789516,
                13817524964733125888
            ],
            [
                4602915950792480938,
                4585351174599532992,
                4602702781385689274
            ],
        ]
    );
    // A longer cloud starts with the same points.
    assert_eq!(&model("random:10:0").unwrap().vertices[..4], &first[..]);
}

#[test]
fn unknown_names_get_suggestions() {
    let cases = [
        ("cubee", "cube"),
        ("cylnder", "cylinder"),
        ("Elipse", "ellipse"),
        ("vrodd", "vrod"),
        ("gs5", "gs1"),
        ("tcub:4", "tcube:4"),
        ("sphre:3", "sphere:3"),
        ("dodecahedro", "dodecahedron"),
    ];
    for (name, want) in cases {
        match model(name) {
            Err(ModelError::Unknown {
                name: n,
                suggestion,
            }) => {
                assert_eq!(n, name);
                assert_eq!(suggestion.as_deref(), Some(want), "{name}");
            }
            other => panic!("{name}: expected Unknown, got {other:?}"),
        }
    }
    match model("zzzzzzzzzzzz") {
        Err(ModelError::Unknown { suggestion, .. }) => assert_eq!(suggestion, None),
        other => panic!("expected Unknown, got {other:?}"),
    }
    let msg = model("cubee").unwrap_err().to_string();
    assert!(msg.contains("cubee") && msg.contains("cube"), "{msg}");
}

#[test]
fn bad_parameters_are_errors() {
    let cases = [
        ("tcube:0", "K"),
        ("tcube:101", "K"),
        ("tcube:-1", "K"),
        ("tcube:x", "K"),
        ("tcube:1.5", "K"),
        ("tcube:2,3", "K"),
        ("tcube:2:3", "group"),
        ("box:1,2", "box"),
        ("box:-1,1,1", "X"),
        ("box:1,0,1", "Y"),
        ("box:1,1,nan", "Z"),
        ("box:1,1,inf", "Z"),
        ("box:1,1,1e400", "Z"),
        ("box:0", "S"),
        ("sphere:0", "N"),
        ("sphere:abc", "N"),
        ("sphere:100000", "N"),
        ("ellipsoid", "A,B,C"),
        ("ellipsoid:1,2", "A,B,C"),
        ("ellipsoid:1,-2,3", "B"),
        ("ellipsoid:1,2,3:0", "N"),
        ("cylinder:2", "N"),
        ("cylinder:", "N"),
        ("cylinder:99999999999999999999999", "N"),
        ("cylinder:8:1", "R,H"),
        ("cylinder:8:1,-2", "H"),
        ("cone:1", "N"),
        ("cone:8:NaN,1", "R"),
        ("capsule:8", "K"),
        ("capsule:8:0", "K"),
        ("capsule:8:2:1,-1", "L"),
        ("random", "N"),
        ("random:3:1", "N"),
        ("random:100:-1", "SEED"),
        ("random:100:x", "SEED"),
        ("random:100000000000:1", "N"),
        ("cube:3", "parameters"),
        ("vrod:1", "parameters"),
    ];
    for (name, mentions) in cases {
        match model(name) {
            Err(ModelError::BadParameter { name: n, message }) => {
                assert_eq!(n, name);
                assert!(
                    message.contains(mentions),
                    "{name}: message `{message}` should mention `{mentions}`"
                );
            }
            other => panic!("{name}: expected BadParameter, got {other:?}"),
        }
    }
}

#[test]
fn no_string_panics() {
    let weird = [
        "",
        " ",
        ":",
        "::",
        ":::::",
        ",",
        "tcube:",
        "tcube::",
        "box:,,",
        "box:1,,1",
        "random::",
        "random:5:",
        "cone:5:,",
        "capsule:::",
        "ellipsoid:,,:",
        "\u{0}",
        "ÄÖÜ",
        "🦀:🦀",
        "sphere:-0",
        "tcube:+5",
        "cylinder:1e3",
        "ellipsoid:1,1,1:1:1",
    ];
    for w in weird {
        // A model, or an error that says why; never a panic.
        match model(w) {
            Ok(m) => assert!(!m.vertices.is_empty(), "{w}"),
            Err(e) => assert!(!e.to_string().is_empty(), "{w}"),
        }
    }
    let long = "x".repeat(10_000);
    assert!(matches!(model(&long), Err(ModelError::Unknown { .. })));
}

proptest::proptest! {
    #[test]
    fn arbitrary_names_never_panic(name in "\\PC{0,40}") {
        match model(&name) {
            Ok(m) => proptest::prop_assert!(!m.vertices.is_empty()),
            Err(e) => proptest::prop_assert!(!e.to_string().is_empty()),
        }
    }

    #[test]
    fn family_like_names_never_panic(
        family in "(tcube|box|sphere|ellipsoid|cylinder|cone|capsule|random|cube|vrod)",
        params in "([-+0-9.eEnaif ]{0,4}[,:]?){0,4}",
    ) {
        if let Ok(mesh) = model(&format!("{family}:{params}")) {
            proptest::prop_assert!(!mesh.vertices.is_empty());
        }
    }
}
