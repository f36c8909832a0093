//! Penetration depth from the candidates of `D = A ⊕ (−B)`
//! ([`super::candidates`]), and the dispatch to the distance
//! ([`super::distance`]) when the origin lies outside `D`.
//!
//! The minimum over all candidates' support values is the distance from the
//! origin to `D`'s boundary when the origin is inside (every facet normal is
//! a candidate and every candidate is an upper bound); the witness points
//! come from the winning facet's features ([`super::closest`] for an
//! edge–edge pair). Everything is computed in one power-of-two frame of the
//! posed vertices (see [`evaluate`]).
use super::candidates::{candidates, refine, winner, Candidate, FacetSet};
use super::closest::line_line;
use super::distance::separation;
use super::frame::Posed;
use super::{Contact, ConvexPair, FeaturePair, Proximity, QueryError, Separation};
use crate::Pose;
use glam::DVec3;

/// Depth or distance from the facets `facets` of `A ⊕ (−B)` (all of them
/// for the exhaustive reference).
///
/// Scale: every construction is made in the query's power-of-two frame
/// ([`super::frame`]) and lengths and points are scaled back by `2^-k`.
/// Scaling is exact, so the same pair at poses scaled by `2^j` gives
/// bit-identical frame coordinates and answers scaled by exactly `2^j`;
/// nothing overflows or underflows at any scale (squared lengths of
/// `1e200` or `1e-200` would). Posed coordinates that overflow `f64`, or
/// an answer that does, is [`QueryError::OutOfRange`].
pub(super) fn evaluate(
    pair: &ConvexPair,
    pose_a: Pose,
    pose_b: Pose,
    facets: &FacetSet,
    scratch: &mut Scratch,
) -> Result<Proximity, QueryError> {
    scratch.posed.reset(pair, pose_a, pose_b)?;
    let answer = evaluate_in_frame(
        pair,
        &scratch.posed,
        facets,
        &mut scratch.cands,
        (&mut scratch.poly, &mut scratch.bounds),
    );
    to_world(&scratch.posed, answer)
}

/// An answer in frame units scaled back to the world.
///
/// # Errors
/// [`QueryError::OutOfRange`] when it overflows.
pub(super) fn to_world(posed: &Posed, answer: Proximity) -> Result<Proximity, QueryError> {
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

/// The buffers of one evaluation, kept by a [`super::ContactTracker`] from
/// frame to frame so that a frame allocates nothing once they are large
/// enough.
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    pub(super) posed: Posed,
    cands: Vec<Candidate>,
    /// A face's posed corners (the separation).
    poly: Vec<DVec3>,
    /// The facing facets' distance bounds (the separation).
    bounds: Vec<f64>,
}

/// [`evaluate`] on frame coordinates.
fn evaluate_in_frame(
    pair: &ConvexPair,
    posed: &Posed,
    facets: &FacetSet,
    cands: &mut Vec<Candidate>,
    (poly, bounds): (&mut Vec<DVec3>, &mut Vec<f64>),
) -> Proximity {
    let tol = posed.tol;
    candidates(pair, posed, facets, tol, cands);
    refine(pair, posed, cands, tol);
    let answer = answer_from(pair, posed, tol, cands, (poly, bounds));
    #[cfg(test)]
    {
        // The pruning (ee-candidates left out, separation by branch and
        // bound) must not change the answer: every candidate, refined.
        let mut all = Vec::new();
        super::candidates::candidates_unpruned(pair, posed, facets, &mut all);
        all.iter_mut().for_each(|c| {
            c.h = super::candidates::climb(pair, posed, c);
            c.refined = true;
        });
        let reference = answer_from(pair, posed, tol, &all, (poly, bounds));
        assert_eq!(answer, reference, "the pruning changed the answer");
    }
    answer
}

/// The answer from refined candidates (every one within the tie tolerance
/// of the least value or of zero among them, in the overlay's order).
fn answer_from(
    pair: &ConvexPair,
    posed: &Posed,
    tol: f64,
    cands: &[Candidate],
    (poly, bounds): (&mut Vec<DVec3>, &mut Vec<f64>),
) -> Proximity {
    let (w, hmin) = winner(cands, tol);
    if hmin < 0.0 {
        return Proximity::Separated(separation(pair, posed, cands, tol, cands[w], poly, bounds));
    }
    let c = cands[w];
    let depth = hmin;
    let (point_on_a, point_on_b) = match c.features {
        FeaturePair::FaceVertex { b_vertex, .. } => {
            let b = posed.b(b_vertex);
            (b + depth * c.n, b)
        }
        FeaturePair::VertexFace { a_vertex, .. } => {
            let a = posed.a(a_vertex);
            (a, a - depth * c.n)
        }
        FeaturePair::EdgeEdge { a_edge, b_edge } => {
            let [u1, u2] = pair.a.edge(a_edge as usize).vertices;
            let [w1, w2] = pair.b.edge(b_edge as usize).vertices;
            line_line(posed.a(u1), posed.a(u2), posed.b(w1), posed.b(w2))
        }
    };
    Proximity::Penetrating(Contact {
        depth,
        normal: c.n,
        point_on_a,
        point_on_b,
        features: c.features,
    })
}
