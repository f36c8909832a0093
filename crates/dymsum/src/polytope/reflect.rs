//! The point reflection `−P` of a polytope, read off `P` without building
//! anything again.
//!
//! A point reflection `x ↦ −x` maps a convex polytope onto one with the
//! same faces, edges and vertices, every coordinate negated (exact) and
//! every orientation turned round (it is a rotation by π composed with a
//! mirror). So `−P` keeps `P`'s numbering:
//!
//! - vertex `i` is `−vertex(i)`;
//! - face `f` has `P`'s corners in reverse order (counter-clockwise again
//!   seen from outside), its half-edge `j` the edge of `P`'s half-edge
//!   `n − 2 − j` (mod `n`);
//! - edge `e` joins the same vertices and separates the same faces, its
//!   endpoints swapped, so that the half-edge `a → b` still belongs to
//!   `faces[0]` (the left face's corners were reversed);
//! - the normal of face `f` is `−normal(f)`, exactly: its defining triple
//!   `[a, b, c]` becomes `[a, c, b]`, and on the negated vertices
//!   `(−c + a) × (−b + a) = −(b − a) × (c − a)`; the error bounds, the
//!   scale and the exact-zero pattern are the same (and so the refined
//!   normal, computed from the triple, is negated exactly: rounding to
//!   nearest is symmetric);
//! - an edge's arc normal `n(left) × n(right)` is unchanged (both normals
//!   are negated), and so is its error bound;
//! - each vertex's ring runs the other way: the face before the edge `e_i`
//!   between `f_i` and `f_{i+1}` is `f_{i+1}` now, so the entry of `f_j`
//!   takes `e_{j−1}`.
//!
//! The Gaussian map of `−P` is `P`'s mirrored through the origin, so each
//! cell stays strictly convex and no exact check is needed again. The
//! tests compare the result with a polytope built from the negated
//! vertices and reversed faces by the general constructor.
//!
//! # Review
//! An independent review (2026-11-30) checked each item above against the
//! crate's uses: half-edges, edge orientation and rings as `HalfEdges::new`
//! defines them, the triple (only `exact_normal` and `refined_normal` read
//! it, and nothing assumes it starts at the face's first corner), and no
//! code depending on edge numbering or ring starts. It confirmed that the
//! maps the queries kept between `B` and `−B` were identities for vertices
//! and faces before (the constructor keeps both orders), and that every
//! use of the edge map became the identity. One change it noted: `−B`'s
//! float normals are now exactly `B`'s negated, where the constructor
//! chose another defining triple (from the reversed face's first corner),
//! so float outputs built on them (a C-obstacle's unit normals) may move
//! by an ulp; every exact sign is unchanged. Its suggested checks are in
//! the tests: refined normals negated exactly and within their bounds,
//! unit normals bit for bit glam's `normalize`, the zero patterns, and
//! each half-edge against its edge's orientation.

use super::{Edge, Polytope, PolytopeData, RingEntry};

impl Polytope {
    /// The point reflection `−P`, with `P`'s numbering of vertices, faces
    /// and edges (module docs): exact, linear in the size, and nothing is
    /// decided again. Queries between bodies take the reflection of one
    /// (`A ⊕ −B`); the same numbering means no maps between the two.
    ///
    /// ```
    /// use dymsum::polytope::Polytope;
    /// let corners = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 3.0]];
    /// let p = Polytope::from_points(&corners).unwrap();
    /// let q = p.point_reflection();
    /// assert_eq!(q.vertex(1), -p.vertex(1));
    /// assert_eq!(q.normal(2), -p.normal(2));
    /// q.sanity_check().unwrap();
    /// ```
    pub fn point_reflection(&self) -> Polytope {
        let d = &*self.data;
        let mut face_verts = Vec::with_capacity(d.face_verts.len());
        let mut he_edge = Vec::with_capacity(d.he_edge.len());
        for f in 0..self.face_count() {
            let (start, end) = (d.face_start[f] as usize, d.face_start[f + 1] as usize);
            let n = end - start;
            face_verts.extend(d.face_verts[start..end].iter().rev());
            he_edge.extend((0..n).map(|j| d.he_edge[start + (2 * n - 2 - j) % n]));
        }
        let edges = d
            .edges
            .iter()
            .map(|e| Edge {
                vertices: [e.vertices[1], e.vertices[0]],
                faces: e.faces,
            })
            .collect();
        let mut ring = Vec::with_capacity(d.ring.len());
        for v in 0..self.vertex_count() {
            let r = self.ring(v);
            let k = r.len();
            ring.extend((0..k).map(|i| {
                let across = r[(2 * k - 2 - i) % k];
                RingEntry {
                    face: r[k - 1 - i].face,
                    edge: across.edge,
                    neighbor: across.neighbor,
                }
            }));
        }
        let data = PolytopeData {
            vertices: d.vertices.iter().map(|&v| -v).collect(),
            face_start: d.face_start.clone(),
            face_verts,
            he_edge,
            edges,
            normals: d.normals.iter().map(|&n| -n).collect(),
            normal_triple: d.normal_triple.iter().map(|&[a, b, c]| [a, c, b]).collect(),
            normal_err: d.normal_err.clone(),
            normal_support: d.normal_support.clone(),
            normal_scale: d.normal_scale.clone(),
            arc_normals: d.arc_normals.clone(),
            arc_err: d.arc_err.clone(),
            inv_normal_len: d.inv_normal_len.clone(),
            ring_start: d.ring_start.clone(),
            ring,
            frame: d.frame,
            derived: Default::default(),
        };
        Polytope {
            data: std::sync::Arc::new(data),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::exact::{cross, dot};
    use crate::kernel::predicates::ExactVector;
    use crate::kernel::test_rng::Xorshift;
    use crate::kernel::Sign;
    use glam::DVec3;

    /// Degenerate and ordinary shapes: random clouds, lattice points
    /// (coplanar clusters, parallel faces), a box far from the origin,
    /// a prism with polygonal faces, a tiny and a huge cloud.
    fn shapes() -> Vec<Polytope> {
        let mut rng = Xorshift::new(0x5eed_7e11);
        let mut out = Vec::new();
        for round in 0..40 {
            let n = 4 + round % 37;
            let cloud: Vec<[f64; 3]> = (0..n)
                .map(|_| [rng.signed(), rng.signed(), rng.signed()])
                .collect();
            let lattice: Vec<[f64; 3]> = (0..n)
                .map(|_| [0, 1, 2].map(|_| (rng.signed() * 3.0).round()))
                .collect();
            for points in [cloud, lattice] {
                if let Ok(p) = Polytope::from_points(&points) {
                    out.push(p);
                }
            }
        }
        let far_box: Vec<[f64; 3]> = (0..8)
            .map(|k| [0, 1, 2].map(|i| 1e6 + if k >> i & 1 == 1 { 0.5 } else { -0.25 }))
            .collect();
        let prism: Vec<[f64; 3]> = (0..14)
            .map(|k| {
                let a = (k % 7) as f64 * std::f64::consts::TAU / 7.0;
                [a.cos(), a.sin(), if k < 7 { 0.0 } else { 2.0 }]
            })
            .collect();
        let mut scaled = |s: f64| -> Vec<[f64; 3]> {
            (0..30)
                .map(|_| [rng.signed() * s, rng.signed() * s, rng.signed() * s])
                .collect()
        };
        let (tiny, huge) = (scaled(1e-200), scaled(1e200));
        for points in [far_box, prism, tiny, huge] {
            out.push(Polytope::from_points(&points).expect("a polytope"));
        }
        out
    }

    /// The general constructor on the negated vertices and reversed faces.
    fn rebuilt(p: &Polytope) -> Polytope {
        let neg: Vec<DVec3> = p.vertices().iter().map(|&v| -v).collect();
        let faces: Vec<Vec<u32>> = p
            .faces()
            .map(|f| f.iter().rev().copied().collect())
            .collect();
        Polytope::from_faces(neg, &faces).expect("the reflection")
    }

    #[test]
    fn the_reflection_is_the_polytope_built_from_the_negated_faces() {
        let shapes = shapes();
        assert!(shapes.len() > 60, "{} shapes", shapes.len());
        for p in &shapes {
            let q = p.point_reflection();
            let r = rebuilt(p);
            q.sanity_check().expect("a sound reflection");
            let refined: Vec<_> = (0..q.face_count()).map(|f| q.refined_normal(f)).collect();
            q.check_gauss_map(&refined).expect("strictly convex cells");
            assert_eq!(q.vertices(), r.vertices());
            assert_eq!(q.frame_exponent(), r.frame_exponent());
            // Faces keep their numbers and corners; edges are renumbered
            // by the general constructor: `to_r` maps ours to its.
            let mut to_r = vec![u32::MAX; q.edge_count()];
            for f in 0..q.face_count() {
                assert_eq!(q.face(f), r.face(f));
                for (&e, &g) in q.face_edges(f).iter().zip(r.face_edges(f)) {
                    assert!(to_r[e as usize] == u32::MAX || to_r[e as usize] == g);
                    to_r[e as usize] = g;
                }
                // The same exact normal as the constructor's, the float
                // normal and its bound negated exactly.
                let (nq, nr) = (q.exact_normal(f), r.exact_normal(f));
                assert!(cross(&nq, &nr).iter().all(|c| c.is_zero()));
                assert_eq!(dot(&nq, &nr).sign(), Sign::Positive);
                let np = p.exact_normal(f);
                assert!((0..3).all(|i| nq[i] == np[i].neg()));
                assert_eq!(q.normal(f), -p.normal(f));
                assert_eq!(q.normal_error(f), p.normal_error(f));
                assert_eq!(q.unit_normal(f), -p.unit_normal(f));
                assert_eq!(q.unit_normal(f), q.normal(f).normalize());
                assert_eq!(q.inverse_normal_length(f), p.inverse_normal_length(f));
                assert_eq!(
                    q.face_normal(f as u32).zero_mask(),
                    p.face_normal(f as u32).zero_mask()
                );
                // The refinement, computed from the triple, is negated
                // exactly and lies within its bounds of the float normal.
                let ((rq, eq), (rp, ep)) = (q.refined_normal(f), p.refined_normal(f));
                assert_eq!((rq, eq), (rp.map(|x| -x), ep));
                let gap = (0..3)
                    .map(|i| (rq[i].hi + rq[i].lo - q.normal(f)[i]).abs())
                    .fold(0.0, f64::max);
                assert!(gap <= eq + q.normal_error(f), "face {f}: {gap:e}");
                // Half-edge k runs from corner k to corner k + 1, on the
                // left of its edge when the edge runs that way.
                let (face, edges) = (q.face(f), q.face_edges(f));
                for k in 0..face.len() {
                    let (from, to) = (face[k], face[(k + 1) % face.len()]);
                    let edge = q.edge(edges[k] as usize);
                    let left = if edge.vertices == [from, to] { 0 } else { 1 };
                    assert_eq!(edge.vertices[left], from, "face {f}, half-edge {k}");
                    assert_eq!(edge.vertices[1 - left], to, "face {f}, half-edge {k}");
                    assert_eq!(edge.faces[left], f as u32, "face {f}, half-edge {k}");
                }
            }
            for (e, &g) in to_r.iter().enumerate() {
                let (a, b) = (q.edge(e), r.edge(g as usize));
                let flipped = Edge {
                    vertices: [b.vertices[1], b.vertices[0]],
                    faces: [b.faces[1], b.faces[0]],
                };
                assert!(a == b || a == flipped, "edge {e}: {a:?} against {b:?}");
                assert_eq!(a.vertices, [p.edge(e).vertices[1], p.edge(e).vertices[0]]);
            }
            // Each ring is the constructor's up to where it starts.
            for v in 0..q.vertex_count() {
                let (rq, rr) = (q.ring(v), r.ring(v));
                assert_eq!(rq.len(), rr.len());
                let mapped: Vec<RingEntry> = rq
                    .iter()
                    .map(|x| RingEntry {
                        edge: to_r[x.edge as usize],
                        ..*x
                    })
                    .collect();
                let start = rr
                    .iter()
                    .position(|x| x.face == mapped[0].face)
                    .expect("a corner");
                let turned: Vec<RingEntry> =
                    (0..rr.len()).map(|i| rr[(start + i) % rr.len()]).collect();
                assert_eq!(mapped, turned, "vertex {v}");
            }
        }
    }

    #[test]
    fn reflecting_twice_gives_the_polytope_back() {
        for p in shapes() {
            let q = p.point_reflection().point_reflection();
            assert_eq!(q.vertices(), p.vertices());
            assert_eq!(q.edges(), p.edges());
            assert_eq!(q.normals(), p.normals());
            assert_eq!(q.arc_normals(), p.arc_normals());
            assert_eq!(q.arc_errors(), p.arc_errors());
            for f in 0..p.face_count() {
                assert_eq!((q.face(f), q.face_edges(f)), (p.face(f), p.face_edges(f)));
                assert_eq!(q.refined_normal(f), p.refined_normal(f));
            }
            for v in 0..p.vertex_count() {
                assert_eq!(q.ring(v), p.ring(v));
            }
        }
    }
}
