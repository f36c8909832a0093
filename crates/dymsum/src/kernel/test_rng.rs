//! One seeded generator for the unit tests (xorshift64, Marsaglia 2003):
//! reproducible streams, the same on every machine, without a
//! dependency. Each test keeps its own seed.

/// A xorshift64 stream (a nonzero seed).
pub(crate) struct Xorshift(u64);

impl Xorshift {
    /// The stream from `seed` (which must not be zero).
    pub(crate) fn new(seed: u64) -> Xorshift {
        Xorshift(seed)
    }

    /// The next 64 bits.
    pub(crate) fn next_u64(&mut self) -> u64 {
        let mut s = self.0;
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        self.0 = s;
        s
    }

    /// Uniform in `[0, 1)`, on 53 bits.
    pub(crate) fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[−1, 1)`.
    pub(crate) fn signed(&mut self) -> f64 {
        self.unit() * 2.0 - 1.0
    }
}
