//! Distance and closest points when the origin lies outside `D = A ⊕ (−B)`.
//!
//! The closest point of `D` to an exterior origin lies on a facet whose
//! support value is negative (the origin is on its outer side), so only
//! those facets are examined. A facet's distance is a feature–feature
//! distance of the bodies: a face of A to a vertex of B (closest point on a
//! convex polygon), a vertex of A to a face of B, or an edge to an edge
//! (closest points of two segments). Every examined pair gives real points
//! of A and B, so the minimum is exact up to rounding. O(facets).

use super::depth::{Candidate, Posed};
use super::{ConvexPair, FeaturePair, Separation};
use glam::DVec3;

/// Closest point to `q` of the convex polygon `verts` (counter-clockwise
/// about `normal`).
pub(super) fn closest_on_polygon(verts: &[DVec3], normal: DVec3, q: DVec3) -> DVec3 {
    let v0 = verts[0];
    let x = q - normal * normal.dot(q - v0) / normal.length_squared();
    let k = verts.len();
    let inside = (0..k).all(|i| {
        let (p, r) = (verts[i], verts[(i + 1) % k]);
        (r - p).cross(x - p).dot(normal) >= 0.0
    });
    if inside {
        return x;
    }
    let mut best = verts[0];
    let mut best_d = f64::INFINITY;
    for i in 0..k {
        let c = closest_on_segment(verts[i], verts[(i + 1) % k], q);
        let d = (c - q).length_squared();
        if d < best_d {
            best_d = d;
            best = c;
        }
    }
    best
}

/// Closest point to `q` of the segment `p r`.
fn closest_on_segment(p: DVec3, r: DVec3, q: DVec3) -> DVec3 {
    let d = r - p;
    let l2 = d.length_squared();
    if l2 == 0.0 {
        return p;
    }
    let t = ((q - p).dot(d) / l2).clamp(0.0, 1.0);
    p + t * d
}

/// Closest points of the segments `p1 q1` and `p2 q2` (Ericson, *Real-Time
/// Collision Detection*, §5.1.9).
pub(super) fn segment_segment(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> (DVec3, DVec3) {
    let d1 = q1 - p1;
    let d2 = q2 - p2;
    let r = p1 - p2;
    let a = d1.length_squared();
    let e = d2.length_squared();
    let f = d2.dot(r);
    let (s, t);
    if a == 0.0 && e == 0.0 {
        return (p1, p2);
    }
    if a == 0.0 {
        s = 0.0;
        t = (f / e).clamp(0.0, 1.0);
    } else {
        let c = d1.dot(r);
        if e == 0.0 {
            t = 0.0;
            s = (-c / a).clamp(0.0, 1.0);
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let mut s0 = if denom > 0.0 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut t0 = (b * s0 + f) / e;
            if t0 < 0.0 {
                t0 = 0.0;
                s0 = (-c / a).clamp(0.0, 1.0);
            } else if t0 > 1.0 {
                t0 = 1.0;
                s0 = ((b - c) / a).clamp(0.0, 1.0);
            }
            s = s0;
            t = t0;
        }
    }
    (p1 + d1 * s, p2 + d2 * t)
}

/// Closest points of the *lines* through `p1 q1` and `p2 q2`, with the
/// parameters clamped to the segments (for the witness points of an
/// edge–edge contact, whose facet contains the projection).
pub(super) fn line_line(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> (DVec3, DVec3) {
    let d1 = q1 - p1;
    let d2 = q2 - p2;
    let r = p1 - p2;
    let (a, b, e) = (d1.length_squared(), d1.dot(d2), d2.length_squared());
    let (c, f) = (d1.dot(r), d2.dot(r));
    let denom = a * e - b * b;
    if denom <= 0.0 || a == 0.0 || e == 0.0 {
        return segment_segment(p1, q1, p2, q2);
    }
    let s = ((b * f - c * e) / denom).clamp(0.0, 1.0);
    let t = ((a * f - b * c) / denom).clamp(0.0, 1.0);
    (p1 + d1 * s, p2 + d2 * t)
}

/// The separation: minimum feature distance over the facets on whose outer
/// side the origin lies (support value below `tol`).
pub(super) fn separation(
    pair: &ConvexPair,
    posed: &Posed,
    cands: &[Candidate],
    tol: f64,
    fallback: Candidate,
) -> Separation {
    let (a, b) = (&pair.a, &pair.b);
    let mut best: Option<(f64, DVec3, DVec3, FeaturePair)> = None;
    let mut poly = Vec::new();
    for c in cands.iter().filter(|c| c.h <= tol) {
        let (pa, pb) = match c.features {
            FeaturePair::FaceVertex { a_face, b_vertex } => {
                poly.clear();
                poly.extend(a.face(a_face as usize).iter().map(|&v| posed.a[v as usize]));
                let q = posed.b[b_vertex as usize];
                let normal = posed.pose_a.rotation.apply(a.normal(a_face as usize));
                (closest_on_polygon(&poly, normal, q), q)
            }
            FeaturePair::VertexFace { a_vertex, b_face } => {
                poly.clear();
                poly.extend(b.face(b_face as usize).iter().map(|&v| posed.b[v as usize]));
                let q = posed.a[a_vertex as usize];
                let normal = posed.pose_b.rotation.apply(b.normal(b_face as usize));
                (q, closest_on_polygon(&poly, normal, q))
            }
            FeaturePair::EdgeEdge { a_edge, b_edge } => {
                let [u1, u2] = a.edge(a_edge as usize).vertices;
                let [w1, w2] = b.edge(b_edge as usize).vertices;
                segment_segment(
                    posed.a[u1 as usize],
                    posed.a[u2 as usize],
                    posed.b[w1 as usize],
                    posed.b[w2 as usize],
                )
            }
        };
        let d = (pb - pa).length();
        if !best.as_ref().is_some_and(|bst| d >= bst.0) {
            best = Some((d, pa, pb, c.features));
        }
    }
    let (distance, point_on_a, point_on_b, features) =
        best.unwrap_or((-fallback.h, DVec3::ZERO, DVec3::ZERO, fallback.features));
    let dir = point_on_b - point_on_a;
    let direction = if dir.length() > 0.0 {
        dir.normalize()
    } else {
        fallback.n
    };
    Separation {
        distance,
        point_on_a,
        point_on_b,
        direction,
        features,
    }
}
