//! The candidate directions of a proximity query: every facet label of the
//! overlay of `D = A ⊕ (−B)` gives a direction `n` (computed from the
//! original bodies' features, see the module docs of [`crate::query`] for
//! why) and its support value `h(n) = h_A(n) + h_B(−n)`, each support found
//! by a hill climb from the facet's feature, so `h(n)` is a true support
//! value of `D` up to rounding even where the float direction is inaccurate.
//!
//! Branch and bound: the value at the facet's own features, `h₀ ≤ h`, costs
//! two dot products. Only candidates with `h₀` within the tie tolerance of
//! the best refined value are refined by the hill climbs; every other
//! candidate has `h > best + tol`, so it can neither win nor tie. Those
//! that may still face the origin (`h₀ ≤ tol`) are kept unrefined for the
//! separation, which refines one only when its distance bound can win; the
//! rest are dropped, and the ee-candidates among them before their square
//! root. The answer is the same as refining all of them (the crate's unit
//! tests compare). The winner is chosen by a rule that does not depend
//! on the order of the candidates (so answers never differ between runs).
//!
//! Complexity: O(facets) for the lower bounds, plus a hill climb per refined
//! candidate.

use super::{ConvexPair, FeaturePair};
use crate::polytope::Polytope;
use crate::sum::Overlay;
use crate::Pose;
use glam::DVec3;

/// One candidate direction.
#[derive(Clone, Copy, Debug)]
pub(super) struct Candidate {
    pub features: FeaturePair,
    /// Unit direction, from A towards B.
    pub n: DVec3,
    /// `h_A(n) + h_B(−n)` once refined, else the lower bound `h₀`.
    pub h: f64,
    /// Whether `h` is the refined support value.
    pub refined: bool,
}

/// The posed vertices of both bodies (buffers reused from query to query).
#[derive(Clone, Debug, Default)]
pub(super) struct Posed {
    pub a: Vec<DVec3>,
    pub b: Vec<DVec3>,
    /// Rotated unit face normals of A and B.
    pub na: Vec<DVec3>,
    pub nb: Vec<DVec3>,
    pub pose_a: Pose,
    pub pose_b: Pose,
    /// The frame's exponent: frame coordinates are world ones times `2^k`.
    pub k: i32,
}

/// `max dir · v` over the posed vertices of `poly`, by a hill climb from the
/// best of `starts` (first one wins ties), moving to the first strictly
/// better neighbour until none is better.
pub(super) fn support(poly: &Polytope, posed: &[DVec3], dir: DVec3, starts: &[u32]) -> f64 {
    let mut v = starts[0];
    let mut best = dir.dot(posed[v as usize]);
    for &s in &starts[1..] {
        let d = dir.dot(posed[s as usize]);
        if d > best {
            best = d;
            v = s;
        }
    }
    loop {
        let mut moved = false;
        for r in poly.ring(v as usize) {
            let d = dir.dot(posed[r.neighbor as usize]);
            if d > best {
                best = d;
                v = r.neighbor;
                moved = true;
            }
        }
        if !moved {
            return best;
        }
    }
}

/// The refined value of a candidate: `h_A(n) + h_B(−n)`, each support
/// found by a hill climb from the candidate's own features (so the value
/// is at least the lower bound `h₀`, exactly: the climbs start at the
/// features `h₀` is taken at and only move up).
pub(super) fn climb(pair: &ConvexPair, posed: &Posed, c: &Candidate) -> f64 {
    let (a, b) = (&pair.a, &pair.b);
    let (ha, hb) = match c.features {
        FeaturePair::FaceVertex { a_face, b_vertex } => (
            support(a, &posed.a, c.n, a.face(a_face as usize)),
            support(b, &posed.b, -c.n, &[b_vertex]),
        ),
        FeaturePair::VertexFace { a_vertex, b_face } => (
            support(a, &posed.a, c.n, &[a_vertex]),
            support(b, &posed.b, -c.n, b.face(b_face as usize)),
        ),
        FeaturePair::EdgeEdge { a_edge, b_edge } => (
            support(a, &posed.a, c.n, &a.edge(a_edge as usize).vertices),
            support(b, &posed.b, -c.n, &b.edge(b_edge as usize).vertices),
        ),
    };
    ha + hb
}

/// Replaces the lower bounds `h₀` by true support values where they can
/// matter to the depth (within the tie tolerance of the best value) and
/// keeps those candidates, in order, together with the unrefined ones that
/// may face the origin (`h₀ ≤ tol`), which the separation refines only
/// when their distance bound can win ([`super::distance::separation`]).
pub(super) fn refine(pair: &ConvexPair, posed: &Posed, cands: &mut Vec<Candidate>, tol: f64) {
    let Some(first) = (0..cands.len()).min_by(|&i, &j| cands[i].h.total_cmp(&cands[j].h)) else {
        return;
    };
    if !cands[first].refined {
        cands[first].h = climb(pair, posed, &cands[first]);
        cands[first].refined = true;
    }
    let mut best = cands[first].h;
    for c in cands.iter_mut() {
        if !c.refined && c.h <= best + tol {
            c.h = climb(pair, posed, c);
            c.refined = true;
            best = best.min(c.h);
        }
    }
    // A candidate left unrefined with `h₀ ≤ tol` may face the origin; the
    // separation refines it if its distance bound can win
    // ([`super::distance::separation`]). The others cannot matter.
    cands.retain(|c| c.refined || c.h <= tol);
}

/// The candidates of all facets of the overlay (P = A, Q = −B), with the
/// lower bounds `h₀` as values, into `out` (cleared first), in the
/// overlay's order.
///
/// The ee-candidates come last and most cost a square root and a division
/// each, so the least fv- or vf-candidate is refined first, and an
/// ee-candidate whose value `h₀` is certainly above the refine bound
/// (by a full tolerance, so that rounding cannot matter) is left out: it
/// would be dropped by [`refine`] anyway.
pub(super) fn candidates(
    pair: &ConvexPair,
    posed: &Posed,
    overlay: &Overlay,
    tol: f64,
    out: &mut Vec<Candidate>,
) {
    push_face_candidates(pair, posed, overlay, out);
    let mut skip_above = f64::INFINITY;
    if let Some(first) = (0..out.len()).min_by(|&i, &j| out[i].h.total_cmp(&out[j].h)) {
        let c = &mut out[first];
        c.h = climb(pair, posed, c);
        c.refined = true;
        // Above `max(best + tol, tol)` a candidate can neither win, nor
        // tie, nor face the origin; one more `tol` of margin for rounding.
        skip_above = (c.h + tol).max(tol) + tol;
    }
    for &(e, e2) in &overlay.ee {
        push_ee_candidates(pair, posed, e, e2, skip_above, out);
    }
}

/// [`candidates`] without leaving any out, for the tests' reference.
#[cfg(test)]
pub(super) fn candidates_unpruned(
    pair: &ConvexPair,
    posed: &Posed,
    overlay: &Overlay,
    out: &mut Vec<Candidate>,
) {
    push_face_candidates(pair, posed, overlay, out);
    for &(e, e2) in &overlay.ee {
        push_ee_candidates(pair, posed, e, e2, f64::INFINITY, out);
    }
}

/// `out` cleared, then the fv- and vf-candidates of the overlay, in order.
fn push_face_candidates(
    pair: &ConvexPair,
    posed: &Posed,
    overlay: &Overlay,
    out: &mut Vec<Candidate>,
) {
    out.clear();
    for (f, &w) in overlay.fv.iter().enumerate() {
        out.push(fv_candidate(pair, posed, f, w));
    }
    for (g, &u) in overlay.vf.iter().enumerate() {
        out.push(vf_candidate(pair, posed, g, u));
    }
}

/// The lower bound `h₀` at a candidate's own features.
#[inline]
fn lower_bound(posed: &Posed, n: DVec3, a_vertex: u32, b_vertex: u32) -> f64 {
    n.dot(posed.a[a_vertex as usize]) - n.dot(posed.b[b_vertex as usize])
}

/// The candidate of the fv-facet of face `f` of A and vertex `w` of `−B`.
#[inline]
pub(super) fn fv_candidate(pair: &ConvexPair, posed: &Posed, f: usize, w: u32) -> Candidate {
    let w = pair.neg_b.vertex_map[w as usize];
    let n = posed.na[f];
    Candidate {
        features: FeaturePair::FaceVertex {
            a_face: f as u32,
            b_vertex: w,
        },
        n,
        h: lower_bound(posed, n, pair.a.face(f)[0], w),
        refined: false,
    }
}

/// The candidate of the vf-facet of vertex `u` of A and face `g` of `−B`.
#[inline]
pub(super) fn vf_candidate(pair: &ConvexPair, posed: &Posed, g: usize, u: u32) -> Candidate {
    let g = pair.neg_b.face_map[g] as usize;
    let n = -posed.nb[g];
    Candidate {
        features: FeaturePair::VertexFace {
            a_vertex: u,
            b_face: g as u32,
        },
        n,
        h: lower_bound(posed, n, u, pair.b.face(g)[0]),
        refined: false,
    }
}

/// The candidates of the ee-facet of edge `e` of A and edge `e2` of `−B`
/// pushed onto `out`: none for parallel edges, two (both signs) when the
/// orientation is uncertain, else one; none either when the orientation is
/// certain and the value is certainly above `skip_above` (tested without
/// normalising the direction).
pub(super) fn push_ee_candidates(
    pair: &ConvexPair,
    posed: &Posed,
    e: u32,
    e2: u32,
    skip_above: f64,
    out: &mut Vec<Candidate>,
) {
    let (a, b) = (&pair.a, &pair.b);
    let (na, nb) = (&posed.na, &posed.nb);
    let e2 = pair.neg_b.edge_map[e2 as usize];
    let (ea, eb) = (a.edge(e as usize), b.edge(e2 as usize));
    let ordered = |[x, y]: [u32; 2]| if x < y { [x, y] } else { [y, x] };
    let [u1, u2] = ordered(ea.vertices);
    let [w1, w2] = ordered(eb.vertices);
    let da = posed.a[u2 as usize] - posed.a[u1 as usize];
    let db = posed.b[w2 as usize] - posed.b[w1 as usize];
    let c = da.cross(db);
    // Outward: n lies on A's arc (between its faces' normals) and −n on
    // B's arc. Exactly antisymmetric under swapping A and B.
    let sa_n = na[ea.faces[0] as usize] + na[ea.faces[1] as usize];
    let sb_n = nb[eb.faces[0] as usize] + nb[eb.faces[1] as usize];
    let x = posed.a[u1 as usize] - posed.b[w1 as usize];
    if certainly_above(c, c.dot(sa_n - sb_n), x, skip_above) {
        return;
    }
    let len = c.length();
    if len == 0.0 || !len.is_finite() {
        return; // parallel edges: a degenerate facet of zero area
    }
    let n = c / len;
    let s = n.dot(sa_n - sb_n);
    let features = FeaturePair::EdgeEdge {
        a_edge: e,
        b_edge: e2,
    };
    let mut push = |n: DVec3| {
        out.push(Candidate {
            features,
            n,
            h: lower_bound(posed, n, u1, w1),
            refined: false,
        })
    };
    if s.abs() < AMBIGUOUS_ORIENTATION {
        // Nearly antipodal arcs: the sign is uncertain, take both (every
        // candidate is a true support value, so extra ones are harmless).
        push(n);
        push(-n);
    } else {
        push(if s > 0.0 { n } else { -n });
    }
}

/// Whether the ee-candidate of direction `c / |c|` (oriented by the sign
/// of `sc = c · (ΣA − ΣB)`), at the facet point `x`, certainly has
/// `h₀ > skip_above`, tested without the square root: only when the
/// orientation is clear (`|sc|` at least twice [`AMBIGUOUS_ORIENTATION`]
/// `|c|`) and no square overflows or underflows. The caller's
/// `skip_above` carries a full tie tolerance of margin for the rounding
/// between `c · x / |c|` and `h₀ = n · a − n · b`.
#[inline]
fn certainly_above(c: DVec3, sc: f64, x: DVec3, skip_above: f64) -> bool {
    let len2 = c.length_squared();
    let clear = 4.0 * AMBIGUOUS_ORIENTATION * AMBIGUOUS_ORIENTATION * len2;
    if !(len2 > 1e-200 && len2 < 1e200) || sc * sc <= clear {
        return false;
    }
    let hv = if sc > 0.0 { c.dot(x) } else { -c.dot(x) };
    if !(hv > 0.0 && hv < 1e100) {
        return false;
    }
    skip_above <= 0.0 || (skip_above > 1e-100 && hv * hv > skip_above * skip_above * len2)
}

/// Below this `|n · (ΣA − ΣB)|` an ee-candidate's orientation is taken
/// both ways (see [`push_ee_candidates`]).
pub(super) const AMBIGUOUS_ORIENTATION: f64 = 1e-9;

/// `n` or `−n`, whichever is lexicographically larger (a key invariant under
/// negation), and whether `n` itself is that one.
pub(super) fn sign_free_key(n: DVec3) -> ([f64; 3], bool) {
    let pos = if n.x != 0.0 {
        n.x > 0.0
    } else if n.y != 0.0 {
        n.y > 0.0
    } else {
        n.z >= 0.0
    };
    let k = if pos { n } else { -n };
    // `+ 0.0` turns −0 into +0 so that equal keys compare equal.
    ([k.x + 0.0, k.y + 0.0, k.z + 0.0], pos)
}

/// The tie tolerance: `16 ε` times the largest absolute posed coordinate.
pub(super) fn tie_tolerance(posed: &Posed) -> f64 {
    let scale = posed
        .a
        .iter()
        .chain(&posed.b)
        .map(|v| v.abs().max_element())
        .fold(0.0f64, f64::max);
    16.0 * f64::EPSILON * scale.max(f64::MIN_POSITIVE)
}

/// The winning candidate: minimum `h`; among those within `tol` of it the
/// one with the smallest sign-free key, then the "positive" one, then the
/// smaller `h`.
pub(super) fn winner(cands: &[Candidate], tol: f64) -> (usize, f64) {
    let hmin = cands
        .iter()
        .filter(|c| c.refined)
        .map(|c| c.h)
        .fold(f64::INFINITY, f64::min);
    let mut best: Option<(usize, ([f64; 3], bool))> = None;
    for (i, c) in cands.iter().enumerate() {
        if !c.refined || c.h > hmin + tol {
            continue;
        }
        let key = sign_free_key(c.n);
        let better = match &best {
            None => true,
            Some((j, bk)) => {
                let ord = key.0[0]
                    .total_cmp(&bk.0[0])
                    .then(key.0[1].total_cmp(&bk.0[1]))
                    .then(key.0[2].total_cmp(&bk.0[2]))
                    .then(bk.1.cmp(&key.1)) // positive first
                    .then(c.h.total_cmp(&cands[*j].h));
                ord.is_lt()
            }
        };
        if better {
            best = Some((i, key));
        }
    }
    (best.map(|b| b.0).unwrap_or(0), hmin)
}
