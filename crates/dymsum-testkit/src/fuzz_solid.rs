//! The exact solid check ([`dymsum::solid::check_solid_mesh`]) and the
//! closed-mesh check ([`dymsum::solid::closed::check_closed_mesh`]) against
//! meshes whose verdict is known: solids built on the integer grid (boxes
//! of quads or triangles, bars of glued boxes, L-shaped prisms with
//! non-convex caps), each a shell of its own, then changed in one way
//! (a vertex moved, a face dropped, flipped or listed again, a box pinched
//! on at a corner or welded on along an edge, a shell turned inward, an L
//! whose caps' fans fold).
//!
//! Each change has its verdict by construction ([`check`] asserts the
//! kind), and every answer is also judged, rule by rule in the order the
//! solid module documents, by an oracle written independently of
//! `dymsum::solid`: integer arithmetic, corner sets for duplicates, edge
//! multiplicities and face adjacency about each vertex for the topology,
//! and for crossings the Minkowski-difference test of
//! [`crate::fuzz_triangles`] (and, for triangles sharing a corner or an
//! edge, the cones they span there). An error must name a defect the
//! oracle finds, in the first shell or face that has one; an `Ok` must
//! list the oracle's shells. The same mesh in a random exact frame
//! ([`Frame`]) must get the same answer.
//!
//! The stable proptest `crates/dymsum/tests/fuzz_solid.rs` (in CI) and the
//! cargo-fuzz target `fuzz/fuzz_targets/solid.rs` (off CI) both run
//! [`check`].

use std::collections::HashMap;

use crate::fuzz_triangles::{
    collinear, cross, dot, origin_in_hull, sub, triangles_meet_oracle, volume6, Bytes, Frame,
    GridPoint,
};
use dymsum::solid::closed::{check_closed_mesh, ClosedMeshInfo};
use dymsum::solid::{check_solid_mesh, SolidError, SolidInfo};
use dymsum::PolygonMesh;

/// A polygon mesh on the integer grid.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct GridMesh {
    /// The corners.
    pub vertices: Vec<GridPoint>,
    /// The faces, counter-clockwise seen from outside.
    pub faces: Vec<Vec<usize>>,
}

impl GridMesh {
    /// Appends `other` (its vertices renumbered after these); returns the
    /// range of its faces.
    pub fn append(&mut self, other: &GridMesh) -> std::ops::Range<usize> {
        let (base, first) = (self.vertices.len(), self.faces.len());
        self.vertices.extend(&other.vertices);
        self.faces.extend(
            other
                .faces
                .iter()
                .map(|f| f.iter().map(|&v| v + base).collect()),
        );
        first..self.faces.len()
    }

    /// The mesh in `frame` (exact).
    pub fn in_frame(&self, frame: &Frame) -> PolygonMesh {
        PolygonMesh::new(
            self.vertices.iter().map(|&p| frame.apply(p)).collect(),
            self.faces.clone(),
        )
    }
}

/// The corners of the box `[lo, lo + size]`, numbered as
/// [`crate::box_corners`] numbers them (bit `k` picks the high side of
/// axis `k`).
fn grid_box_corners(lo: GridPoint, size: GridPoint) -> Vec<GridPoint> {
    let hi: [f64; 3] = std::array::from_fn(|k| (lo[k] + size[k]) as f64);
    crate::box_corners(lo.map(|x| x as f64), hi)
        .into_iter()
        .map(|p| p.map(|x| x as i64))
        .collect()
}

/// A box: its six quads ([`crate::CUBE_QUADS`]), or with `split`, twelve
/// triangles (bit `q` of `split` picks the diagonal of quad `q`).
pub fn grid_box(lo: GridPoint, size: GridPoint, split: Option<u8>) -> GridMesh {
    let faces = crate::CUBE_QUADS
        .iter()
        .enumerate()
        .flat_map(|(q, &[a, b, c, d])| match split {
            None => vec![vec![a, b, c, d]],
            Some(bits) if bits >> q & 1 == 0 => vec![vec![a, b, c], vec![a, c, d]],
            Some(_) => vec![vec![a, b, d], vec![b, c, d]],
        })
        .collect();
    GridMesh {
        vertices: grid_box_corners(lo, size),
        faces,
    }
}

/// `count` boxes of `size` in a row along x, glued face to face (shared
/// corners, the inner faces left out): one shell whose long sides are
/// split into coplanar quads.
pub fn bar(lo: GridPoint, size: GridPoint, count: usize) -> GridMesh {
    // Ring r (x = lo + r size) holds vertices 4 r + (y bit) + 2 (z bit).
    let vertices = (0..=count)
        .flat_map(|r| {
            (0..4).map(move |yz: i64| {
                [
                    lo[0] + r as i64 * size[0],
                    lo[1] + (yz & 1) * size[1],
                    lo[2] + (yz >> 1) * size[2],
                ]
            })
        })
        .collect();
    let mut faces = Vec::new();
    for i in 0..count {
        for q in crate::CUBE_QUADS {
            let x_bits: Vec<usize> = q.iter().map(|c| c & 1).collect();
            let inner = (x_bits == [1; 4] && i + 1 < count) || (x_bits == [0; 4] && i > 0);
            if !inner {
                faces.push(q.iter().map(|&c| 4 * (i + (c & 1)) + (c >> 1)).collect());
            }
        }
    }
    GridMesh { vertices, faces }
}

/// The corners of the L `[0, w] × [0, b] ∪ [0, a] × [0, h]` (`0 < a < w`,
/// `0 < b < h`), counter-clockwise from the origin. Its kernel (the points
/// that see all of it) is `[0, a] × [0, b]`, which holds corners 0 and 3
/// only: a cap fanned from corner 0 or 3 is its triangulation, and a cap
/// fanned from any other corner folds (one of its fan triangles turns
/// clockwise; no three corners are collinear, so none is flat).
pub fn l_ring(w: i64, h: i64, a: i64, b: i64) -> [[i64; 2]; 6] {
    [[0, 0], [w, 0], [w, b], [a, b], [a, h], [0, h]]
}

/// The corners of [`l_ring`] whose fans are triangulations.
pub const L_KERNEL_CORNERS: [usize; 2] = [0, 3];

/// A prism of height `d` over the L of [`l_ring`] at `lo`: the two caps as
/// hexagons fanned from corner `start`, the sides as quads.
pub fn l_prism(lo: GridPoint, [w, h, a, b, d]: [i64; 5], start: usize) -> GridMesh {
    let ring = l_ring(w, h, a, b);
    let mut vertices: Vec<GridPoint> = ring
        .iter()
        .map(|p| [lo[0] + p[0], lo[1] + p[1], lo[2]])
        .collect();
    vertices.extend(ring.iter().map(|p| [lo[0] + p[0], lo[1] + p[1], lo[2] + d]));
    let mut faces: Vec<Vec<usize>> = vec![
        (0..6).map(|j| 6 + (start + j) % 6).collect(),
        (0..6).map(|j| (start + 6 - j) % 6).collect(),
    ];
    faces.extend((0..6).map(|i| vec![i, (i + 1) % 6, 6 + (i + 1) % 6, 6 + i]));
    GridMesh { vertices, faces }
}

/// One valid shell at a grid position from bytes: a box of quads or of
/// triangles, a bar, or an L prism fanned from a kernel corner.
fn shell(b: &mut Bytes) -> GridMesh {
    let lo = b.point(0, 4);
    match b.byte() % 4 {
        0 => grid_box(lo, b.point(1, 3), None),
        1 => grid_box(lo, b.point(1, 3), Some(b.byte())),
        2 => bar(lo, b.point(1, 2), 2 + usize::from(b.byte() % 2)),
        _ => {
            let (w, h) = (b.range(2, 4), b.range(2, 4));
            let dims = [w, h, b.range(1, w - 1), b.range(1, h - 1), b.range(1, 2)];
            let start = L_KERNEL_CORNERS[usize::from(b.byte() % 2)];
            l_prism(lo, dims, start)
        }
    }
}

/// The changes [`case`] makes to a valid mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Change {
    /// None: a solid.
    Keep,
    /// A vertex moved on the grid: the oracle alone knows the verdict.
    MoveVertex,
    /// A face left out: an open edge.
    DropFace,
    /// A face reversed: two faces run an edge the same way.
    FlipFace,
    /// A face listed again (as it is or reversed): a duplicate face.
    RepeatFace,
    /// A box sharing one corner (by index) with the first shell: a pinch.
    PinchCorner,
    /// A box sharing one edge (by index) with the first shell: an edge in
    /// four faces.
    WeldEdge,
    /// Every face of one shell reversed (each keeping its first corner, so
    /// its fan): an inward shell.
    TurnShell,
    /// An L prism added whose caps are fanned from a corner outside the
    /// kernel: its caps fold.
    FoldCap,
}

const CHANGES: [Change; 9] = [
    Change::Keep,
    Change::MoveVertex,
    Change::DropFace,
    Change::FlipFace,
    Change::RepeatFace,
    Change::PinchCorner,
    Change::WeldEdge,
    Change::TurnShell,
    Change::FoldCap,
];

/// A case from bytes: one to three valid shells, one [`Change`], and a
/// frame. Returns the mesh, the change, the faces of each shell built, and
/// the frame.
pub fn case(data: &[u8]) -> (GridMesh, Change, Vec<std::ops::Range<usize>>, Frame) {
    let mut b = Bytes::new(data);
    let change = CHANGES[usize::from(b.byte()) % CHANGES.len()];
    let mut m = GridMesh::default();
    let mut shells: Vec<std::ops::Range<usize>> = (0..1 + b.byte() % 3)
        .map(|_| {
            let s = shell(&mut b);
            m.append(&s)
        })
        .collect();
    let pick = |b: &mut Bytes, n: usize| usize::from(b.byte()) * 7 % n;
    match change {
        Change::Keep => {}
        Change::MoveVertex => {
            // Half the time on triangles (the same solid, its faces' fans),
            // where a move leaves every face planar and reaches the
            // crossing and volume rules.
            if b.byte().is_multiple_of(2) {
                let mut first_fan = vec![0];
                for f in &m.faces {
                    first_fan.push(first_fan[first_fan.len() - 1] + f.len() - 2);
                }
                for s in &mut shells {
                    *s = first_fan[s.start]..first_fan[s.end];
                }
                m.faces = fans(&m).into_iter().map(|(t, _)| t.to_vec()).collect();
            }
            for _ in 0..1 + b.byte() % 2 {
                let v = pick(&mut b, m.vertices.len());
                let old = m.vertices[v];
                m.vertices[v] = if b.byte().is_multiple_of(4) {
                    b.point(-1, 7)
                } else {
                    let d = b.point(-2, 2);
                    std::array::from_fn(|k| old[k] + d[k])
                };
            }
        }
        Change::DropFace => {
            let k = pick(&mut b, m.faces.len());
            m.faces.remove(k);
        }
        Change::FlipFace => {
            let k = pick(&mut b, m.faces.len());
            m.faces[k].reverse();
        }
        Change::RepeatFace => {
            let k = pick(&mut b, m.faces.len());
            let mut f = m.faces[k].clone();
            if b.byte() % 2 == 1 {
                f.reverse();
            }
            m.faces.push(f);
        }
        Change::PinchCorner => {
            let v = m.faces[0][pick(&mut b, m.faces[0].len())];
            let size = b.point(1, 2);
            let signs = [b.byte() % 2, b.byte() % 2, b.byte() % 2];
            // The box's corner `c` sits on `v` (with its own index first).
            let c: usize = (0..3).map(|k| usize::from(signs[k]) << k).sum();
            let lo = std::array::from_fn(|k| m.vertices[v][k] - i64::from(signs[k]) * size[k]);
            let base = m.vertices.len();
            let added = m.append(&grid_box(lo, size, None));
            for f in &mut m.faces[added] {
                for x in f.iter_mut() {
                    if *x == base + c {
                        *x = v;
                    }
                }
            }
        }
        Change::WeldEdge => {
            // An axis-parallel edge of the first face (every shell's faces
            // have one).
            let f = m.faces[0].clone();
            let n = f.len();
            let (u, w) = (0..n)
                .map(|i| (f[i], f[(i + 1) % n]))
                .find(|&(u, w)| {
                    let d = sub(m.vertices[w], m.vertices[u]);
                    d.iter().filter(|&&x| x != 0).count() == 1
                })
                .expect("an axis-parallel edge");
            let (pu, pw) = (m.vertices[u], m.vertices[w]);
            let axis = (0..3).find(|&k| pu[k] != pw[k]).expect("an edge");
            let size = b.point(1, 2);
            let signs = [b.byte() % 2, b.byte() % 2, b.byte() % 2];
            let lo: GridPoint = std::array::from_fn(|k| {
                if k == axis {
                    pu[k].min(pw[k])
                } else {
                    pu[k] - i64::from(signs[k]) * size[k]
                }
            });
            let mut dims = size;
            dims[axis] = (pu[axis] - pw[axis]).abs();
            let welded = grid_box(lo, dims, None);
            let of = |p: GridPoint| welded.vertices.iter().position(|&q| q == p);
            let base = m.vertices.len();
            let (cu, cw) = (
                base + of(pu).expect("a corner"),
                base + of(pw).expect("a corner"),
            );
            let added = m.append(&welded);
            for f in &mut m.faces[added] {
                for x in f.iter_mut() {
                    if *x == cu {
                        *x = u;
                    } else if *x == cw {
                        *x = w;
                    }
                }
            }
        }
        Change::TurnShell => {
            let s = shells[pick(&mut b, shells.len())].clone();
            for f in &mut m.faces[s] {
                f[1..].reverse();
            }
        }
        Change::FoldCap => {
            let (w, h) = (b.range(2, 4), b.range(2, 4));
            let dims = [w, h, b.range(1, w - 1), b.range(1, h - 1), b.range(1, 2)];
            let start = [1, 2, 4, 5][usize::from(b.byte() % 4)];
            let l = l_prism(b.point(0, 4), dims, start);
            shells.push(m.append(&l));
        }
    }
    let frame = Frame::from_bytes([b.byte(), b.byte(), b.byte(), b.byte()]);
    (m, change, shells, frame)
}

// ------------------------------------------------------------- the oracle

/// The fan triangles of each face, in face order, with their faces.
fn fans(m: &GridMesh) -> Vec<([usize; 3], usize)> {
    m.faces
        .iter()
        .enumerate()
        .flat_map(|(face, f)| (1..f.len() - 1).map(move |i| ([f[0], f[i], f[i + 1]], face)))
        .collect()
}

/// The connected parts (through shared vertices) of `polygons`, each its
/// polygons ascending, in the order of their first one.
fn components(n: usize, polygons: &[&[usize]]) -> Vec<Vec<usize>> {
    let mut label: Vec<Option<usize>> = vec![None; polygons.len()];
    let mut by_vertex: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, f) in polygons.iter().enumerate() {
        for &v in f.iter() {
            by_vertex[v].push(i);
        }
    }
    let mut out: Vec<Vec<usize>> = Vec::new();
    for start in 0..polygons.len() {
        if label[start].is_some() {
            continue;
        }
        let id = out.len();
        let mut members = vec![start];
        label[start] = Some(id);
        let mut k = 0;
        while k < members.len() {
            for &v in polygons[members[k]] {
                for &g in &by_vertex[v] {
                    if label[g].is_none() {
                        label[g] = Some(id);
                        members.push(g);
                    }
                }
            }
            k += 1;
        }
        members.sort_unstable();
        out.push(members);
    }
    out
}

/// Directed edges of `polygons` and the polygons holding each.
fn directed(polygons: &[&[usize]]) -> HashMap<(usize, usize), Vec<usize>> {
    let mut out: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for (i, f) in polygons.iter().enumerate() {
        for k in 0..f.len() {
            out.entry((f[k], f[(k + 1) % f.len()])).or_default().push(i);
        }
    }
    out
}

/// The topology of `polygons` (faces, or fan triangles): the edges in
/// more than one polygon the same way, the edges without a reverse, and,
/// when there are none of those, the vertices whose polygons form more
/// than one fan (polygons joined across an edge at the vertex).
struct Topology {
    holders: HashMap<(usize, usize), Vec<usize>>,
    repeated: bool,
    open: bool,
    pinched: Vec<usize>,
}

impl Topology {
    fn new(n: usize, polygons: &[&[usize]]) -> Topology {
        let holders = directed(polygons);
        let repeated = holders.values().any(|h| h.len() > 1);
        let open = holders.keys().any(|&(a, b)| !holders.contains_key(&(b, a)));
        let mut pinched = Vec::new();
        if !repeated && !open {
            let mut around: Vec<Vec<usize>> = vec![Vec::new(); n];
            for (i, f) in polygons.iter().enumerate() {
                for &v in f.iter() {
                    around[v].push(i);
                }
            }
            for (v, ps) in around.iter().enumerate() {
                if ps.is_empty() {
                    continue;
                }
                // Polygons at v joined when they share an edge at v.
                let edges_at = |i: usize| -> Vec<usize> {
                    let f = polygons[i];
                    let k = f.iter().position(|&x| x == v).expect("a corner");
                    vec![f[(k + 1) % f.len()], f[(k + f.len() - 1) % f.len()]]
                };
                let mut seen = vec![false; ps.len()];
                let mut fans = 0;
                for s in 0..ps.len() {
                    if seen[s] {
                        continue;
                    }
                    fans += 1;
                    let mut stack = vec![s];
                    seen[s] = true;
                    while let Some(x) = stack.pop() {
                        let ex = edges_at(ps[x]);
                        for y in 0..ps.len() {
                            if !seen[y] && edges_at(ps[y]).iter().any(|e| ex.contains(e)) {
                                seen[y] = true;
                                stack.push(y);
                            }
                        }
                    }
                }
                if fans > 1 {
                    pinched.push(v);
                }
            }
        }
        Topology {
            holders,
            repeated,
            open,
            pinched,
        }
    }

    fn defective(&self) -> bool {
        self.repeated || self.open || !self.pinched.is_empty()
    }

    fn holders(&self, a: usize, b: usize) -> &[usize] {
        self.holders.get(&(a, b)).map_or(&[], |h| &h[..])
    }

    /// Whether `err` names one of these defects (`face_of` numbers the
    /// polygons as faces).
    fn names(&self, err: &SolidError, face_of: &dyn Fn(usize) -> usize) -> bool {
        let faces =
            |a, b| -> Vec<usize> { self.holders(a, b).iter().map(|&p| face_of(p)).collect() };
        match *err {
            SolidError::InconsistentOrientation { from, to, faces: f } => {
                let mut got = f.to_vec();
                got.sort_unstable();
                let mut want = faces(from, to);
                want.sort_unstable();
                got == want && self.holders(to, from).is_empty()
            }
            SolidError::NonManifoldEdge {
                from,
                to,
                count,
                face,
            } => {
                let (same, back) = (self.holders(from, to).len(), self.holders(to, from).len());
                same > 1
                    && !(same == 2 && back == 0)
                    && count == same + back
                    && faces(from, to).contains(&face)
            }
            SolidError::OpenEdge { from, to, face } => {
                faces(from, to).contains(&face) && self.holders(to, from).is_empty()
            }
            SolidError::NonManifoldVertex { vertex } => self.pinched.contains(&vertex),
            _ => false,
        }
    }
}

/// Whether the edge `{a, b}` is a side of the polygon `f`.
fn is_side(f: &[usize], a: usize, b: usize) -> bool {
    let n = f.len();
    (0..n).any(|k| {
        let (x, y) = (f[k], f[(k + 1) % n]);
        (x, y) == (a, b) || (x, y) == (b, a)
    })
}

/// Rule 6 for two fan triangles of one shell (not flat), independently:
/// do they meet other than along what they share?
fn pair_meets(m: &GridMesh, (t, ft): ([usize; 3], usize), (u, fu): ([usize; 3], usize)) -> bool {
    let p = |i: usize| m.vertices[i];
    let shared: Vec<usize> = t.iter().copied().filter(|x| u.contains(x)).collect();
    let others = |x: [usize; 3]| -> Vec<usize> {
        x.iter().copied().filter(|v| !shared.contains(v)).collect()
    };
    match shared[..] {
        [] => triangles_meet_oracle(&t.map(p), &u.map(p)),
        [v] => {
            // Past v exactly when the cones at v share a ray: the origin in
            // the hull of t's edge vectors and u's negated ones.
            let (a, b) = (others(t), others(u));
            let pv = p(v);
            origin_in_hull(&[
                sub(p(a[0]), pv),
                sub(p(a[1]), pv),
                sub(pv, p(b[0])),
                sub(pv, p(b[1])),
            ])
        }
        [a, b] => {
            let (f, g) = (&m.faces[ft], &m.faces[fu]);
            if ft != fu && !(is_side(f, a, b) && is_side(g, a, b)) {
                return true; // a diagonal against a side or another diagonal
            }
            // A fold: both on one side of the edge, in one plane.
            let e = sub(p(b), p(a));
            let nt = cross(e, sub(p(others(t)[0]), p(a)));
            let nu = cross(e, sub(p(others(u)[0]), p(a)));
            cross(nt, nu) == [0; 3] && dot(nt, nu) > 0
        }
        _ => true,
    }
}

/// Six times the signed volume of fan triangles, its sign.
fn volume_sign(m: &GridMesh, tris: &[[usize; 3]]) -> i64 {
    let Some(first) = tris.first() else { return 0 };
    let o = m.vertices[first[0]];
    tris.iter()
        .map(|t| volume6(o, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]))
        .sum::<i64>()
        .signum()
}

/// Judges `check_solid_mesh`'s answer on `m`: `Ok(())` when it holds, else
/// what is wrong.
pub fn judge_solid(m: &GridMesh, got: &Result<SolidInfo, SolidError>) -> Result<(), String> {
    let fail = |why: &str| Err(format!("{why}: got {got:?}"));
    if m.faces.is_empty() {
        return match got {
            Err(SolidError::Empty) => Ok(()),
            _ => fail("no faces"),
        };
    }
    // Rule 2: corner sets.
    let key = |f: &Vec<usize>| {
        let mut k = f.clone();
        k.sort_unstable();
        k
    };
    let keys: Vec<Vec<usize>> = m.faces.iter().map(key).collect();
    if (0..keys.len()).any(|b| keys[..b].contains(&keys[b])) {
        return match *got {
            Err(SolidError::DuplicateFace { a, b }) if a < b && keys[a] == keys[b] => Ok(()),
            _ => fail("a face listed twice"),
        };
    }
    // Rules 3 and 4, face by face.
    for (face, f) in m.faces.iter().enumerate() {
        let p = |i: usize| m.vertices[i];
        let flat: Vec<[usize; 3]> = (1..f.len() - 1)
            .map(|i| [f[0], f[i], f[i + 1]])
            .filter(|t| collinear(p(t[0]), p(t[1]), p(t[2])))
            .collect();
        if !flat.is_empty() {
            return match *got {
                Err(SolidError::ZeroAreaTriangle { face: g, corners })
                    if g == face && flat.contains(&corners) =>
                {
                    Ok(())
                }
                _ => fail(&format!("face {face} has flat fan triangles {flat:?}")),
            };
        }
        let off: Vec<usize> = f[3..]
            .iter()
            .copied()
            .filter(|&x| volume6(p(f[0]), p(f[1]), p(f[2]), p(x)) != 0)
            .collect();
        if !off.is_empty() {
            return match *got {
                Err(SolidError::NonPlanarFace { face: g, vertex })
                    if g == face && off.contains(&vertex) =>
                {
                    Ok(())
                }
                _ => fail(&format!("face {face} is not planar ({off:?} off)")),
            };
        }
    }
    // Rule 5, on the faces.
    let polygons: Vec<&[usize]> = m.faces.iter().map(|f| &f[..]).collect();
    let topology = Topology::new(m.vertices.len(), &polygons);
    if topology.defective() {
        return match got {
            Err(e) if topology.names(e, &|f| f) => Ok(()),
            _ => fail("a topological defect"),
        };
    }
    // Rules 6 and 7, shell by shell.
    let shells = components(m.vertices.len(), &polygons);
    let all = fans(m);
    for (s, shell) in shells.iter().enumerate() {
        let tris: Vec<([usize; 3], usize)> = all
            .iter()
            .copied()
            .filter(|(_, f)| shell.binary_search(f).is_ok())
            .collect();
        let meets = |i: usize, j: usize| pair_meets(m, tris[i], tris[j]);
        let crossing = (0..tris.len()).any(|i| (i + 1..tris.len()).any(|j| meets(i, j)));
        if crossing {
            return match *got {
                Err(SolidError::TrianglesCross { a, b }) if a <= b => {
                    let of = |f: usize| -> Vec<usize> {
                        (0..tris.len()).filter(|&i| tris[i].1 == f).collect()
                    };
                    let (ia, ib) = (of(a), of(b));
                    let real = ia
                        .iter()
                        .any(|&i| ib.iter().any(|&j| i != j && meets(i, j)));
                    if real && shell.binary_search(&a).is_ok() {
                        Ok(())
                    } else {
                        fail(&format!("faces {a} and {b} of shell {s} do not cross"))
                    }
                }
                _ => fail(&format!("shell {s} crosses itself")),
            };
        }
        let corners: Vec<[usize; 3]> = tris.iter().map(|t| t.0).collect();
        let sign = volume_sign(m, &corners);
        if sign <= 0 {
            let want = SolidError::NonPositiveVolume {
                shell: s,
                face: shell[0],
                negative: sign < 0,
            };
            return match got {
                Err(e) if *e == want => Ok(()),
                _ => fail(&format!("want {want:?}")),
            };
        }
    }
    match got {
        Ok(info) if info.shells == shells && info.triangles == all.len() => Ok(()),
        _ => fail(&format!("a solid of shells {shells:?}")),
    }
}

/// Judges `check_closed_mesh`'s answer on `m` (rule 1, the topology of the
/// fan triangles, the total volume; then what it measured).
pub fn judge_closed(m: &GridMesh, got: &Result<ClosedMeshInfo, SolidError>) -> Result<(), String> {
    let fail = |why: &str| Err(format!("{why}: got {got:?}"));
    if m.faces.is_empty() {
        return match got {
            Err(SolidError::Empty) => Ok(()),
            _ => fail("no faces"),
        };
    }
    let all = fans(m);
    let tris: Vec<&[usize]> = all.iter().map(|t| &t.0[..]).collect();
    let topology = Topology::new(m.vertices.len(), &tris);
    if topology.defective() {
        return match got {
            Err(e) if topology.names(e, &|t| all[t].1) => Ok(()),
            _ => fail("a topological defect"),
        };
    }
    let corners: Vec<[usize; 3]> = all.iter().map(|t| t.0).collect();
    let sign = volume_sign(m, &corners);
    if sign <= 0 {
        let want = SolidError::NonPositiveTotalVolume { negative: sign < 0 };
        return match got {
            Err(e) if *e == want => Ok(()),
            _ => fail(&format!("want {want:?}")),
        };
    }
    let shells = components(m.vertices.len(), &tris).len();
    let used = {
        let mut u: Vec<usize> = corners.iter().flatten().copied().collect();
        u.sort_unstable();
        u.dedup();
        u.len()
    };
    let chi = used as i64 - (3 * corners.len() / 2) as i64 + corners.len() as i64;
    let slivers = corners
        .iter()
        .filter(|t| collinear(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]))
        .count();
    let o = m.vertices[corners[0][0]];
    let volume6_sum: i64 = corners
        .iter()
        .map(|t| volume6(o, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]))
        .sum();
    match got {
        Ok(info)
            if info.shells == shells
                && info.vertices == used
                && info.triangles == corners.len()
                && info.genus == shells as i64 - chi / 2
                && info.slivers == slivers
                && (info.volume - volume6_sum as f64 / 6.0).abs()
                    <= 1e-9 * (volume6_sum as f64).abs() =>
        {
            Ok(())
        }
        _ => fail(&format!(
            "want {shells} shells, {used} vertices, {} triangles, χ {chi}, {slivers} slivers, volume {}",
            corners.len(),
            volume6_sum as f64 / 6.0
        )),
    }
}

/// Every property (panics naming the one broken): both checks answer as
/// the change makes certain and as the oracle judges, and the same in a
/// random exact frame.
pub fn check(data: &[u8]) {
    let (m, change, shells, frame) = case(data);
    let mesh = m.in_frame(&Frame::IDENTITY);
    let solid = check_solid_mesh(&mesh);
    let closed = check_closed_mesh(&mesh);
    let show = || format!("{change:?} on {m:?}");
    if let Err(why) = judge_solid(&m, &solid) {
        panic!("check_solid_mesh: {why}\n{}", show());
    }
    if let Err(why) = judge_closed(&m, &closed) {
        panic!("check_closed_mesh: {why}\n{}", show());
    }
    // What the change makes certain.
    let certain = match change {
        Change::Keep => matches!(&solid, Ok(i) if i.shells.len() == shells.len()) && closed.is_ok(),
        Change::MoveVertex => true,
        Change::DropFace => {
            matches!(solid, Err(SolidError::OpenEdge { .. }))
                && matches!(closed, Err(SolidError::OpenEdge { .. }))
        }
        Change::FlipFace => {
            matches!(solid, Err(SolidError::InconsistentOrientation { .. }))
                && matches!(closed, Err(SolidError::InconsistentOrientation { .. }))
        }
        Change::RepeatFace => {
            matches!(solid, Err(SolidError::DuplicateFace { b, .. }) if b == m.faces.len() - 1)
                && matches!(closed, Err(SolidError::NonManifoldEdge { .. }))
        }
        Change::PinchCorner => {
            matches!(solid, Err(SolidError::NonManifoldVertex { .. }))
                && matches!(closed, Err(SolidError::NonManifoldVertex { .. }))
        }
        Change::WeldEdge => {
            matches!(solid, Err(SolidError::NonManifoldEdge { count: 4, .. }))
                && matches!(closed, Err(SolidError::NonManifoldEdge { count: 4, .. }))
        }
        Change::TurnShell => matches!(
            solid,
            Err(SolidError::NonPositiveVolume { face, negative: true, .. })
                if shells.iter().any(|s| s.start == face)
        ),
        Change::FoldCap => {
            let l = shells.last().expect("the L");
            matches!(solid, Err(SolidError::TrianglesCross { a, b })
                if a == l.start || a == l.start + 1 || b == l.start || b == l.start + 1)
                && closed.is_ok()
        }
    };
    assert!(
        certain,
        "the change's verdict: solid {solid:?}, closed {closed:?}\n{}",
        show()
    );
    // The same answers in another exact frame.
    let moved = m.in_frame(&frame);
    assert_eq!(check_solid_mesh(&moved), solid, "{frame:?}\n{}", show());
    let closed_moved = check_closed_mesh(&moved);
    let measured = |r: &Result<ClosedMeshInfo, SolidError>| {
        r.clone()
            .map(|i| (i.vertices, i.triangles, i.shells, i.genus, i.slivers))
    };
    assert_eq!(
        measured(&closed_moved),
        measured(&closed),
        "{frame:?}\n{}",
        show()
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_builders_make_solids() {
        let mut m = GridMesh::default();
        m.append(&grid_box([0; 3], [1, 2, 3], None));
        m.append(&grid_box([1; 3], [2, 1, 1], Some(0b10_1101)));
        m.append(&bar([0, 0, 5], [1, 2, 1], 3));
        for start in L_KERNEL_CORNERS {
            m.append(&l_prism([3, 0, 0], [3, 4, 1, 2, 1], start));
        }
        let mesh = m.in_frame(&Frame::IDENTITY);
        assert_eq!(check_solid_mesh(&mesh).map(|i| i.shells.len()), Ok(5));
        assert_eq!(judge_solid(&m, &check_solid_mesh(&mesh)), Ok(()));
        assert_eq!(judge_closed(&m, &check_closed_mesh(&mesh)), Ok(()));
        for start in [1, 2, 4, 5] {
            let l = l_prism([0; 3], [3, 4, 1, 2, 1], start);
            let got = check_solid_mesh(&l.in_frame(&Frame::IDENTITY));
            assert!(
                matches!(got, Err(SolidError::TrianglesCross { .. })),
                "{start}: {got:?}"
            );
            assert_eq!(judge_solid(&l, &got), Ok(()));
        }
    }
}
