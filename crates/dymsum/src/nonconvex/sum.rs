//! `A ⊕ B` of unions of convex pieces: the exact piece-pair sums, culled,
//! merged into one validated closed mesh.

use glam::DVec3;

use super::merge::union_meshes;
use super::UnionMeshError;
use crate::body::ConvexUnion;
use crate::dynamic::DynamicSum;
use crate::dynamic::UpdateReport;
use crate::kernel::rotation::Pose;
use crate::kernel::rotation::Rotation;
use crate::mesh::PolygonMesh;
use crate::sanity::SanityError;
use crate::solid::closed::ClosedMeshInfo;
use crate::sum::contained::uncontained;
use crate::sum::{minkowski_sum_posed, Method};

/// How a [`UnionSum`] was made, and what it measured.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct UnionSumInfo {
    /// The number of pieces of A and of B.
    pub pieces: (usize, usize),
    /// Piece pairs (`pieces.0 · pieces.1`).
    pub pairs: usize,
    /// Pair sums left out of the union: certified inside another pair sum
    /// (exact orientation tests on its vertices).
    pub pairs_culled: usize,
    /// The merged mesh: vertices, triangles, volume, shells, genus.
    pub mesh: ClosedMeshInfo,
}

/// `A ⊕ B` of two unions of convex pieces as one closed mesh.
///
/// The L of two boxes plus a 0.5 cube placed four times far apart (each
/// a piece of B): four closed shells of volume 12.375 each.
///
/// ```
/// use dymsum::nonconvex::UnionSum;
/// use dymsum::{sum::Method, ConvexUnion, Polytope, Pose};
/// let cuboid = |lo: [f64; 3], hi: [f64; 3]| {
///     let c: Vec<[f64; 3]> = (0..8)
///         .map(|i| std::array::from_fn(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
///         .collect();
///     Polytope::from_points(&c).unwrap()
/// };
/// let l = ConvexUnion::new(vec![cuboid([0., 0., 0.], [3., 1., 1.]), cuboid([0., 0., 0.], [1., 3., 1.])]).unwrap();
/// let cubes = ConvexUnion::new(
///     [[0., 0., 0.], [10., 0., 0.], [0., 0., 5.], [-3., -3., 0.]]
///         .iter()
///         .map(|o: &[f64; 3]| cuboid(*o, std::array::from_fn(|k| o[k] + 0.5)))
///         .collect(),
/// )
/// .unwrap();
/// let sum = UnionSum::new(&l, Pose::IDENTITY, &cubes, Pose::IDENTITY, Method::Walk, true)?;
/// // Four disjoint copies of the L grown by the cube, 12.375 each.
/// assert!((sum.info().mesh.volume - 4.0 * 12.375).abs() < 1e-9);
/// assert_eq!(sum.info().mesh.shells, 4);
/// assert_eq!(sum.info().mesh.genus, 0);
/// # Ok::<(), dymsum::nonconvex::UnionMeshError>(())
/// ```
#[derive(Clone, Debug)]
pub struct UnionSum {
    mesh: PolygonMesh,
    info: UnionSumInfo,
}

impl UnionSum {
    /// `(pose_a · A) ⊕ (pose_b · B)`: every piece-pair sum exactly (by
    /// `method`), pair sums certified inside another dropped when `cull`,
    /// the rest merged by `boolmesh` and validated.
    ///
    /// # Errors
    /// [`UnionMeshError::Sum`] or [`UnionMeshError::Mesh`] from a pair sum
    /// (a posed vertex out of range); [`UnionMeshError::Boolean`] when
    /// `boolmesh` refuses a mesh or fails; [`UnionMeshError::Invalid`] when
    /// the merged mesh fails validation (never returned).
    pub fn new(
        a: &ConvexUnion,
        pose_a: Pose,
        b: &ConvexUnion,
        pose_b: Pose,
        method: Method,
        cull: bool,
    ) -> Result<UnionSum, UnionMeshError> {
        let mut sums = Vec::new();
        for (i, p) in a.pieces().iter().enumerate() {
            for (j, q) in b.pieces().iter().enumerate() {
                let s = minkowski_sum_posed(p, pose_a, q, pose_b, method)?;
                sums.push(((i, j), s.try_to_mesh()?));
            }
        }
        merge_pair_sums(sums, (a.pieces().len(), b.pieces().len()), cull)
    }

    /// The merged mesh: triangles, counter-clockwise seen from outside.
    pub fn mesh(&self) -> &PolygonMesh {
        &self.mesh
    }

    /// The merged mesh, owned.
    pub fn into_mesh(self) -> PolygonMesh {
        self.mesh
    }

    /// How it was made and what it measured.
    pub fn info(&self) -> &UnionSumInfo {
        &self.info
    }

    /// Re-checks the mesh ([`super::check_closed_mesh`]) and that its
    /// measurements are those recorded.
    ///
    /// # Errors
    /// [`SanityError::UnionMesh`] naming the failed check.
    pub fn sanity_check(&self) -> Result<(), SanityError> {
        let info = super::check_closed_mesh(&self.mesh).map_err(|e| SanityError::UnionMesh {
            reason: e.to_string(),
        })?;
        if info != self.info.mesh {
            return Err(SanityError::UnionMesh {
                reason: format!("measured {info:?}, recorded {:?}", self.info.mesh),
            });
        }
        if self.info.pairs != self.info.pieces.0 * self.info.pieces.1
            || self.info.pairs_culled >= self.info.pairs
        {
            return Err(SanityError::UnionMesh {
                reason: format!("pair counts {:?}", self.info),
            });
        }
        Ok(())
    }
}

/// Culls and merges pair sums `((i, j), mesh)`.
fn merge_pair_sums(
    sums: Vec<((usize, usize), PolygonMesh)>,
    pieces: (usize, usize),
    cull: bool,
) -> Result<UnionSum, UnionMeshError> {
    let pairs = sums.len();
    let kept = if cull { cull_contained(sums) } else { sums };
    let named: Vec<(String, PolygonMesh)> = kept
        .into_iter()
        .map(|((i, j), m)| (format!("the sum of pieces {i} and {j}"), m))
        .collect();
    let pairs_culled = pairs - named.len();
    let (mesh, info) = union_meshes(&named)?;
    Ok(UnionSum {
        mesh,
        info: UnionSumInfo {
            pieces,
            pairs,
            pairs_culled,
            mesh: info,
        },
    })
}

/// Drops convex pair sums certified inside another kept one
/// ([`crate::sum::contained::uncontained`]).
fn cull_contained(sums: Vec<((usize, usize), PolygonMesh)>) -> Vec<((usize, usize), PolygonMesh)> {
    let meshes: Vec<&PolygonMesh> = sums.iter().map(|(_, m)| m).collect();
    let mut keep = vec![false; sums.len()];
    for k in uncontained(&meshes) {
        keep[k] = true;
    }
    sums.into_iter()
        .zip(keep)
        .filter_map(|(s, k)| k.then_some(s))
        .collect()
}

/// `A ⊕ B` of unions kept up to date while they move: one [`DynamicSum`]
/// per piece pair, repaired by DYMSUM on each pose change (exact, as for
/// convex bodies); [`DynamicUnionSum::union`] merges the current pair sums
/// into one validated closed mesh, redone on each call.
///
/// ```
/// use dymsum::nonconvex::DynamicUnionSum;
/// use dymsum::{ConvexUnion, Polytope, Pose, Rotation, DVec3};
/// let cube = |o: [f64; 3]| {
///     let c: Vec<[f64; 3]> = (0..8).map(|i| std::array::from_fn(|k| o[k] + (i >> k & 1) as f64)).collect();
///     Polytope::from_points(&c).unwrap()
/// };
/// let l = ConvexUnion::new(vec![cube([0., 0., 0.]), cube([1., 0., 0.]), cube([0., 1., 0.])]).unwrap();
/// let mut d = DynamicUnionSum::new(&l, Pose::IDENTITY, &l, Pose::IDENTITY)?;
/// let r = Rotation::from_axis_angle(DVec3::Z, 0.3).unwrap();
/// d.set_pose(Pose::new(r, DVec3::ZERO), Pose::IDENTITY);
/// let sum = d.union(true)?;
/// assert_eq!(sum.info().pairs, 9);
/// sum.sanity_check().unwrap();
/// # Ok::<(), dymsum::nonconvex::UnionMeshError>(())
/// ```
#[derive(Clone, Debug)]
pub struct DynamicUnionSum {
    pieces: (usize, usize),
    sums: Vec<((usize, usize), DynamicSum)>,
}

impl DynamicUnionSum {
    /// One dynamic sum per piece pair, at the given poses.
    ///
    /// # Errors
    /// [`UnionMeshError::Sum`] when a posed vertex is out of range.
    pub fn new(
        a: &ConvexUnion,
        pose_a: Pose,
        b: &ConvexUnion,
        pose_b: Pose,
    ) -> Result<DynamicUnionSum, UnionMeshError> {
        let mut sums = Vec::new();
        for (i, p) in a.pieces().iter().enumerate() {
            for (j, q) in b.pieces().iter().enumerate() {
                sums.push(((i, j), DynamicSum::new(p, pose_a, q, pose_b)?));
            }
        }
        Ok(DynamicUnionSum {
            pieces: (a.pieces().len(), b.pieces().len()),
            sums,
        })
    }

    /// The number of piece pairs.
    pub fn pair_count(&self) -> usize {
        self.sums.len()
    }

    /// The piece pairs `(piece of A, piece of B)` and their dynamic sums.
    pub fn pairs(&self) -> impl Iterator<Item = ((usize, usize), &DynamicSum)> + '_ {
        self.sums.iter().map(|(ij, s)| (*ij, s))
    }

    /// Turns A further by `r` about the origin (every pair sum repaired by
    /// DYMSUM). Returns one report per pair, in pair order.
    pub fn rotate_a_by(&mut self, r: Rotation) -> Vec<UpdateReport> {
        self.sums
            .iter_mut()
            .map(|(_, s)| s.rotate_p_by(r))
            .collect()
    }

    /// Moves both bodies; every pair sum is repaired by DYMSUM. Returns one
    /// report per pair, in pair order.
    pub fn set_pose(&mut self, pose_a: Pose, pose_b: Pose) -> Vec<UpdateReport> {
        self.sums
            .iter_mut()
            .map(|(_, s)| s.set_pose(pose_a, pose_b))
            .collect()
    }

    /// The current pair sums merged into one closed mesh (as
    /// [`UnionSum::new`]).
    ///
    /// # Errors
    /// As [`UnionSum::new`].
    pub fn union(&self, cull: bool) -> Result<UnionSum, UnionMeshError> {
        let sums = self
            .sums
            .iter()
            .map(|(ij, s)| s.try_to_mesh().map(|m| (*ij, m)))
            .collect::<Result<Vec<_>, _>>()?;
        merge_pair_sums(sums, self.pieces, cull)
    }

    /// Every pair's [`DynamicSum::sanity_check`].
    ///
    /// # Errors
    /// The first pair's failure.
    pub fn sanity_check(&self) -> Result<(), SanityError> {
        self.sums.iter().try_for_each(|(_, s)| s.sanity_check())
    }
}

impl ConvexUnion {
    /// C-obstacle slices of this union as a robot among `obstacle`, each
    /// merged into one closed mesh: for each orientation `R`, the union of
    /// the piece-pair sums `O_j ⊕ (−R·A_i)` (the translations that make the
    /// robot overlap the obstacle). One [`DynamicSum`] per piece pair is
    /// turned from orientation to orientation by DYMSUM (exact); the union
    /// is redone per slice by `boolmesh` and validated, as
    /// [`UnionSum::new`]. Feature `union-mesh`.
    ///
    /// ```
    /// use dymsum::query::orientations_about_axis;
    /// use dymsum::{ConvexUnion, DVec3, Polytope};
    /// let cuboid = |lo: [f64; 3], hi: [f64; 3]| {
    ///     let c: Vec<[f64; 3]> = (0..8)
    ///         .map(|i| std::array::from_fn(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
    ///         .collect();
    ///     Polytope::from_points(&c).unwrap()
    /// };
    /// let l = ConvexUnion::new(vec![cuboid([0., 0., 0.], [3., 1., 1.]), cuboid([0., 0., 0.], [1., 3., 1.])]).unwrap();
    /// let turns = orientations_about_axis(DVec3::Z, 4).unwrap();
    /// let slices = l.cobstacle_union_slices(&l, &turns)?;
    /// assert_eq!(slices.len(), 4);
    /// assert!(slices.iter().all(|s| s.info().mesh.shells == 1));
    /// # Ok::<(), dymsum::nonconvex::UnionMeshError>(())
    /// ```
    ///
    /// # Errors
    /// [`UnionMeshError::Polytope`] when a negated piece cannot be built;
    /// those of [`UnionSum::new`] for a slice.
    pub fn cobstacle_union_slices(
        &self,
        obstacle: &ConvexUnion,
        orientations: &[Rotation],
    ) -> Result<Vec<UnionSum>, UnionMeshError> {
        let Some(&first) = orientations.first() else {
            return Ok(Vec::new());
        };
        let neg = self
            .pieces()
            .iter()
            .map(|p| super::depth::negated(p, Pose::IDENTITY).map(|(n, _)| n))
            .collect::<Result<Vec<_>, _>>()?;
        let neg = ConvexUnion::new(neg)
            .ok_or(UnionMeshError::Invalid(crate::solid::SolidError::Empty))?;
        let at = |r: Rotation| Pose::new(r, DVec3::ZERO);
        let mut sums = DynamicUnionSum::new(obstacle, Pose::IDENTITY, &neg, at(first))?;
        let mut out = Vec::with_capacity(orientations.len());
        for &r in orientations {
            sums.set_pose(Pose::IDENTITY, at(r));
            out.push(sums.union(true)?);
        }
        Ok(out)
    }
}
