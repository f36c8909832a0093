//! The one interval search both motion checks run
//! ([`crate::query::MotionChecker`] once per piece pair,
//! [`crate::query::SceneChecker`] once for the whole body), and the one
//! margin both add to what they certify over an interval.
//!
//! A checker plugs in two answers ([`Sweep`]): whether an interval `[a, b]`
//! of the motion is *certified free* (no contact at any `t` in it: `false`
//! means "not proved", never "collides"), and whether the body collides
//! at one time `t` (exact, at the float pose
//! [`Motion::at`](crate::query::Motion::at)). How each
//! checker certifies an interval, and why that is sound, is in its own
//! module docs (`query::motion`: a swept convex piece against a convex
//! obstacle; `query::scene::sweep`: swept triangles against triangles).
//!
//! # The margin
//! Over an interval `[a, b]` the rotation turns by `δ = Θ (b − a)` about
//! one fixed axis of the body (`Θ` the whole motion's angle, at most `π`
//! on the shorter arc: slerp turns at a constant rate), so a body point
//! `p` with `|p| ≤ r` (`r` the reach about the body's origin) moves on a
//! circle arc of angle `δ ≤ π` and radius at most `r`, whose points lie
//! within the sagitta `s = r (1 − cos(δ/2)) = 2 r sin²(δ/4)` of the chord
//! between its ends `R(a) p` and `R(b) p`; the translation moves on the
//! segment `[T(a), T(b)]`. So at every `t` in `[a, b]` the point lies
//! within `s` of `conv(R(a) p, R(b) p) ⊕ [T(a), T(b)]`, and a set built
//! from the end poses only (a swept hull) grown by `s` holds the body over
//! the whole interval.
//!
//! The end poses are floats ([`Motion::at`](crate::query::Motion::at)): every point the searches
//! build from them is within `e = 2⁻⁴³ r + 6u (M + D)` of the exact
//! motion's (`u = 2⁻⁵³`, `M` the largest end translation coordinate, `D`
//! the largest of their difference; derived in `query::rounding`: the
//! rotation's error is relative to the reach, the translation's a few ulps
//! of the coordinates). `δ` is rounded up from the float angle plus its
//! error bound (`2⁻⁴⁶`, `query::rounding`), and `s` up (`sin` on
//! `[0, π/4]`, clamped there: the exact `δ/4` never exceeds it).
//! [`SweepMargin::inflation`] is `s + e`: a checker certifies `[a, b]`
//! only when its swept set is more than that apart from every obstacle.
//!
//! # The bow
//! The margin is the same over the whole interval, while a point strays
//! from its chord only inside it. With `λ = (t − a)/(b − a)`, a body point
//! is at `f(λ) = R(a) E(λ) p + T(λ)`, `T` linear in `λ` and `E(λ)` the
//! turn about the fixed axis at the constant rate `δ`: `f'' = R(a) E''(λ)
//! p`, so `|f''| ≤ δ² |p|`. Along any direction `n`, `n·f` is then within
//! `λ(1 − λ)/2` times its largest second derivative of its chord (the
//! error of linear interpolation): `n·f(λ) ≥ (1 − λ) n·f(0) + λ n·f(1) −
//! λ(1 − λ) |n| δ² r / 2` ([`bow`]). With `A` and `B` certified gaps along
//! `n` between a convex part of the body and an obstacle at the two ends
//! (each less `e|n|`), the gap on the way is at least `(1 − λ) A + λ B −
//! λ(1 − λ) c`, `c = |n| δ² r / 2`, positive on all of `[0, 1]` exactly
//! when `A > 0`, `B > 0` and `(√A + √B)² > c`
//! ([`bowed_chord_stays_positive`]). Where the margin needs the sagitta
//! below the clearance at the nearer end, this needs about `c` below the
//! clearance at the farther one: an interval that leaves a grazing pose
//! to first order is certified whole. Both motion checkers try it where
//! the swept set leaves an interval uncertified.
//!
//! # The search
//! Intervals are examined left to right from `[0, limit]` (`limit` is `1`,
//! or for one piece pair of the convex checker the earliest contact that
//! another pair already bracketed), cut first into a few equal pieces
//! where the checker asks for them (the triangle checker, for motions
//! that sweep the body farther than its own reach: a failed attempt to
//! certify a wide interval costs as much as a success, so the wide
//! intervals a long motion would surely halve are not tried); a stack
//! whose right half is pushed first, so the intervals are examined in the order of their left ends,
//! and each one examined starts where the certified ones before it end.
//! Hence the invariant: **when `[a, b]` is examined, `[0, a]` is
//! certified free**. Each examined interval:
//!
//! 1. takes one step of the budget; with none left the search stops with
//!    `[0, a]` certified
//!    ([`MotionError::BudgetExhausted`](crate::query::MotionError::BudgetExhausted));
//! 2. is done when certified free;
//! 3. once no wider than the tolerance, has its right end `b` checked
//!    exactly: a contact there is the bracket `(a, b)`; an interval that
//!    left a record ("Reuse across halving") only once it is
//!    [`STUCK`] times narrower than the tolerance: near a grazing pose
//!    most right ends are free, each a state check near contact, while
//!    halving on a record costs a few pair tests. A contact is then
//!    bracketed by a probe of step 4 or by a right end once stuck, both
//!    at most the tolerance wide, about ten halvings later than before; a
//!    crossing lasting `d` is found once the interval is narrower than
//!    `min(d, tol/1024)`, if the search gets there: a grazing stretch
//!    just before it can now end the search undecided or out of budget
//!    where the right end inside the crossing used to bracket it at once
//!    (only work and the kind of answer change, never its truth);
//! 4. once [`STUCK`] times narrower than the tolerance (halving keeps
//!    ending just before a contact that no halving point hits: the body
//!    within the margin of an obstacle it is about to enter), has the
//!    times `a + tol/128`, `a + tol/64`, …, `a + tol` checked, nearest
//!    first, each rounded down to a multiple of the largest power of two
//!    at most an eighth of its offset (an exact float: so the left ends of
//!    a grazing stretch probe the same times, each checked once) and
//!    clamped to `limit` (and an ulp back while it rounds past the
//!    tolerance): since `[0, a]` is certified, a contact at any of them
//!    is a valid bracket, the nearest the tightest (each offset at least
//!    `7/8` of its nominal one, less the half ulp of `a + offset`'s
//!    rounding, so the first probe past a contact at `c` is at most about
//!    `16/7 (c − a)` past `a`, or `tol/128`);
//! 5. once no wider than [`MIN_WIDTH`] (the body within rounding of an
//!    obstacle, grazing), is undecided
//!    ([`MotionError::Undecided`](crate::query::MotionError::Undecided))
//!    with `[0, a]` certified;
//! 6. else is halved.
//!
//! When the stack empties, `[0, limit]` is certified. Every answer is
//! therefore either certified (free up to `limit`, or free up to `a` and
//! colliding exactly at a time at most the tolerance after it) or says
//! how far it is certified: never a guess. A thin wall is not stepped
//! over: an interval sweeping through it is never certified, and halving
//! goes on until a checked time lies inside it.
//!
//! # Reuse across halving
//! Certifying `[a, b]` is a statement about the exact motion at every
//! time of `[a, b]`, so whatever part of it holds also holds over every
//! interval cut from `[a, b]`. A sweep may therefore answer an interval
//! it did not certify with what it left uncertified ([`Within`]: the
//! pairs of parts, say, that no test separated over `[a, b]`), and the
//! search hands that to both halves: an interval cut from `[a, b]` is
//! certified once those parts alone are, every other part having been
//! certified over `[a, b]` already. A sweep's record is a stack of its own
//! (`query::scene::sweep`): the search examines intervals depth first,
//! so when an interval is examined, every interval examined after the one
//! it was cut from, and not its ancestor, is finished, and the record
//! above its range can be dropped. The search itself only carries the
//! token; a sweep that records nothing answers [`Within::EVERYTHING`]
//! (the default).
//!
//! Each right end is checked at most once and each left end probed at
//! most once, and a time among the last sixteen checked free (right ends
//! and probes) is not checked again (the
//! exact answers at the same time do not change: only work is saved). The
//! budget counts examined intervals, so the same check gives the same
//! answer on any machine and under any load.
//!
//! # Independent review (2026-11-29)
//! The left-to-right invariant, that no time is skipped (children share
//! the exact float midpoint), termination, and the sagitta and
//! parallelogram margin were verified. Found and mended: when `a` is below
//! the tolerance, the float `t − a` could round onto it, so a bracket
//! could exceed the tolerance by under half an ulp (2 in 200,000 random
//! sweeps); the comparison is now exact ([`exceeds`]). Stated more
//! precisely after it: the margin certifies the exact motion (a float
//! pose of an inner time may lie up to the rounding bound from it), and
//! `t_safe = 0` rests on the caller's exact check of the start pose.
//!
//! # Independent review (2026-11-30)
//! Of the right ends checked once stuck after a record, the probes on a
//! grid and the times remembered free. Verified: every answer still comes
//! from an exact check at a time `t` with `t − a` at most the tolerance,
//! tested exactly ([`exceeds`], exact for `t ≤ a` too), with `[0, a]`
//! certified; no probe falls at or before `a` (an offset of at least
//! about `2⁻⁴⁵`, hundreds of ulps of any `a < 1`); a NaN never passes;
//! only times answered free are remembered, and the remembered times are
//! local to one search. Found and mended: the grid was `step/8`, not a
//! power of two, so its multiples rounded and a probe's offset could fall
//! an ulp below the stated `7/8` (and the first past `tol/128` by 1.5
//! ulps); the doc promised a short crossing would be found "as before",
//! which holds only below `tol/1024` (stated now in step 3).

use crate::kernel::bounds::U;
use crate::query::rounding::{pose_rounding_bound, ANGLE_ROUNDING};

/// The default work budget of a motion check
/// ([`crate::query::Checker::budget`]): the most intervals the search
/// examines (over all piece pairs of a [`crate::query::MotionChecker`])
/// before it gives up with
/// [`MotionError::BudgetExhausted`](crate::query::MotionError::BudgetExhausted).
/// Each costs at
/// most a few near-extreme searches and one exact query, so the default
/// caps a check at roughly 25–100 ms on this project's 2-core machines;
/// the motion tests and benchmarks need at most a few hundred
/// (docs/BENCHMARKS.md).
pub const DEFAULT_BUDGET: u64 = 4096;

/// The narrowest interval (in `t`) the search halves to before declaring
/// a grazing motion undecided
/// ([`MotionError::Undecided`](crate::query::MotionError::Undecided)).
pub const MIN_WIDTH: f64 = 1.0 / (1u64 << 48) as f64;

/// The smallest tolerance a check accepts: the search halves intervals no
/// further than [`MIN_WIDTH`], and brackets a contact it keeps ending just
/// before only once an interval is `1/1024` of the tolerance wide, so a
/// tolerance below `1024 · MIN_WIDTH = 2⁻³⁸ ≈ 3.6e-12` could never be met.
pub const MIN_TOLERANCE: f64 = STUCK * MIN_WIDTH;

/// How many times narrower than the tolerance an interval is when the
/// search probes ahead of it (module docs, step 4).
const STUCK: f64 = 1024.0;

/// How many times the search probes ahead: `a + tol/2^k` for `k` from
/// `PROBES − 1` down to `0`.
const PROBES: u32 = 8;

/// What a checker plugs into the search (module docs).
pub(crate) trait Sweep {
    /// Why an answer could not be given (an exact query failed).
    type Error;

    /// Whether no contact happens at any `t` in `[a, b]` of the exact
    /// motion, certified; `false` means "not proved". (The float pose of
    /// an inner time may lie up to the rounding bound `e` from the exact
    /// one: the margin covers the exact motion, not every float pose.)
    fn certified_free(&mut self, a: f64, b: f64) -> Result<bool, Self::Error>;

    /// Whether the body at the float pose of time `t` touches or overlaps
    /// an obstacle (exact).
    fn collides_at_time(&mut self, t: f64) -> Result<bool, Self::Error>;

    /// [`Sweep::certified_free`] for an interval cut from one whose
    /// examination left `within` uncertified (module docs, "Reuse across
    /// halving"; [`Within::EVERYTHING`] for a first piece): `None` when
    /// `[a, b]` is certified free, else what its own examination left
    /// uncertified, for the intervals cut from it. The default examines
    /// everything every time.
    fn certified_free_within(
        &mut self,
        a: f64,
        b: f64,
        within: Within,
    ) -> Result<Option<Within>, Self::Error> {
        let _ = within;
        Ok((!self.certified_free(a, b)?).then_some(Within::EVERYTHING))
    }
}

/// What the examination of an interval left uncertified, handed to the
/// intervals cut from it (module docs, "Reuse across halving"): a range
/// `start..end` of the sweep's own record of uncertified parts, or the
/// token for all of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Within {
    /// The record's first entry.
    pub(crate) start: u32,
    /// One past the record's last entry.
    pub(crate) end: u32,
}

impl Within {
    /// Everything: a first piece, or an interval whose examination
    /// recorded nothing (or found more than the sweep may record).
    pub(crate) const EVERYTHING: Within = Within {
        start: u32::MAX,
        end: u32::MAX,
    };

    /// Whether this names a range of the record (not the token).
    pub(crate) fn is_range(self) -> bool {
        self.start != u32::MAX
    }
}

/// An interval waiting to be examined: `(a, b)` and what the interval it
/// was cut from left uncertified.
pub(crate) type Pending = (f64, f64, Within);

/// Why a search stopped without an answer.
#[derive(Debug, PartialEq)]
pub(crate) enum Stop<E> {
    /// The budget ran out; `[0, t_safe]` is certified.
    Budget {
        /// The last time certified free.
        t_safe: f64,
    },
    /// An interval no wider than [`MIN_WIDTH`] from `t_safe` to `t` is
    /// neither certified nor bracketed (a grazing motion); `[0, t_safe]`
    /// is certified.
    Undecided {
        /// The last time certified free.
        t_safe: f64,
        /// The end of the undecided interval.
        t: f64,
    },
    /// The sweep failed.
    Failed(E),
}

impl<E> From<E> for Stop<E> {
    fn from(e: E) -> Stop<E> {
        Stop::Failed(e)
    }
}

/// The first contact bracket `(t_safe, t_contact)` of `sweep` in
/// `[0, limit]`, or `None` when all of it is certified free (module docs,
/// "The search"), starting from `pieces` equal intervals (at least one).
/// Each examined interval takes one step of `steps_left`; `stack` is a
/// buffer.
///
/// # Errors
/// [`Stop::Budget`] with none left, [`Stop::Undecided`] for a grazing
/// motion, and the sweep's errors.
pub(crate) fn first_contact<S: Sweep>(
    sweep: &mut S,
    limit: f64,
    pieces: usize,
    tolerance: f64,
    steps_left: &mut u64,
    stack: &mut Vec<Pending>,
) -> Result<Option<(f64, f64)>, Stop<S::Error>> {
    stack.clear();
    // The first intervals: `[0, limit]` cut into `pieces` (module docs);
    // neighbours share the same float end, computed by one expression.
    let pieces = pieces.max(1);
    let cut = |k: usize| {
        if k == pieces {
            limit
        } else {
            limit * (k as f64 / pieces as f64)
        }
    };
    for k in (0..pieces).rev() {
        stack.push((cut(k), cut(k + 1), Within::EVERYTHING));
    }
    let mut free = FreeTimes::new();
    let mut probed_from = f64::NAN;
    while let Some((a, b, within)) = stack.pop() {
        if *steps_left == 0 {
            return Err(Stop::Budget { t_safe: a });
        }
        *steps_left -= 1;
        let Some(left) = sweep.certified_free_within(a, b, within)? else {
            continue;
        };
        let width = b - a;
        // An interval that left a record of what it could not certify
        // has its right end checked once stuck, not at every level below
        // the tolerance (module docs, step 3).
        let checked_end = !left.is_range() || width <= tolerance / STUCK;
        if !exceeds(b, a, tolerance) && checked_end && !free.contains(b) {
            if sweep.collides_at_time(b)? {
                return Ok(Some((a, b)));
            }
            free.insert(b);
        }
        if width <= tolerance / STUCK && a != probed_from {
            probed_from = a;
            if let Some(c) = contact_ahead(sweep, a, limit, tolerance, &mut free)? {
                return Ok(Some((a, c)));
            }
        }
        if width <= MIN_WIDTH {
            return Err(Stop::Undecided { t_safe: a, t: b });
        }
        let m = 0.5 * (a + b);
        stack.push((m, b, left));
        stack.push((a, m, left));
    }
    Ok(None)
}

/// Whether `t − a > tolerance` exactly, for floats `0 ≤ a ≤ t` (a float
/// `t − a` may round onto the tolerance when `a` is smaller than it; the
/// independent review found brackets an ulp wider than asked). When
/// `a ≥ tolerance`: `t − a` is exact for `t ≤ 2a` (Sterbenz), and for
/// `t > 2a` both `t − a > tolerance` and its rounding (at least the next
/// float above `a`) hold. When `a < tolerance`: `t < tolerance / 2` gives
/// `t − a < tolerance`; else `t − tolerance` is exact for `t ≤ 2 ·
/// tolerance` (Sterbenz) and exceeds `tolerance > a` beyond.
fn exceeds(t: f64, a: f64, tolerance: f64) -> bool {
    if a >= tolerance {
        t - a > tolerance
    } else if t < 0.5 * tolerance {
        false
    } else {
        t - tolerance > a
    }
}

/// The first of `a + tolerance / 2^k` (`k` from `PROBES − 1` down to `0`,
/// each rounded down to its grid, at most `limit`, an ulp back while
/// rounded past the tolerance) at which the body collides, if any (module
/// docs, step 4).
///
/// A time in `free` (checked free before) is not checked again, and each
/// time checked free goes there: near a grazing end every probe clamps to
/// `limit`, and the left ends of a grazing stretch share their grid's
/// times, which the search would otherwise check once per left end.
fn contact_ahead<S: Sweep>(
    sweep: &mut S,
    a: f64,
    limit: f64,
    tolerance: f64,
    free: &mut FreeTimes,
) -> Result<Option<f64>, S::Error> {
    let mut last = a;
    for k in (0..PROBES).rev() {
        let step = tolerance / f64::from(1u32 << k);
        // `a + step` rounded down to a multiple of the largest power of
        // two at most `step / 8` (module docs, step 4): the multiples are
        // exact floats, and neighbouring left ends probe the same times.
        let grid = power_of_two_below(step / 8.0);
        let mut t = (((a + step) / grid).floor() * grid).min(limit);
        for _ in 0..4 {
            if !exceeds(t, a, tolerance) {
                break;
            }
            // Rounded past the tolerance: one ulp back (`t > a ≥ 0`).
            t = f64::from_bits(t.to_bits() - 1);
        }
        if t > last && !exceeds(t, a, tolerance) {
            if !free.contains(t) {
                if sweep.collides_at_time(t)? {
                    return Ok(Some(t));
                }
                free.insert(t);
            }
            last = t;
        }
    }
    Ok(None)
}

/// The largest power of two at most `x`, for a positive normal `x` (its
/// exponent's bits alone); `x` itself otherwise.
fn power_of_two_below(x: f64) -> f64 {
    if x.is_normal() && x > 0.0 {
        f64::from_bits(x.to_bits() & 0xfff0_0000_0000_0000)
    } else {
        x
    }
}

/// The last times the search checked free ([`FREE_TIMES`] of them): none
/// is checked twice while remembered.
struct FreeTimes {
    times: [f64; FREE_TIMES],
    next: usize,
}

/// How many times checked free the search remembers: two left ends'
/// probes.
const FREE_TIMES: usize = 2 * PROBES as usize;

impl FreeTimes {
    fn new() -> FreeTimes {
        FreeTimes {
            times: [f64::NAN; FREE_TIMES],
            next: 0,
        }
    }

    fn contains(&self, t: f64) -> bool {
        self.times.contains(&t)
    }

    fn insert(&mut self, t: f64) {
        self.times[self.next] = t;
        self.next = (self.next + 1) % FREE_TIMES;
    }
}

/// The indices `k` of `0 < k < segments` in bisection order (the middle
/// first, then the quarters, then the eighths, …), at most `most` of them.
pub(crate) fn bisection_order(segments: usize, most: usize) -> Vec<usize> {
    let mut out: Vec<usize> = Vec::new();
    let mut level = 2usize;
    while out.len() < most.min(segments.saturating_sub(1)) && level <= 2 * segments.max(1) {
        for j in (1..level).step_by(2) {
            let k = (j * segments + level / 2) / level;
            if k > 0 && k < segments && !out.contains(&k) && out.len() < most {
                out.push(k);
            }
        }
        level *= 2;
    }
    out
}

/// How far a body of a given reach strays over an interval of a motion
/// beyond what its end poses show (module docs, "The margin").
#[derive(Clone, Copy, Debug)]
pub(crate) struct SweepMargin {
    /// The motion's float angle plus its rounding bound.
    angle: f64,
    /// The body's reach about its origin (rounded up).
    reach: f64,
    /// `e`: how far a float-posed point is from the exact motion's.
    pose_error: f64,
}

impl SweepMargin {
    /// The margin of a body of reach `reach` (rounded up) over a motion
    /// of float angle `angle` ([`Motion::angle`]) and translation extent
    /// `extent` (`Motion::translation_extent`, `(M, D)`).
    ///
    /// [`Motion::angle`]: crate::query::Motion::angle
    pub(crate) fn new(angle: f64, extent: (f64, f64), reach: f64) -> SweepMargin {
        SweepMargin {
            angle: angle + ANGLE_ROUNDING,
            reach,
            pose_error: pose_rounding_bound(reach, extent),
        }
    }

    /// `δ`, the angle the body turns over an interval of width `width`,
    /// rounded up.
    pub(crate) fn turn(&self, width: f64) -> f64 {
        (self.angle * width) * (1.0 + 1e-12)
    }

    /// `e`, the distance between a float-posed point and the exact
    /// motion's (`query::rounding`).
    pub(crate) fn pose_error(&self) -> f64 {
        self.pose_error
    }

    /// The sagitta of the turn over an interval of width `width` for a
    /// radius of 1 (`2 sin²(δ/4)`), rounded up: a point `ρ` from the
    /// turn's axis strays at most `ρ` times this from its chord.
    pub(crate) fn sagitta_per_radius(&self, width: f64) -> f64 {
        let q = (self.turn(width) / 4.0)
            .min(std::f64::consts::FRAC_PI_4)
            .sin();
        2.0 * q * q * (1.0 + 1e-12)
    }

    /// `s + e`: the sagitta of the turn over an interval of width `width`
    /// and the poses' rounding, rounded up.
    pub(crate) fn inflation(&self, width: f64) -> f64 {
        let q = (self.turn(width) / 4.0)
            .min(std::f64::consts::FRAC_PI_4)
            .sin();
        let sagitta = 2.0 * self.reach * q * q * (1.0 + 1e-12);
        sagitta + self.pose_error
    }
}

/// The bow of a point's path over an interval (module docs, "The bow"):
/// a point at most `reach` from the body's origin, turned by at most
/// `turn`, is at most `λ(1 − λ)` times `turn² reach / 2` (rounded up) from
/// its chord at the fraction `λ` of the interval.
pub(crate) fn bow(turn: f64, reach: f64) -> f64 {
    0.5 * turn * turn * reach * (1.0 + 8.0 * U)
}

/// Whether `(1 − λ) a + λ b − λ(1 − λ) c > 0` for every `λ` in `[0, 1]`,
/// certified (module docs, "The bow"), for `a` and `b` each within one
/// rounding of its exact value (one subtraction each) and `c ≥ 0` rounded
/// up: both ends positive and `(√a + √b)² > c`, since for `0 < λ < 1` the
/// expression over `λ(1 − λ)` is `a/λ + b/(1 − λ) − c`, whose least value
/// over `λ` is `(√a + √b)² − c` (at `λ = √a/(√a + √b)`). The left side
/// takes four roundings, each within a relative `u`, and `a` and `b` one
/// more each: a relative `16u` covers them while every value is a normal
/// number, so `a` and `b` below the least normal one are refused (in the
/// subnormal range a rounding is not relative; found by the independent
/// review: harmless there, but only by an argument of its own), and a
/// product `ab` below `10⁻²⁹⁰` is left out (a smaller left side).
pub(crate) fn bowed_chord_stays_positive(a: f64, b: f64, c: f64) -> bool {
    if !(a >= f64::MIN_POSITIVE && b >= f64::MIN_POSITIVE) {
        return false;
    }
    let ab = a * b;
    let root = if ab > 1e-290 { 2.0 * ab.sqrt() } else { 0.0 };
    (a + b + root) * (1.0 - 16.0 * U) > c
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The least of `(1 − λ) a + λ b − λ(1 − λ) c` is `(√a + √b)² − c`
    /// over `λ(1 − λ)`: on integers below 2²⁰ and `λ = k/1024`, where
    /// every value is exact, a curve said positive is positive at every
    /// `λ`, and one whose least value clears `c` by a relative `10⁻⁹` is
    /// said positive.
    #[test]
    fn a_bowed_chord_is_said_positive_exactly_when_it_stays_positive() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(37);
        let (mut yes, mut no) = (0, 0);
        for k in 0..20_000 {
            let big = 1u64 << (k % 20 + 1);
            let mut draw = || rng.random_range(1..big) as f64;
            let (a, b) = (draw(), draw());
            let c = (a.sqrt() + b.sqrt()).powi(2) * rng.random_range(0.9..1.1);
            let c = c.round();
            let said = bowed_chord_stays_positive(a, b, c);
            if said {
                yes += 1;
                for j in 0..=1024 {
                    let l = j as f64 / 1024.0;
                    let q = (1.0 - l) * a + l * b - l * (1.0 - l) * c;
                    assert!(q > 0.0, "{a} {b} {c} at {l}: {q}");
                }
            } else {
                no += 1;
                assert!(
                    (a.sqrt() + b.sqrt()).powi(2) <= c * (1.0 + 1e-9),
                    "{a} {b} {c} refused"
                );
            }
        }
        assert!(yes > 5_000 && no > 5_000, "{yes} {no}");
        // Either end at or below zero is never positive.
        assert!(!bowed_chord_stays_positive(0.0, 1.0, 0.0));
        assert!(!bowed_chord_stays_positive(1.0, -1e-300, 0.0));
        assert!(!bowed_chord_stays_positive(f64::NAN, 1.0, 0.0));
    }

    /// Bisection order visits each inner index once, the middle first.
    #[test]
    fn bisection_order_visits_each_inner_sample_once_middle_first() {
        assert_eq!(bisection_order(8, 100), vec![4, 2, 6, 1, 3, 5, 7]);
        assert_eq!(bisection_order(8, 3), vec![4, 2, 6]);
        assert!(bisection_order(1, 10).is_empty() && bisection_order(0, 10).is_empty());
        for n in 2..60 {
            let mut all = bisection_order(n, usize::MAX);
            all.sort_unstable();
            assert_eq!(all, (1..n).collect::<Vec<_>>(), "{n}");
        }
    }

    /// A sweep over `[0, 1]` that collides on `[hit, 1]` and certifies an
    /// interval when it ends at least `gap` before `hit`; counts its
    /// exact checks.
    struct Wall {
        hit: f64,
        gap: f64,
        checks: Vec<f64>,
    }

    impl Sweep for Wall {
        type Error = ();

        fn certified_free(&mut self, _a: f64, b: f64) -> Result<bool, ()> {
            Ok(b + self.gap <= self.hit)
        }

        fn collides_at_time(&mut self, t: f64) -> Result<bool, ()> {
            self.checks.push(t);
            Ok(t >= self.hit)
        }
    }

    /// Whether `c − a ≤ tol` exactly (the difference as an exact float
    /// sum by Knuth's two-sum, independent of [`exceeds`]).
    fn exactly_within(c: f64, a: f64, tol: f64) -> bool {
        let d = c - a;
        let bb = d - c;
        let err = (c - (d - bb)) + (-a - bb);
        d < tol || (d == tol && err <= 0.0)
    }

    /// The independent review's counterexample: a bracket an ulp wider
    /// than the tolerance when its left end is below the tolerance (the
    /// float `t − a` rounded onto it); and the same on random walls.
    #[test]
    fn brackets_are_never_wider_than_the_tolerance_exactly() {
        struct Strict(f64, f64);
        impl Sweep for Strict {
            type Error = ();
            fn certified_free(&mut self, _a: f64, b: f64) -> Result<bool, ()> {
                Ok(b + self.1 < self.0)
            }
            fn collides_at_time(&mut self, t: f64) -> Result<bool, ()> {
                Ok(t >= self.0)
            }
        }
        let check = |limit: f64, tol: f64, hit: f64, gap: f64| {
            for pieces in [1, 3, 64] {
                let mut left = 1 << 20;
                let found = first_contact(
                    &mut Strict(hit, gap),
                    limit,
                    pieces,
                    tol,
                    &mut left,
                    &mut Vec::new(),
                );
                if let Ok(Some((a, c))) = found {
                    assert!(a < hit && c >= hit, "{a} {c}");
                    assert!(exactly_within(c, a, tol), "{a} {c} {tol}");
                }
            }
        };
        check(
            0.8067142476936945,
            0.005978819470047294,
            0.0036183057259554586,
            0.0029883845840746634,
        );
        let mut rng = crate::kernel::test_rng::Xorshift::new(0x1234_5678_9abc_def1u64);
        let mut unit = move || rng.unit();
        for _ in 0..20_000 {
            let (limit, tol) = (0.5 + 0.5 * unit(), 0.01 * unit() + 1e-9);
            let hit = unit() * 2.0 * tol;
            check(limit, tol, hit, unit() * tol);
        }
    }

    /// Cut into first pieces, the search still examines intervals left to
    /// right from `0`, each starting where the certified ones before it
    /// end, and the certified ones tile `[0, limit]` exactly: neighbouring
    /// pieces share their float end.
    #[test]
    fn first_pieces_tile_the_interval_left_to_right() {
        /// Certifies intervals no wider than `.0`; never collides; records
        /// every interval it is asked about.
        struct Narrow(f64, Vec<(f64, f64, bool)>);
        impl Sweep for Narrow {
            type Error = ();
            fn certified_free(&mut self, a: f64, b: f64) -> Result<bool, ()> {
                let ok = b - a <= self.0;
                self.1.push((a, b, ok));
                Ok(ok)
            }
            fn collides_at_time(&mut self, _t: f64) -> Result<bool, ()> {
                Ok(false)
            }
        }
        for (limit, width) in [(1.0, 0.3), (0.7, 0.01), (1.0, 1.0), (0.123_456_789, 0.05)] {
            for pieces in [1, 2, 3, 7, 10, 64] {
                let mut sweep = Narrow(width, Vec::new());
                let mut left = 1 << 20;
                let found =
                    first_contact(&mut sweep, limit, pieces, 1e-6, &mut left, &mut Vec::new());
                assert_eq!(found, Ok(None));
                let mut end = 0.0;
                for &(a, b, ok) in &sweep.1 {
                    assert_eq!(a, end, "{limit} {pieces}");
                    assert!(b > a);
                    if ok {
                        end = b;
                    }
                }
                assert_eq!(end, limit);
                assert!(sweep.1.iter().filter(|x| x.2).count() >= pieces.min(64));
            }
        }
    }

    /// A search's answer: a bracket, `None` (free), or why it stopped.
    type Found = Result<Option<(f64, f64)>, Stop<()>>;

    /// The search over `[0, 1]`, and the steps it took.
    fn run(wall: &mut Wall, tol: f64, budget: u64) -> (Found, u64) {
        let mut left = budget;
        let out = first_contact(wall, 1.0, 1, tol, &mut left, &mut Vec::new());
        (out, budget - left)
    }

    #[test]
    fn a_contact_is_bracketed_within_the_tolerance() {
        let mut wall = Wall {
            hit: 0.3,
            gap: 0.0,
            checks: Vec::new(),
        };
        let (out, _) = run(&mut wall, 1e-6, DEFAULT_BUDGET);
        let (a, c) = out.unwrap().unwrap();
        assert!(a < 0.3 && c >= 0.3 && c - a <= 1e-6, "{a} {c}");
    }

    #[test]
    fn stuck_before_a_contact_the_probes_bracket_it() {
        // Nothing within 1e-7 of the wall is certified: halving alone would
        // end at MIN_WIDTH; the probes reach past the margin.
        let mut wall = Wall {
            hit: 0.3,
            gap: 1e-7,
            checks: Vec::new(),
        };
        let (out, _) = run(&mut wall, 1e-6, DEFAULT_BUDGET);
        let (a, c) = out.unwrap().unwrap();
        assert!(
            a + 1e-7 <= 0.3 + 1e-12 && c >= 0.3 && c - a <= 1e-6,
            "{a} {c}"
        );
        // Nearest first: the first probe past the wall is taken (each
        // offset at least 7/8 of its nominal one, module docs).
        assert!(c - a <= 16.0 / 7.0 * (0.3 - a).max(1e-6 / 128.0), "{a} {c}");
        // No time is checked twice.
        let mut seen = wall.checks.clone();
        seen.sort_by(f64::total_cmp);
        seen.dedup();
        assert_eq!(seen.len(), wall.checks.len());
    }

    /// Towards a grazing end every probe clamps to the end, checked free
    /// already: no time is checked twice (the end was checked once per
    /// halving level), and the motion is certified.
    #[test]
    fn a_grazing_end_is_checked_once() {
        /// Certifies intervals no wider than their distance from `1`
        /// (or `1e-9`); never collides; records the times checked.
        struct Grazing(Vec<f64>);
        impl Sweep for Grazing {
            type Error = ();
            fn certified_free(&mut self, a: f64, b: f64) -> Result<bool, ()> {
                Ok(b - a <= (1.0 - b).max(1e-9))
            }
            fn collides_at_time(&mut self, t: f64) -> Result<bool, ()> {
                self.0.push(t);
                Ok(false)
            }
        }
        let mut sweep = Grazing(Vec::new());
        let mut left = DEFAULT_BUDGET;
        let out = first_contact(&mut sweep, 1.0, 1, 0.125, &mut left, &mut Vec::new());
        assert_eq!(out, Ok(None));
        let mut seen = sweep.0.clone();
        seen.sort_by(f64::total_cmp);
        seen.dedup();
        assert_eq!(seen.len(), sweep.0.len(), "{:?}", sweep.0);
        assert!(sweep.0.contains(&1.0));
    }

    #[test]
    fn a_margin_wider_than_the_tolerance_is_undecided() {
        let mut wall = Wall {
            hit: 0.3,
            gap: 1e-3,
            checks: Vec::new(),
        };
        let (out, _) = run(&mut wall, 1e-6, DEFAULT_BUDGET);
        let Err(Stop::Undecided { t_safe, t }) = out else {
            panic!("{out:?}");
        };
        assert!(t_safe + 1e-3 <= 0.3 && t - t_safe <= MIN_WIDTH);
    }

    #[test]
    fn the_budget_counts_intervals_and_keeps_what_is_certified() {
        let mut wall = Wall {
            hit: 0.3,
            gap: 0.0,
            checks: Vec::new(),
        };
        let (out, used) = run(&mut wall, 1e-6, 5);
        let Err(Stop::Budget { t_safe }) = out else {
            panic!("{out:?}");
        };
        assert_eq!(used, 5);
        assert!(t_safe < 0.3);
        // Free everywhere: one interval.
        let mut free = Wall {
            hit: 2.0,
            gap: 0.0,
            checks: Vec::new(),
        };
        let (out, used) = run(&mut free, 1e-6, 5);
        assert!(matches!(out, Ok(None)) && used == 1);
    }
}
