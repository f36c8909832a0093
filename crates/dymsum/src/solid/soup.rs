//! Triangle meshes as they come out of CAD and planning suites (issue 28,
//! "Bodies as they come"): open, double-sided, non-manifold, several
//! components, float32 coordinates. [`clean_soup`] cleans such a mesh
//! exactly and says what each connected component is:
//!
//! 1. identical vertices (bit-equal coordinates, `-0.0` as `0.0`) are
//!    merged;
//! 2. faces are taken as their fan triangles; a triangle whose corners are
//!    exactly collinear (exact predicates) or repeat a vertex is dropped;
//! 3. of triangles with the same corners, the first is kept: a copy with
//!    the same orientation is a duplicate, one with the opposite
//!    orientation the back of a double-sided face (exports write every face
//!    twice, back to back); a polygon of more than three corners that
//!    repeats a kept polygon's cycle, either way round, is dropped whole
//!    first (a double-sided quad fans into other triangles from its other
//!    side);
//! 4. each connected component (through shared vertices) is a
//!    [`ComponentKind::Solid`] when it can be oriented consistently (every
//!    edge in exactly two of its triangles, the orientation propagated
//!    across them without a contradiction) and then passes the exact solid
//!    check ([`super::check_solid_mesh`]: manifold at every vertex, no two
//!    triangles crossing, positive volume, with the whole component flipped
//!    when its volume is negative): its triangles come back oriented
//!    outward. Anything else is a [`ComponentKind::Surface`], its triangles
//!    as given.
//!
//! Every decision is exact; the counts say what was changed.

use std::collections::HashMap;

use super::{check_solid_mesh, collinear, shells, SolidError};
use crate::mesh::PolygonMesh;

/// What a connected component of a cleaned mesh is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ComponentKind {
    /// Closed, manifold, consistently oriented (outward), not crossing
    /// itself, of positive volume: contact includes being inside it.
    Solid,
    /// Anything else (open, non-manifold, non-orientable, crossing
    /// itself): contact means touching one of its triangles.
    Surface,
}

/// One connected component of a cleaned mesh.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Component {
    /// Its triangles (indices into [`CleanSoup::mesh`]'s faces), ascending.
    pub triangles: Vec<usize>,
    /// What it is.
    pub kind: ComponentKind,
}

/// A mesh cleaned by [`clean_soup`], with what the cleaning changed.
#[derive(Clone, Debug, PartialEq)]
pub struct CleanSoup {
    /// The cleaned triangles (solids oriented outward) over the merged
    /// vertices.
    pub mesh: PolygonMesh,
    /// Vertices merged into an identical one.
    pub merged_vertices: usize,
    /// Triangles dropped as exactly collinear or repeating a vertex.
    pub dropped_zero_area: usize,
    /// Triangles dropped as a copy of a kept one with the same orientation.
    pub dropped_duplicates: usize,
    /// Triangles dropped as the back of a kept one (double-sided faces).
    pub dropped_back_to_back: usize,
    /// Triangles of solid components flipped to face outward.
    pub flipped: usize,
    /// The connected components, in the order of their first triangle.
    pub components: Vec<Component>,
}

impl CleanSoup {
    /// How many components are solids.
    pub fn solids(&self) -> usize {
        self.components
            .iter()
            .filter(|c| c.kind == ComponentKind::Solid)
            .count()
    }
}

/// Cleans a triangle (or polygon) mesh exactly and classifies its
/// components (module docs).
///
/// ```
/// use dymsum::solid::soup::{clean_soup, ComponentKind};
/// use dymsum::PolygonMesh;
/// // A tetrahedron exported double-sided: every face twice, back to back.
/// let v = vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
/// let one = vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]];
/// let mut faces = one.clone();
/// faces.extend(one.iter().map(|f| vec![f[0], f[2], f[1]]));
/// let soup = clean_soup(&PolygonMesh::new(v, faces))?;
/// assert_eq!((soup.mesh.faces.len(), soup.dropped_back_to_back), (4, 4));
/// assert_eq!(soup.components[0].kind, ComponentKind::Solid);
/// # Ok::<(), dymsum::SolidError>(())
/// ```
///
/// # Errors
/// [`SolidError::Empty`] without faces, [`SolidError::NonFinite`] for a
/// coordinate that is not finite, [`SolidError::BadFace`] for a face of
/// fewer than three corners or an index out of range.
pub fn clean_soup(mesh: &PolygonMesh) -> Result<CleanSoup, SolidError> {
    if mesh.faces.is_empty() {
        return Err(SolidError::Empty);
    }
    if let Some(vertex) = mesh
        .vertices
        .iter()
        .position(|p| !p.iter().all(|x| x.is_finite()))
    {
        return Err(SolidError::NonFinite { vertex });
    }
    // 1. Identical vertices.
    let mut first: HashMap<[u64; 3], usize> = HashMap::with_capacity(mesh.vertices.len());
    let mut vertices: Vec<[f64; 3]> = Vec::new();
    let remap: Vec<usize> = mesh
        .vertices
        .iter()
        .map(|p| {
            let key = p.map(|x| (x + 0.0).to_bits());
            *first.entry(key).or_insert_with(|| {
                vertices.push(p.map(|x| x + 0.0));
                vertices.len() - 1
            })
        })
        .collect();
    let merged_vertices = mesh.vertices.len() - vertices.len();
    // 2. Fan triangles, degenerate ones dropped; 3. duplicates and backs.
    let mut triangles: Vec<[usize; 3]> = Vec::new();
    let mut by_corners: HashMap<[usize; 3], usize> = HashMap::new();
    let (mut dropped_zero_area, mut dropped_duplicates, mut dropped_back_to_back) = (0, 0, 0);
    let mut polygons: HashMap<Vec<usize>, ()> = HashMap::new();
    for (face, f) in mesh.faces.iter().enumerate() {
        if f.len() < 3 || f.iter().any(|&v| v >= remap.len()) {
            return Err(SolidError::BadFace { face });
        }
        if f.len() > 3 {
            // A polygon repeated, or listed again the other way round (a
            // double-sided quad), is dropped whole: fanned from another
            // corner its triangles would not repeat the first copy's.
            let cycle: Vec<usize> = f.iter().map(|&v| remap[v]).collect();
            let reversed: Vec<usize> = cycle.iter().rev().copied().collect();
            let (fwd, back) = (canonical_cycle(&cycle), canonical_cycle(&reversed));
            if polygons.contains_key(&fwd) {
                dropped_duplicates += f.len() - 2;
                continue;
            }
            if polygons.contains_key(&back) {
                dropped_back_to_back += f.len() - 2;
                continue;
            }
            polygons.insert(fwd, ());
        }
        for w in f[1..].windows(2) {
            let t = [remap[f[0]], remap[w[0]], remap[w[1]]];
            if t[0] == t[1]
                || t[1] == t[2]
                || t[0] == t[2]
                || collinear(vertices[t[0]], vertices[t[1]], vertices[t[2]])
            {
                dropped_zero_area += 1;
                continue;
            }
            let mut key = t;
            key.sort_unstable();
            match by_corners.get(&key) {
                Some(&kept) if same_orientation(triangles[kept], t) => dropped_duplicates += 1,
                Some(_) => dropped_back_to_back += 1,
                None => {
                    by_corners.insert(key, triangles.len());
                    triangles.push(t);
                }
            }
        }
    }
    // 4. Components.
    let mut flipped = 0;
    let mut components = Vec::new();
    for comp in shells(vertices.len(), &triangles) {
        let kind = match oriented(&triangles, &comp) {
            Some(flips) => {
                let mut tris: Vec<[usize; 3]> = comp
                    .iter()
                    .zip(&flips)
                    .map(|(&k, &flip)| flipped_if(triangles[k], flip))
                    .collect();
                match solid_orientation(&vertices, &tris) {
                    Some(outward) => {
                        if !outward {
                            tris.iter_mut().for_each(|t| *t = flipped_if(*t, true));
                        }
                        for (&k, t) in comp.iter().zip(&tris) {
                            if triangles[k] != *t {
                                flipped += 1;
                            }
                            triangles[k] = *t;
                        }
                        ComponentKind::Solid
                    }
                    None => ComponentKind::Surface,
                }
            }
            None => ComponentKind::Surface,
        };
        components.push(Component {
            triangles: comp,
            kind,
        });
    }
    Ok(CleanSoup {
        mesh: PolygonMesh::new(vertices, triangles.iter().map(|t| t.to_vec()).collect()),
        merged_vertices,
        dropped_zero_area,
        dropped_duplicates,
        dropped_back_to_back,
        flipped,
        components,
    })
}

/// A vertex cycle rotated to start at its smallest index (the same cycle
/// from any start gives the same key).
fn canonical_cycle(cycle: &[usize]) -> Vec<usize> {
    let start = (0..cycle.len()).min_by_key(|&i| cycle[i]).unwrap_or(0);
    cycle[start..]
        .iter()
        .chain(&cycle[..start])
        .copied()
        .collect()
}

/// Whether two triangles with the same corners run the same way round.
fn same_orientation(a: [usize; 3], b: [usize; 3]) -> bool {
    (0..3).any(|r| [b[r], b[(r + 1) % 3], b[(r + 2) % 3]] == a)
}

/// The triangle, reversed when `flip`.
fn flipped_if(t: [usize; 3], flip: bool) -> [usize; 3] {
    if flip {
        [t[0], t[2], t[1]]
    } else {
        t
    }
}

/// Per triangle of the component, whether to flip it so that every edge is
/// used once in each direction; `None` when an edge lies in other than two
/// of its triangles or the orientation cannot be made consistent (a Möbius
/// band).
fn oriented(triangles: &[[usize; 3]], comp: &[usize]) -> Option<Vec<bool>> {
    // Undirected edge → (position in comp, runs from the smaller vertex).
    let mut edges: HashMap<(usize, usize), Vec<(usize, bool)>> = HashMap::new();
    for (i, &k) in comp.iter().enumerate() {
        let t = triangles[k];
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            edges
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push((i, a < b));
        }
    }
    if edges.values().any(|users| users.len() != 2) {
        return None;
    }
    let mut flip: Vec<Option<bool>> = vec![None; comp.len()];
    let mut stack = vec![0];
    flip[0] = Some(false);
    while let Some(i) = stack.pop() {
        let t = triangles[comp[i]];
        let fi = flip[i].expect("set before pushed");
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            let users = &edges[&(a.min(b), a.max(b))];
            let (j, j_forward) = if users[0].0 == i { users[1] } else { users[0] };
            // Consistent: the two run the edge in opposite directions after
            // their flips.
            let i_forward = (a < b) != fi;
            let want = j_forward == i_forward; // flip j iff it runs the same way
            match flip[j] {
                None => {
                    flip[j] = Some(want);
                    stack.push(j);
                }
                Some(f) if f != want => return None,
                Some(_) => {}
            }
        }
    }
    flip.into_iter().collect()
}

/// For a consistently oriented closed component: `Some(true)` when it
/// passes the exact solid check as it is, `Some(false)` when it does once
/// flipped (negative volume), `None` when it is no solid either way.
fn solid_orientation(vertices: &[[f64; 3]], tris: &[[usize; 3]]) -> Option<bool> {
    // The component alone, its vertices renumbered (the check's cost
    // follows the component, not the whole mesh).
    let mut local: HashMap<usize, usize> = HashMap::new();
    let mut points: Vec<[f64; 3]> = Vec::new();
    let compact: Vec<[usize; 3]> = tris
        .iter()
        .map(|t| {
            t.map(|v| {
                *local.entry(v).or_insert_with(|| {
                    points.push(vertices[v]);
                    points.len() - 1
                })
            })
        })
        .collect();
    let mesh = PolygonMesh::new(points, compact.iter().map(|t| t.to_vec()).collect());
    // The component is one shell (connected through shared vertices, as
    // the check counts shells), and the volume sign is the check's last
    // rule: a negative volume means every other rule held, and flipping
    // every triangle keeps them and negates the volume exactly, so the
    // flipped component is a solid without checking it again.
    match check_solid_mesh(&mesh) {
        Ok(_) => Some(true),
        Err(SolidError::NonPositiveVolume { negative: true, .. }) => Some(false),
        Err(_) => None,
    }
}
