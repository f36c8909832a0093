//! Configuration-space obstacles of a translating robot at given
//! orientations: one exact convex slice per orientation kept by DYMSUM
//! ([`slices`]), the slices as half-spaces without a mesh ([`halfspaces`]),
//! and certified slabs that hold every slice over a range of orientations
//! ([`slabs`]).

pub(in crate::query) mod face_depths;
pub(in crate::query) mod halfspaces;
pub mod slabs;
pub(in crate::query) mod slices;
