//! The convex pieces of a closed mesh: its exactly convex components, or a
//! decomposition (parry's V-HACD under the `parry` feature).

use super::merge::{boolean, to_manifold, volume};
use super::UnionMeshError;
use crate::body::solid_shells;
use crate::mesh::PolygonMesh;
use crate::polytope::MeshPolicy;
use crate::polytope::Polytope;

/// How a non-convex closed mesh becomes convex pieces.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Decomposition {
    /// Only exact: each shell (connected component) must be exactly
    /// convex; anything else is refused with
    /// [`UnionMeshError::NeedsDecomposition`].
    #[default]
    Components,
    /// Exactly convex components as they are, the others by parry's V-HACD
    /// (needs the `parry` feature, otherwise
    /// [`UnionMeshError::DecompositionUnavailable`]): approximate, its
    /// volume error against the input is reported.
    Vhacd {
        /// Voxel grid resolution along the longest axis (parry's default 64).
        resolution: u32,
        /// Maximum concavity, relative to the size (parry's default 0.01).
        concavity: f64,
        /// Maximum number of convex parts (parry's default 1024).
        max_hulls: u32,
    },
}

impl Decomposition {
    /// V-HACD with parry's default parameters.
    pub const VHACD: Decomposition = Decomposition::Vhacd {
        resolution: 64,
        concavity: 0.01,
        max_hulls: 1024,
    };

    /// `"components"` or `"vhacd"`.
    pub fn name(&self) -> &'static str {
        match self {
            Decomposition::Components => "components",
            Decomposition::Vhacd { .. } => "vhacd",
        }
    }
}

/// How a body's convex pieces were obtained.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct DecompositionInfo {
    /// `"convex"` (one convex body), `"given"` (pieces given by the
    /// caller), `"components"` (the mesh's shells, each exactly convex) or
    /// `"vhacd"`.
    pub method: &'static str,
    /// `true` when the union of the pieces is the input exactly (every
    /// method but a decomposition library).
    pub exact: bool,
    /// The number of pieces.
    pub pieces: usize,
    /// Pieces taken exactly from convex components (the rest come from the
    /// decomposition).
    pub convex_components: usize,
    /// For a decomposition: the input mesh's volume.
    pub input_volume: Option<f64>,
    /// For a decomposition: the volume of the union of the pieces.
    pub union_volume: Option<f64>,
    /// For a decomposition: `(vol(U \ M) + vol(M \ U)) / vol(M)` for the
    /// union `U` of the pieces and the input `M` (by `boolmesh`; when it
    /// refuses the input, `|vol(U) − vol(M)| / vol(M)`).
    pub volume_error: Option<f64>,
}

impl DecompositionInfo {
    /// The info for pieces given as they are (`method`: `"convex"` or
    /// `"given"`).
    pub fn exact(method: &'static str, pieces: usize) -> DecompositionInfo {
        DecompositionInfo {
            method,
            exact: true,
            pieces,
            convex_components: pieces,
            input_volume: None,
            union_volume: None,
            volume_error: None,
        }
    }
}

/// The convex pieces of a mesh given as a solid.
///
/// A convex mesh is one piece. Otherwise the mesh is first checked exactly
/// by [`crate::solid::check_solid_mesh`] (each shell closed, oriented, manifold, not
/// crossing itself, of positive volume; no face listed twice or back to
/// back), and refused with [`UnionMeshError::Solid`] when it fails: the
/// body is the union of its shells (which may overlap). Each shell that is
/// exactly convex is taken as it is; the others go, shell by shell, to
/// `decomposition`.
///
/// ```
/// use dymsum::nonconvex::{convex_pieces, Decomposition, UnionMeshError};
/// use dymsum::PolygonMesh;
/// // Two disjoint unit cubes in one mesh: two exact pieces.
/// let mut v = Vec::new();
/// let mut f = Vec::new();
/// for dx in [0.0, 3.0] {
///     let o = v.len();
///     v.extend((0..8).map(|i| [dx + (i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64]));
///     for q in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
///         f.push(q.iter().map(|&i| o + i).collect());
///     }
/// }
/// let (pieces, info) = convex_pieces(&PolygonMesh::new(v.clone(), f.clone()), Decomposition::Components)?;
/// assert_eq!((pieces.len(), info.method, info.exact), (2, "components", true));
/// // The same faces listed twice: no solid, refused whatever the decomposition.
/// f.extend(f.clone());
/// let err = convex_pieces(&PolygonMesh::new(v, f), Decomposition::VHACD).unwrap_err();
/// assert!(matches!(err, UnionMeshError::Solid(_)));
/// # Ok::<(), UnionMeshError>(())
/// ```
///
/// # Errors
/// [`UnionMeshError::Solid`] when the mesh is not a solid;
/// [`UnionMeshError::NeedsDecomposition`] for a non-convex shell under
/// [`Decomposition::Components`];
/// [`UnionMeshError::DecompositionUnavailable`] for V-HACD without the
/// `parry` feature; [`UnionMeshError::Decomposition`] when it returns no
/// solid part.
pub fn convex_pieces(
    mesh: &PolygonMesh,
    decomposition: Decomposition,
) -> Result<(Vec<Polytope>, DecompositionInfo), UnionMeshError> {
    if let Ok((p, _)) = Polytope::from_mesh(mesh, MeshPolicy::strict()) {
        if mesh.signed_volume() > 0.0 {
            return Ok((vec![p], DecompositionInfo::exact("convex", 1)));
        }
    }
    let shells = solid_shells(mesh)?;
    let mut pieces = Vec::new();
    let mut rest: Vec<&PolygonMesh> = Vec::new();
    for shell in &shells {
        match &shell.convex {
            Some(p) => pieces.push(p.clone()),
            None => rest.push(&shell.mesh),
        }
    }
    if rest.is_empty() {
        let n = pieces.len();
        let mut info = DecompositionInfo::exact("components", n);
        info.convex_components = n;
        return Ok((pieces, info));
    }
    if decomposition == Decomposition::Components {
        return Err(UnionMeshError::NeedsDecomposition {
            components: shells.len(),
            nonconvex: rest.len(),
        });
    }
    let convex_components = pieces.len();
    for sub in rest {
        let parts = decompose(sub, decomposition)?;
        if parts.is_empty() {
            return Err(UnionMeshError::Decomposition(format!(
                "the {} decomposition returned no solid part",
                decomposition.name()
            )));
        }
        pieces.extend(parts);
    }
    // The input as one closed mesh: the union of its shells when they are
    // several (they may overlap).
    let (input, total) = if shells.len() == 1 {
        (mesh.clone(), mesh.signed_volume())
    } else {
        let shells: Vec<(String, PolygonMesh)> = shells
            .iter()
            .enumerate()
            .map(|(k, s)| (format!("shell {k} of the input"), s.mesh.clone()))
            .collect();
        let (union, info) = super::merge::union_meshes(&shells)?;
        (union, info.volume)
    };
    let (union_volume, volume_error) = volume_error(&pieces, &input, total)?;
    let n = pieces.len();
    Ok((
        pieces,
        DecompositionInfo {
            method: decomposition.name(),
            exact: false,
            pieces: n,
            convex_components,
            input_volume: Some(total),
            union_volume: Some(union_volume),
            volume_error: Some(volume_error),
        },
    ))
}

/// The union's volume and its volume error against the input.
fn volume_error(
    pieces: &[Polytope],
    input: &PolygonMesh,
    input_volume: f64,
) -> Result<(f64, f64), UnionMeshError> {
    let meshes: Vec<(String, PolygonMesh)> = pieces
        .iter()
        .enumerate()
        .map(|(i, p)| (format!("decomposition piece {i}"), p.to_mesh()))
        .collect();
    let (union, info) = super::merge::union_meshes(&meshes)?;
    let u = to_manifold(&union, "the union of the decomposition")?;
    let err = match to_manifold(input, "the input mesh") {
        Ok(m) => {
            let extra = volume(&boolean(
                &u,
                &m,
                boolmesh::prelude::OpType::Subtract,
                "union − input",
            )?);
            let missing = volume(&boolean(
                &m,
                &u,
                boolmesh::prelude::OpType::Subtract,
                "input − union",
            )?);
            (extra.max(0.0) + missing.max(0.0)) / input_volume
        }
        Err(_) => (info.volume - input_volume).abs() / input_volume,
    };
    Ok((info.volume, err))
}

#[cfg(feature = "parry")]
fn decompose(mesh: &PolygonMesh, d: Decomposition) -> Result<Vec<Polytope>, UnionMeshError> {
    use crate::solid::closed::triangles;
    use parry3d_f64::transformation::vhacd::{VHACDParameters, VHACD};
    let Decomposition::Vhacd {
        resolution,
        concavity,
        max_hulls,
    } = d
    else {
        return Ok(Vec::new());
    };
    let tris = triangles(mesh).map_err(|e| UnionMeshError::Decomposition(e.to_string()))?;
    let points: Vec<glam::DVec3> = mesh
        .vertices
        .iter()
        .map(|&p| glam::DVec3::from(p))
        .collect();
    let idx: Vec<[u32; 3]> = tris.iter().map(|t| t.map(|i| i as u32)).collect();
    let params = VHACDParameters {
        resolution,
        concavity,
        max_convex_hulls: max_hulls,
        ..VHACDParameters::default()
    };
    let parts = std::panic::catch_unwind(|| {
        VHACD::decompose(&params, &points, &idx, false).compute_convex_hulls(4)
    })
    .map_err(|_| UnionMeshError::Decomposition("parry's V-HACD panicked".into()))?;
    // A flat part (fewer than 4 affinely independent points) adds nothing.
    Ok(parts
        .into_iter()
        .filter_map(|(pts, _)| Polytope::from_dvec3s(&pts).ok())
        .collect())
}

#[cfg(not(feature = "parry"))]
fn decompose(_mesh: &PolygonMesh, d: Decomposition) -> Result<Vec<Polytope>, UnionMeshError> {
    Err(UnionMeshError::DecompositionUnavailable(d.name()))
}
