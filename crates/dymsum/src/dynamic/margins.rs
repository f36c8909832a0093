//! Certified margins (paper §4.1, the float side of FindErrors): how far a
//! face normal is from leaving its cell of the other map.
//!
//! * `arc_normals`: unit normals of every ring arc's great circle, oriented
//!   into the cell, from the polytope's accurate arc normals;
//! * `margin`: `min m · x` over the arcs of a cell, a lower bound of the sine
//!   of the distance from `x` to the cell's boundary (negative outside);
//! * `locate_certified`: hill climbing in floats that gives up (to the exact
//!   `GaussView::locate`) as soon as a decision is within its bound of zero;
//! * `single_crossing`: the arc a moving normal certainly crossed, and only
//!   it (the "exactly one event" case of the module docs).
//!
//! Complexity: O(degree) per margin, O(path · degree) per location.
//! Degeneracies: exact ties have margin 0 and are left to the exact path.

use super::*;

/// Unit normals of the great circles of every ring arc, in the reference
/// frame, laid out like the rings and oriented so that the cell is on the
/// positive side. Taken from the polytope's accurate arc normals (not from
/// a float cross product of unit normals, which is meaningless for the
/// very short arcs between nearly coplanar faces).
pub(super) fn arc_normals(poly: &Polytope) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(poly.ring_len_total());
    for v in 0..poly.vertex_count() {
        for r in poly.ring(v) {
            let m = poly.arc_normals()[r.edge as usize].normalize_or_zero();
            let forward = poly.edge(r.edge as usize).faces[0] == r.face;
            out.push(if forward { m } else { -m });
        }
    }
    out
}

/// Per face, a bound on the angle between the float unit normal (also
/// after a rotation) and the exact normal's direction.
pub(super) fn direction_errors(poly: &Polytope) -> Vec<f64> {
    (0..poly.face_count())
        .map(|f| 1.01 * poly.normal_error(f) / poly.normal(f).length() + 1e-14)
        .collect()
}

/// `min m · x` over the arcs of the cell of `v` (a lower bound of the sine of
/// the distance from `x` to the cell's boundary; negative when outside).
#[inline]
pub(super) fn margin(poly: &Polytope, arcs: &[DVec3], v: u32, x: DVec3) -> f64 {
    let off = poly.ring_offset(v as usize);
    // A plain comparison (arcs and normals are finite): the same least
    // value as `f64::min`, without its NaN handling.
    let mut least = f64::INFINITY;
    for m in &arcs[off..off + poly.degree(v as usize)] {
        let d = m.dot(x);
        if d < least {
            least = d;
        }
    }
    least
}

/// Below this float margin (plus the face's direction error) the exact
/// predicate decides.
pub(super) const EXACT_BELOW: f64 = 1e-12;
/// Slack added to the drift bound to cover float error in margins.
pub(super) const SLACK: f64 = 1e-10;

/// Where [`locate_certified`] ended: the cell, `x`'s [`margin`] in it, and
/// the least value of `x` on the cell's arcs other than the one shared with
/// the start cell (the new side of [`single_crossing`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct Located {
    pub(super) cell: u32,
    pub(super) margin: f64,
    pub(super) least_off_start: f64,
}

/// Hill climbing in floats on the unit ring arcs (oriented inwards): cross
/// the most violated arc until every arc is clearly satisfied. Returns the
/// cell and `x`'s [`margin`] in it (the same value: the same products,
/// least taken exactly) with the least of them off the arc shared with
/// `start` ([`Located`]), or `None` as soon as a decision is within `thr`
/// of zero (the exact [`GaussView::locate`] takes over) or after `V`
/// steps.
pub(super) fn locate_certified(
    poly: &Polytope,
    arcs: &[DVec3],
    x: DVec3,
    thr: f64,
    start: u32,
) -> Option<Located> {
    let mut v = start;
    for _ in 0..poly.vertex_count() {
        let off = poly.ring_offset(v as usize);
        let ring = poly.ring(v as usize);
        let mut worst = (thr, u32::MAX);
        let mut least = f64::INFINITY;
        let mut least_off_start = f64::INFINITY;
        for (i, r) in ring.iter().enumerate() {
            let s = arcs[off + i].dot(x);
            // Also a NaN (a NaN rotation) goes to the exact path.
            let clear = s.abs() > thr;
            if !clear {
                return None;
            }
            if s < -worst.0 {
                worst = (-s, r.neighbor);
            }
            if s < least {
                least = s;
            }
            if s < least_off_start && r.neighbor != start {
                least_off_start = s;
            }
        }
        if worst.1 == u32::MAX {
            return Some(Located {
                cell: v,
                margin: least,
                least_off_start,
            });
        }
        v = worst.1;
    }
    None
}

/// The arc a moving normal certainly crossed, and only it: the old cell `v`
/// and new cell `w` are adjacent across arc `x`, the old position is farther
/// than `reach` from every other arc of `v` and the new one from every other
/// arc of `w`. Then the path (no longer than `reach`) stays in `v ∪ w`,
/// whose common boundary is `x`, and meets `x`'s great circle at most twice
/// (a small circle meets a great circle in at most two points) and an odd
/// number of times: exactly once. `new_side`, where known, is the least
/// value of `x_new` on the arcs of `w` other than `x` ([`Located`]'s
/// `least_off_start`: the same products), which settles the new side
/// without recomputing them.
pub(super) fn single_crossing(
    poly: &Polytope,
    arcs: &[DVec3],
    (v, x_old): (u32, DVec3),
    (w, x_new): (u32, DVec3),
    reach: f64,
    new_side: Option<f64>,
) -> Option<u32> {
    let x = poly.ring(v as usize).iter().find(|r| r.neighbor == w)?.edge;
    let clear = |cell: u32, pos: DVec3| {
        let off = poly.ring_offset(cell as usize);
        poly.ring(cell as usize)
            .iter()
            .enumerate()
            .all(|(i, r)| r.edge == x || arcs[off + i].dot(pos) > reach)
    };
    let new_clear = new_side.map_or_else(|| clear(w, x_new), |least| least > reach);
    debug_assert_eq!(new_clear, clear(w, x_new), "the located cell's values");
    (clear(v, x_old) && new_clear).then_some(x)
}
