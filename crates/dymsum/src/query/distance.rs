//! Distance and closest points when the origin lies outside `D = A ⊕ (−B)`.
//!
//! The closest point of `D` to an exterior origin lies on a facet whose
//! support value is negative (the origin is on its outer side), so only
//! those facets are examined. A facet's distance is a feature–feature
//! distance of the bodies: a face of A to a vertex of B (closest point on a
//! convex polygon), a vertex of A to a face of B, or an edge to an edge
//! (closest points of two segments). Every examined pair gives real points
//! of A and B, so the minimum is exact up to rounding. O(facets).

use super::candidates::{Candidate, Posed};
use super::closest::{closest_on_polygon, segment_segment};
use super::{ConvexPair, FeaturePair, Separation};
use glam::DVec3;

/// The separation: minimum feature distance over the facets on whose outer
/// side the origin lies (support value below `tol`). `poly` is a reused
/// buffer for a face's posed corners.
pub(super) fn separation(
    pair: &ConvexPair,
    posed: &Posed,
    cands: &[Candidate],
    tol: f64,
    fallback: Candidate,
    poly: &mut Vec<DVec3>,
) -> Separation {
    let (a, b) = (&pair.a, &pair.b);
    let mut best: Option<(f64, DVec3, DVec3, FeaturePair)> = None;
    for c in cands.iter().filter(|c| c.h <= tol) {
        let (pa, pb) = match c.features {
            FeaturePair::FaceVertex { a_face, b_vertex } => {
                poly.clear();
                poly.extend(a.face(a_face as usize).iter().map(|&v| posed.a[v as usize]));
                let q = posed.b[b_vertex as usize];
                let normal = posed.pose_a.rotation.apply(a.normal(a_face as usize));
                (closest_on_polygon(poly, normal, q), q)
            }
            FeaturePair::VertexFace { a_vertex, b_face } => {
                poly.clear();
                poly.extend(b.face(b_face as usize).iter().map(|&v| posed.b[v as usize]));
                let q = posed.a[a_vertex as usize];
                let normal = posed.pose_b.rotation.apply(b.normal(b_face as usize));
                (q, closest_on_polygon(poly, normal, q))
            }
            FeaturePair::EdgeEdge { a_edge, b_edge } => {
                let [u1, u2] = a.edge(a_edge as usize).vertices;
                let [w1, w2] = b.edge(b_edge as usize).vertices;
                segment_segment(
                    posed.a[u1 as usize],
                    posed.a[u2 as usize],
                    posed.b[w1 as usize],
                    posed.b[w2 as usize],
                )
            }
        };
        let d = (pb - pa).length();
        if !best.as_ref().is_some_and(|bst| d >= bst.0) {
            best = Some((d, pa, pb, c.features));
        }
    }
    let (distance, point_on_a, point_on_b, features) =
        best.unwrap_or((-fallback.h, DVec3::ZERO, DVec3::ZERO, fallback.features));
    let dir = point_on_b - point_on_a;
    let direction = if dir.length() > 0.0 {
        dir.normalize()
    } else {
        fallback.n
    };
    Separation {
        distance,
        point_on_a,
        point_on_b,
        direction,
        features,
    }
}
