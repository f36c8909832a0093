//! Exact incremental 3-D convex hull (Quickhull with conflict lists).
//!
//! Every combinatorial decision is an exact predicate of the point set
//! ([`HullPoints::orient`], [`HullPoints::collinear`],
//! [`HullPoints::coincident`]); float coordinates only steer heuristics (which
//! point to insert next, which candidates to try first for the initial
//! simplex), so they affect speed, never the result's correctness.

use super::{ConvexHull, HullError, HullPoints};
use crate::kernel::Sign;
use glam::DVec3;

/// "No index".
const NONE: u32 = u32::MAX;

/// A triangle of the (triangulated) hull, counter-clockwise seen from outside.
#[derive(Clone, Debug)]
struct Face {
    /// Vertices (point indices).
    v: [u32; 3],
    /// `adj[i]` is the face across edge `v[i] → v[(i + 1) % 3]`.
    adj: [u32; 3],
    /// Float plane (un-normalised normal and offset), for heuristics only.
    normal: DVec3,
    offset: f64,
    /// Head of the outside set (linked through `Builder::next`).
    head: u32,
    /// The outside point furthest from the float plane.
    far: u32,
    far_dist: f64,
    alive: bool,
    /// Epoch of the last visibility test and its result.
    mark: u32,
    visible: bool,
}

/// A horizon edge `a → b` of a deleted (visible) face `old`, whose
/// non-visible neighbour across it is `nb`.
#[derive(Clone, Copy, Debug)]
struct HorizonEdge {
    a: u32,
    b: u32,
    old: u32,
    nb: u32,
}

struct Builder<'a, P: HullPoints + ?Sized> {
    pts: &'a P,
    /// Float coordinates of all points (heuristics only).
    xyz: Vec<DVec3>,
    faces: Vec<Face>,
    free: Vec<u32>,
    /// Outside-set links, one per point.
    next: Vec<u32>,
    /// Faces that may have a non-empty outside set.
    pending: Vec<u32>,
    epoch: u32,
    // Scratch buffers, reused across insertions.
    visible: Vec<u32>,
    horizon: Vec<HorizonEdge>,
    new_faces: Vec<u32>,
    orphans: Vec<u32>,
    /// Per point: the new face whose horizon edge starts at this vertex.
    start_slot: Vec<u32>,
}

/// The exact convex hull of a point set, with maximal (merged) faces.
///
/// Returns the hull's corner vertices (ascending) and its faces as
/// counter-clockwise (seen from outside) cycles of corner indices, each
/// starting at its smallest index, sorted lexicographically. Points in the
/// relative interior of a face or of an edge, and duplicates, are left out.
///
/// # Errors
///
/// [`HullError`] when the points do not span three dimensions (fewer than
/// four points, all coincident, all collinear or all coplanar).
///
/// # Panics
///
/// If the point set has `u32::MAX` or more points.
pub fn convex_hull<P: HullPoints + ?Sized>(pts: &P) -> Result<ConvexHull, HullError> {
    let n = pts.len();
    if n < 4 {
        return Err(HullError::TooFewPoints { count: n });
    }
    assert!(n < NONE as usize, "too many points for the hull ({n})");
    let simplex = initial_simplex(pts)?;
    let mut b = Builder::new(pts);
    b.start(simplex);
    b.run();
    Ok(b.output())
}

/// Squared float distance of `x` from the line through `a` with direction `d`
/// (un-normalised; heuristic only).
#[inline]
fn line_dist2(a: DVec3, d: DVec3, x: DVec3) -> f64 {
    d.cross(x - a).length_squared()
}

/// Finds four affinely independent points: a first pair by float extremes,
/// each further point by float distance, every choice confirmed exactly and,
/// if the heuristic choice fails, replaced by an exact scan of all points.
fn initial_simplex<P: HullPoints + ?Sized>(pts: &P) -> Result<[usize; 4], HullError> {
    let n = pts.len();
    let xyz = |i: usize| pts.coords(i);
    // Extremes along the axes; the pair furthest apart.
    let mut ext = [0usize; 6];
    let mut ext_val = [xyz(0); 6];
    for i in 1..n {
        let c = xyz(i);
        for k in 0..3 {
            if c[k] < ext_val[2 * k][k] {
                ext[2 * k] = i;
                ext_val[2 * k] = c;
            }
            if c[k] > ext_val[2 * k + 1][k] {
                ext[2 * k + 1] = i;
                ext_val[2 * k + 1] = c;
            }
        }
    }
    let mut best = (f64::NEG_INFINITY, ext[0], ext[1]);
    for s in 0..6 {
        for t in s + 1..6 {
            let d = (ext_val[s] - ext_val[t]).length_squared();
            if d > best.0 {
                best = (d, ext[s], ext[t]);
            }
        }
    }
    let a = best.1;
    let mut b = best.2;
    if pts.coincident(a, b) {
        b = (0..n)
            .find(|&i| !pts.coincident(a, i))
            .ok_or(HullError::AllCoincident { count: n })?;
    }
    // Third point: furthest from the line ab.
    let (ca, cb) = (xyz(a), xyz(b));
    let dir = cb - ca;
    let mut c = (0..n)
        .max_by(|&i, &j| {
            line_dist2(ca, dir, xyz(i))
                .total_cmp(&line_dist2(ca, dir, xyz(j)))
                .then(j.cmp(&i))
        })
        .unwrap_or(0);
    if pts.collinear(a, b, c) {
        c = (0..n)
            .find(|&i| !pts.collinear(a, b, i))
            .ok_or(HullError::AllCollinear { count: n })?;
    }
    // Fourth point: furthest from the plane abc.
    let normal = (cb - ca).cross(xyz(c) - ca);
    let mut d = (0..n)
        .max_by(|&i, &j| {
            normal
                .dot(xyz(i) - ca)
                .abs()
                .total_cmp(&normal.dot(xyz(j) - ca).abs())
                .then(j.cmp(&i))
        })
        .unwrap_or(0);
    if pts.orient(a, b, c, d) == Sign::Zero {
        d = (0..n)
            .find(|&i| pts.orient(a, b, c, i) != Sign::Zero)
            .ok_or(HullError::AllCoplanar { count: n })?;
    }
    Ok([a, b, c, d])
}

impl<'a, P: HullPoints + ?Sized> Builder<'a, P> {
    fn new(pts: &'a P) -> Self {
        let n = pts.len();
        Builder {
            pts,
            xyz: (0..n).map(|i| pts.coords(i)).collect(),
            faces: Vec::new(),
            free: Vec::new(),
            next: vec![NONE; n],
            pending: Vec::new(),
            epoch: 0,
            visible: Vec::new(),
            horizon: Vec::new(),
            new_faces: Vec::new(),
            orphans: Vec::new(),
            start_slot: vec![NONE; n],
        }
    }

    #[inline]
    fn orient_face(&self, f: u32, x: u32) -> Sign {
        let v = self.faces[f as usize].v;
        self.pts
            .orient(v[0] as usize, v[1] as usize, v[2] as usize, x as usize)
    }

    /// Creates a face (reusing a free slot) with no neighbours and an empty
    /// outside set.
    fn new_face(&mut self, v: [u32; 3]) -> u32 {
        let (a, b, c) = (
            self.xyz[v[0] as usize],
            self.xyz[v[1] as usize],
            self.xyz[v[2] as usize],
        );
        let normal = (b - a).cross(c - a);
        let face = Face {
            v,
            adj: [NONE; 3],
            normal,
            offset: normal.dot(a),
            head: NONE,
            far: NONE,
            far_dist: f64::NEG_INFINITY,
            alive: true,
            mark: 0,
            visible: false,
        };
        match self.free.pop() {
            Some(id) => {
                self.faces[id as usize] = face;
                id
            }
            None => {
                self.faces.push(face);
                (self.faces.len() - 1) as u32
            }
        }
    }

    /// Adds point `x` (strictly outside face `f`) to `f`'s outside set.
    #[inline]
    fn add_outside(&mut self, f: u32, x: u32) {
        let dist = {
            let face = &self.faces[f as usize];
            face.normal.dot(self.xyz[x as usize]) - face.offset
        };
        let face = &mut self.faces[f as usize];
        if face.head == NONE {
            self.pending.push(f);
        }
        self.next[x as usize] = face.head;
        face.head = x;
        if face.far == NONE || dist > face.far_dist {
            face.far = x;
            face.far_dist = dist;
        }
    }

    /// Builds the initial tetrahedron and distributes all points.
    fn start(&mut self, s: [usize; 4]) {
        let s = s.map(|i| i as u32);
        // Faces opposite each vertex, oriented with the opposite vertex below.
        let mut ids = [0u32; 4];
        for (k, id) in ids.iter_mut().enumerate() {
            let others: Vec<u32> = (0..4).filter(|&j| j != k).map(|j| s[j]).collect();
            let mut v = [others[0], others[1], others[2]];
            let o = self
                .pts
                .orient(v[0] as usize, v[1] as usize, v[2] as usize, s[k] as usize);
            debug_assert_ne!(o, Sign::Zero);
            if o == Sign::Positive {
                v.swap(1, 2);
            }
            *id = self.new_face(v);
        }
        // Adjacency: the face across edge a → b contains the edge b → a.
        for &f in &ids {
            for i in 0..3 {
                let v = self.faces[f as usize].v;
                let (a, b) = (v[i], v[(i + 1) % 3]);
                let g = ids
                    .iter()
                    .copied()
                    .find(|&g| {
                        let w = self.faces[g as usize].v;
                        g != f && (0..3).any(|j| w[j] == b && w[(j + 1) % 3] == a)
                    })
                    .expect("tetrahedron adjacency");
                self.faces[f as usize].adj[i] = g;
            }
        }
        // Distribute the points: each goes to the first face it strictly sees.
        for x in 0..self.xyz.len() as u32 {
            if s.contains(&x) {
                continue;
            }
            if let Some(&f) = ids
                .iter()
                .find(|&&f| self.orient_face(f, x) == Sign::Positive)
            {
                self.add_outside(f, x);
            }
        }
    }

    fn run(&mut self) {
        while let Some(f) = self.pending.pop() {
            let face = &self.faces[f as usize];
            if !face.alive || face.head == NONE {
                continue;
            }
            let eye = face.far;
            self.insert(f, eye);
        }
    }

    /// Inserts `eye`, strictly outside face `f0`.
    fn insert(&mut self, f0: u32, eye: u32) {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            for f in &mut self.faces {
                f.mark = 0;
            }
            self.epoch = 1;
        }
        let epoch = self.epoch;
        // 1. Visible faces (connected, found by search from f0) and horizon.
        self.visible.clear();
        self.horizon.clear();
        {
            let f = &mut self.faces[f0 as usize];
            f.mark = epoch;
            f.visible = true;
        }
        self.visible.push(f0);
        let mut k = 0;
        while k < self.visible.len() {
            let f = self.visible[k];
            k += 1;
            for i in 0..3 {
                let nb = self.faces[f as usize].adj[i];
                let seen = self.faces[nb as usize].mark == epoch;
                let vis = if seen {
                    self.faces[nb as usize].visible
                } else {
                    let vis = self.orient_face(nb, eye) == Sign::Positive;
                    let g = &mut self.faces[nb as usize];
                    g.mark = epoch;
                    g.visible = vis;
                    if vis {
                        self.visible.push(nb);
                    }
                    vis
                };
                if !vis {
                    let v = self.faces[f as usize].v;
                    self.horizon.push(HorizonEdge {
                        a: v[i],
                        b: v[(i + 1) % 3],
                        old: f,
                        nb,
                    });
                }
            }
        }
        // 2. Orphaned outside points; delete the visible faces.
        self.orphans.clear();
        for idx in 0..self.visible.len() {
            let f = self.visible[idx];
            let mut x = self.faces[f as usize].head;
            while x != NONE {
                if x != eye {
                    self.orphans.push(x);
                }
                x = self.next[x as usize];
            }
            let face = &mut self.faces[f as usize];
            face.alive = false;
            face.head = NONE;
            self.free.push(f);
        }
        // 3. The cone of new faces from the horizon to the eye.
        self.new_faces.clear();
        for h in 0..self.horizon.len() {
            let HorizonEdge { a, b, old, nb } = self.horizon[h];
            let nf = self.new_face([a, b, eye]);
            self.faces[nf as usize].adj[0] = nb;
            let g = &mut self.faces[nb as usize];
            let j = (0..3)
                .find(|&j| g.adj[j] == old && g.v[j] == b)
                .expect("horizon neighbour");
            g.adj[j] = nf;
            self.start_slot[a as usize] = nf;
            self.new_faces.push(nf);
        }
        for h in 0..self.new_faces.len() {
            let nf = self.new_faces[h];
            let b = self.faces[nf as usize].v[1];
            let g = self.start_slot[b as usize];
            debug_assert_ne!(g, NONE);
            self.faces[nf as usize].adj[1] = g;
            self.faces[g as usize].adj[2] = nf;
        }
        for h in 0..self.new_faces.len() {
            let a = self.faces[self.new_faces[h] as usize].v[0];
            self.start_slot[a as usize] = NONE;
        }
        // 4. Orphans go to the first new face they strictly see; the others
        //    are inside or on the new hull.
        for o in 0..self.orphans.len() {
            let x = self.orphans[o];
            for h in 0..self.new_faces.len() {
                let nf = self.new_faces[h];
                if self.orient_face(nf, x) == Sign::Positive {
                    self.add_outside(nf, x);
                    break;
                }
            }
        }
    }

    /// Merges coplanar neighbours into maximal faces and keeps the corners.
    fn output(&self) -> ConvexHull {
        let nf = self.faces.len();
        // Union-find over faces (dead faces stay singletons and are ignored).
        let mut parent: Vec<u32> = (0..nf as u32).collect();
        fn find(parent: &mut [u32], mut x: u32) -> u32 {
            while parent[x as usize] != x {
                let p = parent[parent[x as usize] as usize];
                parent[x as usize] = p;
                x = p;
            }
            x
        }
        for f in 0..nf as u32 {
            let face = &self.faces[f as usize];
            if !face.alive {
                continue;
            }
            for i in 0..3 {
                let g = face.adj[i];
                if g < f {
                    continue; // each pair once
                }
                let gf = &self.faces[g as usize];
                let j = (0..3)
                    .find(|&j| gf.adj[j] == f)
                    .expect("symmetric adjacency");
                let apex = gf.v[(j + 2) % 3];
                if self.orient_face(f, apex) == Sign::Zero {
                    let (rf, rg) = (find(&mut parent, f), find(&mut parent, g));
                    if rf != rg {
                        parent[rf.max(rg) as usize] = rf.min(rg);
                    }
                }
            }
        }
        // Boundary edges of each merged group, bucketed by group.
        let mut edges: Vec<(u32, u32, u32)> = Vec::new(); // (root, from, to)
        for f in 0..nf as u32 {
            let face = &self.faces[f as usize];
            if !face.alive {
                continue;
            }
            let rf = find(&mut parent, f);
            for i in 0..3 {
                if find(&mut parent, face.adj[i]) != rf {
                    edges.push((rf, face.v[i], face.v[(i + 1) % 3]));
                }
            }
        }
        edges.sort_unstable();
        // Number of distinct maximal faces at each vertex (each boundary
        // vertex appears once per face cycle).
        let n = self.xyz.len();
        let mut count = vec![0u32; n];
        for &(_, from, _) in &edges {
            count[from as usize] += 1;
        }
        let mut succ = vec![NONE; n];
        let mut faces: Vec<Vec<usize>> = Vec::new();
        let mut s = 0;
        while s < edges.len() {
            let root = edges[s].0;
            let mut e = s;
            while e < edges.len() && edges[e].0 == root {
                let (_, from, to) = edges[e];
                debug_assert_eq!(succ[from as usize], NONE, "face boundary not simple");
                succ[from as usize] = to;
                e += 1;
            }
            // Walk the cycle from the smallest vertex.
            let first = edges[s..e].iter().map(|t| t.1).min().unwrap_or(0);
            let mut cycle = Vec::new();
            let mut x = first;
            let mut steps = 0;
            loop {
                if count[x as usize] >= 3 {
                    cycle.push(x as usize);
                }
                steps += 1;
                x = succ[x as usize];
                if x == first || x == NONE || steps > e - s {
                    break;
                }
            }
            debug_assert_eq!(steps, e - s, "face boundary is not a single cycle");
            for &(_, from, _) in &edges[s..e] {
                succ[from as usize] = NONE;
            }
            // Start at the smallest kept corner.
            if let Some(m) = (0..cycle.len()).min_by_key(|&k| cycle[k]) {
                cycle.rotate_left(m);
            }
            debug_assert!(cycle.len() >= 3);
            faces.push(cycle);
            s = e;
        }
        faces.sort_unstable();
        let mut vertices: Vec<usize> = (0..n).filter(|&v| count[v] >= 3).collect();
        vertices.sort_unstable();
        ConvexHull { vertices, faces }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hull::{FloatPoints, PairwiseSums};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::collections::HashSet;

    fn unit_cube() -> Vec<DVec3> {
        (0..8)
            .map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect()
    }

    fn boxed(lo: DVec3, hi: DVec3) -> Vec<DVec3> {
        (0..8)
            .map(|i| {
                DVec3::new(
                    if i & 1 == 0 { lo.x } else { hi.x },
                    if i & 2 == 0 { lo.y } else { hi.y },
                    if i & 4 == 0 { lo.z } else { hi.z },
                )
            })
            .collect()
    }

    /// Checks the hull against the point set: every face is convex, planar
    /// and ccw outward, every point is inside or on every face plane (all
    /// exactly), the edges pair up, Euler's formula holds, and the corners
    /// are exactly the face vertices.
    fn check<P: HullPoints + ?Sized>(pts: &P, h: &ConvexHull) {
        let n = pts.len();
        let mut edge_set = HashSet::new();
        let mut used = HashSet::new();
        for f in &h.faces {
            assert!(f.len() >= 3, "face {f:?}");
            let k = f.len();
            for i in 0..k {
                // Strictly convex corners, all in one plane.
                let (a, b, c) = (f[i], f[(i + 1) % k], f[(i + 2) % k]);
                assert!(!pts.collinear(a, b, c), "collinear corners in {f:?}");
                assert!(edge_set.insert((a, b)), "edge {a}->{b} twice");
                used.insert(a);
            }
            let (a, b, c) = (f[0], f[1], f[2]);
            for &x in f.iter() {
                assert_eq!(pts.orient(a, b, c, x), Sign::Zero, "non-planar face");
            }
            for x in 0..n {
                assert_ne!(
                    pts.orient(a, b, c, x),
                    Sign::Positive,
                    "point {x} outside {f:?}"
                );
            }
            // Some point strictly inside (the hull has volume).
            assert!((0..n).any(|x| pts.orient(a, b, c, x) == Sign::Negative));
        }
        for &(a, b) in &edge_set {
            assert!(edge_set.contains(&(b, a)), "unpaired edge {a}->{b}");
        }
        let v = h.vertices.len() as i64;
        let e = edge_set.len() as i64 / 2;
        let fc = h.faces.len() as i64;
        assert_eq!(v - e + fc, 2, "Euler");
        let mut used: Vec<usize> = used.into_iter().collect();
        used.sort_unstable();
        assert_eq!(used, h.vertices);
        assert!(h.vertices.windows(2).all(|w| w[0] < w[1]));
        // Outward orientation: positive signed volume (float, from centroid).
        let c: DVec3 =
            h.vertices.iter().map(|&i| pts.coords(i)).sum::<DVec3>() / h.vertices.len() as f64;
        let faces = h.faces.iter().map(|f| &f[..]);
        let vol = crate::mesh::six_signed_volume(faces, |i| pts.coords(i) - c);
        assert!(vol > 0.0, "faces must be ccw seen from outside");
    }

    fn hull_of(p: &[DVec3]) -> ConvexHull {
        let h = convex_hull(&FloatPoints(p)).expect("hull");
        check(&FloatPoints(p), &h);
        h
    }

    fn face_sizes(h: &ConvexHull) -> Vec<usize> {
        let mut s: Vec<usize> = h.faces.iter().map(|f| f.len()).collect();
        s.sort_unstable();
        s
    }

    #[test]
    fn unit_cube_six_quads() {
        let h = hull_of(&unit_cube());
        assert_eq!(h.vertices, (0..8).collect::<Vec<_>>());
        assert_eq!(face_sizes(&h), vec![4; 6]);
    }

    #[test]
    fn tessellated_cube() {
        let mut p = Vec::new();
        for i in 0..4 {
            for j in 0..4 {
                for k in 0..4 {
                    p.push(DVec3::new(i as f64, j as f64, k as f64) / 3.0);
                }
            }
        }
        let h = hull_of(&p);
        assert_eq!(face_sizes(&h), vec![4; 6]);
        assert_eq!(h.vertices.len(), 8);
        let corners: Vec<usize> = (0..64)
            .filter(|&i| {
                let c = p[i];
                [c.x, c.y, c.z].iter().all(|&x| x == 0.0 || x == 1.0)
            })
            .collect();
        assert_eq!(h.vertices, corners);
        // The same with shuffled order and duplicates.
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let mut q = p.clone();
        q.extend_from_slice(&p);
        for i in (1..q.len()).rev() {
            q.swap(i, rng.random_range(0..=i));
        }
        let h = hull_of(&q);
        assert_eq!(face_sizes(&h), vec![4; 6]);
        assert_eq!(h.vertices.len(), 8);
    }

    #[test]
    fn cube_with_points_on_faces_edges_and_center() {
        let mut p = unit_cube();
        p.push(DVec3::splat(0.5));
        p.push(DVec3::new(0.5, 0.5, 0.0));
        p.push(DVec3::new(0.5, 0.0, 0.0));
        p.push(DVec3::new(1.0, 0.25, 1.0));
        p.push(DVec3::new(0.1, 1.0, 0.7));
        let h = hull_of(&p);
        assert_eq!(h.vertices, (0..8).collect::<Vec<_>>());
        assert_eq!(face_sizes(&h), vec![4; 6]);
    }

    #[test]
    fn tetrahedron() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::splat(0.1)];
        let h = hull_of(&p);
        assert_eq!(h.vertices, vec![0, 1, 2, 3]);
        assert_eq!(face_sizes(&h), vec![3; 4]);
        assert!(h.faces.contains(&vec![0, 2, 1]));
        assert!(h.faces.contains(&vec![1, 2, 3]));
    }

    #[test]
    fn random_ball() {
        let mut rng = ChaCha8Rng::seed_from_u64(42);
        let mut p = Vec::new();
        while p.len() < 2000 {
            let x = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            if x.length_squared() <= 1.0 {
                p.push(x);
            }
        }
        let h = hull_of(&p);
        assert!(h.faces.iter().all(|f| f.len() == 3));
        // Deterministic.
        assert_eq!(h, hull_of(&p));
    }

    #[test]
    fn sphere_200() {
        let n = 200;
        let p = crate::hull::fibonacci_sphere(n);
        let h = hull_of(&p);
        assert_eq!(h.vertices.len(), n);
    }

    #[test]
    fn errors() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y];
        assert_eq!(
            convex_hull(&FloatPoints(&p)),
            Err(HullError::TooFewPoints { count: 3 })
        );
        let p = [DVec3::splat(0.3); 10];
        assert_eq!(
            convex_hull(&FloatPoints(&p)),
            Err(HullError::AllCoincident { count: 10 })
        );
        let p: Vec<DVec3> = (0..10)
            .map(|i| DVec3::new(1.0, 2.0, 3.0) * (i % 4) as f64 * 0.25)
            .collect();
        assert_eq!(
            convex_hull(&FloatPoints(&p)),
            Err(HullError::AllCollinear { count: 10 })
        );
        let p: Vec<DVec3> = (0..20)
            .map(|i| DVec3::new((i % 5) as f64 * 0.125, (i / 5) as f64 * 0.375, 0.0))
            .map(|v| DVec3::new(v.x, v.y, v.x + 2.0 * v.y))
            .collect();
        assert_eq!(
            convex_hull(&FloatPoints(&p)),
            Err(HullError::AllCoplanar { count: 20 })
        );
        // Degeneracies hidden by rounding in pairwise sums.
        let a = [DVec3::splat(0.1), DVec3::splat(0.2)];
        let b = [DVec3::splat(0.2), DVec3::splat(0.1)];
        let s = PairwiseSums::new(&a, &b);
        // The real sums 0.3, 0.2, 0.4, 0.3 (per coordinate) lie on a line.
        assert_eq!(convex_hull(&s), Err(HullError::AllCollinear { count: 4 }));
        let a = [DVec3::splat(0.1); 2];
        let b = [DVec3::splat(0.2); 3];
        assert_eq!(
            convex_hull(&PairwiseSums::new(&a, &b)),
            Err(HullError::AllCoincident { count: 6 })
        );
    }

    #[test]
    fn duplicated_points() {
        let mut p = unit_cube();
        let q = p.clone();
        for _ in 0..5 {
            p.extend_from_slice(&q);
        }
        let h = hull_of(&p);
        assert_eq!(face_sizes(&h), vec![4; 6]);
        assert_eq!(h.vertices.len(), 8);
        // One representative per corner.
        let mut seen: Vec<DVec3> = h.vertices.iter().map(|&i| p[i]).collect();
        seen.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
        seen.dedup();
        assert_eq!(seen.len(), 8);
    }

    fn sum_hull(p: &[DVec3], q: &[DVec3]) -> ConvexHull {
        let s = PairwiseSums::new(p, q);
        let h = convex_hull(&s).expect("hull");
        check(&s, &h);
        h
    }

    #[test]
    fn pairwise_cube_plus_cube() {
        let c = unit_cube();
        let h = sum_hull(&c, &c);
        assert_eq!(face_sizes(&h), vec![4; 6]);
        assert_eq!(h.vertices.len(), 8);
        let s = PairwiseSums::new(&c, &c);
        for &v in &h.vertices {
            let (i, j) = s.split(v);
            assert_eq!(
                c[i], c[j],
                "a corner of 2C is the sum of a corner with itself"
            );
        }
    }

    #[test]
    fn pairwise_cube_plus_tetrahedron() {
        let c = unit_cube();
        let t = [
            DVec3::ZERO,
            DVec3::new(0.5, 0.0, 0.0),
            DVec3::new(0.0, 0.5, 0.0),
            DVec3::new(0.0, 0.0, 0.5),
        ];
        let h = sum_hull(&c, &t);
        // Count by the Gaussian maps: the tetrahedron's normals are -x, -y,
        // -z (shared with the cube) and (1,1,1); its arcs from (1,1,1) to
        // -x, -y, -z cross the cube's arcs between +y/+z, +z/+x, +x/+y. So
        // the sum has 6 (cube normals) + 1 + 3 (parallelograms) faces.
        assert_eq!(h.faces.len(), 6 + 1 + 3);
        // Same result with awkward scaling.
        let c2: Vec<DVec3> = c
            .iter()
            .map(|v| *v * 0.1 + DVec3::splat(1e6 + 0.1))
            .collect();
        let t2: Vec<DVec3> = t.iter().map(|v| *v * 0.3 - DVec3::splat(0.7)).collect();
        assert_eq!(sum_hull(&c2, &t2).faces.len(), 10);
    }

    #[test]
    fn pairwise_box_plus_box_awkward() {
        let b1 = boxed(
            DVec3::new(0.1, 0.3, 1e6 + 0.1),
            DVec3::new(0.7, 1e6 + 0.3, 1e6 + 0.9),
        );
        let b2 = boxed(
            DVec3::new(-0.3, 1e-6, 0.1),
            DVec3::new(1e-6 + 0.1, 0.3, 1.7),
        );
        let h = sum_hull(&b1, &b2);
        assert_eq!(face_sizes(&h), vec![4; 6]);
        assert_eq!(h.vertices.len(), 8);
        // Tiny boxes.
        let b3 = boxed(DVec3::splat(1e-6), DVec3::new(3e-6, 1.1e-6, 7e-6));
        let h = sum_hull(&b1, &b3);
        assert_eq!(face_sizes(&h), vec![4; 6]);
    }

    #[test]
    fn pairwise_random_sets_far_and_small() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut set = |center: f64, scale: f64, n: usize| -> Vec<DVec3> {
            (0..n)
                .map(|_| {
                    DVec3::new(
                        rng.random_range(-1.0..1.0),
                        rng.random_range(-1.0..1.0),
                        rng.random_range(-1.0..1.0),
                    ) * scale
                        + DVec3::splat(center)
                })
                .collect()
        };
        let p = set(1e6, 1.0, 30);
        let q = set(1e-6, 1e-6, 30);
        let hp = hull_of(&p);
        let hq = hull_of(&q);
        let h = sum_hull(&p, &q);
        // Every face of P ⊕ Q is a translate of a face of P or Q, or a
        // parallelogram (edge ⊕ edge): for generic sets all faces of the
        // summands appear, and the number of faces is
        // F(P) + F(Q) + (number of parallelograms).
        let quads = h.faces.iter().filter(|f| f.len() == 4).count();
        let tris = h.faces.iter().filter(|f| f.len() == 3).count();
        assert_eq!(quads + tris, h.faces.len());
        assert_eq!(tris, hp.faces.len() + hq.faces.len());
        // Vertex count: each corner is the sum of a P corner and a Q corner.
        let s = PairwiseSums::new(&p, &q);
        for &v in &h.vertices {
            let (i, j) = s.split(v);
            assert!(hp.vertices.contains(&i) && hq.vertices.contains(&j));
        }
    }

    #[test]
    fn degenerate_lattice_stress() {
        // Small lattices: many exactly coplanar and collinear points, in
        // random order, as plain points and as pairwise sums with awkward
        // (inexact) scaling.
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for round in 0..60 {
            let k = 3 + round % 4;
            let mut grid = |n: usize, scale: f64, shift: f64| -> Vec<DVec3> {
                (0..n)
                    .map(|_| {
                        DVec3::new(
                            rng.random_range(0..k) as f64,
                            rng.random_range(0..k) as f64,
                            rng.random_range(0..k) as f64,
                        ) * scale
                            + DVec3::splat(shift)
                    })
                    .collect()
            };
            let p = grid(40, 1.0, 0.0);
            if let Ok(h) = convex_hull(&FloatPoints(&p)) {
                check(&FloatPoints(&p), &h);
            }
            let a = grid(12, 0.1, 1e6 + 0.1);
            let b = grid(12, 0.3, -0.7);
            let s = PairwiseSums::new(&a, &b);
            if let Ok(h) = convex_hull(&s) {
                check(&s, &h);
            }
        }
    }

    /// 482 × 482 pairwise sums of two ellipsoids (UV spheres with 20 rings of
    /// 24 vertices plus poles), the second rotated.
    fn ellipsoids() -> (Vec<DVec3>, Vec<DVec3>) {
        let uv = |a: f64, b: f64, c: f64| -> Vec<DVec3> {
            let mut v = vec![DVec3::new(0.0, 0.0, c), DVec3::new(0.0, 0.0, -c)];
            for r in 1..=20 {
                let th = std::f64::consts::PI * r as f64 / 21.0;
                for s in 0..24 {
                    let ph = 2.0 * std::f64::consts::PI * s as f64 / 24.0;
                    v.push(DVec3::new(
                        a * th.sin() * ph.cos(),
                        b * th.sin() * ph.sin(),
                        c * th.cos(),
                    ));
                }
            }
            v
        };
        let p = uv(1.0, 0.5, 0.5);
        let rot = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, 0.7, 1.1);
        let q = uv(1.0, 0.5, 0.5).into_iter().map(|x| rot * x).collect();
        (p, q)
    }

    #[test]
    fn pairwise_ellipsoids_small() {
        let (p, q) = ellipsoids();
        let p: Vec<DVec3> = p.into_iter().step_by(7).collect();
        let q: Vec<DVec3> = q.into_iter().step_by(5).collect();
        sum_hull(&p, &q);
    }

    #[test]
    #[ignore = "timing: run with --release -- --ignored --nocapture"]
    fn timing_ellipsoid_pairwise_sums() {
        let (p, q) = ellipsoids();
        assert_eq!(p.len(), 482);
        let s = PairwiseSums::new(&p, &q);
        let t = std::time::Instant::now();
        let h = convex_hull(&s).unwrap();
        let dt = t.elapsed();
        println!(
            "{} points -> {} vertices, {} faces in {:?}",
            s.len(),
            h.vertices.len(),
            h.faces.len(),
            dt
        );
    }
}
