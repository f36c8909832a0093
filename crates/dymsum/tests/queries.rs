//! Oracle tests for the proximity queries (`dymsum::query`, paper §1).
//!
//! * **Brute force**: the exact hull of all pairwise differences `a − b` of
//!   the posed vertices (`dymsum::hull::convex_hull` on `PairwiseSums`); the
//!   depth is the minimum over its face planes of the origin's distance, the
//!   distance the minimum over its (fan-triangulated) faces of the distance
//!   from the origin. Ours must match within `1e-9` relative.
//! * **parry3d-f64** (GJK/EPA) `contact` and `distance`: where parry differs
//!   from ours, ours must match the brute force; the test prints by how much
//!   parry was off and fails only if both are off.
//! * Named cases libraries get wrong: edge–edge deepest direction between
//!   rotated boxes, barely touching boxes, deep overlaps, identical bodies at
//!   the same pose, swapped arguments.
//! * The tracker equals the static query every frame; C-obstacle slices are
//!   identical sequentially, in parallel and from scratch, and contain
//!   exactly the colliding translations; unions collide iff a pair does.

use dymsum::hull::{convex_hull, PairwiseSums};
use dymsum::query::{
    self, cobstacle_slices, orientations_about_axis, CObstacle, ConvexPair, ConvexUnion,
    FeaturePair, Proximity, QueryError, UnionProximity,
};
use dymsum::{DVec3, Polytope, Pose, Rotation};
use dymsum_testkit::{cube_points, proptest_cases, random_rotation, Kind};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

// ---------------------------------------------------------------- helpers

fn posed(p: &Polytope, pose: Pose) -> Vec<DVec3> {
    p.vertices().iter().map(|&v| pose.apply(v)).collect()
}

fn scale(a: &[DVec3], b: &[DVec3]) -> f64 {
    a.iter()
        .chain(b)
        .map(|v| v.abs().max_element())
        .fold(1.0f64, f64::max)
}

/// Brute force: `(signed depth, distance)` from the exact hull of pairwise
/// differences. Signed depth = min over face planes of `n · x` (negative when
/// the origin is outside); distance = 0 inside, else min distance to faces.
fn brute(a: &Polytope, pa: Pose, b: &Polytope, pb: Pose) -> (f64, f64) {
    let p = posed(a, pa);
    let q: Vec<DVec3> = posed(b, pb).into_iter().map(|v| -v).collect();
    let sums = PairwiseSums::new(&p, &q);
    let hull = convex_hull(&sums).expect("hull of differences");
    let pt = |k: usize| {
        let (i, j) = sums.split(k);
        p[i] + q[j]
    };
    let mut hmin = f64::INFINITY;
    let mut dmin = f64::INFINITY;
    for f in &hull.faces {
        let c: Vec<DVec3> = f.iter().map(|&k| pt(k)).collect();
        // Newell normal.
        let mut n = DVec3::ZERO;
        for i in 0..c.len() {
            let (u, v) = (c[i], c[(i + 1) % c.len()]);
            n += DVec3::new(
                (u.y - v.y) * (u.z + v.z),
                (u.z - v.z) * (u.x + v.x),
                (u.x - v.x) * (u.y + v.y),
            );
        }
        let n = n.normalize();
        let centroid = c.iter().copied().sum::<DVec3>() / c.len() as f64;
        hmin = hmin.min(n.dot(centroid));
        for i in 1..c.len() - 1 {
            dmin = dmin.min(point_triangle(DVec3::ZERO, c[0], c[i], c[i + 1]).length());
        }
    }
    (hmin, if hmin >= 0.0 { 0.0 } else { dmin })
}

/// Closest point of triangle `abc` to `p` minus `p` (Ericson §5.1.5).
fn point_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a - p;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b - p;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3)) - p;
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c - p;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6)) - p;
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))) - p;
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom) - p
}

/// parry's `(signed depth, distance)` (GJK/EPA on world-space hulls).
fn parry(a: &Polytope, pa: Pose, b: &Polytope, pb: Pose) -> Option<(f64, f64, DVec3)> {
    use parry3d_f64::math::{Pose as PPose, Vector};
    use parry3d_f64::shape::ConvexPolyhedron;
    // dymsum's `DVec3` is parry's `Vector` (the same glam version): no
    // conversion. This stops compiling if the versions ever split.
    let (va, vb): (Vec<Vector>, Vec<Vector>) = (posed(a, pa), posed(b, pb));
    let sa = ConvexPolyhedron::from_convex_hull(&va)?;
    let sb = ConvexPolyhedron::from_convex_hull(&vb)?;
    let id = PPose::IDENTITY;
    let c = parry3d_f64::query::contact(&id, &sa, &id, &sb, 0.0).ok()?;
    let d = parry3d_f64::query::distance(&id, &sa, &id, &sb).ok()?;
    Some(match c {
        Some(c) => (-c.dist, d.distance, c.normal1),
        None => (f64::NAN, d.distance, DVec3::NAN),
    })
}

/// Checks one configuration against the brute force (and reports parry's
/// error); returns the query result.
fn check(a: &Polytope, pa: Pose, b: &Polytope, pb: Pose, label: &str) -> Proximity {
    let ours = query::query(a, pa, b, pb).unwrap();
    let (h, dist) = brute(a, pa, b, pb);
    let s = scale(&posed(a, pa), &posed(b, pb));
    let tol = 1e-9 * s;
    match &ours {
        Proximity::Penetrating(c) => {
            assert!(
                h >= -tol,
                "{label}: we say overlapping (depth {}), brute force says apart ({h})",
                c.depth
            );
            assert!(
                (c.depth - h.max(0.0)).abs() <= tol,
                "{label}: depth {} vs brute force {h}",
                c.depth
            );
            assert!(
                (c.normal.length() - 1.0).abs() < 1e-12,
                "{label}: unit normal"
            );
            let w = c.point_on_a - c.point_on_b;
            assert!(
                (w - c.depth * c.normal).length() <= 1e-8 * s,
                "{label}: witnesses {w} vs depth·normal {}",
                c.depth * c.normal
            );
            // Translating A by −depth·normal (a bit more) separates.
            let moved = Pose::new(
                pa.rotation,
                pa.translation - (c.depth + 1e-7 * s) * c.normal,
            );
            let (h2, _) = brute(a, moved, b, pb);
            assert!(
                h2 < 0.0,
                "{label}: moving A by −depth·normal does not separate ({h2})"
            );
        }
        Proximity::Separated(sep) => {
            assert!(h <= tol, "{label}: we say apart, brute force depth {h}");
            assert!(
                (sep.distance - dist).abs() <= tol,
                "{label}: distance {} vs brute force {dist}",
                sep.distance
            );
            assert!(
                ((sep.point_on_b - sep.point_on_a).length() - sep.distance).abs() <= tol,
                "{label}: witnesses"
            );
        }
    }
    if let Some((pd, pdist, _)) = parry(a, pa, b, pb) {
        let ours_depth = ours.depth();
        if ours.intersects() && !pd.is_nan() && (pd - ours_depth).abs() > tol {
            println!(
                "{label}: parry EPA depth {pd:.17} differs from exact {ours_depth:.17} by {:.3e}",
                (pd - ours_depth).abs()
            );
        }
        if !ours.intersects() && (pdist - ours.distance()).abs() > tol {
            println!(
                "{label}: parry GJK distance {pdist:.17} differs from exact {:.17} by {:.3e}",
                ours.distance(),
                (pdist - ours.distance()).abs()
            );
        }
    }
    ours
}

fn cube(lo: f64, hi: f64) -> Polytope {
    Polytope::from_points(&cube_points(lo, hi)).unwrap()
}

fn box_(lo: DVec3, hi: DVec3) -> Polytope {
    let pts: Vec<DVec3> = (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect();
    Polytope::from_dvec3s(&pts).unwrap()
}

fn at(x: f64, y: f64, z: f64) -> Pose {
    Pose::new(Rotation::IDENTITY, DVec3::new(x, y, z))
}

fn random_polytope(r: &mut ChaCha8Rng, n: usize) -> Polytope {
    dymsum_testkit::random_polytope(Kind::Cube, n, r)
}

fn random_pose(r: &mut ChaCha8Rng, spread: f64) -> Pose {
    Pose::new(
        random_rotation(r),
        DVec3::new(
            r.random_range(-spread..spread),
            r.random_range(-spread..spread),
            r.random_range(-spread..spread),
        ),
    )
}

// ---------------------------------------------------------------- named cases

#[test]
fn face_contact_of_axis_aligned_cubes_is_exact() {
    let c = cube(0.0, 1.0);
    let hit = check(&c, at(0.0, 0.0, 0.0), &c, at(0.75, 0.1, -0.2), "cubes");
    let contact = hit.contact().unwrap();
    assert_eq!(contact.depth, 0.25);
    assert_eq!(contact.normal, DVec3::X);
    let sep = query::distance(&c, at(0.0, 0.0, 0.0), &c, at(1.5, 0.1, 0.0)).unwrap();
    assert_eq!(sep.distance, 0.5);
    assert_eq!(sep.direction, DVec3::X);
}

#[test]
fn edge_edge_deepest_direction_between_rotated_boxes() {
    // A: a unit cube turned 45° about z (a vertical edge at x = √½);
    // B: a unit cube turned 45° about y (an edge along y at x = −√½ of its
    // centre). Placed so those edges cross with overlap δ along x, then the
    // whole scene is turned by a generic rotation.
    let c = cube(-0.5, 0.5);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for (k, delta) in [0.05, 1e-3, 1e-6].into_iter().enumerate() {
        let scene = Rotation::from_axis_angle(DVec3::new(0.3, -0.7, 0.2), 0.9 + k as f64).unwrap();
        let ra = Rotation::from_axis_angle(DVec3::Z, std::f64::consts::FRAC_PI_4)
            .unwrap()
            .then(&scene);
        let rb = Rotation::from_axis_angle(DVec3::Y, std::f64::consts::FRAC_PI_4)
            .unwrap()
            .then(&scene);
        let tb = scene.apply(DVec3::new(2.0 * h - delta, 0.0, 0.0));
        let (pa, pb) = (Pose::new(ra, DVec3::ZERO), Pose::new(rb, tb));
        let label = format!("edge–edge δ={delta}");
        let hit = check(&c, pa, &c, pb, &label);
        let contact = *hit.contact().expect("overlapping");
        assert!(
            matches!(contact.features, FeaturePair::EdgeEdge { .. }),
            "{label}: {:?}",
            contact.features
        );
        assert!(
            (contact.depth - delta).abs() < 1e-12,
            "{label}: {}",
            contact.depth
        );
        assert!((contact.normal - scene.apply(DVec3::X)).length() < 1e-9);
        // Swapped: same depth, opposite normal.
        let swapped = query::penetration_depth(&c, pb, &c, pa).unwrap().unwrap();
        assert_eq!(swapped.depth, contact.depth, "{label}");
        assert_eq!(swapped.normal, -contact.normal, "{label}");
        if let Some((pd, _, pn)) = parry(&c, pa, &c, pb) {
            println!(
                "{label}: exact depth {:.3e}, parry EPA {:.3e} (off by {:.2e}, normal off by {:.2e})",
                contact.depth,
                pd,
                (pd - contact.depth).abs(),
                (pn - contact.normal).length()
            );
        }
    }
}

#[test]
fn barely_touching_and_barely_apart_boxes() {
    let c = cube(0.0, 1.0);
    // Exactly touching: depth 0, intersecting.
    let touch = check(&c, at(0.0, 0.0, 0.0), &c, at(1.0, 0.3, 0.2), "touching");
    assert!(touch.intersects());
    assert_eq!(touch.depth(), 0.0);
    assert!(query::intersects(&c, at(0.0, 0.0, 0.0), &c, at(1.0, 0.3, 0.2)).unwrap());
    // Overlapping by ~1e-12: exactly 1 − x (Sterbenz).
    let x = 1.0 - 1e-12;
    let hit = check(
        &c,
        at(0.0, 0.0, 0.0),
        &c,
        at(x, 0.3, 0.2),
        "barely overlapping",
    );
    assert_eq!(hit.depth(), 1.0 - x);
    assert_eq!(hit.contact().unwrap().normal, DVec3::X);
    // Apart by ~1e-12.
    let y = 1.0 + 1e-12;
    let gap = check(&c, at(0.0, 0.0, 0.0), &c, at(y, 0.3, 0.2), "barely apart");
    assert!(!gap.intersects());
    assert_eq!(gap.distance(), y - 1.0);
    // Corner to corner, touching at one point.
    let corner = check(
        &c,
        at(0.0, 0.0, 0.0),
        &c,
        at(1.0, 1.0, 1.0),
        "corners touching",
    );
    assert!(corner.intersects());
    assert_eq!(corner.depth(), 0.0);
}

#[test]
fn deep_overlaps() {
    let a = box_(DVec3::new(-2.0, -0.5, -0.25), DVec3::new(2.0, 0.5, 0.25));
    let b = cube(-0.4, 0.4);
    let mut r = ChaCha8Rng::seed_from_u64(7);
    for k in 0..20 {
        let pb = Pose::new(
            random_rotation(&mut r),
            DVec3::new(r.random_range(-1.0..1.0), 0.05, -0.02),
        );
        let hit = check(&a, Pose::IDENTITY, &b, pb, &format!("deep {k}"));
        assert!(hit.depth() > 0.3, "deep {k}: {}", hit.depth());
    }
    // B entirely inside A, centred: depth is the thinnest way out, along z.
    let hit = check(
        &a,
        Pose::IDENTITY,
        &cube(-0.1, 0.1),
        Pose::IDENTITY,
        "nested",
    );
    let c = hit.contact().unwrap();
    assert_eq!(c.depth, 0.35);
    assert_eq!(c.normal.x, 0.0);
    assert_eq!(c.normal.y, 0.0);
}

#[test]
fn identical_bodies_at_the_same_pose() {
    let c = cube(0.0, 1.0);
    let hit = check(&c, Pose::IDENTITY, &c, Pose::IDENTITY, "identical cubes");
    let contact = hit.contact().unwrap();
    assert_eq!(contact.depth, 1.0);
    // Six tied directions, centrally symmetric: the fixed rule (smallest
    // sign-free key, then the positive one) picks +z. parry's EPA reports 0.
    assert_eq!(contact.normal, DVec3::Z);
    let mut r = ChaCha8Rng::seed_from_u64(11);
    for k in 0..10 {
        let p = random_polytope(&mut r, 12);
        let pose = random_pose(&mut r, 1.0);
        let a = check(&p, pose, &p, pose, &format!("identical random {k}"));
        let b = check(&p, pose, &p, pose, &format!("identical random {k} again"));
        assert_eq!(a, b, "deterministic");
    }
}

#[test]
fn swapping_bodies_negates_the_direction() {
    let mut r = ChaCha8Rng::seed_from_u64(5);
    let mut exact = 0;
    let total = 60;
    for k in 0..total {
        let a = random_polytope(&mut r, 6 + k % 20);
        let b = random_polytope(&mut r, 4 + (k * 7) % 25);
        let (pa, pb) = (random_pose(&mut r, 0.8), random_pose(&mut r, 0.8));
        let ab = query::query(&a, pa, &b, pb).unwrap();
        let ba = query::query(&b, pb, &a, pa).unwrap();
        match (ab, ba) {
            (Proximity::Penetrating(x), Proximity::Penetrating(y)) => {
                assert!(
                    (x.depth - y.depth).abs() <= 1e-14,
                    "{k}: {} vs {}",
                    x.depth,
                    y.depth
                );
                assert!((x.normal + y.normal).length() <= 1e-12, "{k}");
                assert!((x.point_on_a - y.point_on_b).length() <= 1e-9, "{k}");
                if x.depth == y.depth && x.normal == -y.normal {
                    exact += 1;
                }
            }
            (Proximity::Separated(x), Proximity::Separated(y)) => {
                assert!((x.distance - y.distance).abs() <= 1e-12, "{k}");
                assert!((x.direction + y.direction).length() <= 1e-9, "{k}");
                exact += 1;
            }
            other => panic!("{k}: swap changed the answer: {other:?}"),
        }
    }
    // Generic inputs are symmetric bit for bit.
    assert_eq!(exact, total, "bitwise-symmetric cases");
}

// ---------------------------------------------------------------- proptest

proptest! {
    #![proptest_config(ProptestConfig::with_cases(proptest_cases(64)))]

    #[test]
    fn random_pairs_match_brute_force(
        seed in any::<u64>(),
        na in 4usize..30,
        nb in 4usize..30,
        spread in 0.1f64..2.5,
    ) {
        let mut r = ChaCha8Rng::seed_from_u64(seed);
        let a = random_polytope(&mut r, na);
        let b = random_polytope(&mut r, nb);
        let (pa, pb) = (random_pose(&mut r, spread), random_pose(&mut r, spread));
        let label = format!("seed {seed}");
        let res = check(&a, pa, &b, pb, &label);
        prop_assert_eq!(res.intersects(), query::intersects(&a, pa, &b, pb).unwrap());
    }
}

// ---------------------------------------------------------------- tracker

#[test]
fn tracker_equals_static_query_every_frame() {
    let mut r = ChaCha8Rng::seed_from_u64(3);
    for trial in 0..4 {
        let a = random_polytope(&mut r, 40);
        let b = random_polytope(&mut r, 30);
        let pair = ConvexPair::new(&a, &b).unwrap();
        let axis_a = DVec3::new(r.random_range(-1.0..1.0), 1.0, 0.2);
        let axis_b = DVec3::new(0.3, r.random_range(-1.0..1.0), 1.0);
        let pose = |k: usize| {
            let t = k as f64 / 50.0;
            (
                Pose::new(
                    Rotation::from_axis_angle(axis_a, t * 3.0).unwrap(),
                    DVec3::new(3.0 * (t * 2.0).cos(), 0.2, 0.0),
                ),
                Pose::new(
                    Rotation::from_axis_angle(axis_b, -t * 2.0).unwrap(),
                    DVec3::ZERO,
                ),
            )
        };
        let (pa, pb) = pose(0);
        let mut tracker = pair.tracker(pa, pb).unwrap();
        let (mut hits, mut misses) = (0, 0);
        for k in 1..=200 {
            let (pa, pb) = pose(k);
            let got = tracker.update(pa, pb).unwrap();
            let want = pair.query(pa, pb).unwrap();
            assert_eq!(got, want, "trial {trial} frame {k}");
            if got.intersects() {
                hits += 1
            } else {
                misses += 1
            }
        }
        assert!(
            hits > 0 && misses > 0,
            "trial {trial}: {hits} hits, {misses} misses"
        );
    }
}

// ---------------------------------------------------------------- C-obstacles

/// `true` when `t` lies in the closed convex mesh (within `tol`).
fn mesh_contains(mesh: &dymsum::PolygonMesh, t: DVec3, tol: f64) -> bool {
    mesh.faces.iter().all(|f| {
        let v: Vec<DVec3> = f.iter().map(|&i| DVec3::from(mesh.vertices[i])).collect();
        let mut n = DVec3::ZERO;
        for i in 0..v.len() {
            n += v[i].cross(v[(i + 1) % v.len()]);
        }
        n.normalize().dot(t - v[0]) <= tol
    })
}

#[test]
fn cobstacle_slices_sequential_parallel_static_agree() {
    let mut r = ChaCha8Rng::seed_from_u64(9);
    let robot = random_polytope(&mut r, 25);
    let obstacle = random_polytope(&mut r, 30);
    let turns = orientations_about_axis(DVec3::new(0.2, 0.3, 1.0), 97).unwrap();
    let seq = cobstacle_slices(&robot, &obstacle, &turns).unwrap();
    let cob = CObstacle::new(&robot, &obstacle).unwrap();
    let par = cob.slices_par(&turns).unwrap();
    assert_eq!(seq.len(), 97);
    assert_eq!(seq, par);
    for (k, &rot) in turns.iter().enumerate().step_by(8) {
        assert_eq!(seq[k], cob.slice(rot).unwrap(), "slice {k}");
        // t in the slice ⟺ the robot at (R, t) meets the obstacle.
        for _ in 0..20 {
            let t = DVec3::new(
                r.random_range(-2.5..2.5),
                r.random_range(-2.5..2.5),
                r.random_range(-2.5..2.5),
            );
            let collide =
                query::query(&robot, Pose::new(rot, t), &obstacle, Pose::IDENTITY).unwrap();
            if collide.depth() > 1e-9 || collide.distance() > 1e-9 {
                assert_eq!(
                    mesh_contains(&seq[k], t, 0.0),
                    collide.intersects(),
                    "slice {k}, t = {t}"
                );
            }
        }
    }
}

// ---------------------------------------------------------------- unions

#[test]
fn unions_collide_when_a_pair_does_and_refuse_depth() {
    // An L made of two boxes, and a small cube probing the notch.
    let l = ConvexUnion::new(vec![
        box_(DVec3::new(0.0, 0.0, 0.0), DVec3::new(3.0, 1.0, 1.0)),
        box_(DVec3::new(0.0, 1.0, 0.0), DVec3::new(1.0, 3.0, 1.0)),
    ])
    .unwrap();
    let probe = ConvexUnion::new(vec![cube(0.0, 0.5)]).unwrap();
    // In the notch: apart; distance 0.25 to both arms.
    let p = at(1.25, 1.25, 0.25);
    assert!(!l.collides(Pose::IDENTITY, &probe, p).unwrap());
    assert!((l.distance(Pose::IDENTITY, &probe, p).unwrap() - 0.25).abs() < 1e-15);
    // Hitting one arm.
    let p = at(2.0, 0.8, 0.25);
    assert!(l.collides(Pose::IDENTITY, &probe, p).unwrap());
    match l.query(Pose::IDENTITY, &probe, p).unwrap() {
        UnionProximity::Colliding(hits) => assert_eq!(hits.len(), 1),
        other => panic!("{other:?}"),
    }
    assert_eq!(
        l.penetration_depth(Pose::IDENTITY, &probe, p).unwrap_err(),
        QueryError::UnionDepthUnsupported
    );
    // Single pieces: the convex depth.
    let one = ConvexUnion::new(vec![cube(0.0, 1.0)]).unwrap();
    let d = one
        .penetration_depth(Pose::IDENTITY, &probe, at(0.75, 0.2, 0.2))
        .unwrap()
        .unwrap();
    assert_eq!(d.depth, 0.25);
    // Slices: one mesh per piece pair per orientation.
    let turns = orientations_about_axis(DVec3::Z, 6).unwrap();
    let slices = probe.cobstacle_slices(&l, &turns).unwrap();
    assert_eq!(slices.len(), 6);
    assert!(slices.iter().all(|s| s.len() == 2));
}
