//! The separation certificate: a slab around GJK's direction.
//!
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

use super::{collect, Circle, Keep, LocalScratch, ANY};
use crate::gauss::edges_cross;
use crate::kernel::exact::mul_pow2_vec;
use crate::kernel::rotation::Pose;
use crate::query::frame::Posed;
use crate::query::pair::ConvexPair;
use crate::query::proximity::certificate::candidates::FacetSet;
use crate::query::proximity::gjk::{near_max_pair, CertScratch, Gjk};
use crate::query::proximity::support::NearMax;
use glam::DVec3;
/// The near-extreme sets of A in `−n` and of B in `n` (in `cert.set_a`,
/// `cert.set_b`), each covering at least `tau`, with the rigorous lower bound
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
    cert: &mut CertScratch,
) -> SeparatingSlab {
    let (na, nb) = near_max_pair(pair, posed, (-n, tau), (n, tau), warm, cert);
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
/// most `best`, into `local.facets`.
pub(in crate::query) fn separation_facets(
    pair: &ConvexPair,
    posed: &Posed,
    s: &SeparatingSlab,
    best: f64,
    cert: &mut CertScratch,
    local: &mut LocalScratch,
) {
    local.facets.clear();
    // With one vertex in each set every facet found touches the closest
    // pair of vertices, so the lateral bound would keep them all: skip it.
    let lat = if cert.set_a.len() == 1 && cert.set_b.len() == 1 {
        Lateral::everywhere(s.n)
    } else {
        Lateral::new(pair, posed, s, best, cert, local)
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
        cert,
        local,
        Keep {
            face_a,
            face_b,
            edge_a,
            edge_b,
            pair: |x, y| lat.near(x, y),
            both: false,
        },
    );
    local.facets.dedup();
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
        cert: &CertScratch,
        local: &mut LocalScratch,
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
        lat.disk_a = lat.cap_disk(&pair.a, |v| posed.a(v), &cert.set_a, Side::A, local);
        lat.disk_b = lat.cap_disk(&pair.b, |w| posed.b(w), &cert.set_b, Side::B, local);
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
        local: &mut LocalScratch,
    ) -> (DVec3, f64) {
        local.points.clear();
        for &v in set {
            let p = at(v);
            if !self.in_cap(side, p) {
                continue;
            }
            local.points.push(self.project(p));
            for r in poly.ring(v as usize) {
                let q = at(r.neighbor);
                if !self.in_cap(side, q) {
                    local.points.push(self.project(self.cut(side, p, q)));
                }
            }
        }
        if local.points.is_empty() {
            return (DVec3::ZERO, f64::INFINITY);
        }
        let c = local.points.iter().fold(DVec3::ZERO, |s, &x| s + x) / local.points.len() as f64;
        let r = local
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
