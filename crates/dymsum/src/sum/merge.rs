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
//! 4. Validation (`validated_mesh`): the vertices are the float sums, so a
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

use super::validate::{
    check_convex_faces, check_convex_geometry, check_sphere_faces, edge_is_convex, face_defect,
    ExactPoints,
};
use super::{Operands, Overlay};
use crate::error::MeshError;
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
    let m = overlay.fv.len();
    let n = overlay.vf.len();
    let total = overlay.len();
    let mut uf = UnionFind::new(total);
    let mut degenerate = vec![false; total];
    let mut any = false;
    let (vp, vq) = (ops.view_p(), ops.view_q());
    for (f, &w) in overlay.fv.iter().enumerate() {
        for r in ops.q.ring(w as usize) {
            if same_direction(&vp.normal(f as u32), &vq.normal(r.face)) {
                uf.union(f as u32, (m + r.face as usize) as u32);
                any = true;
            }
        }
    }
    for (k, &(e, e2)) in overlay.ee.iter().enumerate() {
        let id = (m + n + k) as u32;
        let [f0, f1] = ops.p.edge(e as usize).faces;
        let [g0, g1] = ops.q.edge(e2 as usize).faces;
        let (a, b) = (vp.normal(f0), vp.normal(f1));
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

/// How faithfully the output coordinates hold the exact sum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Precision {
    /// The rounding step (ulp) of the largest output coordinate.
    pub ulp: f64,
    /// The size of the sum (sum of the operands' bounding-box diagonals).
    pub size: f64,
}

impl Precision {
    /// Relative rounding above which callers should warn (about eight
    /// significant digits of the size left).
    pub const WARN_RELATIVE: f64 = 1e-8;
    /// `ulp / size` (infinite for a zero size).
    pub fn relative(&self) -> f64 {
        self.ulp / self.size
    }
    /// `true` when [`Self::relative`] exceeds [`Self::WARN_RELATIVE`].
    pub fn is_coarse(&self) -> bool {
        self.relative().is_nan() || self.relative() > Self::WARN_RELATIVE
    }
}

impl std::fmt::Display for Precision {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "rounding step {:.3e} relative to size {:.3e} ({:.1e})",
            self.ulp,
            self.size,
            self.relative()
        )
    }
}

/// A validated mesh of a sum.
#[derive(Clone, Debug, PartialEq)]
pub struct SumMesh {
    /// The mesh: closed, oriented, convex, maximal faces, checked exactly.
    pub mesh: PolygonMesh,
    /// The rounding of its coordinates relative to the sum's size.
    pub precision: Precision,
    /// `true` when rounding broke the exact faces and the mesh is the exact
    /// hull of the rounded vertices instead (the merged mesh with its bent
    /// faces folded, or, if that fails the check, a hull from scratch).
    pub hull_fallback: bool,
}

fn ulp(x: f64) -> f64 {
    let a = x.abs();
    if a.is_finite() {
        f64::from_bits(a.to_bits() + 1) - a
    } else {
        f64::INFINITY
    }
}

/// The merged mesh, validated exactly (see [`super::validate`]): the
/// combinatorial merge when its float coordinates are exactly convex, else
/// the exact hull of the rounded vertices.
pub(crate) fn validated_mesh(ops: &Operands, overlay: &Overlay) -> Result<SumMesh, MeshError> {
    let merged = merged_mesh(ops, overlay, true).map_err(MeshError::Merge)?;
    let merged = if merged.shortcut {
        match mesh_or_hull(ops, merged, false)? {
            Some(mesh) => return Ok(mesh),
            // The facets as faces failed the check: merge in full, which
            // also names a broken facet complex.
            None => merged_mesh(ops, overlay, false).map_err(MeshError::Merge)?,
        }
    } else {
        merged
    };
    mesh_or_hull(ops, merged, true)?.ok_or_else(|| MeshError::Merge("no mesh and no hull".into()))
}

/// The merged mesh if it passes the exact check (with its bent faces
/// folded), else (with `hull`) the exact hull of its rounded vertices, else
/// `None`.
fn mesh_or_hull(ops: &Operands, merged: Merged, hull: bool) -> Result<Option<SumMesh>, MeshError> {
    use super::validate::check_convex_mesh;
    let max = merged
        .mesh
        .vertices
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let precision = Precision {
        ulp: ulp(max),
        // Bounding-box diagonals, computed in each shape's frame (no
        // overflow of squared lengths at large scales).
        size: ops.p.diameter() + ops.q.diameter(),
    };
    if !max.is_finite() {
        return Err(MeshError::OutOfRange);
    }
    let pts: Vec<DVec3> = merged.mesh.vertices.iter().map(|&v| v.into()).collect();
    let points = ExactPoints::new(&pts);
    // Rounded sums usually bend the faces of four or more corners (the
    // parallelograms of edge pairs). Rounding moves each vertex by at most
    // half an ulp, so the exact hull of the rounded vertices is almost
    // always the merged mesh with its bent faces folded: try that first
    // (O(size)), keep it only if it passes the full exact check, else build
    // the hull from scratch.
    let mut faces = merged.mesh.faces;
    let folded = if merged.exact {
        Some(false)
    } else {
        fold_bent_faces(&mut faces, &points)
    };
    if let Some(bent) = folded {
        // The directed-edge index is built once here and reused by the
        // repairs of the same faces.
        let (checked, directed) = match check_sphere_faces(&faces, points.points().len()) {
            Ok(d) => (check_convex_geometry(&faces, &d, &points), Some(d)),
            Err(defect) => (Err(defect), None),
        };
        match checked {
            Ok(()) => {
                return Ok(Some(SumMesh {
                    mesh: PolygonMesh {
                        vertices: merged.mesh.vertices,
                        faces,
                    },
                    precision,
                    hull_fallback: bent,
                }))
            }
            // Exact coordinates cannot bend anything: a failure is a broken
            // overlay, reported (after the full merge, which names it)
            // and never repaired into a plausible mesh.
            Err(defect) if merged.exact => {
                return match hull {
                    true => Err(MeshError::Invalid(defect)),
                    false => Ok(None),
                }
            }
            Err(_) => {
                // Rounding made some neighbouring faces reflex or coplanar,
                // or pushed a vertex inside: rebuild only around those.
                // Flips first (cheap, local); what they leave, a local hull.
                let vertices = &merged.mesh.vertices;
                let local_hull = |faces: &[Vec<usize>], directed: &DirectedEdges| {
                    repair_defects(faces, directed, &points)
                        .and_then(|faces| compact_checked(vertices, &faces, &points))
                };
                // Not a closed sphere (no index): nothing local to repair.
                let repaired = directed.and_then(|directed| {
                    match flip_reflex_edges(faces.clone(), &directed, &points) {
                        Some(flipped) => {
                            compact_checked(vertices, &flipped, &points).or_else(|| {
                                let n = points.points().len();
                                let d = check_sphere_faces(&flipped, n).ok()?;
                                local_hull(&flipped, &d)
                            })
                        }
                        None => local_hull(&faces, &directed),
                    }
                });
                if let Some(mesh) = repaired {
                    return Ok(Some(SumMesh {
                        mesh,
                        precision,
                        hull_fallback: true,
                    }));
                }
            }
        }
    }
    if !hull {
        return Ok(None);
    }
    let hull = crate::hull::convex_hull(&points).map_err(|e| MeshError::PrecisionLost {
        ulp: precision.ulp,
        size: precision.size,
        collapse: match e {
            crate::hull::HullError::AllCoincident { .. } => "coincide".into(),
            crate::hull::HullError::AllCollinear { .. } => "are collinear".into(),
            crate::hull::HullError::AllCoplanar { .. } => "are coplanar (flat)".into(),
            other => other.to_string(),
        },
    })?;
    let mesh = hull.to_mesh(&points);
    check_convex_mesh(&mesh)?;
    Ok(Some(SumMesh {
        mesh,
        precision,
        hull_fallback: true,
    }))
}

/// Replaces, in place, each face whose rounded corners are not coplanar by
/// the outer side of their hull: a quadrilateral is split along the
/// diagonal that folds outward (the same exact `orient3d` that found it
/// bent), a larger face by the faces of its corners' hull that face the
/// same way as the polygon. Extra pieces go to the end of the list.
/// Returns whether any face was bent, or `None` when a bent face's corners
/// have no usable hull. The result is a candidate only:
/// [`super::validate::check_convex_faces`] decides.
fn fold_bent_faces(faces: &mut Vec<Vec<usize>>, points: &ExactPoints) -> Option<bool> {
    let mut bent = false;
    for i in 0..faces.len() {
        let f = &mut faces[i];
        // The sign of the first off-plane corner, if any.
        let Some(sign) = f[3..]
            .iter()
            .map(|&d| points.orient3(f[0], f[1], f[2], d))
            .find(|&s| s != Sign::Zero)
        else {
            continue;
        };
        bent = true;
        if let [a, b, c, d] = f[..] {
            // `d` below the plane of `a, b, c`: the fold along `a c` is
            // convex; above: the fold along `b d` is.
            let other = if sign == Sign::Negative {
                f.truncate(3);
                vec![a, c, d]
            } else {
                f.remove(2);
                f[0..3].copy_from_slice(&[b, c, d]);
                vec![a, b, d]
            };
            faces.push(other);
            continue;
        }
        let mut side = outer_side(f, points)?.into_iter();
        faces[i] = side.next()?;
        faces.extend(side);
    }
    Some(bent)
}

/// A subset of exact points (by index), for local hulls.
struct Corners<'a>(&'a [usize], &'a ExactPoints);

impl crate::hull::HullPoints for Corners<'_> {
    fn len(&self) -> usize {
        self.0.len()
    }
    fn coords(&self, i: usize) -> DVec3 {
        self.1.points()[self.0[i]]
    }
    fn orient(&self, a: usize, b: usize, c: usize, d: usize) -> Sign {
        self.1.orient3(self.0[a], self.0[b], self.0[c], self.0[d])
    }
    fn collinear(&self, a: usize, b: usize, c: usize) -> bool {
        (0..3).all(|axis| self.1.orient2(axis, self.0[a], self.0[b], self.0[c]) == Sign::Zero)
    }
}

/// The faces of the hull of the polygon `face`'s corners whose normals point
/// the polygon's way (float normals: a wrong pick fails the exact check).
fn outer_side(face: &[usize], points: &ExactPoints) -> Option<Vec<Vec<usize>>> {
    // Scaled coordinates: the normals neither underflow nor depend on the
    // scale.
    let pts = points.scaled_points();
    let newell = |f: &mut dyn Iterator<Item = usize>| {
        let ring: Vec<DVec3> = f.map(|i| pts[i]).collect();
        let o = ring[0];
        (1..ring.len())
            .map(|k| (ring[k] - o).cross(ring[(k + 1) % ring.len()] - o))
            .sum::<DVec3>()
    };
    let normal = newell(&mut face.iter().copied());
    let corners = Corners(face, points);
    let hull = crate::hull::convex_hull(&corners).ok()?;
    let outer: Vec<Vec<usize>> = hull
        .faces
        .iter()
        .filter(|h| newell(&mut h.iter().map(|&i| face[i])).dot(normal) > 0.0)
        .map(|h| h.iter().map(|&i| face[i]).collect())
        .collect();
    (!outer.is_empty()).then_some(outer)
}

/// The faces with the region around every defect replaced by the outer side
/// of the hull of the region's corners. A defect is a face that is not a
/// strictly convex planar polygon or an edge that is not strictly convex;
/// the region is the faces at the defects grown by one ring of faces
/// around their corners. The outer side is found from the region's
/// boundary: the hull faces holding its edges (same direction) and all hull
/// faces reached from them without crossing it. `faces` must be a closed
/// sphere with the directed-edge index `directed` ([`check_sphere_faces`]).
/// `None` when the region is the whole mesh (then the caller's hull from
/// scratch is the same work) or the boundary is not on the hull. The
/// result is a candidate only (its corners may have lost vertices pushed
/// inside): [`compact_checked`] decides.
fn repair_defects(
    faces: &[Vec<usize>],
    directed: &DirectedEdges,
    points: &ExactPoints,
) -> Option<Vec<Vec<usize>>> {
    let n = points.points().len();
    // The face across the edge at `pos`, leaving `a`.
    let across = |a: usize, pos: usize| directed.face_of(directed.target[pos], a);
    let mut in_region: Vec<bool> = faces
        .iter()
        .enumerate()
        .map(|(fi, f)| face_defect(fi, f, points).is_err())
        .collect();
    for a in 0..n {
        for pos in directed.start[a]..directed.start[a + 1] {
            if directed.target[pos] > a && !edge_is_convex(faces, directed, pos, points) {
                in_region[directed.face_corner(pos).0] = true;
                in_region[across(a, pos)?] = true;
            }
        }
    }
    // Grow by the faces around the region's corners.
    let mut corner = vec![false; n];
    for (f, _) in faces.iter().zip(&in_region).filter(|(_, &r)| r) {
        for &v in f {
            corner[v] = true;
        }
    }
    for v in (0..n).filter(|&v| corner[v]) {
        for pos in directed.start[v]..directed.start[v + 1] {
            in_region[directed.face_corner(pos).0] = true;
        }
    }
    let mut sub = Vec::new();
    corner.iter_mut().for_each(|c| *c = false);
    for (f, _) in faces.iter().zip(&in_region).filter(|(_, &r)| r) {
        for &v in f {
            if !corner[v] {
                corner[v] = true;
                sub.push(v);
            }
        }
    }
    let hull = crate::hull::convex_hull(&Corners(&sub, points)).ok()?;
    let hull_faces: Vec<Vec<usize>> = hull
        .faces
        .iter()
        .map(|h| h.iter().map(|&i| sub[i]).collect())
        .collect();
    // The region's boundary, directed as in its faces.
    let mut boundary = Vec::new();
    for a in 0..n {
        for pos in directed.start[a]..directed.start[a + 1] {
            if in_region[directed.face_corner(pos).0] && !in_region[across(a, pos)?] {
                boundary.push((a, directed.target[pos]));
            }
        }
    }
    if boundary.is_empty() {
        // The region is the whole mesh: that is the hull from scratch.
        return None;
    }
    boundary.sort_unstable();
    let hull_edges = DirectedEdges::new(n, &hull_faces);
    let mut top = vec![false; hull_faces.len()];
    let mut stack = Vec::new();
    for &(a, b) in &boundary {
        let h = hull_edges.face_of(a, b)?;
        if !top[h] {
            top[h] = true;
            stack.push(h);
        }
    }
    while let Some(h) = stack.pop() {
        let f = &hull_faces[h];
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            if boundary.binary_search(&(a, b)).is_ok() {
                continue;
            }
            let g = hull_edges.face_of(b, a)?;
            if !top[g] {
                top[g] = true;
                stack.push(g);
            }
        }
    }
    let kept = faces
        .iter()
        .zip(&in_region)
        .filter(|(_, &r)| !r)
        .map(|(f, _)| f.clone());
    let outer = hull_faces
        .into_iter()
        .zip(top)
        .filter(|(_, t)| *t)
        .map(|(f, _)| f);
    Some(kept.chain(outer).collect())
}

/// The mesh of `faces` over the vertices they use (renumbered in order),
/// if it passes the exact check and every vertex it leaves out lies inside
/// or on it (so it is the exact hull of all of `vertices`).
fn compact_checked(
    vertices: &[[f64; 3]],
    faces: &[Vec<usize>],
    points: &ExactPoints,
) -> Option<PolygonMesh> {
    let n = vertices.len();
    let mut new_id = vec![usize::MAX; n];
    for &v in faces.iter().flatten() {
        new_id[v] = 0;
    }
    let mut kept = Vec::with_capacity(n);
    for (v, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            *id = kept.len();
            kept.push(v);
        }
    }
    let renumbered: Vec<Vec<usize>> = faces
        .iter()
        .map(|f| f.iter().map(|&v| new_id[v]).collect())
        .collect();
    let compact;
    let ep = if kept.len() == n {
        points
    } else {
        let pts: Vec<DVec3> = kept.iter().map(|&v| points.points()[v]).collect();
        compact = ExactPoints::new(&pts);
        &compact
    };
    check_convex_faces(&renumbered, ep).ok()?;
    for v in (0..n).filter(|&v| new_id[v] == usize::MAX) {
        if faces
            .iter()
            .any(|f| points.orient3(f[0], f[1], f[2], v) == Sign::Positive)
        {
            return None;
        }
    }
    Some(PolygonMesh {
        vertices: kept.iter().map(|&v| vertices[v]).collect(),
        faces: renumbered,
    })
}

/// The faces with every reflex edge between two triangles flipped to the
/// other diagonal of their quadrilateral (which is then convex), and the
/// edges around each flip re-tested, until no such edge is left: the local
/// convexification of a mesh whose vertices rounding moved by an ulp.
/// Other defects (a reflex edge at a polygon, a flat edge, a flip that
/// would duplicate an edge) are left for [`repair_defects`]. `faces` must
/// be a closed sphere with the directed-edge index `directed`
/// ([`check_sphere_faces`]). `None` when flips do not settle. The result
/// is a candidate only: [`compact_checked`] decides.
fn flip_reflex_edges(
    mut faces: Vec<Vec<usize>>,
    directed: &DirectedEdges,
    points: &ExactPoints,
) -> Option<Vec<Vec<usize>>> {
    use std::collections::HashMap;
    let n = points.points().len();
    let mut queue = Vec::new();
    for a in 0..n {
        for pos in directed.start[a]..directed.start[a + 1] {
            let b = directed.target[pos];
            if b > a && !edge_is_convex(&faces, directed, pos, points) {
                queue.push((a, b));
            }
        }
    }
    // Directed edges changed by flips (`None`: removed), over the index.
    let mut changed: HashMap<(usize, usize), Option<usize>> = HashMap::new();
    let face_of =
        |changed: &HashMap<(usize, usize), Option<usize>>, a: usize, b: usize| match changed
            .get(&(a, b))
        {
            Some(&f) => f,
            None => directed.face_of(a, b),
        };
    let mut budget = 8 * queue.len() + 64;
    while let Some((a, b)) = queue.pop() {
        budget = budget.checked_sub(1)?;
        // An edge queued twice may have been flipped away meanwhile.
        let (Some(fi), Some(gi)) = (face_of(&changed, a, b), face_of(&changed, b, a)) else {
            continue;
        };
        let (f, g) = (&faces[fi], &faces[gi]);
        if f.len() != 3 || g.len() != 3 {
            continue;
        }
        // f runs a → b → c, g runs b → a → d.
        let c = f[(f.iter().position(|&v| v == b)? + 1) % 3];
        let d = g[(g.iter().position(|&v| v == a)? + 1) % 3];
        if points.orient3(a, b, c, d) != Sign::Positive
            || c == d
            || face_of(&changed, c, d).is_some()
            || face_of(&changed, d, c).is_some()
        {
            continue;
        }
        faces[fi] = vec![a, d, c];
        faces[gi] = vec![d, b, c];
        changed.insert((a, b), None);
        changed.insert((b, a), None);
        for (e, face) in [
            ((a, d), fi),
            ((d, c), fi),
            ((c, a), fi),
            ((d, b), gi),
            ((b, c), gi),
            ((c, d), gi),
        ] {
            changed.insert(e, Some(face));
        }
        queue.extend([(a, d), (d, b), (b, c), (c, a)]);
    }
    Some(faces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hull::{convex_hull, FloatPoints};

    /// A triangulated convex mesh: the hull of points on the unit sphere
    /// (generic, so every face is a triangle).
    fn sphere_mesh(n: usize) -> (Vec<DVec3>, Vec<Vec<usize>>) {
        let pts = crate::hull::fibonacci_sphere(n);
        let hull = convex_hull(&FloatPoints(&pts)).unwrap();
        assert!(hull.faces.iter().all(|f| f.len() == 3));
        (pts, hull.faces)
    }

    /// Flips the edge `a → b` of `faces` to the other diagonal.
    fn flip(faces: &mut [Vec<usize>], a: usize, b: usize) {
        let at =
            |f: &Vec<usize>, x: usize, y: usize| (0..3).any(|k| f[k] == x && f[(k + 1) % 3] == y);
        let fi = faces.iter().position(|f| at(f, a, b)).unwrap();
        let gi = faces.iter().position(|f| at(f, b, a)).unwrap();
        let c = *faces[fi].iter().find(|&&v| v != a && v != b).unwrap();
        let d = *faces[gi].iter().find(|&&v| v != a && v != b).unwrap();
        faces[fi] = vec![a, d, c];
        faces[gi] = vec![d, b, c];
    }

    fn as_mesh(pts: &[DVec3]) -> Vec<[f64; 3]> {
        pts.iter().map(|p| p.to_array()).collect()
    }

    #[test]
    fn flips_undo_reflex_edges() {
        let (pts, good) = sphere_mesh(60);
        let ep = ExactPoints::new(&pts);
        let mut bad = good.clone();
        let (a, b) = (bad[0][0], bad[0][1]);
        flip(&mut bad, a, b);
        let (c, d) = (bad[7][0], bad[7][1]);
        flip(&mut bad, c, d);
        assert!(check_convex_faces(&bad, &ep).is_err());
        let d = check_sphere_faces(&bad, pts.len()).unwrap();
        let fixed = flip_reflex_edges(bad, &d, &ep).unwrap();
        let mesh = compact_checked(&as_mesh(&pts), &fixed, &ep).expect("flips repair it");
        assert_eq!(mesh.faces.len(), good.len());
    }

    /// Review finding: a queued edge flipped away by a neighbouring flip
    /// must be skipped, not end the flips (two edges of one triangle).
    #[test]
    fn flips_skip_edges_already_flipped_away() {
        let (pts, good) = sphere_mesh(60);
        let ep = ExactPoints::new(&pts);
        let mut repaired = 0;
        for t in 0..good.len() {
            let mut bad = good.clone();
            let f = good[t].clone();
            flip(&mut bad, f[0], f[1]);
            flip(&mut bad, f[1], f[2]);
            if check_convex_faces(&bad, &ep).is_ok() {
                continue;
            }
            let d = check_sphere_faces(&bad, pts.len()).unwrap();
            let fixed = flip_reflex_edges(bad, &d, &ep).expect("flips settle");
            assert!(
                compact_checked(&as_mesh(&pts), &fixed, &ep).is_some(),
                "triangle {t}"
            );
            repaired += 1;
        }
        assert!(repaired > 50, "{repaired}");
    }

    /// Review finding: exact coordinates that fail the check are a broken
    /// overlay; the mesh must be refused, never repaired.
    #[test]
    fn an_exact_mesh_that_fails_is_refused_not_repaired() {
        let (pts, mut faces) = sphere_mesh(40);
        let (a, b) = (faces[0][0], faces[0][1]);
        flip(&mut faces, a, b);
        let cube = crate::polytope::Polytope::from_points(&[
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [0., 0., 1.],
        ])
        .unwrap();
        let ops = Operands::new(
            &cube,
            crate::kernel::rotation::Pose::IDENTITY,
            &cube,
            crate::kernel::rotation::Pose::IDENTITY,
        );
        let merged = |shortcut| Merged {
            mesh: PolygonMesh {
                vertices: as_mesh(&pts),
                faces: faces.clone(),
            },
            exact: true,
            shortcut,
        };
        assert!(matches!(mesh_or_hull(&ops, merged(true), false), Ok(None)));
        assert!(matches!(
            mesh_or_hull(&ops, merged(false), true),
            Err(MeshError::Invalid(_))
        ));
    }

    /// Review finding: a region that covers the whole mesh has no boundary;
    /// the repair declines (the hull from scratch is the same work).
    #[test]
    fn a_region_over_the_whole_mesh_is_declined() {
        let mut pts = vec![
            DVec3::X,
            -DVec3::X,
            DVec3::Y,
            -DVec3::Y,
            DVec3::Z,
            -DVec3::Z,
        ];
        let hull = convex_hull(&FloatPoints(&pts)).unwrap();
        // The top vertex pushed through to below the equator: every face
        // meets a reflex edge.
        pts[4] = DVec3::new(0.0, 0.0, -0.25);
        let ep = ExactPoints::new(&pts);
        assert!(check_convex_faces(&hull.faces, &ep).is_err());
        let d = check_sphere_faces(&hull.faces, pts.len()).unwrap();
        assert!(repair_defects(&hull.faces, &d, &ep).is_none());
    }

    #[test]
    fn a_local_hull_drops_a_vertex_pushed_inside() {
        let (mut pts, mut faces) = sphere_mesh(60);
        // A new vertex just inside face 0, which is split into three.
        let f = faces[0].clone();
        let centre = (pts[f[0]] + pts[f[1]] + pts[f[2]]) / 3.0;
        let v = pts.len();
        pts.push(centre * (1.0 - 1e-9));
        faces[0] = vec![f[0], f[1], v];
        faces.push(vec![f[1], f[2], v]);
        faces.push(vec![f[2], f[0], v]);
        let ep = ExactPoints::new(&pts);
        assert!(check_convex_faces(&faces, &ep).is_err());
        let d = check_sphere_faces(&faces, pts.len()).unwrap();
        let region = repair_defects(&faces, &d, &ep).unwrap();
        let mesh = compact_checked(&as_mesh(&pts), &region, &ep).expect("a local hull repairs it");
        assert_eq!(mesh.vertices.len(), pts.len() - 1);
        // A vertex pushed *outside* is kept, never dropped.
        pts[v] = centre * (1.0 + 1e-9);
        let ep = ExactPoints::new(&pts);
        let mesh = compact_checked(&as_mesh(&pts), &faces, &ep).expect("convex as is");
        assert_eq!(mesh.vertices.len(), pts.len());
    }

    #[test]
    fn a_dropped_vertex_outside_is_refused() {
        let (pts, faces) = sphere_mesh(40);
        let ep = ExactPoints::new(&pts);
        // The hull of every vertex but 0 is closed and convex, but vertex 0
        // lies outside it: not the hull of all the vertices.
        let rest: Vec<usize> = (1..pts.len()).collect();
        let hull = convex_hull(&Corners(&rest, &ep)).unwrap();
        let without: Vec<Vec<usize>> = hull
            .faces
            .iter()
            .map(|f| f.iter().map(|&i| rest[i]).collect())
            .collect();
        assert!(compact_checked(&as_mesh(&pts), &without, &ep).is_none());
        assert!(compact_checked(&as_mesh(&pts), &faces, &ep).is_some());
    }
}
