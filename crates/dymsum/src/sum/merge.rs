//! Merging facets into the true faces of `P ⊕ Q`, and checking the result.
//!
//! The facets of the (symbolically perturbed) overlay tile the boundary of
//! the sum. Where the unperturbed input is degenerate several facets are
//! coplanar: they share one normal direction. Two facets are coplanar
//! exactly when their overlay vertices coincide without perturbation, which
//! happens in three ways, each decided exactly on the float normals:
//!
//! * a face normal of P equals a face normal of Q (parallel faces), tested
//!   against the corners of the cell the normal was found in;
//! * the crossing of arcs `(a, b)` of P and `(c, d)` of Q *is* one of the
//!   four endpoints (`det[c, d, a] = 0` etc.: a normal on an arc);
//! * both arcs lie on one great circle (parallel edges): that facet is a
//!   degenerate parallelogram of zero area and is dropped.
//!
//! Groups are the connected components of "coplanar" (union–find). A sum
//! vertex `u + w` is kept iff at least three groups meet at it (otherwise it
//! lies in the middle of an edge or face). Each group becomes one convex
//! polygon: the boundary of the union of its facets, walked edge by edge,
//! with the kept corners only.
//!
//! # Steps and data structures (no hashing)
//!
//! 1. Sum vertices `(u, w)` get dense ids in lexicographic order, bucketed
//!    by `u` (a bucket holds the few `w` paired with `u`); facets become
//!    slices of one flat corner array.
//! 2. General position (no coplanar or degenerate facet, every vertex on at
//!    least three facets): the facets *are* the faces; step 3 is skipped.
//!    This shortcut is trusted only after the exact check of step 4; if the
//!    check fails, the full merge runs (and names a broken facet complex).
//! 3. Otherwise the directed-edge index of `polytope::topology` gives the
//!    facet across each facet edge (binary search in a vertex's row); the
//!    union–find, the corner test and each face's boundary walk use it.
//! 4. Validation (`super::repair::validated_mesh`): the vertices are the float sums, so a
//!    face of four or more corners may be bent by rounding. Each bent face
//!    is folded along the outer side of its corners' hull (a parallelogram:
//!    the diagonal that folds outward, from the one `orient3d` that found it
//!    bent), and the result must pass the exact convexity check
//!    ([`super::validate::check_convex_mesh`]). It then *is* the exact hull
//!    of the rounded vertices (every vertex a strict corner, every edge
//!    strictly convex), found in linear time. Where the check fails, the
//!    defects are repaired locally: reflex edges between triangles are
//!    flipped to the other diagonal (on flat models such as the paper's
//!    ellipse, rounding makes a few dozen of them), and what flips leave
//!    (flat edges, a vertex pushed inside) is replaced by the outer side of
//!    the hull of the faces around it; a vertex left out must lie inside
//!    the checked result. Only if that fails too is the hull built from
//!    scratch, `O(V log V)`.
//!
//! # Complexity
//!
//! `O(F log d)` for `F` facets and vertex degree `d`, plus the exact check
//! (`O(F)` predicates, adaptive only near flat folds) and, rarely, the hull.
//!
//! # Degeneracies
//!
//! Parallel faces, normals on arcs and parallel edges (the three cases
//! above), exactly planar rounded faces (no fold), faces bent by rounding,
//! sums whose rounded vertices are no longer in convex position (hull),
//! and every scale (float normals of the fold are taken in the check's
//! power-of-two scaled frame, so they neither underflow nor depend on the
//! scale).

use super::{Operands, Overlay};
use crate::kernel::predicates::{det3, same_direction, sos_det3};
use crate::kernel::Sign;
use crate::mesh::PolygonMesh;
use crate::polytope::topology::DirectedEdges;
use crate::sanity::SanityError;
use glam::DVec3;

/// A vertex of the sum as `(vertex of P, vertex of Q)`.
type SumVertex = (u32, u32);

pub(crate) struct UnionFind(Vec<u32>);

impl UnionFind {
    fn new(n: usize) -> Self {
        UnionFind((0..n as u32).collect())
    }
    pub(crate) fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let p = self.0[x as usize];
            self.0[x as usize] = self.0[p as usize];
            x = p;
        }
        x
    }
    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.0[ra.max(rb) as usize] = ra.min(rb);
        }
    }
}

/// The merged mesh of `P ⊕ Q` over the float sums of its vertices, and
/// whether every coordinate is the exact sum (no rounding anywhere).
pub(crate) struct Merged {
    /// The mesh.
    pub mesh: PolygonMesh,
    /// `true` when every vertex coordinate is exact, so the mesh must pass
    /// [`super::validate::check_convex_mesh`] as is.
    pub exact: bool,
    /// `true` when the faces are the facets (`facets_as_faces`), not merged.
    pub shortcut: bool,
}

/// The sum vertices `(u, w)` used by the facets, numbered densely in
/// lexicographic order: per vertex `u` of P (a bucket), the sorted vertices
/// `w` of Q it is paired with. No hashing: a lookup is a binary search in a
/// bucket of a few entries.
struct SumVertexIndex {
    /// `start[u]..start[u + 1]`: the ids of the vertices `(u, ·)`.
    start: Vec<u32>,
    /// The `w` of each id.
    w: Vec<u32>,
}

impl SumVertexIndex {
    fn new(p_vertices: usize, keys: &[SumVertex]) -> Self {
        let mut start = vec![0u32; p_vertices + 1];
        for &(u, _) in keys {
            start[u as usize + 1] += 1;
        }
        for u in 0..p_vertices {
            start[u + 1] += start[u];
        }
        let mut fill = start.clone();
        let mut w = vec![0u32; keys.len()];
        for &(u, wq) in keys {
            w[fill[u as usize] as usize] = wq;
            fill[u as usize] += 1;
        }
        // Sort and deduplicate each bucket, compacting in place.
        let mut out = 0usize;
        let mut lo = 0usize;
        for u in 0..p_vertices {
            let hi = start[u + 1] as usize;
            let bucket = &mut w[lo..hi];
            bucket.sort_unstable();
            let begin = out;
            for k in lo..hi {
                if out == begin || w[out - 1] != w[k] {
                    w[out] = w[k];
                    out += 1;
                }
            }
            start[u] = begin as u32;
            lo = hi;
        }
        start[p_vertices] = out as u32;
        w.truncate(out);
        SumVertexIndex { start, w }
    }
    fn len(&self) -> usize {
        self.w.len()
    }
    fn id(&self, (u, w): SumVertex) -> u32 {
        let (lo, hi) = (self.start[u as usize], self.start[u as usize + 1]);
        let k = self.w[lo as usize..hi as usize]
            .binary_search(&w)
            .expect("every corner was indexed");
        lo + k as u32
    }
    /// The `(u, w)` of an id (`u` by binary search over the buckets).
    fn key(&self, id: u32) -> SumVertex {
        let u = self.start.partition_point(|&s| s <= id) - 1;
        (u as u32, self.w[id as usize])
    }
}

/// The corners of every facet as dense sum-vertex ids, in one flat array
/// (`corners[first[i]..first[i + 1]]` for facet `i`), counter-clockwise
/// about the facet's outward normal.
struct FlatFacets {
    first: Vec<u32>,
    corners: Vec<u32>,
    index: SumVertexIndex,
}

impl FlatFacets {
    fn new(ops: &Operands, overlay: &Overlay) -> Self {
        let mut first = Vec::with_capacity(overlay.len() + 1);
        let mut keys: Vec<SumVertex> = Vec::with_capacity(overlay.len() * 4);
        first.push(0);
        for (f, &w) in overlay.fv.iter().enumerate() {
            keys.extend(ops.p.face(f).iter().map(|&u| (u, w)));
            first.push(keys.len() as u32);
        }
        for (g, &u) in overlay.vf.iter().enumerate() {
            keys.extend(ops.q.face(g).iter().map(|&w| (u, w)));
            first.push(keys.len() as u32);
        }
        let (vp, vq) = (ops.view_p(), ops.view_q());
        for &(e, e2) in &overlay.ee {
            let [u1, u2] = ops.p.edge(e as usize).vertices;
            let [w1, w2] = ops.q.edge(e2 as usize).vertices;
            let (a, b) = vp.edge_arc(e);
            let (c, _) = vq.edge_arc(e2);
            // Edge directions are a×b and c×d; the cycle below turns about
            // their cross product, the outward normal iff det[a,b,c] < 0.
            let cyc = [(u1, w1), (u2, w1), (u2, w2), (u1, w2)];
            if sos_det3(&a, &b, &c).is_negative() {
                keys.extend(cyc);
            } else {
                keys.extend(cyc.iter().rev());
            }
            first.push(keys.len() as u32);
        }
        let index = SumVertexIndex::new(ops.p.vertex_count(), &keys);
        let corners = keys.iter().map(|&k| index.id(k)).collect();
        FlatFacets {
            first,
            corners,
            index,
        }
    }
    fn facet(&self, i: usize) -> &[u32] {
        &self.corners[self.first[i] as usize..self.first[i + 1] as usize]
    }
}

/// A rotation that maps coordinates without rounding: each output
/// coordinate is `±` one input coordinate.
#[derive(Clone, Copy)]
struct SignedPermutation([(usize, f64); 3]);

impl SignedPermutation {
    fn of(pose: &crate::kernel::rotation::Pose) -> Option<Self> {
        let m = pose.rotation.matrix();
        let mut out = [(0, 0.0); 3];
        for (k, slot) in out.iter_mut().enumerate() {
            let row = m.row(k);
            let mut nz = (0..3).filter(|&i| row[i] != 0.0);
            let i = nz.next()?;
            if nz.next().is_some() || row[i].abs() != 1.0 {
                return None;
            }
            *slot = (i, row[i]);
        }
        Some(SignedPermutation(out))
    }
    /// `pose.apply(v)` when it is computed without rounding, else `None`.
    fn exact_posed(self, pose: &crate::kernel::rotation::Pose, v: DVec3) -> Option<DVec3> {
        let r = DVec3::from_array(self.0.map(|(i, s)| s * v[i]));
        let t = pose.translation;
        let out = r + t;
        (0..3).all(|k| exact_sum(r[k], t[k])).then_some(out)
    }
}

/// Whether `fl(a + b)` is exact (and finite), by Knuth's TwoSum.
fn exact_sum(a: f64, b: f64) -> bool {
    let (s, error) = crate::kernel::dd::two_sum(a, b);
    error == 0.0 && s.is_finite()
}

/// Union of the coplanar facets (module docs): returns the union-find,
/// which ee-facets are degenerate (zero area), and whether any facet is
/// coplanar with another or degenerate.
pub(crate) fn coplanar_groups(ops: &Operands, overlay: &Overlay) -> (UnionFind, Vec<bool>, bool) {
    coplanar_groups_certified(ops, overlay, |_| false, |_| false)
}

/// [`coplanar_groups`] given certificates: `p_inside(f)` says that P's
/// face `f` has its normal certified strictly inside its cell of Q's map,
/// `q_inside(g)` the same of Q's face `g` in P's map (a dynamic sum's lazy
/// margins, `DynamicSum::normal_strictly_inside`). Such a normal lies on
/// no arc of the other map, so (module docs, "Certified normals") its
/// fv-facet is coplanar with no other facet, and an ee-facet whose four
/// normals are all certified is neither degenerate nor coplanar with
/// anything: their exact tests are skipped, and the answer is the same.
pub(crate) fn coplanar_groups_certified(
    ops: &Operands,
    overlay: &Overlay,
    p_inside: impl Fn(u32) -> bool,
    q_inside: impl Fn(u32) -> bool,
) -> (UnionFind, Vec<bool>, bool) {
    let m = overlay.fv.len();
    let n = overlay.vf.len();
    let total = overlay.len();
    let mut uf = UnionFind::new(total);
    let mut degenerate = vec![false; total];
    let mut any = false;
    let (vp, vq) = (ops.view_p(), ops.view_q());
    // P's normals, turned once each and only where an exact test reads
    // them (a turned view rotates on every read, and each normal is read
    // once per fv-facet and per ee-facet at it).
    let mut np: Vec<Option<_>> = vec![None; m];
    let mut normal_p = |f: u32| *np[f as usize].get_or_insert_with(|| vp.normal(f));
    for (f, &w) in overlay.fv.iter().enumerate() {
        if p_inside(f as u32) {
            continue;
        }
        let nf = normal_p(f as u32);
        for r in ops.q.ring(w as usize) {
            if same_direction(&nf, &vq.normal(r.face)) {
                uf.union(f as u32, (m + r.face as usize) as u32);
                any = true;
            }
        }
    }
    for (k, &(e, e2)) in overlay.ee.iter().enumerate() {
        let id = (m + n + k) as u32;
        let [f0, f1] = ops.p.edge(e as usize).faces;
        let [g0, g1] = ops.q.edge(e2 as usize).faces;
        if p_inside(f0) && p_inside(f1) && q_inside(g0) && q_inside(g1) {
            continue;
        }
        let (a, b) = (normal_p(f0), normal_p(f1));
        let (c, d) = (vq.normal(g0), vq.normal(g1));
        let (abc, abd) = (
            det3(&a, &b, &c) == Sign::Zero,
            det3(&a, &b, &d) == Sign::Zero,
        );
        if abc && abd {
            degenerate[id as usize] = true;
            any = true;
            continue;
        }
        let (cda, cdb) = (
            det3(&c, &d, &a) == Sign::Zero,
            det3(&c, &d, &b) == Sign::Zero,
        );
        any |= cda || cdb || abc || abd;
        if cda {
            uf.union(id, f0);
        }
        if cdb {
            uf.union(id, f1);
        }
        if abc {
            uf.union(id, (m + g0 as usize) as u32);
        }
        if abd {
            uf.union(id, (m + g1 as usize) as u32);
        }
    }
    (uf, degenerate, any)
}

/// The float sums of the sum vertices with these ids, and whether every
/// coordinate is exact (no rounding anywhere).
fn vertex_sums(
    ops: &Operands,
    index: &SumVertexIndex,
    ids: impl Iterator<Item = u32>,
) -> (Vec<[f64; 3]>, bool) {
    let mut exact = true;
    let perm = (
        SignedPermutation::of(&ops.pose_p),
        SignedPermutation::of(&ops.pose_q),
    );
    let vertices = ids
        .map(|id| {
            let (u, w) = index.key(id);
            let (pu, qw) = (ops.p_vertex(u), ops.q_vertex(w));
            // Exact when both posed vertices are (and are the ones used) and
            // so is their sum.
            let exact_vertex = || -> Option<bool> {
                let a = perm.0?.exact_posed(&ops.pose_p, ops.p.vertex(u as usize))?;
                let b = perm.1?.exact_posed(&ops.pose_q, ops.q.vertex(w as usize))?;
                Some(a == pu && b == qw && (0..3).all(|k| exact_sum(a[k], b[k])))
            };
            exact = exact && exact_vertex().unwrap_or(false);
            (pu + qw).to_array()
        })
        .collect();
    (vertices, exact)
}

/// The merged mesh when no two facets are coplanar and none is degenerate
/// (the general position case): every facet is a face and every vertex a
/// corner, so the faces are the facets, each started at its smallest
/// corner, which is what [`merged_mesh`] gives too. `None` when a vertex is
/// on fewer than three facets (left to the general merge).
fn facets_as_faces(ops: &Operands, facets: &FlatFacets) -> Option<Merged> {
    let nv = facets.index.len();
    let mut degree = vec![0u32; nv];
    for &c in &facets.corners {
        degree[c as usize] += 1;
    }
    if degree.iter().any(|&d| d < 3) {
        return None;
    }
    let faces = (0..facets.first.len() - 1)
        .map(|i| {
            let f = facets.facet(i);
            let k = (0..f.len()).min_by_key(|&k| f[k]).unwrap_or(0);
            f[k..].iter().chain(&f[..k]).map(|&v| v as usize).collect()
        })
        .collect();
    let (vertices, exact) = vertex_sums(ops, &facets.index, 0..nv as u32);
    Some(Merged {
        mesh: PolygonMesh { vertices, faces },
        exact,
        shortcut: true,
    })
}

/// The merged mesh of `P ⊕ Q` (see the module docs), or why the facet
/// complex could not be merged (an internal inconsistency).
///
/// Flat arrays throughout: the facets' corners are dense sum-vertex ids
/// (`SumVertexIndex`), the facet across each facet edge is found in the
/// directed-edge index of `polytope::topology`, and each face's boundary
/// is walked through the same index. Vertices are numbered in `(u, w)`
/// order and each face starts at its smallest corner.
///
/// With `shortcut`, the general position case skips the merge (see
/// `facets_as_faces`); its result is only trusted after the full exact check
/// of the mesh, and a mesh that fails it is merged again without shortcut.
pub(crate) fn merged_mesh(
    ops: &Operands,
    overlay: &Overlay,
    shortcut: bool,
) -> Result<Merged, String> {
    let total = overlay.len();
    let (mut uf, degenerate, any_coplanar) = coplanar_groups(ops, overlay);
    let facets = FlatFacets::new(ops, overlay);
    if shortcut && !any_coplanar {
        if let Some(merged) = facets_as_faces(ops, &facets) {
            return Ok(merged);
        }
    }
    let nv = facets.index.len();
    let edges = DirectedEdges::from_faces(nv, total, |i| facets.facet(i));
    // The facet across the facet edge `a → b` (the one holding `b → a`).
    let across = |a: usize, b: usize| -> Result<usize, String> {
        edges
            .face_of(b, a)
            .ok_or_else(|| "facet edge without an opposite facet".to_string())
    };
    if edges.repeated_edge().is_some() {
        return Err("facet edge used twice in one direction".into());
    }
    // A degenerate (zero-area) ee-facet lies on a segment. When all its
    // neighbours lie in one face (the segment is inside that face, e.g. the
    // edges of parallel faces that meet end to end) it joins that face;
    // otherwise it lies on an edge of the sum and belongs to no face.
    let mut in_face = degenerate.iter().map(|&d| !d).collect::<Vec<bool>>();
    for i in 0..total {
        if !degenerate[i] {
            continue;
        }
        let mut roots = [0u32; 4];
        let f = facets.facet(i);
        let k_len = f.len();
        for (k, root) in roots.iter_mut().enumerate().take(k_len) {
            let j = across(f[k] as usize, f[(k + 1) % k_len] as usize)?;
            if degenerate[j] {
                return Err("two degenerate facets share an edge".into());
            }
            *root = uf.find(j as u32);
        }
        if roots[..k_len].iter().all(|&r| r == roots[0]) {
            uf.union(i as u32, roots[0]);
            in_face[i] = true;
        }
    }
    let root: Vec<u32> = (0..total).map(|i| uf.find(i as u32)).collect();
    // A sum vertex is a corner iff at least three faces meet there: the
    // facets around `v` are those of the edges leaving it.
    let mut kept = vec![u32::MAX; nv];
    let mut corners = Vec::new();
    let mut around: Vec<u32> = Vec::new();
    for (v, slot) in kept.iter_mut().enumerate() {
        around.clear();
        for pos in edges.start[v]..edges.start[v + 1] {
            let f = edges.face_corner(pos).0;
            if in_face[f] && !around.contains(&root[f]) {
                around.push(root[f]);
            }
        }
        if around.len() >= 3 {
            *slot = corners.len() as u32;
            corners.push(v as u32);
        }
    }
    let (vertices, exact) = vertex_sums(ops, &facets.index, corners.into_iter());
    // Boundary edges of each face: edges whose facet is in a face and whose
    // opposite facet is not in the same one. Per face its smallest boundary
    // vertex (the walk's start), its number of boundary edges and the
    // first facet (in facet order) with a boundary edge.
    let mut boundary = vec![false; edges.target.len()];
    let mut face_start = vec![(u32::MAX, 0usize, u32::MAX); total];
    for v in 0..nv {
        let row = edges.start[v]..edges.start[v + 1];
        for (pos, is_boundary) in row.clone().zip(&mut boundary[row]) {
            let i = edges.face_corner(pos).0;
            if !in_face[i] {
                continue;
            }
            let j = across(v, edges.target[pos])?;
            if in_face[j] && root[j] == root[i] {
                continue;
            }
            *is_boundary = true;
            let s = &mut face_start[root[i] as usize];
            s.0 = s.0.min(v as u32);
            s.1 += 1;
            s.2 = s.2.min(i as u32);
        }
    }
    let mut order: Vec<u32> = (0..total as u32)
        .filter(|&r| face_start[r as usize].1 > 0)
        .collect();
    order.sort_unstable_by_key(|&r| face_start[r as usize].2);
    // The boundary edge of face `r` leaving `v`: exactly one for a disk.
    let next = |r: u32, v: usize| -> Result<usize, String> {
        let mut found = None;
        for pos in edges.start[v]..edges.start[v + 1] {
            if boundary[pos] && root[edges.face_corner(pos).0] == r {
                if found.is_some() {
                    return Err(format!("the facets of face {r} pinch at a vertex"));
                }
                found = Some(edges.target[pos]);
            }
        }
        found.ok_or_else(|| format!("the boundary of face {r} is open"))
    };
    let mut faces = Vec::with_capacity(order.len());
    for r in order {
        let (first, count, _) = face_start[r as usize];
        let first = first as usize;
        let mut face = Vec::new();
        let mut at = first;
        let mut steps = 0;
        loop {
            if kept[at] != u32::MAX {
                face.push(kept[at] as usize);
            }
            at = next(r, at)?;
            steps += 1;
            if at == first || steps > count {
                break;
            }
        }
        if steps != count {
            return Err(format!("the facets of face {r} do not form a disk"));
        }
        if face.len() < 3 {
            return Err(format!("face {r} has {} corners", face.len()));
        }
        faces.push(face);
    }
    Ok(Merged {
        mesh: PolygonMesh { vertices, faces },
        exact,
        shortcut: false,
    })
}

/// Checks the facet complex of an overlay: closed, 2-manifold, consistently
/// oriented (each directed facet edge once, with its reverse once), no
/// pinched sum vertex, Euler characteristic 2 (the shared checks of
/// `polytope::topology` on the flat facets).
pub(crate) fn check_facet_complex(ops: &Operands, overlay: &Overlay) -> Result<(), SanityError> {
    use crate::polytope::topology::{TopologyDefect, Unused};
    let facets = FlatFacets::new(ops, overlay);
    let edges = DirectedEdges::from_faces(facets.index.len(), overlay.len(), |i| facets.facet(i));
    let key = |v: usize| facets.index.key(v as u32);
    edges.check_sphere(Unused::Skip).map_err(|d| match d {
        TopologyDefect::EdgeUsedTwice(a, b) => SanityError::FacetEdgeTwice {
            from: key(a),
            to: key(b),
        },
        TopologyDefect::OpenEdge(a, b) => SanityError::FacetEdgeUnmatched {
            from: key(a),
            to: key(b),
        },
        TopologyDefect::PinchedVertex(v) | TopologyDefect::UnusedVertex(v) => {
            SanityError::FacetVertexPinched { vertex: key(v) }
        }
        TopologyDefect::Euler(chi) => SanityError::FacetComplexEuler { chi },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamic::DynamicSum;
    use crate::kernel::rotation::{Pose, Rotation};
    use crate::polytope::Polytope;
    use crate::query::test_support::boxed;
    use glam::DVec3;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Each facet's group, named by its smallest member: two groupings are
    /// the same partition exactly when these agree.
    fn named_groups(uf: &mut UnionFind, total: usize) -> Vec<u32> {
        let mut smallest = std::collections::HashMap::new();
        for id in 0..total as u32 {
            let root = uf.find(id);
            smallest.entry(root).or_insert(id);
        }
        (0..total as u32).map(|id| smallest[&uf.find(id)]).collect()
    }

    fn hull(rng: &mut ChaCha8Rng, n: usize, grid: bool) -> Polytope {
        let pts: Vec<[f64; 3]> = (0..n)
            .map(|_| {
                let v = DVec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                if grid {
                    (v * 3.0).round().to_array()
                } else {
                    (v.normalize_or_zero() * 2.0).to_array()
                }
            })
            .collect();
        Polytope::from_points(&pts).unwrap()
    }

    /// The groups a dynamic sum's certified normals give
    /// (`coplanar_groups_certified`, module docs of `dynamic`, "Certified
    /// normals") are the exact ones, facet by facet, with the same
    /// degenerate ee-facets, along motions that pass through coplanar
    /// faces again and again: boxes and integer hulls turning about the
    /// coordinate axes by sixteenths of a turn (every fourth an exact
    /// quarter turn, where faces of both bodies are coplanar), then about
    /// random axes, both bodies moving; most exact tests are skipped.
    /// Certifying a normal on an arc (every normal certified) merges too
    /// few facets here and fails.
    #[test]
    fn certified_normals_leave_the_coplanar_groups_unchanged() {
        let mut rng = ChaCha8Rng::seed_from_u64(36);
        let pairs = [
            (boxed(0.5, 1.0, 1.5), boxed(1.0, 0.5, 0.5)),
            (boxed(0.5, 0.5, 0.5), hull(&mut rng, 30, true)),
            (hull(&mut rng, 40, true), hull(&mut rng, 40, true)),
            (hull(&mut rng, 40, false), boxed(0.5, 1.0, 0.25)),
            (hull(&mut rng, 60, false), hull(&mut rng, 50, false)),
        ];
        let (mut joined, mut skipped, mut tested) = (0usize, 0usize, 0usize);
        for (case, (p, q)) in pairs.iter().enumerate() {
            let mut sum = DynamicSum::new(p, Pose::IDENTITY, q, Pose::IDENTITY).unwrap();
            let mut turns = Vec::new();
            for axis in [DVec3::Z, DVec3::X, DVec3::Y] {
                for k in 0..=32 {
                    let turn = std::f64::consts::PI * k as f64 / 16.0;
                    turns.push((Rotation::from_axis_angle(axis, turn).unwrap(), None));
                }
            }
            let axis = DVec3::new(0.3, -0.8, 0.5);
            for k in 0..40 {
                let a = Rotation::from_axis_angle(axis, 0.02 * k as f64).unwrap();
                let b = Rotation::from_axis_angle(DVec3::new(1.0, 2.0, -1.0), -0.013 * k as f64)
                    .unwrap();
                turns.push((a, Some(b)));
            }
            for (k, (a, b)) in turns.into_iter().enumerate() {
                let pose_q = b.map_or(Pose::IDENTITY, |b| Pose::new(b, DVec3::ZERO));
                sum.set_pose(Pose::new(a, DVec3::ZERO), pose_q);
                let (ops, overlay) = (sum.operands(), sum.overlay());
                let total = overlay.len();
                let (mut plain, plain_degenerate, plain_any) = coplanar_groups(ops, &overlay);
                let (mut fast, fast_degenerate, fast_any) = coplanar_groups_certified(
                    ops,
                    &overlay,
                    |f| sum.normal_strictly_inside(false, f as usize),
                    |g| sum.normal_strictly_inside(true, g as usize),
                );
                let groups = named_groups(&mut plain, total);
                assert_eq!(
                    groups,
                    named_groups(&mut fast, total),
                    "case {case}, turn {k}"
                );
                assert_eq!(plain_degenerate, fast_degenerate, "case {case}, turn {k}");
                assert_eq!(plain_any, fast_any, "case {case}, turn {k}");
                joined += groups
                    .iter()
                    .enumerate()
                    .filter(|&(i, &g)| g != i as u32)
                    .count();
                let m = overlay.fv.len();
                for f in 0..m {
                    if sum.normal_strictly_inside(false, f) {
                        skipped += 1;
                    } else {
                        tested += 1;
                    }
                }
            }
        }
        // Coplanar facets were met often, and most fv-facets' tests skipped.
        assert!(joined > 500, "{joined}");
        assert!(skipped > 2 * tested && tested > 100, "{skipped} {tested}");
    }
}
