//! Minkowski sums of non-convex bodies as one closed mesh (feature
//! `union-mesh`).
//!
//! `A ⊕ B` of two unions of convex pieces ([`ConvexUnion`]) is the union,
//! over every pair of pieces, of the exact convex sums `a_i ⊕ b_j`
//! ([`crate::minkowski_sum_posed`], or one [`crate::dynamic::DynamicSum`] per pair
//! under motion: [`DynamicUnionSum`]). That union is merged into one
//! closed, oriented 2-manifold by the pure-Rust mesh boolean `boolmesh`
//! (after the Manifold library; never hand-written here), then validated
//! by [`check_closed_mesh`] before it is returned: a mesh that fails is an
//! error ([`UnionMeshError::Invalid`]), never a result.
//!
//! What is exact, and what is not:
//!
//! * each piece-pair sum is exact (every decision an exact predicate), its
//!   vertices rounded to `f64` as for any convex sum;
//! * pair sums left out of the union (`pairs_culled`) are certified inside
//!   another pair sum by exact orientation tests;
//! * the union is `boolmesh`'s float boolean: the merged mesh is the union
//!   of the pair sums up to the rounding of its new vertices (where piece
//!   sums cross); holes and cavities are kept;
//! * the validation is exact and combinatorial (every directed edge once
//!   and its reverse once, no pinched vertex); the volume must be positive,
//!   its sign exact (its value a float sum); sliver triangles (corners
//!   exactly collinear) are counted, not refused (`boolmesh` can leave
//!   them where piece sums meet at grazing angles; the surface is still
//!   closed and oriented);
//! * a non-convex closed mesh becomes pieces by [`convex_pieces`], after the
//!   exact check that it is a solid ([`crate::solid`]; else
//!   [`UnionMeshError::Solid`]): exactly convex shells are taken as they
//!   are (exact); anything else needs a decomposition ([`Decomposition::Vhacd`], parry's V-HACD
//!   under the `parry` feature), which is approximate: its volume error
//!   against the input is in the [`DecompositionInfo`];
//! * the penetration depth of two unions
//!   ([`ConvexUnion::penetration_depth_mesh`]) decides collision exactly and
//!   measures the origin's distance to the merged C-obstacle mesh: exact up
//!   to the union's float construction.
//!
//! ```
//! use dymsum::nonconvex::UnionSum;
//! use dymsum::{sum::Method, ConvexUnion, Polytope, Pose};
//! let cuboid = |lo: [f64; 3], hi: [f64; 3]| {
//!     let c: Vec<[f64; 3]> = (0..8)
//!         .map(|i| std::array::from_fn(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
//!         .collect();
//!     Polytope::from_points(&c).unwrap()
//! };
//! // The L: a 3×1×1 and a 1×3×1 box overlapping at the origin.
//! let l = ConvexUnion::new(vec![cuboid([0., 0., 0.], [3., 1., 1.]), cuboid([0., 0., 0.], [1., 3., 1.])]).unwrap();
//! let cube = ConvexUnion::new(vec![cuboid([0., 0., 0.], [0.5, 0.5, 0.5])]).unwrap();
//! let sum = UnionSum::new(&l, Pose::IDENTITY, &cube, Pose::IDENTITY, Method::Walk, true)?;
//! let info = sum.info();
//! assert!((info.mesh.volume - 12.375).abs() < 1e-12);
//! assert_eq!((info.mesh.shells, info.mesh.genus, info.pairs), (1, 0, 2));
//! # Ok::<(), dymsum::nonconvex::UnionMeshError>(())
//! ```

mod decompose;
mod depth;
mod error;
mod merge;
mod sum;

pub use crate::body::ConvexUnion;
#[allow(deprecated)]
pub use crate::solid::closed::ClosedMeshError;
pub use crate::solid::closed::{check_closed_mesh, ClosedMeshInfo};
pub use decompose::{convex_pieces, Decomposition, DecompositionInfo};
pub use depth::UnionDepth;
pub use error::UnionMeshError;
pub use merge::merge_closed_meshes;
pub use sum::{DynamicUnionSum, UnionSum, UnionSumInfo};
