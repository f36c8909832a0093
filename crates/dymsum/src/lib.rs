//! # dymsum
//!
//! Exact Minkowski sums of convex polytopes, static and dynamic (the DYMSUM
//! algorithm: keeping `P ⊕ Q` up to date while `P` rotates).
//!
//! The crate does no file or terminal I/O. Its parts, in the order data flows:
//!
//! * [`error`]: the error types several layers share.
//! * [`kernel`]: exact predicates (`orient3d`, `det3` with symbolic
//!   perturbation) and rotations.
//! * [`hull`]: an exact incremental 3-D convex hull, generic over the point set.
//! * [`polytope`]: convex polytopes with O(1) adjacency and their Gaussian maps.
//! * [`sum`]: static Minkowski sums by three independent methods
//!   ([`sum::Method::Brute`], [`sum::Method::Walk`], [`sum::Method::Hull`]),
//!   all returning the same labelled facet set, and the merged polygon mesh.
//! * [`dynamic`]: DYMSUM, the sum kept up to date while the bodies rotate.
//! * [`mesh`]: a plain polygon mesh, the exchange type with file formats.
//! * [`solid`]: the exact check of a non-convex mesh given as a solid
//!   (closed, oriented, manifold shells that do not cross themselves, of
//!   positive volume).
//! * `nonconvex` (feature `union-mesh`): sums of non-convex bodies (unions
//!   of convex pieces, or closed meshes) merged into one validated closed
//!   mesh.
//! * [`interop`]: conversions of rotations, poses and shapes to and from
//!   glam, and behind the optional features `parry`, `mint` and `nalgebra`,
//!   to and from parry3d-f64, mint and nalgebra.
//!
//! ```
//! use dymsum::{Polytope, sum::{minkowski_sum, Method}};
//! let cube: Vec<[f64; 3]> = (0..8)
//!     .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
//!     .collect();
//! let p = Polytope::from_points(&cube).unwrap();
//! let sum = minkowski_sum(&p, &p, Method::Walk).unwrap();
//! let mesh = sum.try_to_mesh().unwrap();
//! assert_eq!(mesh.faces.len(), 6); // a cube plus a cube is a cube
//! ```
#![forbid(unsafe_code)]
#![warn(clippy::missing_errors_doc, clippy::missing_panics_doc)]
#![warn(missing_docs)]

pub mod body;
pub mod dynamic;
pub mod error;
pub(crate) mod gauss;
pub mod hull;
pub mod interop;
pub mod kernel;
pub mod mesh;
#[cfg(feature = "union-mesh")]
pub mod nonconvex;
pub mod polytope;
pub mod query;
pub mod robot;
pub mod sanity;
pub mod solid;
pub mod sum;

pub use dynamic::{DynamicSum, UpdateReport};
/// The `glam` dymsum uses: 0.33, the version `parry3d-f64` 0.31 uses, so
/// `dymsum::DVec3` and parry's `math::Vector` are one type.
pub use glam;
pub use glam::DVec3;
pub use kernel::rotation::{Pose, Rotation};
pub use mesh::PolygonMesh;
pub use polytope::{Polytope, PolytopeError};
pub use query::{
    CObstacle, Contact, ContactTracker, ContainmentStats, ConvexPair, ConvexUnion, Proximity,
    QueryError, QueryStats, Separation,
};
pub use sanity::SanityError;
pub use solid::{check_solid_mesh, SolidError};
pub use sum::{minkowski_sum, minkowski_sum_posed, Facet, Method, MinkowskiSum, SumError};
