//! Tolerance-free validation of a closed triangle mesh: the check every
//! merged mesh passes before it is returned (Rust's `nonconvex` sums,
//! merged by boolmesh, and Python's, merged by Manifold, through
//! `_dymsum._check_closed_mesh`).

use std::collections::HashMap;

use glam::DVec3;

use crate::mesh::PolygonMesh;

/// Why a mesh is not a closed, oriented 2-manifold of positive volume.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ClosedMeshError {
    /// The mesh has no faces.
    #[error("the mesh has no faces")]
    Empty,
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} is not finite")]
    NonFinite {
        /// The vertex.
        vertex: usize,
    },
    /// A face has fewer than three corners, names a vertex out of range, or
    /// repeats a vertex.
    #[error("face {face} is malformed (fewer than 3 corners, a vertex out of range, or a repeated vertex)")]
    BadFace {
        /// The face.
        face: usize,
    },
    /// A directed edge occurs more than once: a non-manifold edge or an
    /// inconsistent orientation.
    #[error("directed edge ({from}, {to}) occurs {count} times (non-manifold or inconsistently oriented)")]
    RepeatedEdge {
        /// Its first vertex.
        from: usize,
        /// Its second vertex.
        to: usize,
        /// How often it occurs.
        count: usize,
    },
    /// A directed edge has no opposite: the mesh is open or inconsistently
    /// oriented.
    #[error("edge ({from}, {to}) has no opposite half-edge (the mesh is open or inconsistently oriented)")]
    OpenEdge {
        /// Its first vertex.
        from: usize,
        /// Its second vertex.
        to: usize,
    },
    /// The faces around a vertex form more than one fan: the surface
    /// touches itself there.
    #[error("vertex {vertex} is pinched: its faces form {fans} fans, not one")]
    Pinched {
        /// The vertex.
        vertex: usize,
        /// The number of fans around it.
        fans: usize,
    },
    /// The signed volume is not positive: the mesh is inward or empty.
    #[error("signed volume {volume:e} is not positive (inward or empty)")]
    NotPositive {
        /// The signed volume.
        volume: f64,
    },
}

/// What [`check_closed_mesh`] measured on a valid mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct ClosedMeshInfo {
    /// Vertices used by the faces.
    pub vertices: usize,
    /// Triangles (of the fan triangulation of the faces).
    pub triangles: usize,
    /// The enclosed (signed) volume, positive.
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
pub(crate) fn triangles(mesh: &PolygonMesh) -> Result<Vec<[usize; 3]>, ClosedMeshError> {
    let n = mesh.vertices.len();
    let mut out = Vec::with_capacity(mesh.triangle_count());
    for (k, f) in mesh.faces.iter().enumerate() {
        let bad = f.len() < 3
            || f.iter().any(|&i| i >= n)
            || f.iter().enumerate().any(|(a, x)| f[a + 1..].contains(x));
        if bad {
            return Err(ClosedMeshError::BadFace { face: k });
        }
        for w in f[1..].windows(2) {
            out.push([f[0], w[0], w[1]]);
        }
    }
    Ok(out)
}

/// Checks that `mesh` is a closed, oriented 2-manifold of positive volume,
/// without tolerance: finite vertices, well-formed faces, every directed
/// edge once and its reverse once, no pinched vertex (the faces around each
/// vertex form one fan), and a positive signed volume. Returns what it
/// measured, with the number of sliver triangles (corners exactly
/// collinear, by exact predicates), which are allowed.
///
/// ```
/// use dymsum::solid::closed::{check_closed_mesh, ClosedMeshError};
/// use dymsum::PolygonMesh;
/// let v = vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
/// let tetra = PolygonMesh::new(v.clone(), vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]]);
/// let info = check_closed_mesh(&tetra)?;
/// assert_eq!((info.shells, info.genus), (1, 0));
/// assert!((info.volume - 1.0 / 6.0).abs() < 1e-15);
/// let open = PolygonMesh::new(v, vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3]]);
/// assert!(matches!(check_closed_mesh(&open), Err(ClosedMeshError::OpenEdge { .. })));
/// # Ok::<(), ClosedMeshError>(())
/// ```
///
/// # Errors
/// The first [`ClosedMeshError`] found, naming the element.
pub fn check_closed_mesh(mesh: &PolygonMesh) -> Result<ClosedMeshInfo, ClosedMeshError> {
    if let Some(v) = mesh
        .vertices
        .iter()
        .position(|p| !p.iter().all(|x| x.is_finite()))
    {
        return Err(ClosedMeshError::NonFinite { vertex: v });
    }
    let tris = triangles(mesh)?;
    if tris.is_empty() {
        return Err(ClosedMeshError::Empty);
    }
    check_triangles(&mesh.vertices, &tris)
}

/// [`check_closed_mesh`] on triangles.
pub(crate) fn check_triangles(
    vertices: &[[f64; 3]],
    tris: &[[usize; 3]],
) -> Result<ClosedMeshInfo, ClosedMeshError> {
    // Directed half-edges: (from, to) -> index 3 t + k.
    let mut half: HashMap<(usize, usize), usize> = HashMap::with_capacity(3 * tris.len());
    for (t, f) in tris.iter().enumerate() {
        for k in 0..3 {
            let e = (f[k], f[(k + 1) % 3]);
            if half.insert(e, 3 * t + k).is_some() {
                let count = tris
                    .iter()
                    .flat_map(|g| (0..3).map(move |j| (g[j], g[(j + 1) % 3])))
                    .filter(|&x| x == e)
                    .count();
                return Err(ClosedMeshError::RepeatedEdge {
                    from: e.0,
                    to: e.1,
                    count,
                });
            }
        }
    }
    for f in tris {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            if !half.contains_key(&(b, a)) {
                return Err(ClosedMeshError::OpenEdge { from: a, to: b });
            }
        }
    }
    // Fans: the outgoing half-edge a->b of triangle t (corner k) is followed
    // by the outgoing half-edge a->c of the triangle across c->a, where c
    // precedes a in t. One cycle per used vertex.
    let mut seen = vec![false; 3 * tris.len()];
    let mut fans: HashMap<usize, usize> = HashMap::new();
    for start in 0..3 * tris.len() {
        if seen[start] {
            continue;
        }
        let vertex = tris[start / 3][start % 3];
        *fans.entry(vertex).or_insert(0) += 1;
        let mut h = start;
        while !seen[h] {
            seen[h] = true;
            let (t, k) = (h / 3, h % 3);
            let a = tris[t][k];
            let c = tris[t][(k + 2) % 3];
            h = half[&(a, c)];
        }
    }
    if let Some((&vertex, &n)) = fans.iter().filter(|(_, &n)| n > 1).min_by_key(|(&v, _)| v) {
        return Err(ClosedMeshError::Pinched { vertex, fans: n });
    }
    let slivers = tris
        .iter()
        .filter(|f| super::collinear(vertices[f[0]], vertices[f[1]], vertices[f[2]]))
        .count();
    let used = fans.len();
    let edges = half.len() / 2;
    let chi = used as i64 - edges as i64 + tris.len() as i64;
    let shells = super::shells(vertices.len(), tris).len();
    let genus = shells as i64 - chi / 2;
    let volume = signed_volume(vertices, tris);
    if volume.is_nan() || volume <= 0.0 {
        return Err(ClosedMeshError::NotPositive { volume });
    }
    Ok(ClosedMeshInfo {
        vertices: used,
        triangles: tris.len(),
        volume,
        shells,
        genus,
        slivers,
    })
}

/// Signed volume of triangles, relative to their centroid (a float
/// construction).
pub(crate) fn signed_volume(vertices: &[[f64; 3]], tris: &[[usize; 3]]) -> f64 {
    if tris.is_empty() {
        return 0.0;
    }
    let c = tris
        .iter()
        .map(|f| DVec3::from(vertices[f[0]]))
        .sum::<DVec3>()
        / tris.len() as f64;
    let p = |i: usize| DVec3::from(vertices[i]) - c;
    tris.iter()
        .map(|f| p(f[0]).dot(p(f[1]).cross(p(f[2]))))
        .sum::<f64>()
        / 6.0
}
