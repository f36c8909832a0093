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
use super::candidates::{candidates, refine, tie_tolerance, winner, Candidate, Posed};
use super::closest::line_line;
use super::distance::separation;
use super::{Contact, ConvexPair, FeaturePair, Proximity, QueryError, Separation};
use crate::kernel::exact;
use crate::sum::Overlay;
use crate::Pose;
use glam::DVec3;

/// Depth or distance from an overlay of `A ⊕ (−B)`.
///
/// Scale: the posed vertices of both bodies are first scaled by one power
/// of two `2^k` (their common frame: the largest magnitude in `[1, 2)`),
/// every construction is made there, and lengths and points are scaled
/// back by `2^-k`. Scaling is exact, so the same pair at poses scaled by
/// `2^j` gives bit-identical frame coordinates and answers scaled by
/// exactly `2^j`; nothing overflows or underflows at any scale (squared
/// lengths of `1e200` or `1e-200` would). Posed coordinates that overflow
/// `f64`, or an answer that does, is [`QueryError::OutOfRange`].
pub(super) fn evaluate(
    pair: &ConvexPair,
    pose_a: Pose,
    pose_b: Pose,
    overlay: &Overlay,
    scratch: &mut Scratch,
) -> Result<Proximity, QueryError> {
    let posed = &mut scratch.posed;
    posed.a.clear();
    posed
        .a
        .extend(pair.a.vertices().iter().map(|&v| pose_a.apply(v)));
    posed.b.clear();
    posed
        .b
        .extend(pair.b.vertices().iter().map(|&v| pose_b.apply(v)));
    if !posed.a.iter().chain(&posed.b).all(|v| v.is_finite()) {
        return Err(QueryError::OutOfRange(
            "the posed coordinates overflow f64 (|x| > 1.8e308)".into(),
        ));
    }
    let k = exact::frame_exponent(posed.a.iter().chain(&posed.b).flat_map(|v| v.to_array()));
    let to_frame = |v: &mut DVec3| *v = exact::mul_pow2_vec(*v, k);
    posed.a.iter_mut().for_each(to_frame);
    posed.b.iter_mut().for_each(to_frame);
    posed.na.clear();
    posed
        .na
        .extend((0..pair.a.face_count()).map(|f| pose_a.rotation.apply(pair.a.unit_normal(f))));
    posed.nb.clear();
    posed
        .nb
        .extend((0..pair.b.face_count()).map(|g| pose_b.rotation.apply(pair.b.unit_normal(g))));
    posed.pose_a = pose_a;
    posed.pose_b = pose_b;
    posed.k = k;
    let back = |x: f64| exact::mul_pow2(x, -k);
    let back_v = |v: DVec3| exact::mul_pow2_vec(v, -k);
    let answer = evaluate_in_frame(
        pair,
        &scratch.posed,
        overlay,
        &mut scratch.cands,
        (&mut scratch.poly, &mut scratch.bounds),
    );
    let out = match answer {
        Proximity::Penetrating(c) => Proximity::Penetrating(Contact {
            depth: back(c.depth),
            point_on_a: back_v(c.point_on_a),
            point_on_b: back_v(c.point_on_b),
            ..c
        }),
        Proximity::Separated(s) => Proximity::Separated(Separation {
            distance: back(s.distance),
            point_on_a: back_v(s.point_on_a),
            point_on_b: back_v(s.point_on_b),
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
    posed: Posed,
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
    overlay: &Overlay,
    cands: &mut Vec<Candidate>,
    (poly, bounds): (&mut Vec<DVec3>, &mut Vec<f64>),
) -> Proximity {
    let tol = tie_tolerance(posed);
    candidates(pair, posed, overlay, tol, cands);
    refine(pair, posed, cands, tol);
    let answer = answer_from(pair, posed, tol, cands, (poly, bounds));
    #[cfg(test)]
    {
        // The pruning (ee-candidates left out, separation by branch and
        // bound) must not change the answer: every candidate, refined.
        let mut all = Vec::new();
        super::candidates::candidates_unpruned(pair, posed, overlay, &mut all);
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
            let b = posed.b[b_vertex as usize];
            (b + depth * c.n, b)
        }
        FeaturePair::VertexFace { a_vertex, .. } => {
            let a = posed.a[a_vertex as usize];
            (a, a - depth * c.n)
        }
        FeaturePair::EdgeEdge { a_edge, b_edge } => {
            let [u1, u2] = pair.a.edge(a_edge as usize).vertices;
            let [w1, w2] = pair.b.edge(b_edge as usize).vertices;
            line_line(
                posed.a[u1 as usize],
                posed.a[u2 as usize],
                posed.b[w1 as usize],
                posed.b[w2 as usize],
            )
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
