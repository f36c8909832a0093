//! EPA: a polytope `K` inside `D' = A' ⊕ (−B')` around the origin, grown
//! towards the boundary of `D'` nearest the origin (van den Bergen's
//! expanding polytope algorithm), for the penetration-depth certificate of
//! [`crate::query::proximity::certificate`].
//!
//! `K` starts as GJK's final tetrahedron, which encloses the origin. Each
//! step takes the face of `K` nearest the origin, finds the support point
//! `w` of `D'` in its normal (a vertex of A less a vertex of B, by hill
//! climbing from that face's own vertices), and, unless `w` lies on the
//! face's plane to within the tie tolerance, replaces the faces `w` sees by
//! a cone from their horizon to `w`. Every vertex of `K` is a point of
//! `D'` (rounded to floats), so `K` has finitely many possible vertices and
//! the expansion ends; a budget of [`MAX_STEPS`] guards the rare slow
//! cases, after which the certificate simply works with a coarser `K`.
//!
//! Floats only build `K`. What the certificate needs of it is checked
//! exactly afterwards ([`Epa::encloses_origin`]): every face has the origin
//! strictly on its inner side (exact `orient3d` on the float vertices), and
//! the faces close up (each edge in two faces, in opposite directions, by
//! construction). A step that would break the surface (a horizon that is
//! not one loop) ends the expansion with the `K` built so far.

use crate::kernel::predicates::orient;
use crate::kernel::Sign;
use crate::query::frame::Posed;
use crate::query::pair::ConvexPair;
use crate::query::proximity::gjk::Point;
use crate::query::proximity::support::climb_unposed;
use glam::DVec3;

/// The most expansion steps.
pub(in crate::query) const MAX_STEPS: usize = 256;

/// The most expansion steps from a carried polytope ([`Epa::regrow`]):
/// under coherent motion it needs a few; more means the motion jumped, and
/// a fresh start is cheaper.
pub(in crate::query) const MAX_CARRIED_STEPS: usize = 12;

/// How an expansion ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Grown {
    /// The support plane of the nearest face is within the tie tolerance.
    Converged,
    /// The step budget ran out first (`K` is usable, coarser).
    OutOfSteps,
    /// A step broke the surface: `K` must not be used.
    Broken,
}

/// A triangle of `K`, counter-clockwise seen from outside.
#[derive(Clone, Copy, Debug)]
pub(in crate::query) struct Tri {
    /// Its corners (indices into [`Epa::pts`]).
    pub v: [u32; 3],
    /// `adj[i]`: the triangle across the edge from `v[i]` to `v[i + 1]`.
    adj: [u32; 3],
    /// Unit outward normal (float).
    pub n: DVec3,
    /// Offset `n · v[0]` (float).
    pub d: f64,
    /// Bounds on the float normal's angle from the exact one and on the
    /// offset's error (from the corners' cross product and its conditioning).
    pub dm: f64,
    /// See `dm`.
    pub dd: f64,
    /// Still a face of `K`.
    pub alive: bool,
}

/// The expanding polytope and its buffers (kept from query to query).
#[derive(Clone, Debug, Default)]
pub(in crate::query) struct Epa {
    /// The points of `D'` that are vertices of `K`.
    pub pts: Vec<Point>,
    /// The triangles (dead ones stay, marked).
    pub tris: Vec<Tri>,
    /// Horizon edges of one step: (triangle beyond, its edge index).
    horizon: Vec<(u32, u8)>,
    /// Depth-first stack of one step.
    stack: Vec<(u32, u8, u8)>,
    /// [`Epa::regrow`]'s buffers: the last query's points and faces, and
    /// their new indices.
    old_pts: Vec<Point>,
    old_tris: Vec<Tri>,
    remap: Vec<u32>,
    /// The live faces of the last polytope grown from a fresh start.
    fresh_faces: usize,
}

/// A carried `K` may have up to this many times the faces of the last
/// fresh one ([`Epa::regrow`]): re-posing costs per face, and a polytope
/// that kept growing frame after frame costs more to carry than a fresh
/// start (a dozen expansions) does.
const CARRIED_GROWTH: usize = 2;

impl Epa {
    /// Grows `K` from a tetrahedron of `D'` points enclosing the origin.
    /// Returns `false` when `K` cannot be used: the tetrahedron is flat, or
    /// a step broke the surface (a horizon that is not one loop, a
    /// degenerate new face).
    pub(in crate::query) fn run(
        &mut self,
        pair: &ConvexPair,
        posed: &Posed,
        tetra: [Point; 4],
        hint: Option<DVec3>,
    ) -> bool {
        self.pts.clear();
        self.tris.clear();
        let mut t = tetra;
        let det = (t[1].w - t[0].w).dot((t[2].w - t[0].w).cross(t[3].w - t[0].w));
        if det == 0.0 || !det.is_finite() {
            return false;
        }
        if det > 0.0 {
            t.swap(1, 2);
        }
        self.pts.extend_from_slice(&t);
        // (0, 1, 2) is outward with 3 below; the other faces follow.
        for f in [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]] {
            if !self.add_tri(f) {
                return false;
            }
        }
        // Adjacency of the tetrahedron: match each directed edge with its
        // reverse.
        for i in 0..4 {
            for k in 0..3 {
                let (p, q) = (self.tris[i].v[k], self.tris[i].v[(k + 1) % 3]);
                let j = (0..4)
                    .find(|&j| {
                        j != i
                            && (0..3)
                                .any(|m| self.tris[j].v[m] == q && self.tris[j].v[(m + 1) % 3] == p)
                    })
                    .expect("a tetrahedron's faces meet along every edge");
                self.tris[i].adj[k] = j as u32;
            }
        }
        self.grow_fresh(pair, posed, hint)
    }

    /// Re-poses the last query's `K` at this query's poses and grows it
    /// from there: a tracker's frames move the bodies a little, so the
    /// last frame's polytope is nearly converged at the next one, where a
    /// fresh start takes a dozen expansions. Its live faces are kept with
    /// their adjacency, and their corners (pairs of vertex indices of A
    /// and B, so still points of `D'`) are posed anew.
    ///
    /// Nothing here needs the re-posed surface to be convex: the
    /// certificate asks only for a closed surface (every edge in two
    /// faces, in opposite directions, which re-posing keeps) whose
    /// vertices are points of `D'` and whose every face has the origin
    /// strictly inside, checked exactly afterwards
    /// ([`Epa::encloses_origin`]). A step on a slightly non-convex surface
    /// whose horizon is not one loop fails as it would on a fresh one.
    /// `false` when `K` is empty or has more than `CARRIED_GROWTH` times
    /// the faces of the last fresh one, a face turned degenerate, a step broke the surface, or
    /// [`MAX_CARRIED_STEPS`] steps did not reach the support plane (the
    /// motion jumped): the caller then starts afresh.
    pub(in crate::query) fn regrow(&mut self, pair: &ConvexPair, posed: &Posed) -> bool {
        let live = self.live_faces();
        if live < 4 || live > CARRIED_GROWTH * self.fresh_faces {
            return false;
        }
        std::mem::swap(&mut self.pts, &mut self.old_pts);
        std::mem::swap(&mut self.tris, &mut self.old_tris);
        self.pts.clear();
        self.tris.clear();
        // New indices: the live faces' in order (the map's first block),
        // then their corners' in order of first use (the second block).
        let n_old_tris = self.old_tris.len();
        self.remap.clear();
        self.remap.resize(n_old_tris + self.old_pts.len(), u32::MAX);
        let mut next = 0u32;
        for (i, t) in self.old_tris.iter().enumerate() {
            if t.alive {
                self.remap[i] = next;
                next += 1;
            }
        }
        for i in 0..n_old_tris {
            let t = self.old_tris[i];
            if !t.alive {
                continue;
            }
            let mut v = [0u32; 3];
            for (k, &c) in t.v.iter().enumerate() {
                let slot = n_old_tris + c as usize;
                if self.remap[slot] == u32::MAX {
                    self.remap[slot] = self.pts.len() as u32;
                    let p = self.old_pts[c as usize];
                    self.pts.push(Point {
                        w: posed.a(p.a) - posed.b(p.b),
                        a: p.a,
                        b: p.b,
                    });
                }
                v[k] = self.remap[slot];
            }
            if !self.add_tri(v) {
                return false;
            }
            let adj = t.adj.map(|j| self.remap[j as usize]);
            if adj.contains(&u32::MAX) {
                return false;
            }
            let last = self.tris.len() - 1;
            self.tris[last].adj = adj;
        }
        // Within a small budget, else the motion jumped: start afresh.
        let grown = self.grow(pair, posed, None, MAX_CARRIED_STEPS) == Grown::Converged;
        debug_assert!(!grown || self.sanity_check().is_ok());
        grown
    }

    /// Expands `K` (towards `hint` first), then its nearest face until the
    /// support plane is reached (within the tie tolerance) or `budget`
    /// steps are spent.
    fn grow(
        &mut self,
        pair: &ConvexPair,
        posed: &Posed,
        hint: Option<DVec3>,
        budget: usize,
    ) -> Grown {
        let tol = posed.tol;
        let to_a = posed.pose_a.rotation.matrix().transpose();
        let to_b = posed.pose_b.rotation.matrix().transpose();
        // A hint (the last frame's contact normal): first grow the face it
        // points through towards the support point there, which under
        // coherent motion is next to the answer.
        if let Some(h) = hint.filter(|h| h.length_squared() > 0.0) {
            let f = (0..self.tris.len())
                .max_by(|&i, &j| self.tris[i].n.dot(h).total_cmp(&self.tris[j].n.dot(h)))
                .expect("four faces");
            let start = self.pts[self.tris[f].v[0] as usize];
            let a = climb_unposed(&pair.a, &to_a, h, start.a);
            let b = climb_unposed(&pair.b, &to_b, -h, start.b);
            let w = posed.a(a) - posed.b(b);
            let tri = self.tris[f];
            let known = self.pts.iter().any(|p| p.a == a && p.b == b);
            if !known && tri.n.dot(w) - tri.d > tol && !self.expand(f, Point { w, a, b }) {
                return Grown::Broken;
            }
        }
        for _ in 0..budget {
            let Some(f) = self.nearest() else {
                return Grown::Converged;
            };
            let tri = self.tris[f];
            let start = self.pts[tri.v[0] as usize];
            let a = climb_unposed(&pair.a, &to_a, tri.n, start.a);
            let b = climb_unposed(&pair.b, &to_b, -tri.n, start.b);
            let w = posed.a(a) - posed.b(b);
            if tri.v.iter().any(|&i| {
                let p = self.pts[i as usize];
                p.a == a && p.b == b
            }) || tri.n.dot(w) - tri.d <= tol
            {
                return Grown::Converged;
            }
            if !self.expand(f, Point { w, a, b }) {
                return Grown::Broken;
            }
        }
        Grown::OutOfSteps
    }

    /// [`Epa::grow`] from a fresh start, keeping its size for
    /// [`Epa::regrow`]; `false` when a step broke the surface.
    fn grow_fresh(&mut self, pair: &ConvexPair, posed: &Posed, hint: Option<DVec3>) -> bool {
        let grown = self.grow(pair, posed, hint, MAX_STEPS) != Grown::Broken;
        self.fresh_faces = self.live_faces();
        grown
    }

    /// How many faces `K` has.
    fn live_faces(&self) -> usize {
        self.tris.iter().filter(|t| t.alive).count()
    }

    /// The live face nearest the origin.
    pub(in crate::query) fn nearest(&self) -> Option<usize> {
        (0..self.tris.len())
            .filter(|&i| self.tris[i].alive)
            .min_by(|&i, &j| self.tris[i].d.total_cmp(&self.tris[j].d))
    }

    /// Grows `K` from the convex hull of `pts` (points of `D'`), for when
    /// GJK ended without an enclosing tetrahedron (the origin on a face or
    /// an edge of its simplex, typical of axis-aligned boxes): the exact
    /// hull of the points, its faces split into fans. `false` when the
    /// points are flat or a step breaks the surface.
    pub(in crate::query) fn run_from_hull(
        &mut self,
        pair: &ConvexPair,
        posed: &Posed,
        pts: &[Point],
        hint: Option<DVec3>,
    ) -> bool {
        use crate::hull::{convex_hull, FloatPoints};
        self.pts.clear();
        self.tris.clear();
        let ws: Vec<DVec3> = pts.iter().map(|p| p.w).collect();
        let Ok(hull) = convex_hull(&FloatPoints(&ws)) else {
            return false;
        };
        self.pts.extend_from_slice(pts);
        for face in &hull.faces {
            for i in 1..face.len() - 1 {
                if !self.add_tri([face[0] as u32, face[i] as u32, face[i + 1] as u32]) {
                    return false;
                }
            }
        }
        // Adjacency: each directed edge against its reverse.
        let n = self.tris.len();
        for i in 0..n {
            for k in 0..3 {
                let (p, q) = (self.tris[i].v[k], self.tris[i].v[(k + 1) % 3]);
                let Some(j) = (0..n).find(|&j| {
                    j != i
                        && (0..3)
                            .any(|m| self.tris[j].v[m] == q && self.tris[j].v[(m + 1) % 3] == p)
                }) else {
                    return false;
                };
                self.tris[i].adj[k] = j as u32;
            }
        }
        self.grow_fresh(pair, posed, hint)
    }

    /// Adds the triangle `v` (outward normal from its corners); `false`
    /// when it is degenerate.
    fn add_tri(&mut self, v: [u32; 3]) -> bool {
        let [a, b, c] = v.map(|i| self.pts[i as usize].w);
        let (e1, e2) = (b - a, c - a);
        let n = e1.cross(e2);
        let len = n.length();
        if !(len > 0.0 && len.is_finite()) {
            return false;
        }
        let n = n / len;
        // The edges are off by half an ulp per component, the cross product
        // and normalisation by a few more: the angle error is at most
        // `6ε |e1| |e2| / |n| + 4ε`; the offset's, that times |a| plus the
        // dot product's rounding.
        let dm = 6.0 * f64::EPSILON * e1.length() * e2.length() / len + 4.0 * f64::EPSILON;
        self.tris.push(Tri {
            v,
            adj: [u32::MAX; 3],
            n,
            d: n.dot(a),
            dm,
            dd: (dm + 4.0 * f64::EPSILON) * a.length(),
            alive: true,
        });
        true
    }

    /// Replaces the faces the new point `p` sees (starting from face `f`,
    /// which it sees) by a cone from their horizon to `p`. `false` when the
    /// horizon is not a single loop or a new face is degenerate: `K` is
    /// then broken and must not be used.
    fn expand(&mut self, f: usize, p: Point) -> bool {
        let wi = self.pts.len() as u32;
        self.pts.push(p);
        self.horizon.clear();
        self.tris[f].alive = false;
        // Depth-first over the visible faces, leaving by each edge in turn,
        // so the horizon comes out as one counter-clockwise loop.
        self.stack.clear();
        for k in (0..3u8).rev() {
            let Some(b) = back_edge(self, f, k) else {
                return false;
            };
            self.stack.push((self.tris[f].adj[k as usize], b, 0));
        }
        while let Some((t, from, step)) = self.stack.pop() {
            let t_us = t as usize;
            if step == 0 {
                if !self.tris[t_us].alive {
                    continue;
                }
                let tri = self.tris[t_us];
                let a = self.pts[tri.v[0] as usize].w;
                if tri.n.dot(p.w - a) <= 0.0 {
                    self.horizon.push((t, from));
                    continue;
                }
                self.tris[t_us].alive = false;
            }
            if step < 2 {
                // Visit the next edge after `from` (then the one after it).
                self.stack.push((t, from, step + 1));
                let k = (from + 1 + step) % 3;
                let n = self.tris[t_us].adj[k as usize];
                let Some(b) = back_edge(self, t_us, k) else {
                    return false;
                };
                self.stack.push((n, b, 0));
            }
        }
        let h = self.horizon.len();
        if h < 3 {
            return false;
        }
        let first = self.tris.len() as u32;
        for i in 0..h {
            let (t, e) = self.horizon[i];
            let tri = self.tris[t as usize];
            // The horizon edge as seen from the removed side: reversed.
            let (s, q) = (tri.v[(e as usize + 1) % 3], tri.v[e as usize]);
            let next = self.horizon[(i + 1) % h];
            let nt = self.tris[next.0 as usize];
            if nt.v[(next.1 as usize + 1) % 3] != q {
                return false; // not one loop
            }
            if !self.add_tri([s, q, wi]) {
                return false;
            }
            let new = first + i as u32;
            self.tris[new as usize].adj = [
                t,
                first + ((i + 1) % h) as u32,
                first + ((i + h - 1) % h) as u32,
            ];
            self.tris[t as usize].adj[e as usize] = new;
        }
        true
    }

    /// Exactly whether every face of `K` has the origin strictly on its
    /// inner side (with the faces closing up by construction, the faces
    /// then cover every direction from the origin: see
    /// [`crate::query::proximity::certificate`]).
    pub(in crate::query) fn encloses_origin(&self) -> bool {
        self.tris.iter().filter(|t| t.alive).all(|t| {
            // The float offset less its error bound decides most faces.
            t.d - t.dd > 0.0 || {
                let [a, b, c] = t.v.map(|i| self.pts[i as usize].w);
                orient(a, b, c, DVec3::ZERO) == Sign::Negative
            }
        })
    }
}

impl Epa {
    /// The structure's invariants: every live face has three distinct
    /// corners among the points, and across each of its edges a live face
    /// holding the same edge in the opposite direction (so the live faces
    /// close up). A description of the first broken one, if any.
    pub(in crate::query) fn sanity_check(&self) -> Result<(), String> {
        for (i, t) in self.tris.iter().enumerate().filter(|(_, t)| t.alive) {
            let [a, b, c] = t.v;
            if a == b || b == c || a == c || t.v.iter().any(|&v| v as usize >= self.pts.len()) {
                return Err(format!("face {i} has corners {:?}", t.v));
            }
            for k in 0..3u8 {
                let j = t.adj[k as usize] as usize;
                if !self.tris.get(j).is_some_and(|n| n.alive) {
                    return Err(format!("face {i} edge {k}: no live face across ({j})"));
                }
                if back_edge(self, i, k).is_none() {
                    return Err(format!(
                        "face {i} edge {k}: face {j} lacks the reverse edge"
                    ));
                }
            }
        }
        Ok(())
    }
}

/// The index, in the triangle across edge `k` of triangle `t`, of the same
/// edge (`None` if the adjacency is inconsistent).
fn back_edge(epa: &Epa, t: usize, k: u8) -> Option<u8> {
    let tri = &epa.tris[t];
    let (p, q) = (tri.v[k as usize], tri.v[(k as usize + 1) % 3]);
    let n = epa.tris.get(tri.adj[k as usize] as usize)?;
    (0..3u8).find(|&m| n.v[m as usize] == q && n.v[(m as usize + 1) % 3] == p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::rotation::{Pose, Rotation};
    use crate::query::proximity::gjk::{gjk, Simplex};
    use crate::query::proximity::scratch::Scratch;
    use crate::query::test_support::{boxes_and_hulls, Lcg};

    /// The last frame's polytope re-posed ([`Epa::regrow`]) along motions
    /// through deep contact (boxes turning by exact quarter turns among
    /// them): it stays a closed surface, its points are its vertex pairs
    /// posed at the new frame, and its nearest face lies within the tie
    /// tolerance of a fresh polytope's (both are grown until the support
    /// plane is within it of the depth).
    #[test]
    fn a_carried_polytope_stays_closed_and_is_posed_anew() {
        let mut r = Lcg(11);
        let shapes = boxes_and_hulls(&mut r, &[8, 30]);
        let (mut regrown, mut compared) = (0, 0);
        for a in &shapes {
            for b in &shapes {
                let pair = ConvexPair::new(a, b).unwrap();
                let axis = r.unit();
                let mut scratch = Scratch::default();
                let mut carried = false;
                for k in 0..48 {
                    // Coherent steps, and a jump of an exact quarter
                    // turn every twelve frames.
                    let turn = std::f64::consts::FRAC_PI_2 * (k / 12) as f64 + 0.02 * k as f64;
                    let pa = Pose::new(Rotation::from_axis_angle(axis, turn).unwrap(), DVec3::ZERO);
                    let pb = Pose::new(
                        Rotation::IDENTITY,
                        DVec3::new(0.3 * (0.2 * k as f64).sin(), 0.1, 0.0),
                    );
                    scratch.posed.reset(&pair, pa, pb).unwrap();
                    let posed = &scratch.posed;
                    let g = gjk(
                        &pair,
                        posed,
                        (0, 0),
                        DVec3::ZERO,
                        &Simplex::default(),
                        false,
                    );
                    if !(g.enclosed && g.simplex.len == 4) {
                        carried = false;
                        continue;
                    }
                    let epa = &mut scratch.local.epa;
                    if carried && epa.regrow(&pair, posed) {
                        regrown += 1;
                        epa.sanity_check().unwrap();
                        for p in &epa.pts {
                            assert_eq!(p.w, posed.a(p.a) - posed.b(p.b), "frame {k}");
                        }
                        let mut fresh = Epa::default();
                        if fresh.run(&pair, posed, g.simplex.pts, None)
                            && fresh.encloses_origin()
                            && epa.encloses_origin()
                        {
                            compared += 1;
                            let d = |e: &Epa| e.tris[e.nearest().unwrap()].d;
                            assert!(
                                (d(epa) - d(&fresh)).abs() <= 4.0 * posed.tol,
                                "frame {k}: {} against {}",
                                d(epa),
                                d(&fresh)
                            );
                        }
                    }
                    let epa = &mut scratch.local.epa;
                    carried = epa.run(&pair, posed, g.simplex.pts, None);
                    epa.sanity_check().unwrap();
                }
            }
        }
        assert!(
            regrown >= 100 && compared >= 100,
            "{regrown} regrown, {compared} compared"
        );
    }
}
