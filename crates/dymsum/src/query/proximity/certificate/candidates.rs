//! The candidate directions of a proximity query: every facet label of the
//! overlay of `D = A ⊕ (−B)` gives a direction `n` and its support value
//! `h(n) = h_A(n) + h_B(−n)`, each support found by a hill climb from the
//! facet's feature, so `h(n)` is a true support value of `D` up to
//! rounding.
//!
//! Directions: an fv- or vf-facet's is its face's rotated unit normal; an
//! ee-facet's is the crossing point of the two edges' Gaussian arcs, on the
//! side the exact (perturbed) predicate of the overlay chose, computed in
//! double-double from the exact edge vectors and exactly when that is not
//! enough ([`ee_direction`]). Every direction is therefore within a few
//! ulps of the facet's place on the overlay, however nearly parallel the
//! edges: the certificates of [`crate::query::proximity::certificate`] rely on it.
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

use crate::gauss::GaussView;
use crate::polytope::Polytope;
use crate::query::answer::FeaturePair;
use crate::query::frame::Posed;
use crate::query::pair::ConvexPair;
use crate::query::proximity::support::climb as hill_climb;
use crate::sum::Overlay;
use glam::DVec3;

/// One candidate direction.
#[derive(Clone, Copy, Debug)]
pub(in crate::query) struct Candidate {
    pub features: FeaturePair,
    /// Unit direction, from A towards B.
    pub n: DVec3,
    /// `h_A(n) + h_B(−n)` once refined, else the lower bound `h₀`.
    pub h: f64,
    /// Whether `h` is the refined support value.
    pub refined: bool,
}

/// `max dir · v` over the posed vertices of `poly`, by the hill climb of
/// [`crate::query::proximity::support::climb`] from the best of `starts`
/// (first one wins ties).
pub(in crate::query) fn support(
    poly: &Polytope,
    posed: impl Fn(u32) -> DVec3,
    dir: DVec3,
    starts: &[u32],
) -> f64 {
    let mut v = starts[0];
    let mut best = dir.dot(posed(v));
    for &s in &starts[1..] {
        let d = dir.dot(posed(s));
        if d > best {
            best = d;
            v = s;
        }
    }
    hill_climb(poly, posed, dir, v).1
}

/// The refined value of a candidate: `h_A(n) + h_B(−n)`, each support
/// found by a hill climb from the candidate's own features (so the value
/// is at least the lower bound `h₀`, exactly: the climbs start at the
/// features `h₀` is taken at and only move up).
pub(in crate::query) fn climb(pair: &ConvexPair, posed: &Posed, c: &Candidate) -> f64 {
    let (a, b) = (&pair.a, &pair.b);
    let (pa, pb) = (|v| posed.a(v), |w| posed.b(w));
    let (ha, hb) = match c.features {
        FeaturePair::FaceVertex { a_face, b_vertex } => (
            support(a, pa, c.n, a.face(a_face as usize)),
            support(b, pb, -c.n, &[b_vertex]),
        ),
        FeaturePair::VertexFace { a_vertex, b_face } => (
            support(a, pa, c.n, &[a_vertex]),
            support(b, pb, -c.n, b.face(b_face as usize)),
        ),
        FeaturePair::EdgeEdge { a_edge, b_edge } => (
            support(a, pa, c.n, &a.edge(a_edge as usize).vertices),
            support(b, pb, -c.n, &b.edge(b_edge as usize).vertices),
        ),
    };
    ha + hb
}

/// Replaces the lower bounds `h₀` by true support values where they can
/// matter to the depth (within the tie tolerance of the best value) and
/// keeps those candidates, in order, together with the unrefined ones that
/// may face the origin (`h₀ ≤ tol`), which the separation refines only
/// when their distance bound can win ([`crate::query::proximity::distance::separation`]).
pub(in crate::query) fn refine(
    pair: &ConvexPair,
    posed: &Posed,
    cands: &mut Vec<Candidate>,
    tol: f64,
) {
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
    // ([`crate::query::proximity::distance::separation`]). The others cannot matter.
    cands.retain(|c| c.refined || c.h <= tol);
}

/// The facets of `A ⊕ (−B)` whose candidates a query evaluates: the whole
/// overlay (the exhaustive reference, or a tracker's dynamic sum), or the
/// facets a certificate found near the answer ([`crate::query::proximity::certificate`]).
/// Indices as in [`Overlay`]: `fv` pairs a face of A with a vertex of `−B`,
/// `vf` a face of `−B` with a vertex of A, `ee` an edge of A with an edge
/// of `−B`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(in crate::query) struct FacetSet {
    /// `(face of A, vertex of −B)`.
    pub fv: Vec<(u32, u32)>,
    /// `(face of −B, vertex of A)`.
    pub vf: Vec<(u32, u32)>,
    /// `(edge of A, edge of −B)`.
    pub ee: Vec<(u32, u32)>,
}

impl FacetSet {
    /// Empties the set, keeping its buffers.
    pub(in crate::query) fn clear(&mut self) {
        self.fv.clear();
        self.vf.clear();
        self.ee.clear();
    }

    /// Every facet of an overlay.
    pub(in crate::query) fn fill_from(&mut self, overlay: &Overlay) {
        self.clear();
        self.fv
            .extend(overlay.fv.iter().enumerate().map(|(f, &w)| (f as u32, w)));
        self.vf
            .extend(overlay.vf.iter().enumerate().map(|(g, &u)| (g as u32, u)));
        self.ee.extend_from_slice(&overlay.ee);
    }

    /// Whether the set holds no facet.
    pub(in crate::query) fn is_empty(&self) -> bool {
        self.fv.is_empty() && self.vf.is_empty() && self.ee.is_empty()
    }

    /// Sorts each list and removes repeats (a facet found by two searches).
    pub(in crate::query) fn dedup(&mut self) {
        for l in [&mut self.fv, &mut self.vf, &mut self.ee] {
            l.sort_unstable();
            l.dedup();
        }
    }
}

/// The candidates of the facets in `facets`, with the lower bounds `h₀` as
/// values, into `out` (cleared first).
///
/// The ee-candidates come last and cost an exact side test and a
/// double-double direction each, so the least fv- or vf-candidate is
/// refined first, and an ee-candidate whose value `h₀` is certainly above
/// the refine bound (by a full tolerance, so that rounding cannot matter)
/// is left out: it would be dropped by [`refine`] anyway.
pub(in crate::query) fn candidates(
    pair: &ConvexPair,
    posed: &Posed,
    facets: &FacetSet,
    tol: f64,
    out: &mut Vec<Candidate>,
) {
    push_face_candidates(pair, posed, facets, out);
    let mut skip_above = f64::INFINITY;
    if let Some(first) = (0..out.len()).min_by(|&i, &j| out[i].h.total_cmp(&out[j].h)) {
        let c = &mut out[first];
        c.h = climb(pair, posed, c);
        c.refined = true;
        // Above `max(best + tol, tol)` a candidate can neither win, nor
        // tie, nor face the origin; one more `tol` of margin for rounding.
        skip_above = (c.h + tol).max(tol) + tol;
    }
    let (vp, vq) = (posed.view_a(pair), posed.view_neg_b(pair));
    for &(e, e2) in &facets.ee {
        push_ee_candidate(pair, posed, (&vp, &vq), e, e2, skip_above, out);
    }
}

/// [`candidates`] without leaving any out, for the tests' reference.
#[cfg(test)]
pub(in crate::query) fn candidates_unpruned(
    pair: &ConvexPair,
    posed: &Posed,
    facets: &FacetSet,
    out: &mut Vec<Candidate>,
) {
    push_face_candidates(pair, posed, facets, out);
    let (vp, vq) = (posed.view_a(pair), posed.view_neg_b(pair));
    for &(e, e2) in &facets.ee {
        push_ee_candidate(pair, posed, (&vp, &vq), e, e2, f64::INFINITY, out);
    }
}

/// `out` cleared, then the fv- and vf-candidates of `facets`, in order.
fn push_face_candidates(
    pair: &ConvexPair,
    posed: &Posed,
    facets: &FacetSet,
    out: &mut Vec<Candidate>,
) {
    out.clear();
    for &(f, w) in &facets.fv {
        out.push(fv_candidate(pair, posed, f, w));
    }
    for &(g, u) in &facets.vf {
        out.push(vf_candidate(pair, posed, g, u));
    }
}

/// The lower bound `h₀` at a candidate's own features.
#[inline]
fn lower_bound(posed: &Posed, n: DVec3, a_vertex: u32, b_vertex: u32) -> f64 {
    n.dot(posed.a(a_vertex)) - n.dot(posed.b(b_vertex))
}

/// The candidate of the fv-facet of face `f` of A and vertex `w` of `−B`.
#[inline]
pub(in crate::query) fn fv_candidate(
    pair: &ConvexPair,
    posed: &Posed,
    f: u32,
    w: u32,
) -> Candidate {
    let n = posed.na(f);
    Candidate {
        features: FeaturePair::FaceVertex {
            a_face: f,
            b_vertex: w,
        },
        n,
        h: lower_bound(posed, n, pair.a.face(f as usize)[0], w),
        refined: false,
    }
}

/// The candidate of the vf-facet of vertex `u` of A and face `g` of `−B`.
#[inline]
pub(in crate::query) fn vf_candidate(
    pair: &ConvexPair,
    posed: &Posed,
    g: u32,
    u: u32,
) -> Candidate {
    let n = -posed.nb(g);
    Candidate {
        features: FeaturePair::VertexFace {
            a_vertex: u,
            b_face: g,
        },
        n,
        h: lower_bound(posed, n, u, pair.b.face(g as usize)[0]),
        refined: false,
    }
}

/// A bound on the angle between a candidate's direction and the place of
/// its facet on the overlay (turned to the world by B's rotation), for
/// every candidate: fv- and vf-directions are rotated unit normals (a few
/// ulps, plus [`OVERLAY_MISMATCH`]); ee-directions are chosen below to be
/// within this bound.
pub(in crate::query) const DIRECTION_ERROR: f64 = 1.0 / (1u64 << 39) as f64;

/// A bound on how far the overlay's Gaussian maps (A's normals turned by
/// the snapped matrix of the relative rotation `R_b⁻¹ R_a`, then by B's
/// snapped matrix) lie from the Gaussian maps of the bodies posed by their
/// own snapped matrices: each snap moves a matrix entry by less than
/// `2^-47`, the quaternion products and matrices round by a few ulps.
pub(in crate::query) const OVERLAY_MISMATCH: f64 = 1.0 / (1u64 << 44) as f64;

/// Pushes onto `out` the candidate of the ee-facet of edge `e` of A and
/// edge `e2` of `−B` (whose Gaussian arcs cross); none when the arcs are
/// exactly parallel (a facet of zero area), and none when its value is
/// certainly above `skip_above`.
///
/// The direction is the crossing point of the two arcs, on the side the
/// overlay's exact (perturbed) predicate chose: `X = s · (a × b) × (c × d)`
/// for the arcs `a → b` of `e` and `c → d` of `e2`, `s` the side of `d`
/// relative to `a → b` (then `X` is a positive combination of `c` and `d`).
/// When the edges are far from parallel, the normalised cross product of
/// the posed edge vectors, oriented like `X`, is within [`DIRECTION_ERROR`]
/// of it (its error bound is computed, from the rounding of the posed
/// vertices and [`OVERLAY_MISMATCH`], divided by the sine of the edges'
/// angle), and is exactly negated when A and B are swapped; otherwise `X`
/// itself is computed accurately ([`ee_direction`]).
pub(in crate::query) fn push_ee_candidate(
    pair: &ConvexPair,
    posed: &Posed,
    (vp, vq): (&GaussView<'_>, &GaussView<'_>),
    e: u32,
    e2: u32,
    skip_above: f64,
    out: &mut Vec<Candidate>,
) {
    let (a, b) = (&pair.a, &pair.b);
    let ordered = |[x, y]: [u32; 2]| if x < y { [x, y] } else { [y, x] };
    let [u1, u2] = ordered(a.edge(e as usize).vertices);
    let [w1, w2] = ordered(b.edge(e2 as usize).vertices);
    // X up to sign in floats, with a bound on its error.
    let (m, q) = (vp.arc(e), vq.arc(e2));
    let (em, eq) = (vp.arc_errs[e as usize], vq.arc_errs[e2 as usize]);
    let xu = posed.rot_b * m.cross(q);
    let (lm, lq, lx) = (m.length(), q.length(), xu.length());
    let x_err = em * (lq + eq) + lm * eq + 4.0 * f64::EPSILON * lm * lq;
    let p = posed.a(u1) - posed.b(w1);
    if skip_above.is_finite() && lx > 0.0 && lx.is_finite() && x_err <= 1e-6 * lx {
        // X lies on A's arc, a positive combination of the arc's two unit
        // normals, so its sign is that of `xu · (n0 + n1)` when that is
        // clearly non-zero (the arc is not nearly a half circle). Then
        // h₀ ≥ its value at the float direction less the direction's
        // error (angle `delta`) times |p| and the rounding: a candidate
        // certainly above `skip_above` is left out before the exact side.
        let [f0, f1] = a.edge(e as usize).faces;
        let mid = posed.na(f0) + posed.na(f1);
        let t = xu.dot(mid);
        if t.abs() > 1e-6 * lx * mid.length() {
            let delta = 2.0 * x_err / lx + 16.0 * f64::EPSILON + 2.0 * OVERLAY_MISMATCH;
            let pl = p.length();
            if t.signum() * xu.dot(p) / lx - (delta + 4.0 * f64::EPSILON) * pl > skip_above {
                return;
            }
        }
    }
    let (_, d) = vq.edge_arc(e2);
    let s = if vp.arc_side(e, &d).is_negative() {
        -1.0
    } else {
        1.0
    };
    let x_world = xu * s;
    let da = posed.a(u2) - posed.a(u1);
    let db = posed.b(w2) - posed.b(w1);
    let c = da.cross(db);
    let (la, lb, lc) = (da.length(), db.length(), c.length());
    let sin = lc / (la * lb);
    let delta = 2.0
        * (2.0 * posed.eta_a / la + 2.0 * posed.eta_b / lb + 4.0 * f64::EPSILON + OVERLAY_MISMATCH)
        / sin;
    let oriented = c.dot(x_world);
    let n = if lc > 0.0
        && lc.is_finite()
        && delta <= DIRECTION_ERROR
        && x_err <= 0.1 * lx
        && oriented.abs() > 0.5 * lc * x_world.length()
    {
        c * (oriented.signum() / lc)
    } else {
        let Some(n) = ee_direction(pair, posed, e, e2, s) else {
            return; // exactly parallel edges: a facet of zero area
        };
        n
    };
    out.push(Candidate {
        features: FeaturePair::EdgeEdge {
            a_edge: e,
            b_edge: e2,
        },
        n,
        h: lower_bound(posed, n, u1, w1),
        refined: false,
    });
}

/// The world direction of the ee-facet of edge `e` of A and edge `e2` of
/// `−B`, oriented by `s` (the exact side of the crossing, see
/// [`push_ee_candidate`]): the crossing point of their Gaussian arcs,
/// `s · (cof(M) d_A) × d_B` in `−B`'s frame, turned by B's rotation and
/// normalised, where `d_A` and `d_B` are the exact edge vectors (each
/// arc's great circle is spanned by the exact normals of the edge's two
/// faces, whose cross product is a positive multiple of the edge vector
/// taken from its left face) and `M` is the relative rotation, whose
/// cofactor matrix maps cross products of normals as the overlay does.
///
/// Evaluated in double-double (a relative error of order `u² / sin φ` for
/// edges at angle `φ`), and exactly when the cross product is so small that
/// this could matter, so the direction is within a few ulps of the exact
/// crossing point whatever the angle between the edges: what the
/// certificates of [`crate::query::proximity::certificate`] rely on. `None` for exactly parallel
/// edges.
pub(in crate::query) fn ee_direction(
    pair: &ConvexPair,
    posed: &Posed,
    e: u32,
    e2: u32,
    s: f64,
) -> Option<DVec3> {
    use crate::kernel::dd::{self, DD};
    let (a, q) = (&pair.a, &pair.neg_b().polytope);
    let edge_vec = |p: &Polytope, e: u32| {
        let [u, v] = p.edge(e as usize).vertices;
        (
            p.to_frame(p.vertex(u as usize)),
            p.to_frame(p.vertex(v as usize)),
        )
    };
    let (a0, a1) = edge_vec(a, e);
    let (b0, b1) = edge_vec(q, e2);
    let da = [
        DD::diff(a1.x, a0.x),
        DD::diff(a1.y, a0.y),
        DD::diff(a1.z, a0.z),
    ];
    let db = [
        DD::diff(b1.x, b0.x),
        DD::diff(b1.y, b0.y),
        DD::diff(b1.z, b0.z),
    ];
    let wa = match &posed.turn {
        None => da,
        Some(t) => {
            let c = crate::query::frame::cofactor_dd(&t.rot);
            let row = |r: usize| c[r][0] * da[0] + c[r][1] * da[1] + c[r][2] * da[2];
            [row(0), row(1), row(2)]
        }
    };
    let x = dd::cross(&wa, &db);
    let approx = DVec3::new(x[0].hi + x[0].lo, x[1].hi + x[1].lo, x[2].hi + x[2].lo);
    let mag = |v: &[DD; 3]| v.iter().map(|d| d.abs_hi()).fold(0.0, f64::max);
    let size = mag(&wa) * mag(&db);
    let dir = if approx.abs().max_element() > 2f64.powi(-40) * size {
        approx
    } else {
        exact_crossing(posed, a0, a1, b0, b1)?
    };
    let n = posed.rot_b * (dir * s);
    let len = n.length();
    (len > 0.0 && len.is_finite()).then(|| n / len)
}

/// [`ee_direction`]'s cross product `(cof(M) d_A) × d_B`, exactly, rounded
/// to floats scaled by one power of two; `None` when it is exactly zero.
#[cold]
fn exact_crossing(posed: &Posed, a0: DVec3, a1: DVec3, b0: DVec3, b1: DVec3) -> Option<DVec3> {
    use crate::kernel::exact::{self, Dyadic};
    let da = exact::sub(a1, a0);
    let db = exact::sub(b1, b0);
    let wa = match &posed.turn {
        None => da,
        Some(t) => {
            let m = t.rot;
            let cols = [
                exact::cross(&exact::exact(m.y_axis), &exact::exact(m.z_axis)),
                exact::cross(&exact::exact(m.z_axis), &exact::exact(m.x_axis)),
                exact::cross(&exact::exact(m.x_axis), &exact::exact(m.y_axis)),
            ];
            let row = |r: usize| (0..3).fold(Dyadic::zero(), |s, j| s.add(&cols[j][r].mul(&da[j])));
            [row(0), row(1), row(2)]
        }
    };
    let x = exact::cross(&wa, &db);
    let top = x.iter().filter_map(|d| d.top_exponent()).max()?;
    Some(DVec3::new(
        x[0].to_f64_shifted(-top),
        x[1].to_f64_shifted(-top),
        x[2].to_f64_shifted(-top),
    ))
}

/// `n` or `−n`, whichever is lexicographically larger (a key invariant under
/// negation), and whether `n` itself is that one.
pub(in crate::query) fn sign_free_key(n: DVec3) -> ([f64; 3], bool) {
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

/// The winning candidate: minimum `h`; among those within `tol` of it the
/// one with the smallest sign-free key, then the "positive" one, then the
/// smaller `h`, then the first features in [`FeaturePair`]'s order (so the
/// choice depends on the set of candidates only, never on their order).
pub(in crate::query) fn winner(cands: &[Candidate], tol: f64) -> (usize, f64) {
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
                    .then(c.h.total_cmp(&cands[*j].h))
                    .then(c.features.cmp(&cands[*j].features));
                ord.is_lt()
            }
        };
        if better {
            best = Some((i, key));
        }
    }
    (best.map(|b| b.0).unwrap_or(0), hmin)
}
