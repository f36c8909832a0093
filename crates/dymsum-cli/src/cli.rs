//! The command line: subcommands, flags and their value parsers.
//!
//! Every flag value is checked by a clap value parser, so a malformed or
//! meaningless value (`--rotate-p 1,2`, a NaN, a zero quaternion, an output
//! file with an unknown extension) is a usage error: clap prints it with the
//! usage line and the process exits with code 2. Bad *inputs* (missing
//! files, unknown models, non-convex meshes) are found later and exit 1.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use dymsum::sum::Method;
use dymsum::{DVec3, Rotation};

/// Exact static and dynamic Minkowski sums of convex polytopes.
///
/// Operands P and Q are mesh files (.off, .obj, .ply, .stl; a file with no
/// faces is a point cloud, whose hull is taken) or built-in model names
/// (`dymsum models` lists them, e.g. ellipse, gs4, tcube:10, random:1000:7).
#[derive(Debug, Parser)]
#[command(name = "dymsum", version)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Compute P ⊕ Q (P optionally rotated and translated) and write the merged mesh.
    Sum(SumArgs),
    /// Describe a polytope: counts, volume, and what validation changed.
    Info(InfoArgs),
    /// List the built-in models, or write one to a file (`--write NAME FILE`).
    Models(crate::commands::models::ModelsArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell).
    Completions(crate::commands::completions::CompletionsArgs),
    /// Turn P under the paper's random motion and keep P ⊕ Q up to date (DYMSUM).
    Animate(AnimateArgs),
    /// The main job on built-in models: DYMSUM vs static sums on ellipse ⊕ gs4.
    Demo(DemoArgs),
    /// Reproduce the paper's experiments: Table 1, Fig. 4 (rotation), Fig. 5 (size).
    Bench(crate::commands::bench::BenchArgs),
    /// Draw P ⊕ Q (SVG or PNG), optionally highlighting the facets a further turn changes.
    Render(crate::commands::render::RenderArgs),
    /// Configuration-space obstacle slices of a translating robot, one per orientation.
    Cobst(crate::commands::cobst::CobstArgs),
    /// Collision, penetration depth and distance of a robot at given poses.
    Query(crate::commands::query::QueryArgs),
}

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

/// `dymsum sum`.
#[derive(Debug, Args)]
pub struct SumArgs {
    /// First operand P: a mesh file or a built-in model name; `-` reads OFF
    /// from standard input.
    #[arg(value_name = "P")]
    pub p: String,
    /// Second operand Q: as P.
    #[arg(value_name = "Q")]
    pub q: String,
    /// Output mesh; the format follows the extension (.off, .obj, .ply, .stl);
    /// `-` writes OFF to standard output (the summary line then goes to stderr).
    #[arg(short, long, value_name = "OUT", value_parser = parse_output_path)]
    pub output: PathBuf,
    /// Static algorithm.
    #[arg(long, value_enum, default_value_t = MethodArg::Walk)]
    pub method: MethodArg,
    /// Rotate P about the origin by this unit quaternion, scalar first (W,X,Y,Z; renormalised), before summing.
    #[arg(long, value_name = "W,X,Y,Z", value_parser = parse_quaternion, allow_hyphen_values = true)]
    pub rotate_p: Option<Rotation>,
    /// Then translate P by this vector.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vector, allow_hyphen_values = true)]
    pub translate_p: Option<DVec3>,
    /// Refuse meshes that are convex only within tolerance (instead of using their exact hull).
    #[arg(long)]
    pub strict: bool,
}

/// `dymsum info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// A mesh file or a built-in model name.
    #[arg(value_name = "FILE|NAME")]
    pub spec: String,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Refuse meshes that are convex only within tolerance.
    #[arg(long)]
    pub strict: bool,
}

/// `dymsum animate`.
#[derive(Debug, Args)]
pub struct AnimateArgs {
    /// The moving operand P: a mesh file or a built-in model name.
    #[arg(value_name = "P")]
    pub p: String,
    /// The fixed operand Q: a mesh file or a built-in model name.
    #[arg(value_name = "Q")]
    pub q: String,
    /// Steps per full turn: each step turns P by 2π/X about the current axis.
    #[arg(long, value_name = "X", value_parser = parse_steps_per_rev)]
    pub steps_per_rev: f64,
    /// Number of steps.
    #[arg(long, value_name = "N")]
    pub steps: u64,
    /// Seed of the random axes and hold times.
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,
    /// Write one CSV row per step to this file.
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Write the merged sum as DIR/step_NNNNNN.off every K-th step and after the last.
    #[arg(long, value_name = "DIR")]
    pub frames_dir: Option<PathBuf>,
    /// Frame interval K (with --frames-dir).
    #[arg(long, value_name = "K", default_value_t = 1, requires = "frames_dir",
          value_parser = clap::value_parser!(u64).range(1..))]
    pub every: u64,
    /// Refuse meshes that are convex only within tolerance.
    #[arg(long)]
    pub strict: bool,
}

/// `dymsum demo`.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// How long to run the motion, in seconds.
    #[arg(long, value_name = "S", default_value_t = 3.0, value_parser = parse_seconds)]
    pub seconds: f64,
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
pub fn parse_quaternion(s: &str) -> Result<Rotation, String> {
    let v = parse_numbers(s, 4, "W,X,Y,Z")?;
    Rotation::from_wxyz(v[0], v[1], v[2], v[3])
        .ok_or_else(|| "the quaternion is zero (or too small to normalise)".to_string())
}

/// Parses a vector `X,Y,Z` of finite numbers.
pub fn parse_vector(s: &str) -> Result<DVec3, String> {
    let v = parse_numbers(s, 3, "X,Y,Z")?;
    Ok(DVec3::new(v[0], v[1], v[2]))
}

/// Parses `--steps-per-rev X`: a finite number > 0 whose step angle 2π/X is
/// finite too (so not a subnormal like `1e-320`).
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
pub fn parse_positive(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        Ok(x) if x.is_finite() => Err(format!("`{s}` must be greater than 0")),
        Ok(_) => Err(format!("`{s}` is not a finite number")),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

/// Parses a duration in seconds: finite, 0 to 3600.
pub fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && (0.0..=3600.0).contains(&x) => Ok(x),
        Ok(_) => Err(format!("`{s}` must be between 0 and 3600 seconds")),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

/// Checks that an output path has a mesh extension (`-`: OFF on standard
/// output).
pub fn parse_output_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    if s == crate::commands::STDIO {
        return Ok(path);
    }
    dymsum_io::formats::Format::from_path(&path)
        .map(|_| path)
        .map_err(|_| format!("`{s}` has no mesh extension (expected .off, .obj, .ply or .stl)"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn clap_definition_is_consistent() {
        Cli::command().debug_assert();
    }

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
