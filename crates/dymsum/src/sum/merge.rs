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
use crate::PolygonMesh;
use glam::DVec3;
use std::collections::HashMap;

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
pub(crate) fn facet_corners(ops: &Operands<'_>, overlay: &Overlay) -> Vec<Vec<(u32, u32)>> {
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

/// Outward unit normal of the ee-facet `(e, e2)`.
fn ee_normal(ops: &Operands<'_>, e: u32, e2: u32) -> DVec3 {
    let [u1, u2] = ops.p.edge(e as usize).vertices;
    let [w1, w2] = ops.q.edge(e2 as usize).vertices;
    let d1 = ops.p_vertex(u2) - ops.p_vertex(u1);
    let d2 = ops.q_vertex(w2) - ops.q_vertex(w1);
    let (vp, vq) = (ops.view_p(), ops.view_q());
    let (a, b) = vp.edge_arc(e);
    let (c, _) = vq.edge_arc(e2);
    let n = d1.cross(d2).normalize_or_zero();
    if sos_det3(&a, &b, &c).is_negative() {
        n
    } else {
        -n
    }
}

/// The merged mesh of `P ⊕ Q` (see the module docs).
pub fn merged_mesh(ops: &Operands<'_>, overlay: &Overlay) -> PolygonMesh {
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
    // Groups meeting at each sum vertex.
    let mut incidence: Vec<((u32, u32), u32)> = Vec::with_capacity(total * 4);
    let mut root = vec![0u32; total];
    for i in 0..total {
        root[i] = uf.find(i as u32);
        if !degenerate[i] {
            incidence.extend(corners[i].iter().map(|&c| (c, root[i])));
        }
    }
    incidence.sort_unstable();
    incidence.dedup();
    let mut kept: HashMap<(u32, u32), u32> = HashMap::new();
    let mut vertices = Vec::new();
    let mut i = 0;
    while i < incidence.len() {
        let mut j = i;
        while j < incidence.len() && incidence[j].0 == incidence[i].0 {
            j += 1;
        }
        if j - i >= 3 {
            let (u, w) = incidence[i].0;
            kept.insert((u, w), vertices.len() as u32);
            vertices.push(ops.p_vertex(u) + ops.q_vertex(w));
        }
        i = j;
    }
    // Corners and a normal per group.
    let mut group_of_root: HashMap<u32, usize> = HashMap::new();
    let mut groups: Vec<(DVec3, Vec<u32>)> = Vec::new();
    for i in 0..total {
        if degenerate[i] {
            continue;
        }
        let gi = *group_of_root.entry(root[i]).or_insert_with(|| {
            let rep = root[i] as usize; // smallest id: fv before vf before ee
            let normal = if rep < m {
                ops.pose_p.rotation.apply(ops.p.unit_normal(rep))
            } else if rep < m + n {
                ops.pose_q.rotation.apply(ops.q.unit_normal(rep - m))
            } else {
                let (e, e2) = overlay.ee[rep - m - n];
                ee_normal(ops, e, e2)
            };
            groups.push((normal, Vec::new()));
            groups.len() - 1
        });
        for c in &corners[i] {
            if let Some(&v) = kept.get(c) {
                groups[gi].1.push(v);
            }
        }
    }
    let faces = groups
        .into_iter()
        .map(|(normal, mut vs)| {
            vs.sort_unstable();
            vs.dedup();
            sort_ccw(&vertices, normal, &mut vs);
            vs.into_iter().map(|v| v as usize).collect()
        })
        .collect();
    PolygonMesh {
        vertices: vertices.iter().map(|v| v.to_array()).collect(),
        faces,
    }
}

fn sort_ccw(vertices: &[DVec3], normal: DVec3, vs: &mut [u32]) {
    if vs.len() < 3 {
        return;
    }
    let c = vs.iter().map(|&v| vertices[v as usize]).sum::<DVec3>() / vs.len() as f64;
    let t = (vertices[vs[0] as usize] - c).normalize_or_zero();
    let b = normal.cross(t);
    let angle = |v: u32| {
        let d = vertices[v as usize] - c;
        d.dot(b).atan2(d.dot(t))
    };
    vs.sort_by(|&x, &y| angle(x).total_cmp(&angle(y)));
}

/// Checks the facet complex of an overlay: closed, 2-manifold, consistently
/// oriented (each directed facet edge once, with its reverse once), Euler
/// characteristic 2.
pub fn check_facet_complex(ops: &Operands<'_>, overlay: &Overlay) -> Result<(), String> {
    let corners = facet_corners(ops, overlay);
    let mut directed: HashMap<(SumVertex, SumVertex), u32> = HashMap::new();
    let mut verts = std::collections::HashSet::new();
    for (i, cyc) in corners.iter().enumerate() {
        for k in 0..cyc.len() {
            verts.insert(cyc[k]);
            let key = (cyc[k], cyc[(k + 1) % cyc.len()]);
            if directed.insert(key, i as u32).is_some() {
                return Err(format!("facet edge {key:?} used twice in one direction"));
            }
        }
    }
    for &(a, b) in directed.keys() {
        if !directed.contains_key(&(b, a)) {
            return Err(format!("facet edge {:?} has no opposite facet", (a, b)));
        }
    }
    let (v, e, f) = (
        verts.len() as i64,
        directed.len() as i64 / 2,
        corners.len() as i64,
    );
    if v - e + f != 2 {
        return Err(format!(
            "facet complex Euler characteristic {} != 2",
            v - e + f
        ));
    }
    Ok(())
}

/// Checks a merged mesh: closed, 2-manifold, oriented, Euler 2, every face
/// planar and every edge convex within a tolerance of `1e-9` of the size.
/// The mesh is a float construction, so a face's plane is only as well
/// determined as the face is wide: for sliver faces (nearly degenerate
/// polygons, e.g. between nearly coplanar input faces) the tolerance grows
/// with the face's conditioning `L² / (2·area)` times the coordinates'
/// rounding. The exact combinatorial check is [`check_facet_complex`].
pub fn check_mesh(mesh: &PolygonMesh) -> Result<(), String> {
    let pts: Vec<DVec3> = mesh.vertices.iter().map(|p| DVec3::from(*p)).collect();
    let (lo, hi) = crate::polytope::bounds(&pts);
    let size = (hi - lo).length().max(f64::MIN_POSITIVE);
    let coord = lo.abs().max(hi.abs()).max_element();
    let tol = 1e-9 * size;
    let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
    for (fi, f) in mesh.faces.iter().enumerate() {
        if f.len() < 3 {
            return Err(format!("face {fi} has {} vertices", f.len()));
        }
        for k in 0..f.len() {
            if directed.insert((f[k], f[(k + 1) % f.len()]), fi).is_some() {
                return Err(format!(
                    "mesh edge {:?} used twice in one direction",
                    (f[k], f[(k + 1) % f.len()])
                ));
            }
        }
    }
    // (unit normal, offset, tolerance) per face.
    let plane = |f: &Vec<usize>| {
        let c = f.iter().map(|&i| pts[i]).sum::<DVec3>() / f.len() as f64;
        let mut nrm = DVec3::ZERO;
        let mut extent: f64 = 0.0;
        for k in 0..f.len() {
            nrm += (pts[f[k]] - c).cross(pts[f[(k + 1) % f.len()]] - c);
            extent = extent.max((pts[f[k]] - c).length() * 2.0);
        }
        let area = 0.5 * nrm.length();
        let nrm = nrm.normalize_or_zero();
        let conditioning = extent * extent / (2.0 * area).max(f64::MIN_POSITIVE);
        let face_tol = tol + 32.0 * f64::EPSILON * coord.max(size) * conditioning;
        (nrm, nrm.dot(c), face_tol)
    };
    let planes: Vec<_> = mesh.faces.iter().map(plane).collect();
    for (fi, f) in mesh.faces.iter().enumerate() {
        let (nrm, d, t) = planes[fi];
        if nrm == DVec3::ZERO {
            return Err(format!("face {fi} has zero area"));
        }
        for &v in f {
            if (nrm.dot(pts[v]) - d).abs() > t {
                return Err(format!("face {fi} is not planar"));
            }
        }
    }
    for (&(a, b), &fi) in &directed {
        let Some(&gi) = directed.get(&(b, a)) else {
            return Err(format!("mesh edge {:?} has no opposite face", (a, b)));
        };
        let (nrm, d, t) = planes[fi];
        for &v in &mesh.faces[gi] {
            if nrm.dot(pts[v]) - d > t {
                return Err(format!(
                    "edge {:?} between faces {fi} and {gi} is not convex",
                    (a, b)
                ));
            }
        }
    }
    let used: std::collections::HashSet<usize> = mesh.faces.iter().flatten().copied().collect();
    let (v, e, f) = (
        used.len() as i64,
        directed.len() as i64 / 2,
        mesh.faces.len() as i64,
    );
    if v - e + f != 2 {
        return Err(format!("mesh Euler characteristic {} != 2", v - e + f));
    }
    if mesh.signed_volume() <= 0.0 {
        return Err("mesh is not outward (volume <= 0)".into());
    }
    Ok(())
}
