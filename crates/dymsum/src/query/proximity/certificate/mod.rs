//! Certificates that let a query evaluate only the facets of
//! `D = A ⊕ (−B)` near its answer, and still give exactly the answer that
//! evaluating every facet gives.
//!
//! # What must be shown
//! The answer from a set of candidates ([`crate::query::depth`]) depends only on
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
//! [`crate::query::pair::QueryStats::exhaustive_answers`] counts it.
//!
//! # Facts used
//! Notation: `A'`, `B'` the rounded posed vertices, `D' = A' ⊕ (−B')`;
//! `η` the rounding of a posed vertex, `ρ` a body's radius, `δ` =
//! [`DIRECTION_ERROR`] + [`OVERLAY_MISMATCH`].
//! 1. Every candidate's direction `n` lies within `δ` of a direction in
//!    which its features are supporting features of the exactly posed
//!    bodies ([`crate::query::proximity::certificate::candidates`]). By the Lipschitz continuity of the
//!    support function (constant `ρ`), its lower bound `h₀` (the value at
//!    its own features, never above its refined `h`) then satisfies
//!    `h₀ ≥ h_{D'}(n) − E` with `E = 2δ(ρ_A + ρ_B) + 2(η_A + η_B)` plus
//!    the rounding of two dot products.
//! 2. If a facet's direction `n` lies within chord `c` of a direction `m`,
//!    its features' vertices lie within `τ = 2(c + δ)ρ` of the extreme of
//!    their body in `m` (`−m` for B): they are in the near-extreme sets of
//!    [`crate::query::proximity::support::near_max`], which are complete.
//! 3. The overlay's facets are found from features exactly as the static
//!    sums find them: an fv-facet's vertex of `−B` by locating the face's
//!    normal in `−B`'s Gaussian map, an ee-facet by the crossing test of
//!    the two arcs, with the same exact predicates, perturbation and
//!    indices ([`crate::query::frame::Posed::view_a`]). So every facet found is a
//!    facet of the overlay, with the same labels.
//!
//!
//! The two certificates are in [`caps`] (a penetration) and [`slab`] (a
//! separation); what they share (the caps of the Gaussian cells, the
//! bounded searches over the overlay) is here.

pub(in crate::query) mod candidates;
pub(in crate::query) mod caps;
pub(in crate::query) mod slab;

pub(in crate::query) use caps::{grow_polytope, penetration_facets, polytope_depth};
pub(in crate::query) use slab::{separation_facets, single_facet, slab, slab_width, two_facets};

use crate::gauss::edges_cross;
use crate::query::frame::Posed;
use crate::query::pair::ConvexPair;
use crate::query::proximity::certificate::candidates::{
    FacetSet, DIRECTION_ERROR, OVERLAY_MISMATCH,
};
use crate::query::proximity::epa::Epa;
use crate::query::proximity::gjk::CertScratch;
use crate::query::proximity::support::{dot_error, Marks};
use glam::DVec3;

/// How much a cap test's cosine is loosened: the float normals lie within
/// a few ulps (and [`OVERLAY_MISMATCH`]) of the overlay's exact ones.
pub(in crate::query) const CAP_SLACK: f64 = 1e-9;

/// Whether the unit direction `x` may lie in the cap `(c, cos)` (`c`
/// already turned to the world).
#[inline]
pub(in crate::query) fn in_cap(x: DVec3, (c, cos): (DVec3, f64)) -> bool {
    cos <= -1.0 || x.dot(c) >= cos - CAP_SLACK
}

/// Whether two arcs' caps (turned to the world) may meet: the angle
/// between the centres is at most the sum of the half-angles.
#[inline]
pub(in crate::query) fn caps_meet((c1, cos1): (DVec3, f64), (c2, cos2): (DVec3, f64)) -> bool {
    if cos1 <= -1.0 || cos2 <= -1.0 {
        return true;
    }
    let (sin1, sin2) = (
        (1.0 - cos1 * cos1).max(0.0).sqrt(),
        (1.0 - cos2 * cos2).max(0.0).sqrt(),
    );
    c1.dot(c2) >= cos1 * cos2 - sin1 * sin2 - CAP_SLACK
}

#[derive(Clone, Debug, Default)]
pub(in crate::query) struct LocalScratch {
    pub epa: Epa,
    pub facets: FacetSet,
    in_a: Marks,
    in_b: Marks,
    faces_a: Marks,
    faces_b: Marks,
    edges_a: Vec<(u32, Circle, (DVec3, f64))>,
    edges_b: Vec<(u32, Circle, (DVec3, f64))>,
    edge_marks_a: Marks,
    edge_marks_b: Marks,
    /// The penetration's caps: centre, cosine, and the vertices of A and
    /// B its searches start from.
    caps: Vec<(DVec3, f64, (u32, u32))>,
    /// A cap's projected points (the separation's lateral bound).
    points: Vec<DVec3>,
}

/// `E` of fact 1 plus `err_K`, in frame units.
pub(in crate::query) fn value_slack(posed: &Posed) -> f64 {
    let delta = DIRECTION_ERROR + OVERLAY_MISMATCH;
    2.0 * delta * (posed.rho_a + posed.rho_b)
        + 2.0 * (posed.eta_a + posed.eta_b)
        + 2.0 * dot_error(DVec3::ONE, posed.scale)
        + 4.0 * f64::EPSILON * posed.scale
}

/// Grows EPA's polytope from GJK's enclosing tetrahedron (towards `hint`
/// first, a tracker's last contact normal) and checks it exactly; `false`
/// A circle in the projection of the separation's lateral bound: centre
/// and radius.
pub(in crate::query) type Circle = (DVec3, f64);

/// Which features a facet search keeps (beyond touching the near-extreme
/// sets): A's faces, B's faces, A's edges, B's edges (by their own
/// indices; an edge kept comes with a circle for the pair test), and pairs
/// of kept edges (by their circles) before their arcs are tested.
pub(in crate::query) struct Keep<FA, FB, EA, EB, P> {
    face_a: FA,
    face_b: FB,
    edge_a: EA,
    edge_b: EB,
    pair: P,
    /// Edges need both ends in the sets (else one).
    both: bool,
}

/// Pushes onto `local.facets` the overlay facets whose features touch the
/// near-extreme sets `cert.set_a` (of A) and `cert.set_b` (of B) and pass
/// `keep`: fv-facets of A's faces at a vertex of the set, with their vertex
/// of `−B` located; vf-facets of B's faces likewise; and ee-facets of the
/// edges with both ends in the sets (`keep.both`) or one, tested for
/// crossing arcs.
pub(in crate::query) fn collect<FA, FB, EA, EB, P>(
    pair: &ConvexPair,
    posed: &Posed,
    cert: &mut CertScratch,
    local: &mut LocalScratch,
    keep: Keep<FA, FB, EA, EB, P>,
) where
    FA: Fn(u32) -> bool,
    FB: Fn(u32) -> bool,
    EA: Fn(u32) -> Option<Circle>,
    EB: Fn(u32) -> Option<Circle>,
    P: Fn(Circle, Circle) -> bool,
{
    let (a, b) = (&pair.a, &pair.b);
    let (vp, vq) = (posed.view_a(pair), posed.view_neg_b(pair));
    local.in_a.start(a.vertex_count());
    local.in_b.start(b.vertex_count());
    for &v in &cert.set_a {
        local.in_a.mark(v);
    }
    for &w in &cert.set_b {
        local.in_b.mark(w);
    }
    // fv: A's faces at the set, with the vertex of −B their normal lies
    // in. That vertex (B's support opposite the normal) must be in B's set
    // for the facet to matter (fact 2, and the slab), so only a face whose
    // normal may lie in the cell of a vertex of B's set is located, from
    // there, and kept if the vertex found is in the set.
    let (caps_a, caps_b) = (&pair.prep_a.caps, &pair.prep_b.caps);
    let (rot_a, rot_b) = (posed.pose_a.rotation, posed.pose_b.rotation);
    local.faces_a.start(a.face_count());
    for &v in &cert.set_a {
        for r in a.ring(v as usize) {
            if !local.faces_a.mark(r.face) || !(keep.face_a)(r.face) {
                continue;
            }
            let n = posed.na(r.face);
            let Some(&w) = cert.set_b.iter().find(|&&w| {
                let (c, cos) = caps_b.cells[w as usize];
                in_cap(n, (-rot_b.apply(c), cos))
            }) else {
                continue;
            };
            let (wq, _) = vq.locate(&vp.normal(r.face), w);
            if local.in_b.is_marked(wq) {
                local.facets.fv.push((r.face, wq));
            }
        }
    }
    // vf: B's faces at the set, as faces of −B, with the vertex of A (which
    // must be in A's set likewise).
    local.faces_b.start(b.face_count());
    for &w in &cert.set_b {
        for r in b.ring(w as usize) {
            if !local.faces_b.mark(r.face) || !(keep.face_b)(r.face) {
                continue;
            }
            let n = -posed.nb(r.face);
            let Some(&u) = cert.set_a.iter().find(|&&u| {
                let (c, cos) = caps_a.cells[u as usize];
                in_cap(n, (rot_a.apply(c), cos))
            }) else {
                continue;
            };
            let g = r.face;
            let (ua, _) = vp.locate(&vq.normal(g), u);
            if local.in_a.is_marked(ua) {
                local.facets.vf.push((g, ua));
            }
        }
    }
    // ee: edges at the sets, tested pairwise: the arcs' caps (turned to the
    // world; B's negated, as −B's arcs) first, then `keep.pair`, then the
    // exact crossing test.
    let touches = |m: &Marks, ends: [u32; 2]| {
        if keep.both {
            m.is_marked(ends[0]) && m.is_marked(ends[1])
        } else {
            m.is_marked(ends[0]) || m.is_marked(ends[1])
        }
    };
    local.edges_a.clear();
    local.edge_marks_a.start(a.edge_count());
    for &v in &cert.set_a {
        for r in a.ring(v as usize) {
            if local.edge_marks_a.mark(r.edge)
                && touches(&local.in_a, a.edge(r.edge as usize).vertices)
            {
                if let Some(c) = (keep.edge_a)(r.edge) {
                    let (ac, cos) = caps_a.arcs[r.edge as usize];
                    local.edges_a.push((r.edge, c, (rot_a.apply(ac), cos)));
                }
            }
        }
    }
    local.edges_b.clear();
    local.edge_marks_b.start(b.edge_count());
    for &w in &cert.set_b {
        for r in b.ring(w as usize) {
            if local.edge_marks_b.mark(r.edge)
                && touches(&local.in_b, b.edge(r.edge as usize).vertices)
            {
                if let Some(c) = (keep.edge_b)(r.edge) {
                    let (ac, cos) = caps_b.arcs[r.edge as usize];
                    local.edges_b.push((r.edge, c, (-rot_b.apply(ac), cos)));
                }
            }
        }
    }
    for &(e, ca, arc_a) in &local.edges_a {
        for &(e2, cb, arc_b) in &local.edges_b {
            if caps_meet(arc_a, arc_b) && (keep.pair)(ca, cb) && edges_cross(&vp, e, &vq, e2) {
                local.facets.ee.push((e, e2));
            }
        }
    }
}

/// A circle that excludes nothing (the penetration's searches have no
/// lateral bound).
pub(in crate::query) const ANY: Circle = (DVec3::ZERO, f64::INFINITY);

/// Whether the Gaussian arc between the unit normals `p` and `q` (shorter
/// than π) comes within the cap `{x : x · m ≥ cos}`: the largest `x · m`
/// over the arc is at an end, or, where `m`'s projection on the arc's great
/// circle falls inside the arc, `√(1 − (m · g)²)` for the circle's unit
/// normal `g`; taken over the whole circle when the inside test is close,
/// so the answer errs towards keeping.
pub(in crate::query) fn arc_meets_cap(p: DVec3, q: DVec3, m: DVec3, cos: f64) -> bool {
    if p.dot(m) >= cos || q.dot(m) >= cos {
        return true;
    }
    let g = p.cross(q);
    let gl = g.length();
    if gl == 0.0 {
        return false;
    }
    let g = g / gl;
    let mg = m.dot(g);
    let proj = m - mg * g;
    let inside = p.cross(proj).dot(g) >= -1e-9 && proj.cross(q).dot(g) >= -1e-9;
    inside && (1.0 - mg * mg).max(0.0).sqrt() >= cos
}
