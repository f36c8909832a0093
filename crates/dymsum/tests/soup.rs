//! Meshes as they come (issue 28 §1, the first step): `clean_soup` merges
//! identical vertices, drops zero-area triangles, duplicates and the backs
//! of double-sided faces, and says which triangles enclose (solid
//! components, oriented outward) and which are surface (issue 33: by the
//! balance of their edges; tests/winding.rs probes what they enclose). Oracles: counts known by construction,
//! the exact solid check on every component called solid, and the signed
//! volume of the oriented solids.

use dymsum::solid::soup::{clean_soup, ComponentKind};
use dymsum::{check_solid_mesh, PolygonMesh, SolidError};
use proptest::prelude::*;

/// The 12 outward triangles of the box `[lo, hi]`, vertices `offset..`.
fn box_triangles(offset: usize) -> Vec<Vec<usize>> {
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    quads
        .iter()
        .flat_map(|q| {
            [
                vec![q[0] + offset, q[1] + offset, q[2] + offset],
                vec![q[0] + offset, q[2] + offset, q[3] + offset],
            ]
        })
        .collect()
}

fn box_vertices(lo: [f64; 3], hi: [f64; 3]) -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| std::array::from_fn(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
        .collect()
}

fn six_volume(m: &PolygonMesh, tris: &[usize]) -> f64 {
    tris.iter()
        .map(|&k| {
            let f = &m.faces[k];
            let [a, b, c] = [f[0], f[1], f[2]].map(|v| glam::DVec3::from(m.vertices[v]));
            a.dot(b.cross(c))
        })
        .sum()
}

fn reversed(f: &[usize]) -> Vec<usize> {
    vec![f[0], f[2], f[1]]
}

#[test]
fn a_double_sided_box_is_one_outward_solid() {
    let v = box_vertices([0.0; 3], [1.0, 2.0, 3.0]);
    let one = box_triangles(0);
    let mut faces = one.clone();
    faces.extend(one.iter().map(|f| reversed(f)));
    let soup = clean_soup(&PolygonMesh::new(v, faces)).unwrap();
    assert_eq!(soup.mesh.faces.len(), 12);
    assert_eq!(soup.dropped_back_to_back, 12);
    assert_eq!(soup.components.len(), 1);
    assert_eq!(soup.components[0].kind, ComponentKind::Solid);
    assert!((six_volume(&soup.mesh, &soup.components[0].triangles) - 36.0).abs() < 1e-12);
}

#[test]
fn the_back_listed_first_is_kept_and_turned_outward() {
    // Every face given inward first, then outward: the inward copies are
    // kept and the solid is flipped as a whole.
    let v = box_vertices([0.0; 3], [1.0; 3]);
    let one = box_triangles(0);
    let mut faces: Vec<Vec<usize>> = one.iter().map(|f| reversed(f)).collect();
    faces.extend(one.clone());
    let soup = clean_soup(&PolygonMesh::new(v, faces)).unwrap();
    assert_eq!((soup.mesh.faces.len(), soup.flipped), (12, 12));
    assert!(six_volume(&soup.mesh, &soup.components[0].triangles) > 0.0);
    check_solid_mesh(&soup.mesh).unwrap();
}

#[test]
fn randomly_oriented_triangles_of_a_closed_box_are_oriented_outward() {
    let v = box_vertices([-1.0; 3], [1.0; 3]);
    let faces: Vec<Vec<usize>> = box_triangles(0)
        .iter()
        .enumerate()
        .map(|(k, f)| if k % 3 == 1 { reversed(f) } else { f.clone() })
        .collect();
    let soup = clean_soup(&PolygonMesh::new(v, faces)).unwrap();
    assert_eq!(soup.components[0].kind, ComponentKind::Solid);
    assert_eq!(soup.flipped, 4);
    check_solid_mesh(&soup.mesh).unwrap();
}

#[test]
fn unwelded_vertices_and_zero_area_triangles_are_cleaned() {
    // Every triangle with its own three vertices (as STL stores them),
    // plus a sliver triangle on an edge and a triangle repeating a vertex.
    let v = box_vertices([0.0; 3], [1.0; 3]);
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for f in box_triangles(0) {
        let o = vertices.len();
        vertices.extend(f.iter().map(|&i| v[i]));
        faces.push(vec![o, o + 1, o + 2]);
    }
    let o = vertices.len();
    vertices.extend([[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0]]);
    faces.push(vec![o, o + 1, o + 2]); // collinear
    faces.push(vec![0, 0, 1]); // repeats a vertex
    let soup = clean_soup(&PolygonMesh::new(vertices, faces)).unwrap();
    assert_eq!(soup.dropped_zero_area, 2);
    assert_eq!(soup.mesh.faces.len(), 12);
    assert_eq!(soup.solids(), 1);
    // 36 + 3 given, 8 distinct plus the sliver's midpoint.
    assert_eq!(soup.merged_vertices, 39 - 9);
}

#[test]
fn open_non_manifold_and_lone_triangles_are_surfaces_beside_solids() {
    let mut vertices = box_vertices([0.0; 3], [1.0; 3]);
    let mut faces = box_triangles(0);
    // An open box (one side missing).
    vertices.extend(box_vertices([3.0, 0.0, 0.0], [4.0, 1.0, 1.0]));
    faces.extend(box_triangles(8).into_iter().skip(2));
    // A lone triangle.
    vertices.extend([[9.0, 0.0, 0.0], [10.0, 0.0, 0.0], [9.0, 1.0, 0.0]]);
    faces.push(vec![16, 17, 18]);
    // Three triangles on one edge (non-manifold fins).
    vertices.extend([
        [20.0, 0.0, 0.0],
        [20.0, 0.0, 1.0],
        [21.0, 0.0, 0.0],
        [20.0, 1.0, 0.0],
        [19.0, 0.0, 0.0],
    ]);
    faces.extend([vec![19, 20, 21], vec![19, 20, 22], vec![19, 20, 23]]);
    let soup = clean_soup(&PolygonMesh::new(vertices, faces)).unwrap();
    let kinds: Vec<ComponentKind> = soup.components.iter().map(|c| c.kind).collect();
    assert_eq!(
        kinds,
        [
            ComponentKind::Solid,
            ComponentKind::Surface,
            ComponentKind::Surface,
            ComponentKind::Surface
        ]
    );
}

#[test]
fn nested_and_overlapping_boxes_are_solids_each() {
    let mut vertices = box_vertices([0.0; 3], [4.0; 3]);
    vertices.extend(box_vertices([1.0; 3], [2.0; 3]));
    vertices.extend(box_vertices([3.0; 3], [5.0; 3]));
    let mut faces = box_triangles(0);
    faces.extend(box_triangles(8));
    faces.extend(box_triangles(16));
    let soup = clean_soup(&PolygonMesh::new(vertices, faces)).unwrap();
    assert_eq!(soup.solids(), 3);
}

#[test]
fn a_closed_mesh_crossing_itself_encloses() {
    // A box whose top vertex is pulled through the bottom face: a closed
    // cycle, so it encloses its points of non-zero winding number
    // (tests/winding.rs probes them).
    let mut v = box_vertices([0.0; 3], [1.0; 3]);
    v[7] = [0.5, 0.5, -2.0];
    let soup = clean_soup(&PolygonMesh::new(v, box_triangles(0))).unwrap();
    assert_eq!(soup.components[0].kind, ComponentKind::Solid);
}

#[test]
fn bad_input_is_a_typed_error() {
    let v = box_vertices([0.0; 3], [1.0; 3]);
    assert!(matches!(
        clean_soup(&PolygonMesh::new(v.clone(), vec![])),
        Err(SolidError::Empty)
    ));
    assert!(matches!(
        clean_soup(&PolygonMesh::new(v.clone(), vec![vec![0, 1, 99]])),
        Err(SolidError::BadFace { face: 0 })
    ));
    let mut nan = v;
    nan[3][1] = f64::NAN;
    assert!(matches!(
        clean_soup(&PolygonMesh::new(nan, box_triangles(0))),
        Err(SolidError::NonFinite { vertex: 3 })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    /// A box placed anywhere (float32 coordinates, far offsets), its faces
    /// shuffled, some reversed and some listed twice either way, is one
    /// outward solid of the box's volume.
    #[test]
    fn shuffled_double_sided_boxes_are_solids(
        lo in prop::array::uniform3(-1e4f32..1e4f32),
        size in prop::array::uniform3(0.01f32..10.0f32),
        flips in prop::collection::vec(any::<u8>(), 12),
        order in Just((0..12usize).collect::<Vec<_>>()).prop_shuffle(),
    ) {
        let lo = lo.map(f64::from);
        let hi: [f64; 3] = std::array::from_fn(|k| f64::from(lo[k] as f32 + size[k]));
        prop_assume!((0..3).all(|k| hi[k] > lo[k]));
        let v = box_vertices(lo, hi);
        let tris = box_triangles(0);
        let mut faces = Vec::new();
        for &k in &order {
            let f = &tris[k];
            match flips[k] % 4 {
                0 => faces.push(f.clone()),
                1 => faces.push(reversed(f)),
                2 => { faces.push(f.clone()); faces.push(reversed(f)); }
                _ => { faces.push(reversed(f)); faces.push(f.clone()); faces.push(f.clone()); }
            }
        }
        let soup = clean_soup(&PolygonMesh::new(v, faces)).unwrap();
        prop_assert_eq!(soup.mesh.faces.len(), 12);
        prop_assert_eq!(soup.solids(), 1);
        check_solid_mesh(&soup.mesh).unwrap();
        let expect = 6.0 * (0..3).map(|k| hi[k] - lo[k]).product::<f64>();
        let got = six_volume(&soup.mesh, &soup.components[0].triangles);
        prop_assert!((got - expect).abs() <= 1e-6 * expect.abs().max(1.0) * (1.0 + lo.iter().map(|x| x.abs()).fold(0.0, f64::max)), "{} vs {}", got, expect);
    }
}
