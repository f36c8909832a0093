//! A separating plane between two links: a certified lower bound on their
//! distance from their hulls' corners alone, so that a motion search can
//! certify a far pair over a long interval without walking its triangles.
//!
//! # Why it is sound
//! Every point of a triangle mesh, and of the solid it bounds, is a convex
//! combination of its vertices, hence of its convex hull's corners. If
//! for some vector `a` every corner `x` of link `i` (posed) and `y` of
//! link `j` satisfy `a·x + g ≤ a·y`, the slab between the two planes
//! separates the links' hulls and their distance is at least `g / |a|`.
//! The projections are computed in floats; `kernel::separation`'s
//! argument bounds each within `γ₃ S` of the true value (`S = Σ|a_k| m_k`,
//! `m` the coordinatewise largest magnitude of every point involved).
//! [`PlaneCertificate::apart_by`] tests `fl(fl(P₁ + R) + s) < Q₀`, with
//! `P₁` the largest computed projection of `i`'s corners, `Q₀` the least
//! of `j`'s, `R = fl(reach · A)` for `A ≥ |a|` (the float length times
//! `1 + 10⁻¹²`: `sqrt` of a rounded dot product is within `3u` of it when
//! `a·a` does not underflow, and `a` is first scaled by a power of two,
//! exactly, so that its largest component lies in `[1, 2)`) and
//! `s = fl(fl(64u · fl(S + R)) + TINY)`. The two rounded additions err by
//! at most `2.01u (S(1 + γ₃) + R + s)`, `R` is at least `reach · A (1 − u)`
//! and the projections together at most `2γ₃ S` off, all within the
//! `s ≥ 63.9u (S + R)` added; so a passed test means the true gap along
//! `a` exceeds `reach · A ≥ reach · |a|`: the links are more than `reach`
//! apart. Underflow is covered by `TINY` and overflow makes `s` infinite
//! (the comparison fails), as in `kernel::separation`.
//!
//! What the test certifies is the hull of the corners as posed in floats;
//! every point of the link at the float pose lies within `pad` of it (a
//! float-posed vertex need not lie in the hull of the float-posed corners,
//! but the exactly posed one does), which the motion search's margin
//! covers, as for the swept tree test (`robot::motion`).
//!
//! # The direction
//! Any `a` is sound; a good one comes from Gilbert's iteration on the
//! difference of the two corner sets (the point of the segment from the
//! current `v` to the support point `w` nearest the origin), started from
//! the last direction that certified the pair (a warm start: the search
//! moves the links a little between calls).

use glam::{DMat3, DVec3};

use crate::hull::{convex_hull, FloatPoints};
use crate::query::rounding::norm_up;

/// The unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;

/// An absolute slack covering underflowed products (module docs).
const TINY: f64 = 1e-290;

/// Gilbert steps per direction search.
const STEPS: usize = 6;

/// A link's corners for the plane test: its convex hull's corners (all its
/// vertices when they span no volume), in its own frame, and the hull's
/// edges between them (for hill climbing; none without a hull).
#[derive(Clone, Debug)]
pub(super) struct Corners {
    points: Vec<DVec3>,
    /// Per corner, its neighbours along the hull's edges.
    neighbours: Vec<Vec<u32>>,
}

impl Corners {
    /// The hull corners of `vertices`.
    pub(super) fn new(vertices: &[DVec3]) -> Corners {
        let Ok(hull) = convex_hull(&FloatPoints(vertices)) else {
            return Corners {
                points: vertices.to_vec(),
                neighbours: Vec::new(),
            };
        };
        let points = hull.vertices.iter().map(|&k| vertices[k]).collect();
        let mut index = std::collections::HashMap::new();
        for (c, &k) in hull.vertices.iter().enumerate() {
            index.insert(k, c as u32);
        }
        let mut neighbours = vec![Vec::new(); hull.vertices.len()];
        for face in &hull.faces {
            for (k, &from) in face.iter().enumerate() {
                let to = face[(k + 1) % face.len()];
                let (a, b) = (index[&from], index[&to]);
                for (x, y) in [(a, b), (b, a)] {
                    let list: &mut Vec<u32> = &mut neighbours[x as usize];
                    if !list.contains(&y) {
                        list.push(y);
                    }
                }
            }
        }
        Corners { points, neighbours }
    }

    /// The largest norm of a corner (rounded up), which is the largest of
    /// every vertex's: how far the link reaches from its frame's origin.
    pub(super) fn largest_norm(&self) -> f64 {
        self.points.iter().map(|&p| norm_up(p)).fold(0.0, f64::max)
    }

    /// The corners moved by the matrix and translation `(m, t)` into `out`
    /// (cleared first).
    pub(super) fn pose_into(&self, (m, t): (DMat3, DVec3), out: &mut Vec<DVec3>) {
        out.clear();
        out.extend(self.points.iter().map(|&p| m * p + t));
    }

    /// The corner of `points` (these corners, posed or not) with the
    /// largest (`max`) or least projection on `v`, by climbing the hull's
    /// edges from `start` (a local extreme in floats: an estimate, for
    /// choosing a direction), or by a scan without a hull.
    fn climb(&self, points: &[DVec3], v: DVec3, start: u32, max: bool) -> (u32, f64) {
        if self.neighbours.len() != points.len() {
            return extreme(points, v, max);
        }
        let better = |d: f64, best: f64| if max { d > best } else { d < best };
        let mut at = (start as usize).min(points.len() - 1) as u32;
        let mut best = v.dot(points[at as usize]);
        loop {
            let mut moved = false;
            for &n in &self.neighbours[at as usize] {
                let d = v.dot(points[n as usize]);
                if better(d, best) {
                    (at, best) = (n, d);
                    moved = true;
                }
            }
            if !moved {
                return (at, best);
            }
        }
    }
}

/// The last good direction of one link pair, and what it found.
#[derive(Clone, Debug, Default)]
pub(super) struct PlaneCertificate {
    /// The direction that last certified the pair (in `j`'s frame).
    warm: DVec3,
    /// The least distance between two corners met by the last
    /// [`PlaneCertificate::prepare`] (floats): corners are vertices of
    /// the meshes, so the links are no farther apart than this, up to
    /// rounding.
    pub(super) nearest: f64,
    /// How far in the motion (in `t`) this pair is certified free: the
    /// motion search's per-target horizon (`robot::motion`).
    pub(super) horizon: f64,
    /// The last extreme corners (of `i`, of `j`): the climbs' start.
    start: (u32, u32),
}

impl PlaneCertificate {
    /// Looks for a direction separating `posed` (`i`'s corners posed into
    /// `j`'s frame by [`Corners::pose_into`]) from `j`'s corners; returns
    /// the float gap along it (an estimate, not a certificate:
    /// [`PlaneCertificate::apart_by`] certifies). The extremes climb the
    /// hulls' edges from the last ones. Stops looking once the gap
    /// reaches `enough`.
    pub(super) fn prepare(
        &mut self,
        posed: &[DVec3],
        i: &Corners,
        j: &Corners,
        enough: f64,
    ) -> f64 {
        let (a, b) = (posed, &j.points);
        self.nearest = f64::INFINITY;
        if a.is_empty() || b.is_empty() {
            return f64::NEG_INFINITY;
        }
        // v: a point of the difference b − a; Gilbert's step moves it
        // towards the difference's point nearest the origin. The
        // separating direction is v itself.
        let mut v = if self.warm != DVec3::ZERO {
            self.warm
        } else {
            centroid(b) - centroid(a)
        };
        let mut best = (f64::NEG_INFINITY, v);
        for _ in 0..STEPS {
            if !(v.length_squared() > 0.0 && v.is_finite()) {
                break;
            }
            let (ia, hi) = i.climb(a, v, self.start.0, true);
            let (ib, lo) = j.climb(b, v, self.start.1, false);
            self.start = (ia, ib);
            let (xa, yb) = (a[ia as usize], b[ib as usize]);
            let length = v.length();
            let gap = (lo - hi) / length;
            let w = yb - xa;
            self.nearest = self.nearest.min(w.length());
            // Within 1% of the distance between the two support points:
            // near the best a direction can do.
            let done = gap >= 0.99 * self.nearest || gap >= enough;
            if gap > best.0 {
                best = (gap, v);
            }
            // The support point of b − a towards −v, and the point of the
            // segment [v, w] nearest the origin.
            let d = w - v;
            let dd = d.length_squared();
            if done || dd == 0.0 {
                break;
            }
            let s = (-v.dot(d) / dd).clamp(0.0, 1.0);
            if s == 0.0 {
                break;
            }
            v += s * d;
        }
        self.warm = power_of_two_scaled(best.1);
        best.0
    }

    /// Whether `posed` (as given to [`PlaneCertificate::prepare`]) is
    /// certified more than `reach` from `j`'s corners along the prepared
    /// direction (module docs); `false` means "not proved".
    pub(super) fn apart_by(&self, posed: &[DVec3], j: &Corners, reach: f64) -> bool {
        let a = power_of_two_scaled(self.warm);
        if !(a.is_finite() && a != DVec3::ZERO && reach.is_finite())
            || posed.is_empty()
            || j.points.is_empty()
        {
            return false;
        }
        let (_, hi) = extreme(posed, a, true);
        let (_, lo) = extreme(&j.points, a, false);
        let mag = posed
            .iter()
            .chain(&j.points)
            .fold(DVec3::ZERO, |m, p| m.max(p.abs()));
        let big_s = a.abs().dot(mag);
        let r = reach * (a.length() * (1.0 + 1e-12));
        let slack = 64.0 * U * (big_s + r) + TINY;
        hi + r + slack < lo
    }
}

/// `v` times the power of two that brings its largest component into
/// `[1, 2)` (exact: only the exponents change), so that `v·v` neither
/// underflows nor overflows; zero and non-finite vectors as they are.
fn power_of_two_scaled(v: DVec3) -> DVec3 {
    let m = v.abs().max_element();
    if !(m.is_finite() && m > 0.0) {
        return v;
    }
    // m = f · 2^e with f in [1, 2): scale by 2^-e in two steps (each
    // exact, neither overflowing: |e| ≤ 1074).
    let e = m.log2().floor() as i32;
    let e = if m * 2f64.powi(-e / 2) * 2f64.powi(-(e - e / 2)) >= 2.0 {
        e + 1
    } else {
        e
    };
    let e = if m * 2f64.powi(-e / 2) * 2f64.powi(-(e - e / 2)) < 1.0 {
        e - 1
    } else {
        e
    };
    v * 2f64.powi(-e / 2) * 2f64.powi(-(e - e / 2))
}

/// The index of the point of `pts` with the largest (`max`) or least
/// projection on `v`, and that projection.
fn extreme(pts: &[DVec3], v: DVec3, max: bool) -> (u32, f64) {
    let mut best = (0, v.dot(pts[0]));
    for (k, &p) in pts.iter().enumerate().skip(1) {
        let d = v.dot(p);
        if (max && d > best.1) || (!max && d < best.1) {
            best = (k as u32, d);
        }
    }
    best
}

fn centroid(pts: &[DVec3]) -> DVec3 {
    pts.iter().copied().sum::<DVec3>() / pts.len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::rotation::{Pose, Rotation};

    fn cube(c: DVec3, h: f64) -> Vec<DVec3> {
        (0..8)
            .map(|k| {
                c + h * DVec3::new(
                    if k & 1 == 0 { -1.0 } else { 1.0 },
                    if k & 2 == 0 { -1.0 } else { 1.0 },
                    if k & 4 == 0 { -1.0 } else { 1.0 },
                )
            })
            .collect()
    }

    /// Two unit cubes 1 apart face to face: certified apart by less than
    /// their distance, never by it or more.
    #[test]
    fn the_gap_is_certified_below_the_distance_and_never_at_it() {
        let (a, b) = (
            Corners::new(&cube(DVec3::ZERO, 0.5)),
            Corners::new(&cube(DVec3::X * 2.0, 0.5)),
        );
        let mut posed = Vec::new();
        a.pose_into((DMat3::IDENTITY, DVec3::ZERO), &mut posed);
        let mut p = PlaneCertificate::default();
        let gap = p.prepare(&posed, &a, &b, f64::INFINITY);
        assert!((gap - 1.0).abs() < 1e-12, "{gap}");
        assert!(p.apart_by(&posed, &b, 0.999_999));
        assert!(!p.apart_by(&posed, &b, 1.0));
        // Touching: nothing is certified, not even 0.
        let c = Corners::new(&cube(DVec3::X, 0.5));
        let mut p = PlaneCertificate::default();
        p.prepare(&posed, &a, &c, f64::INFINITY);
        assert!(!p.apart_by(&posed, &c, 0.0));
    }

    /// Review (2026-11-29): a direction whose square underflows (a stale
    /// warm start near 1e-154 or below) made the length 0 and the reach
    /// vanish, so any reach passed. Directions are scaled first now.
    #[test]
    fn review_a_direction_whose_square_underflows_certifies_nothing_false() {
        let (a, b) = (
            Corners::new(&cube(DVec3::ZERO, 0.5)),
            Corners::new(&cube(DVec3::X * 3.0, 0.5)),
        );
        let mut posed = Vec::new();
        a.pose_into((DMat3::IDENTITY, DVec3::ZERO), &mut posed);
        for tiny in [1e-150, 1e-160, 1e-170, 1e-300, 5e-324] {
            let p = PlaneCertificate {
                warm: DVec3::new(tiny, 0.0, 0.0),
                ..PlaneCertificate::default()
            };
            assert!(p.apart_by(&posed, &b, 1.999), "{tiny}");
            assert!(!p.apart_by(&posed, &b, 2.0), "{tiny}");
            assert!(!p.apart_by(&posed, &b, 1e300), "{tiny}");
        }
        for v in [
            DVec3::new(3e-320, -1e-310, 0.0),
            DVec3::new(1e300, 2.0, -1e307),
            DVec3::splat(1.5),
        ] {
            let m = power_of_two_scaled(v).abs().max_element();
            assert!((1.0..2.0).contains(&m), "{v} -> {m}");
        }
    }

    /// Random posed point sets far from the origin and at tiny scales: a
    /// certified reach never exceeds the true distance between the hulls
    /// (bounded above by the distance between any two points, and by the
    /// exact-rational gap along the direction used).
    #[test]
    fn a_certificate_never_exceeds_the_distance() {
        let mut rng = crate::kernel::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1du64);
        let mut unit = move || rng.signed();
        let mut proved = 0;
        for round in 0..3000 {
            let scale = [1e-9, 1.0, 1e6][round % 3];
            let far = DVec3::splat(scale * 1e3 * unit());
            let pts = |unit: &mut dyn FnMut() -> f64, c: DVec3| -> Vec<DVec3> {
                (0..12)
                    .map(|_| c + scale * DVec3::new(unit(), unit(), unit()))
                    .collect()
            };
            let offset = far + scale * 2.2 * DVec3::new(unit(), unit(), unit());
            let (a, b) = (pts(&mut unit, far), pts(&mut unit, offset));
            let turn =
                Rotation::from_axis_angle(DVec3::new(unit(), unit(), unit()), unit()).unwrap();
            let pose = Pose::new(turn, DVec3::ZERO);
            let (ca, cb) = (Corners::new(&a), Corners::new(&b));
            let mut p = PlaneCertificate::default();
            let mut posed_corners = Vec::new();
            ca.pose_into(
                (pose.rotation.matrix(), pose.translation),
                &mut posed_corners,
            );
            let gap = p.prepare(&posed_corners, &ca, &cb, f64::INFINITY);
            if gap.is_nan() || gap <= 0.0 {
                continue;
            }
            // The distance between two points bounds the hulls' distance.
            let posed: Vec<DVec3> = a.iter().map(|&x| pose.apply(x)).collect();
            let nearest = posed
                .iter()
                .flat_map(|x| b.iter().map(move |y| (*x - *y).length()))
                .fold(f64::INFINITY, f64::min);
            for f in [0.5, 0.9, 0.999, 1.0, 1.001] {
                if p.apart_by(&posed_corners, &cb, gap * f) {
                    proved += 1;
                    assert!(gap * f < nearest * (1.0 + 1e-9), "{} >= {nearest}", gap * f);
                    assert!(f < 1.0, "certified the float gap itself: {gap}");
                }
            }
        }
        assert!(proved > 1000, "{proved}");
    }
}
