//! Issue 22 §1: C-obstacle slices as half-spaces straight from the facets
//! of the dynamic sum (`CObstacle::halfspace_slices`), no mesh.
//!
//! Oracle: the slice's mesh (`CObstacle::slices`, checked without
//! tolerance). Every mesh vertex satisfies every half-space, in floats with
//! the offsets as computed (no test tolerance), and in double-double
//! arithmetic; every plane touches the mesh (its offset within a few units
//! of rounding of the largest `n·x`). Families: random bodies of every
//! kind (coplanar clusters and grids: merged coplanar facets), shifted far
//! from the origin, scaled by `2^±200`; exact cases (boxes at quarter
//! turns) give exactly the mesh's faces.

use dymsum::query::{orientations_about_axis, HalfSpaces};
use dymsum::{CObstacle, DVec3, PolygonMesh, Polytope, Rotation};
use dymsum_testkit::oracle::random_axis;
use dymsum_testkit::*;
use proptest::prelude::*;
use std::f64::consts::FRAC_PI_2;

fn scaled(p: &Polytope, s: f64, shift: DVec3) -> Polytope {
    let v: Vec<DVec3> = p.vertices().iter().map(|&v| v * s + shift).collect();
    Polytope::from_dvec3s(&v).unwrap()
}

/// `a·b` summed in double-double: the products exactly (`mul_add`), the
/// sums by TwoSum; returns (hi, lo) with `hi + lo` within `2⁻¹⁰⁰|a||b|`.
fn dd_dot(a: DVec3, b: DVec3) -> (f64, f64) {
    let (mut hi, mut lo) = (0.0f64, 0.0f64);
    for k in 0..3 {
        let p = a[k] * b[k];
        let e = a[k].mul_add(b[k], -p);
        let s = hi + p;
        let bb = s - hi;
        let err = (hi - (s - bb)) + (p - bb);
        hi = s;
        lo += err + e;
    }
    (hi, lo)
}

/// Checks `h` against the slice's mesh (module docs).
fn check(h: &HalfSpaces, mesh: &PolygonMesh, what: &str) {
    assert!(!h.is_empty(), "{what}: no half-spaces");
    assert_eq!(h.normals().len(), h.offsets().len());
    let scale = mesh
        .vertices
        .iter()
        .fold(0.0f64, |m, v| m.max(DVec3::from(*v).abs().max_element()));
    for (i, (n, &d)) in h.normals().iter().zip(h.offsets()).enumerate() {
        assert!(
            (n.length() - 1.0).abs() < 1e-12,
            "{what}: normal {i} is not a unit vector: {n:?}"
        );
        let mut top = f64::NEG_INFINITY;
        for v in &mesh.vertices {
            let x = DVec3::from(*v);
            let f = n.dot(x);
            assert!(
                f <= d,
                "{what}: vertex {x:?} outside plane {i} ({n:?}, {d:e}) by {:e}",
                f - d
            );
            let (hi, lo) = dd_dot(*n, x);
            assert!(
                (hi - d) + lo <= 0.0,
                "{what}: vertex {x:?} outside plane {i} in double-double"
            );
            top = top.max(f);
        }
        assert!(
            d - top <= 64.0 * f64::EPSILON * scale.max(f64::MIN_POSITIVE),
            "{what}: plane {i} does not touch the slice: offset {d:e}, max {top:e} \
             (gap {:e}, scale {scale:e})",
            d - top
        );
    }
}

fn check_all(cobst: &CObstacle, turns: &[Rotation], what: &str) {
    let planes = cobst.halfspace_slices(turns).unwrap();
    assert_eq!(planes.len(), turns.len());
    for (k, (slice, h)) in cobst.slices(turns).zip(&planes).enumerate() {
        let mesh = slice.unwrap();
        check(h, &mesh, &format!("{what}, slice {k}"));
        assert_eq!(
            *h,
            cobst.halfspace_slice(turns[k]).unwrap(),
            "{what}, slice {k}: from scratch"
        );
    }
    assert_eq!(
        cobst.halfspace_slices_par(turns).unwrap(),
        planes,
        "{what}: parallel"
    );
}

#[test]
fn boxes_at_quarter_turns_give_exactly_the_faces() {
    let a = Polytope::from_points(&box_points(1.0, 2.0, 3.0)).unwrap();
    let b = Polytope::from_points(&box_points(5.0, 1.0, 2.0)).unwrap();
    let cobst = CObstacle::new(&a, &b).unwrap();
    let turns: Vec<Rotation> = (0..4)
        .map(|k| Rotation::from_axis_angle(DVec3::Z, FRAC_PI_2 * k as f64).unwrap())
        .collect();
    check_all(&cobst, &turns, "box ⊕ box");
    for h in cobst.halfspace_slices(&turns).unwrap() {
        // A box: six planes, the axis directions, merged from coplanar
        // fv, vf and ee facets.
        assert_eq!(h.len(), 6, "{h:?}");
        for n in h.normals() {
            assert_eq!(n.abs().max_element(), 1.0, "{n:?}");
        }
    }
}

#[test]
fn the_doc_pair_turns_about_an_oblique_axis() {
    let tet =
        Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]]).unwrap();
    let block = Polytope::from_points(&box_points(2.0, 1.0, 1.0)).unwrap();
    let cobst = CObstacle::new(&tet, &block).unwrap();
    let turns = orientations_about_axis(DVec3::new(1.0, 2.0, 3.0), 64).unwrap();
    check_all(&cobst, &turns, "tet ⊕ block");
}

#[test]
fn grids_far_away_and_at_extreme_scales() {
    let mut r = rng(22);
    let a = random_polytope(Kind::Grid, 30, &mut r);
    let b = random_polytope(Kind::Coplanar, 40, &mut r);
    for (s, shift) in [
        (1.0, DVec3::ZERO),
        (1.0, DVec3::new(1e6, -3e5, 2e6)),
        (2f64.powi(200), DVec3::ZERO),
        (2f64.powi(-200), DVec3::ZERO),
    ] {
        let cobst = CObstacle::new(&scaled(&a, s, DVec3::ZERO), &scaled(&b, s, shift * s)).unwrap();
        let turns = orientations_about_axis(random_axis(&mut r), 24).unwrap();
        check_all(
            &cobst,
            &turns,
            &format!("grid ⊕ coplanar, scale {s:e}, shift {shift}"),
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn random_bodies_and_turns(seed in any::<u64>(), kinds in (0usize..5, 0usize..5), n in 8usize..40) {
        let kind = |k| [Kind::Ball, Kind::Grid, Kind::Coplanar, Kind::Sphere, Kind::Cube][k];
        let mut r = rng(seed);
        let a = random_polytope(kind(kinds.0), n, &mut r);
        let b = random_polytope(kind(kinds.1), n, &mut r);
        let cobst = CObstacle::new(&a, &b).unwrap();
        let mut turns = orientations_about_axis(random_axis(&mut r), 16).unwrap();
        turns.extend((0..4).map(|_| random_rotation(&mut r)));
        check_all(&cobst, &turns, &format!("seed {seed}, kinds {kinds:?}"));
    }
}
