//! Exact triangle–triangle tests for [`super::check_solid_mesh`]: does a
//! pair of non-degenerate triangles meet anywhere but along what they
//! share?
//!
//! Every decision is the exact sign of `orient3d` ([`orient`]) or of
//! `orient2d` on a coordinate projection ([`orient2`]), or an exact
//! comparison of input coordinates; no value is constructed.
//!
//! The one primitive is [`segment_meets_triangle`] (closed sets). Two
//! triangles with no common vertex meet if and only if an edge of one meets
//! the other: their intersection is convex; when the planes differ it is a
//! segment of their common line whose ends lie on the triangles' edges, and
//! when they are coplanar an overlap holds a vertex of one in the other or
//! two crossing edges. Two triangles `(v, p₁, p₂)` and `(v, q₁, q₂)` sharing
//! only `v` meet elsewhere if and only if `[p₁, p₂]` meets the second or
//! `[q₁, q₂]` meets the first: a second common point `x` makes `[v, x]`
//! common (convexity), and the far end of the shorter of `T₁ ∩ L`, `T₂ ∩ L`
//! along it lies on an opposite edge (for coplanar triangles the same holds
//! of the vertices of the common polygon). Two triangles sharing the edge
//! `uw` meet only along it unless they are coplanar with their third
//! corners on the same side of `uw` (a fold).

use crate::kernel::predicates::{orient, orient2, Sign};
use glam::DVec3;

/// A coordinate plane `(i, j)` onto which the triangle projects without
/// degenerating, or `None` when its corners are collinear (all three
/// projections flat, so exactly collinear).
pub(super) fn projection(t: &[DVec3; 3]) -> Option<(usize, usize)> {
    [(0, 1), (1, 2), (0, 2)]
        .into_iter()
        .find(|&(i, j)| orient2(pr(t[0], i, j), pr(t[1], i, j), pr(t[2], i, j)) != Sign::Zero)
}

#[inline]
fn pr(p: DVec3, i: usize, j: usize) -> [f64; 2] {
    [p[i], p[j]]
}

/// Whether collinear `p` lies on the closed segment `[a, b]` (exact
/// coordinate comparisons: `p` on the line, between the ends in both
/// coordinates).
fn between(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
    (0..2).all(|k| a[k].min(b[k]) <= p[k] && p[k] <= a[k].max(b[k]))
}

/// Closed 2-D segments `[a, b]` and `[c, d]` meet.
fn segments_meet_2d(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let (d1, d2) = (orient2(c, d, a), orient2(c, d, b));
    let (d3, d4) = (orient2(a, b, c), orient2(a, b, d));
    if d1 == d2.flip() && d1 != Sign::Zero && d3 == d4.flip() && d3 != Sign::Zero {
        return true;
    }
    (d1 == Sign::Zero && between(c, d, a))
        || (d2 == Sign::Zero && between(c, d, b))
        || (d3 == Sign::Zero && between(a, b, c))
        || (d4 == Sign::Zero && between(a, b, d))
}

/// `p` in the closed 2-D triangle `t` (not flat).
fn point_in_triangle_2d(p: [f64; 2], t: &[[f64; 2]; 3]) -> bool {
    let s = [
        orient2(t[0], t[1], p),
        orient2(t[1], t[2], p),
        orient2(t[2], t[0], p),
    ];
    !(s.contains(&Sign::Positive) && s.contains(&Sign::Negative))
}

/// The closed segment `[a, b]` meets the closed triangle `t` (not flat).
pub(super) fn segment_meets_triangle(a: DVec3, b: DVec3, t: &[DVec3; 3]) -> bool {
    let (sa, sb) = (orient(t[0], t[1], t[2], a), orient(t[0], t[1], t[2], b));
    if sa == sb && sa != Sign::Zero {
        return false;
    }
    if sa == Sign::Zero && sb == Sign::Zero {
        // In the triangle's plane: on a projection where the triangle is
        // not flat (a bijection on that plane).
        let Some((i, j)) = projection(t) else {
            return false;
        };
        let (a, b) = (pr(a, i, j), pr(b, i, j));
        let q = t.map(|p| pr(p, i, j));
        return point_in_triangle_2d(a, &q)
            || point_in_triangle_2d(b, &q)
            || (0..3).any(|k| segments_meet_2d(a, b, q[k], q[(k + 1) % 3]));
    }
    // The segment meets the plane in one point; it is in the triangle iff
    // the line through the segment passes through the closed triangle.
    let s = [
        orient(a, b, t[0], t[1]),
        orient(a, b, t[1], t[2]),
        orient(a, b, t[2], t[0]),
    ];
    !(s.contains(&Sign::Positive) && s.contains(&Sign::Negative))
}

/// Triangles `t` and `u` (not flat) with no common vertex meet.
pub(super) fn disjoint_triangles_meet(t: &[DVec3; 3], u: &[DVec3; 3]) -> bool {
    (0..3).any(|k| segment_meets_triangle(t[k], t[(k + 1) % 3], u))
        || (0..3).any(|k| segment_meets_triangle(u[k], u[(k + 1) % 3], t))
}

/// The closed segments `[a, b]` and `[c, d]` (either possibly a point)
/// meet: coplanar (exact `orient3d`), then on a coordinate projection that
/// is one-to-one on their plane (or on their line).
pub(crate) fn segments_meet(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> bool {
    if orient(a, b, c, d) != Sign::Zero {
        return false;
    }
    // A projection where some three of the points are not flat maps their
    // plane one to one; when all four are collinear, one where their line
    // is not a point does (between-ness is then per coordinate).
    let planar = [[a, b, c], [a, b, d], [a, c, d], [b, c, d]]
        .iter()
        .find_map(projection);
    let (i, j) = planar.unwrap_or_else(|| {
        let spread = |k: usize| [a, b, c, d].iter().any(|p| p[k] != a[k]);
        match (0..3).find(|&k| spread(k)) {
            Some(0) | None => (0, 1),
            Some(1) => (1, 2),
            Some(_) => (0, 2),
        }
    });
    segments_meet_2d(pr(a, i, j), pr(b, i, j), pr(c, i, j), pr(d, i, j))
}

/// Whether the closed triangles `t` and `u` meet (share at least one
/// point), whatever their degeneracy (a flat triangle is the union of its
/// edges, a point the point): every decision exact, at any scale. The
/// scene checker's test of a body's triangle against a scene's.
///
/// ```
/// use dymsum::solid::triangles_meet;
/// use dymsum::DVec3;
/// let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
/// let t = [v(0., 0., 0.), v(2., 0., 0.), v(0., 2., 0.)];
/// // Touching the hypotenuse at one point, from above and below.
/// assert!(triangles_meet(&t, &[v(1., 1., 0.), v(1., 1., 1.), v(2., 2., -1.)]));
/// // Coplanar and apart.
/// assert!(!triangles_meet(&t, &[v(2., 1., 0.), v(3., 1., 0.), v(2., 2., 0.)]));
/// ```
pub fn triangles_meet(t: &[DVec3; 3], u: &[DVec3; 3]) -> bool {
    // The cheap rejection first (Guigue–Devillers' first step): all of
    // one triangle strictly on one side of the other's plane. A flat
    // triangle has no plane (every sign zero) and is never rejected here.
    if strictly_one_side(u, t) || strictly_one_side(t, u) {
        return false;
    }
    let edges = |x: &[DVec3; 3]| [(x[0], x[1]), (x[1], x[2]), (x[2], x[0])];
    match (projection(t).is_some(), projection(u).is_some()) {
        (true, true) => disjoint_triangles_meet(t, u),
        (false, true) => edges(t)
            .iter()
            .any(|&(a, b)| segment_meets_triangle(a, b, u)),
        (true, false) => edges(u)
            .iter()
            .any(|&(a, b)| segment_meets_triangle(a, b, t)),
        (false, false) => edges(t)
            .iter()
            .any(|&(a, b)| edges(u).iter().any(|&(c, d)| segments_meet(a, b, c, d))),
    }
}

/// Shewchuk's first error bound of `orient3d`, `(7 + 56ε)ε` with
/// `ε = 2⁻⁵³`, rounded up.
const ORIENT3D_BOUND: f64 = 7.771_561_172_376_103e-16;

/// Every corner of `pts` strictly on one side of the plane of `plane`
/// (exact signs; `false` for a flat `plane`). The three signs are first
/// read from one floating-point evaluation sharing the plane's normal,
/// each certified by Shewchuk's static bound for `orient3d` (the same
/// minors, the same order of operations, so the same bound), used only
/// when every nonzero difference lies within `1e±80` (no product
/// underflows or overflows); when any is not certified, all three are
/// decided by the exact `orient3d`.
fn strictly_one_side(plane: &[DVec3; 3], pts: &[DVec3; 3]) -> bool {
    let (ba, ca) = (plane[1] - plane[0], plane[2] - plane[0]);
    let normal = ba.cross(ca);
    let minors = DVec3::new(
        (ba.y * ca.z).abs() + (ba.z * ca.y).abs(),
        (ba.z * ca.x).abs() + (ba.x * ca.z).abs(),
        (ba.x * ca.y).abs() + (ba.y * ca.x).abs(),
    );
    // Shewchuk's bound assumes no underflow: every nonzero difference
    // within 1e±80 keeps every product of three and every sum normal.
    let in_range = |v: DVec3| {
        v.to_array()
            .iter()
            .all(|&x| x == 0.0 || (1e-80..=1e80).contains(&x.abs()))
    };
    let filtered = |p: DVec3| -> Option<bool> {
        let pa = p - plane[0];
        if !(in_range(ba) && in_range(ca) && in_range(pa)) {
            return None;
        }
        let det = pa.dot(normal);
        let permanent = pa.abs().dot(minors);
        let certain =
            permanent > 1e-280 && permanent < 1e280 && det.abs() > ORIENT3D_BOUND * permanent;
        certain.then_some(det > 0.0)
    };
    if let (Some(a), Some(b), Some(c)) = (filtered(pts[0]), filtered(pts[1]), filtered(pts[2])) {
        return a == b && b == c;
    }
    let side = |p: DVec3| orient(plane[0], plane[1], plane[2], p);
    let s0 = side(pts[0]);
    s0 != Sign::Zero && side(pts[1]) == s0 && side(pts[2]) == s0
}

/// Triangles `(v, p₁, p₂)` and `(v, q₁, q₂)` (not flat) sharing only the
/// corner `v` meet elsewhere: `p = [p₁, p₂]`, `q = [q₁, q₂]`.
pub(super) fn vertex_sharing_triangles_meet(
    t: &[DVec3; 3],
    p: [DVec3; 2],
    u: &[DVec3; 3],
    q: [DVec3; 2],
) -> bool {
    segment_meets_triangle(p[0], p[1], u) || segment_meets_triangle(q[0], q[1], t)
}

/// Triangles `(u, w, p)` and `(w, u, q)` (not flat) sharing the edge `uw`
/// overlap: coplanar, with `p` and `q` on the same side of `uw`.
pub(super) fn edge_sharing_triangles_fold(u: DVec3, w: DVec3, p: DVec3, q: DVec3) -> bool {
    if orient(u, w, p, q) != Sign::Zero {
        return false;
    }
    let Some((i, j)) = projection(&[u, w, p]) else {
        return false;
    };
    let side = |x: DVec3| orient2(pr(u, i, j), pr(w, i, j), pr(x, i, j));
    side(p) == side(q)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    #[test]
    fn crossing_touching_and_apart() {
        let t = [v(0., 0., 0.), v(2., 0., 0.), v(0., 2., 0.)];
        // Pierces the interior.
        let u = [v(0.5, 0.5, -1.), v(0.5, 0.5, 1.), v(3., 3., 0.5)];
        assert!(disjoint_triangles_meet(&t, &u));
        // Touches an edge at one point (closed sets meet).
        let u = [v(1., -1., -1.), v(1., 1., -1.), v(1., 0., 0.)];
        assert!(disjoint_triangles_meet(&t, &u));
        // Above the plane.
        let u = [v(0.5, 0.5, 1e-300), v(0.5, 0.6, 1.), v(0.6, 0.5, 1.)];
        assert!(!disjoint_triangles_meet(&t, &u));
        // Coplanar, inside.
        let u = [v(0.1, 0.1, 0.), v(0.5, 0.1, 0.), v(0.1, 0.5, 0.)];
        assert!(disjoint_triangles_meet(&t, &u));
        // Coplanar, apart.
        let u = [v(3., 3., 0.), v(4., 3., 0.), v(3., 4., 0.)];
        assert!(!disjoint_triangles_meet(&t, &u));
    }

    #[test]
    fn the_filtered_side_test_is_the_exact_one() {
        // Grid points (many exactly coplanar), tiny and huge scales, and
        // points one ulp off a plane: the filter never decides otherwise
        // than the exact signs.
        let mut rng = crate::kernel::test_rng::Xorshift::new(0x9e37_79b9_7f4a_7c15);
        let mut next = || rng.next_u64();
        let exact = |plane: &[DVec3; 3], pts: &[DVec3; 3]| {
            let side = |p: DVec3| orient(plane[0], plane[1], plane[2], p);
            let s0 = side(pts[0]);
            s0 != Sign::Zero && side(pts[1]) == s0 && side(pts[2]) == s0
        };
        for scale in [1e-200, 1e-8, 1.0, 1e8, 1e200] {
            for _ in 0..20_000 {
                let mut p = || {
                    let c = |r: u64| ((r % 7) as f64 - 3.0) * scale;
                    let mut q = v(c(next()), c(next()), c(next()));
                    if next() % 5 == 0 {
                        q.z = f64::from_bits(q.z.to_bits() + 1); // one ulp off
                    }
                    q
                };
                let plane = [p(), p(), p()];
                let pts = [p(), p(), p()];
                assert_eq!(
                    strictly_one_side(&plane, &pts),
                    exact(&plane, &pts),
                    "{plane:?} {pts:?}"
                );
            }
        }
    }

    #[test]
    fn the_filter_stands_aside_where_products_underflow() {
        // A review's counterexample: a product of differences underflows
        // to zero, and the float signs all agree while the exact one does
        // not; the point (2¹⁹⁸, 2⁻⁵⁴⁰, 0) lies on both triangles.
        let p2 = |e: i32| 2f64.powi(e);
        let u = [
            v(0., 0., 0.),
            v(p2(200), p2(-538), 0.),
            v(p2(200), 0., p2(-538)),
        ];
        let t = [
            v(p2(197), p2(-540), 0.),
            v(p2(199), p2(-540), 0.),
            v(p2(198), p2(-540), 1.),
        ];
        assert!(!strictly_one_side(&u, &t));
        assert!(triangles_meet(&t, &u));
    }

    #[test]
    fn shared_corner_and_edge() {
        let o = v(0., 0., 0.);
        let t = [o, v(2., 0., 0.), v(0., 2., 0.)];
        // Coplanar, overlapping wedges.
        let u = [o, v(1., 1., 0.), v(-1., 3., 0.)];
        assert!(vertex_sharing_triangles_meet(
            &t,
            [t[1], t[2]],
            &u,
            [u[1], u[2]]
        ));
        // Coplanar, wedges apart.
        let u = [o, v(-1., 0., 0.), v(0., -1., 0.)];
        assert!(!vertex_sharing_triangles_meet(
            &t,
            [t[1], t[2]],
            &u,
            [u[1], u[2]]
        ));
        // Another plane through a wedge's edge: meets along it.
        let u = [o, v(1., 0., 0.), v(1., 0., 1.)];
        assert!(vertex_sharing_triangles_meet(
            &t,
            [t[1], t[2]],
            &u,
            [u[1], u[2]]
        ));
        // A fold about a shared edge, and a flat hinge.
        let (a, b) = (v(0., 0., 0.), v(1., 0., 0.));
        assert!(edge_sharing_triangles_fold(
            a,
            b,
            v(0., 1., 0.),
            v(5., 2., 0.)
        ));
        assert!(!edge_sharing_triangles_fold(
            a,
            b,
            v(0., 1., 0.),
            v(5., -2., 0.)
        ));
        assert!(!edge_sharing_triangles_fold(
            a,
            b,
            v(0., 1., 0.),
            v(5., 2., 1e-300)
        ));
    }
}
