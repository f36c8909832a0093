//! Certificates that let a query evaluate only the facets of
//! `D = A ⊕ (−B)` near its answer, and still give exactly the answer that
//! evaluating every facet gives.
//!
//! # What must be shown
//! The answer from a set of candidates ([`super::depth`]) depends only on
//! * for a penetration: the candidates whose support value `h` lies within
//!   the tie tolerance `tol` of the least one (the *band*);
//! * for a separation: the facing candidates whose measured feature
//!   distance is the least.
//!
//! The winner among those is chosen by rules that do not depend on the
//! candidates' order. So evaluating a set `S` of facets of the overlay
//! gives the exhaustive answer exactly when every facet outside `S` is
//! certainly outside the band (certainly farther). Everything below is
//! such a proof; when a step cannot be made (a bound too weak, a broken
//! EPA polytope) the query evaluates every facet instead and
//! [`super::QueryStats::exhaustive_answers`] counts it.
//!
//! # Facts used
//! Notation: `A'`, `B'` the rounded posed vertices, `D' = A' ⊕ (−B')`;
//! `η` the rounding of a posed vertex, `ρ` a body's radius, `δ` =
//! [`DIRECTION_ERROR`] + [`OVERLAY_MISMATCH`].
//! 1. Every candidate's direction `n` lies within `δ` of a direction in
//!    which its features are supporting features of the exactly posed
//!    bodies ([`super::candidates`]). By the Lipschitz continuity of the
//!    support function (constant `ρ`), its lower bound `h₀` (the value at
//!    its own features, never above its refined `h`) then satisfies
//!    `h₀ ≥ h_{D'}(n) − E` with `E = 2δ(ρ_A + ρ_B) + 2(η_A + η_B)` plus
//!    the rounding of two dot products.
//! 2. If a facet's direction `n` lies within chord `c` of a direction `m`,
//!    its features' vertices lie within `τ = 2(c + δ)ρ` of the extreme of
//!    their body in `m` (`−m` for B): they are in the near-extreme sets of
//!    [`super::support::near_max`], which are complete.
//! 3. The overlay's facets are found from features exactly as the static
//!    sums find them: an fv-facet's vertex of `−B` by locating the face's
//!    normal in `−B`'s Gaussian map, an ee-facet by the crossing test of
//!    the two arcs, with the same exact predicates, perturbation and
//!    indices ([`super::frame::Posed::view_a`]). So every facet found is a
//!    facet of the overlay, with the same labels.
//!
//! # Penetration: caps around EPA's polytope
//! EPA ([`super::epa`]) gives a closed triangulated surface `K` whose
//! vertices are (float-rounded) points of `D'` and, checked exactly, every
//! face of which has the origin strictly on its inner side. Then every ray
//! from the origin crosses some face (the faces' central projections are
//! positively oriented spherical triangles tiling the sphere a positive
//! number of times), and where the ray in unit direction `n` crosses face
//! `k` (unit normal `m_k`, offset `d_k > 0`) at distance `t`, the crossing
//! point is a convex combination of points of `D'`, so
//! `h_{D'}(n) ≥ t = d_k / (n · m_k)` (less the vertices' rounding,
//! `err_K`). Hence `h_{D'}(n) ≤ c` forces `n · m_k ≥ d_k / c` for the face
//! the ray crosses: every direction of support value at most `c` lies in
//! one of the *caps* `{n : n · m_k ≥ d_k / c}` of the faces with
//! `d_k ≤ c` (computed with the rounding of `m_k` and `d_k` bounded from
//! the faces' shapes). With `c = hmin + tol + E + err_K`, fact 1 puts every
//! candidate outside the caps above the band, and fact 2 finds every facet
//! whose candidate lies in a cap. After the evaluation the query checks
//! that its least value `hmin` indeed satisfies the inequality assumed
//! (one retry with the larger `c`, else the exhaustive evaluation). Caps
//! wider than 60° (depths within rounding of zero: touching) go to the
//! exhaustive evaluation.
//!
//! # Separation: a slab around GJK's direction
//! GJK ends with a unit direction `n` and (from the near-extreme searches)
//! a rigorous lower bound `s` on `min_{D'} n · x`. A facet none of whose
//! A-feature's vertices is within `τ` of A's extreme in `−n` has all its
//! A-points (and the float points measured on them, which lie within
//! `2η + 8ε` of the feature) above that extreme by `τ − 2η − …`, so its
//! measured distance exceeds `s + τ − 4(η_A + η_B) − 32 ε B`; likewise for
//! B. With `τ = best − s + 4(η_A + η_B) + 32 ε B`, where `best` is the
//! least measured distance of the facets found, every facet outside the
//! found set is farther than `best` and cannot win. The set found is every
//! facet with an A-feature touching A's near-extreme set and a B-feature
//! touching B's; `best` is first estimated by GJK's `|v|` and checked
//! afterwards (one retry, else the exhaustive evaluation).

use super::candidates::{FacetSet, DIRECTION_ERROR, OVERLAY_MISMATCH};
use super::epa::Epa;
use super::frame::Posed;
use super::gjk::{CertScratch, Gjk};
use super::support::{dot_error, near_max, Marks, NearMax};
use super::ConvexPair;
use crate::gauss::edges_cross;
use glam::DVec3;

/// The most caps a penetration certificate uses.
const MAX_CAPS: usize = 16;

/// The widest cap: `cos θ` at least this (60°).
const MIN_CAP_COS: f64 = 0.5;

/// Buffers of the local searches (kept from query to query).
#[derive(Clone, Debug, Default)]
pub(super) struct LocalScratch {
    pub epa: Epa,
    pub facets: FacetSet,
    in_a: Marks,
    in_b: Marks,
    faces_a: Marks,
    faces_b: Marks,
    edges_a: Vec<u32>,
    edges_b: Vec<u32>,
    edge_marks_a: Marks,
    edge_marks_b: Marks,
    caps: Vec<(DVec3, f64)>,
}

/// `E` of fact 1 plus `err_K`, in frame units.
pub(super) fn value_slack(posed: &Posed) -> f64 {
    let delta = DIRECTION_ERROR + OVERLAY_MISMATCH;
    2.0 * delta * (posed.rho_a + posed.rho_b)
        + 2.0 * (posed.eta_a + posed.eta_b)
        + 2.0 * dot_error(DVec3::ONE, posed.scale)
        + 4.0 * f64::EPSILON * posed.scale
}

/// Grows EPA's polytope from GJK's enclosing tetrahedron and checks it
/// exactly; `false` when there is none to use.
pub(super) fn grow_polytope(
    pair: &ConvexPair,
    posed: &Posed,
    g: &Gjk,
    ls: &mut LocalScratch,
) -> bool {
    if !g.enclosed || g.simplex.len != 4 {
        return false;
    }
    ls.epa.run(pair, posed, g.simplex.pts) && ls.epa.encloses_origin()
}

/// The least offset of a face of EPA's polytope (a lower bound on the
/// depth, up to rounding).
pub(super) fn polytope_depth(ls: &LocalScratch) -> f64 {
    ls.epa.nearest().map_or(f64::INFINITY, |f| ls.epa.tris[f].d)
}

/// The facets of every cap for the support bound `c` (module docs), into
/// `ls.facets`; `false` when a cap is too wide or there are too many.
pub(super) fn penetration_facets(
    pair: &ConvexPair,
    posed: &Posed,
    c: f64,
    cs: &mut CertScratch,
    ls: &mut LocalScratch,
) -> bool {
    if !(c > 0.0 && c.is_finite()) {
        return false;
    }
    ls.caps.clear();
    for t in ls.epa.tris.iter().filter(|t| t.alive) {
        let [a, b, cc] = t.v.map(|i| ls.epa.pts[i as usize].w);
        let (e1, e2) = (b - a, cc - a);
        let area2 = e1.cross(e2).length();
        // Rounding of the unit normal (angle) and of the offset.
        let dm = 6.0 * f64::EPSILON * e1.length() * e2.length() / area2 + 4.0 * f64::EPSILON;
        let dd = (dm + 4.0 * f64::EPSILON) * a.length();
        if !(dm.is_finite() && dm < 1e-3) {
            return false;
        }
        if t.d - dd > c {
            continue;
        }
        let cos = (t.d - dd) / c - dm;
        if cos < MIN_CAP_COS || ls.caps.len() == MAX_CAPS {
            return false;
        }
        ls.caps.push((t.n, cos));
    }
    ls.facets.clear();
    let warm = (
        ls.epa.pts.first().map_or(0, |p| p.a),
        ls.epa.pts.first().map_or(0, |p| p.b),
    );
    for i in 0..ls.caps.len() {
        let (m, cos) = ls.caps[i];
        let chord = (2.0 - 2.0 * cos).max(0.0).sqrt() * (1.0 + 1e-12) + 1e-300;
        let delta = DIRECTION_ERROR + OVERLAY_MISMATCH;
        let tau_a = 2.0 * (chord + delta) * posed.rho_a;
        let tau_b = 2.0 * (chord + delta) * posed.rho_b;
        let na = near_max(
            &pair.a,
            |v| posed.a(v),
            m,
            warm.0,
            tau_a,
            posed.eta_a,
            posed.scale,
            &mut cs.marks_a,
            &mut cs.set_a,
        );
        let nb = near_max(
            &pair.b,
            |w| posed.b(w),
            -m,
            warm.1,
            tau_b,
            posed.eta_b,
            posed.scale,
            &mut cs.marks_b,
            &mut cs.set_b,
        );
        // Faces in the cap: their candidates' directions are their rotated
        // unit normals (compared with a few ulps of slack).
        let min_cos = cos - 8.0 * f64::EPSILON;
        collect(
            pair,
            posed,
            (&na, &nb),
            cs,
            ls,
            |f| posed.na(f).dot(m) >= min_cos,
            |g| -posed.nb(g).dot(m) >= min_cos,
            true,
        );
    }
    ls.facets.dedup();
    true
}

/// The facets near the separation along the unit direction `n` with
/// slab width `tau` (module docs), into `ls.facets`.
pub(super) fn separation_facets(
    pair: &ConvexPair,
    posed: &Posed,
    n: DVec3,
    tau: f64,
    warm: (u32, u32),
    cs: &mut CertScratch,
    ls: &mut LocalScratch,
) {
    let na = near_max(
        &pair.a,
        |v| posed.a(v),
        -n,
        warm.0,
        tau,
        posed.eta_a,
        posed.scale,
        &mut cs.marks_a,
        &mut cs.set_a,
    );
    let nb = near_max(
        &pair.b,
        |w| posed.b(w),
        n,
        warm.1,
        tau,
        posed.eta_b,
        posed.scale,
        &mut cs.marks_b,
        &mut cs.set_b,
    );
    ls.facets.clear();
    collect(pair, posed, (&na, &nb), cs, ls, |_| true, |_| true, false);
    ls.facets.dedup();
}

/// A rigorous lower bound on `min_{D'} n · x` from the near-extreme
/// searches, and the warm start they end at.
pub(super) fn slab_floor(
    pair: &ConvexPair,
    posed: &Posed,
    n: DVec3,
    warm: (u32, u32),
    cs: &mut CertScratch,
) -> f64 {
    let na = near_max(
        &pair.a,
        |v| posed.a(v),
        -n,
        warm.0,
        0.0,
        posed.eta_a,
        posed.scale,
        &mut cs.marks_a,
        &mut cs.set_a,
    );
    let nb = near_max(
        &pair.b,
        |w| posed.b(w),
        n,
        warm.1,
        0.0,
        posed.eta_b,
        posed.scale,
        &mut cs.marks_b,
        &mut cs.set_b,
    );
    -(na.upper + nb.upper)
}

/// The slab width that covers every facet which could measure at most
/// `best` (module docs).
pub(super) fn slab_width(posed: &Posed, best: f64, floor: f64) -> f64 {
    (best - floor).max(0.0) * (1.0 + 4.0 * f64::EPSILON)
        + 4.0 * (posed.eta_a + posed.eta_b)
        + 32.0 * f64::EPSILON * posed.scale
        + 1e-300
}

/// Pushes onto `ls.facets` the overlay facets whose features touch the
/// near-extreme sets `cs.set_a` (of A) and `cs.set_b` (of B): fv-facets of
/// A's faces at a vertex of the set (accepted by `face_a`), with their
/// vertex of `−B` located; vf-facets of B's faces likewise (`face_b`); and
/// ee-facets of the edges with both ends in the sets (`both`) or one,
/// tested for crossing arcs.
#[allow(clippy::too_many_arguments)]
fn collect(
    pair: &ConvexPair,
    posed: &Posed,
    (na, nb): (&NearMax, &NearMax),
    cs: &mut CertScratch,
    ls: &mut LocalScratch,
    face_a: impl Fn(u32) -> bool,
    face_b: impl Fn(u32) -> bool,
    both: bool,
) {
    let (a, b) = (&pair.a, &pair.b);
    let (vp, vq) = (posed.view_a(pair), posed.view_neg_b(pair));
    let prep = &pair.prep_b;
    ls.in_a.start(a.vertex_count());
    ls.in_b.start(b.vertex_count());
    for &v in &cs.set_a {
        ls.in_a.mark(v);
    }
    for &w in &cs.set_b {
        ls.in_b.mark(w);
    }
    // fv: A's faces at the set, with the vertex of −B their normal lies in.
    let hint_q = prep.neg_vertex[nb.vertex as usize];
    ls.faces_a.start(a.face_count());
    for &v in &cs.set_a {
        for r in a.ring(v as usize) {
            if ls.faces_a.mark(r.face) && face_a(r.face) {
                let (w, _) = vq.locate(&vp.normal(r.face), hint_q);
                ls.facets.fv.push((r.face, w));
            }
        }
    }
    // vf: B's faces at the set, as faces of −B, with the vertex of A.
    ls.faces_b.start(b.face_count());
    for &w in &cs.set_b {
        for r in b.ring(w as usize) {
            if ls.faces_b.mark(r.face) && face_b(r.face) {
                let g = prep.neg_face[r.face as usize];
                let (u, _) = vp.locate(&vq.normal(g), na.vertex);
                ls.facets.vf.push((g, u));
            }
        }
    }
    // ee: edges at the sets, tested pairwise.
    let keep = |m: &Marks, ends: [u32; 2]| {
        if both {
            m.is_marked(ends[0]) && m.is_marked(ends[1])
        } else {
            m.is_marked(ends[0]) || m.is_marked(ends[1])
        }
    };
    ls.edges_a.clear();
    ls.edge_marks_a.start(a.edge_count());
    for &v in &cs.set_a {
        for r in a.ring(v as usize) {
            if ls.edge_marks_a.mark(r.edge) && keep(&ls.in_a, a.edge(r.edge as usize).vertices) {
                ls.edges_a.push(r.edge);
            }
        }
    }
    ls.edges_b.clear();
    ls.edge_marks_b.start(b.edge_count());
    for &w in &cs.set_b {
        for r in b.ring(w as usize) {
            if ls.edge_marks_b.mark(r.edge) && keep(&ls.in_b, b.edge(r.edge as usize).vertices) {
                ls.edges_b.push(prep.neg_edge[r.edge as usize]);
            }
        }
    }
    for &e in &ls.edges_a {
        for &e2 in &ls.edges_b {
            if edges_cross(&vp, e, &vq, e2) {
                ls.facets.ee.push((e, e2));
            }
        }
    }
}
