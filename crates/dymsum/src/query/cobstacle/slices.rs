//! Configuration-space obstacles of a translating and rotating robot, one
//! slice per robot orientation.
//!
//! With the robot's reference point at its origin, the robot at orientation
//! `R` and translation `t` occupies `R·A + t`, which meets the obstacle `O`
//! exactly when `t ∈ O ⊕ (−R·A)`. That sum is the C-obstacle slice at `R`.
//! `−R·A = R·(−A)`, so one reflected robot `−A` is built once and rotated;
//! consecutive slices are computed by a [`DynamicSum`] moved from slice to
//! slice (DYMSUM updates). The result of every slice is identical to the
//! static sum at that orientation, so the batch form
//! ([`CObstacle::slices_par`]) — contiguous chunks of the orientation list,
//! one dynamic sum per chunk, chunks on rayon's threads — returns exactly
//! the sequential result, in order.
//!
//! ```
//! use dymsum::{Polytope, DVec3};
//! use dymsum::query::{cobstacle_slices, orientations_about_axis};
//! let tet = Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]]).unwrap();
//! let box_: Vec<[f64; 3]> = (0..8)
//!     .map(|i| [2.0 * (i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
//!     .collect();
//! let obstacle = Polytope::from_points(&box_).unwrap();
//! let turns = orientations_about_axis(DVec3::Z, 8).unwrap();
//! let slices = cobstacle_slices(&tet, &obstacle, &turns).unwrap();
//! assert_eq!(slices.len(), 8);
//! ```

use crate::dynamic::DynamicSum;
use crate::kernel::rotation::Pose;
use crate::kernel::rotation::Rotation;
use crate::mesh::PolygonMesh;
use crate::polytope::Polytope;
use crate::query::error::QueryError;
use crate::query::prep::Reflected;
use crate::sum::{minkowski_sum_posed, Method};
use glam::DVec3;
use rayon::prelude::*;

/// `n` rotations about `axis`, by the angles `2πk/n` for `k = 0..n`.
/// `None` for a zero or non-finite axis or `n = 0`.
pub fn orientations_about_axis(axis: DVec3, n: usize) -> Option<Vec<Rotation>> {
    if n == 0 {
        return None;
    }
    (0..n)
        .map(|k| {
            let angle = std::f64::consts::TAU * k as f64 / n as f64;
            Rotation::from_axis_angle(axis, angle)
        })
        .collect()
}

/// A robot (reflected once) and an obstacle, ready to be sliced.
///
/// The slices at turns about `z`, computed by one dynamic sum moved from
/// slice to slice, equal the slices computed from scratch, and so do the
/// parallel ones:
///
/// ```
/// use dymsum::query::orientations_about_axis;
/// use dymsum::{CObstacle, DVec3, Polytope};
/// let tet = Polytope::from_points(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]])?;
/// let corners: Vec<[f64; 3]> = (0..8)
///     .map(|i| [4.0 + 2.0 * (i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
///     .collect();
/// let obstacle = Polytope::from_points(&corners)?;
/// let cobst = CObstacle::new(&tet, &obstacle)?;
/// let turns = orientations_about_axis(DVec3::Z, 12).ok_or("zero axis")?;
/// let slices = cobst.slices(&turns).collect::<Result<Vec<_>, _>>()?;
/// assert_eq!(slices.len(), 12);
/// for (slice, &turn) in slices.iter().zip(&turns) {
///     assert_eq!(*slice, cobst.slice(turn)?);
///     // A slice holds a translate of the obstacle: at least its volume 2.
///     assert!(slice.signed_volume() > 2.0);
/// }
/// assert_eq!(cobst.slices_par(&turns)?, slices);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct CObstacle {
    neg_robot: std::sync::Arc<Reflected>,
    obstacle: Polytope,
    /// The bodies' reach, for the half-space slices.
    pub(in crate::query) reaches: Reaches,
    /// The reflected robot's face depths (the half-space slices' O(1)
    /// offsets, `halfspaces.rs`).
    face_depths: std::sync::Arc<[crate::query::cobstacle::face_depths::FaceDepth]>,
}

impl CObstacle {
    /// Prepares `robot` (reflects it, [`Reflected::new`]) against `obstacle`.
    ///
    /// # Errors
    /// None for polytopes built by this crate, as [`ConvexPair::new`](crate::query::pair::ConvexPair::new).
    pub fn new(robot: &Polytope, obstacle: &Polytope) -> Result<Self, QueryError> {
        let neg_robot = Reflected::new(robot);
        Ok(CObstacle {
            reaches: Reaches::of(&neg_robot.polytope, obstacle),
            face_depths: crate::query::cobstacle::face_depths::face_depths(&neg_robot.polytope)
                .into(),
            neg_robot: std::sync::Arc::new(neg_robot),
            obstacle: obstacle.clone(),
        })
    }

    /// The reflected robot's face depths (`face_depths.rs`).
    pub(in crate::query) fn face_depths(
        &self,
    ) -> &[crate::query::cobstacle::face_depths::FaceDepth] {
        &self.face_depths
    }

    /// The reflected robot `−A`.
    pub fn reflected_robot(&self) -> &Polytope {
        &self.neg_robot.polytope
    }

    /// The obstacle `O`.
    pub fn obstacle(&self) -> &Polytope {
        &self.obstacle
    }

    /// The slice at one orientation, computed from scratch.
    ///
    /// # Errors
    /// * [`QueryError::Sum`] wrapping [`crate::error::SumError::OutOfRange`] when a
    ///   rotated robot vertex overflows `f64`;
    /// * [`QueryError::Mesh`] when the slice's mesh cannot be produced:
    ///   [`crate::sum::MeshError::PrecisionLost`] (the obstacle is too far
    ///   from the origin for the shapes' size) or
    ///   [`crate::sum::MeshError::OutOfRange`] (a vertex of the slice
    ///   overflows `f64`); other mesh errors are internal;
    /// * [`QueryError::Sum`] wrapping [`crate::error::SumError::Inconsistent`] only
    ///   for an internal error.
    pub fn slice(&self, orientation: Rotation) -> Result<PolygonMesh, QueryError> {
        let sum = minkowski_sum_posed(
            &self.neg_robot.polytope,
            Pose::new(orientation, DVec3::ZERO),
            &self.obstacle,
            Pose::IDENTITY,
            Method::Walk,
        )?;
        Ok(sum.try_to_mesh()?)
    }

    /// The slices in order, one dynamic sum moved from slice to slice; the
    /// iterator yields `Err` (and then stops) if an update fails.
    pub fn slices<'s>(
        &'s self,
        orientations: &'s [Rotation],
    ) -> impl Iterator<Item = Result<PolygonMesh, QueryError>> + 's {
        let mut sum: Option<DynamicSum> = None;
        let mut failed = false;
        orientations.iter().map_while(move |&r| {
            if failed {
                return None;
            }
            let res = self
                .advance(&mut sum, r)
                .and_then(|s| s.try_to_mesh().map_err(QueryError::from));
            failed = res.is_err();
            Some(res)
        })
    }

    pub(in crate::query) fn advance<'b>(
        &self,
        sum: &'b mut Option<DynamicSum>,
        r: Rotation,
    ) -> Result<&'b DynamicSum, QueryError> {
        let pose = Pose::new(r, DVec3::ZERO);
        Ok(match sum {
            Some(s) => {
                s.set_pose(pose, Pose::IDENTITY);
                s
            }
            None => sum.insert(DynamicSum::new(
                &self.neg_robot.polytope,
                pose,
                &self.obstacle,
                Pose::IDENTITY,
            )?),
        })
    }

    /// Maps every slice through `f(index, orientation, sum)` in parallel:
    /// the orientations are split into contiguous chunks (about four per
    /// thread), each chunk walked by its own dynamic sum on a rayon thread.
    /// Results are in input order and do not depend on the chunking.
    ///
    /// # Errors
    /// [`QueryError::Sum`] wrapping [`crate::error::SumError::Inconsistent`] if
    /// building a chunk's first dynamic sum hits an internal error (a bug;
    /// the updates themselves cannot fail); `f` itself cannot fail
    /// here (return a `Result` from it to report per-slice failures, as
    /// [`CObstacle::slices_par`] does).
    pub fn map_par<T, F>(&self, orientations: &[Rotation], f: F) -> Result<Vec<T>, QueryError>
    where
        T: Send,
        F: Fn(usize, Rotation, &DynamicSum) -> T + Sync,
    {
        if orientations.is_empty() {
            return Ok(Vec::new());
        }
        let chunks = (rayon::current_num_threads() * 4).max(1);
        let size = orientations.len().div_ceil(chunks).max(1);
        let parts: Vec<Result<Vec<T>, QueryError>> = orientations
            .par_chunks(size)
            .enumerate()
            .map(|(c, chunk)| {
                let mut sum = None;
                chunk
                    .iter()
                    .enumerate()
                    .map(|(i, &r)| {
                        let s = self.advance(&mut sum, r)?;
                        Ok(f(c * size + i, r, s))
                    })
                    .collect()
            })
            .collect();
        let mut out = Vec::with_capacity(orientations.len());
        for p in parts {
            out.extend(p?);
        }
        Ok(out)
    }

    /// All slices, computed in parallel (see [`CObstacle::map_par`]).
    ///
    /// # Errors
    /// The first failing slice, in input order:
    /// [`QueryError::Sum`] wrapping [`crate::error::SumError::Inconsistent`] if
    /// building a chunk's first dynamic sum hits an internal error (a bug);
    /// [`QueryError::Mesh`] when a slice's mesh cannot be produced
    /// ([`crate::sum::MeshError::PrecisionLost`] for an obstacle too far from
    /// the origin for the shapes' size, [`crate::sum::MeshError::OutOfRange`]
    /// for a vertex beyond `f64`).
    pub fn slices_par(&self, orientations: &[Rotation]) -> Result<Vec<PolygonMesh>, QueryError> {
        self.map_par(orientations, |_, _, s| s.try_to_mesh())?
            .into_iter()
            .map(|m| m.map_err(QueryError::from))
            .collect()
    }
}

/// The C-obstacle slices `O ⊕ (−R·A)` of `robot` among `obstacle`, one per
/// orientation, computed sequentially by one dynamic sum.
///
/// # Errors
/// Those of [`CObstacle::new`] (internal only) and of
/// [`CObstacle::slices_par`]: the first failing slice, in order.
pub fn cobstacle_slices(
    robot: &Polytope,
    obstacle: &Polytope,
    orientations: &[Rotation],
) -> Result<Vec<PolygonMesh>, QueryError> {
    CObstacle::new(robot, obstacle)?
        .slices(orientations)
        .collect()
}

/// [`cobstacle_slices`] spread over rayon's threads (same result).
///
/// # Errors
/// The same as [`cobstacle_slices`].
pub fn cobstacle_slices_par(
    robot: &Polytope,
    obstacle: &Polytope,
    orientations: &[Rotation],
) -> Result<Vec<PolygonMesh>, QueryError> {
    CObstacle::new(robot, obstacle)?.slices_par(orientations)
}

/// The largest `|v|` of each body, computed once per pair.
#[derive(Clone, Copy, Debug, Default)]
pub(in crate::query) struct Reaches {
    pub(in crate::query) p: f64,
    pub(in crate::query) q: f64,
}

impl Reaches {
    pub(in crate::query) fn of(p: &Polytope, q: &Polytope) -> Reaches {
        Reaches {
            p: crate::query::prep::BodyBounds::of(p).reach,
            q: crate::query::prep::BodyBounds::of(q).reach,
        }
    }
}
