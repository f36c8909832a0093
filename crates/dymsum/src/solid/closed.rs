//! Tolerance-free validation of a closed triangle mesh: the check every
//! merged mesh passes before it is returned (Rust's `nonconvex` sums,
//! merged by boolmesh, and Python's, merged by Manifold, through
//! `_dymsum._check_closed_mesh`). It shares rules 1 and 5 of
//! [`check_solid_mesh`](super::check_solid_mesh) (taken on the faces' fan
//! triangles, as boolmesh and Manifold take them) and its error,
//! [`SolidError`]; it does not look for crossings, and asks a positive
//! volume of the whole mesh, not of each shell (a cavity is allowed).

use glam::DVec3;

use super::{
    check_elements, check_topology, collinear, malformed, shells, volume_sign, SolidError,
};
use crate::kernel::exact;
use crate::kernel::predicates::Sign;
use crate::mesh::PolygonMesh;
use crate::polytope::topology::DirectedEdges;

/// The error of [`check_closed_mesh`], now the solid layer's one error.
#[deprecated(
    note = "use `dymsum::SolidError` (`check_closed_mesh` returns it: `RepeatedEdge` is \
            `NonManifoldEdge` or `InconsistentOrientation`, `Pinched` is `NonManifoldVertex`, \
            `NotPositive` is `NonPositiveTotalVolume`)"
)]
pub type ClosedMeshError = SolidError;

/// What [`check_closed_mesh`] measured on a valid mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct ClosedMeshInfo {
    /// Vertices used by the faces.
    pub vertices: usize,
    /// Triangles (of the fan triangulation of the faces).
    pub triangles: usize,
    /// The enclosed (signed) volume, a float sum (its sign, positive, is
    /// decided exactly; infinite beyond `f64`'s range).
    pub volume: f64,
    /// Connected components of the surface (an inner shell bounds a cavity).
    pub shells: usize,
    /// The total genus: `shells − χ / 2` with `χ = V − E + F`; 1 for a ring.
    pub genus: i64,
    /// Sliver triangles: corners exactly collinear (zero area). The mesh is
    /// still closed and oriented; a float boolean can leave such slivers
    /// where piece sums meet at grazing angles.
    pub slivers: usize,
}

/// The fan triangles of a polygon mesh.
///
/// # Errors
/// [`SolidError::BadFace`] for a face of fewer than three corners, a
/// corner out of range or a repeated corner.
pub(crate) fn triangles(mesh: &PolygonMesh) -> Result<Vec<[usize; 3]>, SolidError> {
    let n = mesh.vertices.len();
    let mut out = Vec::with_capacity(mesh.triangle_count());
    for (face, f) in mesh.faces.iter().enumerate() {
        if malformed(f, n) {
            return Err(SolidError::BadFace { face });
        }
        out.extend(f[1..].windows(2).map(|w| [f[0], w[0], w[1]]));
    }
    Ok(out)
}

/// Checks that `mesh` is a closed, oriented 2-manifold of positive volume,
/// without tolerance: at least one face, finite vertices within the exact
/// arithmetic's span, well-formed faces, every directed edge of the fan
/// triangles once and its reverse once, no pinched vertex (the faces
/// around each vertex form one fan), and a positive total volume (its
/// exact sign). Returns what it measured, with the number of sliver
/// triangles (corners exactly collinear, by exact predicates), which are
/// allowed. Crossings are not looked for ([`check_solid_mesh`](super::check_solid_mesh)
/// does).
///
/// ```
/// use dymsum::solid::closed::check_closed_mesh;
/// use dymsum::{PolygonMesh, SolidError};
/// let v = vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
/// let faces = vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]];
/// let info = check_closed_mesh(&PolygonMesh::new(v.clone(), faces.clone()))?;
/// assert_eq!((info.shells, info.genus), (1, 0));
/// assert!((info.volume - 1.0 / 6.0).abs() < 1e-15);
/// let open = PolygonMesh::new(v.clone(), faces[..3].to_vec());
/// assert!(matches!(check_closed_mesh(&open), Err(SolidError::OpenEdge { .. })));
/// let inward: Vec<Vec<usize>> = faces.iter().map(|f| f.iter().rev().copied().collect()).collect();
/// assert_eq!(
///     check_closed_mesh(&PolygonMesh::new(v, inward)),
///     Err(SolidError::NonPositiveTotalVolume { negative: true })
/// );
/// # Ok::<(), SolidError>(())
/// ```
///
/// # Errors
/// The first rule broken, as a [`SolidError`] naming the element (faces
/// in the caller's numbering): [`SolidError::Empty`],
/// [`SolidError::NonFinite`], [`SolidError::BadFace`],
/// [`SolidError::OutOfRange`], [`SolidError::NonManifoldEdge`],
/// [`SolidError::InconsistentOrientation`], [`SolidError::OpenEdge`],
/// [`SolidError::NonManifoldVertex`] or
/// [`SolidError::NonPositiveTotalVolume`].
pub fn check_closed_mesh(mesh: &PolygonMesh) -> Result<ClosedMeshInfo, SolidError> {
    check_elements(mesh)?;
    let vertices = &mesh.vertices;
    let tris = triangles(mesh)?;
    // The face of each fan triangle, to name faces in errors.
    let face_of: Vec<usize> = mesh
        .faces
        .iter()
        .enumerate()
        .flat_map(|(face, f)| std::iter::repeat_n(face, f.len() - 2))
        .collect();
    let d = DirectedEdges::from_faces(vertices.len(), tris.len(), |t| &tris[t][..]);
    check_topology(&d, |t| face_of[t])?;
    let sign = volume_sign(vertices, &tris);
    if sign != Sign::Positive {
        return Err(SolidError::NonPositiveTotalVolume {
            negative: sign == Sign::Negative,
        });
    }
    let slivers = tris
        .iter()
        .filter(|f| collinear(vertices[f[0]], vertices[f[1]], vertices[f[2]]))
        .count();
    let used = (0..vertices.len())
        .filter(|&v| d.start[v + 1] > d.start[v])
        .count();
    // Closed: every half-edge has its reverse.
    let edges = 3 * tris.len() / 2;
    let chi = used as i64 - edges as i64 + tris.len() as i64;
    let shells = shells(vertices.len(), &tris).len();
    Ok(ClosedMeshInfo {
        vertices: used,
        triangles: tris.len(),
        volume: signed_volume(vertices, &tris),
        shells,
        genus: shells as i64 - chi / 2,
        slivers,
    })
}

/// Signed volume of triangles, relative to their centroid (a float
/// construction), summed in the power-of-two frame of their corners (an
/// exact scaling, so tiny and huge meshes keep their precision) and
/// scaled back: infinite when it is beyond `f64`'s range.
pub(crate) fn signed_volume(vertices: &[[f64; 3]], tris: &[[usize; 3]]) -> f64 {
    if tris.is_empty() {
        return 0.0;
    }
    let k = exact::frame_exponent(tris.iter().flatten().flat_map(|&i| vertices[i]));
    let c = tris
        .iter()
        .map(|f| exact::mul_pow2_vec(DVec3::from(vertices[f[0]]), k))
        .sum::<DVec3>()
        / tris.len() as f64;
    let p = |i: usize| exact::mul_pow2_vec(DVec3::from(vertices[i]), k) - c;
    let frame_volume = tris
        .iter()
        .map(|f| p(f[0]).dot(p(f[1]).cross(p(f[2]))))
        .sum::<f64>()
        / 6.0;
    exact::mul_pow2(frame_volume, -3 * k)
}
