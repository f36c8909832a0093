//! The overlay of two Gaussian maps: the exact predicates and local searches
//! shared by every sum method and by the dynamic update.
//!
//! Paper §3–§4. A face normal `x` of one map lies in the cell of vertex `v`
//! of the other map iff it is strictly left of every arc of that cell
//! ([`GaussView::in_cell`]); two arcs cross iff each separates the other's
//! endpoints and they meet in the right hemisphere ([`edges_cross`]). Both use
//! [`sos_det3`](crate::kernel::predicates::sos_det3) with global indices (faces of P first, then faces of Q), so
//! exact ties — parallel faces, a normal on an arc, overlapping arcs — are
//! broken by one consistent symbolic perturbation and every method sees the
//! same generic overlay.
//!
//! Speed: `det[a, b, x]` for an arc `a → b` is `m · x` with the arc's
//! great-circle normal `m = a × b` precomputed accurately per edge
//! ([`crate::Polytope::arc_normals`]), so the common case is one dot product
//! and a certified error bound; only near-ties evaluate the exact normals.
//!
//! Exact ties (issue 8 §2: a box turning about a coordinate axis puts every
//! face normal of one box exactly on an arc or a vertex of the other's map,
//! some 80 ties per sum) are settled in three tiers, each exact:
//! 1. a [`TieCache`] shared by both maps of one pair of operands returns a
//!    tie already settled at this relative rotation (each recurs two or
//!    three times per sum);
//! 2. `GaussView::structural_tie` proves the determinant zero from the
//!    zero pattern of the vectors alone (no arithmetic) and reads the
//!    leading perturbation term off the certified arc normal or one
//!    certified 2×2 minor;
//! 3. otherwise the general symbolic perturbation decides.
//!
//! Tiers 1 and 2 are checked against tier 3 on every (arc, normal) pair of
//! axis-aligned, prismatic, slanted and zonotopal parts turning about each
//! axis (`tests::structural_ties_agree_with_symbolic_perturbation`).

use std::sync::atomic::{AtomicU64, Ordering};

use crate::kernel::bounds;
use crate::kernel::predicates::sos_det3_unfiltered;
use crate::kernel::Sign;
use crate::polytope::{rotated_error, FaceNormal, Polytope, RingEntry};
use glam::{DMat3, DVec3};

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
pub struct TieCache {
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
    fn key(of_q: bool, e: u32, x: u32) -> Option<u64> {
        (e < 1 << 30 && x < 1 << 31)
            .then_some(((of_q as u64) << 61) | ((e as u64) << 31) | x as u64)
    }

    #[inline]
    fn slot(&self, key: u64) -> &AtomicU64 {
        let h = key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - TIE_SLOTS.trailing_zeros());
        &self.slots[h as usize]
    }

    #[inline]
    fn get(&self, key: u64) -> Option<Sign> {
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
    fn put(&self, key: u64, s: Sign) {
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
    /// (`None`: identity, and then `normals` are the polytope's own,
    /// bit for bit), taken as exact.
    pub rotation: Option<&'a DMat3>,
    /// The memo of exact ties shared by both maps of one pair of operands
    /// (`None`: no memo).
    pub ties: Option<&'a TieCache>,
}

impl<'a> GaussView<'a> {
    /// Normal of face `f` as an exact predicate argument.
    #[inline]
    pub fn normal(&self, f: u32) -> FaceNormal<'a> {
        let approx = self.normals[f as usize];
        let err = self.poly.normal_error(f as usize);
        // Unrotated views hold the polytope's own normals, bit for bit
        // (`FaceNormal::zero_mask` reads exactness off them).
        debug_assert!(self.rotation.is_some() || approx == self.poly.normal(f as usize));
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
        let (m, em) = (self.arcs[e as usize], self.arc_errs[e as usize]);
        let (v, bound) = bounds::dot(m, em, x.approx, x.err);
        Sign::certified(v, bound).unwrap_or_else(|| self.tie_side(e, x))
    }

    /// [`GaussView::arc_side`] when the float filter cannot decide: the
    /// exact, perturbed sign, through the tie memo.
    #[cold]
    fn tie_side(&self, e: u32, x: &FaceNormal<'_>) -> Sign {
        let memo = self
            .ties
            .and_then(|t| Some((t, TieCache::key(self.base != 0, e, x.idx)?)));
        if let Some(s) = memo.and_then(|(t, k)| t.get(k)) {
            return s;
        }
        let (a, b) = self.edge_arc(e);
        let s = self
            .structural_tie(e, &a, &b, x)
            .unwrap_or_else(|| sos_det3_unfiltered(&a, &b, x));
        if let Some((t, k)) = memo {
            t.put(k, s);
        }
        s
    }

    /// The perturbed sign of `det[a, b, x]` for the arc `a → b` of edge `e`
    /// when the determinant is exactly zero by the zero pattern of the
    /// vectors (every component of `a × b` or of `x` is structurally zero:
    /// a normal on an arc under a rotation about a coordinate axis, or at
    /// the arc's end) and the leading perturbation terms decide; `None`
    /// otherwise (then the general symbolic perturbation decides).
    ///
    /// With the rows sorted by index `(v0, v1, v2)`, the leading terms of
    /// the perturbed determinant are the cofactors of row 0, i.e. the
    /// components of `v1 × v2` in the order z, y, x
    /// ([`crate::kernel::predicates::sos_det3`]). An arc joins two normals
    /// of one polytope and `x` belongs to the other, so `x` comes first or
    /// last:
    /// * first: `v1 × v2 = ±(a × b)` and the sort's parity cancels the sign,
    ///   so the answer is the sign of the first non-zero component of the
    ///   arc normal, read off its certified float value;
    /// * last: the terms are `b × x` (or `a × x`, with one transposition,
    ///   when `b` sorts first), evaluated with the same zero pattern and a
    ///   certified float filter; if that vanishes (`x` parallel to an end
    ///   of the arc) the general path decides.
    #[inline]
    fn structural_tie(
        &self,
        e: u32,
        a: &FaceNormal<'_>,
        b: &FaceNormal<'_>,
        x: &FaceNormal<'_>,
    ) -> Option<Sign> {
        use crate::kernel::predicates::ExactVector;
        let (za, zb, zx) = (a.zero_mask(), b.zero_mask(), x.zero_mask());
        // Component c of u × w is u_i w_j − u_j w_i, (i, j) cyclic after c.
        let cross_zero = |zu: u8, zw: u8| -> u8 {
            (0..3).fold(0, |m, c| {
                let (i, j) = ((c + 1) % 3, (c + 2) % 3);
                let bit = |z: u8, k: usize| z >> k & 1 != 0;
                let zero = (bit(zu, i) || bit(zw, j)) && (bit(zu, j) || bit(zw, i));
                m | u8::from(zero) << c
            })
        };
        if cross_zero(za, zb) | zx != 0b111 {
            return None;
        }
        if x.idx < a.idx.min(b.idx) {
            let (m, em) = (self.arcs[e as usize], self.arc_errs[e as usize]);
            let known_zero = cross_zero(za, zb);
            return [2, 1, 0]
                .into_iter()
                .find(|&c| known_zero >> c & 1 == 0)
                .and_then(|c| Sign::certified(m[c], em));
        }
        if x.idx < a.idx.max(b.idx) {
            return None;
        }
        let (hi, zh, flip) = if a.idx < b.idx {
            (b, zb, false)
        } else {
            (a, za, true)
        };
        let known_zero = cross_zero(zh, zx);
        let (u, w) = (hi.approx, x.approx);
        let (eu, ew) = (hi.err, x.err);
        for c in [2, 1, 0] {
            if known_zero >> c & 1 != 0 {
                continue;
            }
            let (i, j) = ((c + 1) % 3, (c + 2) % 3);
            let (d, bound) = bounds::minor(u, eu, w, ew, i, j);
            let s = Sign::certified(d, bound)?;
            return Some(if flip { s.flip() } else { s });
        }
        None
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::predicates::sos_det3;
    use crate::sum::Operands;
    use crate::{Pose, Rotation};

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
