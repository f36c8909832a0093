//! Value parsers and value types shared by several subcommands' arguments
//! (quaternions, vectors, positive numbers, durations, output paths, the
//! static method). Each rejects a malformed or meaningless value with a
//! message, so clap reports it as a usage error (exit 2).

use std::path::PathBuf;

use clap::ValueEnum;
use dymsum::sum::Method;
use dymsum::{DVec3, Rotation};

/// The operand or output name for standard input or output.
pub const STDIO: &str = "-";

/// A static method, as a command-line value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// Output-sensitive walks in the Gaussian maps (fastest).
    Walk,
    /// Test every face–vertex and edge–edge pair (the paper's baseline).
    Brute,
    /// Exact hull of all pairwise vertex sums.
    Hull,
}

impl From<MethodArg> for Method {
    fn from(m: MethodArg) -> Method {
        match m {
            MethodArg::Walk => Method::Walk,
            MethodArg::Brute => Method::Brute,
            MethodArg::Hull => Method::Hull,
        }
    }
}

/// Parses `N1,N2,...` into exactly `n` finite numbers.
fn parse_numbers(s: &str, n: usize, what: &str) -> Result<Vec<f64>, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != n {
        return Err(format!(
            "expected {n} comma-separated numbers ({what}), got {}",
            parts.len()
        ));
    }
    parts
        .iter()
        .map(|p| match p.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            Ok(_) => Err(format!("`{p}` is not a finite number")),
            Err(_) => Err(format!("`{p}` is not a number")),
        })
        .collect()
}

/// Parses a quaternion `W,X,Y,Z` (renormalised; zero or non-finite refused).
///
/// # Errors
/// A message (shown by clap as a usage error) when there are not exactly
/// four comma-separated values, a value is not a finite number, or the
/// quaternion is zero.
pub fn parse_quaternion(s: &str) -> Result<Rotation, String> {
    let v = parse_numbers(s, 4, "W,X,Y,Z")?;
    Rotation::from_wxyz(v[0], v[1], v[2], v[3])
        .ok_or_else(|| "the quaternion is zero (or too small to normalise)".to_string())
}

/// Parses a vector `X,Y,Z` of finite numbers.
///
/// # Errors
/// A message when there are not exactly three comma-separated values or a
/// value is not a finite number.
pub fn parse_vector(s: &str) -> Result<DVec3, String> {
    let v = parse_numbers(s, 3, "X,Y,Z")?;
    Ok(DVec3::new(v[0], v[1], v[2]))
}

/// Parses `--steps-per-rev X`: a finite number > 0 whose step angle 2π/X is
/// finite too (so not a subnormal like `1e-320`).
///
/// # Errors
/// A message when the value is not a finite number greater than 0 (as
/// [`parse_positive`]) or so small that `2π/X` overflows, naming the
/// smallest accepted value.
pub fn parse_steps_per_rev(s: &str) -> Result<f64, String> {
    let x = parse_positive(s)?;
    let angle = std::f64::consts::TAU / x;
    if !angle.is_finite() {
        return Err(format!(
            "`{s}` steps per turn gives a step angle 2π/X that is not finite; give at least {:e}",
            std::f64::consts::TAU / f64::MAX
        ));
    }
    Ok(x)
}

/// Parses a finite number > 0.
///
/// # Errors
/// A message saying whether the value is not a number, not finite, or not
/// greater than 0.
pub fn parse_positive(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        Ok(x) if x.is_finite() => Err(format!("`{s}` must be greater than 0")),
        Ok(_) => Err(format!("`{s}` is not a finite number")),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

/// Parses a duration in seconds: finite, 0 to 3600.
///
/// # Errors
/// A message when the value is not a number or lies outside `0..=3600`
/// (NaN and infinities included).
pub fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && (0.0..=3600.0).contains(&x) => Ok(x),
        Ok(_) => Err(format!("`{s}` must be between 0 and 3600 seconds")),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

/// Checks that an output path has a mesh extension (`-`: OFF on standard
/// output).
///
/// # Errors
/// A message when the path (other than `-`) does not end in `.off`,
/// `.obj`, `.ply` or `.stl` (any case).
pub fn parse_output_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    if s == STDIO {
        return Ok(path);
    }
    dymsum_io::formats::Format::from_path(&path)
        .map(|_| path)
        .map_err(|_| format!("`{s}` has no mesh extension (expected .off, .obj, .ply or .stl)"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn value_parsers() {
        assert!(parse_quaternion("1,0,0,0").is_ok());
        assert!(parse_quaternion("2,0,0,0").unwrap() == Rotation::IDENTITY);
        assert!(parse_quaternion("1,2").is_err());
        assert!(parse_quaternion("0,0,0,0").is_err());
        assert!(parse_quaternion("NaN,0,0,1").is_err());
        assert!(parse_quaternion("inf,0,0,1").is_err());
        assert_eq!(
            parse_vector("1, -2,3e1").unwrap(),
            DVec3::new(1.0, -2.0, 30.0)
        );
        assert!(parse_vector("1,2,x").is_err());
        assert!(parse_positive("0").is_err());
        assert!(parse_positive("500").is_ok());
        assert!(parse_seconds("-1").is_err());
        assert!(parse_output_path("a.OFF").is_ok());
        assert!(parse_output_path("a.txt").is_err());
    }
}
