//! The penetration certificate: caps around EPA's polytope.
//!
//! EPA ([`crate::query::proximity::epa`]) gives a closed triangulated surface `K` whose
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

use super::{arc_meets_cap, collect, Keep, LocalScratch, ANY};
use crate::query::frame::Posed;
use crate::query::pair::ConvexPair;
use crate::query::proximity::certificate::candidates::{DIRECTION_ERROR, OVERLAY_MISMATCH};
use crate::query::proximity::gjk::{near_max_pair, CertScratch, Gjk};
use crate::query::proximity::support::climb_unposed;
use glam::DVec3;
/// The most caps a penetration certificate uses.
const MAX_CAPS: usize = 16;

/// The widest cap: `cos θ` at least this (60°).
const MIN_CAP_COS: f64 = 0.5;

/// Buffers of the local searches (kept from query to query).
/// when there is none to use.
pub(in crate::query) fn grow_polytope(
    pair: &ConvexPair,
    posed: &Posed,
    g: &Gjk,
    hint: Option<DVec3>,
    carried: bool,
    local: &mut LocalScratch,
) -> bool {
    let grown = if carried {
        local.epa.regrow(pair, posed)
    } else if g.enclosed && g.simplex.len == 4 {
        local.epa.run(pair, posed, g.simplex.pts, hint)
    } else {
        // No enclosing tetrahedron (the origin on a face or an edge of
        // GJK's simplex): start from the hull of the simplex and the
        // support points along the axes.
        let mut pts = [crate::query::proximity::gjk::Point::default(); 10];
        pts[..g.simplex.len].copy_from_slice(&g.simplex.pts[..g.simplex.len]);
        let mut k = g.simplex.len;
        let to_a = posed.pose_a.rotation.matrix().transpose();
        let to_b = posed.pose_b.rotation.matrix().transpose();
        for d in [
            DVec3::X,
            DVec3::NEG_X,
            DVec3::Y,
            DVec3::NEG_Y,
            DVec3::Z,
            DVec3::NEG_Z,
        ] {
            let a = climb_unposed(&pair.a, &to_a, d, g.warm.0);
            let b = climb_unposed(&pair.b, &to_b, -d, g.warm.1);
            if !pts[..k].iter().any(|p| p.a == a && p.b == b) {
                pts[k] = crate::query::proximity::gjk::Point {
                    w: posed.a(a) - posed.b(b),
                    a,
                    b,
                };
                k += 1;
            }
        }
        local.epa.run_from_hull(pair, posed, &pts[..k], hint)
    };
    grown && local.epa.encloses_origin()
}

/// The least offset of a face of EPA's polytope (a lower bound on the
/// depth, up to rounding).
pub(in crate::query) fn polytope_depth(local: &LocalScratch) -> f64 {
    local
        .epa
        .nearest()
        .map_or(f64::INFINITY, |f| local.epa.tris[f].d)
}

/// The facets of every cap for the support bound `c` (module docs), into
/// `local.facets`; `false` when a cap is too wide or there are too many.
pub(in crate::query) fn penetration_facets(
    pair: &ConvexPair,
    posed: &Posed,
    c: f64,
    cert: &mut CertScratch,
    local: &mut LocalScratch,
) -> bool {
    if !(c > 0.0 && c.is_finite()) {
        return false;
    }
    local.caps.clear();
    for t in local.epa.tris.iter().filter(|t| t.alive) {
        let (dm, dd) = (t.dm, t.dd);
        if t.d - dd > c {
            continue;
        }
        if !(dm.is_finite() && dm < 1e-3) {
            return false;
        }
        let cos = (t.d - dd) / c - dm;
        if cos < MIN_CAP_COS || local.caps.len() == MAX_CAPS {
            return false;
        }
        // The searches start from the face's first corner: a support
        // point of D' near the cap's direction.
        let corner = local.epa.pts[t.v[0] as usize];
        local.caps.push((t.n, cos, (corner.a, corner.b)));
    }
    local.facets.clear();
    for i in 0..local.caps.len() {
        let (m, cos, warm) = local.caps[i];
        let chord = (2.0 - 2.0 * cos).max(0.0).sqrt() * (1.0 + 1e-12) + 1e-300;
        let delta = DIRECTION_ERROR + OVERLAY_MISMATCH;
        let tau_a = 2.0 * (chord + delta) * posed.rho_a;
        let tau_b = 2.0 * (chord + delta) * posed.rho_b;
        near_max_pair(pair, posed, (m, tau_a), (-m, tau_b), warm, cert);
        // Faces in the cap: their candidates' directions are their rotated
        // unit normals (compared with a few ulps of slack). Edges whose
        // float arcs come near the cap: an ee-candidate's direction lies
        // within DIRECTION_ERROR of its place on both overlay arcs, which
        // lie within OVERLAY_MISMATCH (and rounding) of the float ones.
        let min_cos = cos - 8.0 * f64::EPSILON;
        let arc_cos = cos - 2.0 * (DIRECTION_ERROR + OVERLAY_MISMATCH) - 1e-12;
        let (a, b) = (&pair.a, &pair.b);
        collect(
            pair,
            posed,
            cert,
            local,
            Keep {
                face_a: |f| posed.na(f).dot(m) >= min_cos,
                face_b: |g| -posed.nb(g).dot(m) >= min_cos,
                edge_a: |e| {
                    let [f0, f1] = a.edge(e as usize).faces;
                    arc_meets_cap(posed.na(f0), posed.na(f1), m, arc_cos).then_some(ANY)
                },
                edge_b: |e| {
                    let [g0, g1] = b.edge(e as usize).faces;
                    arc_meets_cap(-posed.nb(g0), -posed.nb(g1), m, arc_cos).then_some(ANY)
                },
                pair: |_, _| true,
                both: true,
            },
        );
    }
    local.facets.dedup();
    true
}
