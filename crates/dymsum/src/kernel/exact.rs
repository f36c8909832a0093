//! Exact dyadic arithmetic without heap allocation: every finite `f64` is
//! `m · 2^e` with an integer `m`, so sums, differences and products of
//! floats are exact as [`Dyadic`]s.
//!
//! A [`Dyadic`] is a sign, a binary exponent and a magnitude of at most
//! [`CAPACITY_BITS`] bits held in a fixed array on the stack (no `Vec`, no
//! big-integer crate), normalised so that its lowest bit is set: its length
//! is the *span* of the value (top bit minus lowest set bit), not its
//! magnitude, so the scale of the input costs nothing. Used only on the slow
//! path of the filtered predicates, when the float evaluation cannot certify
//! a sign (near or exact degeneracies).
//!
//! # Capacity
//!
//! The span of a sum or product of dyadics is at most the sum of the spans
//! of the factors (plus a carry bit per addition), so the span of a
//! polynomial value is bounded by its degree times the span of its inputs.
//! The predicates evaluate at most degree 9 in the vertex coordinates of one
//! polytope (the determinant of three rotated exact normals: each normal is
//! degree 2 in coordinates, times a rotation entry) and degree 3 in
//! pairwise sums of two polytopes' coordinates (the hull method), and degree
//! 3 (`orient`) or 2 (`orient2`) in differences of arbitrary finite floats
//! (at most 2100 bits each). Every polytope constructor checks
//! [`coordinate_span_ok`] (coordinates spanning more than [`MAX_COORD_SPAN`]
//! bits are refused with the typed `PolytopeError::OutOfRange`), so every
//! value stays below [`CAPACITY_BITS`] (the worst cases are worked out at
//! [`CAPACITY_BITS`]) and the capacity assertions cannot fire on any input
//! a constructor accepted; they remain as a guard against a wrong answer.
//!
//! # Scale
//!
//! Exponents are normalised by exact power-of-two scaling: [`mul_pow2`],
//! [`frame_exponent`] (a coordinate set's *frame*: the largest magnitude
//! scaled into `[1, 2)`). Polytopes derive their float data in their frame,
//! queries work in the pair's frame, and the float predicates scale their
//! inputs into Shewchuk's exact range per call (see
//! `kernel::predicates::orient`), so results do not depend on the scale.
//!
//! Complexity: addition `O(n)` and multiplication `O(n²)` in the number of
//! 64-bit limbs actually used (one or two for typical coordinates).

use super::Sign;
use glam::{DMat3, DVec3};

/// Limbs of a [`Dyadic`] magnitude.
const LIMBS: usize = 112;

/// The largest magnitude span, in bits, a [`Dyadic`] can hold (7168).
///
/// Worst cases with coordinates of one polytope spanning at most
/// [`MAX_COORD_SPAN`] = 960 bits (plus the 53-bit mantissa: 1013 bits per
/// coordinate, counted from the top bit of the largest to the lowest set bit
/// of the smallest): an exact normal (cross product of differences) spans at
/// most 2·1014 + 2 = 2030 bits; a rotated normal (matrix entries are 0, ±1
/// or at least `2^-47` in magnitude, so span ≤ 100) at most 2030 + 100 + 3 =
/// 2133; the determinant of three of them at most 3·2133 + 3 = 6402 < 7168.
/// For the hull method each row value spans at most the exponent range of
/// two polytopes' coordinates, ≤ 2098 + 53 + 2 bits, and the determinant
/// three times that plus 3 bits: 6462 < 7168.
pub const CAPACITY_BITS: usize = LIMBS * 64;

/// The largest supported binary-exponent spread between the largest
/// coordinate magnitude of a polytope and its smallest non-zero one
/// (`2^960 ≈ 1e289`). See [`coordinate_span_ok`].
pub const MAX_COORD_SPAN: i32 = 960;

/// Decomposes a finite `f64` into `(m, e)` with value exactly `m · 2^e`
/// (`|m| < 2^53`).
#[inline]
pub fn decompose(x: f64) -> (i64, i32) {
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i32;
    let frac = (bits & ((1u64 << 52) - 1)) as i64;
    let (m, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1i64 << 52), exp - 1075)
    };
    if bits >> 63 == 1 {
        (-m, e)
    } else {
        (m, e)
    }
}

/// The binary exponent of the lowest set bit of a non-zero finite float.
#[inline]
pub fn low_exponent(x: f64) -> i32 {
    let (m, e) = decompose(x);
    e + m.unsigned_abs().trailing_zeros() as i32
}

/// The binary exponent `k` with `2^k ≤ |x| < 2^(k+1)` of a non-zero finite
/// float.
#[inline]
pub fn top_exponent(x: f64) -> i32 {
    let (m, e) = decompose(x);
    e + 63 - m.unsigned_abs().leading_zeros() as i32
}

/// An exact dyadic rational `±m · 2^e`, on the stack.
#[derive(Clone, Copy)]
pub struct Dyadic {
    m: [u64; LIMBS],
    len: u32,
    neg: bool,
    e: i32,
}

impl std::fmt::Debug for Dyadic {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Dyadic")
            .field("neg", &self.neg)
            .field("limbs", &&self.m[..self.len as usize])
            .field("e", &self.e)
            .finish()
    }
}

impl PartialEq for Dyadic {
    fn eq(&self, other: &Dyadic) -> bool {
        self.len == other.len
            && (self.len == 0
                || (self.neg == other.neg
                    && self.e == other.e
                    && self.m[..self.len as usize] == other.m[..other.len as usize]))
    }
}
impl Eq for Dyadic {}

/// Shifts `src` left by `bits` into `dst` (zeroed beyond the result);
/// returns the length.
fn shl_into(src: &[u64], bits: usize, dst: &mut [u64; LIMBS]) -> usize {
    if src.is_empty() {
        return 0;
    }
    let (w, b) = (bits / 64, bits % 64);
    assert!(
        w + src.len() <= LIMBS,
        "exact arithmetic capacity exceeded (inputs outside the supported range)"
    );
    let mut len = w + src.len();
    if b == 0 {
        dst[w..len].copy_from_slice(src);
    } else {
        let mut carry = 0u64;
        for (i, &x) in src.iter().enumerate() {
            dst[w + i] = (x << b) | carry;
            carry = x >> (64 - b);
        }
        if carry != 0 {
            assert!(
                len < LIMBS,
                "exact arithmetic capacity exceeded (inputs outside the supported range)"
            );
            dst[len] = carry;
            len += 1;
        }
    }
    len
}

fn cmp_mag(a: &[u64], b: &[u64]) -> std::cmp::Ordering {
    if a.len() != b.len() {
        return a.len().cmp(&b.len());
    }
    for i in (0..a.len()).rev() {
        if a[i] != b[i] {
            return a[i].cmp(&b[i]);
        }
    }
    std::cmp::Ordering::Equal
}

impl Dyadic {
    /// Zero.
    #[inline]
    pub fn zero() -> Dyadic {
        Dyadic {
            m: [0; LIMBS],
            len: 0,
            neg: false,
            e: 0,
        }
    }

    /// The exact value of a finite float (non-finite values map to zero;
    /// callers validate finiteness first).
    #[inline]
    pub fn from_f64(x: f64) -> Dyadic {
        let mut d = Dyadic::zero();
        if x == 0.0 || !x.is_finite() {
            return d;
        }
        let (m, e) = decompose(x);
        let a = m.unsigned_abs();
        let tz = a.trailing_zeros();
        d.m[0] = a >> tz;
        d.len = 1;
        d.neg = m < 0;
        d.e = e + tz as i32;
        d
    }

    /// `true` for zero.
    #[inline]
    pub fn is_zero(&self) -> bool {
        self.len == 0
    }

    /// The sign.
    #[inline]
    pub fn sign(&self) -> Sign {
        if self.len == 0 {
            Sign::Zero
        } else if self.neg {
            Sign::Negative
        } else {
            Sign::Positive
        }
    }

    #[inline]
    fn mag(&self) -> &[u64] {
        &self.m[..self.len as usize]
    }

    /// Strips trailing zero bits into the exponent (lowest bit set).
    fn normalise(&mut self) {
        let len = self.len as usize;
        if len == 0 {
            self.neg = false;
            self.e = 0;
            return;
        }
        let k = self.m[..len].iter().position(|&x| x != 0).unwrap_or(0);
        let t = self.m[k].trailing_zeros() as usize;
        if k == 0 && t == 0 {
            return;
        }
        let n = len - k;
        if t == 0 {
            self.m.copy_within(k..len, 0);
        } else {
            for i in 0..n {
                let hi = if k + i + 1 < len {
                    self.m[k + i + 1] << (64 - t)
                } else {
                    0
                };
                self.m[i] = (self.m[k + i] >> t) | hi;
            }
        }
        for x in &mut self.m[n..len] {
            *x = 0;
        }
        let mut l = n;
        while l > 0 && self.m[l - 1] == 0 {
            l -= 1;
        }
        self.len = l as u32;
        self.e += (64 * k + t) as i32;
    }

    /// `self + other`, exactly.
    pub fn add(&self, other: &Dyadic) -> Dyadic {
        if self.len == 0 {
            return *other;
        }
        if other.len == 0 {
            return *self;
        }
        // `hi` has the larger exponent; shift it down to `lo`'s exponent.
        let (hi, lo) = if self.e >= other.e {
            (self, other)
        } else {
            (other, self)
        };
        let shift = (hi.e - lo.e) as usize;
        assert!(
            shift < CAPACITY_BITS,
            "exact arithmetic capacity exceeded (inputs outside the supported range)"
        );
        let mut a = [0u64; LIMBS];
        let alen = shl_into(hi.mag(), shift, &mut a);
        let (a, b) = (&a[..alen], lo.mag());
        let mut r = Dyadic::zero();
        r.e = lo.e;
        if hi.neg == lo.neg {
            r.neg = hi.neg;
            let n = a.len().max(b.len());
            let mut carry = 0u64;
            for i in 0..n {
                let x = *a.get(i).unwrap_or(&0) as u128 + *b.get(i).unwrap_or(&0) as u128;
                let s = x + carry as u128;
                r.m[i] = s as u64;
                carry = (s >> 64) as u64;
            }
            let mut len = n;
            if carry != 0 {
                assert!(
                    n < LIMBS,
                    "exact arithmetic capacity exceeded (inputs outside the supported range)"
                );
                r.m[n] = carry;
                len += 1;
            }
            r.len = len as u32;
        } else {
            let (big, small, neg) = match cmp_mag(a, b) {
                std::cmp::Ordering::Equal => return Dyadic::zero(),
                std::cmp::Ordering::Greater => (a, b, hi.neg),
                std::cmp::Ordering::Less => (b, a, lo.neg),
            };
            r.neg = neg;
            let mut borrow = 0u64;
            for (i, &x) in big.iter().enumerate() {
                let (d1, b1) = x.overflowing_sub(*small.get(i).unwrap_or(&0));
                let (d2, b2) = d1.overflowing_sub(borrow);
                r.m[i] = d2;
                borrow = (b1 || b2) as u64;
            }
            let mut len = big.len();
            while len > 0 && r.m[len - 1] == 0 {
                len -= 1;
            }
            r.len = len as u32;
        }
        r.normalise();
        r
    }

    /// `self − other`, exactly.
    #[inline]
    pub fn sub(&self, other: &Dyadic) -> Dyadic {
        self.add(&other.neg())
    }

    /// `−self`.
    #[inline]
    pub fn neg(&self) -> Dyadic {
        let mut r = *self;
        if r.len != 0 {
            r.neg = !r.neg;
        }
        r
    }

    /// `self · other`, exactly.
    pub fn mul(&self, other: &Dyadic) -> Dyadic {
        if self.len == 0 || other.len == 0 {
            return Dyadic::zero();
        }
        let (a, b) = (self.mag(), other.mag());
        assert!(
            a.len() + b.len() <= LIMBS,
            "exact arithmetic capacity exceeded (inputs outside the supported range)"
        );
        let mut r = Dyadic::zero();
        for (i, &x) in a.iter().enumerate() {
            let mut carry = 0u128;
            for (j, &y) in b.iter().enumerate() {
                let t = x as u128 * y as u128 + r.m[i + j] as u128 + carry;
                r.m[i + j] = t as u64;
                carry = t >> 64;
            }
            r.m[i + b.len()] = carry as u64;
        }
        let mut len = a.len() + b.len();
        while len > 0 && r.m[len - 1] == 0 {
            len -= 1;
        }
        r.len = len as u32;
        r.neg = self.neg != other.neg;
        // The product of two odd magnitudes is odd: already normalised.
        r.e = self.e + other.e;
        r
    }

    /// The binary exponent `k` with `2^k ≤ |self| < 2^(k+1)`, `None` for
    /// zero.
    pub fn top_exponent(&self) -> Option<i32> {
        let len = self.len as usize;
        if len == 0 {
            return None;
        }
        let bits = 64 * (len - 1) + (64 - self.m[len - 1].leading_zeros() as usize);
        Some(self.e + bits as i32 - 1)
    }

    /// `self · 2^k` as a float, with a relative error below `3u` when the
    /// result is a normal float (the top three limbs, rounded and summed).
    pub fn to_f64_shifted(self, k: i32) -> f64 {
        let len = self.len as usize;
        if len == 0 {
            return 0.0;
        }
        let mut v = 0.0;
        let lo = len.saturating_sub(3);
        for i in (lo..len).rev() {
            v += mul_pow2(self.m[i] as f64, 64 * (i as i32 - (len as i32 - 1)));
        }
        let v = mul_pow2(v, self.e + 64 * (len as i32 - 1) + k);
        if self.neg {
            -v
        } else {
            v
        }
    }

    /// The value as the nearest-ish float (for tests and diagnostics; not
    /// correctly rounded, may overflow to infinity).
    pub fn to_f64_approx(self) -> f64 {
        let mut v = 0.0;
        for &x in self.mag().iter().rev() {
            v = v * 18446744073709551616.0 + x as f64;
        }
        let v = v * 2f64.powi(self.e.clamp(-1100, 1100));
        if self.neg {
            -v
        } else {
            v
        }
    }
}

/// An exact 3-vector.
pub type ExactVec = [Dyadic; 3];

/// The exact vector of a float vector.
#[inline]
pub fn exact(v: DVec3) -> ExactVec {
    [
        Dyadic::from_f64(v.x),
        Dyadic::from_f64(v.y),
        Dyadic::from_f64(v.z),
    ]
}

/// `a − b`, exactly.
pub fn sub(a: DVec3, b: DVec3) -> ExactVec {
    let (a, b) = (exact(a), exact(b));
    [a[0].sub(&b[0]), a[1].sub(&b[1]), a[2].sub(&b[2])]
}

/// `a × b`, exactly.
pub fn cross(a: &ExactVec, b: &ExactVec) -> ExactVec {
    [
        det2(&a[1], &a[2], &b[1], &b[2]),
        det2(&a[2], &a[0], &b[2], &b[0]),
        det2(&a[0], &a[1], &b[0], &b[1]),
    ]
}

/// `a · b`, exactly.
pub fn dot(a: &ExactVec, b: &ExactVec) -> Dyadic {
    a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]))
}

/// `M v` for a float matrix `M` taken as exact, exactly.
pub fn mat_vec(m: &DMat3, v: &ExactVec) -> ExactVec {
    let row = |r: usize| {
        let row = m.row(r);
        let mut s = Dyadic::zero();
        for k in 0..3 {
            if row[k] != 0.0 && !v[k].is_zero() {
                s = s.add(&Dyadic::from_f64(row[k]).mul(&v[k]));
            }
        }
        s
    };
    [row(0), row(1), row(2)]
}

/// `det[a, b, c] = (a × b) · c`, exactly.
pub fn det3(a: &ExactVec, b: &ExactVec, c: &ExactVec) -> Dyadic {
    dot(&cross(a, b), c)
}

/// `p0 q1 − p1 q0`, exactly.
#[inline]
pub fn det2(p0: &Dyadic, p1: &Dyadic, q0: &Dyadic, q1: &Dyadic) -> Dyadic {
    let (x, y) = (p0.mul(q1), p1.mul(q0));
    if y.is_zero() {
        x
    } else if x.is_zero() {
        y.neg()
    } else {
        x.sub(&y)
    }
}

/// `x · 2^k`, computed in steps so that the factor itself never overflows:
/// exact whenever the result is representable without rounding (every
/// step moves the value monotonically towards the result).
pub fn mul_pow2(mut x: f64, mut k: i32) -> f64 {
    while k != 0 && x != 0.0 {
        let s = k.clamp(-1000, 1000);
        x *= f64::from_bits(((s + 1023) as u64) << 52);
        k -= s;
    }
    x
}

/// `v · 2^k` componentwise, exact as [`mul_pow2`]: one multiplication by
/// `2^k` when that is a normal float (`|k| ≤ 1000`), steps beyond.
#[inline]
pub fn mul_pow2_vec(v: DVec3, k: i32) -> DVec3 {
    if (-1000..=1000).contains(&k) {
        v * f64::from_bits(((k + 1023) as u64) << 52)
    } else {
        DVec3::new(mul_pow2(v.x, k), mul_pow2(v.y, k), mul_pow2(v.z, k))
    }
}

/// The largest top exponent and the smallest low exponent (see
/// [`top_exponent`], [`low_exponent`]) over the non-zero finite values,
/// `None` when there are none.
pub fn exponent_range(coords: impl Iterator<Item = f64>) -> Option<(i32, i32)> {
    let mut top = i32::MIN;
    let mut low = i32::MAX;
    for x in coords {
        if x != 0.0 && x.is_finite() {
            top = top.max(top_exponent(x));
            low = low.min(low_exponent(x));
        }
    }
    (top != i32::MIN).then_some((top, low))
}

/// The power-of-two *frame* of a finite coordinate set: the exponent `k`
/// with the largest magnitude times `2^k` in `[1, 2)`. Scaling every
/// coordinate by `2^k` is exact when the set passes
/// [`coordinate_span_ok`] (its lowest bit stays above `2^-1074`), and a set
/// scaled by `2^j` has frame `k − j`, so frame coordinates do not depend on
/// the input's scale. `0` for a set of zeros.
pub fn frame_exponent(coords: impl Iterator<Item = f64>) -> i32 {
    // The top exponent grows with the magnitude, so the largest magnitude
    // has the largest one: one exponent read instead of two per coordinate
    // (the low one, which `exponent_range` also finds, is not needed).
    let largest = coords
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if largest == 0.0 {
        0
    } else {
        -top_exponent(largest)
    }
}

/// Whether a finite coordinate set is within what the exact predicates
/// decide: every non-zero magnitude within `2^MAX_COORD_SPAN` of the
/// largest one. Returns the largest and smallest non-zero binary exponents
/// `(top, low)` on failure; `Ok(())` also for sets of zeros.
pub fn coordinate_span_ok(coords: impl Iterator<Item = f64>) -> Result<(), (i32, i32)> {
    match exponent_range(coords) {
        Some((top, low)) if top - low > MAX_COORD_SPAN => Err((top, low)),
        _ => Ok(()),
    }
}

/// Error-free float evaluation for the cheap exact stage: each function
/// returns the exact value when it is a float computed without any rounding,
/// overflow or underflow, else `None` (then the caller evaluates with
/// [`Dyadic`]s). Exact ties of axis-aligned or otherwise simple geometry
/// (parallel box faces) are settled here without multi-limb arithmetic.
pub mod float {
    use glam::DVec3;

    /// Products whose magnitude is at least this have an exactly
    /// representable rounding error (`2^-969 = 2^(-1022 + 53)`).
    const MIN_EXACT_PRODUCT: f64 = 2.004168360008973e-292;

    /// `a · b` if the float product is exact.
    #[inline]
    pub fn mul(a: f64, b: f64) -> Option<f64> {
        let p = a * b;
        if p == 0.0 {
            return (a == 0.0 || b == 0.0).then_some(0.0);
        }
        if !p.is_finite() || p.abs() < MIN_EXACT_PRODUCT {
            return None;
        }
        // A power-of-two factor (unit normals' ±1, halves) only shifts the
        // other's exponent: exact here, without the fused multiply-add
        // (a library call on targets without FMA).
        if is_pow2(a) || is_pow2(b) {
            return Some(p);
        }
        (a.mul_add(b, -p) == 0.0).then_some(p)
    }

    /// `true` for a normal float `±2^k` (zero fraction bits).
    #[inline]
    fn is_pow2(x: f64) -> bool {
        x.is_normal() && x.to_bits() & ((1u64 << 52) - 1) == 0
    }

    /// `a + b` if the float sum is exact (Knuth's TwoSum).
    #[inline]
    pub fn add(a: f64, b: f64) -> Option<f64> {
        let s = a + b;
        if !s.is_finite() {
            return None;
        }
        let bb = s - a;
        ((a - (s - bb)) + (b - bb) == 0.0).then_some(s)
    }

    /// `p0 q1 − p1 q0` if evaluated exactly.
    #[inline]
    pub fn det2(p0: f64, p1: f64, q0: f64, q1: f64) -> Option<f64> {
        add(mul(p0, q1)?, -mul(p1, q0)?)
    }

    /// `a × b` if evaluated exactly.
    #[inline]
    pub fn cross(a: DVec3, b: DVec3) -> Option<DVec3> {
        Some(DVec3::new(
            det2(a.y, a.z, b.y, b.z)?,
            det2(a.z, a.x, b.z, b.x)?,
            det2(a.x, a.y, b.x, b.y)?,
        ))
    }

    /// `a · b` if evaluated exactly.
    #[inline]
    pub fn dot(a: DVec3, b: DVec3) -> Option<f64> {
        add(add(mul(a.x, b.x)?, mul(a.y, b.y)?)?, mul(a.z, b.z)?)
    }

    /// `a − b` if evaluated exactly.
    #[inline]
    pub fn sub(a: DVec3, b: DVec3) -> Option<DVec3> {
        Some(DVec3::new(
            add(a.x, -b.x)?,
            add(a.y, -b.y)?,
            add(a.z, -b.z)?,
        ))
    }

    /// `det[a, b, c]` if evaluated exactly.
    #[inline]
    pub fn det3(a: DVec3, b: DVec3, c: DVec3) -> Option<f64> {
        dot(cross(a, b)?, c)
    }

    /// `M v` (rows of `M` dotted with `v`) if evaluated exactly.
    #[inline]
    pub fn mat_vec(m: &glam::DMat3, v: DVec3) -> Option<DVec3> {
        Some(DVec3::new(
            dot(m.row(0), v)?,
            dot(m.row(1), v)?,
            dot(m.row(2), v)?,
        ))
    }

    /// `v · 2^k` for a power of two `s = 2^k` if exact (no overflow or
    /// underflow).
    #[inline]
    pub fn scale(v: DVec3, s: f64) -> Option<DVec3> {
        let w = v * s;
        (w.is_finite() && w / s == v).then_some(w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The frame is the top exponent of the largest magnitude, the same as
    /// the largest top exponent of `exponent_range`, on sets mixing
    /// subnormals, huge values, signs, zeros and non-finite entries.
    #[test]
    fn frame_exponent_is_the_largest_top_exponent() {
        let values = [
            0.0,
            -0.0,
            5e-324,
            -2.2e-308,
            1e-300,
            0.1,
            -0.75,
            1.0,
            1.5,
            -2.0,
            3.0,
            1e17,
            -1e300,
            f64::MAX,
            f64::NAN,
            f64::INFINITY,
        ];
        let mut rng = crate::kernel::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1d);
        for _ in 0..2000 {
            let set: Vec<f64> = (0..5)
                .map(|_| values[(rng.next_u64() % values.len() as u64) as usize])
                .collect();
            let want = exponent_range(set.iter().copied()).map_or(0, |(top, _)| -top);
            assert_eq!(frame_exponent(set.iter().copied()), want, "{set:?}");
        }
    }

    #[test]
    fn floats_are_exact() {
        for x in [0.1, -3.5, 1e-300, 5e-324, 1e300, f64::MAX, -0.0, 3.0] {
            let d = Dyadic::from_f64(x);
            if x.abs() > 1e-290 && x.abs() < 1e290 {
                assert_eq!(d.to_f64_approx(), x);
            }
            assert_eq!(d.sign(), Sign::of(x));
        }
    }

    #[test]
    fn hidden_cancellation_is_exact() {
        // 0.1 + 0.2 - 0.3 is not zero in binary; the float sum says 5.5e-17.
        let s = Dyadic::from_f64(0.1)
            .add(&Dyadic::from_f64(0.2))
            .sub(&Dyadic::from_f64(0.3));
        assert_eq!(s.sign(), Sign::Positive);
        assert_eq!(s.to_f64_approx(), 2f64.powi(-55));
        let z = Dyadic::from_f64(1e300).sub(&Dyadic::from_f64(1e300));
        assert_eq!(z.sign(), Sign::Zero);
        // Far-apart exponents: (2^600 + 2^-600) − 2^600 = 2^-600.
        let big = Dyadic::from_f64(2f64.powi(600));
        let small = Dyadic::from_f64(2f64.powi(-600));
        let d = big.add(&small).sub(&big);
        assert_eq!(d, small);
        assert_eq!(big.add(&small).sub(&small), big);
    }

    #[test]
    fn products_and_carries() {
        // (2^53 − 1)^2 = 2^106 − 2^54 + 1, checked through a difference.
        let m = Dyadic::from_f64(9007199254740991.0);
        let sq = m.mul(&m);
        let expect = Dyadic::from_f64(2f64.powi(106))
            .sub(&Dyadic::from_f64(2f64.powi(54)))
            .add(&Dyadic::from_f64(1.0));
        assert_eq!(sq, expect);
        // A long carry chain: (2^64·k − 1) + 1.
        let a = Dyadic::from_f64(2f64.powi(200)).sub(&Dyadic::from_f64(1.0));
        assert_eq!(
            a.add(&Dyadic::from_f64(1.0)),
            Dyadic::from_f64(2f64.powi(200))
        );
        assert_eq!(
            a.neg().add(&Dyadic::from_f64(2f64.powi(200))),
            Dyadic::from_f64(1.0)
        );
    }

    #[test]
    fn exact_det() {
        let a = exact(DVec3::X);
        let b = exact(DVec3::Y);
        let c = exact(DVec3::Z);
        assert_eq!(det3(&a, &b, &c).sign(), Sign::Positive);
        assert_eq!(det3(&b, &a, &c).sign(), Sign::Negative);
        assert_eq!(det3(&a, &b, &a).sign(), Sign::Zero);
    }

    #[test]
    fn matches_i128_on_small_integers() {
        // Random small-integer determinants against i128 arithmetic.
        let mut s = 12345u64;
        let mut next = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 33) % 2001) as i64 - 1000
        };
        for _ in 0..2000 {
            let v: Vec<i64> = (0..9).map(|_| next()).collect();
            let f = |i: usize| DVec3::new(v[i] as f64, v[i + 1] as f64, v[i + 2] as f64);
            let d = det3(&exact(f(0)), &exact(f(3)), &exact(f(6)));
            let m = |i: usize| v[i] as i128;
            let want = m(0) * (m(4) * m(8) - m(5) * m(7)) - m(1) * (m(3) * m(8) - m(5) * m(6))
                + m(2) * (m(3) * m(7) - m(4) * m(6));
            assert_eq!(d.to_f64_approx(), want as f64);
        }
    }

    #[test]
    fn shifted_conversion() {
        for x in [1.0, -3.5, 0.1, 1e300, 5e-324, -2.5e-310, 123456789.123] {
            let d = Dyadic::from_f64(x);
            let t = d.top_exponent().unwrap();
            assert_eq!(t, top_exponent(x));
            let y = d.to_f64_shifted(-t);
            assert!((1.0..2.0).contains(&y.abs()), "{x}: {y}");
            assert_eq!(mul_pow2(y, t), x);
        }
        // A long value: (2^200 − 1) · 2^-1100, shifted into [1, 2).
        let a = Dyadic::from_f64(2f64.powi(200))
            .sub(&Dyadic::from_f64(1.0))
            .mul(&Dyadic::from_f64(2f64.powi(-1000)))
            .mul(&Dyadic::from_f64(2f64.powi(-100)));
        assert_eq!(a.top_exponent(), Some(-901));
        assert_eq!(a.to_f64_shifted(901), 2.0); // 2 − 2^-199, rounded
        assert_eq!(Dyadic::zero().top_exponent(), None);
    }

    #[test]
    fn extreme_exponents() {
        // det of a cube scaled by 2^-1000 / 2^1000 stays exact.
        for k in [-1000, -300, 0, 300, 1000] {
            let s = 2f64.powi(k);
            let d = det3(
                &exact(DVec3::X * s),
                &exact(DVec3::Y * s),
                &exact(DVec3::Z * s),
            );
            assert_eq!(d.sign(), Sign::Positive);
        }
        assert!(coordinate_span_ok([1e300, 1e-300].into_iter()).is_err());
        assert!(coordinate_span_ok([1e8, 1e-3, 1e-17, 0.0].into_iter()).is_ok());
    }
}
