//! Conversions to and from [parry3d-f64](https://parry.rs) 0.31 (Cargo
//! feature `parry`).
//!
//! # What converts to what
//! | from | to | trait |
//! | --- | --- | --- |
//! | [`Pose`] | parry's `math::Pose` (its isometry, glamx `DPose3`) | `From` |
//! | parry's `math::Pose` | [`Pose`] | `TryFrom` |
//! | `&`[`Polytope`] | `shape::ConvexPolyhedron` | `TryFrom` |
//! | `&shape::ConvexPolyhedron` | [`Polytope`] | `TryFrom` |
//!
//! Vectors need no conversion: parry's `math::Vector` is glam's `DVec3`, the
//! same type as [`glam::DVec3`]; parry's `math::Rotation` is glam's `DQuat`,
//! which converts to and from [`crate::kernel::rotation::Rotation`] in [`super`].
//!
//! # Conventions
//! parry's pose maps `p ↦ rotation · p + translation`, as [`Pose::apply`]
//! does; its rotation is a glam quaternion (`x, y, z, w` stored, Hamilton
//! product, active). Faces on both sides are listed counter-clockwise seen
//! from outside.
//!
//! # Shapes
//! * Polytope → `ConvexPolyhedron`: the polytope's vertices, bit for bit,
//!   and its faces fan-triangulated, through
//!   `ConvexPolyhedron::from_convex_mesh`. parry merges neighbouring
//!   triangles whose float normals differ by less than about `1.7e-4` rad
//!   (its `1 − √ε` test on the dot product), so its face count can be lower
//!   than [`Polytope::face_count`] for nearly coplanar faces; the shape (the
//!   hull of the same vertices) is the same.
//! * `ConvexPolyhedron` → Polytope (`TryFrom`): the *exact* convex hull
//!   of all of parry's points ([`Polytope::from_dvec3s`]), coordinates bit
//!   for bit. That is the shape parry's own queries see: its support map
//!   (GJK, EPA, distances, contacts) runs over all its points, while its
//!   faces are a float approximation in which nearly coplanar triangles are
//!   merged and a vertex inside such a merged face is on no face at all. So
//!   `Polytope → ConvexPolyhedron → Polytope` gives back the same vertices
//!   and faces for every polytope.
//! * [`to_polytope`] instead reads parry's points *and* faces as a
//!   [`PolygonMesh`] ([`to_polygon_mesh`]) through [`Polytope::from_mesh`]:
//!   the face structure is validated (closed, manifold, a sphere, convex
//!   within the policy's tolerance, exactly planar under
//!   [`MeshPolicy::strict`]), the [`ConvexityReport`] says what was found,
//!   and the polytope is the exact hull of the points the faces use (so
//!   without a vertex parry's face merging left on no face).
//!
//! # What can fail
//! * parry pose → [`Pose`]: a zero or non-finite quaternion
//!   ([`InteropError::BadQuaternion`]) or a non-finite translation
//!   ([`InteropError::NonFiniteTranslation`]).
//! * Polytope → `ConvexPolyhedron`: a triangle whose edge directions or
//!   normal parry's float arithmetic cannot normalise (squares underflow or
//!   overflow: shapes of even aspect below about `1e-77` or above about
//!   `1e77` in size, which dymsum supports and parry would silently
//!   mangle; [`InteropError::ParryOutOfRange`], checked before calling
//!   parry by the same float operations parry does); parry returns `None`
//!   or no faces ([`InteropError::ParryRefused`]; not seen for a valid
//!   polytope); a face normal of parry's that is not a finite unit vector
//!   ([`InteropError::ParryDegenerateNormal`]; a check on parry's output
//!   that the range check makes unreachable).
//! * `ConvexPolyhedron` → Polytope: any [`PolytopeError`] of
//!   [`Polytope::from_dvec3s`] ([`PolytopeError::TooFewPoints`],
//!   [`PolytopeError::Flat`] for a flat polyhedron,
//!   [`PolytopeError::NonFinite`], [`PolytopeError::OutOfRange`]); through
//!   [`to_polytope`] any of [`Polytope::from_mesh`] (e.g.
//!   [`PolytopeError::OpenEdge`] when parry dropped a degenerate face,
//!   [`PolytopeError::NonConvex`] for a dented mesh parry accepted).
//!
//! ```
//! use dymsum::{DVec3, Polytope, Pose, Rotation};
//! use parry3d_f64::shape::ConvexPolyhedron;
//!
//! let cube: Vec<[f64; 3]> = (0..8)
//!     .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
//!     .collect();
//! let p = Polytope::from_points(&cube).unwrap();
//! let shape = ConvexPolyhedron::try_from(&p).unwrap();
//! assert_eq!(shape.points().len(), 8);
//! let back = Polytope::try_from(&shape).unwrap();
//! assert_eq!((back.vertex_count(), back.face_count()), (8, 6));
//!
//! let pose = Pose::new(Rotation::from_axis_angle(DVec3::Z, 0.3).unwrap(), DVec3::X);
//! let iso = parry3d_f64::math::Pose::from(pose);
//! let q = DVec3::new(0.5, -1.0, 2.0);
//! assert!((iso.transform_point(q) - pose.apply(q)).length() < 1e-15);
//! assert_eq!(Pose::try_from(iso).unwrap(), pose);
//! ```

use super::{pose_from_parts, InteropError};
use crate::kernel::rotation::Pose;
use crate::mesh::PolygonMesh;
use crate::polytope::Polytope;
use crate::polytope::PolytopeError;
use crate::polytope::{ConvexityReport, MeshPolicy};
use parry3d_f64::math::Pose as ParryPose;
use parry3d_f64::shape::ConvexPolyhedron;

impl From<Pose> for ParryPose {
    /// parry's pose with the same rotation (the unit quaternion, `w ≥ 0`)
    /// and translation.
    fn from(p: Pose) -> ParryPose {
        ParryPose::from_parts(p.translation, p.rotation.quat())
    }
}

impl TryFrom<ParryPose> for Pose {
    type Error = InteropError;

    /// The pose of a parry pose; a non-unit quaternion is normalised.
    ///
    /// # Errors
    /// [`InteropError::BadQuaternion`] for a zero or non-finite quaternion,
    /// [`InteropError::NonFiniteTranslation`] for a non-finite translation.
    fn try_from(p: ParryPose) -> Result<Pose, InteropError> {
        pose_from_parts(p.rotation.to_array(), p.translation)
    }
}

impl TryFrom<&Polytope> for ConvexPolyhedron {
    type Error = InteropError;

    /// parry's polyhedron of the polytope's vertices (bit for bit) and
    /// fan-triangulated faces (see the module docs for parry's face
    /// merging).
    ///
    /// # Errors
    /// [`InteropError::ParryOutOfRange`] when parry's float arithmetic
    /// cannot normalise an edge direction or a triangle normal (shapes below
    /// about `1e-77` or above about `1e77`); [`InteropError::ParryRefused`]
    /// when parry returns `None` or no faces;
    /// [`InteropError::ParryDegenerateNormal`] when a face normal of parry's
    /// is not a finite unit vector.
    fn try_from(p: &Polytope) -> Result<ConvexPolyhedron, InteropError> {
        let points = p.vertices().to_vec();
        let mut triangles = Vec::with_capacity(p.triangle_count());
        for face in p.faces() {
            for w in face[1..].windows(2) {
                triangles.push([face[0], w[0], w[1]]);
            }
        }
        // parry's own float steps (from_convex_mesh: each edge direction
        // `(b - a).try_normalize()`, each triangle normal
        // `(b - a).cross(c - a).try_normalize()`) need squared lengths that
        // are normal floats: zero or infinite makes parry drop the edge or
        // give the face a zero normal, subnormal makes the "unit" normal
        // off by up to 100%, silently.
        for t in &triangles {
            let [a, b, c] = t.map(|i| points[i as usize]);
            let normalisable = [b - a, c - b, a - c, (b - a).cross(c - a)]
                .iter()
                .all(|v| v.length_squared().is_normal());
            if !normalisable {
                return Err(InteropError::ParryOutOfRange { triangle: *t });
            }
        }
        let refused = InteropError::ParryRefused {
            vertices: points.len(),
            triangles: triangles.len(),
        };
        let shape = ConvexPolyhedron::from_convex_mesh(points, &triangles)
            .filter(|s| !s.faces().is_empty())
            .ok_or(refused)?;
        for (face, f) in shape.faces().iter().enumerate() {
            // parry normalises its normals and stores a failed one as zero.
            if !f.normal.is_finite() || (f.normal.length_squared() - 1.0).abs() > 1e-6 {
                return Err(InteropError::ParryDegenerateNormal {
                    face,
                    normal: f.normal.to_array(),
                });
            }
        }
        Ok(shape)
    }
}

impl TryFrom<&ConvexPolyhedron> for Polytope {
    type Error = PolytopeError;

    /// The exact convex hull of all of parry's points, the shape parry's
    /// support map sees (see the module docs; [`to_polytope`] validates
    /// parry's faces instead).
    ///
    /// # Errors
    /// Any [`PolytopeError`] of [`Polytope::from_dvec3s`]: fewer than 4
    /// points, all points in a plane ([`PolytopeError::Flat`]), a
    /// non-finite coordinate, coordinates out of range.
    fn try_from(shape: &ConvexPolyhedron) -> Result<Polytope, PolytopeError> {
        Polytope::from_dvec3s(shape.points())
    }
}

/// parry's points and polygonal faces as a [`PolygonMesh`]: every point
/// (also points no face uses), each face's vertices in parry's order
/// (counter-clockwise seen from outside). No validation.
pub fn to_polygon_mesh(shape: &ConvexPolyhedron) -> PolygonMesh {
    let adj = shape.vertices_adj_to_face();
    let faces = shape
        .faces()
        .iter()
        .map(|f| {
            let start = f.first_vertex_or_edge as usize;
            let end = start + f.num_vertices_or_edges as usize;
            adj[start..end].iter().map(|&v| v as usize).collect()
        })
        .collect();
    PolygonMesh::new(shape.points().iter().map(|p| p.to_array()).collect(), faces)
}

/// A polytope from a parry polyhedron's points *and* faces, validated as a
/// mesh under a given [`MeshPolicy`], with the report of what
/// [`Polytope::from_mesh`] found (e.g. whether parry's faces were exactly
/// planar). The polytope is the exact hull of the points parry's faces use;
/// a point on no face (inside a face parry merged) is left out, unlike
/// `Polytope::try_from(&ConvexPolyhedron)`.
///
/// ```
/// use dymsum::interop::parry::to_polytope;
/// use dymsum::polytope::MeshPolicy;
/// use parry3d_f64::math::Vector;
/// use parry3d_f64::shape::ConvexPolyhedron;
///
/// let pts = [Vector::ZERO, Vector::X, Vector::Y, Vector::Z, Vector::splat(0.1)];
/// let shape = ConvexPolyhedron::from_convex_hull(&pts).unwrap();
/// let (tet, report) = to_polytope(&shape, MeshPolicy::strict()).unwrap();
/// assert_eq!((tet.vertex_count(), tet.face_count()), (4, 4));
/// assert!(report.exactly_convex);
/// ```
///
/// # Errors
/// Any [`PolytopeError`] of [`Polytope::from_mesh`]; with
/// [`MeshPolicy::strict`] also [`PolytopeError::NotExactlyConvex`] when a
/// face parry merged is not exactly planar.
pub fn to_polytope(
    shape: &ConvexPolyhedron,
    policy: MeshPolicy,
) -> Result<(Polytope, ConvexityReport), PolytopeError> {
    Polytope::from_mesh(&to_polygon_mesh(shape), policy)
}
