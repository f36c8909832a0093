//! The certified motion search of a [`SceneChecker`].
//!
//! # Why "free" is certain
//! The motion is [`Motion`]'s (linear translation, slerp rotation, the
//! arc decided exactly). Over an interval `[a, b]` every point of a body
//! triangle `P` stays within the margin `s + e` of
//! `query::interval_search` (`s` the sagitta of the turn over the
//! interval for the body's reach `r`, `e` the float poses' rounding, both
//! rounded up; derived there, once for both motion checkers) of
//!
//! `conv(R(a) P ∪ R(b) P) ⊕ [T(a), T(b)]`,
//!
//! the hull of twelve points (each corner turned as at `a` and at `b`,
//! moved as at `a` and at `b`): the motion search's *swept hull* (the
//! convex checker's bound, [`crate::query::MotionChecker`], per triangle).
//! The twelve points are computed from the float poses (posed in floats,
//! then moved by the float difference of the translations), and `e`
//! bounds the distance between each as computed and its exact value on
//! the exact motion (`query::rounding`). If every pair of a swept hull and
//! a scene triangle is more than `s + e` apart, no triangles meet anywhere
//! in `[a, b]`. Pairs whose boxes are more than that apart on an axis are
//! dropped by the broad phase (an exact comparison after a monotone
//! rounding), the others are certified by [`super::gap`]: floats propose
//! an axis, and the gap along it is bounded below rigorously, about the
//! scene triangle's first corner (so its rounding is a few ulps of the
//! local sizes, not of the coordinates).
//!
//! The broad phase also drops a pair of tree nodes when the scene node's
//! oriented box is proven apart ([`crate::solid::obb`], certified) from
//! the body node's box posed at `a`, grown by the node's *swept reach*:
//! with `ρ` an upper bound on the norm of every point of the node's box
//! (`(|c| + |h| + fuzz)(1 + 10⁻¹¹)`: a point is `c + Σ sᵢeᵢ` (plus the
//! fuzz ball) with `|sᵢ| ≤ hᵢ` and axes orthonormal up to `β ≤ 2⁻⁴⁴`, so
//! `|Σ sᵢeᵢ| ≤ |h|(1 + 3β)`; each norm rounded up by `query::rounding`'s
//! `norm_up`, and the factor covers `3β` and the sum's roundings) and `θ` one on `‖M(b) − M(a)‖₂` (`spectral_norm_up`:
//! `√(‖A‖₁‖A‖∞)`, Hölder's bound, at most `√3` times the norm where the
//! sum of the entries' magnitudes used before is up to `3√2` times on a
//! difference of rotations;
//! both are taken of the vector or matrix divided by its largest
//! magnitude and scaled back, so no square of a coordinate below 1e-154
//! underflows: with plain Euclidean norms a body of size 1e-165 had a
//! colliding motion called free, found by the review in `solid::obb`,
//! `tests/oriented_boxes.rs` pins it),
//! each of the twelve points of a node triangle lies within
//! `θρ + 2|Δt|₁ + 4·pad + 16u(size + 2|Δt|₁) + 10⁻³⁰⁰` of `M(a) p + t(a)` for the
//! triangle's corner `p` (the other end's corners move by at most
//! `θρ + |Δt|`, the shifted copies by one more `|Δt|`; each float posing
//! errs by at most `pad` a coordinate, each float shift by an ulp of the
//! sizes). The hull of points within that distance of the posed box lies
//! within it too (a ball around a convex set is convex), and the test
//! adds `s + e` to the grown distance. Where both end poses' matrices
//! are close enough to rotations for the oriented test, the node's box
//! is instead tested against the hull of the node's box posed at both
//! ends and each moved by the other end's translation, grown by `s + e`
//! (the swept hull above, for the node's box: `solid::obb`, "The swept
//! test"), which is second order in the turn where the grown reach is
//! first: on the worst robot-part pairs it cut the triangle pairs a walk
//! tests by 85% to 87%. Neither is tried where both nodes are leaves:
//! there the triangles' own boxes and pair tests follow at once, and on
//! robot parts the oriented boxes parted only 4–10% of such pairs, at
//! about 1,500 instructions a test (skipping them saved 3–5% of a
//! decision's instructions on four pairs, the same decisions and
//! intervals; docs/BENCHMARKS.md, "Motions: fewer products a pair"). A
//! culling test only drops pairs, so where it is skipped nothing is
//! certified that would not be. A slide along a wall certifies in one
//! interval (the hull stays on its side); the sagitta is second order in
//! the interval's width. Containment
//! cannot begin without triangles meeting, and the body is not inside
//! anything at `t = 0` (checked first), so the certified intervals,
//! examined left to right from `0`, are free of every contact.
//!
//! # The search
//! The interval search of `query::interval_search` over `[0, 1]` (left to
//! right, halving, probes ahead when stuck, the budget, undecided below
//! [`MIN_WIDTH`](crate::query::MIN_WIDTH); its soundness argument is
//! there), started from about two equal intervals per reach the body's
//! farthest point travels (`first_pieces`: a schedule, not a bound),
//! with the bound above certifying an interval
//! (`SceneChecker::certified_apart`) and the exact state check
//! (`scene::state`) checking a time.
//!
//! # In the body's frame
//! A pair the swept hull leaves uncertified is tried once more, in the
//! body's frame, where the body triangle `P` stands still and the scene
//! triangle `U` moves: a body face turning near a scene corner tilts
//! against every fixed axis of the world by its length times the turn, a
//! loss of the first order in the interval's width, so that near a
//! contact the certified intervals shrank with the distance left (tens
//! of intervals per halving of it on robot parts); along the body face's
//! own normal the loss is the sagitta alone.
//!
//! Over `[a, b]` a scene point `y` is at `R(t)ᵀ (y − T(t))` in the body's
//! frame. With `λ = (t − a)/(b − a)`, `y − T(t) = (1 − λ) q_a + λ q_b`
//! (`q_a = y − T(a)`, `q_b = y − T(b)`), and `R(t)ᵀ = E(t) R(a)ᵀ` with
//! `E(t)` the turn about one fixed axis through the body's origin by at
//! most `δ` (the slerp's constant rate; the same turn as the world's, seen
//! from the body). So `R(t)ᵀ q` runs on an arc of angle at most `δ` and
//! radius at most `|q|` from `R(a)ᵀ q` to `R(b)ᵀ q`, within the sagitta
//! `2 |q| sin²(δ/4)` of their chord, and `R(t)ᵀ (y − T(t))` lies within
//! `s' = 2 ρ sin²(δ/4)` (`ρ ≥ |q_a|, |q_b|`) of the hull of the four points
//! `R(a)ᵀ q_a, R(b)ᵀ q_b, R(b)ᵀ q_a, R(a)ᵀ q_b`; `U`'s points, convex
//! combinations of its corners, within `s'` of the hull of its corners'
//! twelve. The twelve are computed from the float poses as
//! `fl(M̃ᵀ fl(y − T̃))`: per `query::rounding`, `|M̃ − R| ≤ 675u` and the
//! product rounds by `5.3u |q̃|`, and `fl(y − T̃)` is within `2.01u D +
//! 1.02u M` (the translation) plus `u (Y + M)` (the subtraction; `Y` the
//! largest coordinate of `U`) of `y − T` per coordinate, so every point is
//! within `e' = 2⁻⁴³ ρ + 6u (M + D + Y)` of the exact one, and `ρ` is
//! the largest float `|q̃|` rounded up plus that `6u (M + D + Y)`. The
//! body triangle is the body's own floats, exact. If the hull of the
//! twelve is more than `s' + e'` from `P` ([`super::gap`]), no point of
//! `U` meets `P` at any `t` of `[a, b]` (a rigid motion keeps distances).
//! Nothing else changes: the pair is dropped only when certified. The
//! twelve points, `ρ`, `e'`, the swept hull's margin and the bow below
//! depend on the scene triangle and the interval alone, so each scene
//! triangle's are computed once an interval, for every body triangle it
//! meets (`RelativeTriangles`, `relative_triangle`; on the Cassie shin
//! against Talos's gripper an interval meets 47 to 100 scene triangles in
//! 360 to 540 pairs).
//!
//! # Between the ends
//! The margin `s + e` above is the same over the whole interval, while a
//! point strays from its chord only inside it: near a grazing end the
//! swept hull is as close as that end, so an interval leaving a pose
//! `10⁻¹²` from contact was certified only once its sagitta fell below
//! `10⁻¹²` (tens of intervals per motion on robot parts, thousands where
//! a motion stays near). A pair is also tried against a bound that
//! vanishes at the ends; where the interval's frame allows it, that test
//! comes first (in the world and in the body's frame, in the order of
//! "The swept hull after the bow" below), and the swept hull's second,
//! where it may add anything: each certifies alone, so the order changes
//! no answer, and on robot parts near contact the swept hull failed on
//! about half the pairs the walk tests (`docs/BENCHMARKS.md`, "The bow
//! first").
//!
//! The bound is `query::interval_search`'s ("The bow"): a body point `p`
//! strays from its chord by at most `λ(1 − λ) δ² |p| / 2`, and `|p| ≤ r`,
//! the largest norm of the triangle's corners (rounded up: the
//! triangle's points are convex combinations of its corners). Along an
//! axis `n`, with `A` and `B` the certified gaps between the scene
//! triangle and the body triangle's float corners at `a` and at `b`
//! (`super::gap`, "Between the ends"), each less `e |n|` (the corners'
//! float poses are within `e` of the exact ones, and `f(0)`, `f(1)` are
//! affine in the triangle's points), the gap at `λ` is at least `(1 − λ)
//! A + λ B − λ(1 − λ) c`, `c = δ² r |n| / 2` (rounded up), positive on
//! all of `[0, 1]` exactly when `A > 0`, `B > 0` and `(√A + √B)² > c`.
//!
//! In the body's frame (above), the scene point is at `x(λ) = E(λ) w(λ)`
//! with `w(λ) = R(a)ᵀ (y − T(t))` linear in `λ`, `|w| ≤ ρ` and `|w'| =
//! |T(b) − T(a)|`, and this `E` (that of "In the body's frame", `R(t)ᵀ
//! R(a)`) turns at the same rate: `x'' = E''w +
//! 2E'w'`, `|x''| ≤ δ² ρ + 2δ |T(b) − T(a)|`, so `c = (δ² ρ / 2 + δ |T(b)
//! − T(a)|) |n|`, with `|T(b) − T(a)|` at most the float difference's norm
//! (rounded up, `4u` more for the subtraction) plus `2e'` (each float
//! translation lies within `e'` of the exact one: its share of `e'` above),
//! and `e'` for `e`. The body triangle is exact there.
//!
//! On the worst pairs of robot parts (`parts_motions`, 40 motions from
//! near-contact poses each), the median number of intervals of a decision
//! fell from 29–67 to 1, and the most from 4,096 (the budget) to 91.
//!
//! # Boxes between the ends
//! Near a grazing end the node boxes' swept tests cannot drop anything
//! (the swept hull's margin does not vanish at the ends), so an interval
//! leaving a pose near contact had every scene triangle near the body's
//! swept triangles tested one by one with the bow above: a 23 cm plate
//! turning 5° near a finely cut part tested 7,454 triangle pairs in one
//! interval. The bow's argument holds for any set of scene points, so a
//! body leaf is also tested against a scene node's oriented box, carried
//! back into the body's frame at both ends
//! ([`crate::solid::obb::Obb::seen_from`]), along each of the leaf's
//! triangles' normals (`super::gap`, "A box between the ends"): the box's
//! points run within `e'` of those carried ends and within the body
//! frame's bow (`δ² ρ / 2 + δ |T(b) − T(a)|`, `ρ` bounding every point's
//! `|y − T|` at both ends, hence at every time between, as `y − T(t)` is
//! a convex combination of the two; "In the body's frame") of their chords, and a
//! box that stays on one side of every leaf triangle's plane meets none
//! of them anywhere in the interval; the node pair is dropped, as a node
//! box's other tests drop it (a statement about the whole interval, so
//! the record of "Reuse across halving" may rely on it). It is tried where
//! the world's oriented test did not part a body leaf from an inner scene
//! node, on intervals with a body frame; the second end and the bounds
//! only where the first end's gap is positive. On `parts_motions`' 40
//! decisions per pair (instructions): the plate above 261 M → 157 M, a
//! human lower arm against a TIAGo antenna 528 M → 145 M, a Centauro knee
//! against a TALOS arm link 2,096 M → 315 M; two ROS-Industrial pairs
//! where it parts nothing +0.6% and +1.9%. Pinned by
//! `a_node_certified_between_the_ends_meets_no_body_triangle` (a corner's
//! arc through a finely cut face between clear ends is never certified;
//! without the bow it is; and random certified nodes are checked against
//! their leaves at sampled times). Its independent review (2026-12-02)
//! is recorded in `super::gap`, "A box between the ends".
//!
//! # The swept hull after the bow
//! Where the bowed chord's test did not certify a pair, the swept hull's
//! (margin `m`, the ends' rounding `e`) is tried only where it may
//! certify what the bow did not. If it holds along an axis `n` (scaled,
//! `|n| ≥ 1` but for subnormal proposals, below), every hull point's gap
//! bound exceeds `m |n|`, and the hull holds both ends' corners, whose
//! gap bounds are at least the hull's (the same error formula on fewer
//! points, monotone in the gap), so the bow's `A` and `B` (those bounds
//! less `e |n|`) exceed `(m − e) |n|`, and `(√A + √B)² > 4 (m − e) |n|`. The bow's test then holds along the same
//! axis (the same proposals, `super::gap::Pair`) whenever `4 (m − e) >
//! c (1 + 10⁻⁹)` (the factor covers the roundings of both sides; `m − e`
//! above `10⁻¹⁴⁰` keeps `A B` above the test's least product and the ends
//! above the least normal number), and the hull is not tried
//! (`swept_hull_may_add`). In the world `m − e` is the body's sagitta
//! `2 r sin²(δ/4)` and `c` the triangle's bow `δ² r_T / 2`, so only
//! triangles within about `δ²/48` of the body's reach still try the hull.
//! In the body's frame `c` has the term `δ |T(b) − T(a)|` the hull's
//! margin lacks, and the hull is tried as before. On six robot part
//! pairs of both families, no swept hull tried after the bow certified a
//! pair (on the Cassie shin against Talos's gripper, none of 15,511 in
//! the world and none of 5,189 in the body's frame).
//!
//! Skipping a test never changes an answer (each test only certifies);
//! the argument above says the skip also costs no certification. Its
//! rounding: the hull's bound exceeds `m |n| (1 + 8u)` strictly, so by an
//! ulp at least, and with `m` near `e` that ulp, not the factor
//! `1 + 10⁻⁹`, absorbs the subtraction of `e |n|` (the test
//! `the_swept_hull_is_skipped_only_where_the_bow_certifies_all_it_would`
//! draws `e` up to `m (1 − 10⁻¹⁰)` for this). Two corners where it may
//! cost a certification (never an answer): a gap bound one ulp lower for
//! a larger gap where the error term nearly equals the gap (a rounding
//! tie), and proposals scaled from subnormal products (`|n|` below 1,
//! `A B` then possibly below the bow's least product).
//!
//! An independent review (2026-12-01) verified the shared tests of
//! `gap::Pair` (bit-identical bounds on the same axis and points; the
//! closest points' direction tried both ways is the mirror bound), that
//! the hull's twelve points hold both ends' corners as the same floats in
//! both frames, the rounding argument above, and that the frames' order
//! changes no answer; a probe of 4,000 pairs with `e` 10⁸–10¹⁰ times
//! `m − e` found no pair the hull certified and the bow did not. Its
//! remarks (the two corners, the ulp, the test's range of `e`, a comment's
//! reference) are applied.
//!
//! The world's and the body frame's tests each certify alone, so their
//! order changes no answer. On some pairs the body's frame certifies
//! nearly every pair the world does and more (the Cassie shin against
//! Talos's gripper: 10,322 pairs only there, 17 only in the world), on
//! others the world certifies many the body's frame does not (1,355
//! against 2); so within an interval the frame that alone certified the
//! last such pair is tried first.
//!
//! # Reuse across halving
//! An interval the walk does not certify records, in the check's scratch,
//! the triangle pairs it could not certify (up to [`FRONT_MOST`]), and
//! goes on walking past them: every other pair of the two trees was
//! certified over that interval, by a node box, an oriented box, a
//! triangle's box or its swept hull, each a statement about the exact
//! motion over the whole interval, so over every interval cut from it.
//! The halves then test the recorded pairs alone, with their own (smaller)
//! margin, and record which of those they could not certify in turn
//! (`query::interval_search`, "Reuse across halving", for why the record
//! is a stack). A walk that finds more pairs than it may record stops at
//! the next one, as a walk recording nothing does, and the halves walk
//! the trees again, trying the last blocking pair first. Near a contact
//! the record is the few pairs there: the halving towards a grazing pose
//! costs a few microseconds an interval, not a walk.
//!
//! A walk records only right after an interval was certified; otherwise
//! it stops at the first pair it cannot certify, trying the last blocking
//! pair first, as a walk without a record does. Halving towards a grazing
//! end certifies the left half of every interval it cuts, so the first
//! right half records, and everything after it is the record's; a motion
//! into an obstacle certifies nothing near its start, and its failed
//! walks stay cheap (recording there walked to 512 pairs at every level:
//! 2 to 5 ms on robot parts where stopping at the first takes
//! microseconds). Each recording walk follows a certified walk, so it at
//! most doubles what walking cost without a record.
//!
//! # Independent review (2026-12-01, second): shared work
//! Of the scene triangles' relative points computed once an interval
//! (`RelativeTriangles`), the leaves' skipped oriented test, and the
//! swept oriented test's shared products (`solid::obb`). Verified: the
//! cached values read only the scene triangle and the interval's frame,
//! never the body triangle; a stale entry cannot be read (`start` empties
//! the entries, and an entry is valid only when it names the triangle
//! asked); one frame is built per interval, right after `start`; the
//! world's tests, their order and the frame order are unchanged; a
//! skipped culling test only lets more pairs reach the certified tests,
//! so it can cost a certification, never make an answer "free"; glam's
//! `DVec3::dot` is `x x' + y y' + z z'` in that order without fused
//! products, so `n·x` and `x·n` are the same floats, the shared indices
//! are right, and the axis order and early exit are as before (over the
//! pinned test's 200,000 samples every one of the nine axes is the first
//! to part some). Its remarks (a misplaced doc comment, a dropped code
//! comment, the oriented test's description above, a reference, two
//! ratios and the twelve points' order) are applied.
//!
//! # Independent review (2026-11-30, second): between the ends
//! Of "Between the ends" and `super::gap`'s `apart_between_ends`.
//! Verified: poses apply to the body's vertices about the body's origin,
//! and the exact slerp is `R(t) = R(a) E(λ)` with `E` a turn about a fixed
//! axis at the constant rate, so both second-derivative bounds hold
//! (without `δ ≤ π`: an unclamped turn is fine); `e` and `e'` bound the
//! float corners and translations as used; the per-end gaps about the
//! scene triangle's first corner are valid with the same slack; the
//! bowed-chord test is sound in floats. Tried to break it: 4,000 motions ×
//! 399 samples with the production turn (half turns exactly, angles to
//! `10⁻¹²`, translations dominating, far from the origin; the worst
//! deviation 0.99997 of its bow), and about 150,000 adversarial arcs
//! poking a face by down to `10⁻⁷` of the sagitta inside the extremum of
//! a path, in the world and in the body's frame: none certified (pinned
//! as `review_adversarial_arcs_are_never_certified`). Found: the relative
//! rounding argument of the bowed-chord test does not cover subnormal
//! ends (harmless, by an argument of its own); the test now refuses ends
//! below the least normal number. Its remarks on the wording (the body
//! frame's `E`, the count of roundings) are applied.
//!
//! # Independent review (2026-11-29, second)
//! Of the first pieces, the exact per-interval triangle boxes, the body
//! normals as proposals (`super::gap`) and the Hölder and scaled
//! Euclidean norms of the swept reach. Verified: `turn · radius` bounds
//! every node point's displacement (the float difference of the matrices,
//! the scaling and near-orthonormal axes included); the triangle boxes are
//! those of the twelve points certified; the normal tested both ways gives
//! the old bounds bit for bit; `normalised_scale` scales by an exact power
//! of two at every magnitude; the first pieces keep the left-to-right
//! invariant with shared float ends. Found and mended: the triangle boxes
//! were forgotten only when the motion search itself wrapped the query
//! counter, so after a wrap inside a state check a stale box could certify
//! a crossing pose free (pinned by
//! `regression_swept_boxes_are_forgotten_when_a_state_check_wraps_the_counter`);
//! the norms lacked an absolute term for subnormal products and dropped
//! NaN (both harmless where used, mended in `query::rounding`).
//!
//! # Independent review (2026-11-30)
//! Of "Reuse across halving", "In the body's frame", the closest edges'
//! common normal (`super::gap`) and the probes' skip of a time checked
//! free (`query::interval_search`). Verified: every pair not recorded is
//! dropped by a test over the whole parent interval with its own margin;
//! the pending ranges are exactly the ancestors' and the record is cut back
//! only above them (checked with a copy that tags every range and asserts
//! each read, at caps of 3, 16 and 512); the slerp makes `R(t)ᵀ = E(t)
//! R(a)ᵀ` with `E` a turn about a fixed axis by at most `δ`, the sagitta's
//! radius and the rounding tally (`705u + 5.3u < 2⁻⁴³`, the translation's
//! `3.5u (M + D) + 1.75u Y < 6u (M + D + Y)`) hold, and the "about the
//! first corner" error model applies with the body triangle as `u`. Tried
//! to break it: a corner whose body-frame arc dips exactly the sagitta
//! (never certified when it collides), 182 random lifted pairs up to 1e3
//! from the origin (the lowest certified lift always above the sampled
//! contact), 130 free verdicts near contact against 2,001 sampled times
//! each. Found and mended: the record grew with the budget (entries of
//! finished intervals below new appends), and its `u32` offsets could have
//! wrapped past a budget of about 8.4 million; walks now record only below
//! [`FRONT_KEPT`] entries.

use super::checker::{
    cached, cells, shifted, Lazy, RelativeTriangle, RelativeTriangles, SceneChecker, Scratch,
};
use std::sync::atomic::Ordering;

use glam::{DMat3, DVec3};

use super::gap::{apart_by_more_than, box_apart_between_ends, Pair};
use crate::kernel::bounds::U;
use crate::kernel::rotation::Pose;
use crate::query::checker::{Checker, MotionCheck};
use crate::query::error::{MotionError, QueryError};
use crate::query::interval_search::{bow, first_contact, Sweep, SweepMargin, Within};
use crate::query::motion::Motion;
use crate::query::rounding::{norm_up, pose_rounding_bound, spectral_norm_up};
use crate::solid::aabb::Aabb;
use crate::solid::obb::pose_skew;

impl SceneChecker {
    /// The twelve points of body triangle `i`'s swept hull (module docs):
    /// its corners posed at both ends (by `at` and `at_b`), and each moved
    /// by the other end's translation.
    pub(super) fn swept_points(
        &self,
        (at, at_b): (&mut Lazy, &mut Lazy),
        i: usize,
        from: &Pose,
        to: &Pose,
    ) -> [DVec3; 12] {
        let shift = to.translation - from.translation;
        let t = self.body.triangles[i];
        let a = t.map(|v| at.get(&self.body.vertices, from, v));
        let b = t.map(|v| at_b.get(&self.body.vertices, to, v));
        std::array::from_fn(|k| match k / 3 {
            0 => a[k % 3],
            1 => b[k % 3],
            2 => a[k % 3] + shift,
            _ => b[k % 3] - shift,
        })
    }

    /// Whether swept hull `hull` comes within `reach` of scene triangle
    /// `j` (not certified apart), its exact box already within `reach` of
    /// the triangle's box.
    fn hull_near(
        &self,
        hull: &[DVec3; 12],
        i: usize,
        j: usize,
        reach: f64,
        frame: Option<&BodyFrame>,
    ) -> bool {
        let ends = [[hull[0], hull[1], hull[2]], [hull[3], hull[4], hull[5]]];
        let u = self.scene_triangle(j);
        let Some(f) = frame else {
            return !apart_by_more_than(hull, &ends, &u, reach);
        };
        // The world's test only where it is tried. The frame that
        // certified the last pair first (module docs, "The swept hull
        // after the bow"): each certifies alone, so the order changes no
        // answer, only what a pair costs.
        let in_world = || {
            // Between the ends (module docs): each point of the triangle
            // runs on an arc about the body's origin, radius at most the
            // triangle's reach, turning by `δ`.
            let reach_of_triangle = self.body.triangles[i]
                .map(|v| norm_up(self.body.vertices[v as usize]))
                .into_iter()
                .fold(0.0, f64::max);
            let bow = bow(f.turn, reach_of_triangle);
            let hull_adds = swept_hull_may_add(reach, f.pose_error, bow);
            let mut pair = Pair::new(&ends, &u);
            certified_deferring(&f.world_axes_failed, |deferred| {
                pair.apart_between_ends_from(f.pose_error, bow, deferred)
            }) || (hull_adds && pair.hull_apart_by_more_than(hull, reach))
        };
        let apart = if f.body_frame_first.get() {
            self.apart_in_body_frame(i, j, f) || {
                let apart = in_world();
                f.body_frame_first.set(!apart);
                apart
            }
        } else {
            in_world() || {
                let apart = self.apart_in_body_frame(i, j, f);
                f.body_frame_first.set(apart);
                apart
            }
        };
        !apart
    }

    /// Whether body triangle `i` stays apart from scene triangle `j` over
    /// the interval of `frame`, certified in the body's frame (module docs,
    /// "In the body's frame"): the scene triangle's twelve relative points
    /// against the body triangle as given, more than their sagitta and
    /// rounding apart.
    fn apart_in_body_frame(&self, i: usize, j: usize, frame: &BodyFrame) -> bool {
        let p = self.body.triangles[i].map(|v| self.body.vertices[v as usize]);
        let mut relative = frame.relative.borrow_mut();
        let scene = relative.get(j, || self.relative_triangle(j, frame));
        let ends = [
            [scene.points[0], scene.points[1], scene.points[2]],
            [scene.points[3], scene.points[4], scene.points[5]],
        ];
        let mut pair = Pair::new(&ends, &p);
        certified_deferring(&frame.body_axes_failed, |deferred| {
            pair.apart_between_ends_from(scene.rounding, scene.bow, deferred)
        }) || (swept_hull_may_add(scene.margin, scene.rounding, scene.bow)
            && pair.hull_apart_by_more_than(&scene.points, scene.margin))
    }

    /// Whether every body triangle of `items` stays apart from every
    /// triangle of scene node `j` over the interval of `frame`, certified
    /// in the body's frame (module docs, "Boxes between the ends"): the
    /// node's box carried back at both ends, its points' rounding and bow
    /// as a scene triangle's (`relative_triangle`), against each body
    /// triangle's plane. `false` proves nothing.
    fn leaf_apart_from_node_between_ends(
        &self,
        items: &[u32],
        j: usize,
        frame: &BodyFrame,
    ) -> bool {
        let node = &self.scene.obbs()[j];
        let start = node.seen_from(&frame.ma_t, frame.ta);
        // The second end and the bounds, made once and only where a body
        // triangle's first end is apart (`box_apart_between_ends`).
        let rest = std::cell::OnceCell::new();
        let rest_of_node = || {
            *rest.get_or_init(|| {
                // Every point of the box lies within `|h|(1 + 3β) + fuzz` of
                // its centre (`solid::obb`, "Fitting"; `(1 + 10⁻¹¹)` covers
                // `3β`) and has coordinates at most `|c|∞ + |h|₁(1 + 3β) +
                // fuzz` (`1.01` covers `1 + 3β`, the last factor the sum's
                // rounding): `ρ` and `Y` of "In the body's frame", then `e'`
                // and the bow as a scene triangle's (`relative_triangle`).
                let spread = (norm_up(node.h) + node.fuzz) * (1.0 + 1e-11);
                let y_max = (node.c.abs().max_element() + node.h.element_sum() * 1.01 + node.fuzz)
                    * (1.0 + 1e-11);
                let radius = norm_up(node.c - frame.ta).max(norm_up(node.c - frame.tb)) + spread;
                let (_, rounding, bow) = frame.relative_bounds(radius, y_max);
                let sizes = node.c.abs().max_element()
                    + frame.ta.abs().max_element()
                    + frame.tb.abs().max_element();
                (node.seen_from(&frame.mb_t, frame.tb), sizes, rounding, bow)
            })
        };
        items.iter().all(|&i| {
            let t = self.body.triangles[i as usize].map(|v| self.body.vertices[v as usize]);
            box_apart_between_ends(&t, &start, (node.h, node.fuzz), rest_of_node)
        })
    }

    /// Scene triangle `j` over the interval of `frame`, in the body's
    /// frame (module docs, "In the body's frame"): its twelve relative
    /// points, their rounding, their sagitta's margin and their bow, the
    /// same for every body triangle.
    fn relative_triangle(&self, j: usize, frame: &BodyFrame) -> RelativeTriangle {
        let u = self.scene_triangle(j);
        let mut points = [DVec3::ZERO; 12];
        let (mut radius, mut y_max) = (0.0f64, 0.0f64);
        for (k, y) in u.iter().enumerate() {
            let (qa, qb) = (*y - frame.ta, *y - frame.tb);
            radius = radius.max(norm_up(qa)).max(norm_up(qb));
            y_max = y_max.max(y.abs().max_element());
            points[k] = frame.ma_t * qa;
            points[3 + k] = frame.mb_t * qb;
            points[6 + k] = frame.mb_t * qa;
            points[9 + k] = frame.ma_t * qb;
        }
        let (radius, rounding, bow) = frame.relative_bounds(radius, y_max);
        let margin = (radius * frame.sagitta_per_radius + rounding) * (1.0 + 8.0 * U) + 1e-300;
        RelativeTriangle {
            scene_triangle: j as u32,
            points,
            rounding,
            margin,
            bow,
        }
    }

    /// Whether the body's triangles swept over `[from, to]` (poses at the
    /// interval's ends) stay more than `reach` from every scene triangle,
    /// certified (module docs); `false` means "not proved". The body's
    /// tree is walked with each node's box carried to both poses, joined
    /// with both moved by the other end's translation (which holds the
    /// swept hulls of its triangles), computed once per interval for the
    /// nodes reached; a triangle's own box is the exact box of its swept
    /// hull's twelve points, computed once per interval for the triangles
    /// reached, and only their corners are posed.
    pub(super) fn certified_apart(
        &self,
        from: Pose,
        to: Pose,
        reach: f64,
        s: &mut Scratch,
    ) -> bool {
        self.walk_apart(from, to, reach, None, s, 0, true) == Walk::Apart
    }

    /// [`SceneChecker::certified_apart`] for an interval cut from one that
    /// left `within` uncertified (`query::interval_search`, "Reuse across
    /// halving"; module docs): `None` when certified, else the pairs it
    /// leaves uncertified, recorded in `s.front`.
    fn certified_apart_within(
        &self,
        from: Pose,
        to: Pose,
        (reach, frame): (f64, Option<&BodyFrame>),
        within: Within,
        s: &mut Scratch,
    ) -> Option<Within> {
        let left = if within.is_range() {
            self.pairs_apart(from, to, (reach, frame), within, s)
        } else {
            // Record only right after a certified interval (module docs,
            // "Reuse across halving"): else walk as without a record, the
            // last blocking pair first, stopping at the first pair not
            // certified.
            let start = s.front.len();
            let room = s.front.len() <= FRONT_KEPT;
            let record = if s.last_certified && room {
                FRONT_MOST
            } else {
                0
            };
            match self.walk_apart(from, to, reach, frame, s, record, record == 0) {
                Walk::Apart => None,
                Walk::Recorded => Some(Within {
                    start: start as u32,
                    end: s.front.len() as u32,
                }),
                Walk::Crowded => {
                    s.front.truncate(start);
                    Some(Within::EVERYTHING)
                }
            }
        };
        s.last_certified = left.is_none();
        left
    }

    /// Starts an interval's examination: a new epoch for the lazily posed
    /// vertices at both ends and the per-interval caches.
    fn begin_interval(&self, s: &mut Scratch) {
        let n = self.body.vertices.len();
        s.at.start(n);
        s.at_b.start(n);
        self.fit_node_cache(s);
        let triangles = self.body.triangles.len();
        if s.swept_boxes.len() != triangles {
            s.swept_boxes = vec![[0.0; 7]; triangles];
        }
    }

    /// Whether the swept hull of body triangle `i` (`hull`) may come
    /// within `reach` of scene triangle `j`: its exact box within reach of
    /// the triangle's box, and not certified apart.
    fn pair_near(
        &self,
        hull: &[DVec3; 12],
        i: usize,
        j: usize,
        reach: f64,
        frame: Option<&BodyFrame>,
    ) -> bool {
        hull_box(hull).within(&self.scene.tree().boxes()[j], reach)
            && self.hull_near(hull, i, j, reach, frame)
    }

    /// The pairs of `within` (a range of `s.front`) over `[from, to]`:
    /// `None` when every one is certified apart, else the range of those
    /// that are not, appended to the record after dropping what lies above
    /// `within` (`query::interval_search`, "Reuse across halving": those
    /// entries belong to finished intervals).
    fn pairs_apart(
        &self,
        from: Pose,
        to: Pose,
        (reach, frame): (f64, Option<&BodyFrame>),
        within: Within,
        s: &mut Scratch,
    ) -> Option<Within> {
        self.begin_interval(s);
        s.front.truncate(within.end as usize);
        let start = s.front.len();
        let mut last_hull: Option<(u32, [DVec3; 12])> = None;
        for k in within.start as usize..within.end as usize {
            let (i, j) = s.front[k];
            let hull = match last_hull {
                Some((h, hull)) if h == i => hull,
                _ => {
                    let hull = self.swept_points((&mut s.at, &mut s.at_b), i as usize, &from, &to);
                    last_hull = Some((i, hull));
                    hull
                }
            };
            if self.pair_near(&hull, i as usize, j as usize, reach, frame) {
                s.front.push((i, j));
            }
        }
        (s.front.len() > start).then_some(Within {
            start: start as u32,
            end: s.front.len() as u32,
        })
    }

    /// The walk of [`SceneChecker::certified_apart`]: the last blocking
    /// pair tried first when `blocker_first`; up to `record` pairs not
    /// certified are appended to `s.front` and the walk goes on past
    /// them, and the next one stops it ([`Walk::Crowded`]).
    #[allow(clippy::too_many_arguments)]
    fn walk_apart(
        &self,
        from: Pose,
        to: Pose,
        reach: f64,
        frame: Option<&BodyFrame>,
        s: &mut Scratch,
        record: usize,
        blocker_first: bool,
    ) -> Walk {
        self.begin_interval(s);
        let scene = self.scene.tree();
        if let Some((i, j)) = s.blocker.filter(|_| blocker_first) {
            let hull = self.swept_points((&mut s.at, &mut s.at_b), i, &from, &to);
            if self.pair_near(&hull, i, j, reach, frame) {
                return Walk::Crowded;
            }
        }
        let (ma, ta, mb, tb) = (
            from.rotation.matrix(),
            from.translation,
            to.rotation.matrix(),
            to.translation,
        );
        let pad = self.pad(&from).max(self.pad(&to));
        let shift = tb - ta;
        let swept = |b: &Aabb| {
            let (a, z) = (b.transformed(&ma, ta, pad), b.transformed(&mb, tb, pad));
            a.join(&z)
                .join(&shifted(&a, shift))
                .join(&shifted(&z, -shift))
        };
        let bounds = self.body.tree().bounds();
        let mut cache = std::mem::take(&mut s.node_cache);
        let cache_cells = cells(&mut cache);
        let mut swept_boxes = std::mem::take(&mut s.swept_boxes);
        let swept_boxes_cells = cells(&mut swept_boxes);
        let epoch = s.at.epoch;
        let mut stack = std::mem::take(&mut s.stack);
        let mut front = std::mem::take(&mut s.front);
        let mut recorded = 0;
        let lazy = std::cell::RefCell::new((&mut s.at, &mut s.at_b));
        let hull_of = |i: usize| {
            let (at, at_b) = &mut *lazy.borrow_mut();
            self.swept_points((at, at_b), i, &from, &to)
        };
        // A triangle's box: the exact box of its swept hull's points, as
        // computed (what `apart_by_more_than` certifies; module docs).
        let own_box = |i: usize| cached(swept_boxes_cells, epoch, i, || hull_box(&hull_of(i)));
        let mut blocker = None;
        // The walk meets each body triangle's pairs one after another: its
        // hull is kept for the next pair.
        let mut last_hull: Option<(usize, [DVec3; 12])> = None;
        // Then the oriented boxes (`solid::obb`): a node's swept hulls lie
        // within `swept_reach` of its box posed at `from` (module docs).
        let turn = spectral_norm_up(mb - ma);
        let size = self.body.reach + ta.abs().max_element().max(tb.abs().max_element());
        // Norms as sums of magnitudes: never below the Euclidean norm and
        // never underflowing (squares of coordinates below 1e-154 would).
        let shift_len = shift.abs().element_sum() * (1.0 + 1e-12);
        let oriented = pose_skew(&ma).is_some();
        let oriented_b = oriented && pose_skew(&mb).is_some();
        let mut obb_cache = std::mem::take(&mut s.obb_cache);
        let obb_cache_cells = cells(&mut obb_cache);
        let mut obb_cache_b = std::mem::take(&mut s.obb_cache_b);
        let obb_cache_b_cells = cells(&mut obb_cache_b);
        let (body_obbs, scene_obbs) = (self.body.obbs(), self.scene.obbs());
        let obb_apart = |k: usize, j: usize| {
            let a = &body_obbs[k];
            let posed = cached(obb_cache_cells, epoch, k, || a.posed(&ma, ta));
            // The box's own swept hull (`solid::obb`, "The swept test"):
            // second order in the turn where the reach below is first. When
            // it applies it is the only test: the first-order reach after
            // it certified too few pairs to pay for itself (4–9% of a
            // near-contact decision's instructions on robot parts,
            // docs/BENCHMARKS.md, "The bow first").
            if oriented_b {
                let posed_b = cached(obb_cache_b_cells, epoch, k, || a.posed(&mb, tb));
                return scene_obbs[j].swept_apart(
                    [&posed, &posed_b],
                    shift,
                    a.h,
                    a.fuzz,
                    pad,
                    reach,
                );
            }
            let radius = (norm_up(a.c) + norm_up(a.h) + a.fuzz) * (1.0 + 1e-11);
            let swept_reach = turn * radius
                + 2.0 * shift_len
                + 4.0 * pad
                + 8.0 * f64::EPSILON * (size + 2.0 * shift_len)
                + 1e-300;
            scene_obbs[j].apart(&posed, a.h, a.fuzz + swept_reach + reach, pad)
        };
        let body_tree = self.body.tree();
        let blocked = body_tree.for_each_pair(
            |k, j, o| {
                cached(cache_cells, epoch, k, || swept(&bounds[k])).within(o, reach)
                    // Not at two leaves (module docs).
                    && !(oriented
                        && (body_tree.leaf_items(k).is_none() || scene.leaf_items(j).is_none())
                        && obb_apart(k, j))
                    // A body leaf against a scene node's box between the
                    // ends, in the body's frame (module docs, "Boxes
                    // between the ends").
                    && !(scene.leaf_items(j).is_none()
                        && frame.is_some_and(|f| {
                            body_tree.leaf_items(k).is_some_and(|items| {
                                self.leaf_apart_from_node_between_ends(items, j, f)
                            })
                        }))
            },
            |k| bounds[k].size(),
            |i, o| own_box(i).within(o, reach),
            |i, o| own_box(i).within(o, reach),
            scene,
            scene.boxes(),
            scene.bounds(),
            &mut stack,
            |i, j| {
                let hull = match last_hull {
                    Some((k, hull)) if k == i => hull,
                    _ => {
                        let hull = hull_of(i);
                        last_hull = Some((i, hull));
                        hull
                    }
                };
                if !self.hull_near(&hull, i, j, reach, frame) {
                    return false;
                }
                blocker.get_or_insert((i, j));
                if recorded < record {
                    front.push((i as u32, j as u32));
                    recorded += 1;
                    return false;
                }
                true
            },
        );
        s.stack = stack;
        s.front = front;
        s.node_cache = cache;
        s.swept_boxes = swept_boxes;
        s.obb_cache = obb_cache;
        s.obb_cache_b = obb_cache_b;
        if blocker.is_some() {
            s.blocker = blocker;
        }
        if blocked {
            Walk::Crowded
        } else if recorded > 0 {
            Walk::Recorded
        } else {
            Walk::Apart
        }
    }

    /// Whether every triangle of the body at `pose` is more than `reach`
    /// from every scene triangle, certified (`false`: not proved): the
    /// swept test of an interval whose ends are both `pose`.
    pub(crate) fn apart_at(&self, pose: Pose, reach: f64) -> bool {
        let mut s = self.scratch();
        let out = self.certified_apart(pose, pose, reach, &mut s);
        self.give_back(s);
        out
    }

    /// Checks the straight motion from `from` to `to` (module docs) with
    /// the bracket no wider than `tolerance` (in `t`).
    ///
    /// # Errors
    /// [`MotionError::Tolerance`] for a tolerance outside
    /// `[MIN_TOLERANCE, 1)` ([`crate::query::MIN_TOLERANCE`]);
    /// [`MotionError::Query`] when a posed coordinate is not finite;
    /// [`MotionError::Undecided`] for a grazing motion;
    /// [`MotionError::BudgetExhausted`] past the budget.
    pub fn check(&self, from: Pose, to: Pose, tolerance: f64) -> Result<MotionCheck, MotionError> {
        MotionError::check_tolerance(tolerance)?;
        let mut s = self.scratch();
        let out = self.search(from, to, tolerance, &mut s);
        self.give_back(s);
        out
    }

    /// [`SceneChecker::check`] with a tolerance already checked, on the
    /// buffers `s`.
    fn search(
        &self,
        from: Pose,
        to: Pose,
        tolerance: f64,
        s: &mut Scratch,
    ) -> Result<MotionCheck, MotionError> {
        self.check_range(&to)?;
        if self.collides_with(from, s)? {
            return Ok(MotionCheck::Collides {
                t_safe: None,
                t_contact: 0.0,
            });
        }
        let motion = Motion::new(from, to);
        s.front.clear();
        s.last_certified = false;
        let mut intervals = std::mem::take(&mut s.intervals);
        let mut steps_left = self.budget;
        let mut sweep = BodySweep::new(self, motion, &mut *s);
        let travel =
            motion.angle() * self.body.reach + (to.translation - from.translation).length();
        let pieces = first_pieces(travel, self.body.reach, self.budget);
        let found = first_contact(
            &mut sweep,
            1.0,
            pieces,
            tolerance,
            &mut steps_left,
            &mut intervals,
        );
        s.intervals = intervals;
        self.steps
            .fetch_add(self.budget - steps_left, Ordering::Relaxed);
        match found {
            Ok(None) => Ok(MotionCheck::Free),
            Ok(Some((t_safe, t_contact))) => Ok(MotionCheck::Collides {
                t_safe: Some(t_safe),
                t_contact,
            }),
            Err(stop) => Err(MotionError::from_stop(stop, self.budget)),
        }
    }

    /// [`Checker::check_many`] (here without the trait in scope): the
    /// motions `(from, to)` in parallel (rayon), in order.
    ///
    /// # Errors
    /// The first error of [`SceneChecker::check`].
    pub fn check_many(
        &self,
        motions: &[(Pose, Pose)],
        tolerance: f64,
    ) -> Result<Vec<MotionCheck>, MotionError> {
        Checker::check_many(self, motions, tolerance)
    }
}

/// How many equal intervals the search starts from
/// (`query::interval_search`): [`PIECES_PER_REACH`] for each length of the
/// body's reach that its farthest point travels (`travel`: the turn times
/// the reach, plus the translation), rounded up, from 1 to `budget / 64`
/// (so a small budget is spent as before, on the halving) and at most 64.
/// A schedule only: any cut is sound.
fn first_pieces(travel: f64, reach: f64, budget: u64) -> usize {
    let most = (budget / 64).clamp(1, 64) as f64;
    let pieces = (PIECES_PER_REACH * travel / reach).ceil();
    if pieces.is_finite() {
        pieces.clamp(1.0, most) as usize
    } else {
        1
    }
}

/// The first intervals per reach travelled ([`first_pieces`]), chosen by
/// measurement on the motions RRTConnect asks on OMPL.app's problems
/// (docs/BENCHMARKS.md): a failed attempt to certify a wide interval
/// walks every triangle pair near its swept hulls before the one that
/// is too near, about as much work as a success, and a motion that sweeps
/// the body farther than its reach is seldom certified whole. On the
/// alpha puzzle's free motions (100° turns) 2 cuts the median check from
/// 1.8 ms to 19 µs; on the free motions of eleven problems 1 had the
/// higher mean time on 8 and 4 on 6. A short planner motion (a few
/// degrees, a fraction of the reach) stays one piece.
const PIECES_PER_REACH: f64 = 2.0;

/// The whole body's search with a check's buffers: what the interval
/// search runs (`query::interval_search`).
struct BodySweep<'a> {
    checker: &'a SceneChecker,
    motion: Motion,
    /// The body's margin over the motion.
    margin: SweepMargin,
    s: &'a mut Scratch,
}

impl<'a> BodySweep<'a> {
    /// The search of `motion` by `checker` on the buffers `s`.
    fn new(checker: &'a SceneChecker, motion: Motion, s: &'a mut Scratch) -> BodySweep<'a> {
        BodySweep {
            checker,
            margin: SweepMargin::new(
                motion.angle(),
                motion.translation_extent(),
                checker.body.reach,
            ),
            motion,
            s,
        }
    }
}

impl Sweep for BodySweep<'_> {
    type Error = QueryError;

    fn certified_free(&mut self, a: f64, b: f64) -> Result<bool, QueryError> {
        let reach = self.margin.inflation(b - a);
        let (from, to) = (self.motion.at(a), self.motion.at(b));
        Ok(self.checker.certified_apart(from, to, reach, self.s))
    }

    fn collides_at_time(&mut self, t: f64) -> Result<bool, QueryError> {
        self.checker.collides_with(self.motion.at(t), self.s)
    }

    fn certified_free_within(
        &mut self,
        a: f64,
        b: f64,
        within: Within,
    ) -> Result<Option<Within>, QueryError> {
        let reach = self.margin.inflation(b - a);
        let (from, to) = (self.motion.at(a), self.motion.at(b));
        let mut relative = std::mem::take(&mut self.s.relative);
        relative.start(self.checker.scene.triangles.len());
        let frame = BodyFrame::over(&self.margin, &self.motion, (a, b), relative);
        let left =
            self.checker
                .certified_apart_within(from, to, (reach, Some(&frame)), within, self.s);
        self.s.relative = frame.relative.into_inner();
        Ok(left)
    }
}

/// Whether the swept hull's test with margin `margin` may certify a pair
/// that the bowed chord's, with `rounding` at the ends and bow `bow`, did
/// not (module docs, "The swept hull after the bow"): `false` when a gap
/// above `margin` at every hull point, so above `margin − rounding` at
/// both ends after their rounding, makes the bowed chord positive.
fn swept_hull_may_add(margin: f64, rounding: f64, bow: f64) -> bool {
    let least = margin - rounding;
    !(least > 1e-140 && 4.0 * least > bow * (1.0 + 1e-9))
}

/// The axes (`gap::Pair`'s, bit `k` for axis `k`) to try last on the next
/// pair certified between an interval's ends, and the pairs asked since
/// all were last tried in order (`gap`'s module docs, "The axes that
/// failed last").
#[derive(Clone, Copy, Default)]
struct DeferredAxes {
    axes: u8,
    pairs: u8,
}

/// Every how many pairs the axes are all tried in their own order.
const PAIRS_BETWEEN_ORDERED: u8 = 8;

/// Whether `certify`, given the axes to try last, certified: those of
/// `deferred` (none every [`PAIRS_BETWEEN_ORDERED`]th pair), which is left
/// holding the axes to defer next when one held (`gap`'s module docs,
/// "The axes that failed last").
fn certified_deferring(
    deferred: &std::cell::Cell<DeferredAxes>,
    certify: impl FnOnce(u8) -> (Option<usize>, u8),
) -> bool {
    let last = deferred.get();
    let pairs = (last.pairs + 1) % PAIRS_BETWEEN_ORDERED;
    let (held, next) = certify(if pairs == 0 { 0 } else { last.axes });
    let axes = if held.is_some() { next } else { last.axes };
    deferred.set(DeferredAxes { axes, pairs });
    held.is_some()
}

/// An interval's end poses for the test in the body's frame (module docs,
/// "In the body's frame").
pub(super) struct BodyFrame {
    /// The transposed rotation matrices of the float poses at the ends.
    ma_t: DMat3,
    mb_t: DMat3,
    /// Their translations.
    ta: DVec3,
    tb: DVec3,
    /// The turn's sagitta per unit radius, rounded up.
    sagitta_per_radius: f64,
    /// `M + D` of the motion (`query::rounding`).
    m_plus_d: f64,
    /// `δ`, the turn over the interval, rounded up.
    turn: f64,
    /// `e`, how far a float-posed body point is from the exact motion's.
    pose_error: f64,
    /// Whether the body's frame certified the last pair that one frame
    /// alone certified: it is then tried first.
    body_frame_first: std::cell::Cell<bool>,
    /// The axes to try last on the next pair between the ends in the
    /// world's frame, and in the body's (`certified_deferring`).
    world_axes_failed: std::cell::Cell<DeferredAxes>,
    body_axes_failed: std::cell::Cell<DeferredAxes>,
    /// The scene triangles' relative points over the interval, each found
    /// once.
    relative: std::cell::RefCell<RelativeTriangles>,
}

impl BodyFrame {
    /// The frame of the interval `[a, b]` of `motion` (module docs, "In
    /// the body's frame"), its search's `margin`, with `relative` for the
    /// scene triangles' points (started for the interval).
    fn over(
        margin: &SweepMargin,
        motion: &Motion,
        (a, b): (f64, f64),
        relative: RelativeTriangles,
    ) -> BodyFrame {
        let (from, to) = (motion.at(a), motion.at(b));
        let (m, d) = motion.translation_extent();
        BodyFrame {
            ma_t: from.rotation.matrix().transpose(),
            mb_t: to.rotation.matrix().transpose(),
            ta: from.translation,
            tb: to.translation,
            sagitta_per_radius: margin.sagitta_per_radius(b - a),
            m_plus_d: m + d,
            turn: margin.turn(b - a),
            pose_error: margin.pose_error(),
            body_frame_first: std::cell::Cell::new(false),
            world_axes_failed: Default::default(),
            body_axes_failed: Default::default(),
            relative: std::cell::RefCell::new(relative),
        }
    }

    /// For scene points whose float `|y − T̃|` at both ends is at most
    /// `radius` and whose coordinates are at most `y_max`: `ρ` (at least
    /// every exact `|y − T|`), `e'` (each relative point's distance from
    /// the exact motion's) and the bow of their paths between the ends
    /// (module docs, "In the body's frame" and "Between the ends"): the
    /// world's rounding bound with `M + D + Y` for `M + D`, its part
    /// without a reach for `ρ`'s slack, all of it for `e'`; the relative
    /// point's second derivative at most `δ² ρ + 2 δ |T(b) − T(a)|`.
    #[inline]
    fn relative_bounds(&self, radius: f64, y_max: f64) -> (f64, f64, f64) {
        let extent = (self.m_plus_d + y_max, 0.0);
        let radius = radius + pose_rounding_bound(0.0, extent);
        let rounding = pose_rounding_bound(radius, extent);
        let shift = norm_up(self.tb - self.ta) * (1.0 + 4.0 * U) + 2.0 * rounding;
        (radius, rounding, body_frame_bow(self.turn, radius, shift))
    }
}

/// How a walk of the body's tree over an interval ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Walk {
    /// Every pair certified.
    Apart,
    /// Some pairs not certified, all recorded.
    Recorded,
    /// Stopped at a pair not certified, with more than could be recorded
    /// (or none to be).
    Crowded,
}

/// The most triangle pairs one walk records for the intervals cut from
/// its interval (module docs, "Reuse across halving"): past it, the walk
/// stops as a walk recording nothing would, at the next pair not
/// certified, and the halves walk the trees again.
const FRONT_MOST: usize = 512;

/// The most entries the record holds before a walk may add to it: an
/// interval not cut from a recorded one appends above entries of finished
/// intervals, never dropped until the search ends, so without a bound the
/// record would grow with the budget (and its `u32` offsets could wrap;
/// found by the independent review). Ranges cut from recorded ones add at
/// most their parent's length per level, so the record stays far below
/// `u32::MAX` (about 1 MB).
const FRONT_KEPT: usize = 1 << 16;

/// The bow of a scene point's path in the body's frame (module docs,
/// "Between the ends"), for a turn `δ`, the point at most `radius` from
/// the body's origin and the translation moving by at most `shift`:
/// `δ² radius / 2 + δ shift`, rounded up.
fn body_frame_bow(turn: f64, radius: f64, shift: f64) -> f64 {
    (0.5 * turn * turn * radius + turn * shift) * (1.0 + 8.0 * U)
}

/// The exact box of a swept hull's twelve points, as computed.
fn hull_box(hull: &[DVec3; 12]) -> Aabb {
    Aabb::of(hull.map(|p| p.to_array()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::MeshBody;
    use crate::kernel::rotation::Rotation;
    use crate::mesh::PolygonMesh;

    /// The search without "Reuse across halving": every interval walks
    /// both trees, with the same tests (the record is dropped each time).
    struct WalkEveryTime<'a>(BodySweep<'a>);

    impl Sweep for WalkEveryTime<'_> {
        type Error = QueryError;

        fn certified_free(&mut self, a: f64, b: f64) -> Result<bool, QueryError> {
            Ok(self
                .certified_free_within(a, b, Within::EVERYTHING)?
                .is_none())
        }

        fn collides_at_time(&mut self, t: f64) -> Result<bool, QueryError> {
            self.0.collides_at_time(t)
        }

        fn certified_free_within(
            &mut self,
            a: f64,
            b: f64,
            _within: Within,
        ) -> Result<Option<Within>, QueryError> {
            self.0.s.front.clear();
            let left = self.0.certified_free_within(a, b, Within::EVERYTHING)?;
            Ok(left.map(|_| Within::EVERYTHING))
        }
    }

    /// The swept hull is skipped only where it cannot certify what the
    /// bowed chord did not (module docs, "The swept hull after the bow"):
    /// on random pairs whose gap is about the margin (half of them sliding
    /// along the scene's plane), at scales 10⁻⁴ to 10³, roundings `e` up to
    /// `m (1 − 10⁻¹⁰)` and bows about `4 (m − e)`, wherever `swept_hull_may_add` says
    /// no and the hull's test certifies, the bow's does too; where it says
    /// yes, the hull certifies pairs the bow does not (the rule is not
    /// vacuous: a laxer rule fails here).
    #[test]
    fn the_swept_hull_is_skipped_only_where_the_bow_certifies_all_it_would() {
        use super::super::gap::Pair;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(61);
        let (mut skipped_and_certified, mut hull_alone) = (0, 0);
        for k in 0..100_000 {
            let scale = 10f64.powi(k % 8 - 4);
            let point = |rng: &mut rand_chacha::ChaCha8Rng, r: f64| {
                DVec3::new(
                    rng.random_range(-r..r),
                    rng.random_range(-r..r),
                    rng.random_range(-r..r),
                ) * scale
            };
            let body = [
                point(&mut rng, 1.0),
                point(&mut rng, 1.0),
                point(&mut rng, 1.0),
            ];
            let (move_a, mut move_b) = (point(&mut rng, 0.2), point(&mut rng, 0.2));
            if k % 2 == 0 {
                // Sliding along the scene's plane: both ends as near as the
                // hull, where the bow is weakest.
                move_b.z = move_a.z;
            }
            let ends = [body.map(|p| p + move_a), body.map(|p| p + move_b)];
            let shift = move_b - move_a;
            let hull: [DVec3; 12] = std::array::from_fn(|i| match i / 3 {
                0 => ends[0][i % 3],
                1 => ends[1][i % 3],
                2 => ends[0][i % 3] + shift,
                _ => ends[1][i % 3] - shift,
            });
            let top = hull.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
            let margin = rng.random_range(0.001..0.1) * scale;
            // Rounding far above `m − e` too (a translation's motion, where
            // the sagitta is tiny beside the posing's rounding).
            let rounding = if k % 4 == 1 {
                margin * (1.0 - 10f64.powf(-rng.random_range(2.0..10.0)))
            } else {
                margin * rng.random_range(0.0..0.5)
            };
            let bow = 4.0 * (margin - rounding) * rng.random_range(0.9..1.1);
            let h = top + margin * rng.random_range(0.99..1.5);
            let u = [
                DVec3::new(-5.0, -5.0, 0.0) * scale + DVec3::Z * h,
                DVec3::new(5.0, -5.0, 0.0) * scale + DVec3::Z * h,
                DVec3::new(0.0, 5.0, 0.0) * scale + DVec3::Z * h,
            ];
            // Turned as a whole: the scene's normal is then not an axis.
            let turn = glam::DMat3::from_axis_angle(
                point(&mut rng, 1.0).normalize(),
                rng.random_range(0.0..3.0),
            );
            let (ends, hull, u) = (
                ends.map(|t| t.map(|p| turn * p)),
                hull.map(|p| turn * p),
                u.map(|p| turn * p),
            );
            if !Pair::new(&ends, &u).hull_apart_by_more_than(&hull, margin) {
                continue;
            }
            let bow_certifies = Pair::new(&ends, &u).apart_between_ends(rounding, bow);
            if swept_hull_may_add(margin, rounding, bow) {
                hull_alone += usize::from(!bow_certifies);
            } else {
                assert!(bow_certifies, "{ends:?} {u:?} {margin} {rounding} {bow}");
                skipped_and_certified += 1;
            }
        }
        assert!(skipped_and_certified > 10_000, "{skipped_and_certified}");
        assert!(hull_alone > 1_000, "{hull_alone}");
    }

    /// The frame of "In the body's frame" over the whole of `motion`, as
    /// `certified_free_within` makes it for an interval.
    fn frame_of(checker: &SceneChecker, motion: Motion) -> BodyFrame {
        let margin = SweepMargin::new(
            motion.angle(),
            motion.translation_extent(),
            checker.body.reach,
        );
        BodyFrame::over(&margin, &motion, (0.0, 1.0), RelativeTriangles::default())
    }

    /// Boxes between the ends (module docs): a scene node certified
    /// against a body leaf meets it nowhere on the motion. A body corner
    /// swinging on an arc through a finely cut face between ends clear of
    /// it (the arc pokes `0.005` through at its apex, the ends are clear by
    /// about `0.04`), both ways round: no node holding a triangle the
    /// corner meets is certified, and the motion is never called free
    /// (without the bow the chord's test certifies them). Then random
    /// blobs and plates near each other on random motions, every 97th
    /// certified node's triangles checked against the leaf's at 41 times
    /// of the motion.
    #[test]
    fn a_node_certified_between_the_ends_meets_no_body_triangle() {
        use crate::solid::intersect::triangles_meet;
        use rand::{Rng, SeedableRng};
        let (r, poke, delta) = (10.0, 0.005, 0.2f64);
        let spike = spike(r);
        // The face `x = r − poke`, cut into 2·24² triangles.
        let cuts = 24;
        let mut vertices = Vec::new();
        for i in 0..=cuts {
            for j in 0..=cuts {
                let (y, z) = (
                    -5.0 + 10.0 * i as f64 / cuts as f64,
                    -5.0 + 10.0 * j as f64 / cuts as f64,
                );
                vertices.push([r - poke, y, z]);
            }
        }
        let at = |i: usize, j: usize| i * (cuts + 1) + j;
        let mut faces = Vec::new();
        for i in 0..cuts {
            for j in 0..cuts {
                faces.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                faces.push(vec![at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        let face = PolygonMesh::new(vertices, faces);
        let yaw = |a: f64| Pose::new(Rotation::from_axis_angle(DVec3::Z, a).unwrap(), DVec3::ZERO);
        let (from, to) = (yaw(-delta / 2.0), yaw(delta / 2.0));
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(35);
        let (mut certified, mut checked) = (0usize, 0usize);
        // Every `stride`-th certified node against the leaf's triangles at
        // `times` + 1 times of the motion.
        let mut verify = |checker: &SceneChecker, motion: Motion, times: usize, stride: usize| {
            let frame = frame_of(checker, motion);
            let (body_tree, scene_tree) = (checker.body.tree(), checker.scene.tree());
            let spans = scene_tree.node_spans();
            let items = scene_tree.items();
            let mut found = 0;
            for k in 0..body_tree.bounds().len() {
                let Some(leaf) = body_tree.leaf_items(k) else {
                    continue;
                };
                for (j, &(a, b)) in spans.iter().enumerate() {
                    if scene_tree.leaf_items(j).is_some()
                        || !checker.leaf_apart_from_node_between_ends(leaf, j, &frame)
                    {
                        continue;
                    }
                    found += 1;
                    if found % stride != 0 {
                        continue;
                    }
                    for step in 0..=times {
                        let pose = motion.at(step as f64 / times as f64);
                        for &i in leaf {
                            let t = checker.body.triangles[i as usize]
                                .map(|v| pose.apply(checker.body.vertices[v as usize]));
                            for &u in &items[a as usize..b as usize] {
                                let u = checker.scene_triangle(u as usize);
                                assert!(!triangles_meet(&t, &u), "leaf {k} node {j} at {step}");
                                checked += 1;
                            }
                        }
                    }
                }
            }
            found
        };
        // A cluster of triangles at the spike's tip (a scene with inner
        // nodes, whose boxes the face's leaves are tested against).
        let tip = blob(&mut rng, 200, 0.003, DVec3::new(r - poke, 0.0, 0.0));
        for (body, scene) in [(&spike, &face), (&face, &tip)] {
            let checker = checker_of(body, scene);
            assert!(!checker.collides_at(from).unwrap() && !checker.collides_at(to).unwrap());
            assert!(checker.collides_at(yaw(0.0)).unwrap());
            certified += verify(&checker, Motion::new(from, to), 200, 1);
            assert!(matches!(
                checker.check(from, to, 1e-6).unwrap(),
                MotionCheck::Collides { .. }
            ));
        }
        for case in 0..12 {
            let plate = PolygonMesh::new(
                vec![
                    [-0.6, -0.4, 0.0],
                    [0.6, -0.4, 0.0],
                    [0.6, 0.4, 0.0],
                    [-0.6, 0.4, 0.0],
                ],
                vec![vec![0, 1, 2, 3]],
            );
            let body = if case % 2 == 0 {
                plate
            } else {
                blob(&mut rng, 40, 0.5, DVec3::ZERO)
            };
            let centre = DVec3::new(0.0, 0.0, rng.random_range(0.45..0.9));
            let scene = blob(&mut rng, 400, 0.4, centre);
            let checker = checker_of(&body, &scene);
            let mut axis = || {
                DVec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                )
            };
            let (a, b) = (axis(), axis());
            let from = Pose::new(Rotation::from_axis_angle(a, 0.3 * a.x).unwrap(), 0.05 * b);
            let turn = Rotation::from_axis_angle(b, 0.4 * b.y).unwrap();
            let to = Pose::new(from.rotation.then(&turn), from.translation + 0.05 * a);
            certified += verify(&checker, Motion::new(from, to), 40, 97);
        }
        // Both kinds are met, and the certificates are checked widely.
        assert!(
            certified > 100_000 && checked > 1_000_000,
            "{certified} {checked}"
        );
    }

    /// Found by the independent review of boxes between the ends: scene
    /// coordinates near `7·10³⁰⁷` made a node box's carried centre
    /// overflow to `+∞`, read as an infinite gap, and a motion ending in
    /// the scene was called free.
    #[test]
    fn regression_an_overflowing_box_centre_proves_nothing() {
        let s = 0.36898513638629843;
        let body = PolygonMesh::new(
            vec![[s, -s, 0.0], [0.0, s, -s], [-s, 0.0, s]],
            vec![vec![0, 1, 2]],
        );
        let (v, b) = (-1.702893502890368e292, 7.335425499690069e307);
        let scene = PolygonMesh::new(
            vec![[v, v, v], [b, b, b], [b, b, v], [v, b, b], [b, v, b]],
            vec![vec![0, 1, 2], vec![0, 1, 3], vec![0, 1, 4]],
        );
        let checker = checker_of(&body, &scene);
        let from = Pose::new(Rotation::IDENTITY, DVec3::splat(-2.3083342940609796e292));
        let to = Pose::new(Rotation::IDENTITY, DVec3::splat(-1.5718013869302512e292));
        assert!(checker.collides_at(to).unwrap());
        match checker.check(from, to, 1e-6).unwrap() {
            MotionCheck::Collides { t_contact, .. } => {
                assert!(checker
                    .collides_at(Motion::new(from, to).at(t_contact))
                    .unwrap());
            }
            MotionCheck::Free => panic!("a motion into the scene called free"),
        }
    }

    /// The checker of one body mesh against one scene mesh.
    fn checker_of(body: &PolygonMesh, scene: &PolygonMesh) -> SceneChecker {
        SceneChecker::new(
            &MeshBody::new(body).unwrap(),
            &[MeshBody::new(scene).unwrap()],
        )
        .unwrap()
    }

    /// A spike: one triangle from `(r, 0, 0)` back to `x = r/2`, 0.2 wide,
    /// whose corner swings on an arc of radius `r` as the body yaws.
    fn spike(r: f64) -> PolygonMesh {
        PolygonMesh::new(
            vec![[r, 0.0, 0.0], [r / 2.0, 0.1, 0.0], [r / 2.0, -0.1, 0.0]],
            vec![vec![0, 1, 2]],
        )
    }

    /// A random hull of `n` points of radius about `r` at `c`, as a mesh.
    fn blob(rng: &mut impl rand::Rng, n: usize, r: f64, c: DVec3) -> PolygonMesh {
        let points: Vec<[f64; 3]> = (0..n)
            .map(|_| {
                let p = DVec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                (c + p.normalize_or_zero() * r).to_array()
            })
            .collect();
        crate::Polytope::from_points(&points).unwrap().to_mesh()
    }

    /// Halving with the record of uncertified pairs answers as walking
    /// every interval does: on short motions from near-contact poses
    /// (where the record is a few pairs) and on long ones through the
    /// scene (where a walk finds more pairs than it may record), every
    /// verdict agrees and every contact found is one.
    #[test]
    fn halving_on_the_recorded_pairs_answers_as_walking_every_interval() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(36);
        let body = MeshBody::new(&blob(&mut rng, 300, 1.0, DVec3::ZERO)).unwrap();
        let scene: Vec<MeshBody> = (0..3)
            .map(|k| {
                let c = DVec3::new(2.2 * k as f64 - 2.2, 0.0, 0.0);
                MeshBody::new(&blob(&mut rng, 300, 0.9, c)).unwrap()
            })
            .collect();
        let checker = SceneChecker::new(&body, &scene).unwrap();
        let (mut near, mut crowded, mut both_free) = (0, 0, 0);
        for k in 0..60 {
            let long = k % 4 == 3;
            let axis = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
            .normalize();
            let turn = Rotation::from_axis_angle(axis, rng.random_range(0.0..1.0)).unwrap();
            // A free pose within 2^-40 of contact, bisected along z.
            let base = Pose::new(turn, DVec3::new(rng.random_range(-2.0..2.0), 0.3, 0.0));
            let lift = |z: f64| Pose::new(base.rotation, base.translation + DVec3::Z * z);
            let (mut lo, mut hi) = (0.0, 4.0);
            if !checker.collides_at(lift(lo)).unwrap() || checker.collides_at(lift(hi)).unwrap() {
                continue;
            }
            for _ in 0..40 {
                let mid = 0.5 * (lo + hi);
                if checker.collides_at(lift(mid)).unwrap() {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let from = lift(hi);
            let degrees = if long { 60.0 } else { 3.0 };
            let spin = Rotation::from_axis_angle(
                axis.cross(DVec3::Z).normalize_or(DVec3::X),
                rng.random_range(-degrees..degrees) * std::f64::consts::PI / 180.0,
            )
            .unwrap();
            let shift = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            ) * if long { 2.0 } else { 0.02 };
            let to = Pose::new(from.rotation.then(&spin), from.translation + shift);
            for (a, b) in [(from, to), (to, from)] {
                if checker.collides_at(a).unwrap() {
                    continue;
                }
                let recorded = checker.check(a, b, 1e-6);
                let motion = Motion::new(a, b);
                let mut s = checker.scratch();
                let plain = {
                    let mut walk = WalkEveryTime(BodySweep::new(&checker, motion, &mut s));
                    let mut left = checker.budget;
                    first_contact(&mut walk, 1.0, 1, 1e-6, &mut left, &mut Vec::new())
                };
                checker.give_back(s);
                match (&recorded, &plain) {
                    (Ok(MotionCheck::Free), Ok(None)) => both_free += 1,
                    (Ok(MotionCheck::Collides { t_contact, .. }), Ok(Some((_, c)))) => {
                        assert!(checker.collides_at(motion.at(*t_contact)).unwrap());
                        assert!(checker.collides_at(motion.at(*c)).unwrap());
                    }
                    (Err(_), Err(_)) => {}
                    _ => panic!("{recorded:?} against {plain:?}"),
                }
                if long {
                    crowded += 1;
                } else {
                    near += 1;
                }
            }
        }
        assert!(
            near > 40 && crowded > 10 && both_free > 20,
            "{near} {crowded} {both_free}"
        );
    }

    /// A body face tilting over a scene corner `1e-6` above it: every
    /// fixed axis of the world loses the face's length times the turn
    /// (`1e-3` rad, about twice the corner's height), so the swept hull
    /// alone leaves the interval uncertified; in the body's frame the
    /// corner stays `1e-6` above the face, and the interval is certified.
    #[test]
    fn a_face_tilting_over_a_corner_is_certified_in_the_body_frame() {
        let face = PolygonMesh::new(
            vec![[-1.0, -1.0, 0.0], [2.0, -1.0, 0.0], [-1.0, 2.0, 0.0]],
            vec![vec![0, 1, 2]],
        );
        let spike = PolygonMesh::new(
            vec![[0.0, 0.0, 1e-6], [0.1, 0.0, 1.0], [0.0, 0.1, 1.0]],
            vec![vec![0, 1, 2]],
        );
        let checker = checker_of(&face, &spike);
        let tilt = |deg: f64| {
            Pose::new(
                Rotation::from_axis_angle(DVec3::X, deg.to_radians()).unwrap(),
                DVec3::ZERO,
            )
        };
        let (from, to) = (tilt(0.0), tilt(1e-3f64.to_degrees()));
        let motion = Motion::new(from, to);
        let mut s = checker.scratch();
        let mut sweep = BodySweep::new(&checker, motion, &mut s);
        assert!(!sweep.certified_free(0.0, 1.0).unwrap());
        assert_eq!(
            sweep
                .certified_free_within(0.0, 1.0, Within::EVERYTHING)
                .unwrap(),
            None
        );
        // Lifted 2e-6 while tilting, the face passes the corner: never
        // certified, in either frame.
        let lifted = Pose::new(to.rotation, DVec3::new(0.0, 0.0, 2e-6));
        let through = Motion::new(from, lifted);
        let mut sweep = BodySweep::new(&checker, through, &mut s);
        assert!(sweep
            .certified_free_within(0.0, 1.0, Within::EVERYTHING)
            .unwrap()
            .is_some());
        checker.give_back(s);
        assert!(checker.check(from, to, 1e-6).unwrap().is_free());
        assert!(!checker.check(from, lifted, 1e-6).unwrap().is_free());
    }

    /// The bows of "Between the ends" (module docs) hold on random motions
    /// and sub-intervals: every body point's path in the world, and every
    /// scene point's path in the body's frame, is within `λ(1 − λ)` times
    /// its bow of its chord at 200 times; without the term of the
    /// translation the body frame's bow fails on some.
    #[test]
    fn paths_stay_within_their_bows_of_their_chords() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(40);
        let mut short = 0;
        for _ in 0..300 {
            let mut point = |r: f64| {
                DVec3::new(
                    rng.random_range(-r..r),
                    rng.random_range(-r..r),
                    rng.random_range(-r..r),
                )
            };
            let (axis0, axis1, t0, t1, p, y) = (
                point(1.0),
                point(1.0),
                point(2.0),
                point(2.0),
                point(3.0),
                point(5.0),
            );
            let pose = |axis: DVec3, angle: f64, t: DVec3| {
                Pose::new(
                    Rotation::from_axis_angle(axis.normalize(), angle).unwrap(),
                    t,
                )
            };
            // Now and then a turn of nearly half a turn, or one below the
            // slerp's 1e-9 (its normalised lerp), about one axis.
            let (axis1, angle) = match rng.random_range(0..6) {
                0 => (axis0, std::f64::consts::PI - 1e-12),
                1 => (axis0, 1e-10),
                _ => (axis1, rng.random_range(0.0..2.0)),
            };
            let motion = Motion::new(pose(axis0, 0.7, t0), pose(axis1, 0.7 + angle, t1));
            let (a, b) = {
                let (u, v): (f64, f64) = (rng.random_range(0.0..1.0), rng.random_range(0.0..1.0));
                (u.min(v), u.max(v))
            };
            let delta = motion.angle() * (b - a) * (1.0 + 1e-9) + 1e-12;
            let world = |t: f64| motion.at(t).apply(p);
            let relative = |t: f64| {
                let at = motion.at(t);
                at.rotation.matrix().transpose() * (y - at.translation)
            };
            let (ta, tb) = (motion.at(a).translation, motion.at(b).translation);
            let radius = (y - ta).length().max((y - tb).length());
            let bows = [
                bow(delta, p.length()),
                body_frame_bow(delta, radius, (tb - ta).length()),
                body_frame_bow(delta, radius, 0.0),
            ];
            let mut worst = [0.0f64; 3];
            for k in 1..200 {
                let l = k as f64 / 200.0;
                let t = a + (b - a) * l;
                let w = (world(t) - world(a).lerp(world(b), l)).length();
                let r = (relative(t) - relative(a).lerp(relative(b), l)).length();
                let slack = 1e-12;
                worst[0] = worst[0].max((w - slack) / (l * (1.0 - l)));
                worst[1] = worst[1].max((r - slack) / (l * (1.0 - l)));
                worst[2] = worst[2].max((r - slack) / (l * (1.0 - l)));
            }
            assert!(worst[0] <= bows[0], "world: {} > {}", worst[0], bows[0]);
            assert!(
                worst[1] <= bows[1],
                "body frame: {} > {}",
                worst[1],
                bows[1]
            );
            short += usize::from(worst[2] > bows[2]);
        }
        assert!(short > 30, "{short}");
    }

    /// Between the ends (module docs): a corner turning 0.2 rad on an
    /// arc of radius 10 pokes `0.01` through a face at its apex, while at
    /// both ends it is clear of it by about `0.04` (the sagitta less the
    /// poke). The chord between the ends stays clear; only the bow of the
    /// arc meets the face. Both ways round: the body's corner through a
    /// scene face (the world's bow), and a scene corner through the
    /// body's face (the body frame's). Neither motion is called free.
    #[test]
    fn an_arc_through_a_face_between_clear_ends_is_never_certified() {
        let (r, poke, delta) = (10.0, 0.01, 0.2f64);
        let spike = spike(r);
        let face = PolygonMesh::new(
            vec![
                [r - poke, -5.0, -5.0],
                [r - poke, 5.0, -5.0],
                [r - poke, 0.0, 5.0],
            ],
            vec![vec![0, 1, 2]],
        );
        let yaw = |a: f64| Pose::new(Rotation::from_axis_angle(DVec3::Z, a).unwrap(), DVec3::ZERO);
        let (from, to) = (yaw(-delta / 2.0), yaw(delta / 2.0));
        for (body, scene) in [(&spike, &face), (&face, &spike)] {
            let checker = checker_of(body, scene);
            assert!(!checker.collides_at(from).unwrap() && !checker.collides_at(to).unwrap());
            assert!(checker.collides_at(yaw(0.0)).unwrap());
            let mut s = checker.scratch();
            let motion = Motion::new(from, to);
            let mut sweep = BodySweep::new(&checker, motion, &mut s);
            assert!(sweep
                .certified_free_within(0.0, 1.0, Within::EVERYTHING)
                .unwrap()
                .is_some());
            checker.give_back(s);
            match checker.check(from, to, 1e-6).unwrap() {
                MotionCheck::Collides { t_contact, .. } => {
                    assert!(checker.collides_at(motion.at(t_contact)).unwrap());
                }
                MotionCheck::Free => panic!("an arc through a face called free"),
            }
        }
    }

    /// Found by the independent review of the per-interval swept boxes:
    /// when the query counter wrapped inside a state check, the boxes
    /// stamped in the counter's last cycle passed for the next interval's,
    /// and a pose where the body crosses the scene was certified free.
    #[test]
    fn regression_swept_boxes_are_forgotten_when_a_state_check_wraps_the_counter() {
        let scene = PolygonMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [10.0, 0.0, 0.0],
                [11.0, 0.0, 0.0],
                [10.0, 1.0, 0.0],
            ],
            vec![vec![0, 1, 2], vec![3, 4, 5]],
        );
        let body = PolygonMesh::new(
            vec![[0.2, 0.2, -0.5], [0.2, 0.2, 0.5], [0.4, 0.1, 0.0]],
            vec![vec![0, 1, 2]],
        );
        let checker = checker_of(&body, &scene);
        let at = |x: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, 0.0, 0.0));
        let mut s = checker.scratch();
        assert!(!checker.collides_with(at(5.0), &mut s).unwrap());
        assert!(checker.certified_apart(at(5.0), at(5.0), 0.0, &mut s));
        let stamped = s.at.epoch;
        assert!(checker.collides_at(at(0.0)).unwrap());
        // The counter wraps inside a state check; the next interval takes
        // the stamp the boxes at x = 5 carry.
        s.at.epoch = u32::MAX;
        let _ = checker.collides_with(at(5.0), &mut s).unwrap();
        assert!(!checker.certified_apart(at(0.0), at(0.0), 0.0, &mut s));
        assert_eq!(s.at.epoch, stamped);
    }
}

#[cfg(test)]
mod review_tests {
    use super::*;
    use crate::body::MeshBody;
    use crate::kernel::rotation::Rotation;
    use crate::mesh::PolygonMesh;
    use rand::{Rng, SeedableRng};

    fn unit(rng: &mut impl Rng) -> DVec3 {
        loop {
            let v = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            let l = v.length();
            if l > 0.1 && l < 1.0 {
                return v / l;
            }
        }
    }

    fn perp(n: DVec3) -> DVec3 {
        let a = if n.x.abs() < 0.6 { DVec3::X } else { DVec3::Y };
        n.cross(a).normalize()
    }

    fn mesh(p: [DVec3; 3]) -> PolygonMesh {
        PolygonMesh::new(
            p.iter().map(|v| v.to_array()).collect(),
            vec![vec![0, 1, 2]],
        )
    }

    fn angle_draw(rng: &mut impl Rng) -> f64 {
        match rng.random_range(0..5) {
            0 => 10f64.powf(rng.random_range(-12.0..-3.0)),
            1 => rng.random_range(0.0..1.0),
            2 => rng.random_range(2.5..std::f64::consts::PI),
            3 => std::f64::consts::PI,
            _ => rng.random_range(0.0..std::f64::consts::PI),
        }
    }

    /// From the independent review of "Between the ends" (2026-11-30):
    /// adversarial arcs. A spike tip (in the world) or a scene tip seen in
    /// the body's frame whose path has a local extremum along `n` at `t*`,
    /// a face `poke` inside that extremum (or beyond it: a near miss);
    /// turns from 1e-12 to exactly π, translations from 1e-4 to 1e2 of the
    /// size, up to 1e6 from the origin. Every interval about `t*` that
    /// `certified_free_within` certifies has no colliding sample, and the
    /// poked tips collide at `t*`.
    #[test]
    fn review_adversarial_arcs_are_never_certified() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let cases = 400;
        let (mut tested, mut certified, mut bad) = (0, 0, 0);
        let mut per_mode = [[0usize; 3]; 2];
        let (mut miss_cert, mut miss_tested) = (0, 0);
        for k in 0..cases {
            let body_frame = k % 2 == 1;
            let s = 10f64.powf(rng.random_range(-6.0..3.0));
            let far = if rng.random_bool(0.5) {
                10f64.powf(rng.random_range(0.0..6.0))
            } else {
                0.0
            };
            let origin = unit(&mut rng) * far;
            let r0 = Rotation::from_axis_angle(unit(&mut rng), rng.random_range(0.0..3.0)).unwrap();
            let r1 =
                r0.then(&Rotation::from_axis_angle(unit(&mut rng), angle_draw(&mut rng)).unwrap());
            let t0 = origin + unit(&mut rng) * s * rng.random_range(0.0..2.0);
            let t1 = t0 + unit(&mut rng) * s * 10f64.powf(rng.random_range(-4.0..2.0));
            let (from, to) = (Pose::new(r0, t0), Pose::new(r1, t1));
            let motion = Motion::new(from, to);
            let star: f64 = rng.random_range(0.05..0.95);
            let tip_body = unit(&mut rng) * s * rng.random_range(0.3..1.0);
            // The tip's path, in the world (world mode) or in the body's
            // frame (body-frame mode, for the scene point `y`).
            let y = motion.at(star).apply(tip_body);
            let path = |t: f64| -> DVec3 {
                let p = motion.at(t);
                if body_frame {
                    p.rotation.matrix().transpose() * (y - p.translation)
                } else {
                    p.apply(tip_body)
                }
            };
            let h = 1e-3;
            let (fm, f0, fp) = (path(star - h), path(star), path(star + h));
            let d1 = (fp - fm) / (2.0 * h);
            let d2 = (fp - 2.0 * f0 + fm) / (h * h);
            let d1n = d1.normalize_or_zero();
            let mut n = -(d2 - d1n * d1n.dot(d2));
            if n.length() < 1e-6 * d2.length().max(s * 1e-9) || !n.is_finite() {
                n = perp(if d1n == DVec3::ZERO { DVec3::Z } else { d1n });
            }
            let n = n.normalize();
            let curvature = (-n.dot(d2)).max(1e-12 * s);
            let sag = curvature / 8.0;
            let scale = s + far;
            let pose_error = pose_rounding_bound(2.0 * s, motion.translation_extent());
            let poke_frac = 10f64.powf(-rng.random_range(0.0..7.0));
            let poke = (sag * poke_frac).min(0.1 * s);
            if poke < 1e4 * pose_error + 1e-14 * scale {
                continue;
            }
            let near_miss = rng.random_bool(0.3);
            let depth = if near_miss { -poke } else { poke };
            let dt = (2.0 * poke / curvature).sqrt();
            let radius = 4.0 * d1.length() * dt + 0.05 * s + 8.0 * poke;
            let centre = f0 - n * depth;
            let (u, v) = (perp(n), n.cross(perp(n)));
            let face = [
                centre + u * radius,
                centre + (u * -0.5 + v * 0.866) * radius,
                centre + (u * -0.5 - v * 0.866) * radius,
            ];
            // The spike: the tip and two corners back from it, off the face.
            let w = perp(n);
            let (body_mesh, scene_mesh) = if body_frame {
                let nw = motion.at(star).rotation.matrix() * n;
                let w = motion.at(star).rotation.matrix() * w;
                let back = y - nw * (0.3 * s);
                let spike = [y, back + w * 0.02 * s, back - w * 0.02 * s];
                (mesh(face), mesh(spike))
            } else {
                // In the body's frame, `n` at `t*` is R(t*)ᵀ n.
                let m = motion.at(star).rotation.matrix().transpose();
                let nb = m * n;
                let wb = m * w;
                let back = tip_body - nb * (0.3 * s);
                let spike = [tip_body, back + wb * 0.02 * s, back - wb * 0.02 * s];
                (mesh(spike), mesh(face))
            };
            let Ok(body) = MeshBody::new(&body_mesh) else {
                continue;
            };
            let Ok(scene) = MeshBody::new(&scene_mesh) else {
                continue;
            };
            let checker = SceneChecker::new(&body, &[scene]).unwrap();
            tested += 1;
            let star_hits = checker.collides_at(motion.at(star)).unwrap();
            if !near_miss {
                per_mode[usize::from(body_frame)][0] += 1;
                per_mode[usize::from(body_frame)][1] += usize::from(star_hits);
            } else {
                per_mode[usize::from(body_frame)][2] += 1;
            }
            let mut sc = checker.scratch();
            let mut intervals = vec![(0.0, 1.0)];
            for _ in 0..4 {
                let a = star
                    - rng.random_range(0.0..1.0) * star * 10f64.powf(-rng.random_range(0.0..3.0));
                let b = star
                    + rng.random_range(0.0..1.0)
                        * (1.0 - star)
                        * 10f64.powf(-rng.random_range(0.0..3.0));
                intervals.push((a, b));
            }
            for (a, b) in intervals {
                let ok = {
                    let mut sweep = BodySweep::new(&checker, motion, &mut sc);
                    sweep.s.front.clear();
                    sweep
                        .certified_free_within(a, b, Within::EVERYTHING)
                        .unwrap()
                        .is_none()
                };
                if near_miss {
                    miss_tested += 1;
                    miss_cert += usize::from(ok);
                }
                if !ok {
                    continue;
                }
                certified += 1;
                let mut times: Vec<f64> = (0..=64).map(|j| a + (b - a) * j as f64 / 64.0).collect();
                for j in -16..=16 {
                    let t = star + dt * j as f64 / 8.0;
                    if t >= a && t <= b {
                        times.push(t);
                    }
                }
                if let Some(t) = times
                    .iter()
                    .find(|&&t| checker.collides_at(motion.at(t)).unwrap())
                {
                    bad += 1;
                    eprintln!(
                        "VIOLATION k={k} frame={body_frame} [{a},{b}] t={t} s={s:e} far={far:e} angle={} poke={poke:e} sag={sag:e} from={from:?} to={to:?} body={body_mesh:?} scene={scene_mesh:?}",
                        motion.angle()
                    );
                }
            }
            checker.give_back(sc);
        }
        assert_eq!(bad, 0);
        assert!(
            tested > 200 && certified > 100 && miss_cert > 50,
            "{tested} {certified} {miss_cert}/{miss_tested}"
        );
        // Every poked tip collides at `t*` (the cases are what they say).
        for [poked, hit, _] in per_mode {
            assert_eq!(poked, hit, "{per_mode:?}");
        }
    }
}
