//! Oracle tests for the conversions of `dymsum::interop` (features `parry`,
//! `mint`, `nalgebra`; run by CI as
//! `cargo test --release -p dymsum --features parry,mint,nalgebra --test interop`).
//!
//! * **Conventions**: a quarter turn about `+z` takes `+x` to `+y` in every
//!   crate, built on either side; a generic rotation acts on a vector the
//!   same in every crate (catches swapped or reordered components).
//! * **Round trips**: `Rotation`/`Pose → other → Rotation`/`Pose` is the
//!   identity bit for bit (quaternion forms) or within `1e-12` rad (matrix
//!   forms); `other → ours → other` is the same rotation.
//! * **Shapes**: `Polytope → ConvexPolyhedron` keeps the vertices bit for bit
//!   and parry's volume equals ours; `→ Polytope` again gives the same
//!   vertex set and the same faces; parry's own hulls convert to the exact
//!   hull of their points; parry's face merging (pinned case) is seen by
//!   `to_polytope` and not by `TryFrom`.
//! * **Errors**: zero / non-finite quaternions, non-rotation matrices,
//!   non-rigid 4×4 matrices, non-finite translations, shapes parry's float
//!   normals cannot represent, flat and dented parry meshes.
#![cfg(all(feature = "parry", feature = "mint", feature = "nalgebra"))]

use dymsum::glam::{DMat3, DMat4, DQuat};
use dymsum::interop::parry::{to_polygon_mesh, to_polytope};
use dymsum::interop::InteropError;
use dymsum::polytope::MeshPolicy;
use dymsum::{DVec3, Polytope, PolytopeError, Pose, Rotation};
use dymsum_testkit::{proptest_cases, random_polytope, random_rotation, rng, Kind};
use nalgebra::{Isometry3, Point3, Quaternion, Rotation3, UnitQuaternion, Vector3};
use parry3d_f64::math::Pose as ParryPose;
use parry3d_f64::shape::{ConvexPolyhedron, Shape};
use proptest::prelude::*;
use rand::Rng;
use std::collections::BTreeSet;
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2};

// ---------------------------------------------------------------- helpers

/// The rotation of every representation, applied to `v`.
fn actions(r: Rotation, v: DVec3) -> [(&'static str, DVec3); 7] {
    let q = DQuat::from(r);
    let parry = ParryPose::from(Pose::new(r, DVec3::ZERO));
    let na_q = UnitQuaternion::from(r);
    let na_m = Rotation3::from(r);
    let mint_q = mint::Quaternion::from(r);
    let mint_m = mint::ColumnMatrix3::from(r);
    let nv = Vector3::new(v.x, v.y, v.z);
    let na = |w: Vector3<f64>| DVec3::new(w.x, w.y, w.z);
    [
        ("glam DQuat", q * v),
        ("glam DMat3", DMat3::from(r) * v),
        ("parry Pose", parry.transform_vector(v)),
        ("nalgebra UnitQuaternion", na(na_q * nv)),
        ("nalgebra Rotation3", na(na_m * nv)),
        // mint stores; act through glam (the feature's conversions).
        ("mint Quaternion", DQuat::from(mint_q) * v),
        ("mint ColumnMatrix3", DMat3::from(mint_m) * v),
    ]
}

fn bits(v: DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}

fn vertex_set(p: &Polytope) -> BTreeSet<[u64; 3]> {
    p.vertices().iter().map(|&v| bits(v)).collect()
}

/// Faces as sets of vertex coordinates (bit patterns), each rotated to start
/// at its smallest vertex (so orientation is compared too).
fn face_set(p: &Polytope) -> BTreeSet<Vec<[u64; 3]>> {
    p.faces()
        .map(|f| {
            let mut c: Vec<[u64; 3]> = f.iter().map(|&i| bits(p.vertex(i as usize))).collect();
            let k = (0..c.len()).min_by_key(|&k| c[k]).unwrap();
            c.rotate_left(k);
            c
        })
        .collect()
}

fn assert_same_polytope(a: &Polytope, b: &Polytope, ctx: &str) {
    assert_eq!(vertex_set(a), vertex_set(b), "{ctx}: vertex sets differ");
    assert_eq!(face_set(a), face_set(b), "{ctx}: faces differ");
}

/// The bits of the quaternion a `BadQuaternion` error names, `None` for any
/// other outcome.
fn quat_err<T>(r: Result<T, InteropError>) -> Option<[u64; 4]> {
    match r {
        Err(InteropError::BadQuaternion { xyzw }) => Some(xyzw.map(f64::to_bits)),
        _ => None,
    }
}

fn cube(s: f64) -> Polytope {
    Polytope::from_points(&dymsum_testkit::cube_points(-s, s)).unwrap()
}

// ---------------------------------------------------------------- conventions

#[test]
fn quarter_turn_about_z_takes_x_to_y_in_every_crate() {
    let r = Rotation::from_axis_angle(DVec3::Z, FRAC_PI_2).unwrap();
    assert_eq!(r.apply(DVec3::X), DVec3::Y);
    for (name, got) in actions(r, DVec3::X) {
        assert!((got - DVec3::Y).length() < 1e-15, "{name}: +x -> {got}");
    }
    // Component order, by name, in each crate.
    // (w, x, y, z) = (h, 0, 0, h) up to the last bit of h.
    let h = FRAC_1_SQRT_2;
    let wxyz = |w: f64, x: f64, y: f64, z: f64| {
        (w - h).abs() < 1e-15 && x == 0.0 && y == 0.0 && (z - h).abs() < 1e-15
    };
    let [x, y, z, w] = DQuat::from(r).to_array();
    assert!(wxyz(w, x, y, z), "glam {:?}", DQuat::from(r));
    let nq = UnitQuaternion::from(r);
    assert!(wxyz(nq.w, nq.i, nq.j, nq.k), "nalgebra {nq:?}");
    let mq = mint::Quaternion::from(r);
    assert!(wxyz(mq.s, mq.v.x, mq.v.y, mq.v.z), "mint {mq:?}");
    let pq = ParryPose::from(Pose::new(r, DVec3::ZERO)).rotation;
    assert!(wxyz(pq.w, pq.x, pq.y, pq.z), "parry {pq:?}");

    // The same turn built in each crate gives ours, exactly (snapped).
    let built: [(&str, Result<Rotation, InteropError>); 7] = [
        (
            "glam",
            Rotation::try_from(DQuat::from_rotation_z(FRAC_PI_2)),
        ),
        (
            "glam DMat3",
            Rotation::try_from(DMat3::from_rotation_z(FRAC_PI_2)),
        ),
        (
            "parry",
            Pose::try_from(ParryPose::rotation(DVec3::new(0.0, 0.0, FRAC_PI_2)))
                .map(|p| p.rotation),
        ),
        (
            "nalgebra UnitQuaternion",
            Rotation::try_from(UnitQuaternion::from_axis_angle(
                &Vector3::z_axis(),
                FRAC_PI_2,
            )),
        ),
        (
            "nalgebra Rotation3",
            Rotation::try_from(Rotation3::from_axis_angle(&Vector3::z_axis(), FRAC_PI_2)),
        ),
        (
            "mint Quaternion",
            Rotation::try_from(mint::Quaternion {
                v: mint::Vector3 {
                    x: 0.0,
                    y: 0.0,
                    z: h,
                },
                s: h,
            }),
        ),
        (
            "mint ColumnMatrix3",
            Rotation::try_from(mint::ColumnMatrix3 {
                x: mint::Vector3 {
                    x: 0.0,
                    y: 1.0,
                    z: 0.0,
                },
                y: mint::Vector3 {
                    x: -1.0,
                    y: 0.0,
                    z: 0.0,
                },
                z: mint::Vector3 {
                    x: 0.0,
                    y: 0.0,
                    z: 1.0,
                },
            }),
        ),
    ];
    for (name, b) in built {
        let b = b.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(b.apply(DVec3::X), DVec3::Y, "{name}");
        assert_eq!(b.apply(DVec3::Y), -DVec3::X, "{name}");
        assert_eq!(b.apply(DVec3::Z), DVec3::Z, "{name}");
    }
}

#[test]
fn generic_rotation_acts_the_same_in_every_crate() {
    // Axis (1, 2, 3), 0.7 rad: every component non-zero and distinct, so a
    // swapped or reordered component changes the image.
    let r = Rotation::from_axis_angle(DVec3::new(1.0, 2.0, 3.0), 0.7).unwrap();
    let v = DVec3::new(0.3, -1.1, 2.0);
    let ours = r.apply(v);
    for (name, got) in actions(r, v) {
        assert!(
            (got - ours).length() < 1e-14,
            "{name}: {got} vs ours {ours}"
        );
    }
    // And a pose: rotation first, then translation, in every crate.
    let pose = Pose::new(r, DVec3::new(5.0, -7.0, 0.25));
    let want = pose.apply(v);
    let parry = ParryPose::from(pose).transform_point(v);
    let iso = Isometry3::from(pose) * Point3::new(v.x, v.y, v.z);
    let mat = DMat4::from(pose).transform_point3(v);
    let mint_m: mint::ColumnMatrix4<f64> = pose.into();
    let mint_p = DMat4::from(mint_m).transform_point3(v);
    for (name, got) in [
        ("parry", parry),
        ("nalgebra", DVec3::new(iso.x, iso.y, iso.z)),
        ("glam DMat4", mat),
        ("mint ColumnMatrix4", mint_p),
    ] {
        assert!((got - want).length() < 1e-14, "{name}: {got} vs {want}");
    }
}

// ---------------------------------------------------------------- round trips

fn arb_rotation() -> impl Strategy<Value = Rotation> {
    any::<u64>().prop_map(|s| random_rotation(&mut rng(s)))
}

fn arb_pose() -> impl Strategy<Value = Pose> {
    (arb_rotation(), prop::array::uniform3(-1e3..1e3f64))
        .prop_map(|(r, t)| Pose::new(r, DVec3::from(t)))
}

proptest! {
    // Failures are pinned as named tests with literal values, not files.
    #![proptest_config(ProptestConfig {
        cases: proptest_cases(256),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn rotations_round_trip(r in arb_rotation(), v in prop::array::uniform3(-10.0..10.0f64)) {
        let v = DVec3::from(v);
        // Quaternion forms: bit for bit.
        prop_assert_eq!(Rotation::try_from(DQuat::from(r)).unwrap(), r);
        prop_assert_eq!(Rotation::try_from(UnitQuaternion::from(r)).unwrap(), r);
        prop_assert_eq!(Rotation::try_from(mint::Quaternion::from(r)).unwrap(), r);
        // Matrix forms: the same rotation up to the matrix-to-quaternion
        // rounding.
        let m = Rotation::try_from(DMat3::from(r)).unwrap();
        prop_assert!(m.angle_to(&r) < 1e-12, "glam DMat3: {}", m.angle_to(&r));
        let m = Rotation::try_from(Rotation3::from(r)).unwrap();
        prop_assert!(m.angle_to(&r) < 1e-12, "nalgebra Rotation3: {}", m.angle_to(&r));
        let m = Rotation::try_from(mint::ColumnMatrix3::from(r)).unwrap();
        prop_assert!(m.angle_to(&r) < 1e-12, "mint ColumnMatrix3: {}", m.angle_to(&r));
        // Every representation acts as ours.
        let scale = 1e-14 * v.length().max(1.0);
        for (name, got) in actions(r, v) {
            prop_assert!((got - r.apply(v)).length() <= scale, "{}: {} vs {}", name, got, r.apply(v));
        }
    }

    #[test]
    fn foreign_rotations_round_trip(s in any::<u64>()) {
        // other -> ours -> other: the same rotation (q or -q).
        let mut g = rng(s);
        let axis = Vector3::new(g.random_range(-1.0..1.0), g.random_range(-1.0..1.0), g.random_range(-1.0..1.0));
        prop_assume!(axis.norm() > 1e-3);
        let na = UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(axis), g.random_range(-7.0..7.0));
        let back = UnitQuaternion::from(Rotation::try_from(na).unwrap());
        prop_assert!(back.angle_to(&na) < 1e-12, "nalgebra: {}", back.angle_to(&na));
        let gq = DQuat::from_xyzw(na.i, na.j, na.k, na.w);
        let back = DQuat::from(Rotation::try_from(gq).unwrap());
        prop_assert!(back.angle_between(gq) < 1e-7, "glam: {}", back.angle_between(gq));
        prop_assert!(back.dot(gq).abs() > 1.0 - 1e-15);
    }

    #[test]
    fn poses_round_trip(pose in arb_pose()) {
        prop_assert_eq!(Pose::try_from(ParryPose::from(pose)).unwrap(), pose);
        prop_assert_eq!(Pose::try_from(Isometry3::from(pose)).unwrap(), pose);
        for (name, back) in [
            ("glam DMat4", Pose::try_from(DMat4::from(pose)).unwrap()),
            ("mint ColumnMatrix4", Pose::try_from(mint::ColumnMatrix4::from(pose)).unwrap()),
        ] {
            prop_assert_eq!(back.translation, pose.translation, "{}", name);
            prop_assert!(back.rotation.angle_to(&pose.rotation) < 1e-12, "{}", name);
        }
    }
}

// ---------------------------------------------------------------- shapes

/// Polytope → parry → Polytope, with parry's volume and faces checked.
/// Returns whether parry merged faces.
fn check_shape_round_trip(p: &Polytope, ctx: &str) -> bool {
    let shape = ConvexPolyhedron::try_from(p).unwrap_or_else(|e| panic!("{ctx}: {e}"));
    // Vertices bit for bit, in order.
    assert_eq!(shape.points(), p.vertices(), "{ctx}: points");
    // parry's faces are unions of ours (it merges, never splits or invents):
    // no more of them, every normal a unit vector, every face's vertices in
    // one closed half-space of that normal within rounding.
    let merged = shape.faces().len() < p.face_count();
    assert!(
        shape.faces().len() <= p.face_count(),
        "{ctx}: parry has more faces"
    );
    // parry's volume (its mass at density 1, from its faces) is ours; when
    // it merged nearly coplanar faces, its faces skip the vertices inside
    // them and its volume is a little smaller.
    let (ours, theirs) = (p.volume(), shape.mass_properties(1.0).mass());
    let tol = if merged { 1e-6 } else { 1e-12 };
    assert!(
        (ours - theirs).abs() <= tol * ours && theirs <= ours * (1.0 + 1e-12),
        "{ctx}: volume {ours} vs parry's {theirs} (merged: {merged})"
    );
    let diam = p.diameter();
    for (k, f) in shape.faces().iter().enumerate() {
        assert!(
            (f.normal.length() - 1.0).abs() < 1e-12,
            "{ctx}: face {k} normal"
        );
        let anchor =
            shape.points()[shape.vertices_adj_to_face()[f.first_vertex_or_edge as usize] as usize];
        for &q in shape.points() {
            assert!(
                (q - anchor).dot(f.normal) <= 1e-9 * diam,
                "{ctx}: parry face {k} is not supporting"
            );
        }
    }
    // Back: the same polytope, exactly.
    let back = Polytope::try_from(&shape).unwrap_or_else(|e| panic!("{ctx}: back: {e}"));
    assert_same_polytope(p, &back, ctx);
    assert_eq!(
        back.volume(),
        p.volume(),
        "{ctx}: volume after the round trip"
    );
    merged
}

#[test]
fn shapes_round_trip_through_parry() {
    let (mut tried, mut merged) = (0, 0);
    for (kind, n) in [
        (Kind::Ball, 8),
        (Kind::Ball, 60),
        (Kind::Grid, 30),
        (Kind::Coplanar, 40),
        (Kind::Sphere, 200),
    ] {
        let mut g = rng(0x1f0 + n as u64);
        for i in 0..20 {
            let p = random_polytope(kind, n, &mut g);
            merged += check_shape_round_trip(&p, &format!("{kind:?} n={n} #{i}")) as usize;
            tried += 1;
        }
    }
    assert_eq!(tried, 100);
    println!("{tried} random polytopes, parry merged faces of {merged}");
    check_shape_round_trip(&cube(1.0), "unit cube");
    // Any overall scale parry's float normals can represent.
    check_shape_round_trip(&cube(1e-60), "cube 1e-60");
    check_shape_round_trip(&cube(1e60), "cube 1e60");
}

#[test]
fn parry_hulls_convert_to_the_exact_hull_of_their_points() {
    let mut g = rng(77);
    let mut checked = 0;
    for kind in [Kind::Ball, Kind::Grid, Kind::Coplanar, Kind::Sphere] {
        for i in 0..10 {
            let pts = dymsum_testkit::points(kind, 50, &mut g);
            let Some(shape) = ConvexPolyhedron::from_convex_hull(&pts) else {
                continue;
            };
            let ctx = format!("{kind:?} #{i}");
            let ours = Polytope::try_from(&shape).unwrap();
            assert_same_polytope(&ours, &Polytope::from_dvec3s(shape.points()).unwrap(), &ctx);
            // Through parry's faces: the same shape, faces outward.
            let (via_mesh, report) = to_polytope(&shape, MeshPolicy::default()).unwrap();
            assert!(!report.inward_oriented, "{ctx}: parry's faces inward");
            assert_same_polytope(&ours, &via_mesh, &ctx);
            let (ov, pv) = (ours.volume(), shape.mass_properties(1.0).mass());
            assert!((ov - pv).abs() <= 1e-12 * ov, "{ctx}: {ov} vs {pv}");
            checked += 1;
        }
    }
    // parry's own hull may fail on a draw; not on most.
    assert!(checked >= 36, "only {checked} of 40 parry hulls built");
    println!("{checked} of 40 parry hulls checked");
}

/// A box whose top face has its centre lifted by `1e-7`: four exactly
/// non-coplanar top triangles for us, one merged face for parry (normals
/// within its `1 − √ε` test), on which the centre lies on no face.
#[test]
fn parry_face_merging_is_seen_by_to_polytope_not_by_try_from() {
    let mut pts = dymsum_testkit::box_points(1.0, 1.0, 1.0);
    pts.push([0.0, 0.0, 1.0 + 1e-7]);
    let p = Polytope::from_points(&pts).unwrap();
    assert_eq!((p.vertex_count(), p.face_count()), (9, 9));
    let shape = ConvexPolyhedron::try_from(&p).unwrap();
    assert_eq!(shape.faces().len(), 6, "parry merges the lifted top");
    let used: BTreeSet<usize> = to_polygon_mesh(&shape).faces.concat().into_iter().collect();
    assert_eq!(used.len(), 8, "the lifted centre is on no parry face");
    // TryFrom: the exact hull of all points, the shape parry's support
    // map sees: the centre is kept.
    assert_same_polytope(&Polytope::try_from(&shape).unwrap(), &p, "try_from");
    // to_polytope: parry's faces as a mesh; exactly a box.
    let (boxed, report) = to_polytope(&shape, MeshPolicy::strict()).unwrap();
    assert!(report.exactly_convex);
    assert_eq!((boxed.vertex_count(), boxed.face_count()), (8, 6));
}

// ---------------------------------------------------------------- errors

#[test]
fn bad_quaternions_are_refused() {
    for xyzw in [
        [0.0; 4],
        [f64::NAN, 0.0, 0.0, 1.0],
        [0.0, f64::INFINITY, 0.0, 1.0],
    ] {
        // The error names the quaternion, scalar last (bits: NaN != NaN).
        let want = Some(xyzw.map(f64::to_bits));
        let [x, y, z, w] = xyzw;
        let nq = Quaternion::new(w, x, y, z);
        let nu = UnitQuaternion::new_unchecked(nq);
        let got = [
            (
                "glam",
                quat_err(Rotation::try_from(DQuat::from_array(xyzw))),
            ),
            (
                "mint",
                quat_err(Rotation::try_from(mint::Quaternion::from(xyzw))),
            ),
            ("nalgebra Quaternion", quat_err(Rotation::try_from(nq))),
            ("nalgebra UnitQuaternion", quat_err(Rotation::try_from(nu))),
            (
                "parry Pose",
                quat_err(Pose::try_from(ParryPose::from_parts(
                    DVec3::ZERO,
                    DQuat::from_array(xyzw),
                ))),
            ),
            (
                "nalgebra Isometry3",
                quat_err(Pose::try_from(Isometry3::from_parts(
                    Vector3::zeros().into(),
                    nu,
                ))),
            ),
        ];
        for (name, got) in got {
            assert_eq!(got, want, "{name}: {xyzw:?}");
        }
    }
    // nalgebra's normalisation of zero gives NaN, refused.
    let nan = UnitQuaternion::new_normalize(Quaternion::new(0.0, 0.0, 0.0, 0.0));
    assert!(matches!(
        Rotation::try_from(nan),
        Err(InteropError::BadQuaternion { .. })
    ));
}

#[test]
fn finite_non_unit_quaternions_are_normalised() {
    let turn = Rotation::from_axis_angle(DVec3::Z, FRAC_PI_2).unwrap();
    for s in [2.0, 1e-300, 1e300, 5e-324] {
        let a = Rotation::try_from(DQuat::from_xyzw(0.0, 0.0, s, s)).unwrap();
        let b = Rotation::try_from(mint::Quaternion::from([0.0, 0.0, -s, -s])).unwrap();
        for (name, r) in [("glam", a), ("mint, negated", b)] {
            assert_eq!(r.matrix(), turn.matrix(), "{name}, scale {s:e}");
            assert!(r.angle_to(&turn) < 1e-15, "{name}, scale {s:e}");
            assert!(r.quat().is_normalized());
        }
    }
}

#[test]
fn non_rotation_matrices_and_non_rigid_transforms_are_refused() {
    let r = Rotation::from_axis_angle(DVec3::new(1.0, 1.0, 0.0), 0.4).unwrap();
    let scaled = r.matrix() * 1.01;
    let reflected = r.matrix() * DMat3::from_diagonal(DVec3::new(1.0, 1.0, -1.0));
    for m in [
        scaled,
        reflected,
        DMat3::ZERO,
        DMat3::from_diagonal(DVec3::splat(f64::NAN)),
    ] {
        // The error names the matrix (bits: NaN != NaN).
        let want = Some(m.to_cols_array().map(f64::to_bits));
        let matrix_err = |r: Result<Rotation, InteropError>| match r {
            Err(InteropError::NotRotation { columns }) => Some(
                DMat3::from_cols_array_2d(&columns)
                    .to_cols_array()
                    .map(f64::to_bits),
            ),
            _ => None,
        };
        assert_eq!(
            matrix_err(Rotation::try_from(mint::ColumnMatrix3::from(m))),
            want
        );
        let na = Rotation3::from_matrix_unchecked(nalgebra::Matrix3::from(m));
        assert_eq!(matrix_err(Rotation::try_from(na)), want);
        assert_eq!(matrix_err(Rotation::try_from(m)), want);
    }
    let good = Pose::new(r, DVec3::new(1.0, 2.0, 3.0)).to_mat4();
    let mut projective = good;
    projective.x_axis.w = 1e-3;
    let mut scaled = good;
    scaled.y_axis *= 2.0;
    let mut nan = good;
    nan.w_axis.y = f64::NAN;
    for m in [projective, scaled, nan] {
        let want = InteropError::NotRigid {
            columns: Box::new(m.to_cols_array_2d()),
        };
        // (NaN != NaN: compare the variant, then the bits.)
        for got in [
            Pose::try_from(m).unwrap_err(),
            Pose::try_from(mint::ColumnMatrix4::from(m)).unwrap_err(),
        ] {
            let (InteropError::NotRigid { columns: a }, InteropError::NotRigid { columns: b }) =
                (&got, &want)
            else {
                panic!("{got:?}")
            };
            let flat =
                |c: &[[f64; 4]; 4]| c.concat().iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(flat(a), flat(b));
        }
    }
}

#[test]
fn non_finite_translations_are_refused() {
    for t in [
        DVec3::new(f64::NAN, 0.0, 0.0),
        DVec3::new(0.0, 0.0, f64::NEG_INFINITY),
    ] {
        let pp = ParryPose::from_parts(t, DQuat::IDENTITY);
        let got = Pose::try_from(pp).unwrap_err();
        assert!(
            matches!(got, InteropError::NonFiniteTranslation { translation } if bits(DVec3::from(translation)) == bits(t)),
            "{got:?}"
        );
        let iso = Isometry3::from_parts(
            nalgebra::Translation3::new(t.x, t.y, t.z),
            UnitQuaternion::identity(),
        );
        assert!(matches!(
            Pose::try_from(iso),
            Err(InteropError::NonFiniteTranslation { .. })
        ));
    }
}

#[test]
fn shapes_beyond_parrys_float_range_are_refused() {
    // dymsum handles any overall scale (power-of-two frame); parry squares
    // cross products of coordinate differences, which underflow (cube of
    // half-size 1e-80: normals ~4e-160, squared 0) or overflow (1e80).
    for s in [1e-80, 1e-200, 1e80, 1e200] {
        let p = cube(s);
        assert_eq!(p.face_count(), 6);
        let err = ConvexPolyhedron::try_from(&p).unwrap_err();
        let InteropError::ParryOutOfRange { triangle } = err else {
            panic!("scale {s:e}: {err:?}")
        };
        // The first triangle of the first face.
        let f0 = p.face(0);
        assert_eq!(triangle, [f0[0], f0[1], f0[2]], "scale {s:e}");
    }
    // Mixed scales: the unit corner tetrahedron plus a point 1e-160 from
    // its corner at the origin, outside it (y < 0): the edge between the
    // two has a subnormal squared length.
    let e = 1e-160;
    let p = Polytope::from_points(&[
        [0.0, 0.0, 0.0],
        [e, -e, -e],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ])
    .unwrap();
    assert_eq!(p.vertex_count(), 5);
    let err = ConvexPolyhedron::try_from(&p).unwrap_err();
    assert!(
        matches!(err, InteropError::ParryOutOfRange { .. }),
        "{err:?}"
    );
    // Within range: accepted (and round trips, see shapes_round_trip_through_parry).
    for s in [1e-60, 1e60] {
        assert!(ConvexPolyhedron::try_from(&cube(s)).is_ok(), "scale {s:e}");
    }
}

#[test]
fn flat_and_dented_parry_meshes_are_refused() {
    // A double-sided triangle and a double-sided square: parry accepts both.
    let tri = ConvexPolyhedron::from_convex_mesh(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y],
        &[[0, 1, 2], [0, 2, 1]],
    )
    .unwrap();
    assert_eq!(
        Polytope::try_from(&tri).unwrap_err(),
        PolytopeError::TooFewPoints { count: 3 }
    );
    let square = ConvexPolyhedron::from_convex_mesh(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
        // Top diagonal 0-2, bottom diagonal 1-3 (parry refuses an edge in
        // more than two triangles).
        &[[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]],
    )
    .unwrap();
    assert!(matches!(
        Polytope::try_from(&square),
        Err(PolytopeError::Flat(_))
    ));
    assert!(matches!(
        to_polytope(&square, MeshPolicy::default()),
        Err(PolytopeError::Flat(_))
    ));
    // An octahedron with its top vertex pushed inside: parry does not check
    // convexity; our mesh validation does. (TryFrom takes the hull of the
    // points, which is convex by construction: the pushed vertex is dropped.)
    let pts = vec![
        DVec3::X,
        DVec3::Y,
        -DVec3::X,
        -DVec3::Y,
        DVec3::new(0.0, 0.0, -0.5), // top, pushed below the equator
        -DVec3::Z,
    ];
    let tris = [
        [0, 1, 4],
        [1, 2, 4],
        [2, 3, 4],
        [3, 0, 4],
        [1, 0, 5],
        [2, 1, 5],
        [3, 2, 5],
        [0, 3, 5],
    ];
    let dented = ConvexPolyhedron::from_convex_mesh(pts, &tris).unwrap();
    let err = to_polytope(&dented, MeshPolicy::default()).unwrap_err();
    assert!(matches!(err, PolytopeError::NonConvex { .. }), "{err:?}");
    let hull = Polytope::try_from(&dented).unwrap();
    assert_eq!(hull.vertex_count(), 5);
}
