//! Support functions of the posed bodies: the vertex of a body farthest in
//! a direction, by hill climbing over the vertex adjacency from a warm
//! start ([`climb`]), and the *near-extreme set*, every vertex within a
//! margin of the farthest, with a rigorous bound on the farthest value
//! ([`near_max`]).
//!
//! # Why the near-extreme set is complete
//! Let `A` be the body posed exactly (`R v + t` with the float matrix `R`
//! taken as exact: an affine image of the body, with its face lattice) and
//! `A'` the rounded posed vertices, each within `η` of its exact value. For
//! a direction `d`, let `M` be the exact maximum of `d · v` over `A`, and
//! `err` bound the rounding of one float dot product `d · v'`.
//!
//! 1. From every vertex `w` that is not a maximum there is an edge path to a
//!    maximum along which `d · v` (exact) strictly increases (a linear
//!    function on a polytope has no other local maxima). Every vertex on it
//!    has a float value at least `fl(d · w') − 2(η|d| + err)`.
//! 2. For any `τ ≥ 0` the vertices with exact value `≥ M − τ` form a
//!    connected subgraph (an upper level set of a linear function on a
//!    convex polytope) that contains the maximum.
//!
//! [`near_max`] climbs to a local maximum, then searches breadth-first over
//! the vertices whose float value is at least the best float value seen so
//! far less `τ₀ = τ + 2(η|d| + err)`, raising the best as it goes. A vertex
//! never admitted was below a threshold that only rises, so the search ends
//! with every vertex of the final threshold's component containing the
//! best vertex, which by (1) contains an exact maximum, and by (2) every
//! vertex with exact value `≥ M − τ` (whose float value is at least
//! `M − τ − η|d| − err`, while the best float value is at most
//! `M + η|d| + err`). With `τ ≥ 2η|d|` the set also holds the maximiser of
//! the *rounded* vertices, so the best float value plus `err` bounds
//! `max d · v'` from above.

use crate::polytope::Polytope;
use glam::{DMat3, DVec3};

/// Marks over a body's vertices with a generation stamp, so that a search
/// clears nothing between uses.
#[derive(Clone, Debug, Default)]
pub(in crate::query) struct Marks {
    stamp: Vec<u32>,
    gen: u32,
}

impl Marks {
    /// Starts a new search over `n` vertices.
    pub(in crate::query) fn start(&mut self, n: usize) {
        if self.stamp.len() != n {
            self.stamp = vec![0; n];
            self.gen = 0;
        }
        self.gen = self.gen.wrapping_add(1);
        if self.gen == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.gen = 1;
        }
    }

    /// Whether `v` is marked.
    #[inline]
    pub(in crate::query) fn is_marked(&self, v: u32) -> bool {
        self.stamp[v as usize] == self.gen
    }

    /// Marks `v`; `false` if it was marked already.
    #[inline]
    pub(in crate::query) fn mark(&mut self, v: u32) -> bool {
        let s = &mut self.stamp[v as usize];
        if *s == self.gen {
            false
        } else {
            *s = self.gen;
            true
        }
    }
}

/// The vertex maximising `dir · v` found by climbing from `start`: move to
/// the first strictly better neighbour until none is better. Returns the
/// vertex and its value.
#[inline]
pub(in crate::query) fn climb(
    poly: &Polytope,
    at: impl Fn(u32) -> DVec3,
    dir: DVec3,
    start: u32,
) -> (u32, f64) {
    let mut v = start;
    let mut best = dir.dot(at(v));
    loop {
        let mut moved = false;
        for r in poly.ring(v as usize) {
            let d = dir.dot(at(r.neighbor));
            if d > best {
                best = d;
                v = r.neighbor;
                moved = true;
            }
        }
        if !moved {
            return (v, best);
        }
    }
}

/// [`climb`] over `poly`'s own vertices for a world direction `dir`, with
/// `to_body` the transpose of the body's rotation matrix: the direction is
/// turned into the body's frame once, and no vertex is posed. A pose's
/// translation adds the same to every vertex's value and a frame's power of
/// two scales them all alike, so in exact arithmetic this is the vertex
/// that climbing the posed vertices finds; in floats the two may differ
/// only between vertices whose values tie to rounding, and a support vertex
/// is a proposal that the callers' certificates check.
#[inline]
pub(in crate::query) fn climb_unposed(
    poly: &Polytope,
    to_body: &DMat3,
    dir: DVec3,
    start: u32,
) -> u32 {
    climb(poly, |v| poly.vertex(v as usize), *to_body * dir, start).0
}

/// A bound on the rounding of one float dot product `d · v'` with
/// `|v'_i| ≤ scale` (three products and two sums).
#[inline]
pub(in crate::query) fn dot_error(d: DVec3, scale: f64) -> f64 {
    4.0 * f64::EPSILON * (d.x.abs() + d.y.abs() + d.z.abs()) * scale + 1e-300
}

/// One dot product's rounding bound `err` along `dir` and the slack
/// `2(η|dir| + err)` a near-extreme search allows for (module docs; `eta`
/// bounds a posed vertex's rounding, `scale` its coordinates): shared by
/// the searches and by certificates that must give the same floats.
#[inline]
pub(in crate::query) fn search_slack(dir: DVec3, eta: f64, scale: f64) -> (f64, f64) {
    let err = dot_error(dir, scale);
    (err, 2.0 * (eta * dir.length() + err))
}

/// The result of [`near_max`].
#[derive(Clone, Copy, Debug)]
pub(in crate::query) struct NearMax {
    /// Its float value.
    pub value: f64,
    /// A rigorous upper bound on `max d · v'` over the rounded posed
    /// vertices.
    pub upper: f64,
    /// The threshold below the best value that the set covers: every vertex
    /// whose exact value is within `τ` of the exact maximum is in the set.
    pub tau: f64,
}

/// The near-extreme set of `poly` in direction `dir` (module docs): every
/// vertex whose exact posed value is within `tau` of the maximum, pushed
/// onto `set` (cleared first) with possibly a few more, found from `start`.
/// `eta` bounds the rounding of a posed vertex and `scale` its coordinates
/// (frame units).
#[allow(clippy::too_many_arguments)]
pub(in crate::query) fn near_max(
    poly: &Polytope,
    at: impl Fn(u32) -> DVec3,
    dir: DVec3,
    start: u32,
    tau: f64,
    eta: f64,
    scale: f64,
    marks: &mut Marks,
    set: &mut Vec<u32>,
) -> NearMax {
    let (best, tau0, err) = near_search(poly, &at, dir, start, tau, eta, scale, marks, set);
    // Keep only the final threshold's members (the others were admitted
    // under a lower one).
    set.retain(|&u| dir.dot(at(u)) >= best - tau0);
    NearMax {
        value: best,
        upper: best + err,
        tau: tau0 - 2.0 * (eta * dir.length() + err),
    }
}

/// [`near_max`]'s upper bound alone (its `upper` with `τ = 0`, bit for
/// bit): the largest float `fl(dir · v')` over *every* vertex plus `err`
/// (module docs: the set holds the maximiser of the rounded vertices), so
/// it depends only on `dir` and the posed vertices, not on `start` or the
/// adjacency. For a `start` near the maximum (a vertex of the facet whose
/// normal is `dir`), without the climb: the search alone, from `start`,
/// ends at a best vertex whose neighbours it has all seen, a float local
/// maximum, and from there the module docs' argument applies unchanged
/// (the increasing path to an exact maximum has float values at least the
/// best less `2(η|d| + err)`, above every threshold of the search, which
/// only rises to the best less `τ₀`).
#[allow(clippy::too_many_arguments)]
pub(in crate::query) fn near_max_upper(
    poly: &Polytope,
    at: impl Fn(u32) -> DVec3,
    dir: DVec3,
    start: u32,
    eta: f64,
    scale: f64,
    marks: &mut Marks,
    set: &mut Vec<u32>,
) -> f64 {
    let (err, slack) = search_slack(dir, eta, scale);
    let tau0 = slack + slack;
    let value = dir.dot(at(start));
    if let Some(best) = near_pair(poly, &at, dir, start, value, tau0) {
        return best + err;
    }
    let best = near_set(poly, &at, dir, start, value, tau0, marks, set);
    best + err
}

/// [`near_set`]'s result in its common cases, without its marks and list
/// (read by the independent review of 2026-12-01: when it answers, its
/// answer is the search's):
/// the search admits no neighbour of `start` (a vertex maximum), or exactly
/// one, `b`, and none of `b`'s (an edge). `None` when it would admit more
/// (then the search runs). The same vertices are read in the same order
/// against the same thresholds: a vertex the search has seen and not
/// admitted is skipped there, and read again here against a threshold no
/// lower (the best only rises), so it is not admitted here either; a NaN
/// is never admitted by either.
#[inline]
fn near_pair(
    poly: &Polytope,
    at: &impl Fn(u32) -> DVec3,
    dir: DVec3,
    start: u32,
    value: f64,
    tau0: f64,
) -> Option<f64> {
    let mut best = value;
    let mut admitted = None;
    for r in poly.ring(start as usize) {
        let x = dir.dot(at(r.neighbor));
        if x >= best - tau0 {
            if admitted.is_some() {
                return None;
            }
            admitted = Some(r.neighbor);
            if x > best {
                best = x;
            }
        }
    }
    let Some(b) = admitted else {
        return Some(best);
    };
    for r in poly.ring(b as usize) {
        if r.neighbor != start && dir.dot(at(r.neighbor)) >= best - tau0 {
            return None;
        }
    }
    Some(best)
}

/// The breadth-first search shared by [`near_max_upper`] and
/// [`near_search`]: from `start` (whose value is `best`), every vertex
/// reached through vertices within `tau0` of the best value seen is
/// admitted into `set`. Returns the best float value.
#[allow(clippy::too_many_arguments)]
#[inline]
fn near_set(
    poly: &Polytope,
    at: &impl Fn(u32) -> DVec3,
    dir: DVec3,
    start: u32,
    mut best: f64,
    tau0: f64,
    marks: &mut Marks,
    set: &mut Vec<u32>,
) -> f64 {
    marks.start(poly.vertex_count());
    set.clear();
    marks.mark(start);
    set.push(start);
    let mut i = 0;
    while i < set.len() {
        let v = set[i];
        i += 1;
        for r in poly.ring(v as usize) {
            let u = r.neighbor;
            if !marks.mark(u) {
                continue;
            }
            let x = dir.dot(at(u));
            if x >= best - tau0 {
                set.push(u);
                if x > best {
                    best = x;
                }
            }
        }
    }
    best
}

/// The search of [`near_max`]: the climb, then the breadth-first search
/// over the vertices within `τ₀` of the best (left in `set`, with some
/// admitted under a lower threshold). Returns the best float value, `τ₀`
/// and the dot products' error bound.
#[allow(clippy::too_many_arguments)]
#[inline]
fn near_search(
    poly: &Polytope,
    at: &impl Fn(u32) -> DVec3,
    dir: DVec3,
    start: u32,
    tau: f64,
    eta: f64,
    scale: f64,
    marks: &mut Marks,
    set: &mut Vec<u32>,
) -> (f64, f64, f64) {
    let (err, slack) = search_slack(dir, eta, scale);
    let tau0 = tau.max(slack) + slack;
    let (top, value) = climb(poly, at, dir, start);
    let best = near_set(poly, at, dir, top, value, tau0, marks, set);
    (best, tau0, err)
}

/// The `K` unit axes nearest a unit direction `v` among those offered (by
/// `axis · v`, largest first; ties keep the earlier), each with a payload:
/// the candidate separating axes tried when GJK's own direction is too
/// coarse (the exact query's and the motion search's feature axes).
pub(in crate::query) struct NearestAxes<T, const K: usize> {
    v: DVec3,
    best: [(f64, DVec3, T); K],
}

impl<T: Copy + Default, const K: usize> NearestAxes<T, K> {
    /// None kept yet.
    pub(in crate::query) fn new(v: DVec3) -> Self {
        NearestAxes {
            v,
            best: [(f64::NEG_INFINITY, DVec3::ZERO, T::default()); K],
        }
    }

    /// Offers the axis along `d` (any length; a zero or non-finite one is
    /// ignored).
    pub(in crate::query) fn offer(&mut self, d: DVec3, payload: T) {
        // Divided by its largest magnitude first, so that no square
        // underflows (an edge cross product of parts below 1e-77 has
        // subnormal squares, and its "unit" axis came out far from unit
        // length, which the gaps along it assume; found by the independent
        // review of 2026-11-30).
        let m = d.abs().max_element();
        if !(m > 0.0 && m.is_finite()) {
            return;
        }
        let d = d / m;
        let len = d.length();
        let d = d / len;
        let score = d.dot(self.v);
        if score > self.best[K - 1].0 {
            self.best[K - 1] = (score, d, payload);
            self.best.sort_by(|x, y| y.0.total_cmp(&x.0));
        }
    }

    /// Offers the unit axis `d` with its own `score` in place of `d · v`
    /// (kept when among the `K` largest).
    pub(in crate::query) fn offer_scored(&mut self, d: DVec3, score: f64, payload: T) {
        if score > self.best[K - 1].0 {
            self.best[K - 1] = (score, d, payload);
            self.best.sort_by(|x, y| y.0.total_cmp(&x.0));
        }
    }

    /// Every kept axis, largest score first.
    pub(in crate::query) fn kept(&self) -> impl Iterator<Item = (DVec3, T)> + '_ {
        self.best
            .iter()
            .filter(|(score, _, _)| *score > f64::NEG_INFINITY)
            .map(|&(_, d, t)| (d, t))
    }

    /// The kept axes facing `v` (`axis · v > 0`), nearest first.
    pub(in crate::query) fn facing(&self) -> impl Iterator<Item = (DVec3, T)> + '_ {
        self.best
            .iter()
            .filter(|(score, _, _)| *score > 0.0)
            .map(|&(_, d, t)| (d, t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::rotation::{Pose, Rotation};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// [`near_max_upper`] (with its mark-free common cases) is the largest
    /// float `dir · v'` over every posed vertex plus `err`, bit for bit,
    /// from any start: spheres (vertex and edge maxima), grids (exact ties
    /// along face normals and axes) and bodies far from the origin, along
    /// random directions, face normals and edge-perpendicular directions.
    #[test]
    fn the_upper_bound_is_the_largest_float_value_from_any_start() {
        let mut rng = ChaCha8Rng::seed_from_u64(35);
        let (mut marks, mut set) = (Marks::default(), Vec::new());
        let unit = |rng: &mut ChaCha8Rng| {
            DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
        };
        for case in 0..60 {
            let pts: Vec<[f64; 3]> = (0..20 + 3 * case)
                .map(|_| {
                    let v = unit(&mut rng);
                    match case % 3 {
                        0 => v.normalize_or_zero().to_array(),
                        1 => (v * 3.0).round().to_array(),
                        _ => (v * 1e-6 + DVec3::new(3e2, -1e2, 7e1)).to_array(),
                    }
                })
                .collect();
            let poly = Polytope::from_points(&pts).unwrap();
            let pose = if case % 2 == 0 {
                Pose::IDENTITY
            } else {
                Pose::new(
                    Rotation::from_axis_angle(unit(&mut rng), 1.0).unwrap(),
                    unit(&mut rng) * 10.0,
                )
            };
            let posed: Vec<DVec3> = (0..poly.vertex_count())
                .map(|v| pose.apply(poly.vertex(v)))
                .collect();
            let scale = posed
                .iter()
                .map(|p| p.abs().max_element())
                .fold(0.0, f64::max);
            let eta = 8.0 * f64::EPSILON * scale;
            let mut dirs: Vec<DVec3> = (0..poly.face_count())
                .map(|f| pose.rotation.apply(poly.unit_normal(f)))
                .collect();
            dirs.extend((0..poly.edge_count()).map(|e| {
                let [a, b] = poly.edge(e).vertices;
                let along = posed[b as usize] - posed[a as usize];
                along.cross(unit(&mut rng)).cross(along).normalize_or_zero()
            }));
            dirs.extend((0..20).map(|_| unit(&mut rng).normalize_or_zero()));
            for dir in dirs.into_iter().filter(|d| *d != DVec3::ZERO) {
                let best = posed.iter().map(|p| dir.dot(*p)).fold(f64::MIN, f64::max);
                let want = best + dot_error(dir, scale);
                // The lowest vertex (many neighbours above it), and random
                // ones.
                let lowest = (0..poly.vertex_count() as u32)
                    .min_by(|&a, &b| {
                        dir.dot(posed[a as usize])
                            .total_cmp(&dir.dot(posed[b as usize]))
                    })
                    .unwrap();
                let starts = [lowest, rng.random_range(0..poly.vertex_count() as u32)];
                for start in starts
                    .into_iter()
                    .chain((0..2).map(|_| rng.random_range(0..poly.vertex_count() as u32)))
                {
                    let got = near_max_upper(
                        &poly,
                        |v| posed[v as usize],
                        dir,
                        start,
                        eta,
                        scale,
                        &mut marks,
                        &mut set,
                    );
                    assert_eq!(
                        got.to_bits(),
                        want.to_bits(),
                        "case {case}, {dir}, from {start}"
                    );
                }
            }
        }
    }
}
