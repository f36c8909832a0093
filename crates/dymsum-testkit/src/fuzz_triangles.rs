//! The exact triangle–triangle test ([`dymsum::solid::triangles_meet`], the
//! scene checker's and the solid check's) against an oracle written
//! independently of it: two closed triangles `T`, `U` meet exactly when the
//! origin lies in the convex hull of the nine differences `t − u` (their
//! Minkowski difference), and by Carathéodory's theorem a point in the hull
//! of a finite set lies in the hull of an affinely independent subset of at
//! most four of its points ([`origin_in_hull`]). Every step is integer
//! arithmetic on a small grid (exact in `i64`), not the orientation and
//! segment tests of `dymsum::solid::intersect`.
//!
//! The stable proptest `crates/dymsum/tests/fuzz_triangles.rs` (in CI) and
//! the cargo-fuzz target `fuzz/fuzz_targets/triangles.rs` (off CI) both run
//! [`check`]. [`crate::fuzz_solid`] builds its crossing oracle on the same
//! integer predicates.

use dymsum::solid::triangles_meet;
use dymsum::DVec3;

/// A point (or vector) of the integer grid: exact in `i64` and in `f64`.
pub type GridPoint = [i64; 3];

const ORIGIN: GridPoint = [0; 3];

/// `a − b`.
pub fn sub(a: GridPoint, b: GridPoint) -> GridPoint {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a × b`.
pub fn cross(a: GridPoint, b: GridPoint) -> GridPoint {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a · b`.
pub fn dot(a: GridPoint, b: GridPoint) -> i64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `det[b − a, c − a, d − a]`: six times the signed volume of the
/// tetrahedron `abcd`.
pub fn volume6(a: GridPoint, b: GridPoint, c: GridPoint, d: GridPoint) -> i64 {
    dot(sub(b, a), cross(sub(c, a), sub(d, a)))
}

/// Whether `a`, `b`, `c` are collinear (or coincide).
pub fn collinear(a: GridPoint, b: GridPoint, c: GridPoint) -> bool {
    cross(sub(b, a), sub(c, a)) == ORIGIN
}

/// The origin in the closed triangle `abc`, its corners not collinear.
fn origin_in_triangle(a: GridPoint, b: GridPoint, c: GridPoint) -> bool {
    let n = cross(sub(b, a), sub(c, a));
    dot(n, a) == 0
        && [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(x, y)| dot(n, cross(sub(y, x), sub(ORIGIN, x))) >= 0)
}

/// The origin in the closed tetrahedron `abcd` of non-zero volume `v`
/// (`volume6(a, b, c, d)`): its barycentric coordinates, `volume6` with one
/// corner replaced by the origin over `v`, none negative.
fn origin_in_tetrahedron(a: GridPoint, b: GridPoint, c: GridPoint, d: GridPoint, v: i64) -> bool {
    [
        volume6(ORIGIN, b, c, d),
        volume6(a, ORIGIN, c, d),
        volume6(a, b, ORIGIN, d),
        volume6(a, b, c, ORIGIN),
    ]
    .iter()
    .all(|&w| w.signum() * v.signum() >= 0)
}

/// Whether the origin lies in the convex hull of `points`: in the hull of
/// some affinely independent subset (a point, a segment, a triangle or a
/// tetrahedron), which Carathéodory's theorem says is enough.
pub fn origin_in_hull(points: &[GridPoint]) -> bool {
    let p = points;
    let n = p.len();
    if p.contains(&ORIGIN) {
        return true;
    }
    for i in 0..n {
        for j in i + 1..n {
            let (a, b) = (p[i], p[j]);
            // The origin on the segment: collinear with it, between its ends.
            if a != b && cross(a, b) == ORIGIN && dot(a, b) <= 0 {
                return true;
            }
            for k in j + 1..n {
                let c = p[k];
                if !collinear(a, b, c) && origin_in_triangle(a, b, c) {
                    return true;
                }
                for &d in &p[k + 1..] {
                    let v = volume6(a, b, c, d);
                    if v != 0 && origin_in_tetrahedron(a, b, c, d, v) {
                        return true;
                    }
                }
            }
        }
    }
    false
}

/// The oracle: the closed triangles `t` and `u` (any degeneracy) meet
/// exactly when the origin is in the hull of their differences.
pub fn triangles_meet_oracle(t: &[GridPoint; 3], u: &[GridPoint; 3]) -> bool {
    let diffs: Vec<GridPoint> = t
        .iter()
        .flat_map(|&a| u.iter().map(move |&b| sub(a, b)))
        .collect();
    origin_in_hull(&diffs)
}

/// An exact change of frame, the same for every point of a case: an
/// orientation-preserving signed permutation of the axes, a translation
/// by an integer vector, then a scaling by a power of two. Every image is
/// exact in `f64` (integers below `2^53`, exponents within range), and no
/// meeting, crossing or sign of a volume changes.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    perm: [usize; 3],
    signs: [i64; 3],
    shift: GridPoint,
    exponent: i32,
}

impl Frame {
    /// The identity.
    pub const IDENTITY: Frame = Frame {
        perm: [0, 1, 2],
        signs: [1, 1, 1],
        shift: [0; 3],
        exponent: 0,
    };

    /// A frame from four bytes: scales from `2^-1074` (subnormal) to
    /// `2^960`, around the float filters' thresholds (`1e±80`), and shifts
    /// up to `2^31` (so most decisions fall to the exact arithmetic).
    pub fn from_bytes(b: [u8; 4]) -> Frame {
        const PERMS: [[usize; 3]; 6] = [
            [0, 1, 2],
            [1, 2, 0],
            [2, 0, 1],
            [1, 0, 2],
            [0, 2, 1],
            [2, 1, 0],
        ];
        let perm = PERMS[usize::from(b[0] % 6)];
        // An odd permutation reverses orientation, and so does an odd
        // number of flipped axes: flip the third axis to make up.
        let odd = b[0] % 6 >= 3;
        let mut signs: [i64; 3] = [1, 1, 1];
        for (k, s) in signs.iter_mut().enumerate().take(2) {
            if b[1] >> k & 1 == 1 {
                *s = -1;
            }
        }
        let flips = signs.iter().filter(|&&s| s < 0).count();
        if (flips % 2 == 1) != odd {
            signs[2] = -1;
        }
        let exponent = match b[2] % 8 {
            0 | 1 => 0,
            2 => i32::from(b[3] % 16) - 8,
            3 => -1074 + i32::from(b[3] % 40),
            4 => 920 + i32::from(b[3] % 40),
            5 => -270 + i32::from(b[3] % 12),
            6 => 258 + i32::from(b[3] % 12),
            _ => i32::from(b[3]) * 4 - 512,
        };
        // Images stay below 2^32 · 2^960 in magnitude.
        let shift = match b[1] >> 2 & 3 {
            0 => [0; 3],
            1 => [1 << 20, -(1 << 20), 3],
            2 => [(1 << 31) - 7, 5, -(1 << 30)],
            _ => [-(i64::from(b[3]) << 23), i64::from(b[3]), 1 << 26],
        };
        Frame {
            perm,
            signs,
            shift,
            exponent,
        }
    }

    /// The image of a grid point (grid coordinates below `2^20`).
    pub fn apply(&self, p: GridPoint) -> [f64; 3] {
        // Exact: |x| < 2^53, and an integer times a power of two at least
        // 2^-1074 and below 2^1023 is exact (subnormal results included).
        let pow2 = |e: i32| f64::from_bits(((e + 1023) as u64) << 52);
        let scale = |x: i64| {
            let e = self.exponent;
            let (first, second) = if e < -1000 { (-1000, e + 1000) } else { (e, 0) };
            x as f64 * pow2(first) * pow2(second)
        };
        std::array::from_fn(|k| scale(self.signs[k] * p[self.perm[k]] + self.shift[k]))
    }
}

/// A little reader of bytes: zero when they run out.
pub struct Bytes<'a>(std::slice::Iter<'a, u8>);

impl<'a> Bytes<'a> {
    /// Reads `data` from its start.
    pub fn new(data: &'a [u8]) -> Bytes<'a> {
        Bytes(data.iter())
    }

    /// The next byte, or 0.
    pub fn byte(&mut self) -> u8 {
        self.0.next().copied().unwrap_or(0)
    }

    /// The next byte as an integer in `lo..=hi`.
    pub fn range(&mut self, lo: i64, hi: i64) -> i64 {
        lo + i64::from(self.byte()) % (hi - lo + 1)
    }

    /// A grid point with coordinates in `lo..=hi`.
    pub fn point(&mut self, lo: i64, hi: i64) -> GridPoint {
        [self.range(lo, hi), self.range(lo, hi), self.range(lo, hi)]
    }
}

/// The kinds of pairs [`pair`] builds, each rich in one degeneracy.
const KINDS: u8 = 8;

/// A pair of triangles on the grid, from bytes: the first byte picks the
/// kind (apart or crossing at random, a shared corner, a shared edge,
/// coplanar, an edge lying on the other's plane through it, a corner on
/// the other, a flat second triangle, a shifted copy), the next ones the
/// corners. Coordinates are even except where a kind makes them odd (so
/// midpoints and half-unit shifts are on the grid), all within `±40`.
pub fn pair(b: &mut Bytes) -> ([GridPoint; 3], [GridPoint; 3]) {
    let kind = b.byte() % KINDS;
    let even = |p: GridPoint| p.map(|x| 2 * x);
    let t0 = [b.point(-2, 2), b.point(-2, 2), b.point(-2, 2)];
    let t = t0.map(even);
    let random = |b: &mut Bytes| even(b.point(-2, 2));
    // A point of t's plane, 2 t₀ + α (t₁ − t₀) + β (t₂ − t₀) (halved: the
    // grid is doubled), inside or on t when α, β ≥ 0 and α + β ≤ 2.
    let in_plane = |alpha: i64, beta: i64| -> GridPoint {
        std::array::from_fn(|k| {
            2 * t0[0][k] + alpha * (t0[1][k] - t0[0][k]) + beta * (t0[2][k] - t0[0][k])
        })
    };
    let on_t = |b: &mut Bytes| {
        let alpha = b.range(0, 2);
        in_plane(alpha, b.range(0, 2 - alpha))
    };
    let i = usize::from(b.byte() % 3);
    let u = match kind {
        0 => [random(b), random(b), random(b)],
        1 => [t[i], random(b), random(b)],
        2 => {
            let (x, y) = (t[i], t[(i + 1) % 3]);
            let (x, y) = if b.byte().is_multiple_of(2) {
                (x, y)
            } else {
                (y, x)
            };
            [x, y, random(b)]
        }
        3 => std::array::from_fn(|_| in_plane(b.range(-1, 3), b.range(-1, 3))),
        4 => [on_t(b), on_t(b), random(b)],
        5 => {
            let p = on_t(b);
            // Sometimes half a unit off it, along an axis.
            let mut p2 = p;
            let axis = usize::from(b.byte() % 3);
            p2[axis] += b.range(-1, 1);
            [p2, random(b), random(b)]
        }
        6 => {
            let (u0, u1) = (random(b), random(b));
            let c = b.range(-1, 2);
            [u0, u1, std::array::from_fn(|k| u0[k] + c * (u1[k] - u0[k]))]
        }
        _ => {
            let d = b.point(-1, 1);
            let mut u = t.map(|p| std::array::from_fn(|k| p[k] + d[k]));
            if b.byte() % 2 == 1 {
                u.swap(1, 2);
            }
            u
        }
    };
    // Sometimes the first triangle flat too.
    let t = if b.byte().is_multiple_of(8) {
        let c = b.range(-1, 2);
        [
            t[0],
            t[1],
            std::array::from_fn(|k| t[0][k] + c * (t[1][k] - t[0][k])),
        ]
    } else {
        t
    };
    (t, u)
}

/// Every property (panics naming the one broken): `triangles_meet` agrees
/// with the oracle, in a random exact frame and in the grid's own; it is
/// symmetric, and does not depend on the order of the corners.
pub fn check(data: &[u8]) {
    let mut b = Bytes::new(data);
    let (t, u) = pair(&mut b);
    let frame = Frame::from_bytes([b.byte(), b.byte(), b.byte(), b.byte()]);
    let expected = triangles_meet_oracle(&t, &u);
    let image = |f: &Frame, x: &[GridPoint; 3]| x.map(|p| DVec3::from(f.apply(p)));
    for f in [Frame::IDENTITY, frame] {
        let (tf, uf) = (image(&f, &t), image(&f, &u));
        assert_eq!(
            triangles_meet(&tf, &uf),
            expected,
            "t = {t:?}, u = {u:?} in {f:?}: the oracle says {expected}"
        );
        assert_eq!(
            triangles_meet(&uf, &tf),
            expected,
            "swapped: t = {t:?}, u = {u:?} in {f:?}"
        );
        let turned = [tf[1], tf[2], tf[0]];
        let reversed = [uf[0], uf[2], uf[1]];
        assert_eq!(
            triangles_meet(&turned, &reversed),
            expected,
            "corners reordered: t = {t:?}, u = {u:?} in {f:?}"
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_oracle_on_known_pairs() {
        let t = [[0, 0, 0], [4, 0, 0], [0, 4, 0]];
        // Pierces the interior; touches an edge at a point; above; a
        // shared corner only; coplanar and apart; a point on the face.
        assert!(triangles_meet_oracle(
            &t,
            &[[1, 1, -1], [1, 1, 1], [6, 6, 1]]
        ));
        assert!(triangles_meet_oracle(
            &t,
            &[[2, -2, -2], [2, 2, -2], [2, 0, 0]]
        ));
        assert!(!triangles_meet_oracle(
            &t,
            &[[1, 1, 1], [1, 2, 2], [2, 1, 2]]
        ));
        assert!(triangles_meet_oracle(
            &t,
            &[[0, 0, 0], [-1, -1, 3], [-2, 0, 1]]
        ));
        assert!(!triangles_meet_oracle(
            &t,
            &[[3, 3, 0], [5, 3, 0], [3, 5, 0]]
        ));
        assert!(triangles_meet_oracle(
            &t,
            &[[1, 1, 0], [1, 1, 0], [1, 1, 0]]
        ));
        assert!(!triangles_meet_oracle(
            &t,
            &[[3, 3, 0], [3, 3, 0], [3, 3, 0]]
        ));
        // The hypotenuse touched by a segment in the plane, at its middle.
        assert!(triangles_meet_oracle(
            &t,
            &[[2, 2, 0], [4, 4, 0], [4, 4, 0]]
        ));
    }

    #[test]
    fn frames_are_exact_and_keep_orientation() {
        for x in 0..=255u8 {
            for y in [0u8, 1, 2, 3, 4, 8, 12, 255] {
                let f = Frame::from_bytes([x, y, x.wrapping_mul(13), x.wrapping_mul(7)]);
                // The signed permutation's determinant is +1.
                let m: [[i64; 3]; 3] = std::array::from_fn(|r| {
                    std::array::from_fn(|c| if f.perm[r] == c { f.signs[r] } else { 0 })
                });
                assert_eq!(dot(m[0], cross(m[1], m[2])), 1, "{f:?}");
                // Exact: scaling back by the power of two gives the integer.
                for p in [[1, -2, 40], [-40, 0, 3]] {
                    let image = f.apply(p);
                    let back: [f64; 3] = std::array::from_fn(|k| {
                        let mut v = image[k];
                        let mut e = f.exponent;
                        while e != 0 {
                            let step = e.clamp(-1000, 1000);
                            v *= 2f64.powi(-step);
                            e -= step;
                        }
                        v
                    });
                    let want: [f64; 3] =
                        std::array::from_fn(|k| (f.signs[k] * p[f.perm[k]] + f.shift[k]) as f64);
                    assert_eq!(back, want, "{f:?}");
                }
            }
        }
    }
}
