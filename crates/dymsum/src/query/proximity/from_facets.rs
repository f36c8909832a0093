//! The answer from any set of the overlay's facets ([`evaluate_in_frame`]):
//! the penetration depth as the least support value over the candidates of
//! `D = A ⊕ (−B)`, or the distance when the origin lies outside `D`, by
//! rules that depend only on the set (ties by the documented order).
use crate::query::answer::Contact;
use crate::query::answer::FeaturePair;
use crate::query::answer::Proximity;
use crate::query::frame::Posed;
use crate::query::pair::ConvexPair;
use crate::query::proximity::certificate::candidates::{
    candidates, refine, winner, Candidate, FacetSet,
};
use crate::query::proximity::closest::line_line;
use crate::query::proximity::distance::separation;
use glam::DVec3;

/// [`super::evaluate::evaluate`] on frame coordinates, given the exact yes/no answer; with
/// the least refined candidate value (penetration) or NaN when a separation
/// measured no facet (else `0`).
pub(in crate::query) fn evaluate_in_frame(
    pair: &ConvexPair,
    posed: &Posed,
    facets: &FacetSet,
    intersecting: bool,
    cands: &mut Vec<Candidate>,
    (poly, bounds): (&mut Vec<DVec3>, &mut Vec<f64>),
) -> (Proximity, f64) {
    let tol = posed.tol;
    candidates(pair, posed, facets, tol, cands);
    refine(pair, posed, cands, tol);
    let answer = answer_from(pair, posed, tol, intersecting, cands, (poly, bounds));
    #[cfg(test)]
    {
        // The pruning (ee-candidates left out, separation by branch and
        // bound) must not change the answer: every candidate, refined.
        let mut all = Vec::new();
        crate::query::proximity::certificate::candidates::candidates_unpruned(
            pair, posed, facets, &mut all,
        );
        all.iter_mut().for_each(|c| {
            c.h = crate::query::proximity::certificate::candidates::climb(pair, posed, c);
            c.refined = true;
        });
        let reference = answer_from(pair, posed, tol, intersecting, &all, (poly, bounds));
        assert_eq!(answer.0, reference.0, "the pruning changed the answer");
    }
    answer
}

/// The answer from refined candidates (every one within the tie tolerance
/// of the least value or of zero among them, in the overlay's order).
pub(in crate::query) fn answer_from(
    pair: &ConvexPair,
    posed: &Posed,
    tol: f64,
    intersecting: bool,
    cands: &[Candidate],
    (poly, bounds): (&mut Vec<DVec3>, &mut Vec<f64>),
) -> (Proximity, f64) {
    let (w, hmin) = winner(cands, tol);
    if !intersecting {
        let (s, measured) = separation(pair, posed, cands, tol, cands[w], poly, bounds);
        return (
            Proximity::Separated(s),
            if measured { 0.0 } else { f64::NAN },
        );
    }
    let c = cands[w];
    // Overlapping or touching (decided exactly): a least value below zero
    // is rounding, and the depth is zero.
    let depth = hmin.max(0.0);
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
    (
        Proximity::Penetrating(Contact {
            depth,
            normal: c.n,
            point_on_a,
            point_on_b,
            features: c.features,
        }),
        hmin,
    )
}
