//! The union of closed meshes by `boolmesh`, validated.

use std::panic::{catch_unwind, AssertUnwindSafe};

use boolmesh::prelude::{compute_boolean, Manifold, OpType};
use rayon::prelude::*;

use super::UnionMeshError;
use crate::mesh::PolygonMesh;
use crate::solid::closed::{check_closed_mesh, triangles, ClosedMeshInfo};
use crate::solid::SolidError;

/// A mesh handed to `boolmesh`.
pub(crate) fn to_manifold(mesh: &PolygonMesh, what: &str) -> Result<Manifold, UnionMeshError> {
    let tris = triangles(mesh).map_err(|e| UnionMeshError::Boolean {
        step: what.to_string(),
        message: e.to_string(),
    })?;
    let pos: Vec<f64> = mesh.vertices.iter().flatten().copied().collect();
    let idx: Vec<usize> = tris.iter().flatten().copied().collect();
    guarded(what, || Manifold::new(&pos, &idx))
}

/// Runs a `boolmesh` call, turning its `Err` and any panic into
/// [`UnionMeshError::Boolean`].
fn guarded<T>(what: &str, f: impl FnOnce() -> Result<T, String>) -> Result<T, UnionMeshError> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(m)) => Ok(m),
        Ok(Err(message)) => Err(UnionMeshError::Boolean {
            step: what.to_string(),
            message,
        }),
        Err(_) => Err(UnionMeshError::Boolean {
            step: what.to_string(),
            message: "boolmesh panicked".to_string(),
        }),
    }
}

/// The union of closed meshes (each a closed, outward 2-manifold: convex
/// piece sums, C-obstacle slices of piece pairs), merged by `boolmesh` and
/// validated as [`super::check_closed_mesh`].
///
/// ```
/// use dymsum::nonconvex::merge_closed_meshes;
/// use dymsum::Polytope;
/// let cube = |o: f64| {
///     let c: Vec<[f64; 3]> = (0..8).map(|i| std::array::from_fn(|k| o + (i >> k & 1) as f64)).collect();
///     Polytope::from_points(&c).unwrap().to_mesh()
/// };
/// // Two unit cubes overlapping in a 0.5³ corner.
/// let (_mesh, info) = merge_closed_meshes(&[cube(0.0), cube(0.5)])?;
/// assert!((info.volume - (2.0 - 0.125)).abs() < 1e-12);
/// # Ok::<(), dymsum::nonconvex::UnionMeshError>(())
/// ```
///
/// # Errors
/// [`UnionMeshError::Boolean`] when `boolmesh` refuses a mesh (not a
/// closed 2-manifold) or fails; [`UnionMeshError::Invalid`] when there is
/// no mesh or the result fails validation.
pub fn merge_closed_meshes(
    meshes: &[PolygonMesh],
) -> Result<(PolygonMesh, ClosedMeshInfo), UnionMeshError> {
    let named: Vec<(String, PolygonMesh)> = meshes
        .iter()
        .enumerate()
        .map(|(k, m)| (format!("mesh {k}"), m.clone()))
        .collect();
    union_meshes(&named)
}

/// `boolmesh`'s boolean of two manifolds.
pub(crate) fn boolean(
    a: &Manifold,
    b: &Manifold,
    op: OpType,
    what: &str,
) -> Result<Manifold, UnionMeshError> {
    guarded(what, || compute_boolean(a, b, op))
}

/// The triangles of a `boolmesh` manifold as a polygon mesh (unvalidated).
pub(crate) fn from_manifold(m: &Manifold) -> PolygonMesh {
    let vertices = m.ps.iter().map(|p| [p.x, p.y, p.z]).collect();
    let faces =
        m.hs.chunks(3)
            .map(|t| t.iter().map(|h| h.tail).collect())
            .collect();
    PolygonMesh::new(vertices, faces)
}

/// The volume of a `boolmesh` manifold (0 when empty or malformed).
pub(crate) fn volume(m: &Manifold) -> f64 {
    let mesh = from_manifold(m);
    match triangles(&mesh) {
        Ok(t) => crate::solid::closed::signed_volume(&mesh.vertices, &t),
        Err(_) => 0.0,
    }
}

/// The union of closed meshes, folded pairwise in a balanced tree by
/// `boolmesh`, then validated ([`super::check_closed_mesh`]): the result is a
/// closed, oriented 2-manifold triangle mesh of positive volume, or an
/// error. `names` name the meshes in errors.
pub(crate) fn union_meshes(
    meshes: &[(String, PolygonMesh)],
) -> Result<(PolygonMesh, ClosedMeshInfo), UnionMeshError> {
    let mut level: Vec<(String, Manifold)> = meshes
        .iter()
        .map(|(name, m)| to_manifold(m, name).map(|x| (name.clone(), x)))
        .collect::<Result<_, _>>()?;
    if level.is_empty() {
        return Err(UnionMeshError::Invalid(SolidError::Empty));
    }
    // Each level's unions are independent: run them on the rayon pool
    // (the result does not depend on the thread count).
    while level.len() > 1 {
        level = level
            .into_par_iter()
            .chunks(2)
            .map(|pair| {
                let mut it = pair.into_iter();
                let (na, a) = it.next().expect("a chunk is never empty");
                let Some((nb, b)) = it.next() else {
                    return Ok((na, a));
                };
                let name = format!("{na} ∪ {nb}");
                let short = if name.len() > 120 {
                    "the union of the piece sums".to_string()
                } else {
                    name
                };
                let u = boolean(&a, &b, OpType::Add, &short)?;
                Ok((short, u))
            })
            .collect::<Result<Vec<_>, UnionMeshError>>()?;
    }
    let (_, m) = level
        .pop()
        .ok_or(UnionMeshError::Invalid(SolidError::Empty))?;
    let mesh = from_manifold(&m);
    let info = validate(&mesh)?;
    Ok((mesh, info))
}

/// [`super::check_closed_mesh`] as a [`UnionMeshError::Invalid`].
pub(crate) fn validate(mesh: &PolygonMesh) -> Result<ClosedMeshInfo, UnionMeshError> {
    check_closed_mesh(mesh).map_err(UnionMeshError::Invalid)
}
