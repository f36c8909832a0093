//! Any scale (issue 8 §3): scaling every input by a power of two `2^k` is
//! exact in floating point, so it must give exactly the scaled result:
//! identical polytope faces and facet sets for every method and for
//! DYMSUM, vertices, volumes and query answers scaled by exactly `2^k`.
//! Inputs truly beyond the exact predicates (one shape mixing `1e300` and
//! `1e-300`, posed coordinates overflowing `f64`) are refused with typed
//! errors naming the supported range; nothing panics, nothing is called
//! flat, nothing is silently wrong.

use dymsum::polytope::MeshPolicy;
use dymsum::query::{ConvexPair, Proximity, QueryError};
use dymsum::sum::{minkowski_sum_posed, MeshError, Method, SumError};
use dymsum::{DVec3, DynamicSum, PolygonMesh, Polytope, PolytopeError, Pose, Rotation};
use dymsum_testkit::*;
use proptest::prelude::*;

fn pow2(k: i32) -> f64 {
    // 2^k for |k| ≤ 1023 (exact).
    2f64.powi(k)
}

fn scale_pts(p: &[DVec3], k: i32) -> Vec<DVec3> {
    p.iter().map(|v| *v * pow2(k)).collect()
}

fn scale_pose(pose: Pose, k: i32) -> Pose {
    Pose::new(pose.rotation, pose.translation * pow2(k))
}

fn dv(p: &[[f64; 3]]) -> Vec<DVec3> {
    p.iter().map(|v| DVec3::from(*v)).collect()
}

/// The mesh of `P ⊕ Q` for every method at scale `2^k` equals the one at
/// scale 1 with vertices times `2^k` (bit for bit), and the facet sets are
/// identical.
fn check_sums(pa: &[DVec3], pb: &[DVec3], pose: Pose, k: i32) -> Result<(), String> {
    let (p0, q0) = (
        Polytope::from_dvec3s(pa).map_err(|e| e.to_string())?,
        Polytope::from_dvec3s(pb).map_err(|e| e.to_string())?,
    );
    let (p, q) = (
        Polytope::from_dvec3s(&scale_pts(pa, k)).map_err(|e| format!("k={k}: P refused: {e}"))?,
        Polytope::from_dvec3s(&scale_pts(pb, k)).map_err(|e| format!("k={k}: Q refused: {e}"))?,
    );
    let s = pow2(k);
    for (a, b) in [(&p0, &p), (&q0, &q)] {
        if !a.faces().eq(b.faces()) {
            return Err(format!("k={k}: polytope faces differ"));
        }
        if a.vertices()
            .iter()
            .zip(b.vertices())
            .any(|(x, y)| *x * s != *y)
        {
            return Err(format!("k={k}: polytope vertices not scaled exactly"));
        }
        let (v0, v) = (a.volume(), b.volume());
        if v != v0 * pow2(k) * pow2(k) * pow2(k) {
            return Err(format!("k={k}: volume {v:e} is not {v0:e} * 2^(3k)"));
        }
    }
    for m in Method::ALL {
        let base =
            minkowski_sum_posed(&p0, pose, &q0, Pose::IDENTITY, m).map_err(|e| e.to_string())?;
        let sum = minkowski_sum_posed(&p, scale_pose(pose, k), &q, Pose::IDENTITY, m)
            .map_err(|e| format!("k={k} {}: {e}", m.name()))?;
        if sum.facets() != base.facets() {
            return Err(format!("k={k} {}: facet sets differ", m.name()));
        }
        let bm = base.try_to_mesh().map_err(|e| e.to_string())?;
        let sm = sum
            .try_to_mesh()
            .map_err(|e| format!("k={k} {}: mesh: {e}", m.name()))?;
        if sm.faces != bm.faces {
            return Err(format!("k={k} {}: merged faces differ", m.name()));
        }
        let scaled = |v: &[f64; 3]| [v[0] * s, v[1] * s, v[2] * s];
        if sm
            .vertices
            .iter()
            .zip(&bm.vertices)
            .any(|(a, b)| *a != scaled(b))
        {
            return Err(format!(
                "k={k} {}: mesh vertices not scaled exactly",
                m.name()
            ));
        }
        sum.sanity_check()
            .map_err(|e| format!("k={k} {}: {e}", m.name()))?;
    }
    // A few DYMSUM steps, against the unscaled run and a fresh static sum.
    let step = Rotation::from_axis_angle(DVec3::new(1.0, 2.0, 3.0), 0.07).unwrap();
    let mut d0 = DynamicSum::new(&p0, pose, &q0, Pose::IDENTITY).map_err(|e| e.to_string())?;
    let mut d = DynamicSum::new(&p, scale_pose(pose, k), &q, Pose::IDENTITY)
        .map_err(|e| format!("k={k} dynamic: {e}"))?;
    for i in 0..4 {
        d0.rotate_p_by(step);
        if let Some(bug) = d.rotate_p_by(step).recovered {
            return Err(format!("k={k} step {i}: internal inconsistency {bug}"));
        }
        if d.facets() != d0.facets() {
            return Err(format!("k={k} step {i}: dynamic facets differ"));
        }
        let fresh = minkowski_sum_posed(&p, d.pose_p(), &q, d.pose_q(), Method::Walk)
            .map_err(|e| e.to_string())?;
        if fresh.facets() != d.facets() {
            return Err(format!("k={k} step {i}: dynamic differs from static walk"));
        }
    }
    Ok(())
}

/// Depth or distance, points and direction at scale `2^k` equal the ones at
/// scale 1 times `2^k` (direction unchanged).
fn check_query(
    pa: &[DVec3],
    pb: &[DVec3],
    pose_a: Pose,
    pose_b: Pose,
    k: i32,
) -> Result<(), String> {
    let (a0, b0) = (
        Polytope::from_dvec3s(pa).unwrap(),
        Polytope::from_dvec3s(pb).unwrap(),
    );
    let (a, b) = (
        Polytope::from_dvec3s(&scale_pts(pa, k)).unwrap(),
        Polytope::from_dvec3s(&scale_pts(pb, k)).unwrap(),
    );
    let base = ConvexPair::new(&a0, &b0)
        .unwrap()
        .query(pose_a, pose_b)
        .map_err(|e| e.to_string())?;
    let got = ConvexPair::new(&a, &b)
        .unwrap()
        .query(scale_pose(pose_a, k), scale_pose(pose_b, k))
        .map_err(|e| format!("k={k}: {e}"))?;
    let s = pow2(k);
    let ok = match (base, got) {
        (Proximity::Penetrating(x), Proximity::Penetrating(y)) => {
            y.depth == x.depth * s
                && y.normal == x.normal
                && y.point_on_a == x.point_on_a * s
                && y.point_on_b == x.point_on_b * s
                && y.features == x.features
        }
        (Proximity::Separated(x), Proximity::Separated(y)) => {
            y.distance == x.distance * s
                && y.direction == x.direction
                && y.point_on_a == x.point_on_a * s
                && y.point_on_b == x.point_on_b * s
                && y.features == x.features
        }
        _ => false,
    };
    if !ok {
        return Err(format!("k={k}: {got:?} is not {base:?} scaled by 2^{k}"));
    }
    if !(got.depth().is_finite() && got.distance().is_finite()) {
        return Err(format!("k={k}: non-finite answer {got:?}"));
    }
    Ok(())
}

/// Pinned proptest case: the fold of a bent face of the sum computed its
/// float normals in input units, which underflowed at `2^-270` and lost the
/// fold (a different mesh than at scale 1); they are now taken in the
/// scaled frame.
#[test]
fn regression_bent_face_fold_at_tiny_scale() {
    let mut r = rng(901126);
    let kinds = [Kind::Ball, Kind::Grid, Kind::Coplanar, Kind::Sphere];
    let pa = points(kinds[1], 10, &mut r);
    let pb = points(kinds[2], 12, &mut r);
    let pose = Pose::new(random_rotation(&mut r), DVec3::new(0.25, -0.5, 0.125));
    assert_eq!(check_sums(&pa, &pb, pose, -270), Ok(()));
}

fn exponent() -> impl Strategy<Value = i32> {
    prop_oneof![
        -300..=300i32,
        Just(255),
        Just(-255),
        Just(270),
        Just(-270),
        Just(300),
        Just(-300),
        // Beyond 1e±154, where squares of body coordinates underflow or
        // overflow (review finding: the separation's ball radii did).
        Just(600),
        Just(-600),
        Just(900),
        Just(-900),
        Just(1000),
        Just(-1000)
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Random polytopes of every kind, randomly posed, scaled by 2^k.
    #[test]
    fn scaled_polytope_sums_are_exactly_scaled(seed in 0u64..1_000_000, kind in 0usize..4, k in exponent()) {
        let mut r = rng(seed);
        let kinds = [Kind::Ball, Kind::Grid, Kind::Coplanar, Kind::Sphere];
        let pa = points(kinds[kind], 10, &mut r);
        let pb = points(kinds[(kind + 1) % 4], 12, &mut r);
        prop_assume!(Polytope::from_dvec3s(&pa).is_ok() && Polytope::from_dvec3s(&pb).is_ok());
        let pose = Pose::new(random_rotation(&mut r), DVec3::new(0.25, -0.5, 0.125));
        prop_assert_eq!(check_sums(&pa, &pb, pose, k), Ok(()));
    }

    /// Box pairs (exactly parallel faces) about z and about random axes.
    #[test]
    fn scaled_box_sums_are_exactly_scaled(seed in 0u64..1_000_000, k in exponent(), about_z in any::<bool>()) {
        let mut r = rng(seed);
        let pa = dv(&box_points(1.0, 2.0, 0.5));
        let pb = dv(&box_points(0.25, 1.0, 3.0));
        let rot = if about_z {
            Rotation::from_axis_angle(DVec3::Z, 0.3 + seed as f64 * 1e-6).unwrap()
        } else {
            random_rotation(&mut r)
        };
        prop_assert_eq!(check_sums(&pa, &pb, Pose::new(rot, DVec3::new(0.5, 0.0, -0.25)), k), Ok(()));
    }

    /// Distance and penetration depth of box pairs and random polytopes.
    #[test]
    fn scaled_queries_are_exactly_scaled(seed in 0u64..1_000_000, k in exponent(), boxes in any::<bool>(), apart in any::<bool>()) {
        let mut r = rng(seed);
        let (pa, pb) = if boxes {
            (dv(&box_points(1.0, 2.0, 0.5)), dv(&box_points(0.25, 1.0, 3.0)))
        } else {
            (points(Kind::Ball, 12, &mut r), points(Kind::Sphere, 14, &mut r))
        };
        prop_assume!(Polytope::from_dvec3s(&pa).is_ok() && Polytope::from_dvec3s(&pb).is_ok());
        let off = if apart { 3.5 } else { 0.375 };
        let pose_a = Pose::new(random_rotation(&mut r), DVec3::new(off, 0.25, -0.125));
        let pose_b = Pose::new(random_rotation(&mut r), DVec3::new(-0.5, 0.0, 0.0625));
        prop_assert_eq!(check_query(&pa, &pb, pose_a, pose_b, k), Ok(()));
    }
}

/// Unit cube at `1e150` and `1e-110` and `1e300`: once called flat.
#[test]
fn unit_cube_far_scales_load_and_sum() {
    for s in [1e150, 1e-110, 1e300, 1e-300, 1e-8] {
        let c =
            Polytope::from_points(&cube_points(0.0, s)).unwrap_or_else(|e| panic!("{s:e}: {e}"));
        assert_eq!(
            (c.vertex_count(), c.edge_count(), c.face_count()),
            (8, 12, 6),
            "{s:e}"
        );
        c.sanity_check().unwrap();
        for m in Method::ALL {
            let sum = minkowski_sum_posed(&c, Pose::IDENTITY, &c, Pose::IDENTITY, m).unwrap();
            assert_eq!(sum.counts(), (6, 6, 12), "{s:e} {}", m.name());
            let mesh = sum.try_to_mesh().unwrap();
            assert_eq!((mesh.vertices.len(), mesh.faces.len()), (8, 6), "{s:e}");
            let top = mesh
                .vertices
                .iter()
                .flatten()
                .fold(0.0f64, |a, &x| a.max(x));
            assert_eq!(top, 2.0 * s);
        }
    }
}

/// The cube as a quad mesh, scaled and shifted.
fn cube_mesh(size: f64, at: f64) -> PolygonMesh {
    let v = cube_points(0.0, size)
        .iter()
        .map(|p| [p[0] + at, p[1] + at, p[2] + at])
        .collect();
    PolygonMesh::new(v, CUBE_QUADS.iter().map(|q| q.to_vec()).collect())
}

/// A `1e-8` box at `1e6` and a unit box at `1e8` load (mesh and points) and
/// sum with every method.
#[test]
fn small_boxes_far_from_the_origin_load_and_sum() {
    for (size, at) in [(1e-8, 1e6), (1.0, 1e8), (0.01, 1e4), (1e150, 0.0)] {
        let (p, report) = Polytope::from_mesh(&cube_mesh(size, at), MeshPolicy::strict())
            .unwrap_or_else(|e| panic!("{size:e} at {at:e}: {e}"));
        assert!(report.exactly_convex, "{size:e} at {at:e}");
        assert_eq!(p.face_count(), 6);
        for m in Method::ALL {
            let sum = minkowski_sum_posed(&p, Pose::IDENTITY, &p, Pose::IDENTITY, m)
                .unwrap_or_else(|e| panic!("{size:e} at {at:e} {}: {e}", m.name()));
            assert_eq!(sum.counts(), (6, 6, 12));
            assert_eq!(sum.try_to_mesh().unwrap().faces.len(), 6);
        }
    }
}

/// One shape mixing `1e300` and `1e-300` is beyond the exact predicates:
/// a typed error naming the supported range, from points and from a mesh.
#[test]
fn mixed_range_shape_is_refused_with_the_range() {
    let pts = [
        [1e300, 0.0, 0.0],
        [0.0, 1e300, 0.0],
        [0.0, 0.0, 1e-300],
        [0.0, 0.0, 0.0],
    ];
    let e = Polytope::from_points(&pts).unwrap_err();
    assert!(
        matches!(e, PolytopeError::OutOfRange { largest, smallest } if largest == 1e300 && smallest == 1e-300),
        "{e:?}"
    );
    let msg = e.to_string();
    assert!(
        msg.contains("supported range") && msg.contains("960 bits"),
        "{msg}"
    );
    assert!(msg.len() < 400, "{msg}");
    let mesh = PolygonMesh::new(
        pts.to_vec(),
        vec![vec![0, 1, 2], vec![0, 3, 1], vec![1, 3, 2], vec![0, 2, 3]],
    );
    let e = Polytope::from_mesh(&mesh, MeshPolicy::default()).unwrap_err();
    assert!(matches!(e, PolytopeError::OutOfRange { .. }), "{e:?}");
    // Just inside the range: 2^900 and 2^-50 (span 950 bits) is accepted.
    let ok = [
        [pow2(900), 0.0, 0.0],
        [0.0, pow2(900), 0.0],
        [0.0, 0.0, pow2(-50)],
        [0.0, 0.0, 0.0],
    ];
    let t = Polytope::from_points(&ok).unwrap();
    assert_eq!(t.face_count(), 4);
    t.sanity_check().unwrap();
}

/// A pair whose combined range is far beyond `f64` (each shape within
/// range): all methods agree, nothing panics.
#[test]
fn pair_spanning_1e200_to_1e_minus_200_agrees_across_methods() {
    let big = Polytope::from_dvec3s(&scale_pts(&dv(&box_points(1.0, 2.0, 0.5)), 660)).unwrap();
    let small =
        Polytope::from_dvec3s(&scale_pts(&points(Kind::Ball, 12, &mut rng(5)), -660)).unwrap();
    let rot = Rotation::from_axis_angle(DVec3::new(1.0, 2.0, 3.0), 0.4).unwrap();
    for (p, q) in [(&big, &small), (&small, &big)] {
        let sums: Vec<_> = Method::ALL
            .iter()
            .map(|&m| {
                minkowski_sum_posed(p, Pose::new(rot, DVec3::ZERO), q, Pose::IDENTITY, m)
                    .unwrap()
                    .facets()
            })
            .collect();
        assert_eq!(sums[0], sums[1]);
        assert_eq!(sums[0], sums[2]);
        // The tiny shape is below the rounding of the big one's
        // coordinates: the validated mesh is the hull of the rounded
        // vertices (the big box), or a typed precision error.
        let sum = minkowski_sum_posed(
            p,
            Pose::new(rot, DVec3::ZERO),
            q,
            Pose::IDENTITY,
            Method::Walk,
        )
        .unwrap();
        match sum.mesh_with_precision() {
            Ok(m) => assert_eq!(m.mesh.vertices.len(), 8),
            Err(e) => assert!(!e.is_internal(), "{e}"),
        }
        let pair = ConvexPair::new(p, q).unwrap();
        let got = pair
            .query(Pose::new(rot, DVec3::ZERO), Pose::IDENTITY)
            .unwrap();
        assert!(got.depth().is_finite() && got.distance().is_finite());
    }
}

/// Posed coordinates or sums beyond `f64`: typed errors, never NaN.
#[test]
fn overflowing_poses_and_sums_are_typed_errors() {
    let c = Polytope::from_points(&cube_points(0.0, 1.5e308)).unwrap();
    let far = Pose::new(Rotation::IDENTITY, DVec3::new(1e308, 0.0, 0.0));
    for m in Method::ALL {
        let e = minkowski_sum_posed(&c, far, &c, Pose::IDENTITY, m).unwrap_err();
        assert!(
            matches!(e, SumError::OutOfRange { operand: "P", .. }),
            "{e:?}"
        );
        assert!(e.to_string().contains("supported range"));
        // P ⊕ P itself overflows: the facets are right, the mesh is refused.
        let sum = minkowski_sum_posed(&c, Pose::IDENTITY, &c, Pose::IDENTITY, m).unwrap();
        assert_eq!(sum.counts(), (6, 6, 12));
        assert_eq!(sum.try_to_mesh().unwrap_err(), MeshError::OutOfRange);
    }
    let pair = ConvexPair::new(&c, &c).unwrap();
    let e = pair.query(far, Pose::IDENTITY).unwrap_err();
    assert!(
        matches!(
            e,
            QueryError::OutOfRange(_) | QueryError::Sum(SumError::OutOfRange { .. })
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("supported range"), "{e}");
    // A unit cube at 1e308 is finite everywhere: a finite distance.
    let u = Polytope::from_points(&cube_points(0.0, 1.0)).unwrap();
    let pair = ConvexPair::new(&u, &u).unwrap();
    let d = pair.distance(far, Pose::IDENTITY).unwrap();
    assert_eq!(d.distance, 1e308);
}

// Named regressions (all failed before the power-of-two normalisation).

/// Two boxes scaled by 2^340: a box was built as a non-manifold mesh
/// (orient3d overflowed).
#[test]
fn regression_boxes_at_2_pow_340() {
    let pa = dv(&box_points(1.0, 2.0, 0.5));
    let pb = dv(&box_points(0.25, 1.0, 3.0));
    let pose = Pose::new(
        Rotation::from_axis_angle(DVec3::Z, 0.3).unwrap(),
        DVec3::new(0.3, -0.2, 0.1),
    );
    check_sums(&pa, &pb, pose, 340).unwrap();
    check_sums(&pa, &pb, pose, -340).unwrap();
}

/// Box distance at 2^255 and 2^-270: the edge–edge candidates' squared
/// lengths overflowed (2^1020) or underflowed, and were dropped.
#[test]
fn regression_box_queries_at_2_pow_255_and_minus_270() {
    let pa = dv(&box_points(1.0, 2.0, 0.5));
    let pb = dv(&box_points(0.25, 1.0, 3.0));
    let ra = Rotation::from_wxyz(0.8, 0.3, -0.4, 0.3).unwrap();
    let rb = Rotation::from_wxyz(0.6, -0.5, 0.2, 0.6).unwrap();
    for off in [3.5, 0.375] {
        let pose_a = Pose::new(ra, DVec3::new(off, 0.25, -0.125));
        let pose_b = Pose::new(rb, DVec3::new(-0.5, 0.0, 0.0625));
        for k in [255, 270, 300, -255, -270, -300] {
            check_query(&pa, &pb, pose_a, pose_b, k).unwrap();
        }
    }
}

/// Integer grid points at 2^-270: once their hull came out different
/// (orient3d underflowed), so the faces and every sum differed from the
/// unscaled ones.
#[test]
fn regression_grid_hull_at_2_pow_minus_270() {
    let pa = dv(&[
        [
            -0.8528263236817217,
            -0.03889225381640493,
            0.24867243314901044,
        ],
        [
            -0.32847636392942325,
            0.5301972252575622,
            -0.6458215238956053,
        ],
        [-0.81095122994742, 0.4605076889091855, -0.1589809964726956],
        [
            -0.04179373725961533,
            -0.9695465555357314,
            0.01753554883876607,
        ],
        [
            0.28052023095277123,
            -0.5571045389859965,
            0.31594302588169754,
        ],
        [0.37691750972398275, -0.4928800808012159, 0.5450480301847414],
        [-0.4421938344741396, 0.6611673476064825, -0.3459167885638994],
        [
            -0.6294266953114986,
            -0.6366805093336683,
            0.02486843489137014,
        ],
        [
            -0.48773752799413206,
            -0.4379224478712631,
            -0.06523543105853724,
        ],
        [
            -0.5229212749719578,
            0.26290740097766063,
            0.25337814651002066,
        ],
        [
            -0.2745348589755898,
            -0.8244200291657182,
            0.40543821333365093,
        ],
        [
            0.11845808179306028,
            -0.6012507578275548,
            -0.04263136971912784,
        ],
    ]);
    let pb = dv(&[
        [2.0, 2.0, -2.0],
        [0.0, -1.0, -2.0],
        [-2.0, 0.0, 0.0],
        [1.0, -2.0, -2.0],
        [0.0, 2.0, 0.0],
        [-1.0, -1.0, 2.0],
        [2.0, 2.0, 2.0],
        [-2.0, -2.0, -1.0],
        [-2.0, 2.0, 1.0],
        [0.0, 2.0, 0.0],
        [-2.0, 2.0, -2.0],
        [1.0, 2.0, 2.0],
        [2.0, 0.0, 1.0],
        [1.0, 0.0, 2.0],
        [1.0, 2.0, 2.0],
    ]);
    let rot = Rotation::from_wxyz(
        0.5818999106201119,
        0.41284072620215617,
        -0.3085865281419359,
        -0.6290702531979145,
    )
    .unwrap();
    let pose = Pose::new(rot, DVec3::new(0.3, -0.2, 0.1));
    for k in [-270, -300, 270, 300] {
        check_sums(&pa, &pb, pose, k).unwrap();
    }
}
