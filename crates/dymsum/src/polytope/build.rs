//! Building polytopes from point clouds and polygon meshes.
//!
//! * [`Polytope::from_points`]: the exact convex hull of a point cloud
//!   (every decision by exact `orient3d`), maximal faces.
//! * [`Polytope::from_mesh`]: a polygon mesh, validated. Steps:
//!   1. every coordinate finite, every face ≥ 3 distinct valid indices;
//!   2. closed, 2-manifold, consistently oriented, a topological sphere
//!      (each directed edge once with its reverse, one fan per vertex,
//!      V − E + F = 2);
//!   3. the exact hull of its vertices; the mesh must lie on the hull's
//!      boundary: every vertex within `tolerance` of it, every face within
//!      `tolerance` of one hull face plane, and the same volume;
//!   4. the polytope *is* that exact hull. If the mesh was exactly convex
//!      (every face exactly in a hull face plane, every vertex exactly on the
//!      boundary) nothing changed but the merging of coplanar faces;
//!      otherwise the mesh was convex only up to rounding and has been
//!      replaced by its hull: the [`ConvexityReport`] says so, and
//!      [`MeshPolicy::strict`] refuses such a mesh instead.
//!
//! Complexity: the hull is O(n log n) expected; the tolerance check is
//! O(F_mesh · F_hull).

use super::{bounds, Polytope, PolytopeError};
use crate::hull::{convex_hull, ConvexHull, FloatPoints};
use crate::kernel::predicates::orient;
use crate::kernel::Sign;
use crate::PolygonMesh;
use glam::DVec3;
use std::collections::HashMap;

/// How strictly [`Polytope::from_mesh`] treats meshes convex only up to rounding.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshPolicy {
    /// Refuse a mesh that is not exactly convex (instead of replacing it by
    /// the exact hull of its vertices).
    pub strict: bool,
    /// Tolerance for "convex up to rounding", relative to the bounding-box
    /// diagonal. Default `1e-5`.
    pub relative_tolerance: f64,
}

impl Default for MeshPolicy {
    fn default() -> Self {
        MeshPolicy {
            strict: false,
            relative_tolerance: 1e-5,
        }
    }
}

impl MeshPolicy {
    /// The strict policy: only exactly convex meshes are accepted.
    pub fn strict() -> Self {
        MeshPolicy {
            strict: true,
            ..Self::default()
        }
    }
}

/// What [`Polytope::from_mesh`] found and changed.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct ConvexityReport {
    /// Vertices in the input mesh.
    pub input_vertices: usize,
    /// Faces (polygons) in the input mesh.
    pub input_faces: usize,
    /// Triangles of the input's fan triangulation.
    pub input_triangles: usize,
    /// Vertices of the resulting polytope.
    pub vertices: usize,
    /// Maximal faces of the resulting polytope.
    pub faces: usize,
    /// `true` when every mesh face lies exactly in a face plane of the hull
    /// and every vertex exactly on its boundary.
    pub exactly_convex: bool,
    /// `true` when the mesh was convex only within tolerance and the polytope
    /// is the exact hull of its vertices instead.
    pub replaced_by_hull: bool,
    /// Largest distance of a mesh vertex or face from the hull boundary.
    pub max_deviation: f64,
    /// The absolute tolerance that was in force.
    pub tolerance: f64,
    /// Mesh vertices that are not corners of the polytope (in the middle of
    /// an edge or face, or slightly inside).
    pub dropped_vertices: usize,
    /// The mesh's faces were oriented inwards (consistently); the polytope is
    /// outward.
    pub inward_oriented: bool,
}

impl Polytope {
    /// The convex hull of a point cloud (at least 4 points, not all in a
    /// plane, all finite).
    ///
    /// ```
    /// # use dymsum::Polytope;
    /// let tet = Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]]).unwrap();
    /// assert_eq!((tet.vertex_count(), tet.edge_count(), tet.face_count()), (4, 6, 4));
    /// assert!(Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]]).is_err());
    /// ```
    pub fn from_points(points: &[[f64; 3]]) -> Result<Polytope, PolytopeError> {
        let pts: Vec<DVec3> = points.iter().map(|p| DVec3::from(*p)).collect();
        Self::from_dvec3s(&pts)
    }

    /// [`Polytope::from_points`] for `DVec3` input.
    pub fn from_dvec3s(points: &[DVec3]) -> Result<Polytope, PolytopeError> {
        check_finite(points)?;
        if points.len() < 4 {
            return Err(PolytopeError::TooFewPoints {
                count: points.len(),
            });
        }
        let hull = convex_hull(&FloatPoints(points))?;
        Self::from_hull(points, &hull)
    }

    fn from_hull(points: &[DVec3], hull: &ConvexHull) -> Result<Polytope, PolytopeError> {
        let mut new_index = vec![u32::MAX; points.len()];
        let mut verts = Vec::with_capacity(hull.vertices.len());
        for &i in &hull.vertices {
            new_index[i] = verts.len() as u32;
            verts.push(points[i]);
        }
        let faces: Vec<Vec<u32>> = hull
            .faces
            .iter()
            .map(|f| f.iter().map(|&i| new_index[i]).collect())
            .collect();
        Polytope::from_faces(verts, &faces)
    }

    /// A polytope from a polygon mesh, validated (see the module docs), with
    /// the default [`MeshPolicy`]. Returns the report of what changed.
    ///
    /// ```
    /// # use dymsum::{Polytope, PolygonMesh, polytope::MeshPolicy};
    /// // A cube whose faces are split into triangles: 6 maximal faces.
    /// let v = (0..8).map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64]).collect();
    /// let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    /// let faces = quads.iter().flat_map(|q| [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]]).collect();
    /// let (cube, report) = Polytope::from_mesh(&PolygonMesh::new(v, faces), MeshPolicy::default()).unwrap();
    /// assert_eq!(cube.face_count(), 6);
    /// assert!(report.exactly_convex && !report.replaced_by_hull);
    /// ```
    pub fn from_mesh(
        mesh: &PolygonMesh,
        policy: MeshPolicy,
    ) -> Result<(Polytope, ConvexityReport), PolytopeError> {
        let all: Vec<DVec3> = mesh.vertices.iter().map(|p| DVec3::from(*p)).collect();
        check_finite(&all)?;
        check_faces(mesh)?;
        check_topology(mesh)?;
        // Only referenced vertices take part.
        let mut used = vec![false; all.len()];
        for f in &mesh.faces {
            for &i in f {
                used[i] = true;
            }
        }
        let ids: Vec<usize> = (0..all.len()).filter(|&i| used[i]).collect();
        let pts: Vec<DVec3> = ids.iter().map(|&i| all[i]).collect();
        if pts.len() < 4 {
            return Err(PolytopeError::TooFewPoints { count: pts.len() });
        }
        let hull = convex_hull(&FloatPoints(&pts))?;
        let poly = Self::from_hull(&pts, &hull)?;
        let diameter = {
            let (lo, hi) = bounds(&pts);
            (hi - lo).length()
        };
        let tolerance = policy.relative_tolerance * diameter;
        let mut local = vec![usize::MAX; all.len()];
        for (k, &i) in ids.iter().enumerate() {
            local[i] = k;
        }
        let check = compare_with_hull(mesh, &all, &pts, &local, &hull, tolerance)?;
        let inward = mesh.signed_volume() < 0.0;
        let exactly = check.exact && !inward;
        if policy.strict && !exactly {
            let (what, distance) = if inward {
                ("faces are oriented inwards".to_string(), 0.0)
            } else {
                check.first_inexact.clone().unwrap_or_default()
            };
            return Err(PolytopeError::NotExactlyConvex { what, distance });
        }
        let report = ConvexityReport {
            input_vertices: mesh.vertices.len(),
            input_faces: mesh.faces.len(),
            input_triangles: mesh.triangle_count(),
            vertices: poly.vertex_count(),
            faces: poly.face_count(),
            exactly_convex: check.exact,
            replaced_by_hull: !check.exact,
            max_deviation: check.max_deviation,
            tolerance,
            dropped_vertices: mesh.vertices.len() - poly.vertex_count(),
            inward_oriented: inward,
        };
        Ok((poly, report))
    }
}

fn check_finite(points: &[DVec3]) -> Result<(), PolytopeError> {
    for (index, p) in points.iter().enumerate() {
        if !p.is_finite() {
            return Err(PolytopeError::NonFinite {
                index,
                coords: p.to_array(),
            });
        }
    }
    Ok(())
}

fn check_faces(mesh: &PolygonMesh) -> Result<(), PolytopeError> {
    let count = mesh.vertices.len();
    for (face, f) in mesh.faces.iter().enumerate() {
        if let Some(&index) = f.iter().find(|&&i| i >= count) {
            return Err(PolytopeError::IndexOutOfRange { face, index, count });
        }
        let mut s = f.clone();
        s.sort_unstable();
        s.dedup();
        if f.len() < 3 || s.len() != f.len() {
            return Err(PolytopeError::BadFace { face });
        }
    }
    Ok(())
}

/// Closed, manifold, consistently oriented, genus 0.
fn check_topology(mesh: &PolygonMesh) -> Result<(), PolytopeError> {
    let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
    for f in &mesh.faces {
        for k in 0..f.len() {
            let key = (f[k], f[(k + 1) % f.len()]);
            if directed.insert(key, k).is_some() {
                return Err(PolytopeError::NonManifoldEdge { a: key.0, b: key.1 });
            }
        }
    }
    for &(a, b) in directed.keys() {
        if !directed.contains_key(&(b, a)) {
            return Err(PolytopeError::OpenEdge { a, b });
        }
    }
    // One fan per vertex: following "next outgoing edge around the vertex"
    // from any outgoing edge must visit all of them.
    let mut out: HashMap<usize, Vec<usize>> = HashMap::new();
    let mut prev_of: HashMap<(usize, usize), usize> = HashMap::new();
    for f in &mesh.faces {
        let k = f.len();
        for i in 0..k {
            out.entry(f[i]).or_default().push(f[(i + 1) % k]);
            // In this face, the edge into f[i] comes from f[i-1].
            prev_of.insert((f[i], f[(i + 1) % k]), f[(i + k - 1) % k]);
        }
    }
    for (&v, targets) in &out {
        let start = targets[0];
        let mut cur = start;
        let mut seen = 0;
        loop {
            // Outgoing v→cur in face F; the edge into v in F is p→v; the next
            // outgoing edge around v is v→p (in the neighbouring face).
            let p = prev_of[&(v, cur)];
            cur = p;
            seen += 1;
            if cur == start || seen > targets.len() {
                break;
            }
        }
        if seen != targets.len() {
            return Err(PolytopeError::NonManifoldVertex { vertex: v });
        }
    }
    let v = out.len() as i64;
    let e = (directed.len() / 2) as i64;
    let f = mesh.faces.len() as i64;
    if v - e + f != 2 {
        return Err(PolytopeError::NotSphere { euler: v - e + f });
    }
    Ok(())
}

struct HullComparison {
    exact: bool,
    first_inexact: Option<(String, f64)>,
    max_deviation: f64,
}

/// Checks that the mesh surface lies on the hull boundary (within
/// `tolerance`), and whether it does so exactly.
fn compare_with_hull(
    mesh: &PolygonMesh,
    all: &[DVec3],
    pts: &[DVec3],
    local: &[usize],
    hull: &ConvexHull,
    tolerance: f64,
) -> Result<HullComparison, PolytopeError> {
    // Float planes of the hull faces.
    let planes: Vec<(DVec3, f64)> = hull
        .faces
        .iter()
        .map(|f| {
            let a = pts[f[0]];
            let mut n = DVec3::ZERO;
            for k in 0..f.len() {
                let p = pts[f[k]] - a;
                let q = pts[f[(k + 1) % f.len()]] - a;
                n += p.cross(q);
            }
            let n = n.normalize();
            (n, n.dot(a))
        })
        .collect();
    let mut out = HullComparison {
        exact: true,
        first_inexact: None,
        max_deviation: 0.0,
    };
    let note = |out: &mut HullComparison, what: String, d: f64| {
        if out.exact {
            out.first_inexact = Some((what, d));
        }
        out.exact = false;
    };
    // Vertices: distance inside the hull boundary.
    for (i, p) in all.iter().enumerate() {
        if local[i] == usize::MAX {
            continue;
        }
        let mut best = f64::INFINITY;
        let mut best_face = 0;
        for (h, (n, d)) in planes.iter().enumerate() {
            let dist = d - n.dot(*p);
            if dist < best {
                best = dist;
                best_face = h;
            }
        }
        let best = best.max(0.0);
        out.max_deviation = out.max_deviation.max(best);
        if best > tolerance {
            return Err(PolytopeError::NonConvex {
                what: format!("vertex {i}"),
                distance: best,
                tolerance,
            });
        }
        let f = &hull.faces[best_face];
        let on = orient(pts[f[0]], pts[f[1]], pts[f[2]], *p) == Sign::Zero;
        if !on && out.exact {
            note(
                &mut out,
                format!("vertex {i} is not on the hull boundary"),
                best,
            );
        }
    }
    // Faces: each must lie in one hull face plane.
    for (fi, f) in mesh.faces.iter().enumerate() {
        let mut best = f64::INFINITY;
        let mut best_face = 0;
        for (h, (n, d)) in planes.iter().enumerate() {
            let dev = f
                .iter()
                .map(|&i| (n.dot(all[i]) - d).abs())
                .fold(0.0, f64::max);
            if dev < best {
                best = dev;
                best_face = h;
            }
        }
        out.max_deviation = out.max_deviation.max(best);
        if best > tolerance {
            return Err(PolytopeError::NonConvex {
                what: format!("face {fi}"),
                distance: best,
                tolerance,
            });
        }
        if out.exact {
            let h = &hull.faces[best_face];
            let planar = f
                .iter()
                .all(|&i| orient(pts[h[0]], pts[h[1]], pts[h[2]], all[i]) == Sign::Zero);
            if !planar {
                note(&mut out, format!("face {fi} is not exactly planar"), best);
            }
        }
    }
    // Same volume: a mesh folding over itself would cover the hull twice.
    let hull_mesh = hull.to_mesh(&FloatPoints(pts));
    let (hv, mv) = (hull_mesh.signed_volume(), mesh.signed_volume().abs());
    let dv = (hv - mv).abs();
    let vol_tol = tolerance * hull_area(&hull_mesh) + 1e-12 * hv;
    if dv > vol_tol {
        return Err(PolytopeError::NonConvex {
            what: "volume (the mesh does not bound its convex hull)".into(),
            distance: dv,
            tolerance: vol_tol,
        });
    }
    Ok(out)
}

fn hull_area(m: &PolygonMesh) -> f64 {
    let mut a = 0.0;
    for f in &m.faces {
        let p0 = DVec3::from(m.vertices[f[0]]);
        let mut n = DVec3::ZERO;
        for w in f[1..].windows(2) {
            n += (DVec3::from(m.vertices[w[0]]) - p0).cross(DVec3::from(m.vertices[w[1]]) - p0);
        }
        a += 0.5 * n.length();
    }
    a
}
