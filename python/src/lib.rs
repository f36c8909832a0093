//! `dymsum._dymsum`: the Python bindings of dymsum (re-exported by the
//! `dymsum` package).
//!
//! Exact static and dynamic Minkowski sums of convex polytopes, penetration
//! depth and distance, contact tracking and C-obstacle slices, from NumPy
//! arrays. Every long computation (hulls, sums, updates, queries, slices,
//! file I/O) runs with the GIL released; the core types are `Send + Sync`.
//!
//! Conventions (see `convert` for the input rules):
//! * shapes: an (N, 3) point cloud (its exact hull), a `(vertices, faces)`
//!   pair, an object with `.vertices` and `.faces` (trimesh), or a
//!   [`PyPolytope`];
//! * shapes may also be model names or mesh file paths (as `load`);
//! * poses: 4×4 homogeneous rigid transforms (`None` = identity), or a
//!   rotation about the origin: a scipy `Rotation`, a 3×3 matrix, or a
//!   quaternion `(x, y, z, w)`, scalar last, as scipy (see `convert`);
//! * outputs: vertices `float64` (n, 3), faces `int64` (m, 3) fan
//!   triangles, or with `polygons=True` the merged faces as a list of
//!   `int64` arrays;
//! * invalid input raises `ValueError` with dymsum's message.
#![forbid(unsafe_code)]

mod contact;
mod convert;
mod io;
mod maps;
mod motion;
mod polytope;
mod robot;
mod slices;
mod solid;
mod sums;

use pyo3::prelude::*;

#[pymodule]
fn _dymsum(m: &Bound<'_, PyModule>) -> PyResult<()> {
    polytope::register(m)?;
    sums::register(m)?;
    contact::register(m)?;
    slices::register(m)?;
    io::register(m)?;
    motion::register(m)?;
    robot::register(m)?;
    maps::register(m)?;
    solid::register(m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
