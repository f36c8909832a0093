//! A memo of exact ties for one relative rotation ([`TieCache`]), and the
//! tests that check the tie tiers of [`super::GaussView::arc_side`] against
//! the general symbolic perturbation.

use std::sync::atomic::{AtomicU64, Ordering};

use crate::kernel::Sign;

/// Number of slots of a [`TieCache`].
const TIE_SLOTS: usize = 128;

/// A memo of exact ties between an arc of one map and a normal of the
/// other, for one relative rotation: the symbolic-perturbation outcome of
/// each tie is computed once, however often the searches meet it again (a
/// box turning about a coordinate axis meets each of its ties two or three
/// times per sum).
///
/// Direct-mapped, fixed size, no allocation: each slot packs the tie's key
/// (which map the arc belongs to, the edge, the normal's global index) and
/// its sign into one atomic word, so a lookup never sees a torn entry and
/// the operands stay `Send + Sync`. A collision only evicts. The owner
/// clears it whenever the relative rotation changes.
pub(crate) struct TieCache {
    slots: [AtomicU64; TIE_SLOTS],
}

impl TieCache {
    /// An empty cache.
    pub fn new() -> TieCache {
        TieCache {
            slots: std::array::from_fn(|_| AtomicU64::new(0)),
        }
    }

    /// Forgets every tie (the relative rotation changed).
    pub fn clear(&mut self) {
        for s in &mut self.slots {
            *s.get_mut() = 0;
        }
    }

    /// The key of arc `e` of the P map (`of_q == false`) or the Q map and
    /// normal `x`, or `None` when the indices do not fit the packing.
    #[inline]
    pub(super) fn key(of_q: bool, e: u32, x: u32) -> Option<u64> {
        (e < 1 << 30 && x < 1 << 31)
            .then_some(((of_q as u64) << 61) | ((e as u64) << 31) | x as u64)
    }

    #[inline]
    fn slot(&self, key: u64) -> &AtomicU64 {
        let h = key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - TIE_SLOTS.trailing_zeros());
        &self.slots[h as usize]
    }

    #[inline]
    pub(super) fn get(&self, key: u64) -> Option<Sign> {
        let v = self.slot(key).load(Ordering::Relaxed);
        if v >> 2 != key {
            return None;
        }
        match v & 3 {
            1 => Some(Sign::Negative),
            2 => Some(Sign::Positive),
            _ => None,
        }
    }

    #[inline]
    pub(super) fn put(&self, key: u64, s: Sign) {
        let code = match s {
            Sign::Negative => 1,
            Sign::Positive => 2,
            Sign::Zero => return,
        };
        self.slot(key).store(key << 2 | code, Ordering::Relaxed);
    }
}

impl Default for TieCache {
    fn default() -> Self {
        TieCache::new()
    }
}

impl Clone for TieCache {
    fn clone(&self) -> Self {
        TieCache {
            slots: std::array::from_fn(|i| AtomicU64::new(self.slots[i].load(Ordering::Relaxed))),
        }
    }
}

impl std::fmt::Debug for TieCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let used = self
            .slots
            .iter()
            .filter(|s| s.load(Ordering::Relaxed) != 0)
            .count();
        write!(f, "TieCache {{ {used} ties }}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::predicates::sos_det3;
    use crate::kernel::rotation::Pose;
    use crate::kernel::rotation::Rotation;
    use crate::polytope::Polytope;
    use crate::sum::Operands;
    use glam::DVec3;

    fn hull(points: &[[f64; 3]]) -> Polytope {
        Polytope::from_points(points).unwrap()
    }

    fn boxed(x: f64, y: f64, z: f64) -> Polytope {
        let mut pts = Vec::new();
        for i in 0..8 {
            let s = |b: usize| if i >> b & 1 == 1 { 1.0 } else { -1.0 };
            pts.push([s(0) * x, s(1) * y, s(2) * z]);
        }
        hull(&pts)
    }

    /// Axis-aligned and slanted parts: a box, a prism over an integer
    /// polygon (side normals in the xy plane, not on an axis), an
    /// octahedron-like hull (no zero normal components), a zonotope with
    /// generators along x, (1, 0, −1) and (0, 1, 1).
    fn shapes() -> Vec<Polytope> {
        let prism: Vec<[f64; 3]> = [[0.0, 0.0], [3.0, 1.0], [2.0, 3.0], [-1.0, 2.0]]
            .iter()
            .flat_map(|&[x, y]| [[x, y, -1.0], [x, y, 2.0]])
            .collect();
        let octa = [
            [2.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 3.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -2.0],
        ];
        let gens = [[1.0, 0.0, 0.0], [1.0, 0.0, -1.0], [0.0, 1.0, 1.0]];
        let zono: Vec<[f64; 3]> = (0..8)
            .map(|i| {
                let mut p = [0.0; 3];
                for (b, g) in gens.iter().enumerate() {
                    let s = if i >> b & 1 == 1 { 1.0 } else { -1.0 };
                    for k in 0..3 {
                        p[k] += s * g[k];
                    }
                }
                p
            })
            .collect();
        vec![
            boxed(0.5, 1.0, 1.5),
            boxed(1.0, 0.5, 0.5),
            hull(&prism),
            hull(&octa),
            hull(&zono),
        ]
    }

    /// Checks every (arc, normal) pair of both maps: where the structural
    /// tie rule answers, it equals the general symbolic perturbation.
    /// Returns how many pairs it answered.
    fn check_pairs(ops: &Operands) -> usize {
        let mut answered = 0;
        for (arcs, normals) in [(ops.view_p(), ops.view_q()), (ops.view_q(), ops.view_p())] {
            for e in 0..arcs.poly.edge_count() as u32 {
                let (a, b) = arcs.edge_arc(e);
                for f in 0..normals.poly.face_count() as u32 {
                    let x = normals.normal(f);
                    if let Some(s) = arcs.structural_tie(e, &a, &b, &x) {
                        assert_eq!(s, sos_det3(&a, &b, &x), "edge {e}, normal {f}");
                        answered += 1;
                    }
                    assert_eq!(arcs.arc_side(e, &x), sos_det3(&a, &b, &x));
                }
            }
        }
        answered
    }

    #[test]
    fn structural_ties_agree_with_symbolic_perturbation() {
        let shapes = shapes();
        let mut answered = 0;
        for p in &shapes {
            for q in &shapes {
                for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
                    for k in 0..24 {
                        let angle = std::f64::consts::TAU * k as f64 / 24.0;
                        let pose =
                            Pose::new(Rotation::from_axis_angle(axis, angle).unwrap(), DVec3::ZERO);
                        answered += check_pairs(&Operands::new(p, pose, q, Pose::IDENTITY));
                    }
                }
            }
        }
        assert!(
            answered > 1000,
            "only {answered} ties answered structurally"
        );
    }

    #[test]
    fn tie_cache_keeps_what_it_is_given() {
        let mut t = TieCache::new();
        let k = TieCache::key(true, 7, 11).unwrap();
        assert_eq!(t.get(k), None);
        t.put(k, Sign::Negative);
        assert_eq!(t.get(k), Some(Sign::Negative));
        assert_eq!(t.get(TieCache::key(false, 7, 11).unwrap()), None);
        assert_eq!(TieCache::key(false, 1 << 30, 0), None);
        t.clear();
        assert_eq!(t.get(k), None);
    }
}
