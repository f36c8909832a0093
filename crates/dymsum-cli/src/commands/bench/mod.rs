//! `dymsum bench`: the paper's experiments (§5), rerunnable by anyone.
//!
//! * `table1`: Experiment 1 / Table 1, DYMSUM against the static methods on
//!   all 91 pairs of the paper's 13 models ([`table1`]).
//! * `rotation`: Experiment 2 / Fig. 4, update time against steps per full
//!   turn ([`rotation`]).
//! * `size`: Experiment 3 / Fig. 5, update time against input size
//!   ([`size`]).
//!
//! Every experiment turns P under the paper's motion
//! ([`crate::random_motion::PaperMotion`]: a random axis held 1 to 50 steps, each
//! step 2π/X) with Q fixed, times every DYMSUM update, and times the static
//! methods afterwards on the same poses ([`measure`]). Results go to
//! stdout and to CSV (and Markdown or plots) in `--out DIR`.

pub mod measure;
pub mod paper;
pub mod plot;
pub mod rotation;
pub mod size;
pub mod table1;

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{Args, Subcommand};
use indicatif::ProgressBar;

/// Arguments of `dymsum bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Which experiment.
    #[command(subcommand)]
    pub experiment: Experiment,
}

/// The experiments.
#[derive(Debug, Subcommand)]
pub enum Experiment {
    /// The paper's Table 1: all 91 pairs of its 13 models, DYMSUM vs walk, brute and hull.
    Table1(table1::Table1Args),
    /// The paper's Fig. 4: mean update time against steps per full turn.
    Rotation(rotation::RotationArgs),
    /// The paper's Fig. 5: mean update time against input size (tessellated cubes, geodesic spheres).
    Size(size::SizeArgs),
}

/// Runs an experiment.
///
/// # Errors
/// Those of the experiment's `run` ([`table1::run`], [`rotation::run`],
/// [`size::run`]).
pub fn run(a: &BenchArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    match &a.experiment {
        Experiment::Table1(a) => table1::run(a, out),
        Experiment::Rotation(a) => rotation::run(a, out),
        Experiment::Size(a) => size::run(a, out),
    }
}

/// The bench progress bar (see [`crate::progress::bar`]).
pub(crate) fn progress(len: u64) -> ProgressBar {
    crate::progress::bar(len, "bench", "runs")
}

/// Runs `measure_job` on every job in order under one progress bar, whose
/// message names the job being measured (`label`); returns the results in
/// job order. The experiments' common measurement loop.
pub(crate) fn measure_each<J, R>(
    jobs: &[J],
    label: impl Fn(&J) -> String,
    mut measure_job: impl FnMut(&J) -> anyhow::Result<R>,
) -> anyhow::Result<Vec<R>> {
    let pb = progress(jobs.len() as u64);
    let mut results = Vec::with_capacity(jobs.len());
    for job in jobs {
        pb.set_message(label(job));
        results.push(measure_job(job)?);
        pb.inc(1);
    }
    pb.finish_and_clear();
    Ok(results)
}

/// The last line of every experiment's introduction: how the figures
/// combine the repeats.
pub(crate) fn write_repeats_line(out: &mut dyn Write, repeats: usize) -> std::io::Result<()> {
    writeln!(
        out,
        "all repeated {repeats} times with the same motion, each figure the median of the repeats' means."
    )
}

/// Creates the output directory ([`crate::commands::create_output_dir`])
/// and returns the path of `name` in it.
pub(crate) fn out_file(dir: &Path, name: &str) -> anyhow::Result<PathBuf> {
    crate::commands::create_output_dir(dir)?;
    Ok(dir.join(name))
}

/// Writes `header` and `records` as the CSV file `name` in `dir` (created
/// if missing); returns the file's path.
pub(crate) fn write_csv<R>(
    dir: &Path,
    name: &str,
    header: &[&str],
    records: impl IntoIterator<Item = R>,
) -> anyhow::Result<PathBuf>
where
    R: IntoIterator,
    R::Item: AsRef<[u8]>,
{
    let path = out_file(dir, name)?;
    let file = dymsum_io::atomic::AtomicFile::create(&path)?;
    let mut w = csv::Writer::from_writer(file);
    w.write_record(header)?;
    for r in records {
        w.write_record(r)?;
    }
    let file = w
        .into_inner()
        .map_err(|e| anyhow::anyhow!("{}", e.error()))?;
    file.commit()?;
    Ok(path)
}

/// A number for CSV: fixed decimals, `NaN` when not measured.
pub(crate) fn num(x: f64, decimals: usize) -> String {
    if x.is_finite() {
        format!("{x:.decimals$}")
    } else {
        "NaN".to_string()
    }
}

/// Three significant digits or so (`176`, `23.7`, `8.58`), `-` for NaN.
pub(crate) fn sig3(x: f64) -> String {
    if !x.is_finite() {
        "-".to_string()
    } else if x.abs() >= 100.0 {
        format!("{x:.0}")
    } else if x.abs() >= 10.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2}")
    }
}

/// Least-squares slope of `ln y` against `ln x` over the positive, finite
/// points (NaN with fewer than two distinct x).
///
/// ```
/// use dymsum_cli::commands::bench::loglog_slope;
/// let pts: Vec<(f64, f64)> = (1..=5).map(|x| (x as f64, 3.0 * (x as f64).powi(2))).collect();
/// assert!((loglog_slope(&pts) - 2.0).abs() < 1e-12);
/// ```
pub fn loglog_slope(points: &[(f64, f64)]) -> f64 {
    let v: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = v.len() as f64;
    if v.len() < 2 {
        return f64::NAN;
    }
    let mx = v.iter().map(|p| p.0).sum::<f64>() / n;
    let my = v.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = v.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = v.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        f64::NAN
    } else {
        sxy / sxx
    }
}

/// The command line that reproduces a run, for the reports.
pub(crate) fn command_line() -> String {
    let mut args = std::env::args();
    let _ = args.next();
    let rest: Vec<String> = args.collect();
    format!("dymsum {}", rest.join(" "))
}

/// Parses a count from 1 to 10,000,000.
pub(crate) fn parse_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=10_000_000).contains(&n) => Ok(n),
        _ => Err(format!("`{s}` must be a whole number from 1 to 10000000")),
    }
}

/// Parses a count from 0 to 10,000,000.
pub(crate) fn parse_count0(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n <= 10_000_000 => Ok(n),
        _ => Err(format!("`{s}` must be a whole number from 0 to 10000000")),
    }
}
