//! Certified floating-point separating-axis filters: a cheap proof that
//! two triangles, or a triangle and a box, are apart, tried before the
//! exact tests so that the pairs a broad phase lets through cost a few
//! dozen flops instead of several exact orientations.
//!
//! A filter answers `true` only with a proof; `false` means "not proven"
//! (the caller then runs its exact test), never "they meet".
//!
//! # Soundness
//! Any vector `a` is an axis: if `a·p < a·q` for every corner `p` of one
//! set and `q` of the other, the convex hulls are disjoint. The axis need
//! not be exact (a normal or an edge cross product computed in floats is
//! just some vector), only the comparison must be. With `m` the
//! coordinatewise largest magnitude over every point involved and
//! `S = Σ|a_k| m_k`, each computed projection `fl(a·x)` of a 3-term dot
//! product is within `γ₃ S` of `a·x` (`γ₃ = 3u/(1−3u)`, `u = 2⁻⁵³`;
//! with or without fused multiply–adds). The test is
//! `fl(P₁ + s) < Q₀` with `P₁` the largest computed projection of one set,
//! `Q₀` the least of the other, and the slack `s = fl(fl(16u·fl(S)) +
//! TINY)`. Since `|P₁| ≤ (1 + γ₃)S`, the rounded sum is at least
//! `P₁ + s − u((1 + γ₃)S + s)`, and `fl(S) ≥ (1 − γ₃)S` gives `s ≥ 15u S`,
//! so a passed test means `P₁ + 7u S < Q₀`, more than the `2γ₃ S` the two
//! projections may be off by together: the true intervals are apart.
//! Underflowing products err by at most `2⁻¹⁰⁷⁴` each; the absolute term
//! `TINY` (far below any coordinate the crate accepts as a size) covers
//! them. Overflow is safe by monotone rounding: `|fl(a·x)| ≤ fl(S)`, so an
//! overflowed projection forces `fl(S) = ∞`, hence an infinite or NaN
//! slack, and the comparison fails (not because NaN projections fail
//! comparisons: `f64::min`/`max` drop them). Inputs must be finite (a NaN
//! coordinate is no point; the callers' posed coordinates are finite).
//!
//! # Independent review (2026-11-29)
//! The γ₃ bound (glam's `dot` is three rounded products and two rounded
//! sums, never fused), the slack `fl(fl(16u·fl(S)) + TINY) ≥ 15.99u·S` and
//! the rounded comparison were checked: a passed test leaves about
//! `14u·S` of margin against the `6u·S` needed. A port checked against
//! exact rationals on 300,000 axis and point sets at scales `2⁻¹⁰⁷⁰` to
//! `2⁵⁰⁰` found no false proof. The box corners' projections (`select` on
//! the axis' signs) and `magnitude` (box corners included) were verified.
//! The overflow sentence and the slack's formula above were corrected
//! after it; `rounding_never_makes_a_proof` fails when the slack is
//! weakened.

use glam::DVec3;

/// The unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;

/// An absolute slack covering underflowed products (module docs).
const TINY: f64 = 1e-290;

/// The least and largest computed projections of `pts` on `a`.
#[inline]
fn span(a: DVec3, pts: &[DVec3; 3]) -> (f64, f64) {
    let (x, y, z) = (a.dot(pts[0]), a.dot(pts[1]), a.dot(pts[2]));
    (x.min(y).min(z), x.max(y).max(z))
}

/// The slack of axis `a` for points within `mag` coordinatewise (module
/// docs).
#[inline]
fn slack(a: DVec3, mag: DVec3) -> f64 {
    16.0 * U * a.abs().dot(mag) + TINY
}

/// Whether the computed spans `(p0, p1)` and `(q0, q1)` are apart by more
/// than `s`.
#[inline]
fn spans_apart((p0, p1): (f64, f64), (q0, q1): (f64, f64), s: f64) -> bool {
    p1 + s < q0 || q1 + s < p0
}

/// The coordinatewise largest magnitude of some points.
#[inline]
fn magnitude<'a>(pts: impl IntoIterator<Item = &'a DVec3>) -> DVec3 {
    pts.into_iter().fold(DVec3::ZERO, |m, p| m.max(p.abs()))
}

/// A proof that closed triangles `t` and `u` are disjoint: some axis among
/// their normals and the nine cross products of their edges separates
/// them, certified despite rounding (module docs). `false` proves nothing.
#[inline]
pub(crate) fn triangles_apart(t: &[DVec3; 3], u: &[DVec3; 3]) -> bool {
    debug_assert!(t.iter().chain(u.iter()).all(|p| p.is_finite()));
    let mag = magnitude(t.iter().chain(u.iter()));
    let apart = |a: DVec3| spans_apart(span(a, t), span(a, u), slack(a, mag));
    let et = [t[1] - t[0], t[2] - t[1], t[0] - t[2]];
    let eu = [u[1] - u[0], u[2] - u[1], u[0] - u[2]];
    if apart(eu[0].cross(eu[1])) || apart(et[0].cross(et[1])) {
        return true;
    }
    et.iter().any(|&e| eu.iter().any(|&f| apart(e.cross(f))))
}

/// A triangle's plane as a separating axis against many boxes, certified
/// (module docs; a box corner projects to `Σ a_k c_k` with `c_k` either
/// `lo_k` or `hi_k`, a 3-term dot product like any other point) with one
/// slack for all: the
/// points' magnitude is bounded once by `mag`, at least every coordinate's
/// of the triangle and of every box asked (a larger bound only makes the
/// slack larger).
pub(crate) struct PlaneAxis {
    normal: DVec3,
    span: (f64, f64),
    slack: f64,
}

impl PlaneAxis {
    /// The plane of triangle `t`, for boxes whose coordinates and `t`'s are
    /// within `mag` coordinatewise.
    #[inline]
    pub(crate) fn new(t: &[DVec3; 3], mag: DVec3) -> PlaneAxis {
        let normal = (t[1] - t[0]).cross(t[2] - t[1]);
        PlaneAxis {
            normal,
            span: span(normal, t),
            slack: slack(normal, mag),
        }
    }

    /// A proof that the triangle and the closed box `[lo, hi]` are disjoint
    /// (the box on one side of the plane); `false` proves nothing.
    #[inline]
    pub(crate) fn parts(&self, lo: DVec3, hi: DVec3) -> bool {
        let a = self.normal;
        let near = DVec3::select(a.cmpge(DVec3::ZERO), lo, hi);
        let far = DVec3::select(a.cmpge(DVec3::ZERO), hi, lo);
        spans_apart(self.span, (a.dot(near), a.dot(far)), self.slack)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solid::intersect::triangles_meet;

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    #[test]
    fn apart_triangles_are_proven_apart() {
        let t = [v(0., 0., 0.), v(1., 0., 0.), v(0., 1., 0.)];
        let u = [v(0., 0., 1.), v(1., 0., 1.), v(0., 1., 1.)];
        assert!(triangles_apart(&t, &u));
        // Interleaved slivers whose boxes overlap: an edge axis parts them.
        let a = [v(0., 0., 0.), v(10., 10., 0.), v(10., 10.001, 0.)];
        let b = [v(0., 1., 0.), v(10., 11., 0.5), v(10., 11.001, -0.5)];
        assert!(!triangles_meet(&a, &b));
        assert!(triangles_apart(&a, &b));
    }

    #[test]
    fn touching_triangles_are_never_proven_apart() {
        let t = [v(0., 0., 0.), v(1., 0., 0.), v(0., 1., 0.)];
        // A shared corner, an edge on an edge, a corner on the face, and
        // a corner a rounding away from the plane on the other side.
        for u in [
            [v(0., 0., 0.), v(-1., 0., 0.), v(0., -1., 0.)],
            [v(0.5, 0., 0.), v(1.5, 0., 0.), v(1., 0., 1.)],
            [v(0.25, 0.25, 0.), v(0.25, 0.25, 1.), v(1., 1., 1.)],
            [v(0.25, 0.25, 0.0), v(3., 3., 1e-300), v(3., -3., 1.)],
        ] {
            assert!(triangles_meet(&t, &u));
            assert!(!triangles_apart(&t, &u), "{u:?}");
        }
        // Far from the origin, touching at a corner after a shift.
        let s = v(1e6, -3e7, 2.5e5);
        let far = |x: [DVec3; 3]| x.map(|p| p + s);
        let u = [v(1., 0., 0.), v(2., 0., 0.), v(1., 1., 1.)];
        assert!(triangles_meet(&far(t), &far(u)));
        assert!(!triangles_apart(&far(t), &far(u)));
    }

    #[test]
    fn a_triangles_plane_parts_boxes() {
        let t = [v(0., 0., 0.), v(10., 10., 0.), v(10., 10.01, 0.)];
        let plane = PlaneAxis::new(&t, v(20., 20., 1.));
        // A box entirely above the plane, and one touching it.
        assert!(plane.parts(v(-3., -3., 0.5), v(20., 20., 1.)));
        assert!(!plane.parts(v(-3., -3., 0.), v(20., 20., 1.)));
        // A box the plane crosses, off the sliver: the plane cannot part it.
        assert!(!plane.parts(v(6., 1., -1.), v(8., 3., 1.)));
    }

    /// The exact oracle: a corner of `t` in the box, or `t` meeting one of
    /// the twelve triangles of the box's faces.
    fn triangle_meets_box(t: &[DVec3; 3], lo: DVec3, hi: DVec3) -> bool {
        let c =
            |i: usize| DVec3::select(glam::BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0), hi, lo);
        let quads = [
            [0, 1, 3, 2],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 3, 7, 6],
            [0, 2, 6, 4],
            [1, 3, 7, 5],
        ];
        t.iter().any(|p| p.cmpge(lo).all() && p.cmple(hi).all())
            || quads.iter().any(|q| {
                triangles_meet(t, &[c(q[0]), c(q[1]), c(q[2])])
                    || triangles_meet(t, &[c(q[0]), c(q[2]), c(q[3])])
            })
    }

    /// A proof is never given for triangles that meet: random triangles
    /// on a coarse grid (many touch exactly), judged by the exact test.
    #[test]
    fn never_proves_a_meeting_pair_apart() {
        let mut rng = crate::kernel::test_rng::Xorshift::new(0x9e37_79b9_7f4a_7c15);
        let mut next = move || (rng.next_u64() % 5) as f64 - 2.0;
        let (mut proven, mut meeting) = (0, 0);
        for _ in 0..50_000 {
            let mut tri = || [(); 3].map(|_| v(next(), next(), next()));
            let (t, u) = (tri(), tri());
            let meet = triangles_meet(&t, &u);
            meeting += meet as u32;
            if triangles_apart(&t, &u) {
                assert!(!meet, "{t:?} {u:?}");
                proven += 1;
            }
            let (lo, hi) = (u[0].min(u[1]), u[0].max(u[1]));
            let mag = t.iter().fold(lo.abs().max(hi.abs()), |m, p| m.max(p.abs()));
            if PlaneAxis::new(&t, mag).parts(lo, hi) {
                assert!(!triangle_meets_box(&t, lo, hi), "{t:?} {lo} {hi}");
            }
        }
        assert!(proven > 10_000 && meeting > 5_000, "{proven} {meeting}");
    }

    /// Touching made by rounding: a corner put on the other triangle's edge
    /// or face in floats (off it by rounding, to either side), kept when
    /// the exact test says they meet. Without the slack, some of these
    /// would be "proven" apart by a projection an ulp off (this test then
    /// fails: checked by setting the slack to zero).
    #[test]
    fn rounding_never_makes_a_proof() {
        let mut rng = crate::kernel::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1du64);
        let mut unit = move || rng.signed();
        let mut meeting = 0;
        for k in 0..200_000 {
            let mut pts = [(); 5].map(|_| v(unit(), unit(), unit()) * 1e3);
            let u = [pts[0], pts[1], pts[2]];
            let (s, r) = (unit().abs(), unit().abs());
            let on = if k % 2 == 0 {
                u[0] + (u[1] - u[0]) * s
            } else {
                u[0] + (u[1] - u[0]) * (s * 0.5) + (u[2] - u[0]) * (r * 0.5)
            };
            pts.rotate_left(3);
            let t = [on, pts[0], pts[1]];
            if triangles_meet(&t, &u) {
                meeting += 1;
                assert!(!triangles_apart(&t, &u), "{t:?} {u:?}");
            }
        }
        assert!(meeting > 50_000, "{meeting}");
    }

    #[test]
    fn overflow_proves_nothing() {
        let big = 1e200;
        let t = [v(0., 0., 0.), v(big, 0., 0.), v(0., big, 0.)];
        let u = [v(0., 0., -1.), v(big, 0., 1.), v(0., big, 1.)];
        assert!(!triangles_apart(&t, &u));
    }
}
