//! Small timing helpers: mean, median and human-readable durations.
//!
//! ```
//! use dymsum_cli::stats::{mean, median, human_us};
//! assert_eq!(mean(&[1.0, 2.0, 6.0]), 3.0);
//! assert_eq!(median(&[5.0, 1.0, 2.0, 9.0]), 3.5);
//! assert_eq!(human_us(1234.0), "1.23 ms");
//! assert_eq!(human_us(12.345), "12.3 µs");
//! ```

/// Arithmetic mean (0 for an empty slice).
pub fn mean(xs: &[f64]) -> f64 {
    if xs.is_empty() {
        0.0
    } else {
        xs.iter().sum::<f64>() / xs.len() as f64
    }
}

/// Median (mean of the two middle values for an even count; 0 if empty).
pub fn median(xs: &[f64]) -> f64 {
    if xs.is_empty() {
        return 0.0;
    }
    let mut v = xs.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

/// A duration given in microseconds, as `"12.3 µs"`, `"1.23 ms"` or `"1.23 s"`.
pub fn human_us(us: f64) -> String {
    if us < 1000.0 {
        format!("{us:.1} µs")
    } else if us < 1_000_000.0 {
        format!("{:.2} ms", us / 1000.0)
    } else {
        format!("{:.2} s", us / 1_000_000.0)
    }
}

/// A number for human-readable output, never hundreds of digits: Rust's
/// shortest round-trip form when `1e-4 <= |x| < 1e15` (or `x` is 0, or not
/// finite), otherwise scientific (`{:e}`), e.g. `1e300`.
///
/// ```
/// use dymsum_cli::stats::short;
/// assert_eq!(short(2.5), "2.5");
/// assert_eq!(short(1e300), "1e300");
/// assert_eq!(short(-1.5e-200), "-1.5e-200");
/// ```
pub fn short(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// `x` with `decimals` decimals, switching to scientific notation with as
/// many mantissa decimals outside `1e-4 <= |x| < 1e15` (0 stays fixed).
///
/// ```
/// use dymsum_cli::stats::fixed;
/// assert_eq!(fixed(1.5, 3), "1.500");
/// assert_eq!(fixed(1e300, 3), "1.000e300");
/// ```
pub fn fixed(x: f64, decimals: usize) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&x.abs()) {
        format!("{x:.decimals$}")
    } else {
        format!("{x:.decimals$e}")
    }
}

/// `x` with `decimals` decimals (`{:.N}`), never as a negative zero: a
/// value that rounds to zero prints as `0.000…` whatever its sign.
///
/// ```
/// use dymsum_cli::stats::decimals;
/// assert_eq!(decimals(-1.9e-7, 6), "0.000000");
/// assert_eq!(decimals(-0.25, 2), "-0.25");
/// ```
pub fn decimals(x: f64, decimals: usize) -> String {
    let s = format!("{x:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_string(),
        _ => s,
    }
}

/// Microseconds elapsed in a [`std::time::Duration`], as a float.
pub fn micros(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1e6
}
