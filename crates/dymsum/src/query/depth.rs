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
use super::certify::{
    grow_polytope, penetration_facets, polytope_depth, separation_facets, slab_floor, slab_width,
    value_slack, LocalScratch,
};
use super::closest::line_line;
use super::distance::separation;
use super::frame::Posed;
use super::gjk::{certify, gjk, origin_in_difference_hull, CertScratch, Gjk};
use super::{Contact, ConvexPair, FeaturePair, Proximity, QueryError, Reflected, Separation};
use crate::sum::{minkowski_sum_posed, Method};
use crate::Pose;
use glam::DVec3;

/// Where the facets of `A ⊕ (−B)` that a query evaluates come from.
#[derive(Clone, Copy, Debug)]
pub(super) enum Facets<'a> {
    /// Those near the answer, found by the certificates of
    /// [`super::certify`]; all of them, from a static `walk` sum, when a
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
/// and its certificates ([`super::gjk`], the exhaustive exact method when
/// they cannot decide); the depth or distance, direction, witness points
/// and features come from the candidates of the facets `facets`.
///
/// Scale: every construction is made in the query's power-of-two frame
/// ([`super::frame`]) and lengths and points are scaled back by `2^-k`.
/// Scaling is exact, so the same pair at poses scaled by `2^j` gives
/// bit-identical frame coordinates and answers scaled by exactly `2^j`;
/// nothing overflows or underflows at any scale (squared lengths of
/// `1e200` or `1e-200` would). Posed coordinates that overflow `f64`, or
/// an answer that does, is [`QueryError::OutOfRange`].
///
/// # Errors
/// [`QueryError::OutOfRange`] as above; [`QueryError::Sum`] when the
/// exhaustive sum fails (an internal error).
pub(super) fn evaluate(
    pair: &ConvexPair,
    pose_a: Pose,
    pose_b: Pose,
    facets: Facets<'_>,
    scratch: &mut Scratch,
) -> Result<Proximity, QueryError> {
    scratch.posed.reset(pair, pose_a, pose_b)?;
    let intersecting = decide(pair, scratch, false);
    let facets = match facets {
        Facets::Overlay(f) => f,
        Facets::Certified => {
            if let Some(answer) = certified(pair, scratch, intersecting) {
                #[cfg(any(test, feature = "check-reference"))]
                {
                    let mut fresh = Scratch::default();
                    let reference = evaluate(pair, pose_a, pose_b, Facets::Exhaustive, &mut fresh)?;
                    let ours = to_world(&scratch.posed, answer)?;
                    assert_eq!(
                        ours, reference,
                        "the certified answer differs from the exhaustive one at {pose_a:?}, {pose_b:?}"
                    );
                }
                return to_world(&scratch.posed, answer);
            }
            pair.stats.count_exhaustive_answer();
            exhaustive_facets(pair, pose_a, pose_b, &mut scratch.all)?;
            &scratch.all
        }
        Facets::Exhaustive => {
            exhaustive_facets(pair, pose_a, pose_b, &mut scratch.all)?;
            &scratch.all
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

/// The answer (frame units) from the facets near it, when the certificates
/// of [`super::certify`] hold; `None` otherwise.
fn certified(pair: &ConvexPair, scratch: &mut Scratch, intersecting: bool) -> Option<Proximity> {
    let g = scratch.gjk?;
    let posed = &scratch.posed;
    let (tol, slack) = (posed.tol, value_slack(posed));
    let local = &mut scratch.local;
    let buffers = (&mut scratch.poly, &mut scratch.bounds);
    if intersecting {
        if !grow_polytope(pair, posed, &g, local) {
            return None;
        }
        let mut c = polytope_depth(local) + 4.0 * (tol + slack);
        for _ in 0..2 {
            if !penetration_facets(pair, posed, c, &mut scratch.cert, local) {
                return None;
            }
            let (answer, hmin) = evaluate_in_frame(
                pair,
                posed,
                &local.facets,
                true,
                &mut scratch.cands,
                (&mut *buffers.0, &mut *buffers.1),
            );
            let need = hmin + tol + slack;
            if need <= c {
                return Some(answer);
            }
            c = need * (1.0 + 1e-12);
        }
        return None;
    }
    let len = g.v.length();
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    let n = g.v / len;
    let floor = slab_floor(pair, posed, n, g.warm, &mut scratch.cert);
    let mut best = len;
    for _ in 0..2 {
        let tau = slab_width(posed, best, floor);
        separation_facets(pair, posed, n, tau, g.warm, &mut scratch.cert, local);
        let (answer, measured) = evaluate_in_frame(
            pair,
            posed,
            &local.facets,
            false,
            &mut scratch.cands,
            (&mut *buffers.0, &mut *buffers.1),
        );
        let Proximity::Separated(s) = answer else {
            return None;
        };
        if measured.is_nan() {
            return None; // no facet measured
        }
        if slab_width(posed, s.distance, floor) <= tau {
            return Some(answer);
        }
        best = s.distance;
    }
    None
}

/// The exact yes/no answer at the scratch's poses: GJK from the last
/// query's support vertices, its certificate, else the exhaustive exact
/// method (counted).
pub(super) fn decide(pair: &ConvexPair, scratch: &mut Scratch, yes_no: bool) -> bool {
    let posed = &scratch.posed;
    let warm = scratch.warm.clamp(pair);
    let g = gjk(pair, posed, warm, scratch.dir, yes_no);
    scratch.warm = Warm(g.warm.0, g.warm.1);
    if g.v.length_squared() > 0.0 {
        scratch.dir = g.v;
    }
    scratch.gjk = Some(g);
    match certify(pair, posed, &g, &mut scratch.cert) {
        Some(x) => x,
        None => {
            pair.stats.count_exhaustive_decision();
            origin_in_difference_hull(pair, posed)
        }
    }
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
    /// The last support vertices (GJK's warm start).
    warm: Warm,
    /// The last GJK direction.
    dir: DVec3,
    /// The last GJK run.
    pub(super) gjk: Option<Gjk>,
    pub(super) cert: CertScratch,
    /// Every facet (the exhaustive evaluation).
    all: FacetSet,
    /// The certificates' local searches.
    local: LocalScratch,
    cands: Vec<Candidate>,
    /// A face's posed corners (the separation).
    poly: Vec<DVec3>,
    /// The facing facets' distance bounds (the separation).
    bounds: Vec<f64>,
}

impl Scratch {
    /// Forgets the warm start (the buffers stay).
    pub(super) fn cold(&mut self) {
        self.warm = Warm::default();
        self.dir = DVec3::ZERO;
        self.gjk = None;
    }
}

/// Support vertices of A and B to start the next GJK from.
#[derive(Clone, Copy, Debug, Default)]
struct Warm(u32, u32);

impl Warm {
    /// The vertices, or vertex 0 where one is out of range (a scratch
    /// reused with another pair).
    fn clamp(self, pair: &ConvexPair) -> (u32, u32) {
        let ok = |v: u32, n: usize| if (v as usize) < n { v } else { 0 };
        (
            ok(self.0, pair.a.vertex_count()),
            ok(self.1, pair.b.vertex_count()),
        )
    }
}

/// [`evaluate`] on frame coordinates, given the exact yes/no answer; with
/// the least refined candidate value (penetration) or NaN when a separation
/// measured no facet (else `0`).
pub(super) fn evaluate_in_frame(
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
        super::candidates::candidates_unpruned(pair, posed, facets, &mut all);
        all.iter_mut().for_each(|c| {
            c.h = super::candidates::climb(pair, posed, c);
            c.refined = true;
        });
        let reference = answer_from(pair, posed, tol, intersecting, &all, (poly, bounds));
        assert_eq!(answer.0, reference.0, "the pruning changed the answer");
    }
    answer
}

/// The answer from refined candidates (every one within the tie tolerance
/// of the least value or of zero among them, in the overlay's order).
fn answer_from(
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
