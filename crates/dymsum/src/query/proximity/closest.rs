//! Closest features of two bodies' elements: a point and a convex polygon,
//! a point and a segment, two segments (Ericson, *Real-Time Collision
//! Detection*, §5.1), and two lines clamped to their segments (the witness
//! points of an edge–edge contact). Float constructions only: the features
//! they are applied to were chosen by the exact overlay.

use glam::DVec3;

/// Closest point to `q` of the convex polygon `verts` (counter-clockwise
/// about `normal`).
pub(in crate::query) fn closest_on_polygon(verts: &[DVec3], normal: DVec3, q: DVec3) -> DVec3 {
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
pub(in crate::query) fn closest_on_segment(p: DVec3, r: DVec3, q: DVec3) -> DVec3 {
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
pub(in crate::query) fn segment_segment(
    p1: DVec3,
    q1: DVec3,
    p2: DVec3,
    q2: DVec3,
) -> (DVec3, DVec3) {
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
pub(in crate::query) fn line_line(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> (DVec3, DVec3) {
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
