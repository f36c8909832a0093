//! Triangle meshes as they come out of CAD and planning suites: open,
//! double-sided, non-manifold, several touching parts, cavities,
//! T-junctions, float32 coordinates. [`clean_soup`] cleans such a mesh
//! exactly and says which of its triangles *enclose* and which are only
//! *surface*.
//!
//! # What a mesh means (one rule: the winding number)
//!
//! A body given as triangles is the set of points on its triangles together
//! with the points of non-zero winding number of its *enclosing* part, the
//! largest part of it that is closed as a cycle. Contact with a body means
//! touching one of its triangles or lying where its winding number is not
//! zero. So touching solids (a shared corner, edge or face), nested shells,
//! a cavity (an inward shell inside an outward one: its winding number is
//! `1 − 1 = 0`, outside), T-junctions and shells that cross themselves all
//! mean what their winding number says, and non-manifold vertices and edges
//! are no reason to give up the inside.
//!
//! # The cleaning, in order (every decision exact)
//!
//! 1. Identical vertices (bit-equal coordinates, `-0.0` as `0.0`) are
//!    merged.
//! 2. Faces are taken as their fan triangles. A triangle repeating a vertex
//!    is dropped. A triangle whose distinct corners are exactly collinear
//!    (zero area) is dropped: once edges are split at the vertices on them
//!    (below), its edges balance each other, so for the balance it changes
//!    nothing (a T-junction's fill).
//! 3. Of triangles with the same corners one is kept, counted as often as
//!    its copies run its way less the other way: a copy the same way round
//!    (a duplicate, or a face two coincident solids share) adds one, a copy
//!    the other way (the back of a double-sided face, or a face two
//!    touching solids share) takes one away. A kept triangle whose count is
//!    zero is *paired*; a negative count turns it round. A polygon of more
//!    than three corners that repeats a kept polygon's cycle, either way
//!    round, is counted so whole (fanned from another corner its triangles
//!    would not repeat the first copy's).
//! 4. Each connected part (through shared vertices) whose kept triangles
//!    (once each, paired ones either way) use every edge exactly twice and
//!    can be oriented
//!    consistently is a closed shell: it encloses. Where it is not
//!    consistent as given (a few faces flipped, or a double-sided export
//!    whose first copies point either way), the fewer triangles of each
//!    edge-connected piece are flipped. A shell consistent as given keeps
//!    its orientation: an inward shell inside an outward one is a cavity.
//! 5. Every other part is taken as a chain of oriented triangles, each kept
//!    triangle as often as its count (paired ones not at all: a face and its
//!    back cancel in the winding number, as where two solids share a face)
//!    and its zero-area triangles in. An edge is
//!    *balanced* when, after splitting edges at the vertices lying exactly
//!    on them (exact collinearity and order), every piece is run as often in
//!    one direction as in the other. Triangles with an unbalanced edge are
//!    set aside one at a time until none is left: first any whose
//!    unbalanced piece no other kept triangle runs along (such a triangle
//!    is in no balanced part), then the one with the most unbalanced edges
//!    (the lowest index on a tie). What remains is a cycle and encloses
//!    (a closed box with an open fin glued to one edge: the box encloses,
//!    the fin is surface); what was set aside, and the paired triangles, are
//!    surface. The enclosing triangles are then split at the vertices lying
//!    on their edges (the same region exactly), so that the enclosing part
//!    is closed edge for edge and stays a cycle when its vertices are posed
//!    and rounded.
//! 6. Inward input as a whole (every shell inverted) is turned outward: when
//!    the exact signed volume of the enclosing triangles is negative, they
//!    are all flipped, and [`CleanSoup::inverted`] says so.
//!
//! The enclosing triangles are grouped into [`ComponentKind::Solid`]
//! components (connected through shared vertices; each is a cycle by itself,
//! so its winding number is zero outside its box), the surface triangles
//! into [`ComponentKind::Surface`] components. The counts say what was
//! changed.
//!
//! Cost: hashing for steps 1–3, a union–find for step 4; step 5 only for
//! parts that are not closed shells: their edges numbered by sorting, a
//! k-d tree over the vertices for the splitting (built only when an
//! unbalanced edge is met), the edges unbalanced from the start cut in one
//! pass in the tree's order (on several cores when there are many), and no
//! allocation per edge unless a vertex lies inside it. A soup of a million
//! loose triangles is cleaned in a few seconds (docs/BENCHMARKS.md).

use std::collections::BTreeSet;

/// The cleaning's hash maps: foldhash (seeded per process, as std's
/// maps are) hashes the integer keys several times faster than std's
/// SipHash, which took a third of a 46,000-triangle mesh's build.
type HashMap<K, V> = std::collections::HashMap<K, V, foldhash::fast::RandomState>;
type HashSet<K> = std::collections::HashSet<K, foldhash::fast::RandomState>;

use super::aabb::{Aabb, AabbTree};
use super::{collinear, shells_flat, volume_sign, SolidError};
use crate::kernel::predicates::Sign;
use crate::mesh::{canonical_cycle, PolygonMesh};

/// What a component of a cleaned mesh is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ComponentKind {
    /// Triangles that enclose (a cycle: every edge, split at the vertices
    /// on it, run as often each way): contact includes lying where their
    /// winding number is not zero.
    Solid,
    /// Triangles that do not enclose (open, set aside by the balance of
    /// edges, or one side of a double-sided face): contact means touching
    /// one of them.
    Surface,
}

/// One component of a cleaned mesh: triangles of one kind, connected
/// through shared vertices.
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
    /// The cleaned triangles (enclosing ones oriented so that their signed
    /// volume is positive) over the merged vertices.
    pub mesh: PolygonMesh,
    /// Vertices merged into an identical one.
    pub merged_vertices: usize,
    /// Triangles dropped as exactly collinear or repeating a vertex.
    pub dropped_zero_area: usize,
    /// Triangles dropped as a copy of a kept one with the same orientation.
    pub dropped_duplicates: usize,
    /// Triangles dropped as the back of a kept one (double-sided faces).
    pub dropped_back_to_back: usize,
    /// Triangles flipped: to orient a closed shell consistently, or all
    /// enclosing ones when the input was inward as a whole.
    pub flipped: usize,
    /// Whether the enclosing triangles were given inward as a whole
    /// (negative exact volume) and turned.
    pub inverted: bool,
    /// Triangles of parts that are not closed shells set aside as surface
    /// because of an unbalanced edge.
    pub set_aside: usize,
    /// Edges of enclosing triangles split at vertices lying exactly on them
    /// (T-junctions).
    pub split_edges: usize,
    /// Each triangle's weight in the winding number: how many copies of it
    /// enclose (one for a closed shell's triangle; a face two coincident
    /// solids share counts twice), `0` for a surface triangle.
    pub weights: Vec<u32>,
    /// The components, in the order of their first triangle.
    pub components: Vec<Component>,
}

impl CleanSoup {
    /// How many components enclose.
    pub fn solids(&self) -> usize {
        self.components
            .iter()
            .filter(|c| c.kind == ComponentKind::Solid)
            .count()
    }
}

/// Cleans a triangle (or polygon) mesh exactly and says which triangles
/// enclose (module docs).
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
    let mut first: HashMap<[u64; 3], usize> =
        HashMap::with_capacity_and_hasher(mesh.vertices.len(), Default::default());
    let mut vertices: Vec<[f64; 3]> = Vec::with_capacity(mesh.vertices.len());
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
    drop(first);
    let merged_vertices = mesh.vertices.len() - vertices.len();
    // 2. Fan triangles, degenerate ones set apart; 3. duplicates and backs.
    let fans: usize = mesh.faces.iter().map(|f| f.len().saturating_sub(2)).sum();
    let mut triangles: Vec<[usize; 3]> = Vec::with_capacity(fans);
    // How often each kept triangle is listed as kept, less the other way.
    let mut net: Vec<i32> = Vec::with_capacity(fans);
    let mut by_corners: HashMap<[usize; 3], usize> =
        HashMap::with_capacity_and_hasher(fans, Default::default());
    let (mut dropped_zero_area, mut dropped_duplicates, mut dropped_back_to_back) = (0, 0, 0);
    let mut polygons: HashMap<Vec<usize>, Vec<usize>> = HashMap::default();
    for (face, f) in mesh.faces.iter().enumerate() {
        if f.len() < 3 || f.iter().any(|&v| v >= remap.len()) {
            return Err(SolidError::BadFace { face });
        }
        let mut cycle_key = None;
        if f.len() > 3 {
            // A polygon repeated, or listed again the other way round (a
            // double-sided quad), is taken whole: fanned from another
            // corner its triangles would not repeat the first copy's.
            let cycle: Vec<usize> = f.iter().map(|&v| remap[v]).collect();
            let reversed: Vec<usize> = cycle.iter().rev().copied().collect();
            let (fwd, back) = (canonical_cycle(&cycle), canonical_cycle(&reversed));
            if let Some(kept) = polygons.get(&fwd) {
                for &t in kept {
                    net[t] += 1;
                }
                dropped_duplicates += f.len() - 2;
                continue;
            }
            if let Some(kept) = polygons.get(&back) {
                for &t in kept {
                    net[t] -= 1;
                }
                dropped_back_to_back += f.len() - 2;
                continue;
            }
            cycle_key = Some(fwd);
        }
        let mut produced = Vec::new();
        for w in f[1..].windows(2) {
            let t = [remap[f[0]], remap[w[0]], remap[w[1]]];
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                dropped_zero_area += 1;
                continue;
            }
            if collinear(vertices[t[0]], vertices[t[1]], vertices[t[2]]) {
                // Zero area: once edges are split at the vertices on them,
                // its edges balance each other, so it changes nothing.
                dropped_zero_area += 1;
                continue;
            }
            let mut key = t;
            key.sort_unstable();
            match by_corners.get(&key) {
                Some(&kept) if same_orientation(triangles[kept], t) => {
                    net[kept] += 1;
                    dropped_duplicates += 1;
                }
                Some(&kept) => {
                    net[kept] -= 1;
                    dropped_back_to_back += 1;
                }
                None => {
                    by_corners.insert(key, triangles.len());
                    produced.push(triangles.len());
                    triangles.push(t);
                    net.push(1);
                }
            }
        }
        if let Some(key) = cycle_key {
            polygons.insert(key, produced);
        }
    }
    drop((by_corners, polygons));
    // Each kept triangle as its copies net: turned to the way more copies
    // run; paired (a face and its back) when they cancel.
    for (t, n) in triangles.iter_mut().zip(&net) {
        *t = flipped_if(*t, *n < 0);
    }
    // 4. Closed shells; 5. the rest as a chain, each triangle as often as
    // its copies net.
    let mut flip = vec![false; triangles.len()];
    let mut weight = vec![0u32; triangles.len()];
    let mut chain: Vec<usize> = Vec::new();
    let (order, starts) = shells_flat(vertices.len(), &triangles);
    for w in starts.windows(2) {
        let part = &order[w[0]..w[1]];
        match shell_flips(&triangles, part) {
            Some(flips) => {
                for (&k, f) in part.iter().zip(flips) {
                    flip[k] = f;
                    weight[k] = 1;
                }
            }
            None => {
                for &k in part {
                    chain.extend(std::iter::repeat_n(k, net[k].unsigned_abs() as usize));
                }
            }
        }
    }
    let mut split_edges = 0;
    let mut pieces = HashMap::default();
    if !chain.is_empty() {
        let tris: Vec<[usize; 3]> = chain.iter().map(|&k| triangles[k]).collect();
        let mut c = Chain::new(&vertices, tris);
        c.peel();
        for (i, &k) in chain.iter().enumerate() {
            if c.alive[i] {
                weight[k] += 1;
            }
        }
        pieces = std::mem::take(&mut c.inner);
        // The edges split under enclosing triangles (T-junctions that
        // mattered).
        let mut split = HashSet::default();
        for &k in &chain {
            let t = triangles[k];
            for e in 0..3 {
                let key = edge_key(t[e], t[(e + 1) % 3]);
                if weight[k] > 0 && pieces.contains_key(&key) {
                    split.insert(key);
                }
            }
        }
        split_edges = split.len();
    }
    let set_aside = chain
        .iter()
        .enumerate()
        .filter(|&(i, &k)| (i == 0 || chain[i - 1] != k) && weight[k] == 0)
        .count();
    // The enclosing triangles of the chain split where a vertex lies on
    // their edges (the same region exactly), so that the enclosing part is
    // closed edge for edge and stays a cycle wherever its vertices are moved
    // (a posed body's rounded coordinates no longer lie on the edge).
    let (mut split, mut split_weight, mut split_flip) = (Vec::new(), Vec::new(), Vec::new());
    for (k, &t) in triangles.iter().enumerate() {
        let t = flipped_if(t, flip[k]);
        let start = split.len();
        if weight[k] > 0 && !pieces.is_empty() {
            split_at_vertices_on_edges(t, &pieces, &mut split);
        } else {
            split.push(t);
        }
        split_weight.extend(std::iter::repeat_n(weight[k], split.len() - start));
        split_flip.extend(std::iter::repeat_n(flip[k], split.len() - start));
    }
    let (mut triangles, weight, mut flip) = (split, split_weight, split_flip);
    let encloses: Vec<bool> = weight.iter().map(|&w| w > 0).collect();
    // 6. Inward as a whole (each triangle as often as its weight).
    let enclosing: Vec<[usize; 3]> = (0..triangles.len())
        .flat_map(|k| std::iter::repeat_n(triangles[k], weight[k] as usize))
        .collect();
    let inverted = volume_sign(&vertices, &enclosing) == Sign::Negative;
    if inverted {
        for k in 0..triangles.len() {
            if encloses[k] {
                triangles[k] = flipped_if(triangles[k], true);
                flip[k] = !flip[k];
            }
        }
    }
    let flipped = flip.iter().filter(|&&f| f).count();
    // Components: enclosing triangles grouped through shared vertices (each
    // group is then closed edge for edge: a cycle by itself), surface
    // triangles likewise.
    let mut solid_sets = Dsu::new(vertices.len());
    let mut surface_sets = Dsu::new(vertices.len());
    for (k, t) in triangles.iter().enumerate() {
        let sets = if encloses[k] {
            &mut solid_sets
        } else {
            &mut surface_sets
        };
        sets.union(t[0], t[1]);
        sets.union(t[0], t[2]);
    }
    let mut index: HashMap<(bool, usize), usize> = HashMap::default();
    let mut components: Vec<Component> = Vec::new();
    for (k, t) in triangles.iter().enumerate() {
        let key = if encloses[k] {
            (true, solid_sets.find(t[0]))
        } else {
            (false, surface_sets.find(t[0]))
        };
        let c = *index.entry(key).or_insert_with(|| {
            components.push(Component {
                triangles: Vec::new(),
                kind: if key.0 {
                    ComponentKind::Solid
                } else {
                    ComponentKind::Surface
                },
            });
            components.len() - 1
        });
        components[c].triangles.push(k);
    }
    Ok(CleanSoup {
        mesh: PolygonMesh::new(vertices, triangles.iter().map(|t| t.to_vec()).collect()),
        merged_vertices,
        dropped_zero_area,
        dropped_duplicates,
        dropped_back_to_back,
        flipped,
        inverted,
        set_aside,
        split_edges,
        weights: weight,
        components,
    })
}

/// Triangle `t` split at the vertices lying on its edges (`pieces`: each
/// edge with vertices inside it, its vertices in order from its smaller
/// vertex, both ends included), into `out`: the
/// same region, each part with `t`'s orientation and nonzero area (a fan
/// from the corner opposite a cut edge, then the parts' own cut edges).
fn split_at_vertices_on_edges(
    t: [usize; 3],
    pieces: &HashMap<Edge, Vec<usize>>,
    out: &mut Vec<[usize; 3]>,
) {
    for e in 0..3 {
        let (u, v, x) = (t[e], t[(e + 1) % 3], t[(e + 2) % 3]);
        let Some(cut) = pieces.get(&edge_key(u, v)) else {
            continue;
        };
        let along: Vec<usize> = if u < v {
            cut.clone()
        } else {
            cut.iter().rev().copied().collect()
        };
        for w in along.windows(2) {
            split_at_vertices_on_edges([w[0], w[1], x], pieces, out);
        }
        return;
    }
    out.push(t);
}

/// Disjoint sets over `0..n` (path halving, the smaller root kept).
struct Dsu(Vec<usize>);

impl Dsu {
    fn new(n: usize) -> Dsu {
        Dsu((0..n).collect())
    }

    fn find(&mut self, mut x: usize) -> usize {
        while self.0[x] != x {
            self.0[x] = self.0[self.0[x]];
            x = self.0[x];
        }
        x
    }

    fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            self.0[a.max(b)] = a.min(b);
        }
    }
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

/// Per triangle of the part, whether to flip it so that every edge is run
/// once each way, when the part is a closed shell: every edge in exactly
/// two of its triangles and no contradiction in propagating the
/// orientation across them (no Möbius band); `None` otherwise. Each
/// edge-connected piece flips the fewer of its triangles (none when it is
/// consistent as given).
fn shell_flips(triangles: &[[usize; 3]], part: &[usize]) -> Option<Vec<bool>> {
    // Distinct triangles running every edge twice are at least four (two
    // would have the same corners, kept once; three edges twice over make
    // an even count): a loose triangle of a soup is no shell.
    if part.len() < 4 {
        return None;
    }
    // Undirected edge → (position in part, runs from the smaller vertex).
    let mut edges: HashMap<(usize, usize), Vec<(usize, bool)>> = HashMap::default();
    for (i, &k) in part.iter().enumerate() {
        let t = triangles[k];
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            let users = edges.entry((a.min(b), a.max(b))).or_default();
            if users.len() == 2 {
                return None;
            }
            users.push((i, a < b));
        }
    }
    if edges.values().any(|users| users.len() != 2) {
        return None;
    }
    let mut flip: Vec<Option<bool>> = vec![None; part.len()];
    let mut out = vec![false; part.len()];
    for seed in 0..part.len() {
        if flip[seed].is_some() {
            continue;
        }
        flip[seed] = Some(false);
        let mut piece = vec![seed];
        let mut stack = vec![seed];
        while let Some(i) = stack.pop() {
            let t = triangles[part[i]];
            let fi = flip[i].expect("set before pushed");
            for e in 0..3 {
                let (a, b) = (t[e], t[(e + 1) % 3]);
                let users = &edges[&(a.min(b), a.max(b))];
                let (j, j_forward) = if users[0].0 == i { users[1] } else { users[0] };
                // Consistent: the two run the edge in opposite directions
                // after their flips.
                let i_forward = (a < b) != fi;
                let want = j_forward == i_forward; // flip j iff it runs the same way
                match flip[j] {
                    None => {
                        flip[j] = Some(want);
                        piece.push(j);
                        stack.push(j);
                    }
                    Some(f) if f != want => return None,
                    Some(_) => {}
                }
            }
        }
        // The fewer triangles of the piece are the ones flipped.
        let flips = piece.iter().filter(|&&i| flip[i] == Some(true)).count();
        let invert = 2 * flips > piece.len();
        for &i in &piece {
            out[i] = flip[i] == Some(true) && !invert || flip[i] == Some(false) && invert;
        }
    }
    Some(out)
}

/// An undirected edge (or piece of one): its smaller vertex first.
type Edge = (usize, usize);

/// An undirected edge's key: its smaller vertex first.
fn edge_key(a: usize, b: usize) -> Edge {
    (a.min(b), a.max(b))
}

/// The oriented triangles of the parts that are not closed shells, and the
/// balance of their edges split at the vertices lying on them (module docs,
/// step 5).
///
/// An edge's *net* is how often its alive triangles run it from its smaller
/// vertex to its larger, less the other way. An edge whose net is not zero
/// (now or once) is cut into *pieces* at the vertices lying exactly inside
/// it; a piece's net sums the nets of the edges it lies in. Edges whose net
/// was always zero add nothing to any piece, so they need no cutting: the
/// chain is balanced exactly when every piece's net is zero.
///
/// Layout: the edges are numbered in the order of their keys, with their
/// users, nets and pieces in arrays. Piece `k < edges.len()` is the piece
/// with edge `k`'s key, which is the only piece of a cut edge with no vertex
/// inside it (the common case: no allocation per edge); pieces of cut edges
/// with vertices inside get an edge's number when they have its key, else
/// one past the edges. Each piece lists the cut edges it lies in (a linked
/// list through `cover_next`).
struct Chain<'a> {
    vertices: &'a [[f64; 3]],
    tris: Vec<[usize; 3]>,
    alive: Vec<bool>,
    /// The edges' keys, ascending.
    edges: Vec<Edge>,
    /// Triangle `i`'s edges: `tri_edges[i][e]` runs `tris[i][e]` to
    /// `tris[i][e + 1]`.
    tri_edges: Vec<[u32; 3]>,
    /// Edge `k`'s triangles (alive or not), ascending:
    /// `users[user_start[k]..user_start[k + 1]]`.
    user_start: Vec<u32>,
    users: Vec<u32>,
    /// Net over each edge's alive triangles.
    net: Vec<i32>,
    /// Whether each edge was cut.
    cut: Vec<bool>,
    /// Each edge's pieces in `piece_list` when it has vertices inside
    /// (empty otherwise: its one piece is its own number).
    span: Vec<(u32, u32)>,
    /// (piece, +1 when the edge runs it from its smaller vertex, else -1).
    piece_list: Vec<(u32, i32)>,
    /// The vertices of each cut edge with vertices inside it, from its
    /// smaller vertex to its larger, both included.
    inner: HashMap<Edge, Vec<usize>>,
    /// Numbers of pieces whose key is no edge's.
    extra_pieces: HashMap<Edge, u32>,
    /// Each piece's net.
    piece_net: Vec<i32>,
    /// Each piece's first cover (`NONE` without), and each cover's edge and
    /// next cover of the same piece.
    cover_head: Vec<u32>,
    cover_edge: Vec<u32>,
    cover_next: Vec<u32>,
    /// Point boxes of the vertices (built when first needed).
    points: Option<AabbTree>,
}

/// No cover (the end of a piece's list).
const NONE: u32 = u32::MAX;

/// From this many edges unbalanced from the start on, they are cut on
/// several cores (below, one core is cheaper).
const PARALLEL_CUTS: usize = 4096;

impl<'a> Chain<'a> {
    fn new(vertices: &'a [[f64; 3]], tris: Vec<[usize; 3]>) -> Chain<'a> {
        // (key, triangle, which edge), sorted: the edges in key order and
        // each edge's triangles ascending.
        let mut runs: Vec<(Edge, u32, u8)> = Vec::with_capacity(3 * tris.len());
        for (i, t) in tris.iter().enumerate() {
            for e in 0..3 {
                runs.push((edge_key(t[e], t[(e + 1) % 3]), i as u32, e as u8));
            }
        }
        runs.sort_unstable();
        let mut edges: Vec<Edge> = Vec::new();
        let mut user_start: Vec<u32> = Vec::new();
        let mut users: Vec<u32> = Vec::with_capacity(runs.len());
        let mut initial: Vec<i32> = Vec::new();
        let mut tri_edges = vec![[0u32; 3]; tris.len()];
        for &(key, i, e) in &runs {
            if edges.last() != Some(&key) {
                edges.push(key);
                user_start.push(users.len() as u32);
                initial.push(0);
            }
            let k = edges.len() - 1;
            users.push(i);
            tri_edges[i as usize][e as usize] = k as u32;
            let t = tris[i as usize];
            initial[k] += if t[e as usize] < t[(e as usize + 1) % 3] {
                1
            } else {
                -1
            };
        }
        user_start.push(users.len() as u32);
        drop(runs);
        let n = edges.len();
        let mut chain = Chain {
            vertices,
            alive: vec![true; tris.len()],
            tris,
            edges,
            tri_edges,
            user_start,
            users,
            net: vec![0; n],
            cut: vec![false; n],
            span: vec![(0, 0); n],
            piece_list: Vec::new(),
            inner: HashMap::default(),
            extra_pieces: HashMap::default(),
            piece_net: vec![0; n],
            cover_head: vec![NONE; n],
            cover_edge: Vec::new(),
            cover_next: Vec::new(),
            points: None,
        };
        // The edges unbalanced from the start are cut at once: asked in the
        // order of their smaller vertex in the point tree (nearby queries
        // one after another walk the same nodes, which stay in cache), on
        // several cores when there are many, and recorded in key order.
        let unbalanced: Vec<u32> = (0..n as u32)
            .filter(|&k| initial[k as usize] != 0)
            .collect();
        if !unbalanced.is_empty() {
            chain.points();
            let points = chain.points.as_ref().expect("built just above");
            let mut rank = vec![0u32; vertices.len()];
            for (r, &v) in points.items().iter().enumerate() {
                rank[v as usize] = r as u32;
            }
            let mut order: Vec<(u32, u32)> = (0..unbalanced.len() as u32)
                .map(|j| (rank[chain.edges[unbalanced[j as usize] as usize].0], j))
                .collect();
            order.sort_unstable();
            // Only the edges with vertices inside are kept (few).
            let cut = |&(_, j): &(u32, u32)| {
                let edge = chain.edges[unbalanced[j as usize] as usize];
                let inside = vertices_inside(vertices, points, edge);
                (!inside.is_empty()).then_some((j, inside))
            };
            let mut found: Vec<(u32, Vec<usize>)> = if unbalanced.len() >= PARALLEL_CUTS {
                use rayon::prelude::*;
                order.par_iter().filter_map(cut).collect()
            } else {
                order.iter().filter_map(cut).collect()
            };
            drop(order);
            found.sort_unstable_by_key(|f| f.0);
            let mut found = found.into_iter().peekable();
            for (j, &k) in unbalanced.iter().enumerate() {
                let inside = found
                    .next_if(|f| f.0 as usize == j)
                    .map_or_else(Vec::new, |f| f.1);
                chain.record_cut(k, inside);
                chain.set_net(k, initial[k as usize]);
            }
        }
        chain
    }

    /// The point tree over the vertices (built when first needed).
    fn points(&mut self) -> &AabbTree {
        let vertices = self.vertices;
        self.points
            .get_or_insert_with(|| AabbTree::over_points(vertices))
    }

    /// How many pieces cut edge `k` has.
    fn piece_count(&self, k: u32) -> u32 {
        let (s, e) = self.span[k as usize];
        if s == e {
            1
        } else {
            e - s
        }
    }

    /// Cut edge `k`'s `j`-th piece and whether the edge runs it from its
    /// smaller vertex (`1`) or not (`-1`).
    fn piece(&self, k: u32, j: u32) -> (u32, i32) {
        let (s, e) = self.span[k as usize];
        if s == e {
            (k, 1)
        } else {
            self.piece_list[(s + j) as usize]
        }
    }

    /// The number of the piece with `key`, made when it is new.
    fn piece_with_key(&mut self, key: Edge) -> u32 {
        if let Ok(k) = self.edges.binary_search(&key) {
            return k as u32;
        }
        let next = self.piece_net.len() as u32;
        let id = *self.extra_pieces.entry(key).or_insert(next);
        if id == next {
            self.piece_net.push(0);
            self.cover_head.push(NONE);
        }
        id
    }

    /// Records edge `k` as cut at the vertices `inside` it (in order from
    /// its smaller vertex), each of its pieces covered by it.
    fn record_cut(&mut self, k: u32, inside: Vec<usize>) {
        self.cut[k as usize] = true;
        if !inside.is_empty() {
            let (a, b) = self.edges[k as usize];
            let mut all = Vec::with_capacity(inside.len() + 2);
            all.push(a);
            all.extend(inside);
            all.push(b);
            let start = self.piece_list.len() as u32;
            for w in all.windows(2) {
                let piece = self.piece_with_key(edge_key(w[0], w[1]));
                self.piece_list
                    .push((piece, if w[0] < w[1] { 1 } else { -1 }));
            }
            self.span[k as usize] = (start, self.piece_list.len() as u32);
            self.inner.insert((a, b), all);
        }
        for j in 0..self.piece_count(k) {
            let (p, _) = self.piece(k, j);
            self.cover_edge.push(k);
            self.cover_next.push(self.cover_head[p as usize]);
            self.cover_head[p as usize] = self.cover_edge.len() as u32 - 1;
        }
    }

    /// Sets edge `k`'s net, cutting it first when it was never cut.
    fn set_net(&mut self, k: u32, new: i32) {
        let old = self.net[k as usize];
        if old == new {
            return;
        }
        self.net[k as usize] = new;
        if !self.cut[k as usize] {
            let edge = self.edges[k as usize];
            let inside = vertices_inside(self.vertices, self.points(), edge);
            self.record_cut(k, inside);
        }
        for j in 0..self.piece_count(k) {
            let (p, along) = self.piece(k, j);
            self.piece_net[p as usize] += (new - old) * along;
        }
    }

    /// Edge `k`'s alive triangles.
    fn alive_users(&self, k: u32) -> impl Iterator<Item = u32> + '_ {
        let (s, e) = (self.user_start[k as usize], self.user_start[k as usize + 1]);
        self.users[s as usize..e as usize]
            .iter()
            .copied()
            .filter(|&u| self.alive[u as usize])
    }

    /// The cut edges piece `p` lies in.
    fn covers(&self, p: u32) -> impl Iterator<Item = u32> + '_ {
        let mut c = self.cover_head[p as usize];
        std::iter::from_fn(move || {
            (c != NONE).then(|| {
                let k = self.cover_edge[c as usize];
                c = self.cover_next[c as usize];
                k
            })
        })
    }

    /// How many of a triangle's edges have a piece whose net is not zero,
    /// and whether one of those pieces is run by no other alive triangle.
    fn state(&self, i: usize) -> (usize, bool) {
        let (mut unbalanced, mut alone) = (0, false);
        for k in self.tri_edges[i] {
            if !self.cut[k as usize] {
                continue;
            }
            let mut edge_unbalanced = false;
            for j in 0..self.piece_count(k) {
                let (p, _) = self.piece(k, j);
                if self.piece_net[p as usize] == 0 {
                    continue;
                }
                edge_unbalanced = true;
                let runs: usize = self.covers(p).map(|c| self.alive_users(c).count()).sum();
                alone |= runs == 1;
            }
            unbalanced += usize::from(edge_unbalanced);
        }
        (unbalanced, alone)
    }

    /// Sets triangle `i` aside; the alive triangles whose balance it may
    /// have changed go onto `touched`.
    fn set_aside(&mut self, i: usize, touched: &mut Vec<u32>) {
        self.alive[i] = false;
        let t = self.tris[i];
        for e in 0..3 {
            let k = self.tri_edges[i][e];
            let run = if t[e] < t[(e + 1) % 3] { 1 } else { -1 };
            self.set_net(k, self.net[k as usize] - run);
            for j in 0..self.piece_count(k) {
                let (p, _) = self.piece(k, j);
                for c in self.covers(p) {
                    touched.extend(self.alive_users(c));
                }
            }
        }
    }

    /// Sets triangles aside until every piece is balanced (module docs).
    fn peel(&mut self) {
        let mut stack: Vec<u32> = (0..self.tris.len() as u32).rev().collect();
        let mut pending: BTreeSet<u32> = BTreeSet::new();
        loop {
            while let Some(i) = stack.pop() {
                let i = i as usize;
                if !self.alive[i] {
                    continue;
                }
                let (unbalanced, alone) = self.state(i);
                if unbalanced == 0 {
                    pending.remove(&(i as u32));
                } else if alone {
                    pending.remove(&(i as u32));
                    self.set_aside(i, &mut stack);
                } else {
                    pending.insert(i as u32);
                }
            }
            let mut best: Option<(usize, u32)> = None;
            pending.retain(|&i| {
                if !self.alive[i as usize] {
                    return false;
                }
                let (unbalanced, _) = self.state(i as usize);
                if unbalanced > best.map_or(0, |b| b.0) {
                    best = Some((unbalanced, i));
                }
                unbalanced > 0
            });
            let Some((_, i)) = best else {
                break;
            };
            pending.remove(&i);
            self.set_aside(i as usize, &mut stack);
        }
    }
}

/// The vertices lying exactly inside edge `(a, b)` (exact collinearity,
/// then strictly between its ends along a coordinate in which they
/// differ), in order from `a`.
fn vertices_inside(vertices: &[[f64; 3]], points: &AabbTree, (a, b): Edge) -> Vec<usize> {
    let (pa, pb) = (vertices[a], vertices[b]);
    let k = (0..3).find(|&k| pa[k] != pb[k]).unwrap_or(0);
    let (lo, hi) = (pa[k].min(pb[k]), pa[k].max(pb[k]));
    let mut inside = Vec::new();
    points.for_each_meeting(&Aabb::of([pa, pb]), |v| {
        let p = vertices[v];
        if v != a && v != b && lo < p[k] && p[k] < hi && collinear(pa, p, pb) {
            inside.push(v);
        }
    });
    let rising = pa[k] < pb[k];
    inside.sort_by(|&u, &v| {
        let o = vertices[u][k].total_cmp(&vertices[v][k]);
        if rising {
            o
        } else {
            o.reverse()
        }
    });
    inside
}
