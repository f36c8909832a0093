//! The face depths of a polytope: per face, how far the vertices next to
//! it lie below its plane, and how far from it (the half-space read-out's
//! O(1) certificate for an fv-plane's robot term, `halfspaces.rs`'s module
//! docs). Computed once per C-obstacle (`slices.rs`), read per plane.

use crate::polytope::Polytope;

/// Per face `f` of a polytope, the data of the fv-planes' O(1) certificate
/// (module docs): `depth ≤ n̂·(p_v − p_u)` and `span ≥ |p_v − p_u|` over
/// the vertices `v` of the face and `u` adjacent to them off it.
#[derive(Clone, Copy, Debug)]
pub(in crate::query) struct FaceDepth {
    pub(in crate::query) depth: f64,
    pub(in crate::query) span: f64,
}

/// [`FaceDepth`] of every face of `poly`, in O(Σ face size × degree):
/// with `o` a vertex of the face, `n̂·(p_v − p_u) = n̂·(p_v − o) − n̂·(p_u − o)`
/// exactly, so the least over the pairs is bounded by the least face term
/// less the largest neighbour term, each term's rounding bounded by
/// `5ε|n̂|₁|p − o|∞` (the difference's `ε/2` a coordinate and the dot
/// product's `3ε/2`, with room), and `|p_v − p_u| ≤ |p_v − o| + |p_u − o|`,
/// each length bounded by `√3` times its largest coordinate (no squares:
/// they would underflow for parts below about 10⁻¹⁵⁴). A NaN or an overflow
/// certifies nothing.
pub(in crate::query) fn face_depths(poly: &Polytope) -> Vec<FaceDepth> {
    let mut on_face = vec![u32::MAX; poly.vertex_count()];
    (0..poly.face_count())
        .map(|f| {
            let n = poly.unit_normal(f);
            let l1 = n.x.abs() + n.y.abs() + n.z.abs();
            let face = poly.face(f);
            for &v in face {
                on_face[v as usize] = f as u32;
            }
            let o = poly.vertex(face[0] as usize);
            // A term `n̂·(p − o)` with its rounding bound, and `|p − o|`
            // bounded.
            let term = |p: u32| {
                let diff = poly.vertex(p as usize) - o;
                let big = diff.abs().max_element();
                let err = 5.0 * f64::EPSILON * l1 * big + 1e-300;
                (
                    n.dot(diff),
                    err,
                    big * 1.7320508075688774 * (1.0 + 4.0 * f64::EPSILON),
                )
            };
            let (mut lowest, mut reach_face) = (f64::INFINITY, 0.0f64);
            for &v in face {
                let (x, err, len) = term(v);
                lowest = lowest.min(x - err);
                reach_face = reach_face.max(len);
            }
            let (mut highest, mut reach_off) = (f64::NEG_INFINITY, 0.0f64);
            for &v in face {
                for r in poly.ring(v as usize) {
                    if on_face[r.neighbor as usize] == f as u32 {
                        continue;
                    }
                    let (x, err, len) = term(r.neighbor);
                    highest = highest.max(x + err);
                    reach_off = reach_off.max(len);
                }
            }
            // The difference's own rounding, with room.
            let depth = (lowest - highest) - 2.0 * f64::EPSILON * (lowest.abs() + highest.abs());
            if depth.is_nan() || highest == f64::NEG_INFINITY {
                // No vertex off the face (not a solid), or a NaN: never
                // certified.
                return FaceDepth {
                    depth: f64::NEG_INFINITY,
                    span: f64::INFINITY,
                };
            }
            FaceDepth {
                depth,
                span: (reach_face + reach_off) * (1.0 + 2.0 * f64::EPSILON),
            }
        })
        .collect()
}
