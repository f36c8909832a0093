//! File formats and the built-in model library for dymsum.
//!
//! * [`formats`]: read and write OFF, OBJ, PLY (ASCII and binary) and STL
//!   (ASCII and binary read, binary write), chosen by file extension.
//! * [`models`]: the paper's 13 models, tessellated cubes and parametric
//!   primitives, by name.
//! * [`atomic`]: atomic file writes and bounded reads of regular files;
//!   [`staging`]: a set of files in a folder replaced without loss on a kill.
//! * [`npz`]: NumPy `.npz` archives of plain arrays; [`cmap`]: the
//!   C-obstacle map container written in one.
//! * [`load`]: an operand from a file path or a model name, as a polytope
//!   ([`load_polytope`]); [`body`]: an operand read once as a body (the
//!   core's ladder, unions, OBJ objects: [`body::load_body`]).
#![forbid(unsafe_code)]
#![warn(clippy::missing_errors_doc, clippy::missing_panics_doc)]
#![warn(missing_docs)]

pub mod atomic;
pub mod body;
pub mod cmap;
mod collada;
pub mod formats;
pub mod load;
pub mod models;
pub mod npz;
pub mod staging;
pub mod urdf;

pub use body::{load_body, load_polytope, load_polytope_bytes, LoadOptions, LoadedBody};
pub use load::{load_mesh, LoadError, Loaded};
