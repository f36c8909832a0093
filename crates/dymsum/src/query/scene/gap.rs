//! A certified lower bound on the distance between the convex hull of some
//! points and a triangle, for the scenes' motion search
//! ([`super::checker`]: the hull of a body triangle's corners at both ends
//! of an interval): floats propose an axis, and the bound along it is
//! rigorous.
//!
//! For any nonzero direction `n`, `(min_{y ∈ U} n·y − max_{x ∈ H} n·x) / |n|`
//! is at most the distance between the hull `H` and the triangle `U` (the
//! two sets lie in half-spaces that far apart). The directions proposed
//! are the triangle's normal (both ways; a cheap proposal that separates
//! whatever lies beside a large face), then the normals of the triangles
//! `T` (both ways: a body face sliding past the scene; on the alpha
//! puzzle's motions they settle 80% of the pairs the scene normal leaves,
//! at a quarter of the cost of the closest points), then `c_U − c_T` for the closest points of triangles `T` (the body
//! triangle at either end) and `U` found in floating point (the usual
//! vertex–triangle and edge–edge candidates), so the bound is the
//! distance up to rounding when the hull is one triangle; a bad proposal
//! only makes it smaller, never wrong. Each axis is tried both ways (one
//! pass over the points gives both gaps), and the largest magnitudes per
//! coordinate, the same for every axis, and the closest points are found
//! once per pair of triangles ([`Pair`]) for the tests of both
//! [`Pair::apart_between_ends_from`] and [`Pair::hull_apart_by_more_than`]. The dot products are rounded, and
//! the bound subtracts their error: each is off by at most
//! `γ₃ Σₖ |nₖ| |xₖ|` (`γ₃ = 3u/(1 − 3u)`, `u = 2⁻⁵³`), bounded here by
//! `4u · S`, `S = Σₖ |nₖ| maxᵢ |xᵢₖ|` over all the points, and the two
//! subtractions by `u` of their size each, plus `1e-300` for products
//! below the normal range; `n` is first scaled by a power of two to
//! components near 1 (no underflow of `|n|`), and `|n|` is rounded up by
//! a relative `8u`.
//!
//! # Edges within rounding
//! When the closest points join two edges, the direction `c_U − c_T`
//! carries their rounding divided by their distance: two unit-long edges
//! `1e-12` apart (a near-contact pose, or the end of a motion grazing
//! one) get a direction off by about `1e-4` rad, along which the edges'
//! far ends overlap by `1e-4`, and no interval next to such a pose was
//! ever certified (a motion leaving it was undecided). So the common
//! normal of those two edges, their cross product (off by a few ulps of
//! the edges' lengths, independent of their distance), is proposed too,
//! both ways. It is one more axis: the bound along it is valid as every
//! other one is, and a bad proposal only fails to certify.
//!
//! # Between the ends
//! [`apart_between_ends`] certifies a triangle that moves between two
//! sets of corners (the motion search's interval ends, `super::sweep`,
//! "Between the ends") when its points stray from their chords by at
//! most `λ(1 − λ) c` at the fraction `λ` of the way, plus a rounding `e`
//! at the ends. Along an axis `n` the gaps at the two ends, each bounded
//! below as above and less `e|n|`, are `A` and `B`, and the gap on the
//! way is at least `q(λ) = (1 − λ) A + λ B − λ(1 − λ) c|n|`. For `0 < λ <
//! 1`, `q(λ)/(λ(1 − λ)) = A/λ + B/(1 − λ) − c|n|`, whose least value is
//! `(√A + √B)² − c|n|` (at `λ = √A/(√A + √B)`), so `q > 0` on `[0, 1]`
//! exactly when `A > 0`, `B > 0` and `(√A + √B)² > c|n|`, decided with
//! its roundings by `query::interval_search`'s `bowed_chord_stays_positive`. The axes are those proposed above, for
//! both ends: the scene triangle's normal, the ends' normals, the closest
//! points of each end and the scene triangle, and their edges' common
//! normal, each both ways.
//!
//! # The axes that failed last
//! The motion search tests hundreds of neighbouring triangle pairs an
//! interval, and neighbours tend to be parted by the same kind of axis.
//! On the SO-101 finger base plate (a 23 cm bar of 12 triangles) beside
//! the finely cut SO-101 motor holder the
//! closest points' direction certified two pairs in three, each after the
//! three normals had failed. So the search keeps, per interval and per
//! frame, the axes that failed on the last pair certified, and tries them
//! last on the next ([`Pair::apart_between_ends_from`]); when an axis not
//! deferred holds, the deferred ones, not reached, stay deferred (when a
//! deferred one holds, only those that failed before it are deferred
//! next), and every eighth pair tries them all in the proposals' own
//! order again (`super::sweep`, `certified_deferring`),
//! so that a cheap normal that would hold again is not passed over for
//! long. Why no verdict changes: each axis is computed from the pair's own
//! floats ([`Pair::axis`]; the closest points once, on first need), so an
//! axis holds or not whenever it is tried, and every axis is tried until
//! one holds; the verdict is whether one does, whatever the order. Test:
//! `the_axes_deferred_change_no_verdict` (every set of deferred axes on
//! random pairs off corners and edges and touching ones; it fails when the
//! deferred axes are skipped instead of tried last). Instructions of 40
//! decisions a pair (`parts_motions`, `DECISION=1`), before → after: that
//! plate and holder 158.1 → 138.7 M (−12.3%); the TIAGo arm link 2 and
//! SO-101 wrist 212.4 → 201.8 M (−5.0%); four more pairs −0.6% to −4.0%;
//! the Z1 link 1 and TIAGo Pro wheel 128.7 → 132.4 M (+2.9%: there a normal
//! and the closest points both hold on most pairs, and a deferred normal
//! costs a closest-points search until the next eighth pair;
//! docs/BENCHMARKS.md, "The axes that failed last").
//!
//! An independent review (2026-12-02, eleventh stop) found no fault: it
//! compared every verdict with a verbatim copy of the old order on 200,000
//! random pairs of twelve kinds (coplanar, shared edges and corners, sizes
//! from 10⁻³⁰⁰ to 10¹², far from the origin, degenerate triangles, close
//! parallel planes) under all 256 masks, 51.2 million verdicts, all equal;
//! checked that each axis is tried exactly once under every mask, that the
//! tries read nothing the order changes, and the counter's packing. Its
//! remarks are applied: this section's account of which deferred axes stay
//! deferred, and a test that pins each axis to the proposal it names
//! (`each_axis_is_the_proposal_it_names`: the verdict test alone could not
//! see an axis computed wrongly, which only certifies less).
//!
//! # A box between the ends
//! [`box_apart_between_ends`] certifies at once every scene triangle of a
//! tree node against one body triangle `t` over an interval, in the body's
//! frame (`super::sweep`, "Boxes between the ends"), along the body
//! triangle's normal `n` (a float cross product: any nonzero axis bounds
//! the gap). The node's box `{c + Σ sᵢhᵢeᵢ : |sᵢ| ≤ 1} ⊕ B(fuzz)` holds its triangles
//! (`solid::obb`, "Fitting"). At an end with float matrix `M` and
//! translation `T`, the box carried exactly by them is the parallelepiped
//! `Mᵀ(c − T) + Σ sᵢhᵢMᵀeᵢ` grown by `|M| fuzz`, on which `n·x` is at
//! least `n·Mᵀ(c − T) − Σ hᵢ|n·Mᵀeᵢ| − |n| |M| fuzz` (exact: a linear
//! function's least value over a parallelepiped; no orthonormality is
//! used). The float carried centre `fl(Mᵀ fl(c − T))` is within `11u
//! (|c|∞ + |T|∞)` of `Mᵀ(c − T)` per coordinate (the subtraction, then
//! three products summed, rows of norm about 1), so `fl(n·c')` within
//! `17u |n|₁ (|c|∞ + |T|∞)` of `n·Mᵀ(c − T)`; each `fl(n·fl(Mᵀeᵢ))` within
//! `9u |n|₁` of `n·Mᵀeᵢ`, so the radius within `13u |n|₁ Σhᵢ`; the body
//! triangle's `n·pₖ` within `4u |n|₁ |p|∞`; the gap's own two
//! subtractions add about `4u |n|₁` of the same sizes; `|M| ≤ 1.01` (the
//! float matrix's spectral norm). So `64u |n|₁
//! (|c|∞ + |T_a|∞ + |T_b|∞ + Σhᵢ + fuzz + |p|∞) + 1.01 |n|₁ fuzz` covers
//! every rounding and the fuzz, and each end's gap `A`, `B` (the box's
//! least `n·x` less the triangle's largest, or the triangle's least less
//! the box's largest) less that and `rounding·|n|` (the carried points'
//! distance from the exact motion's) is a lower bound on every box
//! point's gap at that end. Between the ends each point's gap strays below
//! its chord by at most `λ(1 − λ) bow |n|` ("Between the ends" above), and
//! the least over points of the chords is at least the chord of the
//! least values, so `bowed_chord_stays_positive(A, B, bow |n|)` proves
//! every point of the box on one side of `t`'s plane at every `λ`: no
//! triangle of the node meets `t` anywhere in the interval. A carried
//! centre or radius that is not finite (an overflow near `10³⁰⁸`) proves
//! nothing.
//!
//! An independent review (2026-12-02) checked the bow (the slerp's turn
//! about a fixed axis, `w` linear with `|w'| = |ΔT|`), `ρ` between the
//! ends (a convex combination), `e'`, `Y`, the slack (about `37u` of the
//! `64u`) and the walk's use; it ran 1,141 arcs poking through body faces
//! (turns `10⁻⁴` to 3 rad, translations to 1000 times the turn's reach,
//! scales `10⁻⁶` to `10³`, offsets to `10⁶`), 824 planes bisected to the
//! lowest level certified (the least clearance left `5·10⁻⁵` of the dip),
//! 240 motions from starts `10⁻¹²` to `10⁻³` from contact and leaves of
//! four triangles: about 6.3 million certified pairs against dense
//! samples and every verdict against the search without the test, none
//! wrong. It found one fault: a centre overflowing to `+∞` near
//! `7·10³⁰⁷` read as an infinite gap, and a motion into the scene was
//! called free (pinned by `regression_an_overflowing_box_centre_proves_nothing`,
//! `super::sweep`); non-finite values now prove nothing.
//!
//! The gap is the same about any origin, so [`apart_by_more_than`] takes
//! it about the triangle's first corner `c`: far from the origin the
//! points' coordinates are large but their differences from `c` small, and
//! the dot products' error is then a few ulps of those differences, not
//! of the coordinates. Each `fl(x − c)` is within `u |fl(x − c)|ₖ/(1 − u)`
//! of `x − c` per coordinate, which moves each side's extreme dot product
//! by at most `1.01u S`: `2.02u S` more, covered by `11u S` in all.

use crate::query::interval_search::bowed_chord_stays_positive;
use crate::solid::obb::PosedObb;
use glam::DVec3;

/// `2⁻⁵³`, the unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;

/// How many axes a [`Pair`] proposes ([`Pair::axis`]).
pub(crate) const AXES: usize = 7;

/// Whether the distance between the hull of `hull` and triangle `u`
/// certainly exceeds `reach`, trying the axes proposed by the triangles
/// `near` (module docs). `false` means only "not proved".
pub(crate) fn apart_by_more_than(
    hull: &[DVec3],
    near: &[[DVec3; 3]; 2],
    u: &[DVec3; 3],
    reach: f64,
) -> bool {
    Pair::new(near, u).hull_apart_by_more_than(hull, reach)
}

/// Whether a triangle that moves from the corners `ends[0]` to the
/// corners `ends[1]` stays apart from triangle `u` all the way, when each
/// of its points runs within `rounding` of the given ends and within
/// `λ(1 − λ) bow` of the chord between them at the fraction `λ` of the way
/// (module docs, "Between the ends"). `false` means only "not proved".
#[cfg(test)]
pub(crate) fn apart_between_ends(
    ends: &[[DVec3; 3]; 2],
    u: &[DVec3; 3],
    rounding: f64,
    bow: f64,
) -> bool {
    Pair::new(ends, u).apart_between_ends(rounding, bow)
}

/// A body triangle at the two ends of an interval and a scene triangle,
/// about the scene triangle's first corner (module docs), with what the
/// tests along the proposed axes share: each triangle's largest
/// magnitudes per coordinate (for the dot products' error bound) and the
/// closest points of each end and the scene triangle, found once for
/// both [`Pair::apart_between_ends_from`] and
/// [`Pair::hull_apart_by_more_than`] (the same proposals from the same
/// floats: the answers are those of two separate calls).
pub(crate) struct Pair {
    /// The scene triangle's first corner, the origin of the others.
    origin: DVec3,
    ends: [[DVec3; 3]; 2],
    u: [DVec3; 3],
    ends_magnitudes: [DVec3; 2],
    u_magnitudes: DVec3,
    closest: [Option<Closest>; 2],
}

impl Pair {
    /// The pair of the body triangle's corners `ends` (at the interval's
    /// two ends) and scene triangle `u`.
    pub(crate) fn new(ends: &[[DVec3; 3]; 2], u: &[DVec3; 3]) -> Pair {
        let origin = u[0];
        let ends = ends.map(|t| t.map(|p| p - origin));
        let u = u.map(|p| p - origin);
        Pair {
            origin,
            ends,
            u,
            ends_magnitudes: ends.map(|t| magnitudes(&t)),
            u_magnitudes: magnitudes(&u),
            closest: [None, None],
        }
    }

    /// The closest points of end `k` and the scene triangle
    /// ([`closest_points`]), found once.
    fn closest(&mut self, k: usize) -> Closest {
        let (t, u) = (&self.ends[k], &self.u);
        *self.closest[k].get_or_insert_with(|| closest_points(t, u))
    }

    /// Axis `k` of the pair's [`AXES`] proposals (module docs): `0` the
    /// scene triangle's normal, `1` and `2` each end's normal, `3` and `5`
    /// the direction of end `0`'s and end `1`'s closest points, `4` and `6`
    /// their edges' common normal when the closest points join two edges
    /// (else `None`). Each is computed from the pair's floats alone, so
    /// the same whenever it is asked for.
    fn axis(&mut self, k: usize) -> Option<DVec3> {
        let normal = |t: &[DVec3; 3]| (t[1] - t[0]).cross(t[2] - t[0]);
        match k {
            0 => Some(normal(&self.u)),
            1 | 2 => Some(normal(&self.ends[k - 1])),
            _ => {
                let end = (k - 3) / 2;
                let closest = self.closest(end);
                if (k - 3) % 2 == 0 {
                    return Some(closest.cu - closest.ct);
                }
                // The common normal of the two edges: exact up to the
                // edges' rounding, where the closest points' direction is
                // off by their rounding over their distance (module docs,
                // "Edges within rounding").
                let (t, u) = (&self.ends[end], &self.u);
                closest
                    .edges
                    .map(|(i, j)| (t[(i + 1) % 3] - t[i]).cross(u[(j + 1) % 3] - u[j]))
            }
        }
    }

    /// The axes proposed for the pair ([`Pair::axis`]), those not in
    /// `deferred` (a set of axis numbers, bit `k` for axis `k`) first, then
    /// those in it, each part in order; `holds` is tried on each until it
    /// holds. The axis that held (or `None`) and the axes to defer for
    /// the next pair: those tried that did not hold, and, when one not
    /// deferred held, the deferred ones (not reached). Whether some axis
    /// holds does not depend on `deferred`: the same axes, each the same
    /// floats, are tried until one holds (module docs, "The axes that
    /// failed last").
    fn any_axis_from(
        &mut self,
        deferred: u8,
        mut holds: impl FnMut(&Pair, DVec3) -> bool,
    ) -> (Option<usize>, u8) {
        let mut failed = 0u8;
        for late in [false, true] {
            for k in 0..AXES {
                if (deferred >> k & 1 == 1) != late {
                    continue;
                }
                if let Some(n) = self.axis(k) {
                    if holds(self, n) {
                        // Held before the deferred ones were reached:
                        // they stay deferred.
                        let untried = if late { 0 } else { deferred };
                        return (Some(k), failed | untried);
                    }
                    failed |= 1 << k;
                }
            }
        }
        (None, failed)
    }

    /// [`Pair::any_axis_from`] in the proposals' own order.
    fn any_axis(&mut self, holds: impl FnMut(&Pair, DVec3) -> bool) -> bool {
        self.any_axis_from(0, holds).0.is_some()
    }

    /// Whether the triangle moving between the ends stays apart from the
    /// scene triangle all the way, each of its points within `rounding`
    /// of the given ends and within `λ(1 − λ) bow` of the chord between
    /// them (module docs, "Between the ends"). `false` means only "not
    /// proved".
    #[cfg(test)]
    pub(crate) fn apart_between_ends(&mut self, rounding: f64, bow: f64) -> bool {
        self.apart_between_ends_from(rounding, bow, 0).0.is_some()
    }

    /// `Pair::apart_between_ends` (the proposals' own order), the axes in
    /// `deferred` tried last
    /// ([`Pair::any_axis_from`]): the axis that certified (or `None`) and
    /// the axes to defer next. The answer is the same whatever `deferred`;
    /// only its cost changes.
    pub(crate) fn apart_between_ends_from(
        &mut self,
        rounding: f64,
        bow: f64,
        deferred: u8,
    ) -> (Option<usize>, u8) {
        self.any_axis_from(deferred, |p, n| {
            let n = normalised_scale(n);
            let u = span(&p.u, n);
            let ends = [0, 1].map(|k| {
                let mags = p.ends_magnitudes[k].max(p.u_magnitudes);
                gaps_of(span(&p.ends[k], n), u, mags, n, 3.0)
            });
            let [(a_ahead, a_behind), (b_ahead, b_behind)] = ends;
            let length = n.length();
            let (e, curve) = (times_norm(rounding, length), times_norm(bow, length));
            bowed_chord_stays_positive(a_ahead - e, b_ahead - e, curve)
                || bowed_chord_stays_positive(a_behind - e, b_behind - e, curve)
        })
    }

    /// Whether the distance between the hull of `hull` (points in the
    /// world, as the ends) and the scene triangle certainly exceeds
    /// `reach`, along the pair's axes (module docs). `false` means only
    /// "not proved".
    pub(crate) fn hull_apart_by_more_than(&mut self, hull: &[DVec3], reach: f64) -> bool {
        // About the scene triangle's first corner (module docs), on the
        // stack for hulls of at most twelve points (the motion search's).
        const MAX: usize = 12;
        let mut buf = [DVec3::ZERO; MAX];
        let heap: Vec<DVec3>;
        let hull: &[DVec3] = if hull.len() <= MAX {
            for (b, p) in buf.iter_mut().zip(hull) {
                *b = *p - self.origin;
            }
            &buf[..hull.len()]
        } else {
            heap = hull.iter().map(|p| *p - self.origin).collect();
            &heap
        };
        let mags = magnitudes(hull).max(self.u_magnitudes);
        // Every axis either way round (one pass gives both gaps).
        self.any_axis(|p, n| {
            let n = normalised_scale(n);
            let (ahead, behind) = gaps_of(span(hull, n), span(&p.u, n), mags, n, 3.0);
            let needed = reach_times_norm(reach, n);
            ahead > needed || behind > needed
        })
    }
}

/// Whether every point of a box that moves between two ends stays on one
/// side of the plane of triangle `t`, hence apart from `t`, all the way
/// (module docs, "A box between the ends"): the box `{c + Σ sᵢhᵢeᵢ : |sᵢ|
/// ≤ 1}` grown by `fuzz` carried to the first end as `fl(Mᵀ fl(c − T))`
/// and `fl(Mᵀ eᵢ)` (`start`, [`crate::solid::obb::Obb::seen_from`]);
/// `rest()` gives the same at the second end, `sizes` at least `|c|∞ +
/// |T_a|∞ + |T_b|∞`, `rounding` (each point within it of the given ends
/// as carried exactly by the float matrices) and `bow` (each point within
/// `λ(1 − λ) bow` of the chord between them at the fraction `λ` of the
/// way), read only where the first end's gap before its slack is
/// positive on some side. `false` means only "not proved".
pub(crate) fn box_apart_between_ends(
    t: &[DVec3; 3],
    start: &PosedObb,
    (h, fuzz): (DVec3, f64),
    rest: impl FnOnce() -> (PosedObb, f64, f64, f64),
) -> bool {
    let n = normalised_scale((t[1] - t[0]).cross(t[2] - t[0]));
    let l1 = n.abs().element_sum();
    if !(l1 > 0.0 && l1.is_finite()) {
        return false;
    }
    let tops = t.map(|p| n.dot(p));
    let (low, high) = (
        tops[0].min(tops[1]).min(tops[2]),
        tops[0].max(tops[1]).max(tops[2]),
    );
    // Each end's gaps ahead of the plane and behind it, before the slack
    // (which only lowers them); none where the carried centre or the
    // radius overflowed (an infinite centre would read as an infinite gap:
    // found by the independent review of 2026-12-02, scene coordinates
    // near 7·10³⁰⁷).
    let gaps = |e: &PosedObb| {
        let centre = n.dot(e.c);
        let radius =
            h.x * n.dot(e.f[0]).abs() + h.y * n.dot(e.f[1]).abs() + h.z * n.dot(e.f[2]).abs();
        if !(centre.is_finite() && radius.is_finite()) {
            return (f64::NEG_INFINITY, f64::NEG_INFINITY);
        }
        (centre - radius - high, low - (centre + radius))
    };
    let (a_ahead, a_behind) = gaps(start);
    if !(a_ahead > 0.0 || a_behind > 0.0) {
        return false;
    }
    let (end, sizes, rounding, bow) = rest();
    let (b_ahead, b_behind) = gaps(&end);
    let length = n.length();
    let corners = t[0].abs().max(t[1].abs()).max(t[2].abs()).max_element();
    // Every dot product and carried centre above, rounded, the fuzz, and
    // the points' distance from the exact motion's (module docs).
    let slack = 64.0 * U * l1 * (sizes + h.element_sum() + fuzz + corners)
        + 1.01 * l1 * fuzz
        + times_norm(rounding, length)
        + 1e-300;
    let curve = times_norm(bow, length);
    bowed_chord_stays_positive(a_ahead - slack, b_ahead - slack, curve)
        || bowed_chord_stays_positive(a_behind - slack, b_behind - slack, curve)
}

/// A lower bound on the distance between triangles `t` and `u`, within
/// rounding of it (`0` when they meet or nearly): the gap along the
/// direction of their closest points found in floating point, divided by
/// `|n|` rounded up, rounded down.
#[cfg(test)]
pub(crate) fn distance_lower_bound(t: &[DVec3; 3], u: &[DVec3; 3]) -> f64 {
    distance_lower_bound_beyond(t, u, f64::INFINITY)
}

/// A lower bound on the distance between triangles `t` and `u` from the
/// gap along `d` (scaled first, [`normalised_scale`]), divided by `|d|`
/// rounded up, rounded down; `0` without a positive gap.
fn distance_bound_along(t: &[DVec3; 3], u: &[DVec3; 3], d: DVec3) -> f64 {
    let n = normalised_scale(d);
    bound_from_gap(gap_along(t, u, n, 0.0), n)
}

/// The better of the bounds along `d` and along `−d`
/// ([`distance_bound_along`] each), in one pass over the corners: dividing
/// by the same positive `|d|` keeps the order of the two gaps.
fn distance_bound_either_way(t: &[DVec3; 3], u: &[DVec3; 3], d: DVec3) -> f64 {
    let n = normalised_scale(d);
    let (ahead, behind) = gaps_both_ways(t, u, n, 0.0);
    bound_from_gap(ahead.max(behind), n)
}

/// `gap / |n|`, `|n|` rounded up and the quotient rounded down; `0`
/// without a positive gap.
fn bound_from_gap(gap: f64, n: DVec3) -> f64 {
    if gap <= 0.0 || !gap.is_finite() {
        return 0.0;
    }
    gap / (n.length() * (1.0 + 8.0 * U)) * (1.0 - 4.0 * U)
}

/// A lower bound on the distance between triangles `t` and `u` as
/// [`distance_lower_bound`] gives it, or any lower bound of at least
/// `enough`: a caller keeping the least distance so far (`enough`) needs
/// no tighter bound for a pair that cannot lower it. So the gap along the
/// line between the triangles' centroids comes first (when it reaches
/// `enough` the closest points, most of the cost, are skipped), and the
/// edges' common normal only when the closest points' direction leaves
/// the bound below `enough`. The caller's least (`enough.min(bound)`) is
/// the same as with the full bound: each step returns early only with a
/// bound of at least `enough`.
pub(crate) fn distance_lower_bound_beyond(t: &[DVec3; 3], u: &[DVec3; 3], enough: f64) -> f64 {
    if enough.is_finite() {
        // Three times each centroid: their difference is the axis.
        let (st, su) = (t[0] + t[1] + t[2], u[0] + u[1] + u[2]);
        if centroids_apart_by(t, u, (st, su), 0.5 * enough) {
            let d = distance_bound_along(t, u, su - st);
            if d >= enough {
                return d;
            }
        }
    }
    let closest = closest_points(t, u);
    let bound = distance_bound_along(t, u, closest.cu - closest.ct);
    match closest.edges {
        // The edges' common normal, both ways (module docs, "Edges within
        // rounding"): the better of two valid bounds.
        Some((i, j)) if bound < enough => {
            let n = (t[(i + 1) % 3] - t[i]).cross(u[(j + 1) % 3] - u[j]);
            bound.max(distance_bound_either_way(t, u, n))
        }
        _ => bound,
    }
}

/// Whether the triangles' centroids are apart by `need` beyond the
/// triangles' radii about them, in floating point (a guess only: the
/// centroids' direction then proves about that much, and nothing when
/// the centroids lie within the radii), given the sums of their corners.
/// One square root: `r_t + r_u` is at most `√(2 (r_t² + r_u²))`.
fn centroids_apart_by(t: &[DVec3; 3], u: &[DVec3; 3], (st, su): (DVec3, DVec3), need: f64) -> bool {
    let third = 1.0 / 3.0;
    let (ct, cu) = (st * third, su * third);
    let radius_squared = |v: &[DVec3; 3], c: DVec3| {
        v.iter()
            .map(|p| (*p - c).length_squared())
            .fold(0.0, f64::max)
    };
    let reach = need + (2.0 * (radius_squared(t, ct) + radius_squared(u, cu))).sqrt();
    ct.distance_squared(cu) >= reach * reach
}

/// `n` scaled by a power of two (exactly, up to the last bits of components
/// far smaller than the largest: any axis is valid) so that its largest
/// component is near 1: its length neither underflows nor overflows. Zero
/// and non-finite `n` stay as they are (refused by [`gap_along`]).
fn normalised_scale(n: DVec3) -> DVec3 {
    let m = n.abs().max_element();
    if m == 0.0 || !m.is_finite() {
        return n;
    }
    // The exponent of `m` from its bits (`floor(log2 m)` for a normal
    // `m`; subnormals are scaled by 2¹⁰⁰⁰), and `2⁻ᵉ` built from bits.
    let biased = ((m.to_bits() >> 52) & 0x7ff) as i32;
    let e = if biased == 0 {
        -1000
    } else {
        (biased - 1023).clamp(-1000, 1000)
    };
    n * f64::from_bits(((1023 - e) as u64) << 52)
}

/// `reach · |n|`, rounded up.
fn reach_times_norm(reach: f64, n: DVec3) -> f64 {
    times_norm(reach, n.length())
}

/// `reach · |n|`, rounded up, for `length` the computed `|n|`.
fn times_norm(reach: f64, length: f64) -> f64 {
    reach * length * (1.0 + 8.0 * U)
}

/// A lower bound on `min_{y ∈ u} n·y − max_{x ∈ t} n·x` (module docs):
/// `−∞` for a zero or non-finite `n`. `shift` more `u S` is subtracted for
/// points that are rounded differences from an origin (module docs).
fn gap_along(t: &[DVec3], u: &[DVec3; 3], n: DVec3, shift: f64) -> f64 {
    gaps_both_ways(t, u, n, shift).0
}

/// The lower bounds of [`gap_along`] for `n` and for `−n`, in one pass
/// over the points (negating `n` negates every dot product exactly, and
/// the error bound depends on `|n|` only).
fn gaps_both_ways(t: &[DVec3], u: &[DVec3; 3], n: DVec3, shift: f64) -> (f64, f64) {
    let mags = magnitudes(t).max(magnitudes(u));
    gaps_of(span(t, n), span(u, n), mags, n, shift)
}

/// `if x < m { x } else { m }`: one machine instruction where `f64::min`
/// is several (it must return the number beside a NaN); it keeps `m`
/// beside a NaN `x` alike, and the points are finite here.
fn lesser(x: f64, m: f64) -> f64 {
    if x < m {
        x
    } else {
        m
    }
}

/// `if x > m { x } else { m }`, as [`lesser`].
fn greater(x: f64, m: f64) -> f64 {
    if x > m {
        x
    } else {
        m
    }
}

/// The least and the greatest of the computed `n·p` over `points`.
fn span(points: &[DVec3], n: DVec3) -> (f64, f64) {
    let (mut least, mut most) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in points {
        let d = n.dot(*p);
        least = lesser(d, least);
        most = greater(d, most);
    }
    (least, most)
}

/// The largest magnitude of each coordinate over `points` (`0` for none):
/// the same for every axis, so found once per set of points.
fn magnitudes(points: &[DVec3]) -> DVec3 {
    let (mut mx, mut my, mut mz) = (0.0f64, 0.0f64, 0.0f64);
    for p in points {
        mx = greater(p.x.abs(), mx);
        my = greater(p.y.abs(), my);
        mz = greater(p.z.abs(), mz);
    }
    DVec3::new(mx, my, mz)
}

/// The lower bounds of [`gap_along`] for `n` and for `−n` from the spans
/// of `n·x` over `t` and `u` ([`span`]) and the largest magnitudes `mags`
/// of each coordinate over both (`S = Σₖ |nₖ| magsₖ`, module docs): the
/// relative bounds, and an absolute one for products that fall below the
/// normal range (each off by at most 2⁻¹⁰⁷⁵); `−∞` for a zero or
/// non-finite `n`.
fn gaps_of(
    (min_t, max_t): (f64, f64),
    (min_u, max_u): (f64, f64),
    mags: DVec3,
    n: DVec3,
    shift: f64,
) -> (f64, f64) {
    if !n.is_finite() || n == DVec3::ZERO {
        return (f64::NEG_INFINITY, f64::NEG_INFINITY);
    }
    let s = n.abs().dot(mags);
    let bound =
        |gap: f64| gap - ((8.0 + shift) * U * s + 2.0 * U * gap.abs() + 1e-300) * (1.0 + 8.0 * U);
    (bound(min_u - max_t), bound(min_t - max_u))
}

/// Closest points of two triangles, in floating point (a proposal only).
///
/// The closest pair of two disjoint triangles lies on two edges or joins
/// a corner to the other's face. The edge pairs come first: when the
/// off-edge corners of both triangles lie outside the slab between the
/// planes through an edge pair's closest points, across the line joining
/// them, each triangle is on its own side of the slab and the pair is the
/// closest (Larsen et al.'s PQP `TriDist` test), so the search stops
/// there. Otherwise the corner nearest the other's plane, when that plane
/// has the whole triangle on one side and the corner's foot lies inside
/// the face, gives the closest pair; else the nearest of the edge pairs
/// does. Most pairs stop at the edge pair that holds their closest points
/// (about half the cost of trying every candidate), and the edge pair
/// whose midpoints are nearest is tried first: on robot part meshes' pairs
/// 1.7 edge pairs a call are tried, against 5.0 in the fixed order.
fn closest_points(t: &[DVec3; 3], u: &[DVec3; 3]) -> Closest {
    let mut best = Closest {
        ct: t[0],
        cu: u[0],
        edges: None,
    };
    let mut best_d = f64::INFINITY;
    // The edge pair whose midpoints are nearest is tried first: it most
    // often holds the closest points, and the slab test then stops there.
    let (mt, mu) = (
        [t[0] + t[1], t[1] + t[2], t[2] + t[0]],
        [u[0] + u[1], u[1] + u[2], u[2] + u[0]],
    );
    let mut first = 0;
    let mut first_d = f64::INFINITY;
    for k in 0..9 {
        let d = (mu[k % 3] - mt[k / 3]).length_squared();
        if d < first_d {
            (first, first_d) = (k, d);
        }
    }
    for k in (first..9).chain(0..first) {
        let (i, j) = (k / 3, k % 3);
        let (a, b) = closest_on_segments(t[i], t[(i + 1) % 3], u[j], u[(j + 1) % 3]);
        let v = b - a;
        let d = v.length_squared();
        if d <= best_d {
            best = Closest {
                ct: a,
                cu: b,
                edges: Some((i, j)),
            };
            best_d = d;
            let off_t = (t[(i + 2) % 3] - a).dot(v);
            let off_u = (u[(j + 2) % 3] - b).dot(v);
            if off_t <= 0.0 && off_u >= 0.0 {
                return best;
            }
        }
    }
    let et = [t[1] - t[0], t[2] - t[1], t[0] - t[2]];
    let eu = [u[1] - u[0], u[2] - u[1], u[0] - u[2]];
    let face = |ct, cu| Closest {
        ct,
        cu,
        edges: None,
    };
    if let Some((p, q)) = corner_over_face(t, &et, u) {
        if (q - p).length_squared() < best_d {
            return face(p, q);
        }
    }
    if let Some((q, p)) = corner_over_face(u, &eu, t) {
        if (q - p).length_squared() < best_d {
            return face(p, q);
        }
    }
    best
}

/// The closest points of two triangles found in floating point
/// ([`closest_points`]), and the edges they lie on (indices `i` of `t`'s
/// edge `t[i] t[i+1]` and `j` of `u`'s) when they join two edges.
#[derive(Clone, Copy)]
struct Closest {
    ct: DVec3,
    cu: DVec3,
    edges: Option<(usize, usize)>,
}

/// The corner of `u` nearest the plane of `t` (edges `et`) and its foot
/// on `t`, when `u` lies strictly on one side of that plane and the foot
/// falls inside `t` (in floating point): `(foot, corner)`.
fn corner_over_face(t: &[DVec3; 3], et: &[DVec3; 3], u: &[DVec3; 3]) -> Option<(DVec3, DVec3)> {
    let n = et[0].cross(et[1]);
    let nn = n.length_squared();
    if nn == 0.0 || !nn.is_finite() {
        return None;
    }
    let h = u.map(|q| (q - t[0]).dot(n));
    let k = if h.iter().all(|&x| x > 0.0) {
        (0..3).min_by(|&a, &b| h[a].total_cmp(&h[b]))?
    } else if h.iter().all(|&x| x < 0.0) {
        (0..3).max_by(|&a, &b| h[a].total_cmp(&h[b]))?
    } else {
        return None;
    };
    let q = u[k];
    let inside = (0..3).all(|e| (q - t[e]).dot(n.cross(et[e])) > 0.0);
    inside.then(|| (q - n * (h[k] / nn), q))
}

/// The point of triangle `t` closest to `p` (Ericson, *Real-Time
/// Collision Detection*, 5.1.5), in floating point (a corner for a flat
/// triangle).
// Used by the union-mesh feature's depth and by the tests' oracle.
#[cfg_attr(not(feature = "union-mesh"), allow(dead_code))]
pub(crate) fn closest_on_triangle(p: DVec3, t: &[DVec3; 3]) -> DVec3 {
    let [a, b, c] = *t;
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = va + vb + vc;
    if denom == 0.0 || !denom.is_finite() {
        return a; // flat triangle: any corner is a valid proposal
    }
    let (v, w) = (vb / denom, vc / denom);
    a + ab * v + ac * w
}

/// Closest points of segments `[p1, q1]` and `[p2, q2]` (Ericson 5.1.9),
/// in floating point.
fn closest_on_segments(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> (DVec3, DVec3) {
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (a, e, f) = (d1.length_squared(), d2.length_squared(), d2.dot(r));
    if a == 0.0 && e == 0.0 {
        return (p1, p2);
    }
    let (s, t) = if a == 0.0 {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(r);
        if e == 0.0 {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let mut s = if denom > 0.0 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            }
            (s, t)
        }
    };
    (p1 + d1 * s, p2 + d2 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [DVec3; 3] {
        [a.into(), b.into(), c.into()]
    }

    fn apart(t: &[DVec3; 3], u: &[DVec3; 3], reach: f64) -> bool {
        apart_by_more_than(t, &[*t, *t], u, reach)
    }

    #[test]
    fn a_hull_of_two_places_is_bounded_too() {
        // A triangle slid along above a floor: its two places' hull stays
        // 0.5 above it, although the places are far apart.
        let t = tri([0., 0., 0.5], [1., 0., 0.5], [0., 1., 0.5]);
        let moved = t.map(|p| p + DVec3::new(50.0, 0.0, 0.0));
        let floor = tri([-100., -100., 0.], [100., -100., 0.], [0., 100., 0.]);
        let hull: Vec<DVec3> = t.iter().chain(moved.iter()).copied().collect();
        assert!(apart_by_more_than(&hull, &[t, moved], &floor, 0.4999));
        assert!(!apart_by_more_than(&hull, &[t, moved], &floor, 0.5));
        // A wall crossed by the slide: never certified.
        let wall = tri([20., -100., -100.], [20., 100., -100.], [20., 0., 100.]);
        assert!(!apart_by_more_than(&hull, &[t, moved], &wall, 0.0));
    }

    #[test]
    fn bound_is_the_distance_up_to_rounding_and_never_above_it() {
        let t = tri([0., 0., 0.], [1., 0., 0.], [0., 1., 0.]);
        // Parallel above, at distance 0.5: certified for 0.4999, not 0.5.
        let u = tri([0., 0., 0.5], [1., 0., 0.5], [0., 1., 0.5]);
        assert!(apart(&t, &u, 0.4999));
        assert!(!apart(&t, &u, 0.5));
        // Edge to edge, crossing skew lines 1 apart.
        let v = tri([0.25, -1., 1.], [0.25, 1., 1.], [0.25, 0., 3.]);
        assert!(apart(&t, &v, 0.999_999));
        assert!(!apart(&t, &v, 1.0));
        // Touching and crossing triangles are never certified apart.
        let w = tri([0.2, 0.2, -1.], [0.2, 0.2, 1.], [3., 3., 0.]);
        assert!(!apart(&t, &w, 0.0));
        assert!(!apart(&t, &t, 0.0));
    }

    #[test]
    fn the_distance_bound_is_below_the_distance_and_close_to_it() {
        let t = tri([0., 0., 0.], [1., 0., 0.], [0., 1., 0.]);
        let v = tri([0.25, -1., 1.], [0.25, 1., 1.], [0.25, 0., 3.]);
        let d = distance_lower_bound(&t, &v);
        assert!(d <= 1.0 && d > 1.0 - 1e-14, "{d}");
        assert_eq!(distance_lower_bound(&t, &t), 0.0);
    }

    #[test]
    fn a_bound_beyond_the_best_is_still_below_the_distance() {
        // The centroids' direction settles a far pair at `enough` or more
        // without the closest points; a near pair gets the full bound.
        let t = tri([0., 0., 0.], [1., 0., 0.], [0., 1., 0.]);
        let v = tri([0.25, -1., 5.], [0.25, 1., 5.], [0.25, 0., 7.]);
        let d = distance_lower_bound_beyond(&t, &v, 1.0);
        assert!((1.0..=5.0).contains(&d), "{d}");
        assert_eq!(
            distance_lower_bound_beyond(&t, &v, 6.0),
            distance_lower_bound(&t, &v)
        );
        assert_eq!(
            distance_lower_bound_beyond(&t, &v, f64::INFINITY),
            distance_lower_bound(&t, &v)
        );
    }

    /// A point with coordinates uniform in `[−r, r)`, times `scale`.
    fn random_point(rng: &mut impl rand::Rng, r: f64, scale: f64) -> DVec3 {
        DVec3::new(
            rng.random_range(-r..r),
            rng.random_range(-r..r),
            rng.random_range(-r..r),
        ) * scale
    }

    /// A triangle of corners within 0.6 per coordinate of a centre within
    /// `centre` of the origin (the centre drawn first, then the corners).
    fn triangle_about(rng: &mut impl rand::Rng, centre: f64) -> [DVec3; 3] {
        let c = random_point(rng, centre, 1.0);
        [0; 3].map(|_| random_point(rng, 0.6, 1.0) + c)
    }

    #[test]
    fn the_least_so_far_is_the_same_as_with_the_full_bound() {
        // `distance_lower_bound_beyond` may stop early only with a bound
        // of at least `enough`: the caller's least is unchanged, on random,
        // sliver and edge-to-edge pairs and thresholds about the distance.
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(36);
        let mut early = 0;
        for k in 0..20_000 {
            let scale = 10f64.powi(k % 5 - 2);
            let mut point = |r: f64| random_point(&mut rng, r, scale);
            let t = [point(1.0), point(1.0), point(1.0)];
            let shift = point(3.0);
            let u = if k % 2 == 0 {
                [point(1.0) + shift, point(1.0) + shift, point(1.0) + shift]
            } else {
                let a = point(1.0) + shift;
                [a, a + point(1e-3), point(1.0) + shift]
            };
            let full = distance_lower_bound(&t, &u);
            for f in [0.0, 0.5, 0.999, 1.0, 1.001, 2.0, 10.0] {
                let enough = full * f + if f == 0.0 { 1e-300 } else { 0.0 };
                let got = distance_lower_bound_beyond(&t, &u, enough);
                assert_eq!(enough.min(got), enough.min(full), "{t:?} {u:?} {enough}");
                assert!(got <= full || got >= enough);
                early += usize::from(got != full);
            }
        }
        assert!(early > 1_000, "{early}");
    }

    /// A corner turning on an arc of radius 1 by `δ = 0.1` towards a wall
    /// at its apex: its ends are the sagitta `1 − cos(δ/2)` from the wall,
    /// and the bound `δ²/2` on the bow is tight there. A wall `10⁻⁶`
    /// beyond the apex is certified; one `10⁻⁹` before it, which the arc
    /// crosses, never is.
    #[test]
    fn an_arc_through_a_wall_is_never_certified_between_its_ends() {
        let delta: f64 = 0.1;
        let body = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.5, 0.1, 0.0),
            DVec3::new(0.5, -0.1, 0.0),
        ];
        let turned = |angle: f64| {
            let m = glam::DMat3::from_rotation_z(angle);
            body.map(|p| m * p)
        };
        let ends = [turned(-delta / 2.0), turned(delta / 2.0)];
        let wall = |x: f64| tri([x, -5., -5.], [x, 5., -5.], [x, 0., 5.]);
        let bow = delta * delta / 2.0 * (1.0 + 1e-12);
        assert!(apart_between_ends(&ends, &wall(1.0 + 1e-6), 1e-15, bow));
        assert!(!apart_between_ends(&ends, &wall(1.0 - 1e-9), 1e-15, bow));
        assert!(!apart_between_ends(&ends, &wall(1.0), 1e-15, bow));
        // Leaving a wall it grazes (`10⁻¹²` off), turning and moving away
        // `0.01`: certified, where the swept hull is no farther than the
        // grazing end, below the sagitta. Turning alone it leaves the wall
        // only to second order, along the arc's tangent: not certified.
        let grazing = wall(1.0 + 1e-12);
        let away = [turned(0.0), turned(-delta).map(|p| p - DVec3::X * 0.01)];
        let hull: Vec<DVec3> = away.iter().flatten().copied().collect();
        let sagitta = 2.0 * (delta / 4.0).sin().powi(2);
        assert!(!apart_by_more_than(&hull, &away, &grazing, sagitta));
        assert!(apart_between_ends(&away, &grazing, 1e-15, bow));
        let tangent = [turned(0.0), turned(-delta)];
        assert!(!apart_between_ends(&tangent, &grazing, 1e-15, bow));
    }

    /// Random triangles moving on exact screw motions (a turn about an
    /// axis through the origin, a straight translation) near random
    /// triangles: whenever `apart_between_ends` certifies a motion, the
    /// triangles meet at none of 513 times along it (exact test on the
    /// posed floats, whose rounding the `10⁻¹²` margin covers), and it
    /// certifies most of the motions that come no nearer than `10⁻³`.
    #[test]
    fn motions_certified_between_their_ends_never_meet_on_the_way() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(38);
        let (mut certified, mut clear, mut clear_certified) = (0, 0, 0);
        for k in 0..3_000 {
            let body = triangle_about(&mut rng, 2.0);
            let mut point = |r: f64| random_point(&mut rng, r, 1.0);
            let axis = point(1.0).normalize();
            let start = glam::DMat3::from_axis_angle(point(1.0).normalize(), 1.0);
            let (t0, t1) = (point(1.0), point(0.1));
            let t1 = t0 + t1;
            let delta = rng.random_range(0.0..0.4);
            let pose = |l: f64| {
                let m = start * glam::DMat3::from_axis_angle(axis, l * delta);
                let t = t0 + (t1 - t0) * l;
                body.map(|p| m * p + t)
            };
            // The scene triangle near the body's way, at a random time, a
            // random distance off.
            let at: f64 = rng.random_range(0.0..1.0);
            let off = 10f64.powi(-(k % 10)) * rng.random_range(0.5..1.0);
            let mut point = |r: f64| random_point(&mut rng, r, 1.0);
            let seed = pose(at)[k as usize % 3] + point(1.0).normalize() * off;
            let u = [seed, seed + point(0.5), seed + point(0.5)];
            let reach = body.iter().map(|p| p.length()).fold(0.0, f64::max);
            let bow = delta * delta * reach / 2.0 * (1.0 + 1e-9);
            let ok = apart_between_ends(&[pose(0.0), pose(1.0)], &u, 1e-12, bow);
            let nearest = (0..=512)
                .map(|j| {
                    let p = pose(j as f64 / 512.0);
                    if crate::solid::intersect::triangles_meet(&p, &u) {
                        0.0
                    } else {
                        closest_points_of_every_candidate(&p, &u)
                    }
                })
                .fold(f64::INFINITY, f64::min);
            if ok {
                certified += 1;
                assert!(nearest > 0.0, "certified, yet they meet: {body:?} {u:?}");
            }
            if nearest > 1e-3 {
                clear += 1;
                clear_certified += usize::from(ok);
            }
        }
        assert!(certified > 300, "{certified}");
        assert!(2 * clear_certified > clear, "{clear_certified} of {clear}");
    }

    /// Each axis is the proposal it names, bit for bit, whatever was asked
    /// before it (module docs, "Between the ends"): the scene triangle's
    /// normal, each end's normal, and per end the closest points'
    /// direction and their edges' common normal, computed here afresh
    /// about the scene triangle's first corner.
    #[test]
    fn each_axis_is_the_proposal_it_names() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(43);
        let same = |a: Option<DVec3>, b: Option<DVec3>| {
            a.map(|v| v.to_array().map(f64::to_bits)) == b.map(|v| v.to_array().map(f64::to_bits))
        };
        let mut edges = 0;
        for k in 0..2_000usize {
            let body = triangle_about(&mut rng, 1.0);
            let mut point = |r: f64| random_point(&mut rng, r, 1.0);
            let ends = [body, body.map(|p| p + point(0.3))];
            let u = if k % 2 == 0 {
                [point(0.6), point(0.6), point(0.6)]
            } else {
                // Across an edge of the first end.
                let mid = 0.5 * (body[0] + body[1]) + point(0.05);
                let d = point(1.0);
                [mid - d, mid + d, mid + point(0.5)]
            };
            let o = u[0];
            let (t, v) = (ends.map(|e| e.map(|p| p - o)), u.map(|p| p - o));
            let normal = |t: &[DVec3; 3]| (t[1] - t[0]).cross(t[2] - t[0]);
            let mut want = vec![Some(normal(&v)), Some(normal(&t[0])), Some(normal(&t[1]))];
            for e in &t {
                let c = closest_points(e, &v);
                want.push(Some(c.cu - c.ct));
                want.push(
                    c.edges
                        .map(|(i, j)| (e[(i + 1) % 3] - e[i]).cross(v[(j + 1) % 3] - v[j])),
                );
            }
            edges += [4, 6].iter().filter(|&&a| want[a].is_some()).count();
            // In order, in reverse, and each alone on a fresh pair.
            let mut forward = Pair::new(&ends, &u);
            let mut backward = Pair::new(&ends, &u);
            for a in 0..AXES {
                let b = AXES - 1 - a;
                assert!(same(forward.axis(a), want[a]), "pair {k}, axis {a}");
                assert!(
                    same(backward.axis(b), want[b]),
                    "pair {k}, axis {b} asked first"
                );
                assert!(
                    same(Pair::new(&ends, &u).axis(a), want[a]),
                    "pair {k}, axis {a} alone"
                );
            }
        }
        assert!(edges > 200, "{edges}");
    }

    /// The axes tried last change no verdict (module docs, "The axes that
    /// failed last"): for random pairs at every scale of distance, grazing
    /// and touching ones, and edge-to-edge ones, every set of deferred
    /// axes gives the answer of the proposals' own order, the axis that
    /// held is not among those to defer next, and each axis to defer next
    /// that was not deferred did not hold: it does not when tried first.
    #[test]
    fn the_axes_deferred_change_no_verdict() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(41);
        let (mut certified, mut late) = (0, 0);
        for k in 0..600usize {
            let body = triangle_about(&mut rng, 2.0);
            let mut point = |r: f64| random_point(&mut rng, r, 1.0);
            let shift = point(0.05);
            let ends = [body, body.map(|p| p + shift)];
            let off = 10f64.powi(-((k % 8) as i32)) * rng.random_range(0.5..1.0);
            let mut point = |r: f64| random_point(&mut rng, r, 1.0);
            let u = match k % 3 {
                // Off a corner.
                0 => {
                    let seed = body[k % 3] + point(1.0).normalize() * off;
                    [seed, seed + point(0.5), seed + point(0.5)]
                }
                // Across an edge: two edges nearly meeting.
                1 => {
                    let mid = 0.5 * (body[0] + body[1]) + point(1.0).normalize() * off;
                    let d = point(1.0);
                    [mid - d, mid + d, mid + point(0.5)]
                }
                // Sharing a corner of the first end: touching.
                _ => [body[0], body[0] + point(0.5), body[0] + point(0.5)],
            };
            let (rounding, bow) = (
                1e-12 * rng.random_range(0.0..2.0),
                off * rng.random_range(0.0..0.5),
            );
            let own = Pair::new(&ends, &u).apart_between_ends(rounding, bow);
            certified += usize::from(own);
            for deferred in 0..1u8 << AXES {
                let (held, failed) =
                    Pair::new(&ends, &u).apart_between_ends_from(rounding, bow, deferred);
                assert_eq!(held.is_some(), own, "pair {k}, deferred {deferred:#b}");
                if let Some(h) = held {
                    assert_eq!(failed >> h & 1, 0, "pair {k}: the axis that held failed");
                    late += usize::from(deferred >> h & 1 == 1);
                }
                // Tried and failed (the others of the set were deferred
                // and not reached).
                for j in (0..AXES).filter(|&j| failed >> j & 1 == 1 && deferred >> j & 1 == 0) {
                    let first_j = (1u8 << AXES) - 1 - (1 << j);
                    let (alone, _) =
                        Pair::new(&ends, &u).apart_between_ends_from(rounding, bow, first_j);
                    assert_ne!(alone, Some(j), "pair {k}: axis {j} said to fail holds");
                }
            }
        }
        assert!(certified > 100 && certified < 590, "{certified}");
        assert!(late > 0);
    }

    /// Every candidate of the closest pair (the six corner–face and the
    /// nine edge–edge pairs), the nearest of them: the oracle of
    /// [`closest_points`]' early stop.
    fn closest_points_of_every_candidate(t: &[DVec3; 3], u: &[DVec3; 3]) -> f64 {
        let mut best = f64::INFINITY;
        for p in t {
            best = best.min(p.distance(closest_on_triangle(*p, u)));
        }
        for q in u {
            best = best.min(q.distance(closest_on_triangle(*q, t)));
        }
        for i in 0..3 {
            for j in 0..3 {
                let (a, b) = closest_on_segments(t[i], t[(i + 1) % 3], u[j], u[(j + 1) % 3]);
                best = best.min(a.distance(b));
            }
        }
        best
    }

    #[test]
    fn the_early_stop_finds_the_nearest_candidate() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(35);
        let mut checked = 0;
        for k in 0..40_000 {
            // Spread, sliver and nearly parallel triangles at scales
            // from 1e-3 to 1e3.
            let scale = 10f64.powi(k % 7 - 3);
            let mut point = |r: f64| random_point(&mut rng, r, scale);
            let t = [point(1.0), point(1.0), point(1.0)];
            let shift = point(2.0);
            let u = match k % 3 {
                0 => [point(1.0) + shift, point(1.0) + shift, point(1.0) + shift],
                // A sliver: two corners close together.
                1 => {
                    let a = point(1.0) + shift;
                    [a, a + point(0.01), point(1.0) + shift]
                }
                // Nearly parallel to `t`, above it.
                _ => {
                    let lift = point(0.01) + shift;
                    [t[0] + lift, t[1] + lift * 1.01, t[2] + lift * 0.99]
                }
            };
            if crate::solid::intersect::triangles_meet(&t, &u) {
                continue;
            }
            checked += 1;
            let Closest { ct: p, cu: q, .. } = closest_points(&t, &u);
            let want = closest_points_of_every_candidate(&t, &u);
            let got = p.distance(q);
            assert!(
                (got - want).abs() <= 1e-9 * scale,
                "{t:?} {u:?}: {got} against {want}"
            );
        }
        assert!(checked > 20_000, "{checked}");
    }

    #[test]
    fn edges_within_rounding_of_each_other_are_certified_by_their_common_normal() {
        // Two skew edges 1e-12 apart, the triangles on either side of the
        // gap, turned and moved at random: the closest points' direction
        // is off by their rounding over 1e-12 (about 1e-4 rad), so along
        // it the unit-long edges overlap; the edges' cross product
        // certifies half the distance every time, and never the distance.
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        let gap = 1e-12;
        for _ in 0..500 {
            let axis = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            let turn = glam::DQuat::from_axis_angle(axis.normalize(), rng.random_range(0.0..3.0));
            let off = DVec3::new(rng.random_range(-2.0..2.0), 0.3, -0.7);
            let pose = |p: [f64; 3]| turn * DVec3::from(p) + off;
            let (a, b) = (rng.random_range(0.2..0.8), rng.random_range(0.2..0.8));
            let t = [[-a, 0., 0.], [1. - a, 0., 0.], [0.1, 0.3, -1.]].map(pose);
            let u = [[0., -b, gap], [0., 1. - b, gap], [0.2, -0.1, 1.]].map(pose);
            assert!(apart(&t, &u, 0.5 * gap), "{t:?} {u:?}");
            assert!(!apart(&t, &u, gap), "{t:?} {u:?}");
            let d = distance_lower_bound(&t, &u);
            assert!(d > 0.5 * gap && d <= gap, "{d}");
        }
    }

    #[test]
    fn far_from_the_origin_the_bound_stays_sound() {
        let off = 1e8;
        let t = tri([off, 0., 0.], [off + 1., 0., 0.], [off, 1., 0.]);
        let u = tri([off, 0., 1e-6], [off + 1., 0., 1e-6], [off, 1., 1e-6]);
        // 1e-6 apart, but the coordinates' rounding is about 1e-8: the
        // bound is below the distance and above zero.
        assert!(!apart(&t, &u, 1e-6));
        assert!(apart(&t, &u, 0.9e-6));
    }
}
