//! The exact check of a mesh given as a solid: [`check_solid_mesh`].
//!
//! A non-convex body given as one polygon mesh (to a non-convex sum, a
//! decomposition, the CLI's mesh loaders, Python's `nonconvex` functions)
//! is a *solid* when it is the union of its shells (connected components),
//! each of which bounds a region by itself. Every rule is decided without
//! tolerance, so a mesh is accepted or refused the same way at any
//! translation and scale (as long as its coordinates span at most
//! `MAX_COORD_SPAN` = 960 bits, else [`SolidError::OutOfRange`]).
//!
//! [`SolidError`] is the layer's one error: the check of every merged
//! mesh, [`closed::check_closed_mesh`] (rules 1 and 5 below on the faces'
//! fans, and a positive total volume), and the cleaning of triangle soups
//! ([`soup::clean_soup`]) report through it too. [`triangles_meet`] is the
//! exact triangle–triangle test (the scene checker's).
//!
//! # The rules, in the order they are checked
//!
//! 1. At least one face; every vertex finite; every face at least three
//!    distinct, in-range corners ([`SolidError::BadFace`]).
//! 2. No face listed twice or back to back: no two faces with the same set
//!    of corners ([`SolidError::DuplicateFace`]). (Two back-to-back
//!    triangles form a closed, oriented 2-manifold of no volume.)
//! 3. Every triangle of every face's fan (`f₀ f_k f_{k+1}`) has non-zero
//!    area: its corners are not collinear, decided by the exact `orient2d`
//!    of its three coordinate projections ([`SolidError::ZeroAreaTriangle`]).
//! 4. Every polygon face is exactly planar: `orient3d(f₀, f₁, f₂, f_k) = 0`
//!    for every corner ([`SolidError::NonPlanarFace`]). A non-planar
//!    polygon has no one surface (each triangulation bounds another solid),
//!    so it is refused rather than triangulated by a guess; triangulate it
//!    first. Faces are then taken as their fans (for the crossing test
//!    below, a non-convex planar polygon whose fan folds is refused too).
//! 5. Closed, consistently oriented, edge- and vertex-manifold (the
//!    directed-edge index of `polytope::topology`, shared with the convex
//!    loaders): every directed edge `a → b` in exactly one face and its
//!    reverse in exactly one other ([`SolidError::OpenEdge`],
//!    [`SolidError::InconsistentOrientation`],
//!    [`SolidError::NonManifoldEdge`]), and the faces about each vertex one
//!    fan ([`SolidError::NonManifoldVertex`]). Any genus is allowed.
//! 6. The shells are the connected components of what is left (through
//!    shared vertices; with rule 5, through shared edges). Within each
//!    shell no two fan triangles meet except along what they share: a
//!    common vertex, or a common edge that is an edge of both their faces
//!    (or a diagonal of the one face they both come from) with the two
//!    triangles not folded onto each other ([`SolidError::TrianglesCross`]).
//!    Candidate pairs come from a bounding-box tree whose boxes are the
//!    exact minimum and maximum of the corners, so no pair that touches is
//!    missed; each pair is decided by exact `orient3d` and `orient2d`
//!    tests (see `intersect`). Shells are not tested against each other:
//!    overlapping shells are a union.
//! 7. Each shell encloses a positive volume: the exact sign of
//!    `Σ det[a − o, b − o, c − o]` over its fan triangles `(a, b, c)`, `o`
//!    one of its vertices (six times the signed volume), summed in exact
//!    dyadic arithmetic ([`SolidError::NonPositiveVolume`]: an inward
//!    shell, for instance a cavity).
//!
//! # Why a shell that passes is a solid
//!
//! By rules 5 and 6 a shell is a closed, oriented 2-manifold embedded in
//! space (its triangles meet only as a triangulated surface does), so by
//! the Jordan–Brouwer separation theorem it bounds one region, and its
//! winding number is `0` outside and the same `±1` everywhere inside; the
//! sign is that of the enclosed signed volume, so rule 7 makes it `+1`. So
//! every shell's winding number is 0 or 1, the shell is that region's
//! boundary, and the body is the union of the regions. A cavity (an
//! inward shell inside another) would need tests between shells; it is
//! refused by rule 7.
//!
//! Cost: `O(H log H)` for the topology and the tree (`H` corners), plus
//! one exact test per pair of triangles whose boxes meet (about a dozen
//! per triangle on a reasonable mesh), in parallel over each shell's
//! triangles.
//!
//! ```
//! use dymsum::solid::{check_solid_mesh, SolidError};
//! use dymsum::PolygonMesh;
//! let v = vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
//! let tetra = vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]];
//! let info = check_solid_mesh(&PolygonMesh::new(v.clone(), tetra.clone()))?;
//! assert_eq!(info.shells, vec![vec![0, 1, 2, 3]]);
//! // Inward: every face reversed.
//! let inward: Vec<Vec<usize>> = tetra.iter().map(|f| f.iter().rev().copied().collect()).collect();
//! let err = check_solid_mesh(&PolygonMesh::new(v.clone(), inward)).unwrap_err();
//! assert!(matches!(err, SolidError::NonPositiveVolume { shell: 0, .. }));
//! // Two triangles back to back: closed and oriented, but no solid.
//! let sheet = PolygonMesh::new(v, vec![vec![0, 1, 2], vec![0, 2, 1]]);
//! assert_eq!(check_solid_mesh(&sheet).unwrap_err().to_string(),
//!     "faces 0 and 1 have the same corners (a face listed twice, or two faces back to back)");
//! # Ok::<(), SolidError>(())
//! ```

pub(crate) mod aabb;
pub mod closed;
mod error;
pub(crate) mod intersect;
pub(crate) mod obb;
pub mod soup;

pub use error::SolidError;
pub use intersect::triangles_meet;

use crate::kernel::exact::{self, Dyadic};
use crate::kernel::predicates::{orient, Sign};
use crate::mesh::PolygonMesh;
use crate::polytope::topology::{DirectedEdges, TopologyDefect, Unused};
use aabb::{Aabb, AabbTree};
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;

/// What [`check_solid_mesh`] found in a solid.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SolidInfo {
    /// The faces of each shell (connected component), ascending; shells in
    /// the order of their first face.
    pub shells: Vec<Vec<usize>>,
    /// Triangles of the faces' fans.
    pub triangles: usize,
}

/// One fan triangle: its corners, its face, and which of its edges
/// (`v0v1`, `v1v2`, `v2v0`) are edges of the face (not diagonals).
#[derive(Clone, Copy)]
struct Tri {
    v: [usize; 3],
    face: usize,
    real: [bool; 3],
}

impl Tri {
    /// Whether the edge `{a, b}` (two of its corners) is an edge of its face.
    fn is_face_edge(&self, a: usize, b: usize) -> bool {
        (0..3).any(|k| {
            let (x, y) = (self.v[k], self.v[(k + 1) % 3]);
            self.real[k] && ((x, y) == (a, b) || (x, y) == (b, a))
        })
    }
}

/// Checks exactly that `mesh` is a solid: each shell closed, consistently
/// oriented, manifold, not crossing itself and of positive volume, with no
/// face listed twice or back to back and no zero-area or non-planar face
/// (the rules and why they are exact: the module docs). Returns the shells.
///
/// # Errors
/// The first rule broken, as a [`SolidError`] naming the faces, edge or
/// vertex (in the caller's numbering).
pub fn check_solid_mesh(mesh: &PolygonMesh) -> Result<SolidInfo, SolidError> {
    let (vertices, faces) = (&mesh.vertices, &mesh.faces);
    let n = vertices.len();
    check_elements(mesh)?;
    check_duplicates(faces)?;
    let p = |i: usize| DVec3::from(vertices[i]);
    let mut tris = Vec::with_capacity(mesh.triangle_count());
    for (face, f) in faces.iter().enumerate() {
        let k = f.len();
        for i in 1..k - 1 {
            let v = [f[0], f[i], f[i + 1]];
            if collinear(vertices[v[0]], vertices[v[1]], vertices[v[2]]) {
                return Err(SolidError::ZeroAreaTriangle { face, corners: v });
            }
            tris.push(Tri {
                v,
                face,
                real: [i == 1, true, i + 1 == k - 1],
            });
        }
        if let Some(&vertex) = f[3..]
            .iter()
            .find(|&&x| orient(p(f[0]), p(f[1]), p(f[2]), p(x)) != Sign::Zero)
        {
            return Err(SolidError::NonPlanarFace { face, vertex });
        }
    }
    check_topology(&DirectedEdges::new(n, faces), |face| face)?;
    let shells = shells(n, faces);
    // The fan triangles of each face are consecutive in `tris`.
    let mut first_tri = Vec::with_capacity(faces.len() + 1);
    first_tri.push(0);
    for f in faces {
        first_tri.push(first_tri.last().copied().unwrap_or(0) + f.len() - 2);
    }
    for (s, shell) in shells.iter().enumerate() {
        let shell_tris: Vec<Tri> = shell
            .iter()
            .flat_map(|&f| tris[first_tri[f]..first_tri[f + 1]].iter().copied())
            .collect();
        if let Some((a, b)) = first_crossing(vertices, &shell_tris) {
            return Err(SolidError::TrianglesCross { a, b });
        }
        let corners: Vec<[usize; 3]> = shell_tris.iter().map(|t| t.v).collect();
        let sign = volume_sign(vertices, &corners);
        if sign != Sign::Positive {
            return Err(SolidError::NonPositiveVolume {
                shell: s,
                face: shell[0],
                negative: sign == Sign::Negative,
            });
        }
    }
    Ok(SolidInfo {
        shells,
        triangles: tris.len(),
    })
}

/// Rule 1 (shared with [`closed::check_closed_mesh`]): at least one face,
/// every vertex finite, every face well formed ([`malformed`]), and the
/// coordinates of the faces within the exact arithmetic's span.
fn check_elements(mesh: &PolygonMesh) -> Result<(), SolidError> {
    let (vertices, faces) = (&mesh.vertices, &mesh.faces);
    if faces.is_empty() {
        return Err(SolidError::Empty);
    }
    if let Some(vertex) = vertices
        .iter()
        .position(|p| !p.iter().all(|x| x.is_finite()))
    {
        return Err(SolidError::NonFinite { vertex });
    }
    if let Some(face) = faces.iter().position(|f| malformed(f, vertices.len())) {
        return Err(SolidError::BadFace { face });
    }
    let coords = faces
        .iter()
        .flatten()
        .flat_map(|&i| vertices[i].into_iter());
    exact::coordinate_span_ok(coords).map_err(|(top, low)| SolidError::OutOfRange { top, low })
}

/// A face of fewer than three corners, a corner not below `n`, or a
/// repeated corner ([`SolidError::BadFace`]).
pub(crate) fn malformed(f: &[usize], n: usize) -> bool {
    f.len() < 3
        || f.iter().any(|&i| i >= n)
        || f.iter().enumerate().any(|(k, x)| f[k + 1..].contains(x))
}

/// Exactly: are three points collinear (every coordinate projection flat)?
pub(crate) fn collinear(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> bool {
    intersect::projection(&[a, b, c].map(DVec3::from)).is_none()
}

/// Rule 2: no two faces with the same corner set.
fn check_duplicates(faces: &[Vec<usize>]) -> Result<(), SolidError> {
    let mut seen: HashMap<Vec<usize>, usize> = HashMap::with_capacity(faces.len());
    for (b, f) in faces.iter().enumerate() {
        let mut key = f.clone();
        key.sort_unstable();
        if let Some(&a) = seen.get(&key) {
            return Err(SolidError::DuplicateFace { a, b });
        }
        seen.insert(key, b);
    }
    Ok(())
}

/// Rule 5 (shared with [`closed::check_closed_mesh`]), by
/// `polytope::topology`'s directed-edge index `d` of the faces (or of
/// their fan triangles, numbered back to faces by `face_of`).
fn check_topology(d: &DirectedEdges, face_of: impl Fn(usize) -> usize) -> Result<(), SolidError> {
    match d.check_manifold(Unused::Skip) {
        Ok(_) => Ok(()),
        Err(TopologyDefect::EdgeUsedTwice(from, to)) => {
            let same = d.faces_of(from, to);
            let back = d.faces_of(to, from);
            if same.len() == 2 && back.is_empty() {
                Err(SolidError::InconsistentOrientation {
                    from,
                    to,
                    faces: [face_of(same[0]), face_of(same[1])],
                })
            } else {
                Err(SolidError::NonManifoldEdge {
                    from,
                    to,
                    count: same.len() + back.len(),
                    face: face_of(same[0]),
                })
            }
        }
        Err(TopologyDefect::OpenEdge(from, to)) => Err(SolidError::OpenEdge {
            from,
            to,
            face: face_of(d.face_of(from, to).unwrap_or(0)),
        }),
        Err(TopologyDefect::PinchedVertex(vertex)) => Err(SolidError::NonManifoldVertex { vertex }),
        // Not reported by `check_manifold` with `Unused::Skip`.
        Err(TopologyDefect::UnusedVertex(_) | TopologyDefect::Euler(_)) => Ok(()),
    }
}

/// The faces of each connected component (through shared vertices),
/// ascending, in the order of their first face; every index below `n`.
/// The one copy (also `nonconvex::check`'s shell count).
pub(crate) fn shells<F: AsRef<[usize]>>(n: usize, faces: &[F]) -> Vec<Vec<usize>> {
    let (order, starts) = shells_flat(n, faces);
    starts
        .windows(2)
        .map(|w| order[w[0]..w[1]].to_vec())
        .collect()
}

/// [`shells`] without a vector per component (a soup of a million loose
/// triangles has a million): the faces of component `k` are
/// `order[starts[k]..starts[k + 1]]`.
pub(crate) fn shells_flat<F: AsRef<[usize]>>(n: usize, faces: &[F]) -> (Vec<usize>, Vec<usize>) {
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for f in faces {
        let f = f.as_ref();
        for &v in &f[1..] {
            let (a, b) = (find(&mut parent, f[0]), find(&mut parent, v));
            if a != b {
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    // Each face's component, numbered in the order of first faces; then
    // the faces counted into place.
    const NONE: usize = usize::MAX;
    let mut number = vec![NONE; n];
    let mut of_face = Vec::with_capacity(faces.len());
    let mut sizes: Vec<usize> = Vec::new();
    for f in faces {
        let root = find(&mut parent, f.as_ref()[0]);
        if number[root] == NONE {
            number[root] = sizes.len();
            sizes.push(0);
        }
        of_face.push(number[root]);
        sizes[number[root]] += 1;
    }
    let mut starts = Vec::with_capacity(sizes.len() + 1);
    starts.push(0);
    for size in &sizes {
        starts.push(starts.last().copied().unwrap_or(0) + size);
    }
    let mut next = starts.clone();
    let mut order = vec![0; faces.len()];
    for (face, &k) in of_face.iter().enumerate() {
        order[next[k]] = face;
        next[k] += 1;
    }
    (order, starts)
}

/// Rule 6 in one shell: the faces of the first pair of triangles (in
/// order) that meet other than along what they share.
fn first_crossing(vertices: &[[f64; 3]], tris: &[Tri]) -> Option<(usize, usize)> {
    let boxes: Vec<Aabb> = tris
        .iter()
        .map(|t| Aabb::of(t.v.map(|i| vertices[i])))
        .collect();
    let tree = AabbTree::new(&boxes);
    (0..tris.len()).into_par_iter().find_map_first(|i| {
        let mut near = Vec::new();
        tree.for_each_meeting(&boxes[i], |j| {
            if j > i {
                near.push(j);
            }
        });
        near.sort_unstable();
        near.into_iter()
            .find(|&j| pair_meets(vertices, &tris[i], &tris[j]))
            .map(|j| {
                let (a, b) = (tris[i].face, tris[j].face);
                (a.min(b), a.max(b))
            })
    })
}

/// Whether two triangles of one shell meet other than along what they
/// share (see `intersect`).
fn pair_meets(vertices: &[[f64; 3]], t: &Tri, u: &Tri) -> bool {
    let p = |i: usize| DVec3::from(vertices[i]);
    let (pt, pu) = (t.v.map(p), u.v.map(p));
    let shared: Vec<(usize, usize)> = (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .filter(|&(i, j)| t.v[i] == u.v[j])
        .collect();
    match shared[..] {
        [] => intersect::disjoint_triangles_meet(&pt, &pu),
        [(i, j)] => intersect::vertex_sharing_triangles_meet(
            &pt,
            [pt[(i + 1) % 3], pt[(i + 2) % 3]],
            &pu,
            [pu[(j + 1) % 3], pu[(j + 2) % 3]],
        ),
        [(i0, _), (i1, _)] => {
            let (a, b) = (t.v[i0], t.v[i1]);
            // A common edge that is a diagonal of one face and an edge or
            // diagonal of another: the surface touches itself along it.
            if t.face != u.face && !(t.is_face_edge(a, b) && u.is_face_edge(a, b)) {
                return true;
            }
            let (i2, j2) = (3 - i0 - i1, (0..3).find(|&j| u.v[j] != b && u.v[j] != a));
            let Some(j2) = j2 else { return true };
            intersect::edge_sharing_triangles_fold(p(a), p(b), pt[i2], pu[j2])
        }
        _ => true,
    }
}

/// How many shells' volume signs the float filter could not settle (the
/// exact sum decided them): [`volume_sign_fallbacks`].
static VOLUME_SIGN_FALLBACKS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// How many volume signs (rule 7) the float filter left to the exact sum,
/// since the process started.
pub fn volume_sign_fallbacks() -> u64 {
    VOLUME_SIGN_FALLBACKS.load(std::sync::atomic::Ordering::Relaxed)
}

/// The sign of six times the signed volume from floats, when the sum's
/// error bound proves it.
///
/// Per triangle, the corners less `o` round by at most `u` each
/// coordinate, so each of the determinant's six products `±a_i b_j c_k`
/// moves by at most `((1 + u)³ − 1) ≤ 3.01u` of its magnitude; evaluating
/// it (a cross product, then a dot product: five rounded operations deep)
/// errs by at most `γ₅` of the sum `P` of the products' magnitudes. So
/// each computed determinant is within `9u P` of the exact one (`P`
/// computed from the rounded differences, `(1 + u)³` of the true). A
/// recursive sum of `n` terms, in any order, errs by at most
/// `γ_{n−1} Σ|d|` with `Σ|d| ≤ (1 + 9u) ΣP`. The bound used,
/// `E = 2 (n + 16) u · fl(ΣP) + n · 2⁻⁹⁶⁰`, doubles the sum of both (`fl`
/// of a sum of non-negative terms is within `γ_n` of it) and covers
/// underflowed products (each off by at most `2⁻¹⁰⁷⁴`). A sum beyond
/// `E` has the exact sum's sign; anything not finite falls to the exact
/// sum.
fn volume_sign_filtered(vertices: &[[f64; 3]], tris: &[[usize; 3]], o: DVec3) -> Option<Sign> {
    let (mut sum, mut size) = (0.0f64, 0.0f64);
    for t in tris {
        let [a, b, c] = t.map(|i| DVec3::from(vertices[i]) - o);
        sum += a.dot(b.cross(c));
        let (a, b, c) = (a.abs(), b.abs(), c.abs());
        size += a.dot(DVec3::new(
            b.y * c.z + b.z * c.y,
            b.z * c.x + b.x * c.z,
            b.x * c.y + b.y * c.x,
        ));
    }
    let n = tris.len() as f64;
    let bound = 2.0 * (n + 16.0) * (f64::EPSILON / 2.0) * size + n * 2f64.powi(-960);
    if !(sum.is_finite() && bound.is_finite()) {
        return None;
    }
    if sum > bound {
        Some(Sign::Positive)
    } else if sum < -bound {
        Some(Sign::Negative)
    } else {
        None
    }
}

/// Rule 7: the exact sign of six times the signed volume of a shell: a
/// float sum when its error bound proves the sign
/// ([`volume_sign_filtered`]), else exact partial sums over chunks, in
/// parallel (the order does not change an exact sum).
pub(crate) fn volume_sign(vertices: &[[f64; 3]], tris: &[[usize; 3]]) -> Sign {
    let Some(first) = tris.first() else {
        return Sign::Zero;
    };
    let o = DVec3::from(vertices[first[0]]);
    if let Some(sign) = volume_sign_filtered(vertices, tris, o) {
        return sign;
    }
    VOLUME_SIGN_FALLBACKS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    volume_sign_exact(vertices, tris, o)
}

/// Rule 7 by the exact sum.
fn volume_sign_exact(vertices: &[[f64; 3]], tris: &[[usize; 3]], o: DVec3) -> Sign {
    tris.par_chunks(1024)
        .map(|chunk| {
            let mut sum = Dyadic::zero();
            for t in chunk {
                let [a, b, c] = t.map(|i| exact::sub(DVec3::from(vertices[i]), o));
                sum = sum.add(&exact::det3(&a, &b, &c));
            }
            sum
        })
        .reduce(Dyadic::zero, |x, y| x.add(&y))
        .sign()
}

#[cfg(test)]
mod volume_sign_tests {
    use super::*;

    /// The float filter never contradicts the exact sum: random triangle
    /// sets at scales from 2⁻⁵⁰⁰ to 2⁵⁰⁰, some far from the origin, and
    /// exactly flat ones on a tilted plane (zero volume, which floats
    /// round to a few ulps either way) among them; it settles the clear
    /// cases and leaves the flat ones to the exact sum.
    #[test]
    fn the_filter_agrees_with_the_exact_sum_and_leaves_ties_to_it() {
        let mut rng = crate::kernel::test_rng::Xorshift::new(0x1234_5678_9abc_def1u64);
        let mut unit = move || rng.signed();
        let (mut settled, mut flat_left) = (0, 0);
        for round in 0..3000 {
            // Powers of two, so that the flat shells below are exactly
            // flat: small integers times 2⁻¹⁰ of the scale, on the tilted
            // plane z = x + y (sums of such numbers are exact).
            let scale = [
                2f64.powi(-500),
                2f64.powi(-30),
                1.0,
                2f64.powi(30),
                2f64.powi(500),
            ][round % 5];
            let far = if round % 3 == 0 { 1024.0 * scale } else { 0.0 };
            let flat = round % 4 == 0;
            let n = 4 + (round % 9);
            let vertices: Vec<[f64; 3]> = (0..n)
                .map(|_| {
                    if flat {
                        let x = (unit() * 1000.0).round() * scale / 1024.0;
                        let y = (unit() * 1000.0).round() * scale / 1024.0;
                        [far + x, far + y, 2.0 * far + x + y]
                    } else {
                        [
                            far + scale * unit(),
                            far - scale * unit(),
                            far + scale * unit(),
                        ]
                    }
                })
                .collect();
            let tris: Vec<[usize; 3]> = (0..n)
                .map(|k| {
                    let i = k % n;
                    let j = ((unit() + 1.0) * 0.5 * n as f64) as usize % n;
                    let l = ((unit() + 1.0) * 0.5 * n as f64) as usize % n;
                    [i, j, l]
                })
                .collect();
            let o = DVec3::from(vertices[tris[0][0]]);
            let exact = volume_sign_exact(&vertices, &tris, o);
            match volume_sign_filtered(&vertices, &tris, o) {
                Some(sign) => {
                    assert_eq!(sign, exact, "round {round}");
                    settled += 1;
                }
                None => flat_left += usize::from(flat),
            }
            if flat {
                assert_eq!(exact, Sign::Zero);
            }
        }
        assert!(settled > 1000, "{settled}");
        assert!(flat_left >= 700, "{flat_left}");
    }
}
