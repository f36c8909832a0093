//! Contact between bodies given as triangle meshes of any topology: the
//! scene checker ([`SceneChecker`]: `checker` the checker and its buffers,
//! `state` exact state checks, `clearance`, `sweep` the certified motion
//! search, `gap` the rigorous gaps; containment by the winding number is the
//! body's, `body::winding`), [`Validator`] (one entry for convex pieces and triangles,
//! [`Body`]), and [`surfaces_touch`] (`surfaces`: whether two meshes touch
//! as surfaces). The bodies themselves live in [`crate::body`].

mod checker;
mod clearance;
pub(crate) mod gap;
mod state;
mod surfaces;
mod sweep;
mod validator;

pub use crate::body::{Body, MeshBody, MeshReport};
pub use checker::SceneChecker;
pub use surfaces::surfaces_touch;
pub use validator::Validator;
