//! `sanity_check()`: the invariants of a [`Polytope`], checked exactly.

use super::Polytope;
use crate::kernel::predicates::orient;
use crate::kernel::Sign;
use crate::sanity::SanityError;

impl Polytope {
    /// Checks every invariant: closed 2-manifold (each edge has two distinct
    /// faces, rings are consistent), Euler `V − E + F = 2`, every face exactly
    /// planar and strictly convex, the whole polytope exactly convex and
    /// outward (no vertex above any face plane; each face has a vertex
    /// strictly below), no two adjacent faces coplanar, no vertex of degree
    /// < 3. O(F · V) exact predicates: meant for tests and fuzzing.
    ///
    /// # Errors
    /// The first broken invariant, as a [`SanityError`] naming the element.
    pub fn sanity_check(&self) -> Result<(), SanityError> {
        let (v, e, f) = (
            self.vertex_count() as i64,
            self.edge_count() as i64,
            self.face_count() as i64,
        );
        if v - e + f != 2 {
            return Err(SanityError::EulerCharacteristic { chi: v - e + f });
        }
        for (i, edge) in self.edges().iter().enumerate() {
            if edge.faces[0] == edge.faces[1] {
                return Err(SanityError::EdgeWithOneFace { edge: i });
            }
        }
        for vtx in 0..self.vertex_count() {
            let r = self.ring(vtx);
            if r.len() < 3 {
                return Err(SanityError::VertexDegree {
                    vertex: vtx,
                    degree: r.len(),
                });
            }
            for (k, entry) in r.iter().enumerate() {
                let edge = self.edge(entry.edge as usize);
                if !edge.vertices.contains(&(vtx as u32))
                    || !edge.vertices.contains(&entry.neighbor)
                {
                    return Err(SanityError::RingWrongEdge {
                        vertex: vtx,
                        entry: k,
                    });
                }
                let next = r[(k + 1) % r.len()].face;
                if !(edge.faces.contains(&entry.face) && edge.faces.contains(&next)) {
                    return Err(SanityError::RingNotSeparating {
                        vertex: vtx,
                        entry: k,
                    });
                }
            }
        }
        for fi in 0..self.face_count() {
            let face = self.face(fi);
            if face.len() < 3 {
                return Err(SanityError::FaceTooSmall {
                    face: fi,
                    corners: face.len(),
                });
            }
            let p = |k: usize| self.vertex(face[k % face.len()] as usize);
            // Strictly convex polygon: consecutive triples turn left around the
            // face normal, decided exactly with the apex of a reference
            // point strictly below the face.
            let below = (0..self.vertex_count())
                .find(|&w| orient(p(0), p(1), p(2), self.vertex(w)) == Sign::Negative);
            let Some(below) = below else {
                return Err(SanityError::NothingBelowFace { face: fi });
            };
            let b = self.vertex(below);
            for k in 0..face.len() {
                if orient(p(0), p(1), p(2), p(k)) != Sign::Zero {
                    return Err(SanityError::FaceNotPlanar {
                        face: fi,
                        corner: k,
                    });
                }
                // p(k), p(k+1), p(k+2) ccw seen from outside <=> b below.
                if orient(p(k), p(k + 1), p(k + 2), b) != Sign::Negative {
                    return Err(SanityError::FaceNotConvex {
                        face: fi,
                        corner: k + 1,
                    });
                }
            }
            for w in 0..self.vertex_count() {
                if orient(p(0), p(1), p(2), self.vertex(w)) == Sign::Positive {
                    return Err(SanityError::VertexAboveFace {
                        vertex: w,
                        face: fi,
                    });
                }
            }
        }
        for (i, edge) in self.edges().iter().enumerate() {
            let f0 = self.face(edge.faces[0] as usize);
            let g = self.face(edge.faces[1] as usize);
            let p = |k: usize| self.vertex(f0[k] as usize);
            let apex = g.iter().find(|&&w| !f0.contains(&w));
            if let Some(&w) = apex {
                if orient(p(0), p(1), p(2), self.vertex(w as usize)) == Sign::Zero {
                    return Err(SanityError::CoplanarFaces { edge: i });
                }
            }
        }
        Ok(())
    }
}
