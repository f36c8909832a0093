//! The exact check of meshes given as solids (issue 26, findings 2, 3 and
//! 7): `dymsum::solid::check_solid_mesh`.
//!
//! Each finding of the issue is a named test; then valid solids of every
//! kind the suites use (convex, non-convex polygons, a ring, overlapping
//! shells), and property tests: random hulls are solids at any offset and
//! scale, and the same hulls with a vertex pulled through the body or a
//! face listed again are refused.

use dymsum::solid::{check_solid_mesh, SolidError};
use dymsum::{PolygonMesh, Polytope};
use proptest::prelude::*;

/// A prism over a simple polygon `ring` (counter-clockwise in xy, star-
/// shaped from its first corner), between heights `z0 < z1`: the caps as
/// one polygon each (fans from corner 0), the sides as quads.
fn prism(ring: &[[f64; 2]], z0: f64, z1: f64) -> PolygonMesh {
    let n = ring.len();
    let mut v: Vec<[f64; 3]> = ring.iter().map(|p| [p[0], p[1], z0]).collect();
    v.extend(ring.iter().map(|p| [p[0], p[1], z1]));
    let mut f: Vec<Vec<usize>> = vec![(n..2 * n).collect()];
    // The bottom reversed, still starting at corner 0.
    f.push(std::iter::once(0).chain((1..n).rev()).collect());
    for i in 0..n {
        let j = (i + 1) % n;
        f.push(vec![i, j, n + j, n + i]);
    }
    PolygonMesh::new(v, f)
}

fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> PolygonMesh {
    prism(
        &[
            [lo[0], lo[1]],
            [hi[0], lo[1]],
            [hi[0], hi[1]],
            [lo[0], hi[1]],
        ],
        lo[2],
        hi[2],
    )
}

/// The L of the issue: `[0,3]×[0,1]² ∪ [0,1]×[0,3]×[0,1]`, one shell.
fn l_prism() -> PolygonMesh {
    let l = [[0., 0.], [3., 0.], [3., 1.], [1., 1.], [1., 3.], [0., 3.]];
    prism(&l, 0.0, 1.0)
}

/// Several meshes as separate shells of one mesh.
fn join(meshes: &[PolygonMesh]) -> PolygonMesh {
    let mut out = PolygonMesh::default();
    for m in meshes {
        let o = out.vertices.len();
        out.vertices.extend(&m.vertices);
        out.faces
            .extend(m.faces.iter().map(|f| f.iter().map(|&i| i + o).collect()));
    }
    out
}

fn check(m: &PolygonMesh) -> Result<usize, SolidError> {
    check_solid_mesh(m).map(|info| info.shells.len())
}

// ------------------------------------------------------------ the findings

/// Finding 2: the L with every triangle listed twice was summed under
/// `decomposition="boundary"` to volume 13.188 reported exact (truth
/// 12.375).
#[test]
fn l_mesh_with_every_triangle_listed_twice_is_refused() {
    let l = l_prism().triangulated();
    assert_eq!(check(&l), Ok(1));
    let mut twice = l.clone();
    twice.faces.extend(l.faces.iter().cloned());
    let err = check(&twice).unwrap_err();
    let b = l.faces.len();
    assert_eq!(err, SolidError::DuplicateFace { a: 0, b });
    assert!(err
        .to_string()
        .starts_with(&format!("faces 0 and {b} have the same corners")));
}

/// Finding 3: closed meshes that cross themselves (winding number 2 or −1
/// in places) were summed.
#[test]
fn self_intersecting_closed_meshes_are_refused() {
    // A cube with a corner pulled through the opposite face.
    let mut cube = cuboid([0.; 3], [1.; 3]).triangulated();
    let top = cube
        .vertices
        .iter()
        .position(|&p| p == [1., 1., 1.])
        .unwrap();
    cube.vertices[top] = [1., 1., -0.5];
    assert!(matches!(
        check(&cube),
        Err(SolidError::TrianglesCross { .. })
    ));
    // A prism over a curl that crosses itself: a closed, oriented
    // 2-manifold of positive volume, winding number 2 in one box and −1 in
    // another.
    let bent = [
        [0., 0.],
        [4., 0.],
        [4., 3.],
        [1., 3.],
        [1., 1.],
        [3., 1.],
        [3., 2.],
        [2., 2.],
        [2., -1.],
        [0., -1.],
    ];
    let mesh = prism(&bent, 0.0, 1.0).triangulated();
    assert!(mesh.signed_volume() > 0.0);
    let err = check(&mesh).unwrap_err();
    assert!(matches!(err, SolidError::TrianglesCross { .. }), "{err}");
    assert!(err
        .to_string()
        .contains(" cross (they meet other than along"));
}

/// Finding 3: a closed zero-volume sheet beside a cube was counted as
/// volume.
#[test]
fn closed_zero_volume_sheets_beside_a_cube_are_refused() {
    let cube = cuboid([0.; 3], [1.; 3]);
    // Two triangles back to back.
    let sheet = PolygonMesh::new(
        vec![[2., 0., 0.], [3., 0., 0.], [2., 1., 0.]],
        vec![vec![0, 1, 2], vec![0, 2, 1]],
    );
    assert_eq!(
        check(&join(&[cube.clone(), sheet])),
        Err(SolidError::DuplicateFace { a: 6, b: 7 })
    );
    // A tetrahedron flattened into its base plane: its faces overlap.
    let flat = PolygonMesh::new(
        vec![[2., 0., 0.], [3., 0., 0.], [2., 1., 0.], [2.25, 0.25, 0.]],
        vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]],
    );
    assert!(matches!(
        check(&join(&[cube.clone(), flat])),
        Err(SolidError::TrianglesCross { a: 6, .. })
    ));
    // A flat tetrahedron on a segment: zero-area triangles.
    let needle = PolygonMesh::new(
        vec![[2., 0., 0.], [3., 0., 0.], [4., 0., 0.], [2., 1., 0.]],
        vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]],
    );
    assert!(matches!(
        check(&join(&[cube, needle])),
        Err(SolidError::ZeroAreaTriangle { face: 6, .. })
    ));
}

/// Finding 7: non-manifold input (under `boundary`) failed inside the mesh
/// boolean instead of naming what is wrong.
#[test]
fn non_manifold_input_is_refused() {
    // Two tetrahedra sharing one vertex.
    let tetra = |s: f64| {
        PolygonMesh::new(
            vec![[0., 0., 0.], [s, 0., 0.], [0., s, 0.], [0., 0., s]],
            vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]],
        )
    };
    let mut two = join(&[tetra(1.0), tetra(-1.0)]);
    for f in &mut two.faces[4..] {
        f.reverse(); // the mirrored tetrahedron, outward again
        for i in f.iter_mut() {
            if *i == 4 {
                *i = 0;
            }
        }
    }
    assert_eq!(
        check(&two),
        Err(SolidError::NonManifoldVertex { vertex: 0 })
    );
    // Two cubes sharing an edge (x = y = 1, z in [0, 1]).
    let mut cubes = join(&[cuboid([0.; 3], [1.; 3]), cuboid([1., 1., 0.], [2., 2., 1.])]);
    let same = |p: [f64; 3]| cubes.vertices.iter().position(|&q| q == p).unwrap();
    let (a, b) = (same([1., 1., 0.]), same([1., 1., 1.]));
    for f in &mut cubes.faces[6..] {
        for i in f.iter_mut() {
            if cubes.vertices[*i] == [1., 1., 0.] {
                *i = a;
            } else if cubes.vertices[*i] == [1., 1., 1.] {
                *i = b;
            }
        }
    }
    let err = check(&cubes).unwrap_err();
    assert!(
        matches!(err, SolidError::NonManifoldEdge { count: 4, .. }),
        "{err}"
    );
}

// ------------------------------------------------------------ other rules

#[test]
fn each_other_defect_is_named() {
    let cube = cuboid([0.; 3], [1.; 3]);
    let mut open = cube.clone();
    open.faces.pop();
    assert!(matches!(check(&open), Err(SolidError::OpenEdge { .. })));
    let mut flipped = cube.clone();
    flipped.faces[2].reverse();
    let err = check(&flipped).unwrap_err();
    assert!(
        matches!(err, SolidError::InconsistentOrientation { .. }),
        "{err}"
    );
    let mut bent = cube.clone();
    let top = bent
        .vertices
        .iter()
        .position(|&p| p == [1., 1., 1.])
        .unwrap();
    bent.vertices[top] = [1., 1., 1.0 + 1e-12];
    assert!(matches!(
        check(&bent),
        Err(SolidError::NonPlanarFace { .. })
    ));
    assert_eq!(check(&bent.triangulated()), Ok(1));
    let mut inward = cube.clone();
    inward.faces.iter_mut().for_each(|f| f.reverse());
    assert_eq!(
        check(&inward),
        Err(SolidError::NonPositiveVolume {
            shell: 0,
            face: 0,
            negative: true
        })
    );
    // A cavity: an inward cube inside a cube (refused: shells are a union).
    let mut inner = cuboid([0.25; 3], [0.75; 3]);
    inner.faces.iter_mut().for_each(|f| f.reverse());
    assert!(matches!(
        check(&join(&[cube.clone(), inner])),
        Err(SolidError::NonPositiveVolume {
            shell: 1,
            face: 6,
            ..
        })
    ));
    let mut nan = cube.clone();
    nan.vertices[3][1] = f64::NAN;
    assert_eq!(check(&nan), Err(SolidError::NonFinite { vertex: 3 }));
    let mut bad = cube.clone();
    bad.faces[1] = vec![0, 1];
    assert_eq!(check(&bad), Err(SolidError::BadFace { face: 1 }));
    assert_eq!(check(&PolygonMesh::default()), Err(SolidError::Empty));
    let mut wide = cube;
    wide.vertices[0] = [1e-300, 0., 0.];
    wide.vertices[6] = [1e300, 1., 1.];
    assert!(matches!(check(&wide), Err(SolidError::OutOfRange { .. })));
}

#[test]
fn valid_solids_pass() {
    let l = l_prism();
    assert_eq!(check(&l), Ok(1));
    assert_eq!(check(&l.triangulated()), Ok(1));
    // A square ring (genus 1): four trapezoids on each cap.
    let (o, i) = (
        [[0., 0.], [4., 0.], [4., 4.], [0., 4.]],
        [[1., 1.], [3., 1.], [3., 3.], [1., 3.]],
    );
    let mut v = Vec::new();
    for z in [0., 1.] {
        v.extend(o.iter().map(|p| [p[0], p[1], z]));
        v.extend(i.iter().map(|p| [p[0], p[1], z]));
    }
    let (ob, ib, ot, it) = (0, 4, 8, 12);
    let mut f = Vec::new();
    for k in 0..4 {
        let j = (k + 1) % 4;
        f.push(vec![ot + k, ot + j, it + j, it + k]);
        f.push(vec![ob + k, ib + k, ib + j, ob + j]);
        f.push(vec![ob + k, ob + j, ot + j, ot + k]);
        f.push(vec![ib + k, it + k, it + j, ib + j]);
    }
    let ring = PolygonMesh::new(v, f);
    assert_eq!(check(&ring), Ok(1));
    assert_eq!(check(&ring.triangulated()), Ok(1));
    // Overlapping and touching shells are a union: not tested against each
    // other.
    let shells = join(&[
        cuboid([0.; 3], [3., 1., 1.]),
        cuboid([0.; 3], [1., 3., 1.]),
        cuboid([3., 0., 0.], [4., 1., 1.]),
    ]);
    assert_eq!(check(&shells), Ok(3));
    // A non-convex cap whose fan from corner 0 folds is refused.
    let l = [[3., 1.], [1., 1.], [1., 3.], [0., 3.], [0., 0.], [3., 0.]];
    let err = check(&prism(&l, 0.0, 1.0)).unwrap_err();
    assert!(
        matches!(err, SolidError::TrianglesCross { a, b } if a == b),
        "{err}"
    );
}

// ------------------------------------------------------------ properties

/// The triangulated hull of points on a grid of `2^-20` in `[-1, 1]³`
/// (so offsets by `2^20` and scalings by powers of two are exact).
fn hull(points: &[[i32; 3]]) -> Option<PolygonMesh> {
    let pts: Vec<[f64; 3]> = points
        .iter()
        .map(|p| p.map(|x| x as f64 * (-20f64).exp2()))
        .collect();
    Polytope::from_points(&pts)
        .ok()
        .map(|p| p.to_mesh().triangulated())
}

fn moved(m: &PolygonMesh, scale: f64, offset: f64) -> PolygonMesh {
    let mut out = m.clone();
    for p in &mut out.vertices {
        *p = p.map(|x| x * scale + offset);
    }
    out
}

fn points() -> impl Strategy<Value = Vec<[i32; 3]>> {
    let c = -(1 << 20)..=(1 << 20);
    prop::collection::vec([c.clone(), c.clone(), c], 5..40)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn hulls_are_solids_at_any_offset_and_scale(pts in points(), k in -60i32..60) {
        let Some(m) = hull(&pts) else { return Ok(()) };
        prop_assert_eq!(check(&m), Ok(1));
        let polygons = Polytope::from_points(&m.vertices).unwrap().to_mesh();
        prop_assert_eq!(check(&polygons), Ok(1));
        let s = (k as f64).exp2();
        prop_assert_eq!(check(&moved(&m, s, 0.0)), Ok(1));
        prop_assert_eq!(check(&moved(&m, 1.0, 1048576.0)), Ok(1));
        prop_assert_eq!(check(&moved(&m, s, -1048576.0 * s)), Ok(1));
    }

    #[test]
    fn a_vertex_pulled_through_the_body_is_refused(pts in points(), pick in 0usize..1000, k in -60i32..60) {
        let Some(m) = hull(&pts) else { return Ok(()) };
        let n = m.vertices.len() as f64;
        let c = m.vertices.iter().fold([0.; 3], |a, p| std::array::from_fn(|i| a[i] + p[i] / n));
        let mut pulled = m.clone();
        let v = pick % m.vertices.len();
        // Pulled through the centroid to three times its distance, on the grid.
        let grid = 1048576.0;
        pulled.vertices[v] =
            std::array::from_fn(|i| ((c[i] - 3.0 * (m.vertices[v][i] - c[i])) * grid).round() / grid);
        let err = check(&pulled);
        // Crossing, or (a tetrahedron turned inside out) inward.
        prop_assert!(
            matches!(err, Err(SolidError::TrianglesCross { .. } | SolidError::NonPositiveVolume { .. })),
            "{:?}",
            err
        );
        // The same answer offset and scaled (exactly: powers of two).
        let s = (k as f64).exp2();
        prop_assert_eq!(check(&moved(&pulled, s, 1048576.0 * s)), err);
    }

    #[test]
    fn a_face_listed_again_is_refused(pts in points(), pick in 0usize..1000, flip in any::<bool>()) {
        let Some(mut m) = hull(&pts) else { return Ok(()) };
        let a = pick % m.faces.len();
        let mut f = m.faces[a].clone();
        if flip {
            f.reverse();
        }
        m.faces.push(f);
        let b = m.faces.len() - 1;
        prop_assert_eq!(check(&m), Err(SolidError::DuplicateFace { a, b }));
    }
}
