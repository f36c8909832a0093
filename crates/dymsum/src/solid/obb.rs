//! Oriented bounding boxes for the nodes of a box tree, and a certified
//! floating-point test that proves two of them apart (issue 35: robot
//! parts are full of long slanted triangles, and an axis-aligned box
//! around a slanted part is mostly empty; an oriented box fitted to the
//! node's corners is not).
//!
//! A node's [`Obb`] is `{c + Σ sᵢ eᵢ : |sᵢ| ≤ hᵢ}` grown by a ball of
//! radius `fuzz`: the axes `eᵢ` are the principal axes of the node's
//! triangle corners (a Jacobi eigen-decomposition of their covariance,
//! orthonormalised in floats, right-handed), `h` the half-widths of the
//! corners' projections, and `fuzz` a bound on everything rounding does to
//! that description. Like the axis-aligned boxes, an oriented box is only
//! ever used to *drop* pairs: [`Obb::apart`] answers `true` only with a
//! proof that the two boxes, hence every point they hold, are apart.
//!
//! # Soundness
//! Let `u = 2⁻⁵³`.
//!
//! **Fitting.** Any float axes will do; they are checked to be
//! orthonormal up to `β`: every `|fl(eᵢ·eⱼ) − δᵢⱼ| + 8u ≤ β ≤ 2⁻⁴⁴` (else
//! the node keeps the coordinate axes, which are exact). Each corner `p`
//! is projected as `dᵢ = fl(eᵢ·fl(p − c₀))` about the node's box centre
//! `c₀`, within `8u·D` of `eᵢ·(p − c₀)` (`D` the box's largest half-side,
//! bounding `|p − c₀|∞`). The box is the midpoint `mᵢ` and half-width `hᵢ`
//! of each projection's range, its centre `c = fl(c₀ + Σ mᵢeᵢ)` (within
//! `8u(|c₀|∞ + 3D)`). Writing `p − c₀ = E⁻ᵀ d*` with `d* = Eᵀ(p − c₀)`
//! exact and `‖E⁻ᵀ − E‖ ≤ 4β`, every corner lies within
//! `4β·3D + 16u·3D + 8u(|c₀|∞ + 3D) < 2⁻³⁸(|c₀|∞ + D)` of the box; `fuzz`
//! is that bound (rounded up, plus an absolute `10⁻³⁰⁰` for underflow).
//! `D` bounds `|p − c₀|∞` up to the rounding of `c₀` itself (`u|c₀|` and
//! an absolute subnormal term), which the `|c₀|∞` term and the absolute
//! one absorb.
//! The box holds every point of the node's triangles, since it is convex.
//!
//! **Posing.** A body node is carried by the pose's float matrix `M` and
//! translation `t`: its posed points are `fl(Mp + t)`, each coordinate
//! within the caller's `pad` of `Mp + t`. The posed box is described by
//! `c' = fl(Mc + t)` and `fᵢ = fl(M eᵢ)`; with `ω ≥ |fl(MᵀM) − I|` entrywise
//! plus `8u` (checked per query, at most `2⁻⁴⁰`, else no oriented test is
//! made), `F = [fᵢ]` is orthonormal up to about `3ω + β + 8u`
//! (`|aᵢᵀ(MᵀM − I)aⱼ| ≤ ω|aᵢ|₁|aⱼ|₁ ≤ 3ω`). The rounding of the posed
//! centre, `u(|c| + |t|)` (not `u|c'|`: `Mc + t` may cancel), is covered
//! by `pad`, which callers take at least `64ε(reach + |t|)`.
//!
//! **The test.** The fifteen separating axes of two boxes (Gottschalk,
//! Lin and Manocha's OBB tree test, as FCL's `obbDisjoint`), computed in
//! the scene box's frame from `C = [eᴮᵢ·fⱼ]` and `T = Eᴮᵀ(c' − cᴮ)`. Every
//! formula there is exact for orthonormal frames (each radius and
//! projection is taken in absolute value, so handedness is never used,
//! and a reflection would do no harm); here each frame is orthonormal up
//! to at most `2⁻³⁸` (`3ω + β`, the rounding of `C` and `T`), which moves
//! each computed projection and radius by at most `64·2⁻³⁸·S`, `S = |c'|∞ + |cᴮ|∞ + |T|₁ + Σhᴬ + Σhᴮ` (every term
//! is a sum of at most six products of a length below `S` with entries of
//! `C` or `T` that are off by at most `2⁻³⁹` relative; the constant 64
//! covers the sum's terms and their rounding). Each axis has length at
//! most `1.01`, so the fuzz balls and the posing move projections by at
//! most `1.01(fuzzᴬ + fuzzᴮ) + 2·pad`. The test declares the boxes apart
//! only when some axis shows a gap above
//! `2⁻³⁰·S + 1.01(fuzzᴬ + fuzzᴮ) + 2·pad`: 4 times what the errors can
//! take. A NaN or overflow anywhere makes every comparison fail (no
//! proof): `S` sums every length, so an infinite or NaN one makes the
//! slack infinite or NaN.
//!
//! **The gap** ([`Obb::gap`], the clearance's lower bound on a node
//! pair's distance). An axis `n` whose projections are `g > 0` apart
//! beyond the slack above puts every point pair at least `g / |n|` apart.
//! The formulas are exact for these axes: a scene face axis `eᵢ`; a body
//! face axis, `f_j` as seen through the scene frame, `n = E Eᵀ f_j`; an
//! edge axis `n = e_{i+1}(e_{i+2}·f_j) − e_{i+2}(e_{i+1}·f_j) =
//! (e_{i+1} × e_{i+2}) × f_j` (the rounding of `C` and `T` is in the
//! slack). A face axis is unit up to `2⁻³⁸`; `|E Eᵀ f_j|² ≤ 1 + 3·skew`
//! (Gershgorin, `skew ≤ 3ω + β + 8u < 2⁻³⁸`); an edge axis is at most
//! `|e_{i+1}| |e_{i+2}| |f_j|`: so `|n| ≤ 1 + 2⁻³⁶`. Over one box's three
//! face axes, orthonormal up to `2⁻³⁸`, `|x − y|² ≥ Σ gᵢ² / (1 + 2⁻³⁶)`.
//! The gap is the largest of these, divided by `1 + 2⁻²⁰`, which covers
//! `|n|`, the face sums' skew and the roundings of the squares, their
//! sum, its root and the quotient: a relative `u` each only while the
//! squares are normal numbers, so the face sums are taken of the gaps
//! scaled by their largest outside `2^±400` ([`super::aabb::gaps_norm`],
//! as the boxes' distance): a subnormal square rounds up by up to
//! `2⁻¹⁰⁷⁵`, and a square above `2¹⁰²⁴` overflows.
//! Until 2026-11-30 the gap was divided by `1.01`, the apart test's loose
//! bound on the axes' length: every node pair's bound was 1% below what
//! it proves, and a clearance query between parallel surfaces took every
//! leaf pair within 1% of the least distance.
//!
//! # The swept test
//! [`Obb::swept_apart`], for the motion search (`query::scene::sweep`):
//! over an interval every point of a body node lies within the search's
//! margin of the hull of the node's box posed at both ends and each moved
//! by the other end's translation (the swept hull of the search, for a
//! box instead of a triangle). Along an axis `n` (the scene box's face
//! axes, then the body box's posed at either end) the projections of the
//! four posed copies are the two ends' (centre `n·(c' − cᴮ)`, radius
//! `Σ hⱼ |n·fⱼ|`, exact for any `n` and orthonormal `fⱼ`, as in the
//! fifteen-axis test), and each moved by `±n·shift`; their hull projects
//! onto the range of the four, and the test declares it apart when that
//! range clears the scene box's radius `Σ hᴮᵢ |n·eᵢ|` by more than the
//! slack above (with `S` summed over both ends, `3|c' − cᴮ|₁` for
//! `|T|₁`, and `|shift|₁`, which bounds the shift's projection and its
//! rounding) plus the margin. The float shift is the search's, whose
//! rounding the search's margin covers (as it does for the triangles'
//! hulls). On the worst robot-part pairs of the motion benchmark it cut
//! the triangle pairs a walk tests by 85% to 87% (with the scene box's
//! axes alone, 28% to 83%). The nine axes share their products (`n·x`
//! taken once serves as `x·n`: the same products summed in the same
//! order, so the same floats and the same answers, pinned by
//! `the_swept_test_shares_its_products_without_changing_an_answer`): a
//! test that parts nothing takes 81 dot products instead of 108, and a
//! motion decision 3–10% fewer instructions on four robot part pairs.
//!
//! # Triangles' own boxes
//! A leaf holds at most two triangles (four in trees over 4,096 items).
//! Where a leaf's two or more triangles meet at an angle, or
//! are the two sides of a thin wall, the leaf's box is as thick as the
//! angle or the wall makes it, while each triangle is flat: a small part
//! near a big one's surface fits whole inside such a box, and the walk
//! then met every node of the small part's tree with that leaf
//! (`example-robot-data`'s Centauro hip against the TIAGo Pro arm link 6:
//! 11,000 node pairs and as many triangle pairs a state, none meeting).
//! [`Obb::of_triangle`] fits a box to one triangle's corners along the
//! triangle's own axes: its unit normal (first, so that the plane is the
//! first axis tried), its longest edge's direction, their cross product,
//! checked orthonormal within `MAX_FIT_SKEW` as the principal axes are
//! (else the coordinate axes). "Fitting" holds for any such axes, so the
//! box holds the triangle. A scene triangle's box is a scene-frame box like
//! a node's. A body triangle's box is fitted to its *posed* corners, the
//! very floats the exact test reads, so it already is a scene-frame box:
//! it enters the fifteen-axis test posed by the identity ([`Obb::unposed`],
//! `ω = 0`, the frame orthonormal within `β`) with `pad = 0`, since no
//! point of it is rounded again. A pair of a leaf and an *inner* node
//! whose boxes were not parted is dropped when *every* triangle of the
//! leaf is proven apart from the node's box: each triangle pair below it
//! has one of those triangles and a triangle inside that box (a scene
//! node's box holds its triangles within its fuzz, "Fitting"; a body
//! node's posed box holds the posed corners within fuzz and `pad`,
//! "Posing"); the walk drops every item pair below a node pair it drops,
//! and `AabbTree::leaf_items` is the range it reads. The state check tries
//! this only where the leaf's box is thicker (its least half-width) than
//! the other node's box is wide (its largest): against a wider node the
//! flat boxes part about as seldom as the leaf's did; a scene leaf also
//! needs the pose to pass [`pose_skew`], as every oriented test does. The
//! boxes are kept in a small direct-mapped cache
//! (`query::scene::checker`): a scene triangle's for every query, a body
//! triangle's for its query's epoch (the cache is reset where the epoch
//! restarts at 1, in `fit_node_cache`, which follows every query's
//! start). Edges are scaled before the normal's cross product, so the
//! box is flat at every scale. An independent review (2026-11-30)
//! checked every step and found it sound: 29,119 triangles' boxes checked
//! in exact rationals (collinear, repeated, subnormal and `10^±300`
//! corners, offsets to `10¹⁶` times the size: no corner outside, at most
//! `1.6·10⁻⁴` of the fuzz used), and 646,194 states of folds, closing
//! wedges, thin reversed walls (gaps to `10⁻¹²` relative) and needles
//! against slivers, both ways round, scales `10^±150`, all agreeing with
//! `surfaces_touch`, with the 3,476,614 triangle pairs below the dropped
//! node pairs checked exactly (none meet); dropping a leaf when *any*
//! triangle is apart gave 662 wrong answers. On that
//! pair the state checks' instructions fell 21-fold (docs/BENCHMARKS.md,
//! "Triangles' own boxes").
//!
//! # Independent review (2026-11-30): the gap
//! A second reading checked "The gap" against an exact rational oracle:
//! 120,000 node pairs of one to three triangles (parallel planes, slanted,
//! axis-aligned and exact copies; crossing needles, points, segments,
//! slivers), scales `10⁻³⁰⁰`–`10²⁹⁰`, offsets to `10⁸` times the scale,
//! identity, exact and near 90° turns and skew near `2⁻⁴⁰`, the true
//! distance taken exactly over the fifteen feature pairs of the triangles
//! the boxes were fitted to. In the normal range no gap exceeded it (the
//! largest ratio 0.99999904). It found the gap unsound at the extremes,
//! as it had been with `1.01`: face sums squared without scaling gave
//! `∞` beyond `2⁵¹¹` (10,188 cases) and rounded subnormal squares up
//! below `2⁻⁵²⁸` (491 cases, up to 1.40 times the distance), and
//! `distance_at` returned clearances above the true distance for sliver
//! soups scaled by `2⁻⁵⁴⁰` (1.157×) and `2⁶⁰⁰` (8.8×). Mended by the
//! scaled sums above; the oracle then found no failure in another
//! 120,000 cases, and `tests/clearance_scale.rs` pins the end-to-end
//! check. Its wording remarks (the axes spelled out, the Gershgorin
//! bound, the squares' range) are applied above.
//!
//! # Independent review (2026-11-29)
//! A second reading checked the fitting (23,000 adversarial point clouds:
//! collinear, coincident, slivers, scales `10⁻³²⁰` to `10²⁵⁰`, offsets to
//! `10¹⁰⁰`, each corner's distance to the grown box measured in exact
//! rationals: at most `10⁻⁴` of the fuzz used), the fifteen-axis test
//! (touching pairs sharing an exact float point, rotations at the skew
//! limit and reflections: 3,152 of 20,000 falsely proven apart with zero
//! slack, none of 120,000 with the real slack, which they use at most
//! `3·10⁻⁴` of), the containment filters and the motion search's swept
//! reach. It found one wrong answer, mended: the swept reach took
//! Euclidean norms, whose squares underflow for bodies below `10⁻¹⁵⁴`,
//! and called a colliding motion of a body of size `10⁻¹⁶⁵` free (then
//! sums of magnitudes; since, norms of the vector or matrix scaled by its
//! largest magnitude, `query::rounding`; `tests/oriented_boxes.rs` pins
//! it). It also
//! corrected the skew bound (`3ω + β`, above), the note on handedness and
//! on the posed centre's rounding, and added an absolute floor to the
//! containment filter's pad.

use glam::{DMat3, DVec3};

use super::aabb::{gaps_norm, Aabb, AabbTree};

const U: f64 = f64::EPSILON / 2.0;
/// Frames further from orthonormal than this are not used.
const MAX_SKEW: f64 = 1.0 / (1u64 << 40) as f64;
/// The fitted axes must be orthonormal within this (else coordinate axes).
const MAX_FIT_SKEW: f64 = 1.0 / (1u64 << 44) as f64;
/// The test's relative slack (module docs).
const SLACK: f64 = 1.0 / (1u64 << 30) as f64;
/// The fitting's relative fuzz (module docs).
const FUZZ: f64 = 1.0 / (1u64 << 38) as f64;
/// A bound on every separating axis's length, rounding included, for
/// [`Obb::gap`] (the apart test's slack uses `1.01`, looser than it needs).
const AXIS_LENGTH: f64 = 1.0 + 1.0 / (1u64 << 20) as f64;
/// Absolute fuzz, for underflow.
const TINY: f64 = 1e-300;

/// An oriented box grown by a ball (module docs).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Obb {
    pub c: DVec3,
    pub axes: [DVec3; 3],
    pub h: DVec3,
    pub fuzz: f64,
}

/// A body node's box at a pose: the centre `fl(Mc + t)` and the axes
/// `fl(M eᵢ)`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PosedObb {
    pub c: DVec3,
    pub f: [DVec3; 3],
}

/// How far a pose's matrix is from orthonormal (`ω` of the module docs),
/// or `None` when more than the test allows (then no oriented test is
/// made for that pose).
pub(crate) fn pose_skew(m: &DMat3) -> Option<f64> {
    let g = m.transpose() * *m;
    let cols = [g.x_axis, g.y_axis, g.z_axis];
    let mut w = 0.0f64;
    for (j, c) in cols.iter().enumerate() {
        for i in 0..3 {
            let d = c[i] - if i == j { 1.0 } else { 0.0 };
            w = w.max(d.abs());
        }
    }
    let w = w + 8.0 * U;
    (w <= MAX_SKEW).then_some(w)
}

impl Obb {
    /// The box fitted to `points` (at least one), whose axis-aligned box
    /// is `around` (module docs).
    pub fn fit(points: &[DVec3], around: &Aabb) -> Obb {
        let (lo, hi) = (DVec3::from(around.lo), DVec3::from(around.hi));
        let c0 = 0.5 * lo + 0.5 * hi;
        let axes = principal_axes(points, c0).unwrap_or([DVec3::X, DVec3::Y, DVec3::Z]);
        Obb::fit_along(points, around, axes)
    }

    /// The box of one triangle (module docs, "Triangles' own boxes"): its
    /// unit normal first, then its longest edge's direction and their
    /// cross product, so that the box is flat; the coordinate axes when
    /// these are not orthonormal within `MAX_FIT_SKEW` (a degenerate
    /// triangle).
    pub fn of_triangle(t: &[DVec3; 3]) -> Obb {
        let around = Aabb::of(t.iter().map(|p| p.to_array()));
        let axes = triangle_axes(t).unwrap_or([DVec3::X, DVec3::Y, DVec3::Z]);
        Obb::fit_along(t, &around, axes)
    }

    /// This box as a posed one at the identity (its points are where they
    /// are: no rounding to cover, `pad` zero, [`Obb::apart`]'s `a`).
    #[inline]
    pub fn unposed(&self) -> PosedObb {
        PosedObb {
            c: self.c,
            f: self.axes,
        }
    }

    /// The box of `points` along `axes` (orthonormal within
    /// `MAX_FIT_SKEW`: module docs, "Fitting"), whose axis-aligned box is
    /// `around`.
    fn fit_along(points: &[DVec3], around: &Aabb, axes: [DVec3; 3]) -> Obb {
        let (lo, hi) = (DVec3::from(around.lo), DVec3::from(around.hi));
        let c0 = 0.5 * lo + 0.5 * hi;
        let d = (0.5 * hi - 0.5 * lo).max_element();
        let (mut plo, mut phi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for &p in points {
            let q = p - c0;
            let d = DVec3::new(axes[0].dot(q), axes[1].dot(q), axes[2].dot(q));
            plo = plo.min(d);
            phi = phi.max(d);
        }
        let m = 0.5 * plo + 0.5 * phi;
        let h = 0.5 * phi - 0.5 * plo;
        let c = c0 + axes[0] * m.x + axes[1] * m.y + axes[2] * m.z;
        let fuzz = FUZZ * (c0.abs().max_element() + d) * (1.0 + 1e-9) + TINY;
        Obb { c, axes, h, fuzz }
    }

    /// Whether the box holds `p`, checked in floats with twice the fuzz
    /// (for [`crate::body::MeshBody::sanity_check`]: a fitted box that
    /// misses a corner by more than its rounding is a bug).
    pub fn holds(&self, p: DVec3) -> bool {
        let q = p - self.c;
        (0..3).all(|i| self.axes[i].dot(q).abs() <= self.h[i] + 2.0 * self.fuzz)
    }

    /// Whether `p`, known up to `pad` per coordinate (a point within `pad`
    /// of `p` on every axis is meant), is proven outside the box: some
    /// axis shows it beyond the half-width by more than the box's fuzz,
    /// the axes' skew and the rounding of the projection can account for
    /// (module docs' `2⁻³⁰` relative slack). `false` proves nothing.
    #[inline]
    pub fn excludes(&self, p: DVec3, pad: f64) -> bool {
        let q = p - self.c;
        let slack = SLACK
            * (p.abs().max_element() + self.c.abs().max_element() + self.h.element_sum())
            + 1.01 * self.fuzz
            + 2.0 * pad;
        (0..3).any(|i| self.axes[i].dot(q).abs() > self.h[i] + slack)
    }

    /// This (body-frame) box at the pose `x ↦ m x + t`.
    #[inline]
    pub fn posed(&self, m: &DMat3, t: DVec3) -> PosedObb {
        PosedObb {
            c: *m * self.c + t,
            f: [*m * self.axes[0], *m * self.axes[1], *m * self.axes[2]],
        }
    }

    /// This (scene-frame) box seen from a frame posed at `x ↦ M x + t`,
    /// given `m_t = Mᵀ`: the centre `fl(Mᵀ fl(c − t))` and the axes
    /// `fl(Mᵀ eᵢ)` (the motion search's boxes in the body's frame,
    /// `query::scene::gap`'s `box_apart_between_ends`).
    #[inline]
    pub fn seen_from(&self, m_t: &DMat3, t: DVec3) -> PosedObb {
        PosedObb {
            c: *m_t * (self.c - t),
            f: [
                *m_t * self.axes[0],
                *m_t * self.axes[1],
                *m_t * self.axes[2],
            ],
        }
    }

    /// Whether `a` (a body node's box, posed; `fuzz_a` its fuzz, `ha` its
    /// half-widths) is proven apart from this (scene-frame) box; `pad`
    /// bounds the rounding of posing each point, per coordinate (module
    /// docs). `false` proves nothing.
    #[inline]
    pub fn apart(&self, a: &PosedObb, ha: DVec3, fuzz_a: f64, pad: f64) -> bool {
        let mut apart = false;
        self.axis_gaps(a, ha, fuzz_a, pad, |_, gap| {
            apart = gap > 0.0;
            apart
        });
        apart
    }

    /// The slack of [`Obb::swept_apart`] before its margin (module docs,
    /// "The swept test"): the relative slack of the sizes summed over both
    /// ends (`3|c' − cᴮ|₁` for `|T|₁`) and the shift, both boxes' fuzz and
    /// the posing's pad.
    fn swept_slack(
        &self,
        ends: [&PosedObb; 2],
        shift: DVec3,
        ha: DVec3,
        fuzz_a: f64,
        pad: f64,
    ) -> f64 {
        let sizes = |a: &PosedObb| {
            a.c.abs().max_element() + 3.0 * (a.c - self.c).abs().element_sum() + ha.element_sum()
        };
        let s = sizes(ends[0])
            + sizes(ends[1])
            + self.c.abs().max_element()
            + self.h.element_sum()
            + shift.abs().element_sum();
        SLACK * s + 1.01 * (fuzz_a + self.fuzz) + 2.0 * pad
    }

    /// Whether the hull of a body node's box posed at both ends of an
    /// interval (`ends`, each as [`Obb::apart`]'s `a`) and each moved by
    /// the float difference `shift` of the end translations (the first
    /// forwards, the second back), grown by `margin`, is proven apart from
    /// this box along one of nine axes: this box's face axes, then the
    /// body box's at either end (module docs, "The swept test"). `false`
    /// proves nothing.
    #[inline]
    pub fn swept_apart(
        &self,
        ends: [&PosedObb; 2],
        shift: DVec3,
        ha: DVec3,
        fuzz_a: f64,
        pad: f64,
        margin: f64,
    ) -> bool {
        let hb = self.h.to_array();
        let slack = self.swept_slack(ends, shift, ha, fuzz_a, pad) + margin;
        let (ca, cb) = (ends[0].c - self.c, ends[1].c - self.c);
        // Along `n`, given `|n·eₖ|` (this box's axes), `|n·fₘ|` at either
        // end.
        let apart_along = |n: DVec3, to_e: [f64; 3], to_a: [f64; 3], to_b: [f64; 3]| {
            let d = n.dot(shift);
            let hb = hb[0] * to_e[0] + hb[1] * to_e[1] + hb[2] * to_e[2];
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for (c, moved, to_f) in [(ca, d, to_a), (cb, -d, to_b)] {
                let t = n.dot(c);
                let r = ha.x * to_f[0] + ha.y * to_f[1] + ha.z * to_f[2];
                for t in [t, t + moved] {
                    lo = lo.min(t - r);
                    hi = hi.max(t + r);
                }
            }
            lo - hb > slack || -hi - hb > slack
        };
        // This box's face axes, then the body box's at either end. The
        // axes' products are shared between them (`n·x` and `x·n` are the
        // same products summed in the same order: the same floats), so an
        // axis of the second end takes half the dot products of one of
        // this box's.
        let (e, fa, fb) = (&self.axes, &ends[0].f, &ends[1].f);
        let abs_dots = |n: DVec3, x: &[DVec3; 3]| x.map(|x| n.dot(x).abs());
        let (mut e_a, mut e_b, mut a_b) = ([[0.0; 3]; 3], [[0.0; 3]; 3], [[0.0; 3]; 3]);
        for i in 0..3 {
            (e_a[i], e_b[i]) = (abs_dots(e[i], fa), abs_dots(e[i], fb));
            if apart_along(e[i], abs_dots(e[i], e), e_a[i], e_b[i]) {
                return true;
            }
        }
        for j in 0..3 {
            a_b[j] = abs_dots(fa[j], fb);
            let to_e = [e_a[0][j], e_a[1][j], e_a[2][j]];
            if apart_along(fa[j], to_e, abs_dots(fa[j], fa), a_b[j]) {
                return true;
            }
        }
        (0..3).any(|j| {
            let to_e = [e_b[0][j], e_b[1][j], e_b[2][j]];
            let to_a = [a_b[0][j], a_b[1][j], a_b[2][j]];
            apart_along(fb[j], to_e, to_a, abs_dots(fb[j], fb))
        })
    }

    /// A certified lower bound on the distance between every point of `a`
    /// and every point of this box (arguments as [`Obb::apart`]), from the
    /// fifteen axes' gaps beyond their slack (`gᵢ`, kept when positive):
    /// along an axis `n` the two boxes' projections are at least `gᵢ`
    /// apart, so `|x − y| ≥ gᵢ / |n|`, and over a box's three face axes,
    /// orthonormal up to `2⁻³⁸`, `|x − y|² ≥ Σ gᵢ² / (1 + 2⁻³⁶)`. The
    /// largest of the two face-axis sums' roots and the nine edge axes'
    /// gaps, divided by `1 + 2⁻²⁰` (`AXIS_LENGTH`): no axis is longer
    /// than `1 + 2⁻³⁶` (face axes orthonormal up to `2⁻³⁸`, an edge axis
    /// the cross product of two of them), and the sums (of the gaps
    /// scaled where their squares would not be normal, `gaps_norm`), their
    /// roots and the quotient add a few `u`; `0` when no axis shows a gap.
    #[inline]
    pub fn gap(&self, a: &PosedObb, ha: DVec3, fuzz_a: f64, pad: f64) -> f64 {
        let (mut faces, mut edges) = ([0.0f64; 6], 0.0f64);
        self.axis_gaps(a, ha, fuzz_a, pad, |axis, gap| {
            let gap = gap.max(0.0);
            match axis {
                0..=5 => faces[axis] = gap,
                _ => edges = edges.max(gap),
            }
            false
        });
        let [a0, a1, a2, b0, b1, b2] = faces;
        gaps_norm([a0, a1, a2])
            .max(gaps_norm([b0, b1, b2]))
            .max(edges)
            / AXIS_LENGTH
    }

    /// Each of the fifteen separating axes' projected gap between `a` and
    /// this box less the slack of the module docs (positive: a certified
    /// gap along that axis), to `visit` with the axis's number (0–2 this
    /// box's face axes, 3–5 `a`'s, 6–14 the edge axes), until it returns
    /// `true`.
    #[inline]
    fn axis_gaps(
        &self,
        a: &PosedObb,
        ha: DVec3,
        fuzz_a: f64,
        pad: f64,
        mut visit: impl FnMut(usize, f64) -> bool,
    ) {
        // Unrolled by hand, in scalars: the loops over index arrays (and
        // `[T; N]::map`, which is not inlined) took about a tenth more
        // instructions a test, and the state checks of a seeded sample of
        // robot part pairs 5% more in all (docs/BENCHMARKS.md, "Oriented
        // boxes unrolled"); every product and sum below is the loops' own,
        // in the same order, so each gap is the same float (the test
        // `unrolled_axes_are_the_loops_bit_for_bit`).
        let [e0, e1, e2] = self.axes;
        let [f0, f1, f2] = a.f;
        let d = a.c - self.c;
        let (t0, t1, t2) = (e0.dot(d), e1.dot(d), e2.dot(d));
        // cij = eᵢ·fⱼ, aij its absolute value.
        let (c00, c01, c02) = (e0.dot(f0), e0.dot(f1), e0.dot(f2));
        let (c10, c11, c12) = (e1.dot(f0), e1.dot(f1), e1.dot(f2));
        let (c20, c21, c22) = (e2.dot(f0), e2.dot(f1), e2.dot(f2));
        let (a00, a01, a02) = (c00.abs(), c01.abs(), c02.abs());
        let (a10, a11, a12) = (c10.abs(), c11.abs(), c12.abs());
        let (a20, a21, a22) = (c20.abs(), c21.abs(), c22.abs());
        let (ha0, ha1, ha2) = (ha.x, ha.y, ha.z);
        let (hb0, hb1, hb2) = (self.h.x, self.h.y, self.h.z);
        let s = a.c.abs().max_element()
            + self.c.abs().max_element()
            + t0.abs()
            + t1.abs()
            + t2.abs()
            + ha0
            + ha1
            + ha2
            + hb0
            + hb1
            + hb2;
        let slack = SLACK * s + 1.01 * (fuzz_a + self.fuzz) + 2.0 * pad;
        macro_rules! axis {
            ($n:expr, $gap:expr) => {
                if visit($n, $gap) {
                    return;
                }
            };
        }
        // The scene box's axes: |tᵢ| against hbᵢ + Σⱼ haⱼ aᵢⱼ.
        axis!(
            0,
            t0.abs() - (hb0 + (ha0 * a00 + ha1 * a01 + ha2 * a02) + slack)
        );
        axis!(
            1,
            t1.abs() - (hb1 + (ha0 * a10 + ha1 * a11 + ha2 * a12) + slack)
        );
        axis!(
            2,
            t2.abs() - (hb2 + (ha0 * a20 + ha1 * a21 + ha2 * a22) + slack)
        );
        // The body box's axes: |Σᵢ tᵢ cᵢⱼ| against haⱼ + Σᵢ hbᵢ aᵢⱼ.
        macro_rules! body_axis {
            ($n:expr, $haj:expr, $c0:ident, $c1:ident, $c2:ident, $a0:ident, $a1:ident, $a2:ident) => {
                let rb = hb0 * $a0 + hb1 * $a1 + hb2 * $a2;
                let p = t0 * $c0 + t1 * $c1 + t2 * $c2;
                axis!($n, p.abs() - ($haj + rb + slack));
            };
        }
        body_axis!(3, ha0, c00, c10, c20, a00, a10, a20);
        body_axis!(4, ha1, c01, c11, c21, a01, a11, a21);
        body_axis!(5, ha2, c02, c12, c22, a02, a12, a22);
        // eᵢ × fⱼ, with (i1, i2) = (i + 1, i + 2) and (k, l) = (j + 1,
        // j + 2) mod 3: p = t[i2] c[i1][j] − t[i1] c[i2][j],
        // rb = hb[i1] a[i2][j] + hb[i2] a[i1][j],
        // ra = ha[k] a[i][l] + ha[l] a[i][k].
        macro_rules! edge_axis {
            ($n:expr, $ti1:ident, $ti2:ident, $hbi1:ident, $hbi2:ident,
             $ci1j:ident, $ci2j:ident, $ai1j:ident, $ai2j:ident,
             $hak:ident, $hal:ident, $ail:ident, $aik:ident) => {
                let p = $ti2 * $ci1j - $ti1 * $ci2j;
                let rb = $hbi1 * $ai2j + $hbi2 * $ai1j;
                let ra = $hak * $ail + $hal * $aik;
                axis!($n, p.abs() - (ra + rb + slack));
            };
        }
        // i = 0: i1 = 1, i2 = 2.
        edge_axis!(6, t1, t2, hb1, hb2, c10, c20, a10, a20, ha1, ha2, a02, a01);
        edge_axis!(7, t1, t2, hb1, hb2, c11, c21, a11, a21, ha2, ha0, a00, a02);
        edge_axis!(8, t1, t2, hb1, hb2, c12, c22, a12, a22, ha0, ha1, a01, a00);
        // i = 1: i1 = 2, i2 = 0.
        edge_axis!(9, t2, t0, hb2, hb0, c20, c00, a20, a00, ha1, ha2, a12, a11);
        edge_axis!(10, t2, t0, hb2, hb0, c21, c01, a21, a01, ha2, ha0, a10, a12);
        edge_axis!(11, t2, t0, hb2, hb0, c22, c02, a22, a02, ha0, ha1, a11, a10);
        // i = 2: i1 = 0, i2 = 1.
        edge_axis!(12, t0, t1, hb0, hb1, c00, c10, a00, a10, ha1, ha2, a22, a21);
        edge_axis!(13, t0, t1, hb0, hb1, c01, c11, a01, a11, ha2, ha0, a20, a22);
        edge_axis!(14, t0, t1, hb0, hb1, c02, c12, a02, a12, ha0, ha1, a21, a20);
    }
}

/// The principal axes of `points` about `c0` (orthonormal within
/// `MAX_FIT_SKEW`, right-handed), or `None` when they cannot be had.
fn principal_axes(points: &[DVec3], c0: DVec3) -> Option<[DVec3; 3]> {
    let mut cov = [[0.0f64; 3]; 3];
    let mut mean = DVec3::ZERO;
    for &p in points {
        mean += p - c0;
    }
    mean /= points.len() as f64;
    for &p in points {
        let q = (p - c0 - mean).to_array();
        for (i, row) in cov.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x += q[i] * q[j];
            }
        }
    }
    let v = jacobi_eigenvectors(cov)?;
    // The largest spread first: Gram–Schmidt keeps it exact-ish.
    let e0 = v[0].try_normalize()?;
    let e1 = (v[1] - e0 * e0.dot(v[1])).try_normalize()?;
    let e2 = e0.cross(e1).try_normalize()?;
    orthonormal([e0, e1, e2])
}

/// A triangle's unit normal, its longest edge's direction and their cross
/// product (right-handed, orthonormal within `MAX_FIT_SKEW`), or `None`
/// for a triangle too degenerate to have them.
fn triangle_axes(t: &[DVec3; 3]) -> Option<[DVec3; 3]> {
    let edges = [t[1] - t[0], t[2] - t[1], t[0] - t[2]];
    let longest = (0..3)
        .max_by(|&a, &b| {
            edges[a]
                .length_squared()
                .total_cmp(&edges[b].length_squared())
        })
        .unwrap_or(0);
    // The edges scaled by the longest's largest coordinate before the
    // cross product, whose squared length would under- or overflow for
    // edges beyond about 10^±77 (the box would then keep the coordinate
    // axes: sound, but not flat).
    let scale = 1.0 / edges[longest].abs().max_element();
    let (a, b) = (edges[longest] * scale, edges[(longest + 1) % 3] * scale);
    let e = a.try_normalize()?;
    let n = a.cross(b).try_normalize()?;
    let n = (n - e * e.dot(n)).try_normalize()?;
    let f = n.cross(e).try_normalize()?;
    orthonormal([n, e, f])
}

/// `axes` when every `|fl(eᵢ·eⱼ) − δᵢⱼ| + 8u ≤ MAX_FIT_SKEW` (module
/// docs, "Fitting"), else `None`.
fn orthonormal(axes: [DVec3; 3]) -> Option<[DVec3; 3]> {
    for i in 0..3 {
        for j in 0..3 {
            let want = if i == j { 1.0 } else { 0.0 };
            let off = (axes[i].dot(axes[j]) - want).abs() + 8.0 * U;
            if off.is_nan() || off > MAX_FIT_SKEW {
                return None;
            }
        }
    }
    Some(axes)
}

/// The eigenvectors of a symmetric 3×3 matrix (cyclic Jacobi), the one of
/// the largest eigenvalue first, then the next.
fn jacobi_eigenvectors(mut a: [[f64; 3]; 3]) -> Option<[DVec3; 3]> {
    if a.iter().flatten().any(|x| !x.is_finite()) {
        return None;
    }
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..32 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let diag = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off <= 1e-15 * diag || off == 0.0 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let cs = 1.0 / (t * t + 1.0).sqrt();
            let sn = t * cs;
            // a ← Jᵀ a J, v ← v J.
            let turn = |x: f64, y: f64| (cs * x - sn * y, sn * x + cs * y);
            for row in a.iter_mut().chain(v.iter_mut()) {
                (row[p], row[q]) = turn(row[p], row[q]);
            }
            let (rp, rq) = (a[p], a[q]);
            a[p] = std::array::from_fn(|k| turn(rp[k], rq[k]).0);
            a[q] = std::array::from_fn(|k| turn(rp[k], rq[k]).1);
        }
    }
    let mut order = [0usize, 1, 2];
    order.sort_by(|&x, &y| a[y][y].total_cmp(&a[x][x]));
    let col = |k: usize| DVec3::new(v[0][k], v[1][k], v[2][k]);
    let out = order.map(col);
    out.iter().all(|c| c.is_finite()).then_some(out)
}

/// One oriented box per node of `tree`, fitted to the corners of the
/// node's items (`corners(i)` the triangle of item `i`).
pub(crate) fn node_obbs(tree: &AabbTree, corners: impl Fn(usize) -> [DVec3; 3]) -> Vec<Obb> {
    let spans = tree.node_spans();
    let items = tree.items();
    let bounds = tree.bounds();
    let mut pts = Vec::new();
    spans
        .iter()
        .enumerate()
        .map(|(n, &(s, e))| {
            pts.clear();
            pts.extend(
                items[s as usize..e as usize]
                    .iter()
                    .flat_map(|&i| corners(i as usize)),
            );
            Obb::fit(&pts, &bounds[n])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::rotation::{Pose, Rotation};
    use crate::solid::intersect::triangles_meet;

    /// The body triangle's and the scene triangle's fitted boxes, and the
    /// posing's rounding pad at translation `t` (as the scene checker
    /// takes it).
    fn fitted_with_pad(body: &[DVec3; 3], u: &[DVec3; 3], t: DVec3) -> (Obb, Obb, f64) {
        let pad = 64.0
            * f64::EPSILON
            * (body
                .iter()
                .map(|p| p.abs().max_element())
                .fold(0.0, f64::max)
                * 1.8
                + t.abs().max_element());
        let ob = Obb::fit(body, &Aabb::of(body.map(|p| p.to_array())));
        let os = Obb::fit(u, &Aabb::of(u.map(|p| p.to_array())));
        (ob, os, pad)
    }

    /// A random pose `(m, t)` and a body triangle in its own frame, posed
    /// back by the pose's inverse so that posing it (as a query would)
    /// puts a corner near `on` and the others within `scale` of it: the
    /// pose, the body triangle and its posed corners.
    fn body_through(
        unit: &mut impl FnMut() -> f64,
        on: DVec3,
        scale: f64,
    ) -> (DMat3, DVec3, [DVec3; 3], [DVec3; 3]) {
        let rot =
            Rotation::from_axis_angle(DVec3::new(unit(), unit(), unit()), 3.0 * unit()).unwrap();
        let (m, t) = (rot.matrix(), DVec3::new(unit(), unit(), unit()) * scale);
        let (mi, ti) = (m.transpose(), -(m.transpose() * t));
        let body = [
            mi * on + ti,
            mi * (on + DVec3::new(unit(), unit(), unit()) * scale) + ti,
            mi * (on + DVec3::new(unit(), unit(), unit()) * scale) + ti,
        ];
        (m, t, body, body.map(|p| m * p + t))
    }

    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut rng = crate::kernel::test_rng::Xorshift::new(seed | 1);
        move || rng.signed()
    }

    /// The swept test ("The swept test") on random triangles' boxes and
    /// random motions passing near a scene triangle at a random time:
    /// whenever it proves the body's box swept over the motion apart from
    /// the scene's, the triangles themselves meet at none of 400 times
    /// along it (an exact test of the posed floats), and it proves a
    /// good share of the pairs.
    #[test]
    fn a_box_proven_apart_over_a_motion_never_meets_on_the_way() {
        use crate::query::interval_search::SweepMargin;
        use crate::query::Motion;
        let mut unit = rng(11);
        let (mut proven, mut tried) = (0, 0);
        for k in 0..4_000 {
            let mut point = |r: f64| DVec3::new(unit(), unit(), unit()) * r;
            let centre = point(2.0);
            let body = [
                point(0.5) + centre,
                point(0.5) + centre,
                point(0.5) + centre,
            ];
            let turn = |p: DVec3, a: f64| Rotation::from_axis_angle(p, a).unwrap();
            let from = Pose::new(turn(point(1.0), 1.0), point(1.0));
            let to = Pose::new(
                turn(point(1.0), 1.0 + 0.3 * point(1.0).x),
                from.translation + point(0.2),
            );
            let motion = Motion::new(from, to);
            let posed = |t: f64| {
                let p = motion.at(t);
                body.map(|v| p.apply(v))
            };
            let near = posed(0.5 + 0.5 * point(1.0).x)[k % 3];
            let off = 10f64.powi(-(k as i32 % 6)) * (1.0 + point(1.0).x.abs());
            let seed = near + point(1.0).normalize_or(DVec3::X) * off;
            let u = [seed, seed + point(0.5), seed + point(0.5)];
            let (ob, os, _) = fitted_with_pad(&body, &u, DVec3::ZERO);
            let reach = 1.8
                * body
                    .iter()
                    .map(|p| p.abs().max_element())
                    .fold(0.0, f64::max);
            let margin = SweepMargin::new(motion.angle(), motion.translation_extent(), reach);
            let (ma, mb) = (from.rotation.matrix(), to.rotation.matrix());
            let pad = 64.0
                * f64::EPSILON
                * (reach
                    + from
                        .translation
                        .abs()
                        .max(to.translation.abs())
                        .max_element());
            let ends = [
                ob.posed(&ma, from.translation),
                ob.posed(&mb, to.translation),
            ];
            let shift = to.translation - from.translation;
            tried += 1;
            if !os.swept_apart(
                [&ends[0], &ends[1]],
                shift,
                ob.h,
                ob.fuzz,
                pad,
                margin.inflation(1.0),
            ) {
                continue;
            }
            proven += 1;
            for j in 0..=400 {
                assert!(
                    !triangles_meet(&posed(j as f64 / 400.0), &u),
                    "{body:?} {u:?} {k}"
                );
            }
        }
        assert!(20 * proven > tried, "{proven} of {tried}");
    }

    /// [`Obb::swept_apart`] with every axis's products taken afresh, as it
    /// was before they were shared: the reference of
    /// `the_swept_test_shares_its_products_without_changing_an_answer`.
    fn swept_apart_axis_by_axis(
        b: &Obb,
        ends: [&PosedObb; 2],
        shift: DVec3,
        ha: DVec3,
        (fuzz_a, pad, margin): (f64, f64, f64),
    ) -> bool {
        let hb = b.h.to_array();
        // The slack is shared; the axes' products are what is compared.
        let slack = b.swept_slack(ends, shift, ha, fuzz_a, pad) + margin;
        let apart_along = |n: DVec3| {
            let d = n.dot(shift);
            let hb = hb[0] * n.dot(b.axes[0]).abs()
                + hb[1] * n.dot(b.axes[1]).abs()
                + hb[2] * n.dot(b.axes[2]).abs();
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for (a, moved) in [(ends[0], d), (ends[1], -d)] {
                let t = n.dot(a.c - b.c);
                let r = ha.x * n.dot(a.f[0]).abs()
                    + ha.y * n.dot(a.f[1]).abs()
                    + ha.z * n.dot(a.f[2]).abs();
                for t in [t, t + moved] {
                    lo = lo.min(t - r);
                    hi = hi.max(t + r);
                }
            }
            lo - hb > slack || -hi - hb > slack
        };
        b.axes.iter().any(|&n| apart_along(n))
            || ends[0].f.iter().any(|&n| apart_along(n))
            || ends[1].f.iter().any(|&n| apart_along(n))
    }

    /// The swept test's shared products (`n·x` taken once for `x·n`) give
    /// the answer of every axis's products taken afresh, on random boxes
    /// and motions whose gaps lie about the slack at every axis (each of
    /// the nine axes decides some of them), at scales 10⁻⁶ to 10⁶.
    #[test]
    fn the_swept_test_shares_its_products_without_changing_an_answer() {
        let mut unit = rng(29);
        let (mut apart, mut total) = (0, 0);
        for k in 0..200_000 {
            let scale = 10f64.powi(k % 13 - 6);
            let mut point = |r: f64| DVec3::new(unit(), unit(), unit()) * r * scale;
            let u = [point(1.0), point(1.0), point(1.0)];
            let body = [point(1.0), point(1.0), point(1.0)];
            let (ob, os) = (
                Obb::fit(&body, &Aabb::of(body.map(|p| p.to_array()))),
                Obb::fit(&u, &Aabb::of(u.map(|p| p.to_array()))),
            );
            let turn = |unit: &mut dyn FnMut() -> f64, angle: f64| {
                Rotation::from_axis_angle(DVec3::new(unit(), unit(), unit()), angle)
                    .unwrap()
                    .matrix()
            };
            let (big, small) = (3.0 * unit(), 0.3 * unit());
            let ma = turn(&mut unit, big);
            let mb = ma * turn(&mut unit, small);
            let ta = DVec3::new(unit(), unit(), unit()) * 2.0 * scale;
            let tb = ta + DVec3::new(unit(), unit(), unit()) * 0.3 * scale;
            let ends = [ob.posed(&ma, ta), ob.posed(&mb, tb)];
            let margin = (unit() + 1.0) * 0.2 * scale;
            let pad = 64.0 * f64::EPSILON * 4.0 * scale;
            let shared = os.swept_apart([&ends[0], &ends[1]], tb - ta, ob.h, ob.fuzz, pad, margin);
            let fresh = swept_apart_axis_by_axis(
                &os,
                [&ends[0], &ends[1]],
                tb - ta,
                ob.h,
                (ob.fuzz, pad, margin),
            );
            assert_eq!(shared, fresh, "{k}: {body:?} {u:?}");
            apart += shared as usize;
            total += 1;
        }
        // Both answers occur often.
        assert!(
            apart > total / 10 && apart < total * 9 / 10,
            "{apart} of {total}"
        );
    }

    /// A triangle's own box ("Triangles' own boxes") holds its corners,
    /// is flat (its first axis the normal, half-width within rounding of
    /// zero) unless the triangle is degenerate, and is never proven apart
    /// from a touching triangle's box, posed (the scene side) or fitted to
    /// posed corners and unposed (the body side), at scales `10⁻¹²⁰` to
    /// `10¹²⁰`, far from the origin, and for collinear and repeated corners.
    #[test]
    fn triangle_boxes_are_flat_and_never_part_touching_triangles() {
        let mut unit = rng(0x9e37_79b9_7f4a_7c15);
        let mut meeting = 0;
        for k in 0..24_000 {
            // Beyond 10^±77 a cross product of unscaled edges under- or
            // overflows: the box must still be flat there.
            let scale = [1e-3, 1.0, 1e3, 1e6, 1e-120, 1e120][k % 6];
            let off = DVec3::new(unit(), unit(), unit()) * scale * 100.0;
            let mut u: [DVec3; 3] =
                [(); 3].map(|_| DVec3::new(unit(), unit(), unit()) * scale + off);
            match k % 50 {
                0 => u[2] = u[0] + (u[1] - u[0]) * 0.25,
                1 => u[2] = u[1],
                2 => u = [u[0]; 3],
                _ => {}
            }
            let own = Obb::of_triangle(&u);
            for p in u {
                assert!(own.holds(p), "{k}: {u:?}");
            }
            if k % 50 >= 3 {
                let n = ((u[1] - u[0]) / scale)
                    .cross((u[2] - u[0]) / scale)
                    .normalize();
                assert!(own.axes[0].dot(n).abs() > 1.0 - 1e-9, "{k}");
                assert!(own.h.x <= 1e-12 * (scale * 100.0), "{k}: {:?}", own.h);
            }
            let (s, r) = (unit().abs(), unit().abs());
            let on = u[0] + (u[1] - u[0]) * (s * 0.5) + (u[2] - u[0]) * (r * 0.5);
            let (m, t, body, posed) = body_through(&mut unit, on, scale);
            if !triangles_meet(&posed, &u) {
                continue;
            }
            meeting += 1;
            let (ob, os, pad) = fitted_with_pad(&body, &u, t);
            assert!(!own.apart(&ob.posed(&m, t), ob.h, ob.fuzz, pad), "{k}");
            let posed_own = Obb::of_triangle(&posed);
            assert!(
                !os.apart(&posed_own.unposed(), posed_own.h, posed_own.fuzz, 0.0),
                "{k}"
            );
            assert!(
                !own.apart(&posed_own.unposed(), posed_own.h, posed_own.fuzz, 0.0),
                "{k}"
            );
        }
        assert!(meeting > 5_000, "{meeting}");
    }

    #[test]
    fn jacobi_finds_the_axes_of_a_slanted_slab() {
        let r = Rotation::from_axis_angle(DVec3::new(1.0, 2.0, 3.0), 0.7).unwrap();
        let m = r.matrix();
        let mut unit = rng(7);
        let pts: Vec<DVec3> = (0..500)
            .map(|_| m * DVec3::new(10.0 * unit(), 2.0 * unit(), 0.1 * unit()))
            .collect();
        let b = Aabb::of(pts.iter().map(|p| p.to_array()));
        let o = Obb::fit(&pts, &b);
        assert!(o.axes[0].dot(m.x_axis).abs() > 0.999, "{:?}", o.axes);
        assert!(o.axes[2].dot(m.z_axis).abs() > 0.999, "{:?}", o.axes);
        assert!(
            o.h.x * o.h.y * o.h.z
                < 0.02 * (b.hi[0] - b.lo[0]) * (b.hi[1] - b.lo[1]) * (b.hi[2] - b.lo[2])
        );
        for p in pts {
            let q = p - o.c;
            for i in 0..3 {
                assert!(o.axes[i].dot(q).abs() <= o.h[i] + o.fuzz);
            }
        }
    }

    /// A triangle touching another (a corner on its edge or face, in
    /// floats), both in random frames: the two fitted boxes, one posed,
    /// are never proven apart when the exact test says the posed
    /// triangles meet. Without the slack and fuzz some would be (checked
    /// by setting both to zero).
    #[test]
    fn touching_boxes_are_never_proven_apart() {
        let mut unit = rng(0x2545_f491_4f6c_dd1d);
        let mut meeting = 0;
        for k in 0..20_000 {
            let scale = [1e-3, 1.0, 1e3, 1e6][k % 4];
            let off = DVec3::new(unit(), unit(), unit()) * scale * 100.0;
            let u: [DVec3; 3] = [(); 3].map(|_| DVec3::new(unit(), unit(), unit()) * scale + off);
            let (s, r) = (unit().abs(), unit().abs());
            let on = if k % 2 == 0 {
                u[0] + (u[1] - u[0]) * s
            } else {
                u[0] + (u[1] - u[0]) * (s * 0.5) + (u[2] - u[0]) * (r * 0.5)
            };
            let (m, t, body, posed) = body_through(&mut unit, on, scale);
            if !triangles_meet(&posed, &u) {
                continue;
            }
            meeting += 1;
            let (ob, os, pad) = fitted_with_pad(&body, &u, t);
            assert!(pose_skew(&m).is_some());
            assert!(!os.apart(&ob.posed(&m, t), ob.h, ob.fuzz, pad), "{k}");
        }
        assert!(meeting > 5_000, "{meeting}");
    }

    #[test]
    fn gaps_never_exceed_a_distance_between_the_boxes_points() {
        // Random triangles at random scales, poses and distances: the
        // certified gap between their boxes is never more than the
        // distance between any point of one and any point of the other
        // (sampled on a grid; the true least distance is smaller still),
        // is positive exactly when `apart` says so, and bounds well apart
        // boxes well (not only `0`).
        let mut unit = rng(0x9e37_79b9_7f4a_7c15);
        let mut positive = 0;
        let grid = |t: &[DVec3; 3]| {
            let mut out = Vec::new();
            for i in 0..=10 {
                for j in 0..=10 - i {
                    let (a, b) = (i as f64 / 10.0, j as f64 / 10.0);
                    out.push(t[0] + (t[1] - t[0]) * a + (t[2] - t[0]) * b);
                }
            }
            out
        };
        for k in 0..3_000 {
            let scale = [1e-3, 1.0, 1e3][k % 3];
            let off = DVec3::new(unit(), unit(), unit()) * scale * 100.0;
            let u: [DVec3; 3] = [(); 3].map(|_| DVec3::new(unit(), unit(), unit()) * scale + off);
            let rot = Rotation::from_axis_angle(DVec3::new(unit(), unit(), unit()), 3.0 * unit())
                .unwrap();
            let (m, t) = (rot.matrix(), DVec3::new(unit(), unit(), unit()) * scale);
            let (mi, ti) = (m.transpose(), -(m.transpose() * t));
            let near = u[0] + DVec3::new(unit(), unit(), unit()) * scale * (2.0 * unit().abs());
            let body =
                [(); 3].map(|_| mi * (near + DVec3::new(unit(), unit(), unit()) * scale) + ti);
            let posed = body.map(|p| m * p + t);
            let (ob, os, pad) = fitted_with_pad(&body, &u, t);
            let at = ob.posed(&m, t);
            let gap = os.gap(&at, ob.h, ob.fuzz, pad);
            assert_eq!(gap > 0.0, os.apart(&at, ob.h, ob.fuzz, pad), "{k}");
            let (pa, pb) = (grid(&posed), grid(&u));
            let sampled = pa
                .iter()
                .flat_map(|p| pb.iter().map(move |q| (*p - *q).length()))
                .fold(f64::INFINITY, f64::min);
            assert!(gap <= sampled, "{k}: gap {gap} above a distance {sampled}");
            positive += usize::from(gap > 0.1 * sampled);
        }
        assert!(positive > 300, "{positive}");
    }

    #[test]
    fn the_gap_of_parallel_flat_boxes_is_their_distance_less_its_slack() {
        // A triangle and its copy moved along its normal by `d`, the copy
        // given as a body at a random pose: both boxes are flat, so the
        // gap is the distance less the test's slack (far below 0.1%:
        // dividing by 1.01 for the axes' length, as once, fails this),
        // and never more than `d` (the triangles' exact distance, up to
        // the rounding of their corners, far below the slack).
        // Scales whose gaps' squares would be subnormal or overflow too
        // (review of 2026-11-30, module docs).
        let mut unit = rng(0x51ab);
        let scales = [
            1e-3,
            1.0,
            1e3,
            2f64.powi(-540),
            2f64.powi(-530),
            2f64.powi(515),
            2f64.powi(600),
        ];
        for k in 0..3_500 {
            let scale = scales[k % scales.len()];
            let off = DVec3::new(unit(), unit(), unit()) * scale * 100.0;
            let u: [DVec3; 3] = [(); 3].map(|_| DVec3::new(unit(), unit(), unit()) * scale + off);
            let n = ((u[1] - u[0]) / scale).cross((u[2] - u[0]) / scale);
            if n.length() < 0.1 {
                continue;
            }
            let d = scale * (0.05 + unit().abs());
            let shifted = u.map(|p| p + n.normalize() * d);
            let rot = Rotation::from_axis_angle(DVec3::new(unit(), unit(), unit()), 3.0 * unit())
                .unwrap();
            let (m, t) = (rot.matrix(), DVec3::new(unit(), unit(), unit()) * scale);
            let body = shifted.map(|p| m.transpose() * (p - t));
            let (ob, os, pad) = fitted_with_pad(&body, &u, t);
            let gap = os.gap(&ob.posed(&m, t), ob.h, ob.fuzz, pad);
            assert!(gap <= d, "{k}: gap {gap} above the distance {d}");
            // Tight where the fit finds the triangle's own axes (below
            // about 2⁻⁵⁰⁰ its covariance underflows, and the node keeps
            // the coordinate axes).
            if (1e-100..1e100).contains(&scale) {
                assert!(gap >= 0.999 * d, "{k}: gap {gap} for a distance {d}");
            }
        }
    }

    /// The fifteen gaps as the loops over index arrays computed them
    /// before [`Obb::axis_gaps`] was unrolled: the reference its unrolled
    /// formulas must equal bit for bit.
    fn axis_gaps_by_loops(b: &Obb, a: &PosedObb, ha: DVec3, fuzz_a: f64, pad: f64) -> [f64; 15] {
        let mut out = [0.0; 15];
        let e = &b.axes;
        let d = a.c - b.c;
        let t = [e[0].dot(d), e[1].dot(d), e[2].dot(d)];
        let c: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| e[i].dot(a.f[j])));
        let ac: [[f64; 3]; 3] = c.map(|r| r.map(f64::abs));
        let (ha, hb) = (ha.to_array(), b.h.to_array());
        let s = a.c.abs().max_element()
            + b.c.abs().max_element()
            + t[0].abs()
            + t[1].abs()
            + t[2].abs()
            + ha[0]
            + ha[1]
            + ha[2]
            + hb[0]
            + hb[1]
            + hb[2];
        let slack = SLACK * s + 1.01 * (fuzz_a + b.fuzz) + 2.0 * pad;
        for i in 0..3 {
            let ra = ha[0] * ac[i][0] + ha[1] * ac[i][1] + ha[2] * ac[i][2];
            out[i] = t[i].abs() - (hb[i] + ra + slack);
        }
        for j in 0..3 {
            let rb = hb[0] * ac[0][j] + hb[1] * ac[1][j] + hb[2] * ac[2][j];
            let p = t[0] * c[0][j] + t[1] * c[1][j] + t[2] * c[2][j];
            out[3 + j] = p.abs() - (ha[j] + rb + slack);
        }
        for i in 0..3 {
            let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
            for j in 0..3 {
                let (k, l) = ((j + 1) % 3, (j + 2) % 3);
                let p = t[i2] * c[i1][j] - t[i1] * c[i2][j];
                let rb = hb[i1] * ac[i2][j] + hb[i2] * ac[i1][j];
                let ra = ha[k] * ac[i][l] + ha[l] * ac[i][k];
                out[6 + 3 * i + j] = p.abs() - (ra + rb + slack);
            }
        }
        out
    }

    /// The unrolled axes are the loops' own: on random boxes at random
    /// poses and scales, every one of the fifteen gaps is the same float
    /// as [`axis_gaps_by_loops`]'s, visited in the same order, and the
    /// visit stops where it is told to.
    #[test]
    fn unrolled_axes_are_the_loops_bit_for_bit() {
        let mut unit = rng(0x9e37_79b9_7f4a_7c15);
        for k in 0..20_000 {
            let scale = [1e-3, 1.0, 1e3, 1e6][k % 4];
            let mut point = |r: f64| DVec3::new(unit(), unit(), unit()) * r;
            let body: Vec<DVec3> = (0..3 + k % 5).map(|_| point(scale)).collect();
            let off = point(scale * 2.0);
            let scene: Vec<DVec3> = (0..3 + k % 4).map(|_| point(scale) + off).collect();
            let fit = |v: &[DVec3]| Obb::fit(v, &Aabb::of(v.iter().map(|p| p.to_array())));
            let (ob, os) = (fit(&body), fit(&scene));
            let rot = Rotation::from_axis_angle(DVec3::new(unit(), unit(), unit()), 3.0 * unit())
                .unwrap();
            let (m, t) = (rot.matrix(), DVec3::new(unit(), unit(), unit()) * scale);
            let posed = ob.posed(&m, t);
            let pad = 64.0 * f64::EPSILON * scale;
            let want = axis_gaps_by_loops(&os, &posed, ob.h, ob.fuzz, pad);
            let mut got = Vec::new();
            let stop = k % 16;
            os.axis_gaps(&posed, ob.h, ob.fuzz, pad, |n, gap| {
                got.push((n, gap));
                n == stop
            });
            assert_eq!(got.len(), (stop + 1).min(15), "{k}");
            for (i, &(n, gap)) in got.iter().enumerate() {
                assert_eq!(n, i, "{k}");
                assert_eq!(gap.to_bits(), want[i].to_bits(), "{k}: axis {i}");
            }
        }
    }

    #[test]
    fn separated_slanted_boxes_are_proven_apart() {
        let r = Rotation::from_axis_angle(DVec3::new(1.0, 1.0, 0.0), 0.6).unwrap();
        let m = r.matrix();
        let rod = |x: f64| {
            [
                DVec3::new(x, 0.0, 0.0),
                m * DVec3::new(5.0, 0.0, 0.0) + DVec3::X * x,
                m * DVec3::new(5.0, 0.01, 0.0) + DVec3::X * x,
            ]
        };
        let a = rod(0.0);
        let b = rod(0.05);
        let oa = Obb::fit(&a, &Aabb::of(a.map(|p| p.to_array())));
        let ob = Obb::fit(&b, &Aabb::of(b.map(|p| p.to_array())));
        // Their axis-aligned boxes overlap; their oriented ones do not.
        assert!(Aabb::of(a.map(|p| p.to_array())).meets(&Aabb::of(b.map(|p| p.to_array()))));
        assert!(ob.apart(&oa.posed(&DMat3::IDENTITY, DVec3::ZERO), oa.h, oa.fuzz, 0.0));
    }

    #[test]
    fn skewed_pose_matrices_are_refused() {
        assert!(pose_skew(&DMat3::IDENTITY).is_some());
        assert!(pose_skew(&(DMat3::IDENTITY * (1.0 + 1e-9))).is_none());
    }
}
