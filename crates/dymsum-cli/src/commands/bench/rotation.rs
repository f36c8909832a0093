//! `dymsum bench rotation`: the paper's Experiment 2 (§5.2, Fig. 4).
//!
//! Mean time per step against the rotational resolution X (steps per full
//! turn): for every pair and every X, P turns `--steps` steps of 2π/X under
//! the paper's motion; DYMSUM is timed at every step, `walk` at every pose
//! and `brute` at `--static-poses` evenly spaced poses. Writes
//! `rotation.csv` and the plot `rotation.svg` / `rotation.png` (log–log).

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use dymsum_io::Loaded;

use super::measure::{ensure_no_mismatches, measure, write_verified, Figures, Plan};
use super::plot::{method_series, write_chart, Chart, COLORS};
use super::{measure_each, out_file, write_csv, write_repeats_line};
use crate::commands::load;
use crate::stats::human_us;
use crate::values::parse_steps_per_rev;

/// Default steps per full turn (10 to 100,000).
pub const DEFAULT_STEPS_PER_REV: &str = "10,30,100,300,500,1000,3000,10000,30000,100000";
/// Default pairs.
pub const DEFAULT_PAIRS: &str = "ellipse+ellipse,gs4+gs4,cube+cube";

/// The CSV header.
pub const CSV_HEADER: [&str; 12] = [
    "p",
    "q",
    "steps_per_rev",
    "steps",
    "dymsum_us",
    "walk_us",
    "brute_us",
    "recomputed_steps",
    "checks",
    "mismatches",
    "changes_per_step",
    "dymsum_ns_per_change",
];

/// `dymsum bench rotation`.
#[derive(Debug, Args)]
pub struct RotationArgs {
    /// Steps per full turn (each step turns P by 2π/X), comma-separated.
    #[arg(long, value_name = "LIST", value_delimiter = ',', value_parser = parse_steps_per_rev,
          default_value = DEFAULT_STEPS_PER_REV)]
    pub steps_per_rev: Vec<f64>,
    /// Pairs `P+Q` of built-in models or files, comma-separated (P turns, Q is fixed).
    #[arg(long, value_name = "P+Q,...", value_delimiter = ',', value_parser = parse_pair,
          default_value = DEFAULT_PAIRS)]
    pub pairs: Vec<(String, String)>,
    /// DYMSUM steps per pair and X.
    #[arg(long, value_name = "N", default_value_t = 2000,
          value_parser = super::parse_count)]
    pub steps: usize,
    /// Poses per pair and X, evenly spaced over the run, at which `brute` is timed.
    #[arg(long, value_name = "K", default_value_t = 20,
          value_parser = super::parse_count)]
    pub static_poses: usize,
    /// Repeats of the whole measurement (same motion); each figure is the median of the repeats' means.
    #[arg(long, value_name = "R", default_value_t = 3, value_parser = super::parse_count)]
    pub repeats: usize,
    /// Seed of the motion.
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// Output directory for rotation.csv, rotation.svg and rotation.png
    /// (created if missing).
    #[arg(long, value_name = "DIR", default_value = ".")]
    pub out: PathBuf,
}

/// Parses `P+Q` into its two operands.
///
/// # Errors
/// A message when `s` has no `+` or either side is blank.
pub fn parse_pair(s: &str) -> Result<(String, String), String> {
    match s.split_once('+') {
        Some((p, q)) if !p.trim().is_empty() && !q.trim().is_empty() => {
            Ok((p.trim().to_string(), q.trim().to_string()))
        }
        _ => Err(format!("`{s}` is not a pair P+Q (e.g. ellipse+gs4)")),
    }
}

/// One point of the figure.
struct Point {
    pair: usize,
    x: f64,
    f: Figures,
}

/// Runs `dymsum bench rotation`.
///
/// # Errors
/// An operand cannot be loaded; the output directory, CSV or chart files
/// cannot be written; a sum or a DYMSUM update fails (see
/// [`super::measure::measure`]); or, as an internal error, any facet-set
/// comparison disagrees with DYMSUM (reported after the files are written).
pub fn run(a: &RotationArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    let started = Instant::now();
    let mut loaded = Vec::new();
    for (p, q) in &a.pairs {
        loaded.push((load(p, "P", false)?, load(q, "Q", false)?));
    }
    let mut xs = a.steps_per_rev.clone();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    writeln!(
        out,
        "dymsum bench rotation: mean time per step against steps per full turn X; P turns {} steps of 2π/X \
         (random axis held 1..=50 steps, seed {}); DYMSUM and walk timed at every step, brute at {} evenly spaced poses;",
        a.steps,
        a.seed,
        a.static_poses.min(a.steps),
    )?;
    write_repeats_line(out, a.repeats)?;
    out.flush()?;

    let jobs: Vec<(usize, f64)> = (0..a.pairs.len())
        .flat_map(|i| xs.iter().map(move |&x| (i, x)))
        .collect();
    let points = measure_each(
        &jobs,
        |&(i, x)| {
            let (pn, qn) = &a.pairs[i];
            format!("{pn} + {qn}, X = {x}")
        },
        |&(pair, x)| measure_point(a, &loaded[pair], pair, x),
    )?;

    let csv_path = write_rotation_csv(a, &points)?;
    let svg = out_file(&a.out, "rotation.svg")?;
    let png = out_file(&a.out, "rotation.png")?;
    write_chart(&rotation_chart(&a.pairs, &points), &svg, &png)?;

    writeln!(out)?;
    write_rotation_table(out, &a.pairs, &points)?;
    let mismatches = write_verified(out, points.iter().map(|p| &p.f))?;
    writeln!(
        out,
        "wrote {}, {} and {} ({:.0} s)",
        csv_path.display(),
        svg.display(),
        png.display(),
        started.elapsed().as_secs_f64()
    )?;
    ensure_no_mismatches(mismatches)
}

/// Measures one pair (`loaded`, the pair's index `pair`) at `x` steps per
/// turn.
fn measure_point(
    a: &RotationArgs,
    loaded: &(Loaded, Loaded),
    pair: usize,
    x: f64,
) -> anyhow::Result<Point> {
    let plan = Plan::walk_and_brute(x, a.seed, a.steps, a.static_poses, a.repeats);
    let (p, q) = loaded;
    let t = measure(&p.polytope, &q.polytope, &plan)?;
    Ok(Point {
        pair,
        x,
        f: t.figures(),
    })
}

/// Writes `rotation.csv` in `a.out`; returns its path.
fn write_rotation_csv(a: &RotationArgs, points: &[Point]) -> anyhow::Result<PathBuf> {
    write_csv(
        &a.out,
        "rotation.csv",
        &CSV_HEADER,
        points.iter().map(|pt| {
            let (pn, qn) = &a.pairs[pt.pair];
            let mut record = vec![pn.clone(), qn.clone(), format!("{}", pt.x)];
            record.extend(pt.f.csv_fields());
            record
        }),
    )
}

/// Fig. 4: time per step against X, one colour per pair.
fn rotation_chart(pairs: &[(String, String)], points: &[Point]) -> Chart {
    let mut series = Vec::new();
    for (i, (pn, qn)) in pairs.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        series.extend(method_series(
            &format!("{pn}+{qn}"),
            color,
            &["DYMSUM", "walk", "brute"],
            |time| {
                points
                    .iter()
                    .filter(|p| p.pair == i)
                    .map(|p| (p.x, time(&p.f)))
                    .collect()
            },
        ));
    }
    Chart {
        title: "Fig. 4: mean time per step vs rotational resolution".into(),
        x_label: "steps per full turn (X); each step turns P by 2π/X".into(),
        y_label: "mean time per step (µs)".into(),
        x_log: true,
        y_log: true,
        series,
    }
}

/// The per-pair, per-X table of the report.
fn write_rotation_table(
    out: &mut dyn Write,
    pairs: &[(String, String)],
    points: &[Point],
) -> std::io::Result<()> {
    writeln!(
        out,
        "{:<18} {:>8} {:>12} {:>12} {:>12} {:>9} {:>9} {:>11}",
        "P+Q", "X", "DYMSUM", "walk", "brute", "÷walk", "÷brute", "recomputed"
    )?;
    for pt in points {
        let (pn, qn) = &pairs[pt.pair];
        writeln!(
            out,
            "{:<18} {:>8} {:>12} {:>12} {:>12} {:>8.1}x {:>8.1}x {:>11}",
            format!("{pn}+{qn}"),
            pt.x,
            human_us(pt.f.dymsum),
            human_us(pt.f.walk),
            human_us(pt.f.brute),
            pt.f.walk / pt.f.dymsum,
            pt.f.brute / pt.f.dymsum,
            format!("{}/{}", pt.f.recomputed, pt.f.steps),
        )?;
    }
    Ok(())
}
