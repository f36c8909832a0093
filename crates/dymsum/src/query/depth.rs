//! Penetration depth from the facets of `D = A ⊕ (−B)`, and the dispatch to
//! the distance computation when the origin lies outside `D`.
//!
//! Every facet label of the overlay gives a candidate direction `n` (computed
//! from the original bodies' features, see the module docs of
//! [`crate::query`] for why) and its support value
//! `h(n) = h_A(n) + h_B(−n)`, each support found by a hill climb from the
//! facet's feature, so `h(n)` is a true support value of `D` up to rounding
//! even where the float direction is inaccurate. The minimum over all
//! candidates is the distance from the origin to `D`'s boundary when the
//! origin is inside (every facet normal is a candidate and every candidate
//! is an upper bound).
//!
//! Branch and bound: the value at the facet's own features, `h₀ ≤ h`, costs
//! two dot products. Only candidates with `h₀` within the tie tolerance of
//! the best refined value (or of zero, for the separation) are refined by
//! the hill climbs; every other candidate has `h > best + tol`, so it can
//! neither win nor tie nor face the origin, and the answer is the same as
//! refining all of them.

use super::distance::{line_line, separation};
use super::{Contact, ConvexPair, FeaturePair, Proximity, QueryError, Separation};
use crate::kernel::exact;
use crate::polytope::Polytope;
use crate::sum::Overlay;
use crate::Pose;
use glam::DVec3;

/// One candidate direction.
#[derive(Clone, Copy, Debug)]
pub(super) struct Candidate {
    pub features: FeaturePair,
    /// Unit direction, from A towards B.
    pub n: DVec3,
    /// `h_A(n) + h_B(−n)`.
    pub h: f64,
}

/// The posed vertices of both bodies.
pub(super) struct Posed {
    pub a: Vec<DVec3>,
    pub b: Vec<DVec3>,
    /// Rotated unit face normals of A and B.
    pub na: Vec<DVec3>,
    pub nb: Vec<DVec3>,
    pub pose_a: Pose,
    pub pose_b: Pose,
}

/// `max dir · v` over the posed vertices of `poly`, by a hill climb from the
/// best of `starts` (first one wins ties), moving to the first strictly
/// better neighbour until none is better.
fn support(poly: &Polytope, posed: &[DVec3], dir: DVec3, starts: &[u32]) -> f64 {
    let mut v = starts[0];
    let mut best = dir.dot(posed[v as usize]);
    for &s in &starts[1..] {
        let d = dir.dot(posed[s as usize]);
        if d > best {
            best = d;
            v = s;
        }
    }
    loop {
        let mut moved = false;
        for r in poly.ring(v as usize) {
            let d = dir.dot(posed[r.neighbor as usize]);
            if d > best {
                best = d;
                v = r.neighbor;
                moved = true;
            }
        }
        if !moved {
            return best;
        }
    }
}

/// Replaces the lower bounds `h₀` by true support values where they matter
/// (see the module docs) and returns those candidates.
fn refine(pair: &ConvexPair, posed: &Posed, mut cands: Vec<Candidate>, tol: f64) -> Vec<Candidate> {
    let (a, b) = (&pair.a, &pair.b);
    let climb = |c: &Candidate| -> f64 {
        let (sa, sb): (Vec<u32>, Vec<u32>) = match c.features {
            FeaturePair::FaceVertex { a_face, b_vertex } => {
                (a.face(a_face as usize).to_vec(), vec![b_vertex])
            }
            FeaturePair::VertexFace { a_vertex, b_face } => {
                (vec![a_vertex], b.face(b_face as usize).to_vec())
            }
            FeaturePair::EdgeEdge { a_edge, b_edge } => (
                a.edge(a_edge as usize).vertices.to_vec(),
                b.edge(b_edge as usize).vertices.to_vec(),
            ),
        };
        support(a, &posed.a, c.n, &sa) + support(b, &posed.b, -c.n, &sb)
    };
    let Some(first) = (0..cands.len()).min_by(|&i, &j| cands[i].h.total_cmp(&cands[j].h)) else {
        return cands;
    };
    let mut refined = vec![false; cands.len()];
    cands[first].h = climb(&cands[first]);
    refined[first] = true;
    let mut best = cands[first].h;
    for i in 0..cands.len() {
        if !refined[i] && cands[i].h <= (best + tol).max(tol) {
            cands[i].h = climb(&cands[i]);
            refined[i] = true;
            best = best.min(cands[i].h);
        }
    }
    cands
        .into_iter()
        .zip(refined)
        .filter_map(|(c, r)| r.then_some(c))
        .collect()
}

/// The candidates of all facets of the overlay (P = A, Q = −B), with the
/// lower bounds `h₀` as values.
fn candidates(pair: &ConvexPair, posed: &Posed, overlay: &Overlay) -> Vec<Candidate> {
    let (a, b, r) = (&pair.a, &pair.b, &pair.neg_b);
    let (na, nb) = (&posed.na, &posed.nb);
    let mut out = Vec::with_capacity(overlay.len() + 4);
    // The lower bound h₀ at the facet's own features (refined later).
    let value = |n: DVec3, sa: &[u32], sb: &[u32]| {
        n.dot(posed.a[sa[0] as usize]) - n.dot(posed.b[sb[0] as usize])
    };
    for (f, &w) in overlay.fv.iter().enumerate() {
        let w = r.vertex_map[w as usize];
        let n = na[f];
        out.push(Candidate {
            features: FeaturePair::FaceVertex {
                a_face: f as u32,
                b_vertex: w,
            },
            n,
            h: value(n, a.face(f), &[w]),
        });
    }
    for (g, &u) in overlay.vf.iter().enumerate() {
        let g = r.face_map[g] as usize;
        let n = -nb[g];
        out.push(Candidate {
            features: FeaturePair::VertexFace {
                a_vertex: u,
                b_face: g as u32,
            },
            n,
            h: value(n, &[u], b.face(g)),
        });
    }
    for &(e, e2) in &overlay.ee {
        let e2 = r.edge_map[e2 as usize];
        let (ea, eb) = (a.edge(e as usize), b.edge(e2 as usize));
        let ordered = |[x, y]: [u32; 2]| if x < y { [x, y] } else { [y, x] };
        let [u1, u2] = ordered(ea.vertices);
        let [w1, w2] = ordered(eb.vertices);
        let da = posed.a[u2 as usize] - posed.a[u1 as usize];
        let db = posed.b[w2 as usize] - posed.b[w1 as usize];
        let c = da.cross(db);
        let len = c.length();
        if len == 0.0 || !len.is_finite() {
            continue; // parallel edges: a degenerate facet of zero area
        }
        let n = c / len;
        // Outward: n lies on A's arc (between its faces' normals) and −n on
        // B's arc. Exactly antisymmetric under swapping A and B.
        let sa_n = na[ea.faces[0] as usize] + na[ea.faces[1] as usize];
        let sb_n = nb[eb.faces[0] as usize] + nb[eb.faces[1] as usize];
        let s = n.dot(sa_n - sb_n);
        let features = FeaturePair::EdgeEdge {
            a_edge: e,
            b_edge: e2,
        };
        let (sa, sb) = ([u1, u2], [w1, w2]);
        if s.abs() < 1e-9 {
            // Nearly antipodal arcs: the sign is uncertain, take both (every
            // candidate is a true support value, so extra ones are harmless).
            for n in [n, -n] {
                out.push(Candidate {
                    features,
                    n,
                    h: value(n, &sa, &sb),
                });
            }
        } else {
            let n = if s > 0.0 { n } else { -n };
            out.push(Candidate {
                features,
                n,
                h: value(n, &sa, &sb),
            });
        }
    }
    out
}

/// `n` or `−n`, whichever is lexicographically larger (a key invariant under
/// negation), and whether `n` itself is that one.
fn sign_free_key(n: DVec3) -> ([f64; 3], bool) {
    let pos = if n.x != 0.0 {
        n.x > 0.0
    } else if n.y != 0.0 {
        n.y > 0.0
    } else {
        n.z >= 0.0
    };
    let k = if pos { n } else { -n };
    // `+ 0.0` turns −0 into +0 so that equal keys compare equal.
    ([k.x + 0.0, k.y + 0.0, k.z + 0.0], pos)
}

/// The tie tolerance: `16 ε` times the largest absolute posed coordinate.
pub(super) fn tie_tolerance(posed: &Posed) -> f64 {
    let scale = posed
        .a
        .iter()
        .chain(&posed.b)
        .map(|v| v.abs().max_element())
        .fold(0.0f64, f64::max);
    16.0 * f64::EPSILON * scale.max(f64::MIN_POSITIVE)
}

/// The winning candidate: minimum `h`; among those within `tol` of it the
/// one with the smallest sign-free key, then the "positive" one, then the
/// smaller `h`.
fn winner(cands: &[Candidate], tol: f64) -> (usize, f64) {
    let hmin = cands.iter().map(|c| c.h).fold(f64::INFINITY, f64::min);
    let mut best: Option<(usize, ([f64; 3], bool))> = None;
    for (i, c) in cands.iter().enumerate() {
        if c.h > hmin + tol {
            continue;
        }
        let key = sign_free_key(c.n);
        let better = match &best {
            None => true,
            Some((j, bk)) => {
                let ord = key.0[0]
                    .total_cmp(&bk.0[0])
                    .then(key.0[1].total_cmp(&bk.0[1]))
                    .then(key.0[2].total_cmp(&bk.0[2]))
                    .then(bk.1.cmp(&key.1)) // positive first
                    .then(c.h.total_cmp(&cands[*j].h));
                ord.is_lt()
            }
        };
        if better {
            best = Some((i, key));
        }
    }
    (best.map(|b| b.0).unwrap_or(0), hmin)
}

/// Depth or distance from an overlay of `A ⊕ (−B)`.
///
/// Scale: the posed vertices of both bodies are first scaled by one power
/// of two `2^k` (their common frame: the largest magnitude in `[1, 2)`),
/// every construction is made there, and lengths and points are scaled
/// back by `2^-k`. Scaling is exact, so the same pair at poses scaled by
/// `2^j` gives bit-identical frame coordinates and answers scaled by
/// exactly `2^j`; nothing overflows or underflows at any scale (squared
/// lengths of `1e200` or `1e-200` would). Posed coordinates that overflow
/// `f64`, or an answer that does, is [`QueryError::OutOfRange`].
pub(super) fn evaluate(
    pair: &ConvexPair,
    pose_a: Pose,
    pose_b: Pose,
    overlay: &Overlay,
) -> Result<Proximity, QueryError> {
    let mut a: Vec<DVec3> = pair.a.vertices().iter().map(|&v| pose_a.apply(v)).collect();
    let mut b: Vec<DVec3> = pair.b.vertices().iter().map(|&v| pose_b.apply(v)).collect();
    if !a.iter().chain(&b).all(|v| v.is_finite()) {
        return Err(QueryError::OutOfRange(
            "the posed coordinates overflow f64 (|x| > 1.8e308)".into(),
        ));
    }
    let k = exact::frame_exponent(a.iter().chain(&b).flat_map(|v| v.to_array()));
    let to_frame = |v: &mut DVec3| {
        *v = DVec3::new(
            exact::mul_pow2(v.x, k),
            exact::mul_pow2(v.y, k),
            exact::mul_pow2(v.z, k),
        )
    };
    a.iter_mut().for_each(to_frame);
    b.iter_mut().for_each(to_frame);
    let back = |x: f64| exact::mul_pow2(x, -k);
    let back_v = |v: DVec3| DVec3::new(back(v.x), back(v.y), back(v.z));
    let posed = Posed {
        a,
        b,
        na: (0..pair.a.face_count())
            .map(|f| pose_a.rotation.apply(pair.a.unit_normal(f)))
            .collect(),
        nb: (0..pair.b.face_count())
            .map(|g| pose_b.rotation.apply(pair.b.unit_normal(g)))
            .collect(),
        pose_a,
        pose_b,
    };
    let answer = evaluate_in_frame(pair, &posed, overlay);
    let out = match answer {
        Proximity::Penetrating(c) => Proximity::Penetrating(Contact {
            depth: back(c.depth),
            point_on_a: back_v(c.point_on_a),
            point_on_b: back_v(c.point_on_b),
            ..c
        }),
        Proximity::Separated(s) => Proximity::Separated(Separation {
            distance: back(s.distance),
            point_on_a: back_v(s.point_on_a),
            point_on_b: back_v(s.point_on_b),
            ..s
        }),
    };
    let finite = match &out {
        Proximity::Penetrating(c) => {
            c.depth.is_finite() && c.point_on_a.is_finite() && c.point_on_b.is_finite()
        }
        Proximity::Separated(s) => {
            s.distance.is_finite() && s.point_on_a.is_finite() && s.point_on_b.is_finite()
        }
    };
    if !finite {
        return Err(QueryError::OutOfRange(
            "the answer overflows f64 (|x| > 1.8e308)".into(),
        ));
    }
    Ok(out)
}

/// [`evaluate`] on frame coordinates.
fn evaluate_in_frame(pair: &ConvexPair, posed: &Posed, overlay: &Overlay) -> Proximity {
    let tol = tie_tolerance(posed);
    let cands = refine(pair, posed, candidates(pair, posed, overlay), tol);
    let (w, hmin) = winner(&cands, tol);
    if hmin < 0.0 {
        return Proximity::Separated(separation(pair, posed, &cands, tol, cands[w]));
    }
    let c = cands[w];
    let depth = hmin;
    let (point_on_a, point_on_b) = match c.features {
        FeaturePair::FaceVertex { b_vertex, .. } => {
            let b = posed.b[b_vertex as usize];
            (b + depth * c.n, b)
        }
        FeaturePair::VertexFace { a_vertex, .. } => {
            let a = posed.a[a_vertex as usize];
            (a, a - depth * c.n)
        }
        FeaturePair::EdgeEdge { a_edge, b_edge } => {
            let [u1, u2] = pair.a.edge(a_edge as usize).vertices;
            let [w1, w2] = pair.b.edge(b_edge as usize).vertices;
            line_line(
                posed.a[u1 as usize],
                posed.a[u2 as usize],
                posed.b[w1 as usize],
                posed.b[w2 as usize],
            )
        }
    };
    Proximity::Penetrating(Contact {
        depth,
        normal: c.n,
        point_on_a,
        point_on_b,
        features: c.features,
    })
}
