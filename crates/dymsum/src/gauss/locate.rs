//! Locating a direction in the other map (paper §4.2): the vertex whose
//! cell contains it, by hill climbing across the most violated arc, with an
//! exhaustive exact scan as a guard against cycling. O(path · degree)
//! exact predicates; exact ties are broken by the same symbolic
//! perturbation as everywhere else, so the cells tile the sphere.

use super::GaussView;
use crate::polytope::FaceNormal;

impl GaussView<'_> {
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
                    let m = self.arc(ring[i].edge);
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
}
