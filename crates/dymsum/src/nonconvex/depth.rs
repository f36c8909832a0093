//! The penetration depth of two unions from their merged C-obstacle mesh.

use crate::query::scene::gap::closest_on_triangle;
use glam::DVec3;

use super::{UnionMeshError, UnionSum};
use crate::body::ConvexUnion;
use crate::kernel::rotation::Pose;
use crate::polytope::Polytope;
use crate::sum::Method;

/// The penetration depth of two overlapping unions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnionDepth {
    /// The length of the shortest translation of A that separates the
    /// bodies (to touching): the origin's distance to the boundary of the
    /// merged C-obstacle mesh.
    pub depth: f64,
    /// Unit contact normal from A towards B: translate A by
    /// `−depth · normal` to separate (as [`crate::Contact::normal`]).
    pub normal: DVec3,
    /// The separating translation of A, `−depth · normal`: the nearest point
    /// of the C-obstacle's boundary.
    pub translation: DVec3,
    /// The merged C-obstacle mesh's triangles, vertices and pairs culled.
    pub triangles: usize,
}

/// `−(pose · P)` as a polytope and pose: the negated vertices (exact)
/// under the rotation of `pose` and the negated translation.
pub(crate) fn negated(p: &Polytope, pose: Pose) -> Result<(Polytope, Pose), UnionMeshError> {
    let v: Vec<DVec3> = p.vertices().iter().map(|&x| -x).collect();
    let neg = Polytope::from_dvec3s(&v)?;
    Ok((neg, Pose::new(pose.rotation, -pose.translation)))
}

impl ConvexUnion {
    /// The penetration depth of two unions (non-convex bodies included):
    /// `None` when they do not overlap (the exact collision test of
    /// [`ConvexUnion::collides`]); otherwise the origin's distance to the
    /// boundary of the merged C-obstacle `M = (pose_b·B) ⊕ (−pose_a·A)`,
    /// the set of translations of A that make the bodies overlap, with the
    /// direction. Cavities of `M` (free pockets) count as boundary.
    ///
    /// What is exact: the collision decision and every piece-pair sum of
    /// `M`; the union's new vertices are `boolmesh`'s float constructions,
    /// and the distance is a float evaluation on its triangles. Feature
    /// `union-mesh`.
    ///
    /// ```
    /// use dymsum::{ConvexUnion, DVec3, Polytope, Pose, Rotation};
    /// let cuboid = |lo: [f64; 3], hi: [f64; 3]| {
    ///     let c: Vec<[f64; 3]> = (0..8)
    ///         .map(|i| std::array::from_fn(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
    ///         .collect();
    ///     Polytope::from_points(&c).unwrap()
    /// };
    /// let l = ConvexUnion::new(vec![cuboid([0., 0., 0.], [3., 1., 1.]), cuboid([0., 0., 0.], [1., 3., 1.])]).unwrap();
    /// let cube = ConvexUnion::new(vec![cuboid([0., 0., 0.], [1., 1., 1.])]).unwrap();
    /// let at = |x: f64, y: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, y, 0.0));
    /// // The cube sunk 0.25 into the long arm from above (y = 0.75): the
    /// // shortest way out is up, 0.25.
    /// let d = cube.penetration_depth_mesh(at(2.0, 0.75), &l, Pose::IDENTITY)?.unwrap();
    /// assert!((d.depth - 0.25).abs() < 1e-12);
    /// assert!((d.normal - DVec3::new(0.0, -1.0, 0.0)).length() < 1e-12);
    /// assert_eq!(cube.penetration_depth_mesh(at(1.5, 1.5), &l, Pose::IDENTITY)?, None);
    /// # Ok::<(), dymsum::nonconvex::UnionMeshError>(())
    /// ```
    ///
    /// # Errors
    /// [`UnionMeshError::Query`] from the collision test;
    /// [`UnionMeshError::Polytope`] when a negated piece cannot be built;
    /// those of [`UnionSum::new`] for the C-obstacle.
    pub fn penetration_depth_mesh(
        &self,
        pose: Pose,
        other: &ConvexUnion,
        other_pose: Pose,
    ) -> Result<Option<UnionDepth>, UnionMeshError> {
        if !self.collides(pose, other, other_pose)? {
            return Ok(None);
        }
        let mut pieces = Vec::new();
        let mut neg_pose = Pose::IDENTITY;
        for p in self.pieces() {
            let (n, np) = negated(p, pose)?;
            pieces.push(n);
            neg_pose = np;
        }
        let neg = ConvexUnion::new(pieces)
            .ok_or(UnionMeshError::Invalid(crate::solid::SolidError::Empty))?;
        let m = UnionSum::new(other, other_pose, &neg, neg_pose, Method::Walk, true)?;
        let (c, _) = closest_boundary_point(m.mesh(), DVec3::ZERO);
        let depth = c.length();
        let normal = if depth > 0.0 { -c / depth } else { DVec3::ZERO };
        Ok(Some(UnionDepth {
            depth,
            normal,
            translation: c,
            triangles: m.info().mesh.triangles,
        }))
    }
}

/// The nearest point to `q` on a mesh's triangles, and its distance.
pub(crate) fn closest_boundary_point(mesh: &crate::mesh::PolygonMesh, q: DVec3) -> (DVec3, f64) {
    let mut best = (DVec3::splat(f64::INFINITY), f64::INFINITY);
    for f in &mesh.faces {
        let a = DVec3::from(mesh.vertices[f[0]]);
        for w in f[1..].windows(2) {
            let p = closest_on_triangle(
                q,
                &[
                    a,
                    DVec3::from(mesh.vertices[w[0]]),
                    DVec3::from(mesh.vertices[w[1]]),
                ],
            );
            let d = (p - q).length();
            if d < best.1 {
                best = (p, d);
            }
        }
    }
    best
}
