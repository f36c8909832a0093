//! Distance and closest points when the origin lies outside `D = A ⊕ (−B)`.
//!
//! The closest point of `D` to an exterior origin lies on a facet whose
//! support value is negative (the origin is on its outer side), so only
//! those facets are examined. A facet's distance is a feature–feature
//! distance of the bodies: a face of A to a vertex of B (closest point on a
//! convex polygon), a vertex of A to a face of B, or an edge to an edge
//! (closest points of two segments). Every examined pair gives real points
//! of A and B, so the minimum is exact up to rounding.
//!
//! Branch and bound: each facing facet lies in a ball (a face's corners lie
//! within a precomputed radius of their mean, [`FeatureBalls`]; a
//! parallelogram of two edges within half their lengths' sum of the
//! midpoints' difference), so its distance is at least the distance to the
//! ball's centre less the radius, and at least `−h`. The facet of least
//! bound is measured first; then only facets whose bound (less a rounding
//! safety) does not exceed the best distance so far are measured. Every
//! facet passed over is farther than the answer, so the answer, ties
//! included (the least distance, then the first features in
//! [`FeaturePair`]'s order), is the one measuring all of them gives.
//!
//! Complexity: O(facets) for the bounds, plus one feature distance per
//! facet near the answer.

use crate::query::answer::FeaturePair;
use crate::query::answer::Separation;
use crate::query::frame::Posed;
use crate::query::pair::ConvexPair;
use crate::query::prep::mean;
use crate::query::proximity::certificate::candidates::{climb, Candidate};
use crate::query::proximity::closest::{closest_on_polygon, segment_segment};
use glam::DVec3;

/// A lower bound on the distance from the origin to the facet of `c`
/// (frame units), before the rounding safety: the ball bound, and the
/// plane's `−h` once `h` is refined (the unrefined `h₀ ≤ h` is no bound).
fn distance_bound(pair: &ConvexPair, posed: &Posed, c: &Candidate) -> f64 {
    let (a, b) = (&pair.a, &pair.b);
    let (balls_a, balls_b) = (&pair.prep_a.balls, &pair.prep_b.balls);
    let (frame_a, frame_b) = (
        |r: f64| balls_a.in_frame(r, posed.k),
        |r: f64| balls_b.in_frame(r, posed.k),
    );
    let ball = match c.features {
        FeaturePair::FaceVertex { a_face, b_vertex } => {
            let face = a.face(a_face as usize);
            let centre = mean(face.iter().map(|&v| posed.a(v)), face.len());
            (centre - posed.b(b_vertex)).length() - frame_a(balls_a.face_radius[a_face as usize])
        }
        FeaturePair::VertexFace { a_vertex, b_face } => {
            let face = b.face(b_face as usize);
            let centre = mean(face.iter().map(|&v| posed.b(v)), face.len());
            (posed.a(a_vertex) - centre).length() - frame_b(balls_b.face_radius[b_face as usize])
        }
        FeaturePair::EdgeEdge { a_edge, b_edge } => {
            let [u1, u2] = a.edge(a_edge as usize).vertices;
            let [w1, w2] = b.edge(b_edge as usize).vertices;
            let mid_a = 0.5 * (posed.a(u1) + posed.a(u2));
            let mid_b = 0.5 * (posed.b(w1) + posed.b(w2));
            (mid_a - mid_b).length()
                - (frame_a(balls_a.half_edge[a_edge as usize])
                    + frame_b(balls_b.half_edge[b_edge as usize]))
        }
    };
    if c.refined {
        ball.max(-c.h)
    } else {
        ball
    }
}

/// A measured facet: the distance, the closest points on A and on B, the
/// features.
type Measured = (f64, DVec3, DVec3, FeaturePair);

/// The distance between the features of `c` and their closest points.
fn measure(pair: &ConvexPair, posed: &Posed, c: &Candidate, poly: &mut Vec<DVec3>) -> Measured {
    let (pa, pb) = feature_points(pair, posed, c, poly);
    ((pb - pa).length(), pa, pb, c.features)
}

/// Keeps the measured facet of least distance, and of the first features
/// in [`FeaturePair`]'s order among equal distances (so the answer depends
/// on the set of candidates, never on their order).
#[inline]
fn keep_least(best: &mut Option<Measured>, m: Measured) {
    if !best
        .as_ref()
        .is_some_and(|b| m.0 > b.0 || (m.0 == b.0 && m.3 >= b.3))
    {
        *best = Some(m);
    }
}

/// The closest points of the features of `c` (on A, on B).
fn feature_points(
    pair: &ConvexPair,
    posed: &Posed,
    c: &Candidate,
    poly: &mut Vec<DVec3>,
) -> (DVec3, DVec3) {
    let (a, b) = (&pair.a, &pair.b);
    match c.features {
        FeaturePair::FaceVertex { a_face, b_vertex } => {
            poly.clear();
            poly.extend(a.face(a_face as usize).iter().map(|&v| posed.a(v)));
            let q = posed.b(b_vertex);
            let normal = posed.pose_a.rotation.apply(a.normal(a_face as usize));
            (closest_on_polygon(poly, normal, q), q)
        }
        FeaturePair::VertexFace { a_vertex, b_face } => {
            poly.clear();
            poly.extend(b.face(b_face as usize).iter().map(|&v| posed.b(v)));
            let q = posed.a(a_vertex);
            let normal = posed.pose_b.rotation.apply(b.normal(b_face as usize));
            (q, closest_on_polygon(poly, normal, q))
        }
        FeaturePair::EdgeEdge { a_edge, b_edge } => {
            let [u1, u2] = a.edge(a_edge as usize).vertices;
            let [w1, w2] = b.edge(b_edge as usize).vertices;
            segment_segment(posed.a(u1), posed.a(u2), posed.b(w1), posed.b(w2))
        }
    }
}

/// The separation: minimum feature distance over the facets on whose outer
/// side the origin lies (support value below `tol`), by branch and bound
/// (module docs), and whether any facet was measured (else the answer is
/// `fallback`'s value with zero witness points). `poly` is a reused buffer
/// for a face's posed corners, `bounds` one for the facets' distance
/// bounds.
pub(in crate::query) fn separation(
    pair: &ConvexPair,
    posed: &Posed,
    cands: &[Candidate],
    tol: f64,
    fallback: Candidate,
    poly: &mut Vec<DVec3>,
    bounds: &mut Vec<f64>,
) -> (Separation, bool) {
    // Rounding of the bounds and of the measured distances: a few ulps of
    // the coordinates' scale (`tol` is 16 of them); the posed corners,
    // mean and points are each off the exact pose by at most the pose
    // error, which can exceed `tol` when a body's vertices lie far from its
    // own origin; and an absolute term for radii that reach subnormals.
    let pose_error = posed.eta_a + posed.eta_b;
    let safety = 4.0 * tol + 2.0 * pose_error + 1e-290;
    bounds.clear();
    bounds.extend(cands.iter().map(|c| {
        if c.h <= tol {
            distance_bound(pair, posed, c)
        } else {
            f64::INFINITY
        }
    }));
    // Whether a candidate faces the origin: its refined value is at most
    // `tol` (refined here, once, when [`refine`] left it for later).
    let facing = |c: &Candidate| c.h <= tol && (c.refined || climb(pair, posed, c) <= tol);
    let seed = (0..cands.len())
        .filter(|&i| cands[i].refined && bounds[i].is_finite())
        .min_by(|&i, &j| bounds[i].total_cmp(&bounds[j]));
    let mut limit = seed.map_or(f64::INFINITY, |i| measure(pair, posed, &cands[i], poly).0);
    let mut best: Option<Measured> = None;
    for (c, &bound) in cands.iter().zip(bounds.iter()) {
        if c.h > tol || bound - safety > limit || !facing(c) {
            continue;
        }
        keep_least(&mut best, measure(pair, posed, c, poly));
        limit = limit.min(best.map_or(f64::INFINITY, |b| b.0));
    }
    #[cfg(test)]
    {
        // The bound may skip only facets that cannot win: measuring every
        // facing facet must give the same best, ties included.
        let mut all = None;
        for c in cands.iter().filter(|c| facing(c)) {
            keep_least(&mut all, measure(pair, posed, c, poly));
        }
        assert_eq!(best, all, "the branch and bound changed the separation");
    }
    let measured = best.is_some();
    let (distance, point_on_a, point_on_b, features) =
        best.unwrap_or((-fallback.h, DVec3::ZERO, DVec3::ZERO, fallback.features));
    let dir = point_on_b - point_on_a;
    let direction = if dir.length() > 0.0 {
        dir.normalize()
    } else {
        fallback.n
    };
    (
        Separation {
            distance,
            point_on_a,
            point_on_b,
            direction,
            features,
        },
        measured,
    )
}

#[cfg(test)]
mod tests {
    use crate::kernel::rotation::Pose;
    use crate::kernel::rotation::Rotation;
    use crate::polytope::Polytope;
    use crate::query::{ConvexPair, Proximity};
    use glam::DVec3;

    use crate::query::test_support::{boxed, Lcg};

    /// Random hulls, boxes with parallel faces at exact quarter turns, and
    /// round hulls, apart and overlapping: every query goes through the
    /// checks that the separation's branch and bound equals measuring
    /// every facing facet ([`super::separation`]) and that leaving out
    /// ee-candidates changes no answer (`evaluate::evaluate_in_frame`).
    #[test]
    fn pruned_queries_equal_evaluating_every_facet() {
        let mut r = Lcg(7);
        let mut shapes: Vec<Polytope> = vec![boxed(0.5, 1.0, 1.5), boxed(1.0, 0.5, 0.5)];
        for n in [12, 40, 150] {
            let pts: Vec<DVec3> = (0..n).map(|_| r.unit()).collect();
            shapes.push(Polytope::from_dvec3s(&pts).unwrap());
        }
        let (mut separated, mut penetrating) = (0, 0);
        for a in &shapes {
            for b in &shapes {
                let pair = ConvexPair::new(a, b).unwrap();
                for k in 0..40 {
                    let rot = if k % 4 == 0 {
                        let axis = [DVec3::X, DVec3::Y, DVec3::Z][k % 3];
                        Rotation::from_axis_angle(axis, std::f64::consts::FRAC_PI_2 * k as f64)
                    } else {
                        Rotation::from_axis_angle(r.unit(), 3.0 * r.next())
                    }
                    .unwrap();
                    // Apart, touching and overlapping, half of them
                    // along x (parallel faces at quarter turns).
                    let offset = if k % 4 == 0 {
                        DVec3::new(0.5 + (k / 4) as f64 * 0.4, 0.0, 0.0)
                    } else {
                        r.unit() * (5.0 * r.next().abs())
                    };
                    let answer = pair
                        .query(
                            Pose::new(rot, DVec3::ZERO),
                            Pose::new(Rotation::IDENTITY, offset),
                        )
                        .unwrap();
                    match answer {
                        Proximity::Separated(s) => {
                            assert!(s.distance > 0.0);
                            separated += 1;
                        }
                        Proximity::Penetrating(c) => {
                            assert!(c.depth >= 0.0);
                            penetrating += 1;
                        }
                    }
                }
            }
        }
        assert!(
            separated > 300 && penetrating > 300,
            "{separated} separated, {penetrating} penetrating poses"
        );
    }

    /// The vertices scaled by `s` and moved by `off` (in the body frame).
    fn scaled(p: &Polytope, s: f64, off: DVec3) -> Polytope {
        let pts: Vec<DVec3> = p.vertices().iter().map(|&v| v * s + off).collect();
        Polytope::from_dvec3s(&pts).unwrap()
    }

    /// Review finding: the balls' radii used to be computed in body units,
    /// whose squares underflow below about 1e-154, so at 2^-600 the bound
    /// skipped every facet and the separation returned zero witness
    /// points. Every scale the crate supports, with boxes, a thin plate, a
    /// rod, a many-cornered prism and a random hull, apart and overlapping,
    /// through the all-candidates checks.
    #[test]
    fn regression_pruning_at_every_scale() {
        let mut r = Lcg(99);
        let mut prism = Vec::new();
        for i in 0..48 {
            let t = i as f64 / 48.0 * std::f64::consts::TAU;
            prism.push(DVec3::new(t.cos(), t.sin(), -0.3));
            prism.push(DVec3::new(t.cos(), t.sin(), 0.3));
        }
        let random: Vec<DVec3> = (0..20).map(|_| r.unit()).collect();
        let shapes = [
            boxed(0.5, 1.0, 1.5),
            boxed(2.0, 2.0, 1e-3),
            boxed(3.0, 0.01, 0.01),
            Polytope::from_dvec3s(&prism).unwrap(),
            Polytope::from_dvec3s(&random).unwrap(),
        ];
        let mut separated = 0;
        for s in [1.0, 2f64.powi(-600), 2f64.powi(-900), 1e-250, 1e250, 1e300] {
            for a0 in &shapes {
                for b0 in &shapes {
                    let (a, b) = (scaled(a0, s, DVec3::ZERO), scaled(b0, s, DVec3::ZERO));
                    let pair = ConvexPair::new(&a, &b).unwrap();
                    for k in 0..12 {
                        let rot = if k % 3 == 0 {
                            let axis = [DVec3::X, DVec3::Y, DVec3::Z][(k / 3) % 3];
                            Rotation::from_axis_angle(axis, std::f64::consts::FRAC_PI_2)
                        } else {
                            Rotation::from_axis_angle(r.unit(), 3.0 * r.next())
                        }
                        .unwrap();
                        let offset = r.unit() * (6.0 * r.next().abs()) * s;
                        let answer = pair
                            .query(
                                Pose::new(rot, DVec3::ZERO),
                                Pose::new(Rotation::IDENTITY, offset),
                            )
                            .unwrap();
                        if let Proximity::Separated(sep) = answer {
                            assert!(sep.point_on_a != sep.point_on_b, "scale {s:e}");
                            separated += 1;
                        }
                    }
                }
            }
        }
        assert!(separated > 300, "{separated} separated poses");
    }

    /// Review finding: a body whose vertices lie far from its own origin,
    /// posed back near the world origin, rounds its posed vertices by far
    /// more than the tie tolerance; the ball bound must allow for that. B
    /// is a small tetrahedron just beyond a corner of one of A's faces, in
    /// the face's plane (a tie between the facets at that corner), which
    /// used to pick a different facet in about 1% of the poses.
    #[test]
    fn regression_pruning_with_bodies_far_from_their_origin() {
        let mut r = Lcg(17);
        let mut separated = 0;
        for far in [0.0, 1e4, 1e8, 1e12] {
            let off = DVec3::new(far, -0.7 * far, 0.3 * far);
            let random: Vec<DVec3> = (0..20).map(|_| r.unit()).collect();
            let shapes = [
                boxed(0.5, 1.0, 1.5),
                Polytope::from_dvec3s(&random).unwrap(),
            ];
            for a0 in &shapes {
                let a = scaled(a0, 1.0, off);
                for k in 0..300 {
                    let rot = Rotation::from_axis_angle(r.unit(), 3.0 * r.next()).unwrap();
                    let pose_a = Pose::new(rot, -rot.apply(off));
                    let posed: Vec<DVec3> = a.vertices().iter().map(|&v| pose_a.apply(v)).collect();
                    let f = k % a.face_count();
                    let face = a.face(f);
                    let centre = face.iter().fold(DVec3::ZERO, |s, &v| s + posed[v as usize])
                        / face.len() as f64;
                    let corner = posed[face[(k / 7) % face.len()] as usize];
                    let u = (corner - centre).normalize();
                    let n = rot.apply(a.unit_normal(f));
                    let d = 0.05 + 0.5 * r.next().abs();
                    let q = corner + u * d + n * (d * 1e-3 * (k % 3) as f64);
                    let w = (u + n * 0.5).normalize();
                    let tip = |r: &mut Lcg| (w + r.unit() * 0.3) * 0.2;
                    let tetra = [DVec3::ZERO, tip(&mut r), tip(&mut r), tip(&mut r)];
                    let Ok(b) = Polytope::from_dvec3s(&tetra) else {
                        continue;
                    };
                    let pair = ConvexPair::new(&a, &b).unwrap();
                    let pose_b = Pose::new(Rotation::IDENTITY, q);
                    if !pair.query(pose_a, pose_b).unwrap().intersects() {
                        separated += 1;
                    }
                }
            }
        }
        assert!(separated > 1000, "{separated} separated poses");
    }
}
