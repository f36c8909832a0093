//! Whether a point lies inside a body, exactly: the winding number of its
//! enclosing triangles about the point (the signed count of a ray's
//! crossings with them) is not zero.
//!
//! Precondition: the point is on no triangle of the body (the scenes'
//! checker asks only after finding that no triangles of the two bodies
//! meet, and the point is a corner of one of them). A point in a classified
//! cell of the body's [`super::inside_grid`] is answered from the cell
//! instead, with the same answer (that module's docs).
//!
//! The ray is the segment from `p` to `q = p + L d`, `L` large enough that
//! `q` lies outside the body's box. It *crosses* triangle `abc` when `p`
//! and `q` lie strictly on opposite sides of its plane
//! (`orient3d(a, b, c, ·)` of opposite nonzero signs) and the line `pq`
//! passes strictly inside it (`orient3d(p, q, a, b)`, `(p, q, b, c)`,
//! `(p, q, c, a)` of one nonzero sign). It misses when the plane's signs
//! agree or one is zero (`p` in the plane but off the triangle, by the
//! precondition; `q` in the plane but outside the box), or when the edge
//! signs disagree strictly. Anything else (the segment in the plane, or
//! through an edge or a corner) is *degenerate*, and the next of a fixed
//! list of directions is tried. A crossing counts the triangle's weight
//! (how many coincident copies of it enclose) with a `+` sign when `p` lies
//! on its positive side (`orient3d(a, b, c, p) > 0`) and a `−` sign
//! otherwise. Each solid component is a cycle (every edge, split at the
//! vertices on it, run as often each way: [`crate::solid::soup`]), so the
//! signed count of a ray that is not degenerate and ends outside the
//! component's box is its winding number about `p`, the same for every such
//! ray; a component whose box does not hold `p` has winding number zero
//! there and is not counted. The point is inside when the winding number
//! of some body is not zero: a scene joins its obstacles into one body, and
//! each obstacle's components are summed by themselves (one obstacle's
//! inward shell, winding `−1` and inside it, must not cancel another
//! obstacle's solid around the same point). With every sign exact the answer is exact. A
//! point for which all directions are degenerate gets no answer from the
//! ray (`inside_by_ray` returns `None`; the queries then return
//! `QueryError::OutOfRange` naming it), never a guess; `inside_solid`
//! answers from a classified cell of the grid whatever that point's own
//! rays do.
//!
//! # Second reading (2026-11-28)
//! An independent review found the cycle argument sound (every solid
//! component closed edge for edge, weights included, so posing keeps it a
//! cycle; `tests/review_cycle_balance.rs` checks it on 100,000 random grid
//! soups) and one wrong answer, mended: a scene joins its obstacles, and a
//! sum over all of them let one obstacle's inward shell (winding `−1`,
//! inside it) cancel another's solid around the same point
//! (`tests/review_joined_winding.rs`); each obstacle is now summed by
//! itself. A triangle that posing rounds to collinear corners no longer
//! makes every ray through its box degenerate.

use glam::DVec3;

use crate::body::MeshBody;
use crate::kernel::predicates::{orient, Sign};
use crate::solid::aabb::Aabb;
use crate::solid::collinear;

/// The ray directions, tried in turn: nearly along each axis (thin ray
/// boxes for the tree), skewed by irrational-looking amounts so that
/// axis-aligned models rarely make a ray degenerate.
const DIRECTIONS: [[f64; 3]; 12] = [
    [1.0, 0.001_236_067_977, 0.000_707_106_781],
    [-1.0, 0.000_577_350_269, -0.001_414_213_562],
    [0.000_866_025_403, 1.0, 0.001_118_033_988],
    [-0.001_316_074_012, -1.0, 0.000_543_516_413],
    [0.000_693_147_180, -0.000_301_029_995, 1.0],
    [-0.000_271_828_182, 0.001_732_050_807, -1.0],
    [1.0, 0.618_033_988_749, 0.414_213_562_373],
    [-0.723_606_797_749, 1.0, -0.302_775_637_731],
    [0.267_949_192_431, -0.577_350_269_189, 1.0],
    [-1.0, -0.381_966_011_250, 0.732_050_807_568],
    [0.449_489_742_783, -1.0, -0.645_751_311_064],
    [-0.162_277_660_168, 0.236_067_977_499, -1.0],
];

/// The outcome of one ray against one triangle.
#[derive(PartialEq)]
enum Crossing {
    /// Crosses, with `p` on the triangle's positive side (`true`) or not.
    Crosses(bool),
    Misses,
    Degenerate,
}

fn crossing(p: DVec3, q: DVec3, t: [DVec3; 3]) -> Crossing {
    let (sp, sq) = (orient(t[0], t[1], t[2], p), orient(t[0], t[1], t[2], q));
    if sp == Sign::Zero && sq == Sign::Zero {
        // A triangle that posing rounded to collinear corners has no
        // inside to cross (its edges are other triangles' too, and they
        // still flag a ray through them); else the segment lies in the
        // plane.
        if collinear(t[0].to_array(), t[1].to_array(), t[2].to_array()) {
            return Crossing::Misses;
        }
        return Crossing::Degenerate;
    }
    if sp == sq || sp == Sign::Zero || sq == Sign::Zero {
        return Crossing::Misses;
    }
    let e = [
        orient(p, q, t[0], t[1]),
        orient(p, q, t[1], t[2]),
        orient(p, q, t[2], t[0]),
    ];
    let has = |s: Sign| e.contains(&s);
    if has(Sign::Positive) && has(Sign::Negative) {
        Crossing::Misses
    } else if has(Sign::Zero) {
        Crossing::Degenerate
    } else {
        Crossing::Crosses(sp == Sign::Positive)
    }
}

impl MeshBody {
    /// Whether `p` (in the body's frame, on none of its triangles) lies
    /// where the winding number of its enclosing triangles is not zero,
    /// exactly ([`super::winding`]): read from the body's grid where it
    /// knows ([`super::inside_grid`]), else by a ray. `parity` is a scratch
    /// buffer.
    pub(crate) fn inside_solid(&self, p: DVec3, parity: &mut Vec<u8>) -> Option<bool> {
        match self.inside_grid().classify(p, 0.0) {
            Some(inside) => Some(inside),
            None => self.inside_by_ray(p, parity),
        }
    }

    /// [`MeshBody::inside_solid`] by a ray alone (the grid's own regions
    /// are classified by it).
    pub(crate) fn inside_by_ray(&self, p: DVec3, parity: &mut Vec<u8>) -> Option<bool> {
        let mut candidates = Vec::new();
        let at = p.to_array();
        self.solid_tree
            .for_each_meeting(&Aabb { lo: at, hi: at }, |k| {
                candidates.push(self.solid_components[k])
            });
        let (boxes, bounds) = (self.tree().boxes(), self.tree().bounds());
        inside_solid(
            self,
            |v| self.vertices[v as usize],
            |n| bounds[n],
            |t| boxes[t],
            |c| self.component_boxes[c],
            &candidates,
            p,
            parity,
        )
    }
}

/// Whether `p` lies inside a solid among the `candidates` components of
/// `body` (those whose box holds `p`; the others wind zero times about
/// it), exactly (module docs; `p` on no triangle of the body), with the
/// body's vertex `v` at `vertex(v)`, and boxes holding what the tree's node
/// `n`, triangle `t` and component `c` hold there: `node_box(n)`,
/// `item_box(t)`, `component_box(c)` (boxes larger than the exact ones
/// only make the walk reach more triangles; each is then decided exactly).
/// The ray leaves the candidates' joint box the shortest way first;
/// `None` when every direction is degenerate. `parity` is a scratch buffer
/// marking the candidates (all zero between calls).
#[allow(clippy::too_many_arguments)]
pub(crate) fn inside_solid(
    body: &MeshBody,
    vertex: impl Fn(u32) -> DVec3,
    node_box: impl Fn(usize) -> Aabb,
    item_box: impl Fn(usize) -> Aabb,
    component_box: impl Fn(usize) -> Aabb,
    candidates: &[u32],
    p: DVec3,
    parity: &mut Vec<u8>,
) -> Option<bool> {
    if candidates.is_empty() {
        return Some(false);
    }
    let joint = candidates
        .iter()
        .fold(Aabb::EMPTY, |b, &c| b.join(&component_box(c as usize)));
    let span = (0..3)
        .map(|k| joint.hi[k] - joint.lo[k])
        .fold(0.0, f64::max);
    // The distance to leave the joint box along each direction's main axis.
    let exit = |d: &[f64; 3]| {
        let k = (0..3)
            .max_by(|&i, &j| d[i].abs().total_cmp(&d[j].abs()))
            .unwrap_or(0);
        if d[k] > 0.0 {
            joint.hi[k] - p[k]
        } else {
            p[k] - joint.lo[k]
        }
    };
    let mut order = DIRECTIONS.map(|d| (exit(&d), d));
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    let order = order.map(|(_, d)| d);
    if parity.len() < body.components.len() {
        parity.resize(body.components.len(), 0);
    }
    let out = 'directions: {
        for d in order {
            let length = 2.0 * (exit(&d) + span * 0.002) + 1e-300;
            let q = p + DVec3::from(d) * length;
            if joint.holds(q.to_array()) {
                continue; // not far enough (only at the limits of f64)
            }
            let ray = Aabb {
                lo: p.min(q).to_array(),
                hi: p.max(q).to_array(),
            };
            for &c in candidates {
                parity[c as usize] = 1;
            }
            let mut degenerate = false;
            // The winding number of each body the candidates came from
            // (a joined scene's obstacles each count by themselves: one's
            // inward shell must not cancel another's solid).
            let mut winding: Vec<(u32, i64)> = Vec::new();
            body.tree()
                .for_each_meeting_with(&node_box, &item_box, &ray, |t| {
                    let c = body.component_of[t] as usize;
                    if degenerate || parity[c] == 0 {
                        return;
                    }
                    let tri = body.triangles[t].map(&vertex);
                    match crossing(p, q, tri) {
                        Crossing::Crosses(positive) => {
                            let w = i64::from(body.weights[t]);
                            let source = body.source_of[c];
                            let at = match winding.iter().position(|e| e.0 == source) {
                                Some(i) => i,
                                None => {
                                    winding.push((source, 0));
                                    winding.len() - 1
                                }
                            };
                            winding[at].1 += if positive { w } else { -w };
                        }
                        Crossing::Misses => {}
                        Crossing::Degenerate => degenerate = true,
                    }
                });
            for &c in candidates {
                parity[c as usize] = 0;
            }
            if !degenerate {
                break 'directions Some(winding.iter().any(|e| e.1 != 0));
            }
        }
        None
    };
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::PolygonMesh;

    fn cube(lo: f64, hi: f64) -> PolygonMesh {
        let corners: Vec<[f64; 3]> = (0..8)
            .map(|i| {
                let pick = |k: usize| if i >> k & 1 == 0 { lo } else { hi };
                [pick(0), pick(1), pick(2)]
            })
            .collect();
        crate::polytope::Polytope::from_points(&corners)
            .unwrap()
            .to_mesh()
    }

    fn inside(body: &MeshBody, p: [f64; 3]) -> bool {
        body.inside_solid(p.into(), &mut Vec::new()).unwrap()
    }

    #[test]
    fn nested_cubes_and_points_on_their_axes() {
        // Two nested solid cubes (each a solid): inside either counts.
        let mut m = cube(0.0, 4.0);
        let inner = cube(1.0, 3.0);
        let base = m.vertices.len();
        m.vertices.extend(inner.vertices);
        m.faces.extend(
            inner
                .faces
                .iter()
                .map(|f| f.iter().map(|v| v + base).collect()),
        );
        let body = MeshBody::new(&m).unwrap();
        assert_eq!(body.report().solids, 2);
        // Points level with edges and corners (axis-aligned rays would be
        // degenerate for many of them).
        for p in [
            [0.5, 0.5, 0.5],
            [2.0, 2.0, 2.0],
            [0.5, 1.0, 3.0],
            [3.5, 2.0, 1.0],
        ] {
            assert!(inside(&body, p), "{p:?}");
        }
        for p in [
            [-1.0, 1.0, 1.0],
            [5.0, 0.0, 0.0],
            [2.0, 2.0, 4.5],
            [4.0 + 1e-12, 1.0, 1.0],
        ] {
            assert!(!inside(&body, p), "{p:?}");
        }
    }
}
