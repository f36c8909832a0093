//! A body given as triangles, prepared for the scenes' queries
//! ([`MeshBody`]): the cleaned mesh (or the boundaries of convex pieces),
//! which component each triangle belongs to and what that component is,
//! and a box tree over the triangles in the body's own frame.

use glam::DVec3;

use super::error::BodyError;
use super::inside_grid::InsideGrid;
use super::union::ConvexUnion;
use crate::kernel::rotation::Pose;
use crate::mesh::PolygonMesh;
use crate::sanity::SanityError;
use crate::solid::aabb::{Aabb, AabbTree};
use crate::solid::obb::{node_obbs, Obb};
use crate::solid::soup::{clean_soup, ComponentKind};
use crate::solid::SolidError;

/// What cleaning a body's mesh changed ([`crate::solid::soup::clean_soup`]'s
/// counts), and what its components are.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MeshReport {
    /// Triangles kept.
    pub triangles: usize,
    /// Vertices kept (after merging identical ones).
    pub vertices: usize,
    /// Vertices merged into an identical one.
    pub merged_vertices: usize,
    /// Triangles dropped as exactly collinear or repeating a vertex.
    pub dropped_zero_area: usize,
    /// Triangles dropped as a copy of a kept one.
    pub dropped_duplicates: usize,
    /// Triangles dropped as the back of a kept one (double-sided faces).
    pub dropped_back_to_back: usize,
    /// Triangles flipped (a closed shell oriented consistently, or every
    /// enclosing triangle when the input was inward as a whole).
    pub flipped: usize,
    /// Whether the enclosing triangles were given inward as a whole and
    /// turned (an exact negative volume).
    pub inverted: bool,
    /// Triangles set aside as surface for an unbalanced edge (parts that
    /// are not closed shells: a fin on a box, an open box).
    pub set_aside: usize,
    /// Edges split at vertices lying exactly on them (T-junctions).
    pub split_edges: usize,
    /// Components that enclose (contact includes lying where their winding
    /// number is not zero).
    pub solids: usize,
    /// Components that are surfaces (contact means touching a triangle).
    pub surfaces: usize,
}

/// A body as triangles, of any topology (open, double-sided, non-manifold,
/// several components), prepared for exact collision and motion checks
/// (the scenes' checker, `query::SceneChecker`).
///
/// Its triangles *enclose* (solid components: the largest part that is
/// closed as a cycle) or are *surface* (the rest), as [`clean_soup`]
/// decides exactly. Contact with the body means touching one of its
/// triangles, or lying where the winding number of its enclosing triangles
/// is not zero: touching solids, nested shells and T-junctions enclose, a
/// cavity is outside ([`crate::solid::soup`]).
///
/// ```
/// use dymsum::query::MeshBody;
/// use dymsum::PolygonMesh;
/// // A square exported double-sided (both faces, back to back), and a
/// // closed tetrahedron: one surface, one solid.
/// let mut faces = vec![vec![0, 1, 2, 3], vec![3, 2, 1, 0]];
/// faces.extend([[4, 6, 5], [4, 5, 7], [5, 6, 7], [4, 7, 6]].map(|f| f.to_vec()));
/// let v = vec![
///     [0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.],
///     [5., 0., 0.], [6., 0., 0.], [5., 1., 0.], [5., 0., 1.],
/// ];
/// let body = MeshBody::new(&PolygonMesh::new(v, faces))?;
/// let r = body.report();
/// assert_eq!((r.triangles, r.dropped_back_to_back, r.solids, r.surfaces), (6, 2, 1, 1));
/// # Ok::<(), dymsum::SolidError>(())
/// ```
#[derive(Clone, Debug)]
pub struct MeshBody {
    /// What does not change once the body is assembled, shared by its
    /// clones: a checker holds clones of its bodies, which copy no
    /// triangles and share the box tree once built.
    parts: std::sync::Arc<MeshParts>,
    /// The body each component came from, when bodies were joined
    /// ([`MeshBody::join`]; `0` otherwise): winding numbers are summed per
    /// body.
    pub(crate) source_of: Vec<u32>,
    /// The body as one convex polytope, when it is one solid component
    /// that is exactly convex.
    convex: Option<crate::polytope::Polytope>,
    /// Its empty cells classified as inside a solid or not
    /// ([`super::inside_grid`]), built on first use and shared by its
    /// clones; per body, not per [`MeshParts`], as the answer depends on
    /// `source_of`.
    inside_grid: std::sync::Arc<std::sync::OnceLock<InsideGrid>>,
}

/// The most components whose vertices get a tree
/// ([`MeshBody::component_points`]).
pub(crate) const MOST_COMPONENT_POINTS: usize = 1 << 16;

/// The fewest components whose vertices get a tree
/// ([`MeshBody::component_points`]).
pub(crate) const FEWEST_COMPONENT_POINTS: usize = 16;

/// A [`MeshBody`]'s triangles, components and trees (read through the body
/// itself: `body.vertices`, `body.tree()`).
#[derive(Debug)]
pub struct MeshParts {
    pub(crate) vertices: Vec<DVec3>,
    pub(crate) triangles: Vec<[u32; 3]>,
    /// The component of each triangle.
    pub(crate) component_of: Vec<u32>,
    /// Each triangle's weight in the winding number (`0` for surface
    /// triangles; [`crate::solid::soup::CleanSoup::weights`]).
    pub(crate) weights: Vec<u32>,
    /// Each component's kind and one of its vertices.
    pub(crate) components: Vec<(ComponentKind, u32)>,
    /// The box tree over the triangles and one oriented box per node of it
    /// (body frame; [`crate::solid::obb`]), built on first use
    /// ([`MeshBody::tree`]): a body on the convex path
    /// ([`MeshBody::as_convex`]) never reads them.
    triangle_tree: std::sync::OnceLock<(AabbTree, Vec<Obb>)>,
    /// A tree over each component's vertex of `components` (a point box
    /// each, body frame; item `c` is component `c`), built on first use
    /// ([`MeshBody::component_points`]), for bodies of at most
    /// [`MOST_COMPONENT_POINTS`] components.
    component_points: std::sync::OnceLock<Option<AabbTree>>,
    /// Each component's box (body frame).
    pub(crate) component_boxes: Vec<Aabb>,
    /// The solid components (their indices).
    pub(crate) solid_components: Vec<u32>,
    /// A tree over the solid components' boxes (item `k` is
    /// `solid_components[k]`).
    pub(crate) solid_tree: AabbTree,
    /// The largest vertex norm (rounded up): how far a point of the body
    /// lies from its origin.
    pub(crate) reach: f64,
    report: MeshReport,
}

impl std::ops::Deref for MeshBody {
    type Target = MeshParts;

    fn deref(&self) -> &MeshParts {
        &self.parts
    }
}

impl MeshBody {
    /// The box tree over the triangles (item `i` is triangle `i`), built
    /// with [`MeshBody::obbs`] on first use.
    pub(crate) fn tree(&self) -> &AabbTree {
        &self.triangle_tree().0
    }

    /// One oriented box per node of [`MeshBody::tree`] (body frame).
    pub(crate) fn obbs(&self) -> &[Obb] {
        &self.triangle_tree().1
    }

    /// The body's classified cells ([`super::inside_grid`]), built on
    /// first use (after the tree, which its rays walk).
    pub(crate) fn inside_grid(&self) -> &InsideGrid {
        self.inside_grid.get_or_init(|| InsideGrid::new(self))
    }

    /// The tree over the components' vertices (item `c` at component
    /// `c`'s vertex of `components`), built on first use; `None` past
    /// [`MOST_COMPONENT_POINTS`] components (a soup's: its memory would
    /// rival the triangles' tree) or for fewer than
    /// [`FEWEST_COMPONENT_POINTS`] (a loop over them costs less).
    pub(crate) fn component_points(&self) -> Option<&AabbTree> {
        self.component_points
            .get_or_init(|| {
                let n = self.components.len();
                (FEWEST_COMPONENT_POINTS..=MOST_COMPONENT_POINTS)
                    .contains(&n)
                    .then(|| {
                        let points: Vec<Aabb> = self
                            .components
                            .iter()
                            .map(|&(_, v)| {
                                let at = self.vertices[v as usize].to_array();
                                Aabb { lo: at, hi: at }
                            })
                            .collect();
                        AabbTree::new(&points)
                    })
            })
            .as_ref()
    }

    fn triangle_tree(&self) -> &(AabbTree, Vec<Obb>) {
        self.triangle_tree.get_or_init(|| {
            let (vertices, triangles) = (&self.vertices, &self.triangles);
            let tree = AabbTree::new(&triangle_boxes(vertices, triangles));
            let obbs = node_obbs(&tree, |i| triangles[i].map(|v| vertices[v as usize]));
            (tree, obbs)
        })
    }

    /// Cleans `mesh` exactly and classifies its components
    /// ([`clean_soup`]); the box tree over its triangles is built on first
    /// use.
    ///
    /// # Errors
    /// Those of [`clean_soup`]: no faces, a coordinate that is not finite,
    /// a face of fewer than three corners or naming a missing vertex; and
    /// [`SolidError::Empty`] when every triangle is dropped (all of zero
    /// area).
    pub fn new(mesh: &PolygonMesh) -> Result<MeshBody, SolidError> {
        let soup = clean_soup(mesh)?;
        if soup.mesh.faces.is_empty() {
            return Err(SolidError::Empty);
        }
        let mut component_of = vec![0u32; soup.mesh.faces.len()];
        let mut components = Vec::with_capacity(soup.components.len());
        for (c, comp) in soup.components.iter().enumerate() {
            for &t in &comp.triangles {
                component_of[t] = c as u32;
            }
            components.push((comp.kind, soup.mesh.faces[comp.triangles[0]][0] as u32));
        }
        let triangles = soup
            .mesh
            .faces
            .iter()
            .map(|f| [f[0] as u32, f[1] as u32, f[2] as u32])
            .collect();
        let vertices = soup.mesh.vertices.iter().map(|&p| DVec3::from(p)).collect();
        let report = MeshReport {
            triangles: soup.mesh.faces.len(),
            vertices: soup.mesh.vertices.len(),
            merged_vertices: soup.merged_vertices,
            dropped_zero_area: soup.dropped_zero_area,
            dropped_duplicates: soup.dropped_duplicates,
            dropped_back_to_back: soup.dropped_back_to_back,
            flipped: soup.flipped,
            inverted: soup.inverted,
            set_aside: soup.set_aside,
            split_edges: soup.split_edges,
            solids: soup.solids(),
            surfaces: soup.components.len() - soup.solids(),
        };
        let mut body = MeshBody::assemble(
            vertices,
            triangles,
            component_of,
            soup.weights,
            components,
            report,
        );
        body.convex = body.exactly_convex();
        Ok(body)
    }

    /// The body as one polytope when it is one solid component and exactly
    /// convex ([`crate::polytope::MeshPolicy::strict`]).
    fn exactly_convex(&self) -> Option<crate::polytope::Polytope> {
        if self.components.len() != 1 || self.components[0].0 != ComponentKind::Solid {
            return None;
        }
        if has_reflex_edge(&self.vertices, &self.triangles) {
            exactly_convex_refuted_by_edges_add();
            return None;
        }
        let mesh = self.cleaned_mesh();
        crate::polytope::Polytope::from_mesh(&mesh, crate::polytope::MeshPolicy::strict())
            .ok()
            .map(|(p, _)| p)
    }

    /// The cleaned triangles as a polygon mesh (what the strict convexity
    /// comparison reads).
    fn cleaned_mesh(&self) -> PolygonMesh {
        PolygonMesh::new(
            self.vertices.iter().map(|v| v.to_array()).collect(),
            self.triangles
                .iter()
                .map(|t| t.iter().map(|&v| v as usize).collect())
                .collect(),
        )
    }

    /// The body as one convex polytope, when it is one solid component
    /// that is exactly convex (checked by [`MeshBody::new`]; a mesh convex
    /// only within rounding is not): the convex fast path's input.
    pub fn as_convex(&self) -> Option<&crate::polytope::Polytope> {
        self.convex.as_ref()
    }

    /// The boundaries of convex pieces as one body, each piece a solid
    /// component of its own (pieces may overlap or share vertices).
    pub fn from_union(union: &ConvexUnion) -> MeshBody {
        let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
        let (mut component_of, mut components) = (Vec::new(), Vec::new());
        let mut weights = Vec::new();
        for (c, piece) in union.pieces().iter().enumerate() {
            let base = vertices.len() as u32;
            vertices.extend_from_slice(piece.vertices());
            components.push((ComponentKind::Solid, base));
            for f in piece.faces() {
                for w in f[1..].windows(2) {
                    triangles.push([base + f[0], base + w[0], base + w[1]]);
                    component_of.push(c as u32);
                    weights.push(1);
                }
            }
        }
        let report = MeshReport {
            triangles: triangles.len(),
            vertices: vertices.len(),
            solids: components.len(),
            ..MeshReport::default()
        };
        MeshBody::assemble(
            vertices,
            triangles,
            component_of,
            weights,
            components,
            report,
        )
    }

    /// Several bodies as one (their components side by side), e.g. a
    /// scene's obstacles placed in the world frame.
    pub fn join(bodies: &[MeshBody]) -> MeshBody {
        if let [one] = bodies {
            // What assembling its parts again would build (the same
            // vertices, triangles and components give the same trees),
            // without the work: a robot's checker joins each link alone.
            let mut joined = one.clone();
            if joined.source_of.iter().any(|&s| s != 0) {
                // Its grid's regions were classified per source.
                joined.inside_grid = Default::default();
            }
            joined.source_of.fill(0);
            joined.convex = None;
            return joined;
        }
        MeshBody::join_assembled(bodies)
    }

    /// [`MeshBody::join`] by assembling the bodies' parts side by side.
    fn join_assembled(bodies: &[MeshBody]) -> MeshBody {
        let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
        let (mut component_of, mut components) = (Vec::new(), Vec::new());
        let mut weights = Vec::new();
        let mut report = MeshReport::default();
        let mut sources = Vec::new();
        for (source, b) in bodies.iter().enumerate() {
            let (vb, cb) = (vertices.len() as u32, components.len() as u32);
            vertices.extend_from_slice(&b.vertices);
            triangles.extend(b.triangles.iter().map(|t| t.map(|v| v + vb)));
            component_of.extend(b.component_of.iter().map(|c| c + cb));
            sources.extend(std::iter::repeat_n(source as u32, b.components.len()));
            weights.extend_from_slice(&b.weights);
            components.extend(b.components.iter().map(|&(k, v)| (k, v + vb)));
            let r = b.report;
            report = MeshReport {
                triangles: report.triangles + r.triangles,
                vertices: report.vertices + r.vertices,
                merged_vertices: report.merged_vertices + r.merged_vertices,
                dropped_zero_area: report.dropped_zero_area + r.dropped_zero_area,
                dropped_duplicates: report.dropped_duplicates + r.dropped_duplicates,
                dropped_back_to_back: report.dropped_back_to_back + r.dropped_back_to_back,
                flipped: report.flipped + r.flipped,
                inverted: report.inverted || r.inverted,
                set_aside: report.set_aside + r.set_aside,
                split_edges: report.split_edges + r.split_edges,
                solids: report.solids + r.solids,
                surfaces: report.surfaces + r.surfaces,
            };
        }
        let mut joined = MeshBody::assemble(
            vertices,
            triangles,
            component_of,
            weights,
            components,
            report,
        );
        joined.source_of = sources;
        joined
    }

    fn assemble(
        vertices: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
        component_of: Vec<u32>,
        weights: Vec<u32>,
        components: Vec<(ComponentKind, u32)>,
        report: MeshReport,
    ) -> MeshBody {
        let boxes = triangle_boxes(&vertices, &triangles);
        let mut component_boxes = vec![Aabb::EMPTY; components.len()];
        for (t, b) in boxes.iter().enumerate() {
            let c = component_of[t] as usize;
            component_boxes[c] = component_boxes[c].join(b);
        }
        let solid_components: Vec<u32> = (0..components.len() as u32)
            .filter(|&c| components[c as usize].0 == ComponentKind::Solid)
            .collect();
        let solid_boxes: Vec<Aabb> = solid_components
            .iter()
            .map(|&c| component_boxes[c as usize])
            .collect();
        let solid_tree = AabbTree::new(&solid_boxes);
        // √3 times the largest coordinate bounds every norm without
        // squaring (no underflow for tiny bodies, no overflow for huge ones).
        let reach = vertices
            .iter()
            .map(|v| v.abs().max_element())
            .fold(0.0, f64::max)
            * (3f64.sqrt() * (1.0 + 1e-12))
            + 1e-300;
        MeshBody {
            source_of: vec![0; components.len()],
            parts: std::sync::Arc::new(MeshParts {
                vertices,
                triangles,
                component_of,
                weights,
                components,
                triangle_tree: std::sync::OnceLock::new(),
                component_points: std::sync::OnceLock::new(),
                component_boxes,
                solid_components,
                solid_tree,
                reach,
                report,
            }),
            convex: None,
            inside_grid: Default::default(),
        }
    }

    /// The body placed at `pose` (`Body::placed`): its vertices
    /// posed once in floats, the trees built again, what the cleaning
    /// decided kept.
    ///
    /// # Errors
    /// [`BodyError::NotFinite`] when a posed coordinate is not finite.
    pub fn placed(&self, pose: Pose) -> Result<MeshBody, BodyError> {
        let vertices: Vec<DVec3> = self.vertices.iter().map(|&v| pose.apply(v)).collect();
        if vertices.iter().any(|v| !v.is_finite()) {
            return Err(BodyError::NotFinite {
                translation: pose.translation.to_array(),
            });
        }
        let mut body = MeshBody::assemble(
            vertices,
            self.triangles.clone(),
            self.component_of.clone(),
            self.weights.clone(),
            self.components.clone(),
            self.report,
        );
        body.source_of = self.source_of.clone();
        // Exactly convex again only if the posed triangles still are (as
        // for the same mesh moved by hand).
        if self.convex.is_some() {
            body.convex = body.exactly_convex();
        }
        Ok(body)
    }

    /// What cleaning changed and what the components are.
    pub fn report(&self) -> MeshReport {
        self.report
    }

    /// The vertices (body frame).
    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    /// The triangles (solid components' oriented outward).
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The kind of each connected component.
    pub fn component_kinds(&self) -> impl Iterator<Item = ComponentKind> + '_ {
        self.components.iter().map(|c| c.0)
    }

    /// Checks the invariants the queries rely on: indices in range, one
    /// component and one weight per triangle (a weight exactly for the
    /// enclosing ones), each component's vertex one of its triangles'
    /// corners, finite coordinates, the trees sound
    /// (the box tree's own `sanity_check`) over exactly the triangles' and the
    /// solid components' boxes, the reach above every vertex norm, the
    /// inside grid's own invariants once it is built.
    ///
    /// # Errors
    /// [`SanityError::MeshBody`] naming the broken invariant and where (a
    /// bug, or a body assembled from inconsistent parts), or the trees'
    /// [`SanityError::BoxTree`].
    pub fn sanity_check(&self) -> Result<(), SanityError> {
        let bad = |reason: String| Err(SanityError::MeshBody { reason });
        let n = self.vertices.len() as u32;
        if let Some(v) = self.vertices.iter().position(|v| !v.is_finite()) {
            return bad(format!("vertex {v} is not finite"));
        }
        if self.triangles.len() != self.component_of.len()
            || self.triangles.len() != self.weights.len()
            || self.source_of.len() != self.components.len()
        {
            return bad("not one component and one weight per triangle".into());
        }
        let mut seen = vec![false; self.components.len()];
        for (t, tri) in self.triangles.iter().enumerate() {
            if !tri.iter().all(|&v| v < n) {
                return bad(format!("triangle {t} names a missing vertex"));
            }
            let c = self.component_of[t] as usize;
            let Some(&(kind, corner)) = self.components.get(c) else {
                return bad(format!("triangle {t}: component {c} out of range"));
            };
            if (self.weights[t] > 0) != (kind == ComponentKind::Solid) {
                return bad(format!(
                    "triangle {t}: a weight in the winding number but no solid, or the reverse"
                ));
            }
            seen[c] |= tri.contains(&corner);
        }
        if let Some(c) = seen.iter().position(|&s| !s) {
            return bad(format!("component {c}'s vertex is not on its triangles"));
        }
        self.tree().sanity_check()?;
        self.solid_tree.sanity_check()?;
        let boxes = triangle_boxes(&self.vertices, &self.triangles);
        let same = |a: &Aabb, b: &Aabb| a.lo == b.lo && a.hi == b.hi;
        if boxes.len() != self.tree().boxes().len()
            || boxes
                .iter()
                .zip(self.tree().boxes())
                .any(|(a, b)| !same(a, b))
        {
            return bad("the tree's boxes are not the triangles' boxes".into());
        }
        if self.solid_components.len() != self.solid_tree.boxes().len()
            || self
                .solid_components
                .iter()
                .zip(self.solid_tree.boxes())
                .any(|(&c, b)| !same(&self.component_boxes[c as usize], b))
        {
            return bad("the solid tree's boxes are not the solid components' boxes".into());
        }
        if let Some(points) = self.component_points() {
            points.sanity_check()?;
            let at = |v: u32| self.vertices[v as usize].to_array();
            if points.boxes().len() != self.components.len()
                || self
                    .components
                    .iter()
                    .zip(points.boxes())
                    .any(|(&(_, v), b)| b.lo != at(v) || b.hi != at(v))
            {
                return bad("the component points' tree is not the components' vertices".into());
            }
        }
        if let Some(v) = self.vertices.iter().position(|v| v.length() > self.reach) {
            return bad(format!("the reach is below vertex {v}'s norm"));
        }
        let spans = self.tree().node_spans();
        if self.obbs().len() != spans.len() {
            return bad("not one oriented box per tree node".into());
        }
        for (n, (&(s, e), o)) in spans.iter().zip(self.obbs()).enumerate() {
            let items = &self.tree().items()[s as usize..e as usize];
            let corner = |&i: &u32| self.triangles[i as usize].map(|v| self.vertices[v as usize]);
            if !items.iter().flat_map(corner).all(|p| o.holds(p)) {
                return bad(format!(
                    "node {n}'s oriented box misses a corner of its triangles"
                ));
            }
        }
        if let Some(grid) = self.inside_grid.get() {
            grid.sanity_check()?;
        }
        Ok(())
    }
}

/// The exact boxes of triangles over `vertices`.
pub(crate) fn triangle_boxes(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Vec<Aabb> {
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| vertices[v as usize]);
            Aabb {
                lo: a.min(b).min(c).to_array(),
                hi: a.max(b).max(c).to_array(),
            }
        })
        .collect()
}

/// A convex polytope placed at `pose`: the hull of its posed vertices.
pub(crate) fn placed_polytope(
    p: &crate::polytope::Polytope,
    pose: Pose,
) -> Result<crate::polytope::Polytope, BodyError> {
    let posed: Vec<[f64; 3]> = p
        .vertices()
        .iter()
        .map(|&v| pose.apply(v).to_array())
        .collect();
    if posed.iter().flatten().any(|x| !x.is_finite()) {
        return Err(BodyError::NotFinite {
            translation: pose.translation.to_array(),
        });
    }
    crate::polytope::Polytope::from_points(&posed).map_err(|e| BodyError::Flattened(e.to_string()))
}

/// How many bodies [`MeshBody::new`] found not exactly convex from their
/// edges alone ([`has_reflex_edge`]), without building their hull.
static EXACTLY_CONVEX_REFUTED_BY_EDGES: std::sync::atomic::AtomicU64 =
    std::sync::atomic::AtomicU64::new(0);

pub(crate) fn exactly_convex_refuted_by_edges_add() {
    EXACTLY_CONVEX_REFUTED_BY_EDGES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
}

/// How many bodies (and shells of the body ladder's convex-shells rung)
/// were found not exactly convex by their edges alone, without building
/// their hull (the rest of the one-solid bodies build it and compare): a
/// counter for benchmarks, process-wide.
pub fn exactly_convex_refuted_by_edges() -> u64 {
    EXACTLY_CONVEX_REFUTED_BY_EDGES.load(std::sync::atomic::Ordering::Relaxed)
}

/// `true` when two triangles that share an edge in opposite directions
/// (consistently oriented neighbours) fold strictly inwards: the far
/// corner of the second strictly above the first's plane, on the side its
/// corners wind counter-clockwise (exact `orient3d`), a reflex edge.
///
/// Such a mesh takes the triangle path without its hull being built: a
/// closed sphere whose every triangle lies in the plane of a hull face
/// and faces outwards (what [`crate::polytope::Polytope::from_mesh`]
/// accepts under the strict policy, robot parts included) has every
/// vertex on the closed inner side of every triangle's plane, so no far
/// corner strictly above. The strict comparison checks the orientation
/// by the signed volume only, so it also accepts a surface that folds
/// back inside a face plane (a layer turned inwards between two outward
/// ones, all in the hull's planes: the same solid); such a fold can show
/// a reflex edge here, and then only the convex fast path is lost: the
/// body stays exact as triangles (an independent review found the case;
/// the test below counts how often it happens on moved hulls). Edges with
/// other than two users, or two users running the same way, are skipped:
/// they witness nothing. `false` decides nothing (a mesh can have no
/// reflex edge and still not be exactly convex: it winds twice, or is
/// inward), and the hull is compared as before.
///
/// O(T log T) for T triangles: the 3T directed edges sorted by their
/// undirected key, one `orient3d` (float-filtered) per shared edge until
/// the first reflex one.
pub(crate) fn has_reflex_edge(vertices: &[DVec3], triangles: &[[u32; 3]]) -> bool {
    use crate::kernel::predicates::{orient, Sign};
    // (undirected key, triangle · 3 + position of the edge's first corner)
    let mut edges: Vec<(u64, u32)> = Vec::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
            edges.push((key, (3 * t + k) as u32));
        }
    }
    edges.sort_unstable();
    let mut i = 0;
    while i < edges.len() {
        let mut j = i + 1;
        while j < edges.len() && edges[j].0 == edges[i].0 {
            j += 1;
        }
        if j - i == 2 {
            let corner = |slot: u32| {
                let (t, k) = ((slot / 3) as usize, (slot % 3) as usize);
                (triangles[t], k)
            };
            let ((t0, k0), (t1, k1)) = (corner(edges[i].1), corner(edges[i + 1].1));
            // Opposite directions: t0 runs a → b where t1 runs b → a.
            if t0[k0] == t1[(k1 + 1) % 3] {
                let far = vertices[t1[(k1 + 2) % 3] as usize];
                let [a, b, c] = t0.map(|v| vertices[v as usize]);
                if orient(a, b, c, far) == Sign::Positive {
                    return true;
                }
            }
        }
        i = j;
    }
    false
}

#[cfg(test)]
mod join_tests {
    use super::*;

    /// Joining one body clones it: the same structure, field by field, as
    /// assembling its parts again (the path for several bodies).
    #[test]
    fn joining_one_body_is_assembling_it_again() {
        let v = vec![
            [0., 0., 0.],
            [1., 0., 0.],
            [1., 1., 0.],
            [0., 1., 0.],
            [0., 0., 1.],
            [1., 0., 1.],
            [1., 1., 1.],
            [0., 1., 1.],
            [5., 0., 0.],
            [6., 0., 0.],
            [5., 1., 0.],
        ];
        let faces = vec![
            vec![0, 3, 2, 1],
            vec![4, 5, 6, 7],
            vec![0, 1, 5, 4],
            vec![1, 2, 6, 5],
            vec![2, 3, 7, 6],
            vec![3, 0, 4, 7],
            vec![8, 9, 10],
        ];
        let body = MeshBody::new(&PolygonMesh::new(v, faces)).unwrap();
        let twice = MeshBody::join(&[body.clone(), body.clone()]);
        for one in [body, twice] {
            let fast = MeshBody::join(std::slice::from_ref(&one));
            let slow = MeshBody::join_assembled(std::slice::from_ref(&one));
            assert_eq!(format!("{fast:?}"), format!("{slow:?}"));
        }
    }

    /// The hull of a few points of a small grid (many coplanar corners),
    /// its faces as fans, then one corner moved: the reflex-edge filter
    /// never refutes an unmoved hull, refutes most moved ones, and the
    /// body takes the convex fast path exactly where the strict
    /// comparison accepts and no fold refuted it (rare: at most one in a
    /// hundred refutations).
    #[test]
    fn a_reflex_edge_costs_at_most_the_fast_path_of_a_fold() {
        use crate::polytope::{MeshPolicy, Polytope};
        use proptest::prelude::*;
        use proptest::test_runner::{Config, TestRunner};
        let (refuted, lost) = (std::cell::Cell::new(0), std::cell::Cell::new(0));
        let mut runner = TestRunner::new(Config::with_cases(400));
        let points = proptest::collection::vec(proptest::array::uniform3(-3i8..=3), 5..20);
        let moved = (
            any::<prop::sample::Index>(),
            proptest::array::uniform3(-2i8..=2),
        );
        runner
            .run(&(points, moved), |(points, (which, by))| {
                let pts: Vec<[f64; 3]> = points.iter().map(|p| p.map(f64::from)).collect();
                let Ok(hull) = Polytope::from_points(&pts) else {
                    return Ok(());
                };
                let mut vertices: Vec<DVec3> = hull.vertices().to_vec();
                let mut triangles = Vec::new();
                for f in hull.faces() {
                    for w in f[1..].windows(2) {
                        triangles.push([f[0], w[0], w[1]]);
                    }
                }
                prop_assert!(!has_reflex_edge(&vertices, &triangles));
                let v = which.index(vertices.len());
                vertices[v] += DVec3::from(by.map(f64::from));
                let mesh = PolygonMesh::new(
                    vertices.iter().map(|p| p.to_array()).collect(),
                    triangles
                        .iter()
                        .map(|t| t.iter().map(|&i| i as usize).collect())
                        .collect(),
                );
                let refutes = has_reflex_edge(&vertices, &triangles);
                if refutes {
                    refuted.set(refuted.get() + 1);
                }
                // On the cleaned triangles (an inverted mesh is turned
                // outwards): the fast path only where the strict
                // comparison accepts, and there unless a reflex edge (a
                // fold within a face plane) refuted it first.
                if let Ok(body) = MeshBody::new(&mesh) {
                    if body.components.len() == 1 {
                        let strict =
                            Polytope::from_mesh(&body.cleaned_mesh(), MeshPolicy::strict()).is_ok();
                        let folded = has_reflex_edge(&body.vertices, &body.triangles);
                        prop_assert_eq!(body.as_convex().is_some(), strict && !folded);
                        if strict && folded {
                            lost.set(lost.get() + 1);
                        }
                    }
                }
                Ok(())
            })
            .unwrap();
        let (refuted, lost) = (refuted.get(), lost.get());
        assert!(
            refuted > 50,
            "the filter refuted only {refuted} moved hulls"
        );
        assert!(
            lost * 100 <= refuted,
            "the filter took the fast path from {lost} exactly convex bodies"
        );
    }
}
