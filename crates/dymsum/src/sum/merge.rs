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
//! polygon: its kept corners sorted counter-clockwise about its normal
//! (a float construction). Cost: O(number of facets).

use super::{Operands, Overlay};
use crate::kernel::predicates::{det3, same_direction, sos_det3};
use crate::kernel::Sign;
use crate::sanity::SanityError;
use crate::PolygonMesh;
use glam::DVec3;
use rustc_hash::FxHashMap as HashMap;

/// A vertex of the sum as `(vertex of P, vertex of Q)`.
type SumVertex = (u32, u32);

struct UnionFind(Vec<u32>);

impl UnionFind {
    fn new(n: usize) -> Self {
        UnionFind((0..n as u32).collect())
    }
    fn find(&mut self, mut x: u32) -> u32 {
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

/// The corners of every facet as `(vertex of P, vertex of Q)` keys, in
/// counter-clockwise order about the facet's outward normal.
pub(crate) fn facet_corners(ops: &Operands, overlay: &Overlay) -> Vec<Vec<(u32, u32)>> {
    let mut out = Vec::with_capacity(overlay.len());
    for (f, &w) in overlay.fv.iter().enumerate() {
        out.push(ops.p.face(f).iter().map(|&u| (u, w)).collect());
    }
    for (g, &u) in overlay.vf.iter().enumerate() {
        out.push(ops.q.face(g).iter().map(|&w| (u, w)).collect());
    }
    let (vp, vq) = (ops.view_p(), ops.view_q());
    for &(e, e2) in &overlay.ee {
        let [u1, u2] = ops.p.edge(e as usize).vertices;
        let [w1, w2] = ops.q.edge(e2 as usize).vertices;
        let (a, b) = vp.edge_arc(e);
        let (c, _) = vq.edge_arc(e2);
        // Edge directions are a×b and c×d; the cycle below turns about their
        // cross product, which is the outward normal iff det[a,b,c] < 0.
        let ccw = sos_det3(&a, &b, &c).is_negative();
        let mut cyc = vec![(u1, w1), (u2, w1), (u2, w2), (u1, w2)];
        if !ccw {
            cyc.reverse();
        }
        out.push(cyc);
    }
    out
}

/// The merged mesh of `P ⊕ Q` over the float sums of its vertices, and
/// whether every coordinate is the exact sum (no rounding anywhere).
pub(crate) struct Merged {
    /// The mesh.
    pub mesh: PolygonMesh,
    /// `true` when every vertex coordinate is exact, so the mesh must pass
    /// [`super::validate::check_convex_mesh`] as is.
    pub exact: bool,
}

/// `pose.apply(v)` if that is computed without rounding (signed-permutation
/// rotation, exact translation), else `None`.
fn exact_posed(pose: &crate::Pose, v: DVec3) -> Option<DVec3> {
    let m = pose.rotation.matrix();
    let rows = [m.row(0), m.row(1), m.row(2)];
    let mut r = DVec3::ZERO;
    for (k, row) in rows.iter().enumerate() {
        let nz: Vec<usize> = (0..3).filter(|&i| row[i] != 0.0).collect();
        if nz.len() != 1 || row[nz[0]].abs() != 1.0 {
            return None;
        }
        r[k] = row[nz[0]] * v[nz[0]];
    }
    let t = pose.translation;
    let out = r + t;
    (0..3).all(|k| exact_sum(r[k], t[k], out[k])).then_some(out)
}

/// Knuth's TwoSum: whether `s = fl(a + b)` is exact.
fn exact_sum(a: f64, b: f64, s: f64) -> bool {
    let bb = s - a;
    (a - (s - bb)) + (b - bb) == 0.0 && s.is_finite()
}

/// The merged mesh of `P ⊕ Q` (see the module docs), or why the facet
/// complex could not be merged (an internal inconsistency).
pub(crate) fn merged_mesh(ops: &Operands, overlay: &Overlay) -> Result<Merged, String> {
    let m = overlay.fv.len();
    let n = overlay.vf.len();
    let total = overlay.len();
    let mut uf = UnionFind::new(total);
    let mut degenerate = vec![false; total];
    let (vp, vq) = (ops.view_p(), ops.view_q());
    for (f, &w) in overlay.fv.iter().enumerate() {
        for r in ops.q.ring(w as usize) {
            if same_direction(&vp.normal(f as u32), &vq.normal(r.face)) {
                uf.union(f as u32, (m + r.face as usize) as u32);
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
            continue;
        }
        if det3(&c, &d, &a) == Sign::Zero {
            uf.union(id, f0);
        }
        if det3(&c, &d, &b) == Sign::Zero {
            uf.union(id, f1);
        }
        if abc {
            uf.union(id, (m + g0 as usize) as u32);
        }
        if abd {
            uf.union(id, (m + g1 as usize) as u32);
        }
    }
    let corners = facet_corners(ops, overlay);
    // The facet on the other side of each directed facet edge.
    let mut twin: HashMap<(SumVertex, SumVertex), u32> =
        HashMap::with_capacity_and_hasher(total * 4, Default::default());
    for (i, cyc) in corners.iter().enumerate() {
        for k in 0..cyc.len() {
            if twin
                .insert((cyc[k], cyc[(k + 1) % cyc.len()]), i as u32)
                .is_some()
            {
                return Err("facet edge used twice in one direction".into());
            }
        }
    }
    let across = |i: usize, k: usize| -> Result<usize, String> {
        let cyc = &corners[i];
        twin.get(&(cyc[(k + 1) % cyc.len()], cyc[k]))
            .map(|&j| j as usize)
            .ok_or_else(|| "facet edge without an opposite facet".to_string())
    };
    // A degenerate (zero-area) ee-facet lies on a segment. When all its
    // neighbours lie in one face (the segment is inside that face, e.g. the
    // edges of parallel faces that meet end to end) it joins that face;
    // otherwise it lies on an edge of the sum and belongs to no face.
    let mut in_face = degenerate.iter().map(|&d| !d).collect::<Vec<bool>>();
    for i in 0..total {
        if !degenerate[i] {
            continue;
        }
        let mut roots = Vec::with_capacity(4);
        for k in 0..corners[i].len() {
            let j = across(i, k)?;
            if degenerate[j] {
                return Err("two degenerate facets share an edge".into());
            }
            roots.push(uf.find(j as u32));
        }
        if roots.iter().all(|&r| r == roots[0]) {
            uf.union(i as u32, roots[0]);
            in_face[i] = true;
        }
    }
    let root: Vec<u32> = (0..total).map(|i| uf.find(i as u32)).collect();
    // A sum vertex `u + w` is a corner iff at least three faces meet there.
    let mut incidence: Vec<(SumVertex, u32)> = Vec::with_capacity(total * 4);
    for i in 0..total {
        if in_face[i] {
            incidence.extend(corners[i].iter().map(|&c| (c, root[i])));
        }
    }
    incidence.sort_unstable();
    incidence.dedup();
    let mut kept: HashMap<SumVertex, u32> = HashMap::default();
    let mut vertices = Vec::new();
    let mut exact = true;
    let mut i = 0;
    while i < incidence.len() {
        let mut j = i;
        while j < incidence.len() && incidence[j].0 == incidence[i].0 {
            j += 1;
        }
        if j - i >= 3 {
            let (u, w) = incidence[i].0;
            kept.insert((u, w), vertices.len() as u32);
            let (pu, qw) = (ops.p_vertex(u), ops.q_vertex(w));
            let s = pu + qw;
            exact &= match (
                exact_posed(&ops.pose_p, ops.p.vertex(u as usize)),
                exact_posed(&ops.pose_q, ops.q.vertex(w as usize)),
            ) {
                (Some(a), Some(b)) => {
                    a == pu && b == qw && (0..3).all(|k| exact_sum(a[k], b[k], s[k]))
                }
                _ => false,
            };
            vertices.push(s);
        }
        i = j;
    }
    // Each face: the boundary of the union of its facets, walked edge by
    // edge (a simple cycle for a disk), with non-corner vertices dropped.
    // One map for all faces, keyed by (face, vertex); per face its smallest
    // boundary vertex (the walk's start) and its number of boundary edges.
    let mut boundary: HashMap<(u32, SumVertex), SumVertex> =
        HashMap::with_capacity_and_hasher(total * 2, Default::default());
    let mut start: HashMap<u32, (SumVertex, usize)> = HashMap::default();
    let mut order: Vec<u32> = Vec::new();
    for i in 0..total {
        if !in_face[i] {
            continue;
        }
        let cyc = &corners[i];
        for k in 0..cyc.len() {
            let j = across(i, k)?;
            if in_face[j] && root[j] == root[i] {
                continue;
            }
            let r = root[i];
            if boundary
                .insert((r, cyc[k]), cyc[(k + 1) % cyc.len()])
                .is_some()
            {
                return Err(format!("the facets of face {r} pinch at a vertex"));
            }
            let first = start.entry(r).or_insert_with(|| {
                order.push(r);
                (cyc[k], 0)
            });
            first.0 = first.0.min(cyc[k]);
            first.1 += 1;
        }
    }
    let mut faces = Vec::with_capacity(order.len());
    for r in order {
        let (first, edges) = start[&r];
        let mut face = Vec::new();
        let mut at = first;
        let mut steps = 0;
        loop {
            if let Some(&v) = kept.get(&at) {
                face.push(v as usize);
            }
            at = *boundary
                .get(&(r, at))
                .ok_or_else(|| format!("the boundary of face {r} is open"))?;
            steps += 1;
            if at == first || steps > edges {
                break;
            }
        }
        if steps != edges {
            return Err(format!("the facets of face {r} do not form a disk"));
        }
        if face.len() < 3 {
            return Err(format!("face {r} has {} corners", face.len()));
        }
        faces.push(face);
    }
    Ok(Merged {
        mesh: PolygonMesh {
            vertices: vertices.iter().map(|v| v.to_array()).collect(),
            faces,
        },
        exact,
    })
}

/// Checks the facet complex of an overlay: closed, 2-manifold, consistently
/// oriented (each directed facet edge once, with its reverse once), Euler
/// characteristic 2.
pub(crate) fn check_facet_complex(ops: &Operands, overlay: &Overlay) -> Result<(), SanityError> {
    let corners = facet_corners(ops, overlay);
    let mut directed: HashMap<(SumVertex, SumVertex), u32> = HashMap::default();
    let mut verts = std::collections::HashSet::new();
    for (i, cyc) in corners.iter().enumerate() {
        for k in 0..cyc.len() {
            verts.insert(cyc[k]);
            let key = (cyc[k], cyc[(k + 1) % cyc.len()]);
            if directed.insert(key, i as u32).is_some() {
                return Err(SanityError::FacetEdgeTwice {
                    from: key.0,
                    to: key.1,
                });
            }
        }
    }
    for &(a, b) in directed.keys() {
        if !directed.contains_key(&(b, a)) {
            return Err(SanityError::FacetEdgeUnmatched { from: a, to: b });
        }
    }
    let (v, e, f) = (
        verts.len() as i64,
        directed.len() as i64 / 2,
        corners.len() as i64,
    );
    if v - e + f != 2 {
        return Err(SanityError::FacetComplexEuler { chi: v - e + f });
    }
    Ok(())
}

/// Why the mesh of a sum could not be produced.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// The sum's vertices cannot be told apart in `f64`: after rounding
    /// they are all coincident, collinear or coplanar. Cause: the sum lies
    /// so far from the origin (or is so thin) that the rounding step of its
    /// coordinates is comparable to its size. Fix: move the operands nearer
    /// to the origin (subtract a common offset, add it back outside dymsum).
    #[error(
        "coordinates lose all precision: rounding step {ulp:.3e} against a size of {size:.3e}; the rounded vertices {collapse} (move the operands nearer to the origin)"
    )]
    PrecisionLost {
        /// The rounding step (ulp) of the largest output coordinate.
        ulp: f64,
        /// The size of the sum (sum of the operands' bounding-box diagonals).
        size: f64,
        /// How the rounded vertices collapsed.
        collapse: String,
    },
    /// A vertex of the sum overflows `f64` (an exact vertex sum `p + q`
    /// beyond `±1.8e308`): the sum is outside the supported range.
    #[error("the sum's coordinates overflow f64 (a vertex sum exceeds 1.8e308 in magnitude); outside the supported range")]
    OutOfRange,
    /// The facets could not be merged into faces (a bug: please report the
    /// input).
    #[error("internal error: merging the facets failed: {0}")]
    Merge(String),
    /// The produced mesh failed the exact validity check (a bug: please
    /// report the input). Never written silently.
    #[error("internal error: the merged mesh is invalid: {0}")]
    Invalid(#[from] super::validate::MeshDefect),
}

impl MeshError {
    /// `true` for a bug in dymsum (as opposed to an input beyond `f64`).
    pub fn is_internal(&self) -> bool {
        !matches!(
            self,
            MeshError::PrecisionLost { .. } | MeshError::OutOfRange
        )
    }
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
    /// hull of the rounded vertices instead.
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
    use super::validate::{check_convex_mesh, ExactPoints};
    let merged = merged_mesh(ops, overlay).map_err(MeshError::Merge)?;
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
    // parallelograms of edge pairs): such a mesh cannot pass the full
    // check, so go straight to the hull of the rounded vertices.
    let bent = |f: &Vec<usize>| {
        f[3..]
            .iter()
            .any(|&d| points.orient3(f[0], f[1], f[2], d) != Sign::Zero)
    };
    if merged.exact || !merged.mesh.faces.iter().any(bent) {
        match check_convex_mesh(&merged.mesh) {
            Ok(()) => {
                return Ok(SumMesh {
                    mesh: merged.mesh,
                    precision,
                    hull_fallback: false,
                })
            }
            Err(defect) if merged.exact => return Err(MeshError::Invalid(defect)),
            Err(_) => {}
        }
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
    Ok(SumMesh {
        mesh,
        precision,
        hull_fallback: true,
    })
}
