//! The steps of one query in order ([`evaluate`]): GJK's exact yes/no, then
//! the certified facets near the answer (penetration: [`super::depth`];
//! separation: the slab of [`super::certificate`]), else the exhaustive
//! facet set; and the answer from any facet set ([`evaluate_in_frame`]):
//! the penetration depth as the least support value over the candidates of
//! `D = A ⊕ (−B)` ([`super::certificate::candidates`]), or the distance
//! ([`super::distance`]) when the origin lies outside `D`.
//!
//! The minimum over all candidates' support values is the distance from the
//! origin to `D`'s boundary when the origin is inside (every facet normal is
//! a candidate and every candidate is an upper bound); the witness points
//! come from the winning facet's features ([`super::closest`] for an
//! edge–edge pair). Everything is computed in one power-of-two frame of the
//! posed vertices (see [`evaluate`]).
use crate::kernel::rotation::Pose;
use crate::query::answer::Contact;
use crate::query::answer::Proximity;
use crate::query::answer::Separation;
use crate::query::error::QueryError;
use crate::query::frame::Posed;
use crate::query::pair::ConvexPair;
use crate::query::prep::Reflected;
use crate::query::proximity::certificate::candidates::FacetSet;
use crate::query::proximity::certificate::{
    separation_facets, single_facet, slab, slab_width, two_facets,
};
use crate::query::proximity::depth::penetration;
use crate::query::proximity::from_facets::evaluate_in_frame;
use crate::query::proximity::gjk::{
    certify, encloses_origin, gjk, separated_on_sets, separating_feature_axis,
};
use crate::query::proximity::scratch::Scratch;
use crate::sum::{minkowski_sum_posed, Method};

/// Where the facets of `A ⊕ (−B)` that a query evaluates come from.
#[derive(Clone, Copy, Debug)]
pub(in crate::query) enum Facets<'a> {
    /// Those near the answer, found by the certificates of
    /// [`crate::query::proximity::certificate`]; all of them, from a static `walk` sum, when a
    /// certificate cannot be made.
    Certified,
    /// All of them, from a static `walk` sum (the exhaustive reference).
    Exhaustive,
    /// All of them, from an overlay the caller keeps (a tracker's dynamic
    /// sum).
    Overlay(&'a FacetSet),
}

/// Depth or distance of A and B at their poses.
///
/// The yes/no answer is decided exactly on the rounded posed bodies by GJK
/// and its certificates ([`crate::query::proximity::gjk`], the exhaustive exact method when
/// they cannot decide); the depth or distance, direction, witness points
/// and features come from the candidates of the facets `facets`.
///
/// Scale: every construction is made in the query's power-of-two frame
/// ([`crate::query::frame`]) and lengths and points are scaled back by `2^-k`.
/// Scaling is exact, so the same pair at poses scaled by `2^j` gives
/// bit-identical frame coordinates and answers scaled by exactly `2^j`;
/// nothing overflows or underflows at any scale (squared lengths of
/// `1e200` or `1e-200` would). Posed coordinates that overflow `f64`, or
/// an answer that does, is [`QueryError::OutOfRange`].
///
/// # Errors
/// [`QueryError::OutOfRange`] as above; [`QueryError::Sum`] when the
/// exhaustive sum fails (an internal error).
pub(in crate::query) fn evaluate(
    pair: &ConvexPair,
    pose_a: Pose,
    pose_b: Pose,
    facets: Facets<'_>,
    scratch: &mut Scratch,
) -> Result<Proximity, QueryError> {
    scratch.posed.reset(pair, pose_a, pose_b)?;
    let (intersecting, facets) = match facets {
        Facets::Overlay(f) => (decide(pair, scratch, false), f),
        Facets::Certified => {
            let known = match certified(pair, scratch) {
                Answer(answer) => {
                    #[cfg(any(test, feature = "check-reference"))]
                    {
                        let mut fresh = Scratch::default();
                        let reference =
                            evaluate(pair, pose_a, pose_b, Facets::Exhaustive, &mut fresh)?;
                        let ours = to_world(&scratch.posed, answer)?;
                        assert_eq!(
                        ours, reference,
                        "the certified answer differs from the exhaustive one at {pose_a:?}, {pose_b:?}"
                    );
                    }
                    return to_world(&scratch.posed, answer);
                }
                Uncertified { overlapping } => overlapping,
            };
            pair.stats.count_exhaustive_answer();
            let intersecting = known.unwrap_or_else(|| decide_exhaustively(pair, scratch));
            exhaustive_facets(pair, pose_a, pose_b, &mut scratch.all)?;
            (intersecting, &scratch.all)
        }
        Facets::Exhaustive => {
            let intersecting = decide(pair, scratch, false);
            exhaustive_facets(pair, pose_a, pose_b, &mut scratch.all)?;
            (intersecting, &scratch.all)
        }
    };
    let (answer, _) = evaluate_in_frame(
        pair,
        &scratch.posed,
        facets,
        intersecting,
        &mut scratch.cands,
        (&mut scratch.poly, &mut scratch.bounds),
    );
    to_world(&scratch.posed, answer)
}

/// Every facet of the overlay at these poses, from a static `walk` sum.
fn exhaustive_facets(
    pair: &ConvexPair,
    pose_a: Pose,
    pose_b: Pose,
    all: &mut FacetSet,
) -> Result<(), QueryError> {
    let sum = minkowski_sum_posed(
        &pair.a,
        pose_a,
        &pair.neg_b().polytope,
        Reflected::pose(pose_b),
        Method::Walk,
    )?;
    all.fill_from(sum.overlay());
    Ok(())
}

/// What the certified path found: the answer, or that a certificate could
/// not be made (and, when GJK's exact certificate decided it, whether the
/// bodies overlap), so the exhaustive method must answer.
pub(in crate::query) enum Certified {
    /// The certified answer (frame units).
    Answer(Proximity),
    /// No certificate for the answer; the yes/no answer when known.
    Uncertified {
        /// `Some(true)` overlapping, `Some(false)` apart, `None` unknown.
        overlapping: Option<bool>,
    },
}

use Certified::{Answer, Uncertified};

/// The certified answer (frame units): GJK's exact yes/no, then the facets
/// near the answer by the certificates of
/// [`crate::query::proximity::certificate`].
fn certified(pair: &ConvexPair, scratch: &mut Scratch) -> Certified {
    let carried = std::mem::take(&mut scratch.epa_carried);
    let warm = scratch.warm.clamp(pair);
    let g = gjk(
        pair,
        &scratch.posed,
        warm,
        scratch.dir,
        &scratch.simplex,
        false,
    );
    scratch.remember(&g);
    let posed = &scratch.posed;
    if encloses_origin(posed, &g) {
        return match penetration(pair, scratch, &g, carried) {
            Some(answer) => Answer(answer),
            None => Uncertified {
                overlapping: Some(true),
            },
        };
    }
    let len = g.v.length();
    if !(len > 0.0 && len.is_finite()) {
        return Uncertified { overlapping: None };
    }
    let mut n = g.v / len;
    // One search per body serves the certificate and the slab: its width
    // assumes the true floor within 2^-20 of GJK's distance (checked
    // below, where the answer's distance is known).
    let width = slab_width(posed, len, len * (1.0 - 2f64.powi(-20)));
    let mut s = slab(pair, posed, n, width, g.warm, &mut scratch.cert);
    let mut along_v = true;
    if !(s.floor > 0.0 || separated_on_sets(posed, n, &scratch.cert)) {
        // GJK's direction is too coarse (the bodies nearly touch): a face
        // normal or edge cross product of the simplex's features is exact
        // to rounding, and any separating unit axis bounds the distance
        // from below, so the slab along it serves the same argument.
        let Some(axis) = separating_feature_axis(pair, posed, &g, &mut scratch.cert) else {
            return Uncertified { overlapping: None };
        };
        n = axis;
        s = slab(pair, posed, n, width, g.warm, &mut scratch.cert);
        if !(s.floor > 0.0 || separated_on_sets(posed, n, &scratch.cert)) {
            return Uncertified {
                overlapping: Some(false),
            };
        }
        along_v = false;
    }
    let local = &mut scratch.local;
    // The facets' measured distances come out within a few ulps of GJK's
    // float |v|, above it as often as below: a bound that assumes at most
    // `len` would fail on half of them. Any `best` serves the arguments
    // (the lens and the lateral reach widen with it), so a margin of
    // 2^-30 of the distance keeps them from failing by an ulp.
    let mut best = len * (1.0 + 2f64.powi(-30));
    if along_v
        && s.floor > 0.0
        && (single_facet(pair, posed, &g, n, best, s.floor, &mut local.facets)
            || two_facets(pair, posed, &g, n, best, s.floor, &mut local.facets))
    {
        let (answer, measured) = evaluate_in_frame(
            pair,
            posed,
            &local.facets,
            false,
            &mut scratch.cands,
            (&mut scratch.poly, &mut scratch.bounds),
        );
        if let Proximity::Separated(sep) = answer {
            if !measured.is_nan() && sep.distance <= best {
                return Answer(answer);
            }
        }
    }
    for _ in 0..3 {
        separation_facets(pair, posed, &s, best, &mut scratch.cert, local);
        if local.facets.is_empty() {
            // Too narrow a slab (GJK ended farther from the floor than
            // assumed): widen it to what the floor found says.
            let width = slab_width(posed, best, s.floor);
            s = slab(pair, posed, n, width, g.warm, &mut scratch.cert);
            continue;
        }
        let (answer, measured) = evaluate_in_frame(
            pair,
            posed,
            &local.facets,
            false,
            &mut scratch.cands,
            (&mut scratch.poly, &mut scratch.bounds),
        );
        let Proximity::Separated(sep) = answer else {
            return Uncertified {
                overlapping: Some(false),
            };
        };
        if measured.is_nan() {
            return Uncertified {
                overlapping: Some(false),
            }; // no facet measured
        }
        // The slab and the lateral reach assumed `best`: they hold if the
        // answer measures at most that.
        let need = slab_width(posed, sep.distance, s.floor);
        if need <= s.covered && sep.distance <= best {
            return Answer(answer);
        }
        best = best.max(sep.distance) * (1.0 + 1e-9);
        let width = slab_width(posed, best, s.floor);
        s = slab(pair, posed, n, width, g.warm, &mut scratch.cert);
    }
    Uncertified {
        overlapping: Some(false),
    }
}

/// The exact yes/no answer at the scratch's poses: GJK from the last
/// query's support vertices, its certificate, else the exhaustive exact
/// method (counted).
pub(in crate::query) fn decide(pair: &ConvexPair, scratch: &mut Scratch, yes_no: bool) -> bool {
    let warm = scratch.warm.clamp(pair);
    let g = gjk(
        pair,
        &scratch.posed,
        warm,
        scratch.dir,
        &scratch.simplex,
        yes_no,
    );
    scratch.remember(&g);
    match certify(pair, &scratch.posed, &g, &mut scratch.cert) {
        Some(x) => x,
        None => decide_exhaustively(pair, scratch),
    }
}

/// The exhaustive exact yes/no answer (counted).
fn decide_exhaustively(pair: &ConvexPair, scratch: &Scratch) -> bool {
    pair.stats.count_exhaustive_decision();
    super::hulls_meet::posed_hulls_meet(pair, &scratch.posed)
}

/// An answer in frame units scaled back to the world.
///
/// # Errors
/// [`QueryError::OutOfRange`] when it overflows.
pub(in crate::query) fn to_world(
    posed: &Posed,
    answer: Proximity,
) -> Result<Proximity, QueryError> {
    let out = match answer {
        Proximity::Penetrating(c) => Proximity::Penetrating(Contact {
            depth: posed.back(c.depth),
            point_on_a: posed.back_vec(c.point_on_a),
            point_on_b: posed.back_vec(c.point_on_b),
            ..c
        }),
        Proximity::Separated(s) => Proximity::Separated(Separation {
            distance: posed.back(s.distance),
            point_on_a: posed.back_vec(s.point_on_a),
            point_on_b: posed.back_vec(s.point_on_b),
            ..s
        }),
    };
    let finite = match &out {
        Proximity::Penetrating(c) => {
            c.depth.is_finite() && c.point_on_a.is_finite() && c.point_on_b.is_finite()
        }
        Proximity::Separated(s) => {
            s.distance.is_finite() && s.point_on_a.is_finite() && s.point_on_b.is_finite()
        }
    };
    if !finite {
        return Err(QueryError::OutOfRange(
            "the answer overflows f64 (|x| > 1.8e308)".into(),
        ));
    }
    Ok(out)
}
