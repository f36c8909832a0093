//! The overlay of two Gaussian maps: the exact predicates and local searches
//! shared by every sum method and by the dynamic update.
//!
//! Paper §3–§4. A face normal `x` of one map lies in the cell of vertex `v`
//! of the other map iff it is strictly left of every arc of that cell
//! ([`GaussView::in_cell`]); two arcs cross iff each separates the other's
//! endpoints and they meet in the right hemisphere ([`edges_cross`]). Both use
//! [`sos_det3`] with global indices (faces of P first, then faces of Q), so
//! exact ties — parallel faces, a normal on an arc, overlapping arcs — are
//! broken by one consistent symbolic perturbation and every method sees the
//! same generic overlay.
//!
//! Speed: `det[a, b, x]` for an arc `a → b` is `m · x` with the arc's
//! great-circle normal `m = a × b` precomputed accurately per edge
//! ([`crate::Polytope::arc_normals`]), so the common case is one dot product
//! and a certified error bound; only near-ties evaluate the exact normals.

use crate::kernel::predicates::sos_det3;
use crate::kernel::Sign;
use crate::polytope::{rotated_error, FaceNormal, Polytope, RingEntry};
use glam::{DMat3, DVec3};

/// A polytope's Gaussian map at a given orientation: the polytope, its
/// rotated face normals and arc normals, and the base of its global SoS
/// indices.
#[derive(Clone, Copy)]
pub struct GaussView<'a> {
    /// The polytope.
    pub poly: &'a Polytope,
    /// Rotated exact-input normals, one per face.
    pub normals: &'a [DVec3],
    /// Rotated great-circle normals of the edge arcs, one per edge.
    pub arcs: &'a [DVec3],
    /// Error bounds of `arcs`.
    pub arc_errs: &'a [f64],
    /// Global SoS index of face 0.
    pub base: u32,
    /// The rotation taking the polytope's reference normals to `normals`
    /// (`None`: identity), taken as exact.
    pub rotation: Option<&'a DMat3>,
}

const U: f64 = f64::EPSILON / 2.0;
const SQRT3: f64 = 1.7320508075688774;

impl<'a> GaussView<'a> {
    /// Normal of face `f` as an exact predicate argument.
    #[inline]
    pub fn normal(&self, f: u32) -> FaceNormal<'a> {
        let approx = self.normals[f as usize];
        let err = self.poly.normal_error(f as usize);
        FaceNormal {
            poly: self.poly,
            face: f,
            approx,
            err: if self.rotation.is_some() {
                rotated_error(err, approx)
            } else {
                err
            },
            idx: self.base + f,
            rotation: self.rotation,
        }
    }

    /// Float approximation of the normal of face `f`.
    #[inline]
    pub fn n(&self, f: u32) -> DVec3 {
        self.normals[f as usize]
    }

    /// The side of `x` relative to the arc of edge `e` (from its left face's
    /// normal to its right face's): the SoS sign of `det[n_left, n_right, x]`.
    #[inline]
    pub fn arc_side(&self, e: u32, x: &FaceNormal<'_>) -> Sign {
        let m = self.arcs[e as usize];
        let em = self.arc_errs[e as usize];
        let v = m.dot(x.approx);
        let mm = m.abs().max_element() * SQRT3;
        let xm = x.approx.abs().max_element() * SQRT3;
        let bound = 1.01 * (em * (xm + x.err) + mm * x.err + 6.0 * U * mm * xm);
        Sign::certified(v, bound).unwrap_or_else(|| {
            let (a, b) = self.edge_arc(e);
            sos_det3(&a, &b, x)
        })
    }

    /// The side of `x` relative to ring arc `i` of a vertex (from the ring's
    /// `i`-th face to the next): positive means inside the cell.
    #[inline]
    fn ring_side(&self, ring: &[RingEntry], i: usize, x: &FaceNormal<'_>) -> Sign {
        let e = ring[i].edge;
        let s = self.arc_side(e, x);
        if self.poly.edge(e as usize).faces[0] == ring[i].face {
            s
        } else {
            s.flip()
        }
    }

    /// `true` when the direction `x` lies in the cell of vertex `v`
    /// (perturbed, so never on its boundary).
    #[inline]
    pub fn in_cell(&self, v: u32, x: &FaceNormal<'_>) -> bool {
        let ring = self.poly.ring(v as usize);
        (0..ring.len()).all(|i| self.ring_side(ring, i, x).is_positive())
    }

    /// The vertex whose cell contains `x`, by hill climbing from `start`
    /// (paper §4.2): cross the most violated arc of the current cell until
    /// none is violated. A step budget of `V` guards against cycling, after
    /// which an exhaustive exact scan answers. Returns the vertex and the
    /// number of steps.
    pub fn locate(&self, x: &FaceNormal<'_>, start: u32) -> (u32, usize) {
        let mut v = start;
        let limit = self.poly.vertex_count() + 1;
        for steps in 0..limit {
            let ring = self.poly.ring(v as usize);
            let mut best: Option<(f64, u32)> = None;
            for i in 0..ring.len() {
                if !self.ring_side(ring, i, x).is_positive() {
                    let m = self.arcs[ring[i].edge as usize];
                    let depth = (m.dot(x.approx) / m.length()).abs();
                    if best.is_none_or(|(d, _)| depth > d) {
                        best = Some((depth, ring[i].neighbor));
                    }
                }
            }
            match best {
                None => return (v, steps),
                Some((_, next)) => v = next,
            }
        }
        self.locate_exhaustive(x)
    }

    #[cold]
    fn locate_exhaustive(&self, x: &FaceNormal<'_>) -> (u32, usize) {
        let n = self.poly.vertex_count() as u32;
        let v = (0..n)
            .find(|&v| self.in_cell(v, x))
            .expect("the perturbed cells tile the sphere, so some cell contains x");
        (v, n as usize)
    }

    /// Walks the arc of edge `e` of the `other` map through this map, from
    /// the cell of `from` (which contains the arc's start) to the cell of
    /// `to` (which contains its end), calling `cross(edge)` for every arc of
    /// this map it crosses, in order (paper §4.3). Returns the number of
    /// cells visited. The walk crosses each convex cell once, so it needs at
    /// most `E` steps; exceeding that is reported as an error.
    pub fn walk_arc(
        &self,
        other: &GaussView<'_>,
        e: u32,
        from: u32,
        to: u32,
        cross: impl FnMut(u32),
    ) -> Result<usize, super::SumError> {
        self.walk_arc_hinted(other, e, from, to, &[], cross)
    }

    /// [`GaussView::walk_arc`] with the arcs crossed before a small motion
    /// as a hint: in each cell the next hinted arc is tested first. An arc of
    /// the cell that the walked arc crosses, other than the one it entered
    /// by, is the unique exit of the convex cell, so the hint only changes
    /// the order of the tests, never the result.
    pub fn walk_arc_hinted(
        &self,
        other: &GaussView<'_>,
        e: u32,
        from: u32,
        to: u32,
        hint: &[u32],
        mut cross: impl FnMut(u32),
    ) -> Result<usize, super::SumError> {
        let mut u = from;
        let mut came = u32::MAX;
        let mut steps = 0;
        let mut k = 0;
        while u != to {
            let ring = self.poly.ring(u as usize);
            let mut next = None;
            if let Some(&h) = hint.get(k) {
                if h != came {
                    if let Some(entry) = ring.iter().find(|r| r.edge == h) {
                        if edges_cross(other, e, self, h) {
                            next = Some(*entry);
                        }
                    }
                }
            }
            if next.is_none() {
                for entry in ring {
                    if entry.edge == came {
                        continue;
                    }
                    if edges_cross(other, e, self, entry.edge) {
                        next = Some(*entry);
                        break;
                    }
                }
            }
            let Some(entry) = next else {
                return Err(super::SumError::Inconsistent(format!(
                    "arc walk found no exit from cell {u}"
                )));
            };
            cross(entry.edge);
            k = match hint.iter().position(|&h| h == entry.edge) {
                Some(i) => i + 1,
                None => k,
            };
            came = entry.edge;
            u = entry.neighbor;
            steps += 1;
            if steps > self.poly.edge_count() {
                return Err(super::SumError::Inconsistent(
                    "arc walk did not terminate".into(),
                ));
            }
        }
        Ok(steps)
    }

    /// The arc of edge `e`: normals of its left and right faces.
    #[inline]
    pub fn edge_arc(&self, e: u32) -> (FaceNormal<'a>, FaceNormal<'a>) {
        let [f0, f1] = self.poly.edge(e as usize).faces;
        (self.normal(f0), self.normal(f1))
    }
}

/// `true` when the Gaussian arcs of edge `e` of map `x` and edge `e2` of map
/// `y` cross, under symbolic perturbation (so never a touching case): each
/// arc separates the other's endpoints, and `det[a, b, c] = −det[c, d, a]`
/// picks the crossing of the two great circles that lies on both arcs
/// (arcs `a → b` and `c → d`, each shorter than π).
#[inline]
pub fn edges_cross(x: &GaussView<'_>, e: u32, y: &GaussView<'_>, e2: u32) -> bool {
    let (c, d) = y.edge_arc(e2);
    let s1 = x.arc_side(e, &c);
    let s2 = x.arc_side(e, &d);
    if s1 == s2 {
        return false;
    }
    let (a, b) = x.edge_arc(e);
    let s3 = y.arc_side(e2, &a);
    if s3 == s1 {
        return false;
    }
    let s4 = y.arc_side(e2, &b);
    s3 != s4
}
