//! GJK on the Minkowski difference `D' = A' ⊕ (−B')` of the rounded posed
//! bodies, with an exact certificate for its yes/no answer.
//!
//! # The iteration (floats)
//! Gilbert–Johnson–Keerthi with the signed-volume subalgorithm (Montanari,
//! Petrinic and Barbieri, ACM TOG 2017): a simplex of points `w = a − b` of
//! `D'` (each a vertex of A less a vertex of B, found by hill climbing from
//! the last support vertices, so a step costs O(1) under coherent motion)
//! and the point `v` of the simplex nearest the origin. It stops when the
//! simplex encloses the origin, when `v` no longer improves (`|v|² − v · w`
//! below `2^-44 |v|²`), when a support point repeats, or after
//! [`MAX_ITERATIONS`] steps; in a yes/no query also as soon as a support
//! plane separates (`v · w > 0`).
//!
//! # The certificate (exact)
//! Floats only propose; the answer is decided exactly on `D'`, whose points
//! `a' − b'` are held exactly (as differences of floats):
//! * **apart**: a direction `d` (GJK's `v`) with `min_A' d · a > max_B' d · b`.
//!   Both extremes come from the near-extreme searches of
//!   [`crate::query::proximity::support::near_max`], which bound them rigorously; when the
//!   float bounds cannot separate them, the exact values of the vertices in
//!   the two near-extreme sets (which contain the rounded extremes) are
//!   compared exactly.
//! * **overlapping or touching**: the origin lies in the closed convex hull
//!   of GJK's final simplex, decided exactly ([`origin_in_hull`]: signs of
//!   3×3 determinants of the exact points, and for a flat simplex of the
//!   lower-dimensional tests), so touching (the origin on the boundary of
//!   `D'`) is decided without a tolerance.
//! * **apart, near contact**: GJK's direction is then the difference of
//!   two nearly equal points, too coarse to show the separation, so the
//!   face normals and edge cross products of the features around its
//!   simplex are tried ([`separating_feature_axis`]): the three nearest
//!   GJK's direction, then the three that leave the widest gap between
//!   the simplex's neighbouring vertices, then the three face normals one
//!   edge further that do; each is decided exactly as above, so the
//!   choice needs no error bound.
//! * **overlapping by less than rounding**: two fan triangles, of faces
//!   of A and of B around the simplex's vertices (then one edge further),
//!   that meet exactly ([`local_faces_meet`]); each lies in its posed
//!   body's hull, so a common point is one of the two hulls.
//!
//! When neither certificate holds (the origin within rounding of the
//! boundary, where float directions cannot exhibit a separation), the
//! answer comes from the exhaustive exact method: the exact hull of all
//! `a' − b'` and the exact side of the origin for each of its faces
//! ([`origin_in_difference_hull`]); [`crate::query::pair::QueryStats`] counts how often.

use crate::hull::{convex_hull, PairwiseSums};
use crate::kernel::exact::{self, Dyadic, ExactVec};
use crate::kernel::separation::triangles_apart;
use crate::kernel::Sign;
use crate::polytope::Polytope;
use crate::query::frame::Posed;
use crate::query::pair::ConvexPair;
use crate::query::proximity::support::{climb_unposed, near_max, Marks, NearMax, NearestAxes};
use crate::solid::intersect::triangles_meet;
use glam::DVec3;

/// The most GJK steps before it stops with what it has (never reached in
/// the tests: on a polytope GJK ends in finitely many steps).
pub(in crate::query) const MAX_ITERATIONS: usize = 128;

/// A point of `D'`: `w = a − b` (frame units, rounded) for vertex `a` of A
/// and vertex `b` of B.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(in crate::query) struct Point {
    /// `a' − b'`, rounded.
    pub w: DVec3,
    /// Vertex of A.
    pub a: u32,
    /// Vertex of B.
    pub b: u32,
}

/// GJK's simplex: up to four points of `D'`.
#[derive(Clone, Copy, Debug, Default)]
pub(in crate::query) struct Simplex {
    /// The points; the first `len` are used.
    pub pts: [Point; 4],
    /// How many.
    pub len: usize,
}

impl Simplex {
    fn push(&mut self, p: Point) {
        self.pts[self.len] = p;
        self.len += 1;
    }

    /// Adds a point without vertex labels (GJK on other convex sets).
    pub(in crate::query) fn push_point(&mut self, w: DVec3) {
        self.push(Point { w, a: 0, b: 0 });
    }

    fn has(&self, a: u32, b: u32) -> bool {
        self.pts[..self.len].iter().any(|p| p.a == a && p.b == b)
    }

    /// The points of `self` selected by `mask` (bit `i`: point `i`).
    fn keep(&self, mask: u8) -> Simplex {
        let mut s = Simplex::default();
        for i in 0..self.len {
            if mask >> i & 1 != 0 {
                s.push(self.pts[i]);
            }
        }
        s
    }
}

/// What GJK ended with.
#[derive(Clone, Copy, Debug)]
pub(in crate::query) struct Gjk {
    /// The final simplex.
    pub simplex: Simplex,
    /// Its point nearest the origin (frame units; zero when it encloses the
    /// origin).
    pub v: DVec3,
    /// The simplex is a tetrahedron that (in floats) encloses the origin.
    pub enclosed: bool,
    /// In a yes/no query: a support plane separated (in floats).
    pub separating: bool,
    /// The last support vertices of A and B (a warm start for the next
    /// query).
    pub warm: (u32, u32),
}

/// Runs GJK from the support vertices `warm`, the direction `dir` (towards
/// `D'` from the origin; any non-zero vector) and the vertex pairs of an
/// earlier simplex `prior` (a tracker's last frame: its points, posed
/// anew, are points of `D'`, and under coherent motion they enclose the
/// origin again, or nearly). With `yes_no`, it stops at the first
/// separating support plane.
pub(in crate::query) fn gjk(
    pair: &ConvexPair,
    posed: &Posed,
    warm: (u32, u32),
    dir: DVec3,
    prior: &Simplex,
    yes_no: bool,
) -> Gjk {
    let (a_body, b_body) = (&pair.a, &pair.b);
    let (at_a, at_b) = (|v| posed.a(v), |w| posed.b(w));
    let (mut wa, mut wb) = warm;
    let mut v = if dir.length_squared() > 0.0 && dir.is_finite() {
        dir
    } else {
        posed.a(wa) - posed.b(wb)
    };
    if v.length_squared() == 0.0 {
        v = DVec3::X;
    }
    let mut simplex = Simplex::default();
    let (na, nb) = (a_body.vertex_count() as u32, b_body.vertex_count() as u32);
    if prior.len > 0 && prior.pts[..prior.len].iter().all(|p| p.a < na && p.b < nb) {
        for p in &prior.pts[..prior.len] {
            simplex.push(Point {
                w: posed.a(p.a) - posed.b(p.b),
                ..*p
            });
        }
        let (next, nv) = closest(&simplex);
        if next.len == 4 {
            return Gjk {
                simplex: next,
                v: nv,
                enclosed: true,
                separating: false,
                warm: (wa, wb),
            };
        }
        simplex = next;
        if nv.length_squared() > 0.0 {
            v = nv;
        } else {
            simplex = Simplex::default();
        }
    }
    if simplex.len == 0 {
        // A fresh search: start each climb from the better of the last
        // query's support vertex and the seed nearest its direction (the
        // last query may have been at an unrelated pose).
        let da = posed.pose_a.rotation.matrix().transpose() * -v;
        let db = posed.pose_b.rotation.matrix().transpose() * v;
        wa = better_start(at_a, -v, wa, pair.prep_a.seed(da));
        wb = better_start(at_b, v, wb, pair.prep_b.seed(db));
    }
    let mut enclosed = false;
    let mut separating = false;
    let to_a = posed.pose_a.rotation.matrix().transpose();
    let to_b = posed.pose_b.rotation.matrix().transpose();
    for _ in 0..MAX_ITERATIONS {
        let a = climb_unposed(a_body, &to_a, -v, wa);
        let b = climb_unposed(b_body, &to_b, v, wb);
        (wa, wb) = (a, b);
        let w = posed.a(a) - posed.b(b);
        let vw = v.dot(w);
        if yes_no && vw > 0.0 {
            separating = true;
            break;
        }
        let vv = v.dot(v);
        if simplex.len > 0 && (simplex.has(a, b) || vv - vw <= vv * 2f64.powi(-44)) {
            break;
        }
        let before = simplex;
        simplex.push(Point { w, a, b });
        let (next, nv) = closest(&simplex);
        if before.len > 0 && next.len < 4 && nv.length_squared() >= vv {
            // No progress (rounding in the subalgorithm): keep the best.
            simplex = before;
            break;
        }
        simplex = next;
        v = nv;
        if simplex.len == 4 {
            enclosed = true;
            break;
        }
        let scale = simplex.pts[..simplex.len]
            .iter()
            .map(|p| p.w.length_squared())
            .fold(0.0, f64::max);
        if v.length_squared() <= scale * 2f64.powi(-100) {
            break;
        }
    }
    Gjk {
        simplex,
        v,
        enclosed,
        separating,
        warm: (wa, wb),
    }
}

#[inline]
fn same_sign(a: f64, b: f64) -> bool {
    (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0)
}

/// The sub-simplex of `s` whose hull holds the point of `hull(s)` nearest
/// the origin, and that point (signed volumes).
pub(in crate::query) fn closest(s: &Simplex) -> (Simplex, DVec3) {
    let (mask, lambda) = match s.len {
        1 => (1, [1.0, 0.0, 0.0, 0.0]),
        2 => segment([s.pts[0].w, s.pts[1].w]),
        3 => triangle([s.pts[0].w, s.pts[1].w, s.pts[2].w]),
        _ => tetrahedron([s.pts[0].w, s.pts[1].w, s.pts[2].w, s.pts[3].w]),
    };
    let v = (0..s.len)
        .filter(|&i| mask >> i & 1 != 0)
        .fold(DVec3::ZERO, |v, i| v + lambda[i] * s.pts[i].w);
    (s.keep(mask), v)
}

/// Nearest point of a segment: mask and barycentric weights.
fn segment(s: [DVec3; 2]) -> (u8, [f64; 4]) {
    let t = s[1] - s[0];
    let l2 = t.length_squared();
    if l2 == 0.0 {
        return (0b01, [1.0, 0.0, 0.0, 0.0]);
    }
    let mu = -s[0].dot(t) / l2;
    if mu <= 0.0 {
        (0b01, [1.0, 0.0, 0.0, 0.0])
    } else if mu >= 1.0 {
        (0b10, [0.0, 1.0, 0.0, 0.0])
    } else {
        (0b11, [1.0 - mu, mu, 0.0, 0.0])
    }
}

/// Nearest point of a triangle: mask and barycentric weights.
fn triangle(s: [DVec3; 3]) -> (u8, [f64; 4]) {
    let n = (s[1] - s[0]).cross(s[2] - s[0]);
    let nn = n.length_squared();
    let mut best: Option<(f64, u8, [f64; 4])> = None;
    if nn > 0.0 {
        let p0 = n * (s[0].dot(n) / nn);
        let k = if n.x.abs() >= n.y.abs() && n.x.abs() >= n.z.abs() {
            0
        } else if n.y.abs() >= n.z.abs() {
            1
        } else {
            2
        };
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let area = |a: DVec3, b: DVec3, c: DVec3| {
            (b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i])
        };
        let mu = area(s[0], s[1], s[2]);
        let c = [
            area(p0, s[1], s[2]),
            area(s[0], p0, s[2]),
            area(s[0], s[1], p0),
        ];
        if c.iter().all(|&x| same_sign(mu, x)) {
            return (0b111, [c[0] / mu, c[1] / mu, c[2] / mu, 0.0]);
        }
        for (drop, &cj) in c.iter().enumerate() {
            if !same_sign(mu, cj) {
                consider_face(&s, drop, &mut best);
            }
        }
    } else {
        for drop in 0..3 {
            consider_face(&s, drop, &mut best);
        }
    }
    let (_, mask, l) = best.expect("a triangle has edges");
    (mask, l)
}

/// Offers the segment of `s` without point `drop` as the nearest feature.
fn consider_face(s: &[DVec3; 3], drop: usize, best: &mut Option<(f64, u8, [f64; 4])>) {
    let idx: [usize; 2] = match drop {
        0 => [1, 2],
        1 => [0, 2],
        _ => [0, 1],
    };
    let (m, l) = segment([s[idx[0]], s[idx[1]]]);
    offer(&idx, m, l, |i| s[i], best);
}

/// Records a sub-simplex's nearest point if it is nearer than `best`.
fn offer(
    idx: &[usize],
    mask: u8,
    l: [f64; 4],
    at: impl Fn(usize) -> DVec3,
    best: &mut Option<(f64, u8, [f64; 4])>,
) {
    let (mut full, mut weights, mut v) = (0u8, [0.0; 4], DVec3::ZERO);
    for (k, &i) in idx.iter().enumerate() {
        if mask >> k & 1 != 0 {
            full |= 1 << i;
            weights[i] = l[k];
            v += l[k] * at(i);
        }
    }
    let d = v.length_squared();
    if best.is_none_or(|(bd, _, _)| d < bd) {
        *best = Some((d, full, weights));
    }
}

/// Nearest point of a tetrahedron: mask and barycentric weights.
fn tetrahedron(s: [DVec3; 4]) -> (u8, [f64; 4]) {
    let det = |a: DVec3, b: DVec3, c: DVec3| a.dot(b.cross(c));
    let c = [
        -det(s[1], s[2], s[3]),
        det(s[0], s[2], s[3]),
        -det(s[0], s[1], s[3]),
        det(s[0], s[1], s[2]),
    ];
    let m = c[0] + c[1] + c[2] + c[3];
    if c.iter().all(|&x| same_sign(m, x)) {
        return (0b1111, [c[0] / m, c[1] / m, c[2] / m, c[3] / m]);
    }
    let mut best: Option<(f64, u8, [f64; 4])> = None;
    for (drop, &cj) in c.iter().enumerate() {
        if same_sign(m, cj) {
            continue;
        }
        let idx: [usize; 3] = match drop {
            0 => [1, 2, 3],
            1 => [0, 2, 3],
            2 => [0, 1, 3],
            _ => [0, 1, 2],
        };
        let (mask, l) = triangle([s[idx[0]], s[idx[1]], s[idx[2]]]);
        offer(&idx, mask, l, |i| s[i], &mut best);
    }
    let (_, mask, l) = best.expect("a tetrahedron not enclosing the origin has a face towards it");
    (mask, l)
}

// ------------------------------------------------------------ certificates

/// The buffers of the certificates.
#[derive(Clone, Debug, Default)]
pub(in crate::query) struct CertScratch {
    pub marks_a: Marks,
    pub marks_b: Marks,
    pub set_a: Vec<u32>,
    pub set_b: Vec<u32>,
}

/// The exact answer to "do A' and B' meet?" that GJK's end certifies, or
/// `None` when neither certificate holds (module docs).
pub(in crate::query) fn certify(
    pair: &ConvexPair,
    posed: &Posed,
    g: &Gjk,
    cert: &mut CertScratch,
) -> Option<bool> {
    if encloses_origin(posed, g) {
        return Some(true);
    }
    if g.v.length_squared() > 0.0
        && (separated_along(pair, posed, g.v, g.warm, cert)
            || separating_feature_axis(pair, posed, g, cert).is_some())
    {
        return Some(false);
    }
    if local_faces_meet(pair, posed, g) {
        return Some(true);
    }
    None
}

/// The most faces around GJK's simplex whose triangles
/// [`local_faces_meet`] tries per body.
const LOCAL_FACES: usize = 64;

/// Exactly whether a triangle of A's faces near GJK's final simplex meets
/// a triangle of B's (each face fanned from its first corner, at the
/// posed, rounded vertices): an overlap certificate for bodies that meet
/// by less than rounding can show in GJK's simplex.
///
/// A fan triangle of posed vertices of A lies in the hull of A's posed
/// vertices, and likewise for B, so a common point of two such triangles
/// (decided by [`triangles_meet`], exact, after the box test and the
/// certified float filter [`triangles_apart`]) is a common point of the
/// two hulls: the bodies meet. `false` proves nothing. When the bodies
/// meet by very little and neither holds the other, their boundaries
/// cross next to the features GJK ends on: the faces around its simplex's
/// vertices are tried first, then those one edge further (on tessellated
/// cylinders bisected to 2⁻⁴⁰ of contact the first ring held a crossing
/// pair in nine of ten such states, the second in all).
fn local_faces_meet(pair: &ConvexPair, posed: &Posed, g: &Gjk) -> bool {
    let (mut fa, mut fb) = (LocalFaces::default(), LocalFaces::default());
    LocalFaces::around_simplex(pair, g, false, &mut fa, &mut fb);
    let (first_a, first_b) = (fa.n, fb.n);
    if faces_meet(pair, posed, &fa.faces[..first_a], &fb.faces[..first_b]) {
        return true;
    }
    LocalFaces::around_simplex(pair, g, true, &mut fa, &mut fb);
    // The pairs not tried yet: a new face of A with every face of B, and
    // a first-ring face of A with every new face of B.
    faces_meet(pair, posed, &fa.faces[first_a..fa.n], &fb.faces[..fb.n])
        || faces_meet(pair, posed, &fa.faces[..first_a], &fb.faces[first_b..fb.n])
}

/// Up to [`LOCAL_FACES`] distinct faces of one body.
struct LocalFaces {
    faces: [u32; LOCAL_FACES],
    n: usize,
}

impl Default for LocalFaces {
    fn default() -> Self {
        LocalFaces {
            faces: [0; LOCAL_FACES],
            n: 0,
        }
    }
}

impl LocalFaces {
    /// Adds to `fa` and `fb` the faces of A and of B around the vertices of
    /// GJK's final simplex, or, `further`, around their neighbours (one
    /// edge further).
    fn around_simplex(pair: &ConvexPair, g: &Gjk, further: bool, fa: &mut Self, fb: &mut Self) {
        for p in &g.simplex.pts[..g.simplex.len] {
            for (body, v, faces) in [(&pair.a, p.a, &mut *fa), (&pair.b, p.b, &mut *fb)] {
                if further {
                    for r in body.ring(v as usize) {
                        faces.ring(body, r.neighbor);
                    }
                } else {
                    faces.ring(body, v);
                }
            }
        }
    }

    /// Adds the faces around vertex `v` not held yet (while there is room).
    fn ring(&mut self, body: &Polytope, v: u32) {
        for r in body.ring(v as usize) {
            if self.n < LOCAL_FACES && !self.faces[..self.n].contains(&r.face) {
                self.faces[self.n] = r.face;
                self.n += 1;
            }
        }
    }
}

/// Exactly whether a fan triangle of one of A's faces `fa` meets one of
/// B's faces `fb` (at the posed vertices).
fn faces_meet(pair: &ConvexPair, posed: &Posed, fa: &[u32], fb: &[u32]) -> bool {
    let fan = |c: &[u32], k: usize, at: &dyn Fn(u32) -> DVec3| [at(c[0]), at(c[k]), at(c[k + 1])];
    let (at_a, at_b) = (|v| posed.a(v), |w| posed.b(w));
    let boxed = |t: &[DVec3; 3]| (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
    for &f in fa {
        let ca = pair.a.face(f as usize);
        for k in 1..ca.len() - 1 {
            let t = fan(ca, k, &at_a);
            let (tlo, thi) = boxed(&t);
            for &h in fb {
                let cb = pair.b.face(h as usize);
                for j in 1..cb.len() - 1 {
                    let u = fan(cb, j, &at_b);
                    let (ulo, uhi) = boxed(&u);
                    // Closed boxes (exact comparisons of the corners):
                    // disjoint boxes hold disjoint triangles.
                    if tlo.cmpgt(uhi).any() || ulo.cmpgt(thi).any() {
                        continue;
                    }
                    if !triangles_apart(&t, &u) && triangles_meet(&t, &u) {
                        return true;
                    }
                }
            }
        }
    }
    false
}

/// How many feature axes [`separating_feature_axis`] tries.
const FEATURE_AXES: usize = 3;

/// A unit axis that separates A' and B' exactly, among the features of
/// GJK's final simplex (`None` when none of those tried does): the normals of the faces of A and B around
/// the simplex's vertices and the cross products of their edges, the ones
/// nearest GJK's direction first.
///
/// GJK's direction `v` is the difference of two nearly equal points when
/// the bodies nearly touch, so it is off by about `ε · size / |v|`: along
/// it the separation can fail to show although the bodies are apart by
/// `10⁻⁹` of their size. A face normal or an edge cross product is exact to
/// `ε` whatever the distance, and by the separating axis theorem one of
/// them separates two disjoint polytopes (the one of the features nearest
/// each other, which GJK's simplex holds).
pub(in crate::query) fn separating_feature_axis(
    pair: &ConvexPair,
    posed: &Posed,
    g: &Gjk,
    cert: &mut CertScratch,
) -> Option<DVec3> {
    let v = g.v.normalize();
    if !v.is_finite() {
        return None;
    }
    let mut best = NearestAxes::<(u32, u32), FEATURE_AXES>::new(v);
    for_each_feature_axis(pair, posed, g, v, |d, warm| best.offer(d, warm));
    if let Some((d, _)) = best
        .facing()
        .find(|&(d, warm)| separated_along(pair, posed, d, warm, cert))
    {
        return Some(d);
    }
    // Second try, ranked by the local gap instead (below).
    let local = LocalVertices::around(pair, posed, g);
    let mut widest = NearestAxes::<(u32, u32), FEATURE_AXES>::new(v);
    for_each_feature_axis(pair, posed, g, v, |d, warm| {
        let len = d.length();
        if len > 0.0 && len.is_finite() {
            let d = d / len;
            widest.offer_scored(d, local.gap(d), warm);
        }
    });
    if let Some((d, _)) = widest
        .kept()
        .find(|&(d, warm)| separated_along(pair, posed, d, warm, cert))
    {
        return Some(d);
    }
    // Third try: the normals of the faces one edge further on both
    // bodies (on a float32 cylinder GJK can end a few facets away from
    // the nearest feature), ranked by the gap over the vertices around
    // those faces.
    let (mut fa, mut fb) = (LocalFaces::default(), LocalFaces::default());
    LocalFaces::around_simplex(pair, g, true, &mut fa, &mut fb);
    let wide = LocalVertices::of_faces(pair, posed, &fa.faces[..fa.n], &fb.faces[..fb.n]);
    let warm = g.warm;
    let mut further = NearestAxes::<(u32, u32), FEATURE_AXES>::new(v);
    for &f in &fa.faces[..fa.n] {
        let d = -posed.na(f);
        further.offer_scored(d, wide.gap(d), warm);
    }
    for &h in &fb.faces[..fb.n] {
        let d = posed.nb(h);
        further.offer_scored(d, wide.gap(d), warm);
    }
    let separating = further
        .kept()
        .find(|&(d, warm)| separated_along(pair, posed, d, warm, cert))
        .map(|(d, _)| d);
    separating
}

/// Offers every feature axis of GJK's final simplex (any length, oriented
/// towards `v` = GJK's unit direction) with the support vertices to start
/// from: the outward normals of A's faces around the simplex's vertices
/// of A (negated: facing B), those of B's faces around its vertices of B,
/// and the cross products of the edges leaving those vertices.
fn for_each_feature_axis(
    pair: &ConvexPair,
    posed: &Posed,
    g: &Gjk,
    v: DVec3,
    mut offer: impl FnMut(DVec3, (u32, u32)),
) {
    let pts = &g.simplex.pts[..g.simplex.len];
    for (i, p) in pts.iter().enumerate() {
        if pts[..i].iter().any(|q| q.a == p.a) {
            continue;
        }
        for r in pair.a.ring(p.a as usize) {
            // A's faces facing B: outward normals near −v.
            offer(-posed.na(r.face), (p.a, p.b));
        }
    }
    for (i, p) in pts.iter().enumerate() {
        if pts[..i].iter().any(|q| q.b == p.b) {
            continue;
        }
        for r in pair.b.ring(p.b as usize) {
            offer(posed.nb(r.face), (p.a, p.b));
        }
    }
    for (i, p) in pts.iter().enumerate() {
        if pts[..i].iter().any(|q| q.a == p.a) {
            continue;
        }
        for ra in pair.a.ring(p.a as usize) {
            let ea = posed.a(ra.neighbor) - posed.a(p.a);
            for (j, q) in pts.iter().enumerate() {
                if pts[..j].iter().any(|x| x.b == q.b) {
                    continue;
                }
                for rb in pair.b.ring(q.b as usize) {
                    let c = ea.cross(posed.b(rb.neighbor) - posed.b(q.b));
                    offer(if c.dot(v) < 0.0 { -c } else { c }, (p.a, q.b));
                }
            }
        }
    }
}

/// The posed vertices of A and of B next to GJK's final simplex (its
/// vertices and their neighbours), for ranking candidate axes by the gap
/// they leave between these points alone.
///
/// When the bodies nearly touch, GJK's direction is the difference of two
/// nearly equal points and can be off by far more than the angle between
/// the candidate axes, so ranking them by closeness to it can leave the
/// one separating axis out of the few tried. An axis separates only if it
/// separates these points (`min d · a − max d · b > 0` over them), and
/// the wrong ones mostly do not: a neighbour on the other side shows it.
/// The ranking only chooses what [`separated_along`] tries; that decides
/// exactly, so the ranking needs no error bound.
struct LocalVertices {
    a: [DVec3; LOCAL_VERTICES],
    na: usize,
    b: [DVec3; LOCAL_VERTICES],
    nb: usize,
}

/// The most local vertices kept per body (the simplex's up to three
/// distinct vertices and their rings; the rest are left out of the
/// ranking, which only orders the tries).
const LOCAL_VERTICES: usize = 192;

impl LocalVertices {
    fn empty() -> LocalVertices {
        LocalVertices {
            a: [DVec3::ZERO; LOCAL_VERTICES],
            na: 0,
            b: [DVec3::ZERO; LOCAL_VERTICES],
            nb: 0,
        }
    }

    fn around(pair: &ConvexPair, posed: &Posed, g: &Gjk) -> LocalVertices {
        let mut out = LocalVertices::empty();
        let push = |buf: &mut [DVec3; LOCAL_VERTICES], n: &mut usize, x: DVec3| {
            if *n < LOCAL_VERTICES {
                buf[*n] = x;
                *n += 1;
            }
        };
        for p in &g.simplex.pts[..g.simplex.len] {
            push(&mut out.a, &mut out.na, posed.a(p.a));
            for r in pair.a.ring(p.a as usize) {
                push(&mut out.a, &mut out.na, posed.a(r.neighbor));
            }
            push(&mut out.b, &mut out.nb, posed.b(p.b));
            for r in pair.b.ring(p.b as usize) {
                push(&mut out.b, &mut out.nb, posed.b(r.neighbor));
            }
        }
        out
    }

    /// The corners of faces `fa` of A and `fb` of B (up to
    /// [`LOCAL_VERTICES`] each, repeats allowed).
    fn of_faces(pair: &ConvexPair, posed: &Posed, fa: &[u32], fb: &[u32]) -> LocalVertices {
        let mut out = LocalVertices::empty();
        let corners_a = fa.iter().flat_map(|&f| pair.a.face(f as usize).iter());
        for (k, &v) in corners_a.take(LOCAL_VERTICES).enumerate() {
            out.a[k] = posed.a(v);
            out.na = k + 1;
        }
        let corners_b = fb.iter().flat_map(|&h| pair.b.face(h as usize).iter());
        for (k, &w) in corners_b.take(LOCAL_VERTICES).enumerate() {
            out.b[k] = posed.b(w);
            out.nb = k + 1;
        }
        out
    }

    /// `min d · a − max d · b` over the local vertices (floats).
    fn gap(&self, d: DVec3) -> f64 {
        let lo = self.a[..self.na]
            .iter()
            .fold(f64::INFINITY, |m, x| m.min(d.dot(*x)));
        let hi = self.b[..self.nb]
            .iter()
            .fold(f64::NEG_INFINITY, |m, x| m.max(d.dot(*x)));
        lo - hi
    }
}

/// `seed` when it lies further along `dir` than `warm` (posed), else
/// `warm`: a support search's start.
fn better_start(at: impl Fn(u32) -> DVec3, dir: DVec3, warm: u32, seed: u32) -> u32 {
    if dir.dot(at(seed)) > dir.dot(at(warm)) {
        seed
    } else {
        warm
    }
}

/// Exactly whether GJK's final simplex holds the origin (tested when the
/// simplex is a tetrahedron enclosing it in floats, or when its nearest
/// point is within rounding of the origin).
pub(in crate::query) fn encloses_origin(posed: &Posed, g: &Gjk) -> bool {
    let tiny = g.v.length_squared() <= (posed.scale * 2f64.powi(-30)).powi(2);
    if g.separating || g.simplex.len == 0 || !(g.enclosed || tiny) {
        return false;
    }
    let mut buf = [(DVec3::ZERO, DVec3::ZERO); 4];
    for (i, p) in g.simplex.pts[..g.simplex.len].iter().enumerate() {
        buf[i] = (posed.a(p.a), posed.b(p.b));
    }
    origin_in_hull(&buf[..g.simplex.len])
}

/// Exactly whether `min_A' d · a > max_B' d · b` (a separating direction),
/// from the near-extreme sets of both bodies (module docs).
pub(in crate::query) fn separated_along(
    pair: &ConvexPair,
    posed: &Posed,
    d: DVec3,
    warm: (u32, u32),
    cert: &mut CertScratch,
) -> bool {
    let (na, nb) = near_max_pair(pair, posed, (-d, 0.0), (d, 0.0), warm, cert);
    // max(−d · a) + max(d · b) < 0 ⟺ min d · a > max d · b.
    if na.upper + nb.upper < 0.0 {
        return true;
    }
    let lower = |x: f64, e: f64| x - 2.0 * e;
    if lower(na.value, na.upper - na.value) + lower(nb.value, nb.upper - nb.value) > 0.0 {
        return false; // certainly not separated along d
    }
    // Exactly: the rounded extremes are in the sets.
    separated_on_sets(posed, d, cert)
}

/// The near-extreme sets of A in `a.0` covering at least `a.1` and of B in
/// `b.0` covering at least `b.1` ([`near_max`] on each posed body, into
/// `cert.set_a` and `cert.set_b`), started from the support vertices `warm`.
pub(in crate::query) fn near_max_pair(
    pair: &ConvexPair,
    posed: &Posed,
    (dir_a, tau_a): (DVec3, f64),
    (dir_b, tau_b): (DVec3, f64),
    warm: (u32, u32),
    cert: &mut CertScratch,
) -> (NearMax, NearMax) {
    let na = near_max(
        &pair.a,
        |v| posed.a(v),
        dir_a,
        warm.0,
        tau_a,
        posed.eta_a,
        posed.scale,
        &mut cert.marks_a,
        &mut cert.set_a,
    );
    let nb = near_max(
        &pair.b,
        |w| posed.b(w),
        dir_b,
        warm.1,
        tau_b,
        posed.eta_b,
        posed.scale,
        &mut cert.marks_b,
        &mut cert.set_b,
    );
    (na, nb)
}

/// Exactly whether the separation along `d` holds, from near-extreme sets
/// already in `cert` (of A in `−d`, of B in `d`; they contain the rounded
/// extremes).
pub(in crate::query) fn separated_on_sets(posed: &Posed, d: DVec3, cert: &CertScratch) -> bool {
    let exact_max = |set: &[u32], at: &dyn Fn(u32) -> DVec3, dir: DVec3| {
        let mut best: Option<Dyadic> = None;
        for &u in set {
            let x = exact_dot(dir, at(u));
            if best
                .as_ref()
                .is_none_or(|b| x.sub(b).sign() == Sign::Positive)
            {
                best = Some(x);
            }
        }
        best.expect("a near-extreme set is never empty")
    };
    let ma = exact_max(&cert.set_a, &|v| posed.a(v), -d);
    let mb = exact_max(&cert.set_b, &|w| posed.b(w), d);
    ma.add(&mb).sign() == Sign::Negative
}

/// `d · x`, exactly.
fn exact_dot(d: DVec3, x: DVec3) -> Dyadic {
    exact::dot(&exact::exact(d), &exact::exact(x))
}

/// The exact point `a − b`.
fn exact_diff((a, b): (DVec3, DVec3)) -> ExactVec {
    exact::sub(a, b)
}

/// Sign of `det[x1, x2, x3]` for the exact points `x_i = a_i − b_i`: a
/// float filter (the rounded points and a rigorous bound), exact dyadic
/// arithmetic when it cannot decide.
fn det3_of_diffs(p: [(DVec3, DVec3); 3]) -> Sign {
    let x = p.map(|(a, b)| a - b);
    let det = x[0].dot(x[1].cross(x[2]));
    let ax = x.map(|v| v.abs());
    let perm = ax[0].x * (ax[1].y * ax[2].z + ax[1].z * ax[2].y)
        + ax[0].y * (ax[1].z * ax[2].x + ax[1].x * ax[2].z)
        + ax[0].z * (ax[1].x * ax[2].y + ax[1].y * ax[2].x);
    // Each rounded point is off by at most half an ulp per component; the
    // determinant's own rounding is below 6u of the permanent.
    let bound = 16.0 * f64::EPSILON * perm + 1e-300;
    if det > bound {
        Sign::Positive
    } else if det < -bound {
        Sign::Negative
    } else {
        let e = p.map(exact_diff);
        exact::det3(&e[0], &e[1], &e[2]).sign()
    }
}

/// Exactly whether the origin lies in the closed convex hull of the one to
/// four exact points `a_i − b_i`.
pub(in crate::query) fn origin_in_hull(p: &[(DVec3, DVec3)]) -> bool {
    match p.len() {
        4 => {
            let s = |i: usize, j: usize, k: usize| det3_of_diffs([p[i], p[j], p[k]]);
            // Cramer's rule on [x; 1] λ = [0; 1]: λ_j has the sign of
            // C_j / det with C = (−[1,2,3], [0,2,3], −[0,1,3], [0,1,2]).
            // det[[x; 1]] = Σ C_j: when the non-zero C_j share one sign the
            // sum has it and the origin is inside; opposite signs put it
            // outside whatever the sum; all zero means a flat simplex.
            let c = [s(1, 2, 3).flip(), s(0, 2, 3), s(0, 1, 3).flip(), s(0, 1, 2)];
            let pos = c.contains(&Sign::Positive);
            let neg = c.contains(&Sign::Negative);
            if pos || neg {
                return !(pos && neg);
            }
            // Flat: the origin is in the hull iff it is in one of the
            // triangles (Carathéodory in the plane).
            (0..4).any(|drop| origin_in_hull(&without(p, drop)[..3]))
        }
        3 => {
            let e = [exact_diff(p[0]), exact_diff(p[1]), exact_diff(p[2])];
            if exact::det3(&e[0], &e[1], &e[2]).sign() != Sign::Zero {
                return false; // the origin is off the triangle's plane
            }
            let sub =
                |u: &ExactVec, v: &ExactVec| [u[0].sub(&v[0]), u[1].sub(&v[1]), u[2].sub(&v[2])];
            let n = exact::cross(&sub(&e[1], &e[0]), &sub(&e[2], &e[0]));
            if n.iter().all(|c| c.is_zero()) {
                // Collinear: the origin is in the hull iff it is on a side.
                return (0..3).any(|drop| origin_in_hull(&without(p, drop)[..2]));
            }
            (0..3).all(|i| {
                let (u, v) = (&e[(i + 1) % 3], &e[(i + 2) % 3]);
                exact::dot(&n, &exact::cross(u, v)).sign() != Sign::Negative
            })
        }
        2 => {
            let (u, v) = (exact_diff(p[0]), exact_diff(p[1]));
            exact::cross(&u, &v).iter().all(|c| c.is_zero())
                && exact::dot(&u, &v).sign() != Sign::Positive
        }
        1 => p[0].0 == p[0].1,
        _ => false,
    }
}

/// The points of `p` but the one at `drop`, in order (the first
/// `p.len() − 1` entries).
fn without(p: &[(DVec3, DVec3)], drop: usize) -> [(DVec3, DVec3); 4] {
    let mut out = [(DVec3::ZERO, DVec3::ZERO); 4];
    for (k, &x) in p
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != drop)
        .map(|(_, x)| x)
        .enumerate()
    {
        out[k] = x;
    }
    out
}

/// The exhaustive exact answer: whether the origin lies in the hull of all
/// `a' − b'` (the exact hull of the pairwise sums of A' and `−B'`, then the
/// exact side of the origin for each face).
pub(in crate::query) fn origin_in_difference_hull(pair: &ConvexPair, posed: &Posed) -> bool {
    let p: Vec<DVec3> = (0..pair.a.vertex_count() as u32)
        .map(|v| posed.a(v))
        .collect();
    let q: Vec<DVec3> = (0..pair.b.vertex_count() as u32)
        .map(|w| -posed.b(w))
        .collect();
    let sums = PairwiseSums::new(&p, &q);
    let Ok(hull) = convex_hull(&sums) else {
        // Flat or degenerate difference (not for two polytopes): test the
        // origin against every point triple's plane is not needed, as a
        // polytope difference always has volume.
        return false;
    };
    let point = |k: usize| {
        let (i, j) = sums.split(k);
        (p[i], -q[j])
    };
    hull.faces.iter().all(|f| {
        let (x0, x1, x2) = (point(f[0]), point(f[1]), point(f[2]));
        // Faces are counter-clockwise from outside: the origin is inside
        // or on the face's plane iff det[x1 − x0, x2 − x0, 0 − x0] ≤ 0,
        // i.e. det[x0, x1, x2] ≥ 0... computed on the exact points.
        let e = [exact_diff(x0), exact_diff(x1), exact_diff(x2)];
        exact::det3(&e[0], &e[1], &e[2]).sign() != Sign::Negative
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::proximity::scratch::Scratch;

    use crate::query::test_support::{boxes_and_hulls, oracle_poses, Lcg};

    /// GJK's certificates (when they decide) against the independent
    /// exhaustive exact method (the exact hull of all differences and the
    /// origin's exact side of each face), on random hulls and on boxes
    /// touching exactly or apart or overlapping by an ulp; and the
    /// certificates decide nearly every pose.
    #[test]
    fn certificates_agree_with_the_exact_hull_of_differences() {
        let mut r = Lcg(5);
        let shapes = boxes_and_hulls(&mut r, &[6, 20, 60]);
        let (mut decided, mut total) = (0, 0);
        for a in &shapes {
            for b in &shapes {
                let pair = ConvexPair::new(a, b).unwrap();
                let mut scratch = Scratch::default();
                for k in 0..60 {
                    let (pa, pb) = oracle_poses(&mut r, k);
                    scratch.posed.reset(&pair, pa, pb).unwrap();
                    let posed = &scratch.posed;
                    let exact = origin_in_difference_hull(&pair, posed);
                    for yes_no in [false, true] {
                        let g = gjk(
                            &pair,
                            posed,
                            (0, 0),
                            DVec3::ZERO,
                            &Simplex::default(),
                            yes_no,
                        );
                        total += 1;
                        if let Some(ans) = certify(&pair, posed, &g, &mut scratch.cert) {
                            decided += 1;
                            assert_eq!(ans, exact, "pose {pa:?} {pb:?} yes_no {yes_no}");
                        }
                    }
                }
            }
        }
        assert!(decided * 10 >= total * 9, "{decided} of {total} decided");
    }
}
