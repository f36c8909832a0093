//! Mesh topology, written once: the directed-edge index of a polygon mesh,
//! the checks that make it a closed, oriented 2-manifold sphere, and the
//! half-edge structure (edges with their two faces, vertex rings) that a
//! [`Polytope`](super::Polytope) stores.
//!
//! Three callers share it: [`Polytope::from_mesh`](super::Polytope::from_mesh)
//! validating a user's mesh, `Polytope::from_faces` building the adjacency of
//! a hull, and [`check_convex_mesh`](crate::sum::validate::check_convex_mesh)
//! validating every mesh dymsum writes.
//!
//! # Steps
//! 1. [`DirectedEdges::new`]: every directed edge `a → b` of every face,
//!    grouped by `a` (compressed rows) and sorted by `b`, with the vertex
//!    before `a` in the same face and the edge's half-edge id (its position
//!    in the concatenated face lists). No hashing.
//! 2. [`DirectedEdges::check_sphere`], in this order: each directed edge at
//!    most once (else an edge used twice: a non-manifold edge or
//!    inconsistent orientation); its reverse present (else the mesh is
//!    open); optionally every vertex used; the outgoing edges of each vertex
//!    form one fan (else the vertex is pinched): from `v → t` in face `F`,
//!    whose edge into `v` is `p → v`, the next outgoing edge about `v` is
//!    `v → p`, and following it must visit all of them; and `V − E + F = 2`.
//! 3. [`HalfEdges::new`]: the undirected edges, numbered in order of their
//!    first half-edge, with their left and right faces; and each vertex's
//!    ring, which is exactly the fan of step 2 read counter-clockwise.
//!
//! Complexity: `O(H log d)` for `H` half-edges and largest vertex degree
//! `d` (a sort and binary searches per vertex).
//!
//! Degeneracies: faces are assumed to have at least three distinct,
//! in-range vertices (each caller checks that first, with its own error);
//! unused vertices are either skipped or refused ([`Unused`]).

use super::{Edge, RingEntry};
use crate::mesh::VertexIndex;

/// A topological defect, mapped by each caller to its own error type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TopologyDefect {
    /// The directed edge `a → b` occurs in two faces.
    EdgeUsedTwice(usize, usize),
    /// The directed edge `a → b` has no reverse.
    OpenEdge(usize, usize),
    /// A vertex belongs to no face (only with [`Unused::Refuse`]).
    UnusedVertex(usize),
    /// The faces about a vertex form more than one fan.
    PinchedVertex(usize),
    /// `V − E + F`, when it is not 2.
    Euler(i64),
}

/// What [`DirectedEdges::check_sphere`] does with a vertex in no face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Unused {
    /// Leave it out (and out of `V` in Euler's formula).
    Skip,
    /// Report [`TopologyDefect::UnusedVertex`].
    Refuse,
}

/// The directed edges of a polygon mesh, grouped by origin and sorted by
/// target (see the module docs, step 1).
pub(crate) struct DirectedEdges {
    /// `start[v]..start[v + 1]`: the positions of the edges leaving `v`.
    pub start: Vec<usize>,
    /// The target of the edge at each position.
    pub target: Vec<usize>,
    /// The vertex before the origin in the same face.
    prev: Vec<usize>,
    /// The half-edge id (position in the concatenated faces).
    half_edge: Vec<usize>,
    /// The face and corner of each half-edge id.
    corner: Vec<(u32, u32)>,
    /// Number of faces.
    faces: usize,
}

impl DirectedEdges {
    /// Indexes the directed edges of `faces` over `vertex_count` vertices.
    /// Every index must be below `vertex_count`.
    pub(crate) fn new<I: VertexIndex>(vertex_count: usize, faces: &[Vec<I>]) -> Self {
        Self::from_faces(vertex_count, faces.len(), |f| &faces[f][..])
    }

    /// [`Self::new`] for `count` faces given by `face(f)` (e.g. slices of
    /// one flat corner array).
    pub(crate) fn from_faces<'a, I: VertexIndex + 'a>(
        vertex_count: usize,
        count: usize,
        face: impl Fn(usize) -> &'a [I],
    ) -> Self {
        let n = vertex_count;
        let mut start = vec![0usize; n + 1];
        for f in 0..count {
            for &i in face(f) {
                start[i.index() + 1] += 1;
            }
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let total = start[n];
        let mut fill = start.clone();
        let mut rows = vec![(0usize, 0usize, 0usize); total];
        let mut corner = Vec::with_capacity(total);
        for fi in 0..count {
            let f = face(fi);
            let k = f.len();
            for i in 0..k {
                let a = f[i].index();
                let h = corner.len();
                rows[fill[a]] = (f[(i + 1) % k].index(), f[(i + k - 1) % k].index(), h);
                fill[a] += 1;
                corner.push((fi as u32, i as u32));
            }
        }
        for v in 0..n {
            rows[start[v]..start[v + 1]].sort_unstable();
        }
        let mut target = Vec::with_capacity(total);
        let mut prev = Vec::with_capacity(total);
        let mut half_edge = Vec::with_capacity(total);
        for (t, p, h) in rows {
            target.push(t);
            prev.push(p);
            half_edge.push(h);
        }
        DirectedEdges {
            start,
            target,
            prev,
            half_edge,
            corner,
            faces: count,
        }
    }

    /// Number of vertices indexed.
    pub(crate) fn vertex_count(&self) -> usize {
        self.start.len() - 1
    }

    /// Position of the directed edge `a → b`, if present.
    pub(crate) fn find(&self, a: usize, b: usize) -> Option<usize> {
        let s = self.start[a];
        self.target[s..self.start[a + 1]]
            .binary_search(&b)
            .ok()
            .map(|k| s + k)
    }

    /// The face holding the directed edge `a → b`, if present.
    pub(crate) fn face_of(&self, a: usize, b: usize) -> Option<usize> {
        self.find(a, b).map(|pos| self.face_corner(pos).0)
    }

    /// The faces holding the directed edge `a → b` (more than one when it
    /// is used twice), in the order of their half-edge ids.
    pub(crate) fn faces_of(&self, a: usize, b: usize) -> Vec<usize> {
        let row = self.start[a]..self.start[a + 1];
        let mut faces: Vec<(usize, usize)> = row
            .filter(|&pos| self.target[pos] == b)
            .map(|pos| (self.half_edge[pos], self.face_corner(pos).0))
            .collect();
        faces.sort_unstable();
        faces.into_iter().map(|(_, f)| f).collect()
    }

    /// A directed edge that occurs twice (in two faces or twice in one), if
    /// any.
    pub(crate) fn repeated_edge(&self) -> Option<(usize, usize)> {
        (0..self.vertex_count()).find_map(|v| {
            let t = &self.target[self.start[v]..self.start[v + 1]];
            t.windows(2).find(|w| w[0] == w[1]).map(|w| (v, w[0]))
        })
    }

    /// The face and corner index of the edge at position `pos` (the edge
    /// runs from corner `k` of that face to corner `k + 1`).
    pub(crate) fn face_corner(&self, pos: usize) -> (usize, usize) {
        let (f, k) = self.corner[self.half_edge[pos]];
        (f as usize, k as usize)
    }

    /// The position of the next edge leaving `v` counter-clockwise after
    /// the edge at `pos` (see the module docs, step 2), if it exists.
    fn next_about(&self, v: usize, pos: usize) -> Option<usize> {
        self.find(v, self.prev[pos])
    }

    /// Checks that the mesh is a closed, oriented 2-manifold sphere (module
    /// docs, step 2).
    pub(crate) fn check_sphere(&self, unused: Unused) -> Result<(), TopologyDefect> {
        let used = self.check_manifold(unused)?;
        let edges = (self.target.len() / 2) as i64;
        let euler = used as i64 - edges + self.faces as i64;
        if euler != 2 {
            return Err(TopologyDefect::Euler(euler));
        }
        Ok(())
    }

    /// Checks that the mesh is a closed, oriented 2-manifold of any genus
    /// and any number of components (module docs, step 2 without Euler's
    /// formula); returns the number of vertices used.
    pub(crate) fn check_manifold(&self, unused: Unused) -> Result<usize, TopologyDefect> {
        let n = self.vertex_count();
        if let Some((a, b)) = self.repeated_edge() {
            return Err(TopologyDefect::EdgeUsedTwice(a, b));
        }
        for v in 0..n {
            for &b in &self.target[self.start[v]..self.start[v + 1]] {
                if self.find(b, v).is_none() {
                    return Err(TopologyDefect::OpenEdge(v, b));
                }
            }
        }
        let mut used = 0usize;
        for v in 0..n {
            let degree = self.start[v + 1] - self.start[v];
            if degree == 0 {
                match unused {
                    Unused::Skip => continue,
                    Unused::Refuse => return Err(TopologyDefect::UnusedVertex(v)),
                }
            }
            used += 1;
            let first = self.start[v];
            let (mut pos, mut seen) = (first, 0);
            loop {
                // Every edge has its reverse (checked above), so the next
                // edge about `v` exists.
                pos = self
                    .next_about(v, pos)
                    .ok_or(TopologyDefect::OpenEdge(self.prev[pos], v))?;
                seen += 1;
                if pos == first || seen > degree {
                    break;
                }
            }
            if seen != degree {
                return Err(TopologyDefect::PinchedVertex(v));
            }
        }
        Ok(used)
    }
}

/// The half-edge structure of a closed, oriented 2-manifold sphere (module
/// docs, step 3).
pub(crate) struct HalfEdges {
    /// The undirected edge of each half-edge id.
    pub he_edge: Vec<u32>,
    /// The undirected edges, numbered in order of their first half-edge.
    pub edges: Vec<Edge>,
    /// `ring[ring_start[v]..ring_start[v + 1]]` is the ring of `v`.
    pub ring_start: Vec<u32>,
    /// Every vertex's ring, counter-clockwise seen from outside.
    pub ring: Vec<RingEntry>,
}

impl HalfEdges {
    /// Builds the half-edges of `faces`, checking first that they form a
    /// sphere using every vertex.
    pub(crate) fn new(vertex_count: usize, faces: &[Vec<u32>]) -> Result<Self, TopologyDefect> {
        let d = DirectedEdges::new(vertex_count, faces);
        d.check_sphere(Unused::Refuse)?;
        let nhe = d.half_edge.len();
        // The position of each half-edge id, and the id of its reverse.
        let mut position = vec![0usize; nhe];
        for (pos, &h) in d.half_edge.iter().enumerate() {
            position[h] = pos;
        }
        let origin = |h: usize| {
            let (f, k) = d.corner[h];
            faces[f as usize][k as usize] as usize
        };
        let twin = |h: usize| {
            let (a, b) = (origin(h), d.target[position[h]]);
            // Checked above: every edge has its reverse.
            let reverse = d.find(b, a).ok_or(TopologyDefect::OpenEdge(a, b))?;
            Ok(d.half_edge[reverse])
        };
        let mut he_edge = vec![u32::MAX; nhe];
        let mut edges = Vec::with_capacity(nhe / 2);
        for h in 0..nhe {
            if he_edge[h] == u32::MAX {
                let t = twin(h)?;
                let e = edges.len() as u32;
                he_edge[h] = e;
                he_edge[t] = e;
                edges.push(Edge {
                    vertices: [origin(h) as u32, origin(t) as u32],
                    faces: [d.corner[h].0, d.corner[t].0],
                });
            }
        }
        // The id of the half-edge into the origin of `h`, in the same face.
        let prev_in_face = |h: usize| {
            let (f, k) = d.corner[h];
            let len = faces[f as usize].len() as u32;
            h - k as usize + ((k + len - 1) % len) as usize
        };
        let mut ring_start = Vec::with_capacity(vertex_count + 1);
        let mut ring = Vec::with_capacity(nhe);
        ring_start.push(0u32);
        for v in 0..vertex_count {
            // Start at the last outgoing half-edge id: a fixed choice.
            let outgoing = d.start[v]..d.start[v + 1];
            let first = outgoing
                .max_by_key(|&pos| d.half_edge[pos])
                .ok_or(TopologyDefect::UnusedVertex(v))?;
            let mut pos = first;
            loop {
                let h = d.half_edge[pos];
                let p = prev_in_face(h);
                ring.push(RingEntry {
                    face: d.corner[h].0,
                    edge: he_edge[p],
                    neighbor: d.prev[pos] as u32,
                });
                pos = d
                    .next_about(v, pos)
                    .ok_or(TopologyDefect::PinchedVertex(v))?;
                if pos == first {
                    break;
                }
            }
            ring_start.push(ring.len() as u32);
        }
        Ok(HalfEdges {
            he_edge,
            edges,
            ring_start,
            ring,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TETRA: [[usize; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

    fn check(n: usize, faces: &[Vec<usize>], unused: Unused) -> Result<(), TopologyDefect> {
        DirectedEdges::new(n, faces).check_sphere(unused)
    }

    fn tetra(offset: usize) -> Vec<Vec<usize>> {
        TETRA
            .iter()
            .map(|f| f.iter().map(|&v| v + offset).collect())
            .collect()
    }

    #[test]
    fn each_defect_is_named() {
        assert_eq!(check(4, &tetra(0), Unused::Refuse), Ok(()));
        // A fifth vertex in no face: skipped or refused.
        assert_eq!(check(5, &tetra(0), Unused::Skip), Ok(()));
        assert_eq!(
            check(5, &tetra(0), Unused::Refuse),
            Err(TopologyDefect::UnusedVertex(4))
        );
        // One face flipped: its edges run the same way as their neighbours'.
        let mut flipped = tetra(0);
        flipped[0].reverse();
        assert!(matches!(
            check(4, &flipped, Unused::Refuse),
            Err(TopologyDefect::EdgeUsedTwice(..))
        ));
        // One face missing.
        assert!(matches!(
            check(4, &tetra(0)[1..], Unused::Refuse),
            Err(TopologyDefect::OpenEdge(..))
        ));
        // Two tetrahedra sharing vertex 0: two fans about it.
        let mut pinched = tetra(0);
        pinched.extend(
            tetra(3)
                .into_iter()
                .map(|f| f.into_iter().map(|v| if v == 3 { 0 } else { v }).collect()),
        );
        assert_eq!(
            check(7, &pinched, Unused::Refuse),
            Err(TopologyDefect::PinchedVertex(0))
        );
        // Two separate tetrahedra: V − E + F = 4.
        let mut two = tetra(0);
        two.extend(tetra(4));
        assert_eq!(
            check(8, &two, Unused::Refuse),
            Err(TopologyDefect::Euler(4))
        );
    }

    #[test]
    fn rings_are_the_fans_read_counter_clockwise() {
        let faces: Vec<Vec<u32>> = TETRA
            .iter()
            .map(|f| f.iter().map(|&v| v as u32).collect())
            .collect();
        let h = HalfEdges::new(4, &faces).unwrap();
        assert_eq!(h.edges.len(), 6);
        for v in 0..4 {
            let ring = &h.ring[h.ring_start[v] as usize..h.ring_start[v + 1] as usize];
            assert_eq!(ring.len(), 3);
            for (i, r) in ring.iter().enumerate() {
                let next = ring[(i + 1) % ring.len()];
                let e = h.edges[r.edge as usize];
                // The ring's edge joins v and the neighbour, and separates
                // this corner's face from the next one's.
                let mut ends = e.vertices;
                ends.sort_unstable();
                let mut want = [v as u32, r.neighbor];
                want.sort_unstable();
                assert_eq!(ends, want);
                let mut sides = e.faces;
                sides.sort_unstable();
                let mut want = [r.face, next.face];
                want.sort_unstable();
                assert_eq!(sides, want);
                // The neighbour precedes v in this corner's face.
                let f = &faces[r.face as usize];
                let k = f.iter().position(|&x| x == v as u32).unwrap();
                assert_eq!(f[(k + f.len() - 1) % f.len()], r.neighbor);
            }
        }
    }
}
