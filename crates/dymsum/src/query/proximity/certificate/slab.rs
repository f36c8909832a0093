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
//!
//! # One facet, two facets
//! Before the slab's search, two shortcuts settle most separations of a
//! tracker's frames from GJK's final simplex alone. Every point of `D'`
//! that could measure at most `best` lies in the *lens* `n · x ≥ floor`,
//! `|x| ≤ best` (plus rounding), within `reach` of the axis along `n`
//! ([`lens_reach`]). **One facet** ([`single_facet`]): a triangle simplex
//! labels a facet `F`, confirmed on the overlay exactly, whose projection
//! holds the lens with room `reach` to each side. **Two facets**
//! ([`two_facets`]): a segment simplex from a vertex of one body to an
//! edge of the other labels an edge `S` of `D'`; the two facets at the
//! ends of its Gaussian arc, found exactly, lie on opposite sides of `S`
//! in the projection and hold the lens with room to every side but `S`.
//! Either way every point of `D'` in the lens lies in the facets found,
//! and since facets of a convex polytope meet only along their
//! boundaries (inside the lens, only interior points of `S`, in no third
//! facet), no other facet can measure at most `best`. The bound `best` is
//! GJK's `|v|` widened by `2^-30` of itself: the facets' measured distance
//! comes out within an ulp or two of `|v|`, on either side, and any bound
//! serves once the answer is checked to measure at most it.

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

/// The separation's first shortcut (module docs, "One facet, two facets"): when GJK's final
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
    let face_with = |p: &crate::polytope::Polytope, v: &[u32; 3]| {
        p.ring(v[0] as usize)
            .iter()
            .map(|r| r.face)
            .find(|&f| v[1..].iter().all(|x| p.face(f as usize).contains(x)))
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
            let w = bv[0];
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
            let gq = gb;
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
            let e2 = eb;
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
    let Some(reach) = lens_reach(posed, best, floor) else {
        return false;
    };
    // The origin's projection along n must lie inside the corners'
    // projected polygon (convex: one turning sense about n) with room
    // `reach` to every side.
    let project = |x: DVec3| x - n.dot(x) * n;
    let mut sense = 0.0f64;
    for i in 0..k {
        let (p, q) = (project(corners[i]), project(corners[(i + 1) % k]));
        let Some(side) = origin_from_side(p, q, n) else {
            return false;
        };
        if sense == 0.0 {
            sense = side.signum();
        }
        if side * sense <= reach {
            return false;
        }
    }
    true
}

/// The signed distance of the origin from the line through the projected
/// corners `p` and `q` (projections along the unit `n`), positive to the
/// left of `p → q` about `n`; `None` when they coincide.
fn origin_from_side(p: DVec3, q: DVec3, n: DVec3) -> Option<f64> {
    let d = q - p;
    let len = d.length();
    (len > 0.0).then(|| d.cross(-p).dot(n) / len)
}

/// The lens's lateral reach ([`single_facet`]): every point of `D'` with
/// `n · x ≥ floor` whose distance could measure at most `best` lies within
/// it of the axis along `n`, with the rounding of the posed points and of
/// the projections; `None` when `floor` does not certify a separation.
fn lens_reach(posed: &Posed, best: f64, floor: f64) -> Option<f64> {
    let err_p = 4.0 * (posed.eta_a + posed.eta_b) + 32.0 * f64::EPSILON * posed.scale;
    let far = best + err_p;
    if !(floor > 0.0 && far > floor) {
        return None;
    }
    let margin = err_p + 64.0 * f64::EPSILON * posed.scale;
    Some((far * far - floor * floor).sqrt() * (1.0 + 4.0 * f64::EPSILON) + margin)
}

/// The edge of `p` from vertex `u` to vertex `w`, if they are adjacent.
fn edge_between(p: &crate::polytope::Polytope, u: u32, w: u32) -> Option<u32> {
    p.ring(u as usize)
        .iter()
        .find(|r| r.neighbor == w)
        .map(|r| r.edge)
}

/// The most corners a facet of the two-facet shortcut may have.
const MAX_CORNERS: usize = 64;

/// A facet's corners as labels: (vertex of A, vertex of B), the corner
/// being `A'[a] − B'[b]`.
type Corners = ([(u32, u32); MAX_CORNERS], usize);

/// The separation's second shortcut (module docs, "One facet, two facets"): when
/// GJK's final simplex is a segment from one vertex of one body to an
/// edge of the other, the nearest point lies on that edge `S` of `D'` (if
/// it is one), between the two facets at the ends of its Gaussian arc:
/// for a vertex `a` of A and an edge `e` of B, the arc of `−e` inside `a`'s
/// cell ends at a face of `−B` inside the cell (a vf-facet) or where it
/// leaves the cell across an arc of A at `a` (an ee-facet); likewise with
/// the bodies' roles swapped. Both are found with the overlay's exact
/// predicates, and exactly two must be. When the lens of the one-facet
/// shortcut lies, in the projection along `n`, on the inner side of every
/// side of both facets other than `S`, with room `reach`, and the two
/// facets lie on opposite sides of `S` (so their projections cover the
/// lens), every point of `D'` in the lens lies in one of them, and any
/// other facet meets them only on their boundaries, which inside the lens
/// are interior points of `S`, in no third facet. So the two facets
/// alone decide the separation. Puts them into `facets` and returns
/// `true`; else `false`.
pub(in crate::query) fn two_facets(
    pair: &ConvexPair,
    posed: &Posed,
    g: &Gjk,
    n: DVec3,
    best: f64,
    floor: f64,
    facets: &mut FacetSet,
) -> bool {
    if g.simplex.len != 2 {
        return false;
    }
    let Some(reach) = lens_reach(posed, best, floor) else {
        return false;
    };
    let (p0, p1) = (g.simplex.pts[0], g.simplex.pts[1]);
    let (a, b) = (&pair.a, &pair.b);
    let (vp, vq) = (posed.view_a(pair), posed.view_neg_b(pair));
    facets.clear();
    let mut polys: [Corners; 2] = [([(0, 0); MAX_CORNERS], 0); 2];
    let mut found = 0;
    let mut add = |labels: &mut dyn Iterator<Item = (u32, u32)>| {
        if found == 2 {
            return false;
        }
        let (c, k) = &mut polys[found];
        *k = 0;
        for l in labels {
            if *k == MAX_CORNERS {
                return false;
            }
            c[*k] = l;
            *k += 1;
        }
        found += 1;
        true
    };
    let shared;
    if p0.a == p1.a && p0.b != p1.b {
        // A vertex of A against an edge of B.
        let (v, b0, b1) = (p0.a, p0.b, p1.b);
        let Some(e) = edge_between(b, b0, b1) else {
            return false;
        };
        let e2 = e;
        shared = [(v, b0), (v, b1)];
        for gf in b.edge(e as usize).faces {
            let gq = gf;
            if vp.in_cell(v, &vq.normal(gq)) {
                facets.vf.push((gq, v));
                if !add(&mut b.face(gf as usize).iter().map(|&w| (v, w))) {
                    return false;
                }
            }
        }
        for r in a.ring(v as usize) {
            if edges_cross(&vp, r.edge, &vq, e2) {
                facets.ee.push((r.edge, e2));
                let u = r.neighbor;
                if !add(&mut [(v, b0), (u, b0), (u, b1), (v, b1)].into_iter()) {
                    return false;
                }
            }
        }
    } else if p0.b == p1.b && p0.a != p1.a {
        // An edge of A against a vertex of B.
        let (w, a0, a1) = (p0.b, p0.a, p1.a);
        let Some(e) = edge_between(a, a0, a1) else {
            return false;
        };
        let wq = w;
        shared = [(a0, w), (a1, w)];
        for f in a.edge(e as usize).faces {
            if vq.in_cell(wq, &vp.normal(f)) {
                facets.fv.push((f, wq));
                if !add(&mut a.face(f as usize).iter().map(|&u| (u, w))) {
                    return false;
                }
            }
        }
        for r in b.ring(w as usize) {
            let e2 = r.edge;
            if edges_cross(&vp, e, &vq, e2) {
                facets.ee.push((e, e2));
                let x = r.neighbor;
                if !add(&mut [(a0, w), (a1, w), (a1, x), (a0, x)].into_iter()) {
                    return false;
                }
            }
        }
    } else {
        return false;
    }
    if found != 2 {
        return false;
    }
    // Each facet: the side of its interior off S (relative to S directed
    // from shared[0] to shared[1]), after checking the room to its other
    // sides.
    let project = |x: DVec3| x - n.dot(x) * n;
    let at = |(u, w): (u32, u32)| project(posed.a(u) - posed.b(w));
    let mut off_s = [0.0f64; 2];
    for (k, (labels, len)) in polys.iter().enumerate() {
        let labels = &labels[..*len];
        let m = labels.len();
        let mut corners = [DVec3::ZERO; MAX_CORNERS];
        for (c, &l) in corners.iter_mut().zip(labels) {
            *c = at(l);
        }
        // The polygon's turning sense about n (twice its signed area).
        let mut area = 0.0;
        for i in 0..m {
            area += corners[i].cross(corners[(i + 1) % m]).dot(n);
        }
        let sense = area.signum();
        if area.is_nan() || area == 0.0 {
            return false;
        }
        let mut s_dir = 0.0;
        for i in 0..m {
            let (l0, l1) = (labels[i], labels[(i + 1) % m]);
            if (l0, l1) == (shared[0], shared[1]) {
                s_dir = 1.0;
                continue;
            }
            if (l0, l1) == (shared[1], shared[0]) {
                s_dir = -1.0;
                continue;
            }
            // Positive on the polygon's inner side.
            let Some(side) = origin_from_side(corners[i], corners[(i + 1) % m], n) else {
                return false;
            };
            if side * sense <= reach {
                return false;
            }
        }
        if s_dir == 0.0 {
            return false; // S is not a side of this facet
        }
        off_s[k] = sense * s_dir;
    }
    let both = off_s[0] == -off_s[1];
    #[cfg(test)]
    if both {
        tests::TWO_FACETS.with(|c| c.set(c.get() + 1));
    }
    both
}

/// The slab width that covers every facet which could measure at most
/// `best` (module docs).
pub(in crate::query) fn slab_width(posed: &Posed, best: f64, floor: f64) -> f64 {
    (best - floor).max(0.0) * (1.0 + 4.0 * f64::EPSILON)
        + 4.0 * (posed.eta_a + posed.eta_b)
        + 32.0 * f64::EPSILON * posed.scale
        + 1e-300
}

#[cfg(test)]
mod tests {
    use crate::kernel::rotation::{Pose, Rotation};
    use crate::polytope::Polytope;
    use crate::query::test_support::{boxed, Lcg};
    use crate::query::ConvexPair;
    use glam::DVec3;

    /// Two boxes, a pyramid over a regular `n`-gon (height 2) and a hull
    /// of `m` random unit vectors.
    fn shapes(r: &mut Lcg, n: usize, m: usize) -> [Polytope; 4] {
        let mut pyramid: Vec<DVec3> = (0..n)
            .map(|i| {
                let t = i as f64 / n as f64 * std::f64::consts::TAU;
                DVec3::new(t.cos(), t.sin(), 0.0)
            })
            .collect();
        pyramid.push(DVec3::new(0.0, 0.0, 2.0));
        let hull: Vec<DVec3> = (0..m).map(|_| r.unit()).collect();
        [
            boxed(0.5, 0.5, 0.5),
            boxed(1.0, 0.25, 0.5),
            Polytope::from_dvec3s(&pyramid).unwrap(),
            Polytope::from_dvec3s(&hull).unwrap(),
        ]
    }

    /// The `k`-th orientation of the tests: every third an exact quarter
    /// turn about z (parallel faces with the boxes), the others random.
    fn turn(k: usize, r: &mut Lcg) -> Rotation {
        if k % 3 == 0 {
            Rotation::from_axis_angle(DVec3::Z, std::f64::consts::FRAC_PI_2 * k as f64)
        } else {
            Rotation::from_axis_angle(r.unit(), 3.0 * r.next())
        }
        .unwrap()
    }

    std::thread_local! {
        /// How often [`super::two_facets`] settled a separation.
        pub(super) static TWO_FACETS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
    }

    /// Separations whose nearest points are a vertex of one body and an
    /// edge of the other (boxes at random poses and at quarter turns on a
    /// grid, a pyramid over a 40-gon, a random hull): the two-facet shortcut
    /// settles many of them, and every answer (in a test build) is
    /// compared with evaluating every facet (`evaluate::evaluate`).
    #[test]
    fn the_two_facet_shortcut_equals_evaluating_every_facet() {
        let mut r = Lcg(23);
        let shapes = shapes(&mut r, 40, 30);
        TWO_FACETS.with(|c| c.set(0));
        let mut queries = 0;
        for a in &shapes {
            for b in &shapes {
                let pair = ConvexPair::new(a, b).unwrap();
                for k in 0..60 {
                    let rot = turn(k, &mut r);
                    // At quarter turns, offsets on a half-unit grid: the
                    // nearest points often a corner of D', where a third
                    // facet ties with the two.
                    let offset = if k % 3 == 0 {
                        let grid = |r: &mut Lcg| (r.next() * 6.0).round() * 0.5;
                        DVec3::new(2.0 + grid(&mut r).abs(), grid(&mut r), grid(&mut r))
                    } else {
                        r.unit() * (3.5 + r.next().abs())
                    };
                    pair.query(
                        Pose::new(rot, DVec3::ZERO),
                        Pose::new(Rotation::IDENTITY, offset),
                    )
                    .unwrap();
                    queries += 1;
                }
            }
        }
        let used = TWO_FACETS.with(|c| c.get());
        assert!(used * 20 >= queries, "{used} of {queries} queries");
    }

    /// The shortcut's checks against adversarial simplices: every segment
    /// from a vertex of one body to an edge of the other is offered as
    /// GJK's final simplex, with the true direction and floor. Whenever
    /// the shortcut accepts one and its facets measure at most the bound
    /// (what `evaluate` asks before answering), they give exactly the
    /// answer of evaluating every facet.
    #[test]
    fn the_two_facet_shortcut_accepts_only_what_it_proves() {
        use crate::query::proximity::evaluate::{evaluate, to_world, Facets};
        use crate::query::proximity::from_facets::evaluate_in_frame;
        use crate::query::proximity::gjk::{Gjk, Point, Simplex};
        use crate::query::proximity::scratch::Scratch;
        use crate::query::Proximity;
        let mut r = Lcg(29);
        let shapes = shapes(&mut r, 12, 12);
        let (mut accepted, mut offered) = (0, 0);
        for a in &shapes {
            for b in &shapes {
                let pair = ConvexPair::new(a, b).unwrap();
                for k in 0..12 {
                    let rot = turn(k, &mut r);
                    let (pa, pb) = (
                        Pose::new(rot, DVec3::ZERO),
                        Pose::new(Rotation::IDENTITY, r.unit() * (3.5 + r.next().abs())),
                    );
                    let mut fresh = Scratch::default();
                    let want = evaluate(&pair, pa, pb, Facets::Exhaustive, &mut fresh).unwrap();
                    let Proximity::Separated(sep) = want else {
                        continue;
                    };
                    let mut scratch = Scratch::default();
                    scratch.posed.reset(&pair, pa, pb).unwrap();
                    let posed = &scratch.posed;
                    let n = -sep.direction;
                    let len = crate::kernel::exact::mul_pow2(sep.distance, posed.k);
                    let width = super::slab_width(posed, len, len * (1.0 - 2f64.powi(-20)));
                    let s = super::slab(&pair, posed, n, width, (0, 0), &mut scratch.cert);
                    assert!(s.floor > 0.0);
                    let best = len * (1.0 + 2f64.powi(-30));
                    let point = |u: u32, w: u32| Point {
                        w: posed.a(u) - posed.b(w),
                        a: u,
                        b: w,
                    };
                    let mut segments = Vec::new();
                    for u in 0..a.vertex_count() as u32 {
                        for e in 0..b.edge_count() {
                            let [w0, w1] = b.edge(e).vertices;
                            segments.push([point(u, w0), point(u, w1)]);
                        }
                    }
                    for w in 0..b.vertex_count() as u32 {
                        for e in 0..a.edge_count() {
                            let [u0, u1] = a.edge(e).vertices;
                            segments.push([point(u0, w), point(u1, w)]);
                        }
                    }
                    for seg in segments {
                        let mut pts = [Point::default(); 4];
                        pts[..2].copy_from_slice(&seg);
                        let g = Gjk {
                            simplex: Simplex { pts, len: 2 },
                            v: n * len,
                            enclosed: false,
                            separating: false,
                            warm: (0, 0),
                        };
                        offered += 1;
                        let facets = &mut scratch.local.facets;
                        if !super::two_facets(&pair, posed, &g, n, best, s.floor, facets) {
                            continue;
                        }
                        let (got, measured) = evaluate_in_frame(
                            &pair,
                            posed,
                            facets,
                            false,
                            &mut scratch.cands,
                            (&mut scratch.poly, &mut scratch.bounds),
                        );
                        let Proximity::Separated(got_sep) = got else {
                            panic!("two facets of a separation measured an overlap");
                        };
                        if measured.is_nan() || got_sep.distance > best {
                            continue;
                        }
                        accepted += 1;
                        assert_eq!(to_world(posed, got).unwrap(), want, "{seg:?}");
                    }
                }
            }
        }
        assert!(
            accepted >= 20,
            "{accepted} of {offered} offered segments accepted"
        );
    }
}
