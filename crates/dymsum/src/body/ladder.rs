//! One way from a mesh to a body, tried once in a fixed order
//! ([`Body::from_mesh_with`]), with what it did ([`BodyReport`]): the
//! exact hull when asked for ([`BodyOptions::hull`]), one exactly convex
//! solid, a closed solid of exactly convex shells (their union), or
//! triangles of any topology. The command line, Python and Rust take a
//! mesh through it alike.

use super::mesh::{exactly_convex_refuted_by_edges_add, has_reflex_edge};
use super::{Body, ConvexUnion, MeshBody, MeshReport};
use crate::mesh::PolygonMesh;
use crate::polytope::{ConvexityReport, MeshPolicy, Polytope};
use crate::solid::{check_solid_mesh, SolidError};

/// How [`Body::from_mesh_with`] takes a mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BodyOptions {
    /// Take a mesh that is convex within tolerance ([`MeshPolicy::default`]:
    /// 1e-5 of its box's diagonal) as the exact hull of its vertices, the
    /// deviation reported in [`BodyReport::hull`]. Off by default: a mesh is
    /// taken exactly, and one convex only within rounding stays triangles.
    pub hull: bool,
}

/// The rung of [`Body::from_mesh_with`]'s ladder that took a mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rung {
    /// Asked for ([`BodyOptions::hull`]): the mesh as a polytope under
    /// [`MeshPolicy::default`], itself when exactly convex, else the exact
    /// hull of its vertices ([`BodyReport::hull`] says which, and how far
    /// the mesh deviated). A [`Body::Convex`] of one piece.
    Hull,
    /// Cleaned exactly ([`MeshBody::new`]) into one solid that is exactly
    /// convex: a [`Body::Mesh`] on the convex path
    /// ([`MeshBody::as_convex`]), its triangles and cleaning kept.
    Convex,
    /// A closed solid ([`check_solid_mesh`]) of several shells, each
    /// exactly convex: their union, a [`Body::Convex`] of one piece per
    /// shell (the same set as its triangles enclose).
    ConvexShells,
    /// Anything else: triangles of any topology, cleaned exactly (a
    /// [`Body::Mesh`]).
    Triangles,
}

/// What [`Body::from_mesh_with`] did with a mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyReport {
    /// The rung that took the mesh.
    pub rung: Rung,
    /// What the exact cleaning found and changed ([`MeshBody::report`]);
    /// `None` on [`Rung::Hull`], which takes the mesh before cleaning.
    pub cleaning: Option<MeshReport>,
    /// On [`Rung::Hull`]: [`Polytope::from_mesh`]'s report (whether the
    /// hull replaced the mesh, the largest deviation, the tolerance).
    pub hull: Option<ConvexityReport>,
    /// The convex pieces the body is on the convex path: 1 on
    /// [`Rung::Hull`] and [`Rung::Convex`], one per shell on
    /// [`Rung::ConvexShells`], 0 on [`Rung::Triangles`].
    pub pieces: usize,
}

impl Body {
    /// A mesh taken by one ladder, each rung tried once, in this order:
    ///
    /// 1. with [`BodyOptions::hull`], a mesh convex within tolerance is
    ///    the exact hull of its vertices ([`Rung::Hull`]);
    /// 2. otherwise it is cleaned exactly ([`MeshBody::new`], as
    ///    [`Body::from_mesh`]); one solid that is exactly convex takes the
    ///    convex path ([`Rung::Convex`]);
    /// 3. a closed solid ([`check_solid_mesh`], on the mesh as given) of
    ///    several shells, each exactly convex, is their union
    ///    ([`Rung::ConvexShells`]: the same set, with depth and distance);
    /// 4. anything else is triangles of any topology ([`Rung::Triangles`]).
    ///
    /// Nothing is approximated unless `hull` asks for it: a mesh convex
    /// only within rounding stays triangles. The [`BodyReport`] says which
    /// rung took the mesh and what the cleaning did.
    ///
    /// ```
    /// use dymsum::body::{BodyOptions, Rung};
    /// use dymsum::query::Body;
    /// use dymsum::PolygonMesh;
    /// // Two disjoint unit cubes in one mesh: a closed solid of two convex shells.
    /// let (mut v, mut f) = (Vec::new(), Vec::new());
    /// for dx in [0.0, 3.0] {
    ///     let o = v.len();
    ///     v.extend((0..8).map(|i| [dx + (i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64]));
    ///     for q in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
    ///         f.push(q.iter().map(|&i| o + i).collect::<Vec<usize>>());
    ///     }
    /// }
    /// let two = PolygonMesh::new(v.clone(), f.clone());
    /// let (body, report) = Body::from_mesh_with(&two, &BodyOptions::default())?;
    /// assert!(body.is_convex());
    /// assert_eq!((report.rung, report.pieces), (Rung::ConvexShells, 2));
    /// // One cube: exactly convex.
    /// let one = PolygonMesh::new(v[..8].to_vec(), f[..6].to_vec());
    /// let (_, report) = Body::from_mesh_with(&one, &BodyOptions::default())?;
    /// assert_eq!(report.rung, Rung::Convex);
    /// // Without its lid it is an open surface: triangles.
    /// let open = PolygonMesh::new(v[..8].to_vec(), f[..5].to_vec());
    /// let (body, report) = Body::from_mesh_with(&open, &BodyOptions::default())?;
    /// assert!(!body.is_convex());
    /// assert_eq!((report.rung, report.cleaning.unwrap().surfaces), (Rung::Triangles, 1));
    /// // A lid dented by 1e-9: triangles, unless the hull is asked for.
    /// let mut dented = one.clone();
    /// dented.vertices.push([0.5, 0.5, 1.0 - 1e-9]);
    /// dented.faces.retain(|q| q != &[4, 5, 7, 6]);
    /// dented.faces.extend([vec![4, 5, 8], vec![5, 7, 8], vec![7, 6, 8], vec![6, 4, 8]]);
    /// let (_, exact) = Body::from_mesh_with(&dented, &BodyOptions::default())?;
    /// let (_, hull) = Body::from_mesh_with(&dented, &BodyOptions { hull: true })?;
    /// assert_eq!((exact.rung, hull.rung), (Rung::Triangles, Rung::Hull));
    /// let deviation = hull.hull.unwrap().max_deviation;
    /// assert!(deviation > 0.0 && deviation < 2e-9);
    /// # Ok::<(), dymsum::SolidError>(())
    /// ```
    ///
    /// # Errors
    /// Those of [`MeshBody::new`]: no faces, a coordinate that is not
    /// finite, a malformed face, or no triangle left after cleaning
    /// ([`SolidError::Empty`]).
    pub fn from_mesh_with(
        mesh: &PolygonMesh,
        options: &BodyOptions,
    ) -> Result<(Body, BodyReport), SolidError> {
        if options.hull {
            if let Ok((hull, report)) = Polytope::from_mesh(mesh, MeshPolicy::default()) {
                let report = BodyReport {
                    rung: Rung::Hull,
                    cleaning: None,
                    hull: Some(report),
                    pieces: 1,
                };
                return Ok((Body::Convex(ConvexUnion::from(hull)), report));
            }
        }
        let body = MeshBody::new(mesh)?;
        let report = |rung, pieces| BodyReport {
            rung,
            cleaning: Some(body.report()),
            hull: None,
            pieces,
        };
        if body.as_convex().is_some() {
            let report = report(Rung::Convex, 1);
            return Ok((Body::Mesh(body), report));
        }
        if let Some(union) = exactly_convex_shells(mesh) {
            let report = report(Rung::ConvexShells, union.pieces().len());
            return Ok((Body::Convex(union), report));
        }
        let report = report(Rung::Triangles, 0);
        Ok((Body::Mesh(body), report))
    }
}

/// The union of a mesh's shells when it is a closed solid of at least two
/// shells, each exactly convex: the shells tried in order, and the first
/// that is not ends the search (without building the others' hulls).
fn exactly_convex_shells(mesh: &PolygonMesh) -> Option<ConvexUnion> {
    let solid = check_solid_mesh(mesh).ok()?;
    if solid.shells.len() < 2 {
        return None;
    }
    let pieces: Option<Vec<Polytope>> = solid
        .shells
        .iter()
        .map(|shell| shell_polytope(&shell_mesh(mesh, shell)))
        .collect();
    ConvexUnion::new(pieces?)
}

/// One shell of a mesh given as a solid: its faces' fan triangles as a mesh
/// of their own, and its polytope when it is exactly convex.
#[cfg(feature = "union-mesh")]
pub(crate) struct Shell {
    /// The shell's triangles, with only their vertices (read by
    /// `nonconvex`'s decomposition).
    pub(crate) mesh: PolygonMesh,
    /// The shell as a polytope, when exactly convex
    /// ([`MeshPolicy::strict`]).
    pub(crate) convex: Option<Polytope>,
}

/// The shells of `mesh` after the exact check that it is a solid
/// ([`check_solid_mesh`]), in its order.
///
/// # Errors
/// Those of [`check_solid_mesh`].
#[cfg(feature = "union-mesh")]
pub(crate) fn solid_shells(mesh: &PolygonMesh) -> Result<Vec<Shell>, SolidError> {
    let solid = check_solid_mesh(mesh)?;
    Ok(solid
        .shells
        .iter()
        .map(|shell| {
            let mesh = shell_mesh(mesh, shell);
            let convex = shell_polytope(&mesh);
            Shell { mesh, convex }
        })
        .collect())
}

/// The fan triangles of a shell's faces, with only their vertices.
fn shell_mesh(mesh: &PolygonMesh, shell: &[usize]) -> PolygonMesh {
    let fans = shell.iter().flat_map(|&f| {
        let face = &mesh.faces[f];
        face[1..].windows(2).map(move |w| [face[0], w[0], w[1]])
    });
    submesh(&mesh.vertices, fans)
}

/// A shell's polytope when it is exactly convex ([`MeshPolicy::strict`]):
/// refuted without its hull when two of its triangles fold inwards at an
/// edge (`has_reflex_edge`, which no shell the strict comparison accepts
/// has; counted in [`crate::body::mesh::exactly_convex_refuted_by_edges`]).
/// On example-robot-data's Z1 link 3 (33,580 triangles, many shells), the
/// hulls of every shell were 98% of the ladder's 1.8 s.
fn shell_polytope(shell: &PolygonMesh) -> Option<Polytope> {
    let vertices: Vec<glam::DVec3> = shell.vertices.iter().map(|&v| v.into()).collect();
    let triangles: Vec<[u32; 3]> = shell
        .faces
        .iter()
        .map(|f| [f[0] as u32, f[1] as u32, f[2] as u32])
        .collect();
    if has_reflex_edge(&vertices, &triangles) {
        exactly_convex_refuted_by_edges_add();
        return None;
    }
    Polytope::from_mesh(shell, MeshPolicy::strict())
        .ok()
        .map(|(p, _)| p)
}

fn submesh(vertices: &[[f64; 3]], tris: impl Iterator<Item = [usize; 3]>) -> PolygonMesh {
    let mut map = std::collections::HashMap::new();
    let mut v = Vec::new();
    let mut faces = Vec::new();
    for t in tris {
        faces.push(
            t.iter()
                .map(|&i| {
                    *map.entry(i).or_insert_with(|| {
                        v.push(vertices[i]);
                        v.len() - 1
                    })
                })
                .collect(),
        );
    }
    PolygonMesh::new(v, faces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::shapes::box_mesh;
    use glam::DVec3;

    /// Appends `part` moved by `by` to `mesh`.
    fn push(mesh: &mut PolygonMesh, part: &PolygonMesh, by: [f64; 3]) {
        let base = mesh.vertices.len();
        mesh.vertices.extend(
            part.vertices
                .iter()
                .map(|v| [0, 1, 2].map(|k| v[k] + by[k])),
        );
        mesh.faces.extend(
            part.faces
                .iter()
                .map(|f| f.iter().map(|v| v + base).collect()),
        );
    }

    /// An L-shaped prism: a closed solid with one reflex edge.
    fn ell() -> PolygonMesh {
        let outline = [
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ];
        let mut vertices = Vec::new();
        for z in [0.0, 1.0] {
            vertices.extend(outline.iter().map(|p| [p[0], p[1], z]));
        }
        let mut faces = vec![(0..6).rev().collect::<Vec<_>>(), (6..12).collect()];
        for i in 0..6 {
            let j = (i + 1) % 6;
            faces.push(vec![i, j, j + 6, i + 6]);
        }
        PolygonMesh::new(vertices, faces)
    }

    /// A shell that folds inwards is refuted without its hull, the first
    /// such shell ends the rung, and convex shells still make it.
    #[test]
    fn a_shell_that_folds_inwards_builds_no_hull() {
        let cube = box_mesh(DVec3::ONE);
        let shell = shell_mesh(&ell(), &(0..ell().faces.len()).collect::<Vec<_>>());
        let before = crate::body::mesh::exactly_convex_refuted_by_edges();
        assert!(shell_polytope(&shell).is_none());
        assert!(crate::body::mesh::exactly_convex_refuted_by_edges() > before);
        assert!(Polytope::from_mesh(&shell, MeshPolicy::strict()).is_err());
        let mut mixed = ell();
        push(&mut mixed, &cube, [5.0, 0.0, 0.0]);
        let (_, report) = Body::from_mesh_with(&mixed, &BodyOptions::default()).unwrap();
        assert_eq!(report.rung, Rung::Triangles);
        let mut two = PolygonMesh::new(Vec::new(), Vec::new());
        push(&mut two, &cube, [0.0; 3]);
        push(&mut two, &cube, [5.0, 0.0, 0.0]);
        let (_, report) = Body::from_mesh_with(&two, &BodyOptions::default()).unwrap();
        assert_eq!((report.rung, report.pieces), (Rung::ConvexShells, 2));
    }
}
