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
//! # Penetration: caps around EPA's polytope
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
//!
//! Nothing above needs `n` to be GJK's direction: any unit `n` with
//! `s > 0` serves. When the bodies nearly touch (within about `√ε` of
//! their size), GJK's `v` is the difference of nearly equal points and too
//! coarse for `s > 0`; then the face normals and edge cross products of the
//! final simplex's features (exact to rounding at any distance; by the
//! separating axis theorem one of them separates) are tried instead
//! (`gjk::separating_feature_axis`), before the exhaustive evaluation.

pub(in crate::query) mod candidates;

use crate::gauss::edges_cross;
use crate::kernel::exact::mul_pow2_vec;
use crate::kernel::rotation::Pose;
use crate::query::frame::Posed;
use crate::query::pair::ConvexPair;
use crate::query::proximity::certificate::candidates::{
    FacetSet, DIRECTION_ERROR, OVERLAY_MISMATCH,
};
use crate::query::proximity::epa::Epa;
use crate::query::proximity::gjk::{CertScratch, Gjk};
use crate::query::proximity::support::{dot_error, near_max, Marks, NearMax};
use glam::DVec3;

/// Spherical caps holding a body's Gaussian cells (one per vertex) and arcs
/// (one per edge), in the body's frame: a cell is the spherical polygon of
/// its corners, inside any cap (no wider than a hemisphere) holding the
/// corners; an arc lies in the cap about its midpoint through its ends.
/// Turned with the body, they let the searches skip a cell that cannot
/// hold a direction, and pairs of arcs that cannot cross, with one dot
/// product each; the exact predicates decide the rest.
#[derive(Clone, Debug, Default)]
pub(crate) struct GaussCaps {
    /// Per vertex: the cap's unit centre and the cosine of its angle
    /// (`-1.0`, no rejection, for a cell wider than a hemisphere).
    cells: Vec<(DVec3, f64)>,
    /// Per edge: the unit centre and the cosine of half the arc.
    arcs: Vec<(DVec3, f64)>,
}

/// How much a cap test's cosine is loosened: the float normals lie within
/// a few ulps (and [`OVERLAY_MISMATCH`]) of the overlay's exact ones.
const CAP_SLACK: f64 = 1e-9;

impl GaussCaps {
    /// The caps of `p`.
    pub(crate) fn of(p: &crate::polytope::Polytope) -> GaussCaps {
        let cells = (0..p.vertex_count())
            .map(|v| {
                let ring = p.ring(v);
                let sum = ring
                    .iter()
                    .fold(DVec3::ZERO, |s, r| s + p.unit_normal(r.face as usize));
                let len = sum.length();
                if len.is_nan() || len <= 1e-3 {
                    return (DVec3::X, -1.0);
                }
                let c = sum / len;
                let cos = ring
                    .iter()
                    .map(|r| c.dot(p.unit_normal(r.face as usize)))
                    .fold(1.0, f64::min);
                (c, if cos > 1e-3 { cos } else { -1.0 })
            })
            .collect();
        let arcs = p
            .edges()
            .iter()
            .map(|e| {
                let (a, b) = (
                    p.unit_normal(e.faces[0] as usize),
                    p.unit_normal(e.faces[1] as usize),
                );
                let mid = a + b;
                let len = mid.length();
                if len.is_nan() || len <= 1e-6 {
                    return (DVec3::X, -1.0);
                }
                let c = mid / len;
                (c, c.dot(a).min(c.dot(b)))
            })
            .collect();
        GaussCaps { cells, arcs }
    }
}

/// Whether the unit direction `x` may lie in the cap `(c, cos)` (`c`
/// already turned to the world).
#[inline]
fn in_cap(x: DVec3, (c, cos): (DVec3, f64)) -> bool {
    cos <= -1.0 || x.dot(c) >= cos - CAP_SLACK
}

/// Whether two arcs' caps (turned to the world) may meet: the angle
/// between the centres is at most the sum of the half-angles.
#[inline]
fn caps_meet((c1, cos1): (DVec3, f64), (c2, cos2): (DVec3, f64)) -> bool {
    if cos1 <= -1.0 || cos2 <= -1.0 {
        return true;
    }
    let (sin1, sin2) = (
        (1.0 - cos1 * cos1).max(0.0).sqrt(),
        (1.0 - cos2 * cos2).max(0.0).sqrt(),
    );
    c1.dot(c2) >= cos1 * cos2 - sin1 * sin2 - CAP_SLACK
}

/// The most caps a penetration certificate uses.
const MAX_CAPS: usize = 16;

/// The widest cap: `cos θ` at least this (60°).
const MIN_CAP_COS: f64 = 0.5;

/// Buffers of the local searches (kept from query to query).
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
    caps: Vec<(DVec3, f64)>,
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
/// when there is none to use.
pub(in crate::query) fn grow_polytope(
    pair: &ConvexPair,
    posed: &Posed,
    g: &Gjk,
    hint: Option<DVec3>,
    ls: &mut LocalScratch,
) -> bool {
    let grown = if g.enclosed && g.simplex.len == 4 {
        ls.epa.run(pair, posed, g.simplex.pts, hint)
    } else {
        // No enclosing tetrahedron (the origin on a face or an edge of
        // GJK's simplex): start from the hull of the simplex and the
        // support points along the axes.
        let mut pts = [crate::query::proximity::gjk::Point::default(); 10];
        pts[..g.simplex.len].copy_from_slice(&g.simplex.pts[..g.simplex.len]);
        let mut k = g.simplex.len;
        for d in [
            DVec3::X,
            DVec3::NEG_X,
            DVec3::Y,
            DVec3::NEG_Y,
            DVec3::Z,
            DVec3::NEG_Z,
        ] {
            let (a, _) =
                crate::query::proximity::support::climb(&pair.a, |v| posed.a(v), d, g.warm.0);
            let (b, _) =
                crate::query::proximity::support::climb(&pair.b, |w| posed.b(w), -d, g.warm.1);
            if !pts[..k].iter().any(|p| p.a == a && p.b == b) {
                pts[k] = crate::query::proximity::gjk::Point {
                    w: posed.a(a) - posed.b(b),
                    a,
                    b,
                };
                k += 1;
            }
        }
        ls.epa.run_from_hull(pair, posed, &pts[..k], hint)
    };
    grown && ls.epa.encloses_origin()
}

/// The least offset of a face of EPA's polytope (a lower bound on the
/// depth, up to rounding).
pub(in crate::query) fn polytope_depth(ls: &LocalScratch) -> f64 {
    ls.epa.nearest().map_or(f64::INFINITY, |f| ls.epa.tris[f].d)
}

/// The facets of every cap for the support bound `c` (module docs), into
/// `ls.facets`; `false` when a cap is too wide or there are too many.
pub(in crate::query) fn penetration_facets(
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
        let (dm, dd) = (t.dm, t.dd);
        if t.d - dd > c {
            continue;
        }
        if !(dm.is_finite() && dm < 1e-3) {
            return false;
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
        near_max(
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
        near_max(
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
            cs,
            ls,
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
    ls.facets.dedup();
    true
}

/// The near-extreme sets of A in `−n` and of B in `n` (in `cs.set_a`,
/// `cs.set_b`), each covering at least `tau`, with the rigorous lower bound
/// `floor` on `min_{D'} n · x` they give: the separation's certificate
/// (`floor > 0`) and the slab of its facet search in one search per body.
#[derive(Clone, Copy, Debug)]
pub(in crate::query) struct SeparatingSlab {
    /// The unit direction (from the origin towards `D'`).
    n: DVec3,
    /// `min_{D'} n · x ≥ floor`.
    pub floor: f64,
    /// The width both sets cover.
    pub covered: f64,
    na: NearMax,
    nb: NearMax,
}

/// The [`SeparatingSlab`] of width `tau` along the unit direction `n`.
pub(in crate::query) fn slab(
    pair: &ConvexPair,
    posed: &Posed,
    n: DVec3,
    tau: f64,
    warm: (u32, u32),
    cs: &mut CertScratch,
) -> SeparatingSlab {
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
    SeparatingSlab {
        n,
        floor: -(na.upper + nb.upper),
        covered: na.tau.min(nb.tau),
        na,
        nb,
    }
}

/// The facets of the slab `s` whose features come within the lateral reach
/// of each other (module docs), for a separation of measured distance at
/// most `best`, into `ls.facets`.
pub(in crate::query) fn separation_facets(
    pair: &ConvexPair,
    posed: &Posed,
    s: &SeparatingSlab,
    best: f64,
    cs: &mut CertScratch,
    ls: &mut LocalScratch,
) {
    ls.facets.clear();
    // With one vertex in each set every facet found touches the closest
    // pair of vertices, so the lateral bound would keep them all: skip it.
    let lat = if cs.set_a.len() == 1 && cs.set_b.len() == 1 {
        Lateral::everywhere(s.n)
    } else {
        Lateral::new(pair, posed, s, best, cs, ls)
    };
    let (a, b) = (&pair.a, &pair.b);
    let (balls_a, balls_b) = (&pair.prep_a.balls, &pair.prep_b.balls);
    // Each feature lies in its ball (centre posed, precomputed radius; the
    // rotation keeps lengths to 2^-40, the rounding is in the margin).
    let turned = 1.0 + 2f64.powi(-40);
    let ball = |corners: &[u32], at: &dyn Fn(u32) -> DVec3, r: f64| {
        let c = corners.iter().fold(DVec3::ZERO, |s, &v| s + at(v)) / corners.len() as f64;
        (lat.project(c), r * turned + lat.margin)
    };
    let posed_centre = |pose: &Pose, c: DVec3| mul_pow2_vec(pose.apply(c), posed.k);
    let face_a = |f: u32| {
        let c = posed_centre(&posed.pose_a, balls_a.face_centre(f));
        lat.near(
            (
                lat.project(c),
                balls_a.face(f, posed.k) * turned + lat.margin,
            ),
            lat.disk_b,
        )
    };
    let face_b = |g: u32| {
        let c = posed_centre(&posed.pose_b, balls_b.face_centre(g));
        lat.near(
            (
                lat.project(c),
                balls_b.face(g, posed.k) * turned + lat.margin,
            ),
            lat.disk_a,
        )
    };
    let edge_a = |e: u32| {
        let c = ball(
            &a.edge(e as usize).vertices,
            &|v| posed.a(v),
            balls_a.edge(e, posed.k),
        );
        lat.near(c, lat.disk_b).then_some(c)
    };
    let edge_b = |e: u32| {
        let c = ball(
            &b.edge(e as usize).vertices,
            &|w| posed.b(w),
            balls_b.edge(e, posed.k),
        );
        lat.near(c, lat.disk_a).then_some(c)
    };
    collect(
        pair,
        posed,
        cs,
        ls,
        Keep {
            face_a,
            face_b,
            edge_a,
            edge_b,
            pair: |x, y| lat.near(x, y),
            both: false,
        },
    );
    ls.facets.dedup();
}

/// Which body a cap piece belongs to.
#[derive(Clone, Copy)]
enum Side {
    A,
    B,
}

/// The separation's lateral bound (module docs): a facet that can measure
/// at most `best` has a point `pa` of its A-feature in A's cap (`n · x` at
/// most `level_a`) and a point `pb` of its B-feature in B's cap (`n · x` at
/// least `level_b`), with `|P(pa − pb)| ≤ reach`, `P` the projection along
/// `n`. Caps and their pieces are bounded by circles in the projection.
struct Lateral {
    n: DVec3,
    level_a: f64,
    level_b: f64,
    reach: f64,
    /// Slack for the rounding of the posed points and of the projections.
    margin: f64,
    disk_a: Circle,
    disk_b: Circle,
}

impl Lateral {
    fn new(
        pair: &ConvexPair,
        posed: &Posed,
        s: &SeparatingSlab,
        best: f64,
        cs: &CertScratch,
        ls: &mut LocalScratch,
    ) -> Lateral {
        let n = s.n;
        let err_p = 4.0 * (posed.eta_a + posed.eta_b) + 32.0 * f64::EPSILON * posed.scale;
        let margin = err_p + 64.0 * f64::EPSILON * posed.scale + 1e-300;
        // Caps over-approximated: A's minimum is at most its float value
        // plus the dot product's error, B's maximum at least its float value
        // less it; the slab's width on top.
        let err = crate::query::proximity::support::dot_error(n, posed.scale);
        let level_a = -s.na.value + err + s.covered + margin;
        let level_b = s.nb.value - err - s.covered - margin;
        let far = best + err_p;
        let floor = s.floor.max(0.0);
        let reach = if s.floor > 0.0 && far > floor {
            (far * far - floor * floor).sqrt() * (1.0 + 4.0 * f64::EPSILON)
        } else {
            far
        } + margin;
        let mut lat = Lateral {
            n,
            level_a,
            level_b,
            reach,
            margin,
            disk_a: (DVec3::ZERO, 0.0),
            disk_b: (DVec3::ZERO, 0.0),
        };
        lat.disk_a = lat.cap_disk(&pair.a, |v| posed.a(v), &cs.set_a, Side::A, ls);
        lat.disk_b = lat.cap_disk(&pair.b, |w| posed.b(w), &cs.set_b, Side::B, ls);
        lat
    }

    /// A bound that keeps everything.
    fn everywhere(n: DVec3) -> Lateral {
        Lateral {
            n,
            level_a: f64::INFINITY,
            level_b: f64::NEG_INFINITY,
            reach: f64::INFINITY,
            margin: 0.0,
            disk_a: ANY,
            disk_b: ANY,
        }
    }

    /// `n · x` inside the side's cap.
    #[inline]
    fn in_cap(&self, side: Side, x: DVec3) -> bool {
        match side {
            Side::A => self.n.dot(x) <= self.level_a,
            Side::B => self.n.dot(x) >= self.level_b,
        }
    }

    /// The point where the segment `p → q` (`p` in the cap, `q` not)
    /// leaves the side's cap.
    #[inline]
    fn cut(&self, side: Side, p: DVec3, q: DVec3) -> DVec3 {
        let level = match side {
            Side::A => self.level_a,
            Side::B => self.level_b,
        };
        let (hp, hq) = (self.n.dot(p), self.n.dot(q));
        let t = ((level - hp) / (hq - hp)).clamp(0.0, 1.0);
        p + t * (q - p)
    }

    /// `x` projected along `n`.
    #[inline]
    fn project(&self, x: DVec3) -> DVec3 {
        x - self.n.dot(x) * self.n
    }

    /// A circle holding the projection of the side's whole cap: its
    /// vertices (in the near-extreme set) and the points where the edges
    /// from them leave it.
    fn cap_disk(
        &self,
        poly: &crate::polytope::Polytope,
        at: impl Fn(u32) -> DVec3,
        set: &[u32],
        side: Side,
        ls: &mut LocalScratch,
    ) -> (DVec3, f64) {
        ls.points.clear();
        for &v in set {
            let p = at(v);
            if !self.in_cap(side, p) {
                continue;
            }
            ls.points.push(self.project(p));
            for r in poly.ring(v as usize) {
                let q = at(r.neighbor);
                if !self.in_cap(side, q) {
                    ls.points.push(self.project(self.cut(side, p, q)));
                }
            }
        }
        if ls.points.is_empty() {
            return (DVec3::ZERO, f64::INFINITY);
        }
        let c = ls.points.iter().fold(DVec3::ZERO, |s, &x| s + x) / ls.points.len() as f64;
        let r = ls
            .points
            .iter()
            .map(|&x| (x - c).length())
            .fold(0.0, f64::max);
        (c, r * (1.0 + 8.0 * f64::EPSILON) + self.margin)
    }

    /// Whether two projected circles come within the lateral reach.
    #[inline]
    fn near(&self, x: (DVec3, f64), y: (DVec3, f64)) -> bool {
        (x.0 - y.0).length() <= x.1 + y.1 + self.reach
    }
}

/// The separation's shortcut (module docs, "one facet"): when GJK's final
/// simplex is a triangle whose three points label one facet `F` of the
/// overlay (three vertices of one face of A against one vertex of B, or the
/// reverse, or two edges), `F` is confirmed on the overlay with its exact
/// predicate, and the lens of the points of `D'` that could measure at most
/// `best` (those with `n · x ≥ floor` and `|x| ≤ best` plus rounding lie
/// within `r = √((best + err)² − floor²)` of the axis through the origin
/// along `n`) lies inside `F`'s projection with room `r` to its boundary,
/// then no other facet has a point in the lens (facets of a convex
/// polytope meet only along their boundaries), so `F` alone decides the
/// separation. Puts `F` into `facets` and returns `true`; else `false`.
pub(in crate::query) fn single_facet(
    pair: &ConvexPair,
    posed: &Posed,
    g: &Gjk,
    n: DVec3,
    best: f64,
    floor: f64,
    facets: &mut FacetSet,
) -> bool {
    if g.simplex.len != 3 {
        return false;
    }
    let pts = &g.simplex.pts[..3];
    let (a, b) = (&pair.a, &pair.b);
    let mut av = [pts[0].a, pts[1].a, pts[2].a];
    let mut bv = [pts[0].b, pts[1].b, pts[2].b];
    av.sort_unstable();
    bv.sort_unstable();
    let distinct = |v: &[u32; 3]| 1 + usize::from(v[1] != v[0]) + usize::from(v[2] != v[1]);
    let (vp, vq) = (posed.view_a(pair), posed.view_neg_b(pair));
    let prep = &pair.prep_b;
    let face_with = |p: &crate::polytope::Polytope, v: &[u32; 3]| {
        p.ring(v[0] as usize)
            .iter()
            .map(|r| r.face)
            .find(|&f| v[1..].iter().all(|x| p.face(f as usize).contains(x)))
    };
    let edge_between = |p: &crate::polytope::Polytope, u: u32, w: u32| {
        p.ring(u as usize)
            .iter()
            .find(|r| r.neighbor == w)
            .map(|r| r.edge)
    };
    facets.clear();
    // The facet's corners in D' (for the lens test).
    let mut corners = [DVec3::ZERO; 64];
    let k;
    match (distinct(&av), distinct(&bv)) {
        (3, 1) => {
            let Some(f) = face_with(a, &av) else {
                return false;
            };
            let w = prep.neg_vertex[bv[0] as usize];
            if !vq.in_cell(w, &vp.normal(f)) {
                return false;
            }
            let face = a.face(f as usize);
            if face.len() > corners.len() {
                return false;
            }
            let q = posed.b(bv[0]);
            for (c, &v) in corners.iter_mut().zip(face) {
                *c = posed.a(v) - q;
            }
            k = face.len();
            facets.fv.push((f, w));
        }
        (1, 3) => {
            let Some(gb) = face_with(b, &bv) else {
                return false;
            };
            let gq = prep.neg_face[gb as usize];
            if !vp.in_cell(av[0], &vq.normal(gq)) {
                return false;
            }
            let face = b.face(gb as usize);
            if face.len() > corners.len() {
                return false;
            }
            let p = posed.a(av[0]);
            for (c, &w) in corners.iter_mut().zip(face) {
                *c = p - posed.b(w);
            }
            k = face.len();
            facets.vf.push((gq, av[0]));
        }
        (2, 2) => {
            let (a0, a1) = (av[0], if av[1] != av[0] { av[1] } else { av[2] });
            let (b0, b1) = (bv[0], if bv[1] != bv[0] { bv[1] } else { bv[2] });
            let (Some(e), Some(eb)) = (edge_between(a, a0, a1), edge_between(b, b0, b1)) else {
                return false;
            };
            let e2 = prep.neg_edge[eb as usize];
            if !edges_cross(&vp, e, &vq, e2) {
                return false;
            }
            let (p0, p1, q0, q1) = (posed.a(a0), posed.a(a1), posed.b(b0), posed.b(b1));
            corners[..4].copy_from_slice(&[p0 - q0, p1 - q0, p1 - q1, p0 - q1]);
            k = 4;
            facets.ee.push((e, e2));
        }
        _ => return false,
    }
    // The lens: lateral reach, with the rounding of the posed points.
    let err_p = 4.0 * (posed.eta_a + posed.eta_b) + 32.0 * f64::EPSILON * posed.scale;
    let far = best + err_p;
    if !(floor > 0.0 && far > floor) {
        return false;
    }
    let margin = err_p + 64.0 * f64::EPSILON * posed.scale;
    let reach = (far * far - floor * floor).sqrt() * (1.0 + 4.0 * f64::EPSILON) + margin;
    // The origin's projection along n must lie inside the corners'
    // projected polygon (convex: one turning sense about n) with room
    // `reach` to every side.
    let project = |x: DVec3| x - n.dot(x) * n;
    let mut sense = 0.0f64;
    for i in 0..k {
        let (p, q) = (project(corners[i]), project(corners[(i + 1) % k]));
        let d = q - p;
        let len = d.length();
        if len.is_nan() || len <= 0.0 {
            return false;
        }
        // Signed distance of the origin from the side's line, positive to
        // the left about n.
        let side = d.cross(-p).dot(n) / len;
        if sense == 0.0 {
            sense = side.signum();
        }
        if side * sense <= reach {
            return false;
        }
    }
    true
}

/// The slab width that covers every facet which could measure at most
/// `best` (module docs).
pub(in crate::query) fn slab_width(posed: &Posed, best: f64, floor: f64) -> f64 {
    (best - floor).max(0.0) * (1.0 + 4.0 * f64::EPSILON)
        + 4.0 * (posed.eta_a + posed.eta_b)
        + 32.0 * f64::EPSILON * posed.scale
        + 1e-300
}

/// A circle in the projection of the separation's lateral bound: centre
/// and radius.
type Circle = (DVec3, f64);

/// Which features a facet search keeps (beyond touching the near-extreme
/// sets): A's faces, B's faces, A's edges, B's edges (by their own
/// indices; an edge kept comes with a circle for the pair test), and pairs
/// of kept edges (by their circles) before their arcs are tested.
struct Keep<FA, FB, EA, EB, P> {
    face_a: FA,
    face_b: FB,
    edge_a: EA,
    edge_b: EB,
    pair: P,
    /// Edges need both ends in the sets (else one).
    both: bool,
}

/// Pushes onto `ls.facets` the overlay facets whose features touch the
/// near-extreme sets `cs.set_a` (of A) and `cs.set_b` (of B) and pass
/// `keep`: fv-facets of A's faces at a vertex of the set, with their vertex
/// of `−B` located; vf-facets of B's faces likewise; and ee-facets of the
/// edges with both ends in the sets (`keep.both`) or one, tested for
/// crossing arcs.
fn collect<FA, FB, EA, EB, P>(
    pair: &ConvexPair,
    posed: &Posed,
    cs: &mut CertScratch,
    ls: &mut LocalScratch,
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
    let prep = &pair.prep_b;
    ls.in_a.start(a.vertex_count());
    ls.in_b.start(b.vertex_count());
    for &v in &cs.set_a {
        ls.in_a.mark(v);
    }
    for &w in &cs.set_b {
        ls.in_b.mark(w);
    }
    // fv: A's faces at the set, with the vertex of −B their normal lies
    // in. That vertex (B's support opposite the normal) must be in B's set
    // for the facet to matter (fact 2, and the slab), so only a face whose
    // normal may lie in the cell of a vertex of B's set is located, from
    // there, and kept if the vertex found is in the set.
    let (caps_a, caps_b) = (&pair.prep_a.caps, &pair.prep_b.caps);
    let (rot_a, rot_b) = (posed.pose_a.rotation, posed.pose_b.rotation);
    ls.faces_a.start(a.face_count());
    for &v in &cs.set_a {
        for r in a.ring(v as usize) {
            if !ls.faces_a.mark(r.face) || !(keep.face_a)(r.face) {
                continue;
            }
            let n = posed.na(r.face);
            let Some(&w) = cs.set_b.iter().find(|&&w| {
                let (c, cos) = caps_b.cells[w as usize];
                in_cap(n, (-rot_b.apply(c), cos))
            }) else {
                continue;
            };
            let (wq, _) = vq.locate(&vp.normal(r.face), prep.neg_vertex[w as usize]);
            if ls.in_b.is_marked(pair.neg_b().vertex_map[wq as usize]) {
                ls.facets.fv.push((r.face, wq));
            }
        }
    }
    // vf: B's faces at the set, as faces of −B, with the vertex of A (which
    // must be in A's set likewise).
    ls.faces_b.start(b.face_count());
    for &w in &cs.set_b {
        for r in b.ring(w as usize) {
            if !ls.faces_b.mark(r.face) || !(keep.face_b)(r.face) {
                continue;
            }
            let n = -posed.nb(r.face);
            let Some(&u) = cs.set_a.iter().find(|&&u| {
                let (c, cos) = caps_a.cells[u as usize];
                in_cap(n, (rot_a.apply(c), cos))
            }) else {
                continue;
            };
            let g = prep.neg_face[r.face as usize];
            let (ua, _) = vp.locate(&vq.normal(g), u);
            if ls.in_a.is_marked(ua) {
                ls.facets.vf.push((g, ua));
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
    ls.edges_a.clear();
    ls.edge_marks_a.start(a.edge_count());
    for &v in &cs.set_a {
        for r in a.ring(v as usize) {
            if ls.edge_marks_a.mark(r.edge) && touches(&ls.in_a, a.edge(r.edge as usize).vertices) {
                if let Some(c) = (keep.edge_a)(r.edge) {
                    let (ac, cos) = caps_a.arcs[r.edge as usize];
                    ls.edges_a.push((r.edge, c, (rot_a.apply(ac), cos)));
                }
            }
        }
    }
    ls.edges_b.clear();
    ls.edge_marks_b.start(b.edge_count());
    for &w in &cs.set_b {
        for r in b.ring(w as usize) {
            if ls.edge_marks_b.mark(r.edge) && touches(&ls.in_b, b.edge(r.edge as usize).vertices) {
                if let Some(c) = (keep.edge_b)(r.edge) {
                    let (ac, cos) = caps_b.arcs[r.edge as usize];
                    ls.edges_b
                        .push((prep.neg_edge[r.edge as usize], c, (-rot_b.apply(ac), cos)));
                }
            }
        }
    }
    for &(e, ca, arc_a) in &ls.edges_a {
        for &(e2, cb, arc_b) in &ls.edges_b {
            if caps_meet(arc_a, arc_b) && (keep.pair)(ca, cb) && edges_cross(&vp, e, &vq, e2) {
                ls.facets.ee.push((e, e2));
            }
        }
    }
}

/// A circle that excludes nothing (the penetration's searches have no
/// lateral bound).
const ANY: Circle = (DVec3::ZERO, f64::INFINITY);

/// Whether the Gaussian arc between the unit normals `p` and `q` (shorter
/// than π) comes within the cap `{x : x · m ≥ cos}`: the largest `x · m`
/// over the arc is at an end, or, where `m`'s projection on the arc's great
/// circle falls inside the arc, `√(1 − (m · g)²)` for the circle's unit
/// normal `g`; taken over the whole circle when the inside test is close,
/// so the answer errs towards keeping.
fn arc_meets_cap(p: DVec3, q: DVec3, m: DVec3, cos: f64) -> bool {
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
