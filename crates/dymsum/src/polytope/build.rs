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
//! Tolerances and deviations are measured relative to the shape's own size
//! (its bounding-box diagonal), in coordinates relative to the bounding-box
//! centre and scaled by a power of two (see `convexity`), so position and
//! scale do not matter.
//!
//! Complexity: O(n log n) in all: the topology check sorts the directed
//! edges per vertex (no hashing), the hull is O(n log n) expected, and the
//! mesh is matched to the hull locally through the hull's vertex–face
//! incidence and hill climbing (the old check compared every face with
//! every hull plane, O(F_mesh · F_hull)).

use super::convexity::{compare_with_hull, Frame};
use super::topology::{DirectedEdges, Unused};
use super::{Polytope, PolytopeError};
use crate::hull::{convex_hull, ConvexHull, FloatPoints};
use crate::kernel::exact;
use crate::mesh::PolygonMesh;
use glam::DVec3;

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
    /// Largest distance of a mesh vertex or face from the hull boundary
    /// (exactly `0.0` when [`exactly_convex`](Self::exactly_convex)).
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
    /// # Errors
    /// * [`PolytopeError::NonFinite`] when a coordinate is NaN or infinite
    ///   (naming the point);
    /// * [`PolytopeError::TooFewPoints`] for fewer than 4 points;
    /// * [`PolytopeError::OutOfRange`] when the coordinates span more than
    ///   960 binary orders of magnitude (say `1e300` next to `1e-300`);
    /// * [`PolytopeError::Flat`] when all points coincide, are collinear or
    ///   coplanar (the [`crate::hull::HullError`] says which);
    /// * [`PolytopeError::FaceOutOfRange`] when a hull face is below about
    ///   `2^-500` of the shape's size, and
    ///   [`PolytopeError::DegenerateGaussMap`] when a vertex's face normals
    ///   are not strictly convex after rounding: both only for slivers at
    ///   the limit of `f64`.
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
    ///
    /// # Errors
    /// The same as [`Polytope::from_points`].
    pub fn from_dvec3s(points: &[DVec3]) -> Result<Polytope, PolytopeError> {
        check_finite(points)?;
        if points.len() < 4 {
            return Err(PolytopeError::TooFewPoints {
                count: points.len(),
            });
        }
        let framed = framed(points)?;
        let hull = convex_hull(&FloatPoints(&framed))?;
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
    /// # Errors
    /// The mesh is checked in this order, and the first failure returned:
    /// * [`PolytopeError::NonFinite`]: a vertex coordinate is NaN or
    ///   infinite;
    /// * [`PolytopeError::IndexOutOfRange`]: a face names a vertex that does
    ///   not exist; [`PolytopeError::BadFace`]: a face has fewer than 3
    ///   distinct vertices;
    /// * topology: [`PolytopeError::OpenEdge`] (a hole),
    ///   [`PolytopeError::NonManifoldEdge`] (an edge used twice in one
    ///   direction: more than two faces, or inconsistent orientation),
    ///   [`PolytopeError::NonManifoldVertex`] (a pinch point),
    ///   [`PolytopeError::NotSphere`] (Euler characteristic not 2);
    /// * [`PolytopeError::TooFewPoints`], [`PolytopeError::OutOfRange`],
    ///   [`PolytopeError::Flat`], [`PolytopeError::FaceOutOfRange`] and
    ///   [`PolytopeError::DegenerateGaussMap`] as for
    ///   [`Polytope::from_points`], on the vertices the faces use;
    /// * [`PolytopeError::NonConvex`]: a vertex lies inside the hull, a face
    ///   off its boundary, or the volumes differ, by more than the policy's
    ///   tolerance (a dent, or a mesh folding over itself);
    /// * [`PolytopeError::NotExactlyConvex`]: with a strict policy
    ///   ([`MeshPolicy::strict()`]), the mesh is convex only within tolerance or
    ///   oriented inwards (it would otherwise be replaced by its exact hull).
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
        let adjacency = DirectedEdges::new(mesh.vertices.len(), &mesh.faces);
        adjacency.check_sphere(Unused::Skip)?;
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
        let hull = convex_hull(&FloatPoints(&framed(&pts)?))?;
        let poly = Self::from_hull(&pts, &hull)?;
        // The hull's corners, as polytope vertices, by mesh vertex.
        let mut corner = vec![usize::MAX; all.len()];
        for (c, &k) in hull.vertices.iter().enumerate() {
            corner[ids[k]] = c;
        }
        // The hull's own lists are no longer needed: freed before the
        // comparison's working memory is taken (it set the build's peak).
        drop(hull);
        let frame = Frame::new(&pts);
        let tolerance = frame.length(policy.relative_tolerance * frame.diagonal);
        let check = compare_with_hull(
            mesh,
            &all,
            &used,
            &corner,
            &adjacency.start,
            &adjacency.target,
            &poly,
            &frame,
            policy.relative_tolerance,
        )?;
        let inward = check.inward;
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

/// The points in their power-of-two frame (largest magnitude in `[1, 2)`),
/// after checking that their exponents span at most
/// [`exact::MAX_COORD_SPAN`] bits ([`PolytopeError::OutOfRange`]
/// otherwise), which makes the scaling exact. The hull is built on these:
/// its exact predicates give the same answers as on the input, and its
/// float heuristics see bit-identical coordinates for the same shape at
/// any scale `2^k`, so the result does not depend on the scale at all.
fn framed(points: &[DVec3]) -> Result<Vec<DVec3>, PolytopeError> {
    super::check_span(points)?;
    let k = exact::frame_exponent(points.iter().flat_map(|p| p.to_array()));
    Ok(points.iter().map(|&p| exact::mul_pow2_vec(p, k)).collect())
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
