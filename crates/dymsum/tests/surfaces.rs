//! Surface contact between triangle meshes of any topology (issue 28, the
//! first step): `surfaces_touch` against
//!
//! * the brute force over every triangle pair (the broad phase culls no
//!   touching pair), on random soups including flat and point triangles;
//! * a float separating-axis oracle: a pair separated along one of its 11
//!   axes by more than 1e-9 of the size never touches;
//! * known answers: touching along an edge, at a vertex, face on face,
//!   crossing plates, and gaps of one ulp at offsets up to 1e8.

use dymsum::query::surfaces_touch;
use dymsum::{DVec3, PolygonMesh, Pose, Rotation};
use proptest::prelude::*;

fn square(z: f64) -> PolygonMesh {
    PolygonMesh::new(
        vec![[0., 0., z], [1., 0., z], [1., 1., z], [0., 1., z]],
        vec![vec![0, 1, 2], vec![0, 2, 3]],
    )
}

fn at(x: f64, y: f64, z: f64) -> Pose {
    Pose::new(Rotation::IDENTITY, DVec3::new(x, y, z))
}

#[test]
fn known_contacts_and_one_ulp_gaps() {
    let s = square(0.0);
    // Face on face, edge on edge, vertex on vertex.
    assert!(surfaces_touch(&s, Pose::IDENTITY, &s, Pose::IDENTITY).unwrap());
    assert!(surfaces_touch(&s, Pose::IDENTITY, &s, at(1.0, 0.0, 0.0)).unwrap());
    assert!(surfaces_touch(&s, Pose::IDENTITY, &s, at(1.0, 1.0, 0.0)).unwrap());
    // Stacked squares, coplanar (touching) and one ulp apart, near the
    // origin and far from it.
    for base in [0.0f64, 1.0, 1e8] {
        let up = f64::from_bits(base.to_bits() + 1).max(f64::from_bits(1));
        let lower = at(base, base, base);
        assert!(surfaces_touch(&s, lower, &s, at(base, base, base)).unwrap());
        assert!(
            !surfaces_touch(&s, lower, &s, at(base, base, up)).unwrap(),
            "base {base}"
        );
    }
    // Crossing plates (a vertical square through a horizontal one).
    let turned = Rotation::from_axis_angle(DVec3::X, std::f64::consts::FRAC_PI_2).unwrap();
    let cross = Pose::new(turned, DVec3::new(0.25, 0.5, -0.5));
    assert!(surfaces_touch(&s, Pose::IDENTITY, &s, cross).unwrap());
    // Beside it, not touching.
    let beside = Pose::new(turned, DVec3::new(1.25, 0.5, -0.5));
    assert!(!surfaces_touch(&s, Pose::IDENTITY, &s, beside).unwrap());
}

#[test]
fn double_sided_and_degenerate_triangles_are_surfaces_too() {
    // A flat triangle (a segment) crossing a square, a point on it.
    let seg = PolygonMesh::new(
        vec![[0.5, 0.5, -1.0], [0.5, 0.5, 0.0], [0.5, 0.5, 1.0]],
        vec![vec![0, 1, 2]],
    );
    let s = square(0.0);
    assert!(surfaces_touch(&seg, Pose::IDENTITY, &s, Pose::IDENTITY).unwrap());
    assert!(!surfaces_touch(&seg, at(2.0, 0.0, 0.0), &s, Pose::IDENTITY).unwrap());
    let point = PolygonMesh::new(vec![[0.25, 0.75, 0.0]], vec![vec![0, 0, 0]]);
    assert!(surfaces_touch(&point, Pose::IDENTITY, &s, Pose::IDENTITY).unwrap());
    assert!(!surfaces_touch(&point, at(0.0, 0.0, 1e-300), &s, Pose::IDENTITY).unwrap());
    // Two segments crossing (both flat).
    let other = PolygonMesh::new(
        vec![[0.0, 0.5, 0.0], [0.5, 0.5, 0.0], [1.0, 0.5, 0.0]],
        vec![vec![0, 1, 2]],
    );
    let seg_flat = PolygonMesh::new(
        vec![[0.5, 0.0, 0.0], [0.5, 0.5, 0.0], [0.5, 1.0, 0.0]],
        vec![vec![0, 1, 2]],
    );
    assert!(surfaces_touch(&other, Pose::IDENTITY, &seg_flat, Pose::IDENTITY).unwrap());
    assert!(!surfaces_touch(&other, at(0.0, 0.0, 1e-9), &seg_flat, Pose::IDENTITY).unwrap());
    // Bad input.
    let bad = PolygonMesh::new(vec![[0.0; 3]], vec![vec![0, 1, 2]]);
    assert!(surfaces_touch(&bad, Pose::IDENTITY, &s, Pose::IDENTITY).is_err());
    // A face of fewer than three corners is refused, never skipped.
    for face in [vec![], vec![0], vec![0, 1]] {
        let short = PolygonMesh::new(vec![[0.5, 0.5, 0.0], [0.6, 0.5, 0.0]], vec![face]);
        assert!(surfaces_touch(&short, Pose::IDENTITY, &s, Pose::IDENTITY).is_err());
    }
    let far = PolygonMesh::new(
        vec![[1e308, 0.0, 0.0], [1e308, 1.0, 0.0], [1e308, 0.0, 1.0]],
        vec![vec![0, 1, 2]],
    );
    assert!(surfaces_touch(&far, at(1e308, 0.0, 0.0), &s, Pose::IDENTITY).is_err());
}

/// The same answer as every triangle pair tested by brute force with the
/// same exact test (through a one-triangle mesh per pair).
fn brute(a: &PolygonMesh, pa: Pose, b: &PolygonMesh, pb: Pose) -> bool {
    a.faces.iter().any(|fa| {
        let ta = PolygonMesh::new(a.vertices.clone(), vec![fa.clone()]);
        b.faces.iter().any(|fb| {
            let tb = PolygonMesh::new(b.vertices.clone(), vec![fb.clone()]);
            surfaces_touch(&ta, pa, &tb, pb).unwrap()
        })
    })
}

/// Float separating-axis test: `true` when some axis (the two normals and
/// the nine edge cross products) separates the triangles by more than
/// `margin`.
fn clearly_apart(t: [DVec3; 3], u: [DVec3; 3], margin: f64) -> bool {
    let n1 = (t[1] - t[0]).cross(t[2] - t[0]);
    let n2 = (u[1] - u[0]).cross(u[2] - u[0]);
    let mut axes = vec![n1, n2];
    for i in 0..3 {
        for j in 0..3 {
            axes.push((t[(i + 1) % 3] - t[i]).cross(u[(j + 1) % 3] - u[j]));
        }
    }
    axes.into_iter().any(|d| {
        let l = d.length();
        if l < 1e-6 {
            return false;
        }
        let d = d / l;
        let (tmin, tmax) = t
            .iter()
            .map(|p| p.dot(d))
            .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
        let (umin, umax) = u
            .iter()
            .map(|p| p.dot(d))
            .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
        umin - tmax > margin || tmin - umax > margin
    })
}

fn soup(coords: &[[f64; 3]]) -> PolygonMesh {
    let n = coords.len() / 3 * 3;
    PolygonMesh::new(
        coords[..n].to_vec(),
        (0..n / 3)
            .map(|k| vec![3 * k, 3 * k + 1, 3 * k + 2])
            .collect(),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_soups_agree_with_brute_force_and_the_separating_axes(
        a in prop::collection::vec(prop::array::uniform3(-2.0f64..2.0), 3..24),
        b in prop::collection::vec(prop::array::uniform3(-2.0f64..2.0), 3..24),
        shift in prop::array::uniform3(-3.0f64..3.0),
        snap in any::<bool>(),
    ) {
        // Coordinates on a coarse grid half of the time: coplanar, shared
        // and collinear corners (flat triangles) become common.
        let grid = |v: Vec<[f64; 3]>| if snap { v.into_iter().map(|p| p.map(|x| (x * 2.0).round() / 2.0)).collect() } else { v };
        let (ma, mb) = (soup(&grid(a)), soup(&grid(b)));
        let pb = at(shift[0].round(), shift[1].round(), shift[2].round());
        let got = surfaces_touch(&ma, Pose::IDENTITY, &mb, pb).unwrap();
        prop_assert_eq!(got, brute(&ma, Pose::IDENTITY, &mb, pb));
        if got {
            // No pair may be clearly apart on every pair: some pair touches,
            // so not all are separated.
            let all_apart = ma.faces.iter().all(|fa| mb.faces.iter().all(|fb| {
                let t = [0, 1, 2].map(|k| DVec3::from(ma.vertices[fa[k]]));
                let u = [0, 1, 2].map(|k| pb.apply(DVec3::from(mb.vertices[fb[k]])));
                clearly_apart(t, u, 1e-9)
            }));
            prop_assert!(!all_apart);
        }
    }
}
