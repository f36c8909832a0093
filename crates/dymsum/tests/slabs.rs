//! Issue 20 §2: certified C-obstacle slabs (`dymsum::query::Slab`).
//!
//! Oracle: every vertex of every slice sampled inside a slab's range of
//! orientations (computed by DYMSUM, `CObstacle::slices`) satisfies the
//! slab's half-spaces exactly (`Slab::contains`: the offsets as computed,
//! no test tolerance). Meshes pass the exact checker and contain the
//! slab's boundary. Degenerate families: boxes at exact quarter turns,
//! thin plates, far from the origin, scales `2^±300`. The sagitta term is
//! needed: a bar turned by a quarter turn pokes out of the plain hull of
//! its end slices, and not out of the slab.

use dymsum::kernel::predicates::orient;
use dymsum::kernel::Sign;
use dymsum::query::{
    certified_slab_in_cell, certified_slabs_about_axis, certified_slabs_about_axis_par,
    full_turn_angles, rotations_about_axis, Slab, SlabCover, SlabError, ROTATION_SLACK,
};
use dymsum::sum::validate::check_convex_mesh;
use dymsum::{CObstacle, DVec3, PolygonMesh, Polytope, QueryError, Rotation};
use dymsum_testkit::oracle::random_axis;
use dymsum_testkit::*;
use proptest::prelude::*;
use rand::Rng;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

fn boxed(x: f64, y: f64, z: f64) -> Polytope {
    Polytope::from_points(&box_points(x, y, z)).unwrap()
}

fn scaled(p: &Polytope, s: f64, shift: DVec3) -> Polytope {
    let v: Vec<DVec3> = p.vertices().iter().map(|&v| v * s + shift).collect();
    Polytope::from_dvec3s(&v).unwrap()
}

/// `n + 1` angles evenly spaced over `[lo, hi]`, both ends included.
fn dense(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    let mut a: Vec<f64> = (0..=n)
        .map(|j| lo + (hi - lo) * j as f64 / n as f64)
        .collect();
    a.dedup();
    a
}

/// Checks that every vertex of every slice at `samples` lies in `slab`.
fn holds(cobst: &CObstacle, slab: &Slab, samples: &[Rotation], what: &str) {
    for (j, slice) in cobst.slices(samples).enumerate() {
        let slice = slice.unwrap_or_else(|e| panic!("{what}: slice {j}: {e}"));
        for v in &slice.vertices {
            assert!(
                slab.contains(DVec3::from(*v)),
                "{what}: sample {j} ({:?}) has the vertex {v:?} outside the slab (margin {:e})",
                samples[j].wxyz(),
                slab.margin()
            );
        }
    }
}

/// Checks every slab of a turn about `axis` by `angles` against
/// `per_slab + 1` samples across its interval, and its mesh.
fn check_turn(
    robot: &Polytope,
    obstacle: &Polytope,
    axis: DVec3,
    angles: &[f64],
    per_slab: usize,
    what: &str,
) {
    let cobst = CObstacle::new(robot, obstacle).unwrap();
    let slabs = certified_slabs_about_axis(robot, obstacle, axis, angles)
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_eq!(slabs.len(), angles.len() - 1, "{what}");
    for (k, slab) in slabs.iter().enumerate() {
        let samples =
            rotations_about_axis(axis, &dense(angles[k], angles[k + 1], per_slab)).unwrap();
        holds(&cobst, slab, &samples, &format!("{what}: slab {k}"));
        check_mesh(slab, &format!("{what}: slab {k}"));
    }
}

/// `x` strictly outside a convex mesh (an exact `orient` per face).
fn outside(mesh: &PolygonMesh, x: DVec3) -> bool {
    mesh.faces.iter().any(|f| {
        let p = |i: usize| DVec3::from(mesh.vertices[f[i]]);
        orient(p(0), p(1), p(2), x) == Sign::Positive
    })
}

/// The mesh passes the exact checker and holds the slab's boundary: each
/// vertex of the hull pushed out to each plane near it (points of
/// `{N x ≤ d}` on or near its boundary; those the rounding put outside the
/// slab are skipped, decided exactly).
fn check_mesh(slab: &Slab, what: &str) {
    let mesh = slab.mesh().unwrap_or_else(|e| panic!("{what}: mesh: {e}"));
    assert_eq!(check_convex_mesh(&mesh), Ok(()), "{what}");
    let mut tested = 0;
    for v in slab.hull().vertices() {
        for (&n, &d) in slab.normals().iter().zip(slab.offsets()) {
            if (d - n.dot(*v)).abs() <= 1.5 * slab.margin() {
                let x = *v + n * (d - n.dot(*v));
                if slab.contains(x) {
                    tested += 1;
                    assert!(
                        !outside(&mesh, x),
                        "{what}: the mesh cuts {x:?} off the slab"
                    );
                }
            }
        }
    }
    assert!(
        tested >= slab.len(),
        "{what}: only {tested} boundary points tested"
    );
}

/// A point strictly outside `hull` (exact `orient` against its faces).
fn outside_hull(hull: &Polytope, x: DVec3) -> bool {
    hull.faces().any(|f| {
        let p = |i: usize| hull.vertex(f[i] as usize);
        orient(p(0), p(1), p(2), x) == Sign::Positive
    })
}

#[test]
fn a_bar_turned_a_quarter_pokes_out_of_the_plain_hull_not_out_of_the_slab() {
    let bar = boxed(2.0, 0.1, 0.1);
    let block = boxed(0.5, 0.5, 0.5);
    let cobst = CObstacle::new(&bar, &block).unwrap();
    let slabs = certified_slabs_about_axis(&bar, &block, DVec3::Z, &[0.0, FRAC_PI_2]).unwrap();
    let slab = &slabs[0];
    let middle = cobst
        .slice(Rotation::from_axis_angle(DVec3::Z, FRAC_PI_2 / 2.0).unwrap())
        .unwrap();
    let poking: Vec<DVec3> = middle
        .vertices
        .iter()
        .map(|&v| DVec3::from(v))
        .filter(|&v| outside_hull(slab.hull(), v))
        .collect();
    // The plain hull of the end slices misses the middle of the turn (the
    // bar's ends sweep an arc whose sagitta is 2(1 − cos π/8) ≈ 0.15)...
    assert!(
        !poking.is_empty(),
        "the middle slice is inside the plain hull"
    );
    // ... and the pushed-out planes hold it.
    assert!(poking.iter().all(|&v| slab.contains(v)));
    let samples = rotations_about_axis(DVec3::Z, &dense(0.0, FRAC_PI_2, 64)).unwrap();
    holds(&cobst, slab, &samples, "bar");
    // The margin is the sagitta bound r(1 − cos(δ/2)) plus rounding terms.
    let r = (4.0f64 + 0.01 + 0.01).sqrt();
    let sagitta = r * (1.0 - (FRAC_PI_2 / 2.0).cos());
    assert!(
        slab.margin() >= sagitta && slab.margin() <= sagitta * 1.001,
        "{}",
        slab.margin()
    );
    check_mesh(slab, "bar");
}

#[test]
fn boxes_at_exact_quarter_turns() {
    // Exactly parallel faces at every quarter turn: exact ties everywhere.
    let a = boxed(0.5, 1.0, 0.25);
    let b = boxed(1.0, 0.5, 0.5);
    for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
        check_turn(
            &a,
            &b,
            axis,
            &full_turn_angles(4),
            16,
            &format!("quarter turns about {axis}"),
        );
        check_turn(
            &a,
            &b,
            axis,
            &full_turn_angles(8),
            8,
            &format!("eighth turns about {axis}"),
        );
    }
    // Half turns (steps of exactly π) are allowed: both arcs are covered.
    check_turn(&a, &b, DVec3::Z, &full_turn_angles(2), 16, "half turns");
    // A full turn ends where it started: the last slice is the first.
    let turns = rotations_about_axis(DVec3::Z, &full_turn_angles(4)).unwrap();
    assert_eq!(turns[0], turns[4]);
}

#[test]
fn thin_plates() {
    let plate = boxed(1.0, 1.0, 1e-7);
    let other = scaled(&boxed(0.3, 1e-6, 0.8), 1.0, DVec3::new(0.2, -0.1, 0.05));
    check_turn(
        &plate,
        &other,
        DVec3::new(0.3, -0.5, 0.8),
        &full_turn_angles(12),
        8,
        "plates",
    );
    check_turn(
        &other,
        &plate,
        DVec3::X,
        &full_turn_angles(6),
        8,
        "plates about x",
    );
}

#[test]
fn far_from_the_origin() {
    let robot = boxed(0.5, 0.2, 0.1);
    let mut r = rng(20);
    let obstacle = scaled(
        &random_polytope(Kind::Ball, 30, &mut r),
        1.0,
        DVec3::new(1e6, -3e5, 2e5),
    );
    check_turn(
        &robot,
        &obstacle,
        DVec3::new(1.0, 2.0, 3.0),
        &full_turn_angles(8),
        8,
        "far",
    );
}

#[test]
fn at_scales_two_to_the_plus_and_minus_300() {
    let mut r = rng(21);
    let a = random_polytope(Kind::Sphere, 20, &mut r);
    let b = random_polytope(Kind::Grid, 12, &mut r);
    for e in [300, -300] {
        let s = 2f64.powi(e);
        let (sa, sb) = (
            scaled(&a, s, DVec3::ZERO),
            scaled(&b, s, DVec3::new(3.0 * s, 0.0, 0.0)),
        );
        check_turn(
            &sa,
            &sb,
            DVec3::new(-0.4, 0.1, 0.9),
            &full_turn_angles(6),
            8,
            &format!("2^{e}"),
        );
        let centre = random_rotation(&mut r);
        check_cell(&sa, &sb, centre, 0.2, 24, &mut r, &format!("cell at 2^{e}"));
    }
    // A tiny axis is scaled before it is normalised: the same rotations.
    let tiny = rotations_about_axis(DVec3::new(3e-320, 4e-320, 0.0), &[0.0, 1.0]).unwrap();
    let unit = rotations_about_axis(DVec3::new(0.6, 0.8, 0.0), &[0.0, 1.0]).unwrap();
    assert_eq!(tiny, unit);
}

/// Samples rotations within `radius` of `centre` (random axes, angles up
/// to the radius, the radius itself among them) and checks the cell slab.
fn check_cell(
    robot: &Polytope,
    obstacle: &Polytope,
    centre: Rotation,
    radius: f64,
    n: usize,
    r: &mut rand_chacha::ChaCha8Rng,
    what: &str,
) {
    let cobst = CObstacle::new(robot, obstacle).unwrap();
    let slab = certified_slab_in_cell(robot, obstacle, centre, radius).unwrap();
    assert_eq!(slab.cover(), SlabCover::Cell { centre, radius });
    let samples: Vec<Rotation> = (0..n)
        .map(|i| {
            let angle = if i % 3 == 0 {
                radius
            } else {
                r.random_range(0.0..=radius)
            };
            let turn = Rotation::from_axis_angle(random_axis(r), angle).unwrap();
            let rot = turn.then(&centre);
            assert!(
                centre.angle_to(&rot) <= radius + 1e-12,
                "{what}: sample outside the cell"
            );
            rot
        })
        .collect();
    holds(&cobst, &slab, &samples, what);
    check_mesh(&slab, what);
}

#[test]
fn cells_in_so3() {
    let mut r = rng(22);
    let tet =
        Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]]).unwrap();
    let bar = boxed(2.0, 0.1, 0.1);
    let ball = random_polytope(Kind::Ball, 40, &mut r);
    for (robot, obstacle) in [(&tet, &ball), (&bar, &tet), (&ball, &bar)] {
        for radius in [0.0, 1e-9, 0.01, 0.3, 1.5, 3.0] {
            let centre = random_rotation(&mut r);
            check_cell(
                robot,
                obstacle,
                centre,
                radius,
                16,
                &mut r,
                &format!("radius {radius}"),
            );
        }
    }
    // The margin is r·ρ plus rounding terms.
    let slab = certified_slab_in_cell(&bar, &tet, Rotation::IDENTITY, 0.1).unwrap();
    let r_bar = (4.0f64 + 0.01 + 0.01).sqrt();
    assert!(slab.margin() >= 0.1 * r_bar && slab.margin() <= 0.1 * r_bar * 1.0001);
}

#[test]
fn cells_in_a_batch_hold_their_samples_sequential_and_parallel_alike() {
    // Centres along a wandering path (one dynamic sum moved between them):
    // each batch slab holds the slices sampled in its cell, as the single
    // cell's slab does, with the same margin; the parallel batch is the
    // sequential one.
    let mut r = rng(25);
    let a = random_polytope(Kind::Ball, 20, &mut r);
    let b = random_polytope(Kind::Cube, 15, &mut r);
    let cobst = CObstacle::new(&a, &b).unwrap();
    let mut centres = vec![random_rotation(&mut r)];
    for _ in 0..9 {
        let step = Rotation::from_axis_angle(random_axis(&mut r), 0.3).unwrap();
        centres.push(step.then(centres.last().unwrap()));
    }
    let radius = 0.25;
    let seq = cobst.certified_slabs_in_cells(&centres, radius).unwrap();
    let par = cobst
        .certified_slabs_in_cells_par(&centres, radius)
        .unwrap();
    assert_eq!(seq.len(), centres.len());
    assert_eq!(par.len(), centres.len());
    for (k, (s, p)) in seq.iter().zip(&par).enumerate() {
        assert_eq!(s.normals(), p.normals());
        assert_eq!(s.offsets(), p.offsets());
        let one = cobst.certified_slab_in_cell(centres[k], radius).unwrap();
        assert_eq!(s.cover(), one.cover());
        assert_eq!(s.margin(), one.margin());
        let samples: Vec<Rotation> = (0..12)
            .map(|i| {
                let angle = if i % 3 == 0 {
                    radius
                } else {
                    r.random_range(0.0..=radius)
                };
                Rotation::from_axis_angle(random_axis(&mut r), angle)
                    .unwrap()
                    .then(&centres[k])
            })
            .collect();
        holds(&cobst, s, &samples, &format!("batch cell {k}"));
    }
    assert!(cobst
        .certified_slabs_in_cells(&[], radius)
        .unwrap()
        .is_empty());
    assert!(cobst
        .certified_slabs_in_cells_par(&[], radius)
        .unwrap()
        .is_empty());
    for radius in [-0.1, f64::NAN, PI] {
        for e in [
            cobst
                .certified_slabs_in_cells(&centres, radius)
                .unwrap_err(),
            cobst
                .certified_slabs_in_cells_par(&centres, radius)
                .unwrap_err(),
        ] {
            assert!(
                matches!(e, QueryError::Slab(SlabError::BadRadius { .. })),
                "{radius}: {e}"
            );
        }
    }
}

#[test]
fn slabs_between_any_rotations_hold_the_shortest_path() {
    // Consecutive orientations about different axes: the slab holds the
    // slices along the shortest path (slerp) between them.
    let mut r = rng(23);
    let a = random_polytope(Kind::Cube, 15, &mut r);
    let b = random_polytope(Kind::Coplanar, 25, &mut r);
    let cobst = CObstacle::new(&a, &b).unwrap();
    let turns: Vec<Rotation> = (0..6).map(|_| random_rotation(&mut r)).collect();
    let slabs = cobst.certified_slabs(&turns).unwrap();
    assert_eq!(slabs.len(), 5);
    for (k, slab) in slabs.iter().enumerate() {
        let (q0, q1) = (turns[k].quat(), turns[k + 1].quat());
        let samples: Vec<Rotation> = (0..=24)
            .map(|j| Rotation::from_quat(q0.slerp(q1, j as f64 / 24.0)))
            .collect();
        holds(&cobst, slab, &samples, &format!("path {k}"));
        let SlabCover::Path { from, to, angle } = slab.cover() else {
            panic!("a path slab");
        };
        assert_eq!((from, to), (turns[k], turns[k + 1]));
        assert!(angle >= turns[k].angle_to(&turns[k + 1]));
    }
}

#[test]
fn parallel_slabs_equal_the_sequential_ones() {
    let mut r = rng(24);
    let a = random_polytope(Kind::Ball, 25, &mut r);
    let b = random_polytope(Kind::Grid, 20, &mut r);
    let axis = random_axis(&mut r);
    let angles = full_turn_angles(40);
    let seq = certified_slabs_about_axis(&a, &b, axis, &angles).unwrap();
    let par = certified_slabs_about_axis_par(&a, &b, axis, &angles).unwrap();
    assert_eq!(seq.len(), par.len());
    for (s, p) in seq.iter().zip(&par) {
        assert_eq!(s.normals(), p.normals());
        assert_eq!(s.offsets(), p.offsets());
        assert_eq!(s.cover(), p.cover());
    }
}

#[test]
fn offsets_reach_the_margin_and_no_further() {
    // Each plane is the hull's support plus the margin, rounded up by a
    // few ulps: the slab is not looser than the certificate needs.
    let mut r = rng(25);
    let a = random_polytope(Kind::Sphere, 30, &mut r);
    let b = random_polytope(Kind::Cube, 30, &mut r);
    for slab in
        certified_slabs_about_axis(&a, &b, random_axis(&mut r), &full_turn_angles(10)).unwrap()
    {
        let hull = slab.hull();
        for (&n, &d) in slab.normals().iter().zip(slab.offsets()) {
            let top = hull
                .vertices()
                .iter()
                .map(|&v| n.dot(v))
                .fold(f64::MIN, f64::max);
            let excess = d - top;
            assert!(
                excess >= slab.margin() * 0.999_999,
                "{excess} < {}",
                slab.margin()
            );
            assert!(
                excess <= slab.margin() * 1.000_001 + 1e-12,
                "{excess} > {}",
                slab.margin()
            );
        }
    }
}

#[test]
fn the_rotation_slack_covers_the_rotations_dymsum_computes() {
    // Rodrigues' matrix of the exact axis and angle, against the snapped
    // matrix of `rotations_about_axis` (scaled axes included): within
    // 2^-42, a quarter of the slack.
    let mut r = rng(26);
    for i in 0..2000 {
        let axis = random_axis(&mut r);
        let scale = 2f64.powi([0, 500, -500, 60, -1000][i % 5]);
        let angle = r.random_range(-1000.0..1000.0);
        let got = rotations_about_axis(axis * scale, &[angle, angle + 1.0]).unwrap()[0].matrix();
        let (s, c) = angle.sin_cos();
        let k = glam::DMat3::from_cols(
            DVec3::new(0.0, axis.z, -axis.y),
            DVec3::new(-axis.z, 0.0, axis.x),
            DVec3::new(axis.y, -axis.x, 0.0),
        );
        let want = glam::DMat3::IDENTITY + k * s + k * k * (1.0 - c);
        let diff = got - want;
        let frobenius = [diff.x_axis, diff.y_axis, diff.z_axis]
            .iter()
            .map(|c| c.length_squared())
            .sum::<f64>()
            .sqrt();
        assert!(
            frobenius <= ROTATION_SLACK / 4.0,
            "axis {axis}, angle {angle}: {frobenius:e}"
        );
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let cube = boxed(0.5, 0.5, 0.5);
    let slabs =
        |axis: DVec3, angles: &[f64]| certified_slabs_about_axis(&cube, &cube, axis, angles);
    let slab_err = |e: QueryError| match e {
        QueryError::Slab(e) => e,
        other => panic!("not a slab error: {other}"),
    };
    for axis in [
        DVec3::ZERO,
        DVec3::new(f64::NAN, 0.0, 1.0),
        DVec3::new(f64::INFINITY, 0.0, 0.0),
    ] {
        assert!(matches!(
            slab_err(slabs(axis, &[0.0, 1.0]).unwrap_err()),
            SlabError::BadAxis { .. }
        ));
    }
    assert!(matches!(
        slab_err(slabs(DVec3::Z, &[0.0, f64::NAN]).unwrap_err()),
        SlabError::NonFiniteAngle { index: 1, .. }
    ));
    assert_eq!(
        slab_err(slabs(DVec3::Z, &[0.0, 1.0, 1.0]).unwrap_err()),
        SlabError::NotIncreasing {
            index: 2,
            previous: 1.0,
            angle: 1.0
        }
    );
    assert_eq!(
        slab_err(slabs(DVec3::Z, &[1.0, 0.5]).unwrap_err()),
        SlabError::NotIncreasing {
            index: 1,
            previous: 1.0,
            angle: 0.5
        }
    );
    assert_eq!(
        slab_err(slabs(DVec3::Z, &[0.0, 1.0, 1.0 + PI + 1e-9]).unwrap_err()),
        SlabError::StepTooLarge {
            index: 2,
            step: PI + 1e-9
        }
    );
    assert_eq!(
        slab_err(slabs(DVec3::Z, &[0.0, TAU]).unwrap_err()),
        SlabError::StepTooLarge {
            index: 1,
            step: TAU
        }
    );
    assert_eq!(
        slab_err(slabs(DVec3::Z, &[0.5]).unwrap_err()),
        SlabError::TooFewOrientations { count: 1 }
    );
    let cobst = CObstacle::new(&cube, &cube).unwrap();
    assert_eq!(
        slab_err(cobst.certified_slabs(&[Rotation::IDENTITY]).unwrap_err()),
        SlabError::TooFewOrientations { count: 1 }
    );
    assert!(
        slab_err(cobst.certified_slabs_par(&[]).unwrap_err())
            == SlabError::TooFewOrientations { count: 0 }
    );
    for radius in [-1e-300, f64::NAN, PI, 4.0, f64::INFINITY] {
        let e = slab_err(
            cobst
                .certified_slab_in_cell(Rotation::IDENTITY, radius)
                .unwrap_err(),
        );
        assert!(matches!(e, SlabError::BadRadius { .. }), "{radius}: {e}");
    }
    // Messages name the offending value.
    let msg = slabs(DVec3::Z, &[0.0, 1.0, 1.0]).unwrap_err().to_string();
    assert!(msg.contains("angle 2") && msg.contains("increase"), "{msg}");
}

#[test]
fn contains_is_exact_on_the_planes() {
    let cube = boxed(0.5, 0.5, 0.5);
    let slab = certified_slab_in_cell(&cube, &cube, Rotation::IDENTITY, 0.0).unwrap();
    // Axis-aligned planes: exact normals, so a point on a plane is inside
    // and the next float beyond it is outside.
    let (n, d) = (slab.normals(), slab.offsets());
    let k = n.iter().position(|&n| n == DVec3::X).expect("an x plane");
    let on = DVec3::new(d[k], 0.0, 0.0);
    assert!(slab.contains(on));
    assert!(!slab.contains(DVec3::new(f64::from_bits(d[k].to_bits() + 1), 0.0, 0.0)));
    assert!(!slab.contains(DVec3::new(f64::NAN, 0.0, 0.0)));
    assert_eq!(slab.len(), 6);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(proptest_cases(24)))]

    #[test]
    fn random_turns_hold_their_slices(
        seed in any::<u64>(),
        kinds in (0usize..5, 0usize..5),
        sizes in (5usize..25, 5usize..25),
        steps in proptest::collection::vec(0.01f64..=PI, 1..5),
        start in -10.0f64..10.0,
        offset in (-3.0f64..3.0, -3.0f64..3.0, -3.0f64..3.0),
    ) {
        let kind = |k: usize| [Kind::Ball, Kind::Grid, Kind::Coplanar, Kind::Sphere, Kind::Cube][k];
        let mut r = rng(seed);
        let a = random_polytope(kind(kinds.0), sizes.0, &mut r);
        let b = scaled(&random_polytope(kind(kinds.1), sizes.1, &mut r), 1.0, DVec3::new(offset.0, offset.1, offset.2));
        let mut angles = vec![start];
        for s in &steps {
            let next = angles[angles.len() - 1] + s;
            angles.push(next);
        }
        let axis = random_axis(&mut r);
        check_turn(&a, &b, axis, &angles, 6, &format!("seed {seed}"));
    }

    #[test]
    fn random_cells_hold_their_slices(
        seed in any::<u64>(),
        kinds in (0usize..5, 0usize..5),
        radius in 0.0f64..3.0,
    ) {
        let kind = |k: usize| [Kind::Ball, Kind::Grid, Kind::Coplanar, Kind::Sphere, Kind::Cube][k];
        let mut r = rng(seed);
        let a = random_polytope(kind(kinds.0), 12, &mut r);
        let b = random_polytope(kind(kinds.1), 12, &mut r);
        let centre = random_rotation(&mut r);
        check_cell(&a, &b, centre, radius, 8, &mut r, &format!("seed {seed}"));
    }
}
