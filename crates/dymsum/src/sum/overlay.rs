//! The overlay of two Gaussian maps: the exact predicates and local searches
//! shared by every sum method and by the dynamic update.
//!
//! Paper §3–§4. A face normal `x` of one map lies in the cell of vertex `v`
//! of the other map iff it is strictly left of every arc of that cell
//! ([`GaussView::in_cell`]); two arcs cross iff each separates the other's
//! endpoints and they meet in the right hemisphere ([`arcs_cross`]). Both use
//! [`sos_det3`] with global indices (faces of P first, then faces of Q), so
//! exact ties — parallel faces, a normal on an arc, overlapping arcs — are
//! broken by one consistent symbolic perturbation and every method sees the
//! same generic overlay.

use crate::kernel::predicates::sos_det3;
use crate::polytope::{rotated_error, FaceNormal, Polytope, RingEntry};
use glam::{DMat3, DVec3};

/// A polytope's Gaussian map at a given orientation: the polytope plus its
/// rotated face normals and the base of its global SoS indices.
#[derive(Clone, Copy)]
pub struct GaussView<'a> {
    /// The polytope.
    pub poly: &'a Polytope,
    /// Rotated exact-input normals, one per face.
    pub normals: &'a [DVec3],
    /// Global SoS index of face 0.
    pub base: u32,
    /// The rotation taking the polytope's reference normals to `normals`
    /// (`None`: identity), taken as exact.
    pub rotation: Option<&'a DMat3>,
}

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
    /// The arc of ring entry `i` of vertex `v`: from its face to the next.
    #[inline]
    fn ring_arc(&self, ring: &[RingEntry], i: usize) -> (FaceNormal<'a>, FaceNormal<'a>) {
        let f0 = ring[i].face;
        let f1 = ring[if i + 1 == ring.len() { 0 } else { i + 1 }].face;
        (self.normal(f0), self.normal(f1))
    }

    /// `true` when the direction `x` lies in the cell of vertex `v`
    /// (perturbed, so never on its boundary).
    #[inline]
    pub fn in_cell(&self, v: u32, x: &FaceNormal<'_>) -> bool {
        let ring = self.poly.ring(v as usize);
        (0..ring.len()).all(|i| {
            let (a, b) = self.ring_arc(ring, i);
            sos_det3(&a, &b, x).is_positive()
        })
    }

    /// The vertex whose cell contains `x`, by hill climbing from `start`
    /// (paper §4.2): cross the most violated arc of the current cell until
    /// none is violated. A step budget of `V` guards against cycling, after
    /// which an exhaustive exact scan answers. Returns the vertex and the
    /// number of steps.
    pub fn locate(&self, x: &FaceNormal<'_>, start: u32) -> (u32, usize) {
        let mut v = start;
        let limit = self.poly.vertex_count() + 1;
        let xv = x.approx;
        for steps in 0..limit {
            let ring = self.poly.ring(v as usize);
            let mut best: Option<(f64, u32)> = None;
            for i in 0..ring.len() {
                let (a, b) = self.ring_arc(ring, i);
                if !sos_det3(&a, &b, x).is_positive() {
                    let c = a.approx.cross(b.approx);
                    let depth = -c.dot(xv) / c.length();
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

    /// Walks the arc `a → b` of the other map through this map from the cell
    /// of `from` (which contains `a`) to the cell of `to` (which contains
    /// `b`), calling `cross(edge)` for every arc of this map it crosses, in
    /// order (paper §4.3). Returns the number of cells visited. The walk
    /// crosses each convex cell once, so it needs at most `E` steps;
    /// exceeding that is reported as an error.
    pub fn walk_arc(
        &self,
        a: &FaceNormal<'_>,
        b: &FaceNormal<'_>,
        from: u32,
        to: u32,
        mut cross: impl FnMut(u32),
    ) -> Result<usize, super::SumError> {
        let mut u = from;
        let mut came = u32::MAX;
        let mut steps = 0;
        while u != to {
            let ring = self.poly.ring(u as usize);
            let mut next = None;
            for i in 0..ring.len() {
                if ring[i].edge == came {
                    continue;
                }
                let (c, d) = self.ring_arc(ring, i);
                if arcs_cross(a, b, &c, &d) {
                    next = Some(ring[i]);
                    break;
                }
            }
            let Some(entry) = next else {
                return Err(super::SumError::Inconsistent(format!(
                    "arc walk found no exit from cell {u}"
                )));
            };
            cross(entry.edge);
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

/// `true` when the great arcs `a → b` and `c → d` (each shorter than π)
/// cross, under symbolic perturbation (so never a touching case): each arc
/// separates the other's endpoints, and `det[a, b, c] = −det[c, d, a]` picks
/// the crossing of the two great circles that lies on both arcs.
#[inline]
pub fn arcs_cross(
    a: &FaceNormal<'_>,
    b: &FaceNormal<'_>,
    c: &FaceNormal<'_>,
    d: &FaceNormal<'_>,
) -> bool {
    let s1 = sos_det3(a, b, c);
    let s2 = sos_det3(a, b, d);
    if s1 == s2 {
        return false;
    }
    let s3 = sos_det3(c, d, a);
    if s3 == s1 {
        return false;
    }
    let s4 = sos_det3(c, d, b);
    s3 != s4
}
