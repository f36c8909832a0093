//! `dymsum bench size`: the paper's Experiment 3 (§5.3, Fig. 5).
//!
//! Mean time per step against input size, for two identical operands P = Q
//! of two families: the paper's tessellated 10×10×10 cube `tcube:K`
//! (12 K² triangles, K = 1..10 gives the paper's 12 to 1200) and geodesic
//! spheres `sphere:N` (20 N² triangles, no coplanar facets). P turns at 500
//! steps per turn; DYMSUM and `walk` are timed at every step, `brute` at
//! `--static-poses` evenly spaced poses. Prints the fitted growth exponent
//! (least-squares slope of log time against log input triangles) of every
//! method and family; writes `size.csv`, `size_vs_brute.svg/.png` (Fig.
//! 5a: DYMSUM and brute), `size_dymsum.svg/.png` (Fig. 5b: DYMSUM alone)
//! and `size_per_change.svg/.png` (DYMSUM's time per facet change against
//! faces: flat when the update costs in proportion to the changes; issue
//! 10 §1). `--steps-per-turn` changes the resolution, `--brute-max-faces`
//! skips the quadratic brute force on large models.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;

use super::measure::{ensure_no_mismatches, measure, write_verified, Figures, Plan};
use super::plot::{method_series, write_chart, Chart, Marker, MethodTime, Series, COLORS, METHODS};
use super::{loglog_slope, measure_each, num, out_file, write_csv, write_repeats_line};
use crate::commands::load;
use crate::stats::human_us;

/// Steps per full turn (the paper's x = 500).
pub const STEPS_PER_REV: f64 = 500.0;

/// The CSV header.
pub const CSV_HEADER: [&str; 13] = [
    "family",
    "model",
    "input_triangles",
    "faces",
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

/// `dymsum bench size`.
#[derive(Debug, Args)]
pub struct SizeArgs {
    /// Tessellations K of the cube `tcube:K` (12 K² triangles), comma-separated.
    #[arg(long, value_name = "LIST", value_delimiter = ',', default_value = "1,2,3,4,5,6,7,8,9,10",
          value_parser = clap::value_parser!(u32).range(1..=100))]
    pub tcube: Vec<u32>,
    /// Frequencies N of the geodesic sphere `sphere:N` (20 N² triangles), comma-separated.
    #[arg(long, value_name = "LIST", value_delimiter = ',', default_value = "1,2,3,4,5,6,7,8",
          value_parser = clap::value_parser!(u32).range(1..=32))]
    pub sphere: Vec<u32>,
    /// DYMSUM steps per model.
    #[arg(long, value_name = "N", default_value_t = 2000,
          value_parser = super::parse_count)]
    pub steps: usize,
    /// Poses per model, evenly spaced over the run, at which `brute` is timed.
    #[arg(long, value_name = "K", default_value_t = 30,
          value_parser = super::parse_count)]
    pub static_poses: usize,
    /// Repeats of the whole measurement (same motion); each figure is the median of the repeats' means.
    #[arg(long, value_name = "R", default_value_t = 3, value_parser = super::parse_count)]
    pub repeats: usize,
    /// Seed of the motion.
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// Steps per full turn of the motion (the paper's 500; larger means
    /// smaller steps and fewer facet changes per step).
    #[arg(long, value_name = "X", default_value_t = STEPS_PER_REV,
          value_parser = crate::values::parse_steps_per_rev)]
    pub steps_per_turn: f64,
    /// `brute` is timed only on models with at most this many faces (it
    /// is quadratic: about a second per sum at 5,000 faces); larger models
    /// show no brute figure.
    #[arg(long, value_name = "F", default_value_t = 2000)]
    pub brute_max_faces: usize,
    /// Output directory for size.csv and the plots (created if missing).
    #[arg(long, value_name = "DIR", default_value = ".")]
    pub out: PathBuf,
}

/// One point of the figure.
struct Point {
    family: &'static str,
    model: String,
    triangles: usize,
    faces: usize,
    f: Figures,
}

/// The two families.
const FAMILIES: [(&str, &str); 2] = [
    ("tcube", "tessellated cube tcube:K"),
    ("sphere", "geodesic sphere sphere:N"),
];

/// Runs `dymsum bench size`.
///
/// # Errors
/// An operand cannot be loaded; the output directory, CSV or chart files
/// cannot be written; a sum or a DYMSUM update fails (see
/// [`super::measure::measure`]); or, as an internal error, any facet-set
/// comparison disagrees with DYMSUM (reported after the files are written).
pub fn run(a: &SizeArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    let started = Instant::now();
    let mut models: Vec<(&'static str, String)> = Vec::new();
    models.extend(a.tcube.iter().map(|k| ("tcube", format!("tcube:{k}"))));
    models.extend(a.sphere.iter().map(|n| ("sphere", format!("sphere:{n}"))));
    let plan = Plan::walk_and_brute(a.steps_per_turn, a.seed, a.steps, a.static_poses, a.repeats);
    writeln!(
        out,
        "dymsum bench size: two identical operands P = Q of growing size; P turns {} steps at {} \
         steps per turn (seed {}); DYMSUM and walk timed at every step, brute at {} evenly spaced poses \
         (models of at most {} faces);",
        a.steps,
        a.steps_per_turn,
        a.seed,
        a.static_poses.min(a.steps),
        a.brute_max_faces,
    )?;
    write_repeats_line(out, a.repeats)?;
    out.flush()?;

    let points = measure_each(
        &models,
        |(_, name)| format!("{name} + {name}"),
        |(family, name)| measure_model(family, name, &plan, a.brute_max_faces),
    )?;
    let mut written = vec![write_size_csv(&a.out, &points)?.display().to_string()];
    written.extend(write_size_charts(&a.out, &points)?);

    writeln!(out)?;
    write_size_table(out, &points)?;
    writeln!(out)?;
    write_growth_exponents(out, &points)?;
    let mismatches = write_verified(out, points.iter().map(|p| &p.f))?;
    writeln!(
        out,
        "wrote {} ({:.0} s)",
        written.join(", "),
        started.elapsed().as_secs_f64()
    )?;
    ensure_no_mismatches(mismatches)
}

/// Measures the model `name` of `family` summed with itself.
fn measure_model(
    family: &'static str,
    name: &str,
    plan: &Plan,
    brute_max_faces: usize,
) -> anyhow::Result<Point> {
    let m = load(name, "P", false)?;
    let mut plan = *plan;
    if m.polytope.face_count() > brute_max_faces {
        plan.brute_poses = 0;
    }
    let t = measure(&m.polytope, &m.polytope, &plan)?;
    Ok(Point {
        family,
        model: name.to_string(),
        triangles: m.input.triangle_count(),
        faces: m.polytope.face_count(),
        f: t.figures(),
    })
}

/// Writes `size.csv` in `dir`; returns its path.
fn write_size_csv(dir: &Path, points: &[Point]) -> anyhow::Result<PathBuf> {
    write_csv(
        dir,
        "size.csv",
        &CSV_HEADER,
        points.iter().map(|p| {
            let mut record = vec![
                p.family.to_string(),
                p.model.clone(),
                p.triangles.to_string(),
                p.faces.to_string(),
            ];
            record.extend(p.f.csv_fields());
            record
        }),
    )
}

/// `(input triangles, time)` of every point of `family`, `time` picking a
/// method's figure.
fn family_points(points: &[Point], family: &str, time: MethodTime) -> Vec<(f64, f64)> {
    points
        .iter()
        .filter(|p| p.family == family)
        .map(|p| (p.triangles as f64, time(&p.f)))
        .collect()
}

/// The non-empty series of the methods `wanted`, for both families.
fn family_series(points: &[Point], wanted: &[&str]) -> Vec<Series> {
    let mut v = Vec::new();
    for (fi, (fam, _)) in FAMILIES.iter().enumerate() {
        let all = method_series(fam, COLORS[fi], wanted, |time| {
            family_points(points, fam, time)
        });
        v.extend(all.into_iter().filter(|s| !s.points.is_empty()));
    }
    v
}

/// Writes Fig. 5 (a) and (b) as SVG and PNG in `dir`; returns the paths.
fn write_size_charts(dir: &Path, points: &[Point]) -> anyhow::Result<Vec<String>> {
    let x_label = "input triangles per operand (P = Q)".to_string();
    let chart_a = Chart {
        title: "Fig. 5 (a): DYMSUM and brute force vs input size".into(),
        x_label: x_label.clone(),
        y_label: "mean time per step (µs)".into(),
        x_log: true,
        y_log: true,
        series: family_series(points, &["DYMSUM", "brute"]),
    };
    let chart_b = Chart {
        title: "Fig. 5 (b): DYMSUM alone vs input size".into(),
        x_label,
        y_label: "mean DYMSUM update time (µs)".into(),
        x_log: false,
        y_log: false,
        series: family_series(points, &["DYMSUM"]),
    };
    let chart_c = Chart {
        title: "DYMSUM time per facet change vs input size".into(),
        x_label: "faces per operand (P = Q)".into(),
        y_label: "mean update time per facet change (ns)".into(),
        x_log: true,
        y_log: false,
        series: per_change_series(points),
    };
    let files = [
        ("size_vs_brute.svg", "size_vs_brute.png", &chart_a),
        ("size_dymsum.svg", "size_dymsum.png", &chart_b),
        ("size_per_change.svg", "size_per_change.png", &chart_c),
    ];
    let mut written = Vec::new();
    for (svg, png, chart) in files {
        let (svg, png) = (out_file(dir, svg)?, out_file(dir, png)?);
        write_chart(chart, &svg, &png)?;
        written.push(svg.display().to_string());
        written.push(png.display().to_string());
    }
    Ok(written)
}

/// DYMSUM's time per facet change against faces, one series per family.
fn per_change_series(points: &[Point]) -> Vec<Series> {
    FAMILIES
        .iter()
        .enumerate()
        .map(|(fi, (fam, desc))| Series {
            label: format!("DYMSUM, {desc}"),
            color: COLORS[fi],
            marker: Marker::Circle,
            dashed: false,
            points: points
                .iter()
                .filter(|p| p.family == *fam)
                .map(|p| (p.faces as f64, p.f.ns_per_change()))
                .collect(),
        })
        .filter(|s| s.points.iter().any(|(_, y)| y.is_finite()))
        .collect()
}

/// The per-model table of the report.
fn write_size_table(out: &mut dyn Write, points: &[Point]) -> std::io::Result<()> {
    writeln!(
        out,
        "{:<11} {:>9} {:>6} {:>12} {:>12} {:>12} {:>9} {:>9} {:>9} {:>11}",
        "model",
        "triangles",
        "faces",
        "DYMSUM",
        "walk",
        "brute",
        "÷brute",
        "changes",
        "ns/change",
        "recomputed"
    )?;
    for p in points {
        writeln!(
            out,
            "{:<11} {:>9} {:>6} {:>12} {:>12} {:>12} {:>8.1}x {:>9.1} {:>9.0} {:>11}",
            p.model,
            p.triangles,
            p.faces,
            human_us(p.f.dymsum),
            human_us(p.f.walk),
            human_us(p.f.brute),
            p.f.brute / p.f.dymsum,
            p.f.changes,
            p.f.ns_per_change(),
            format!("{}/{}", p.f.recomputed, p.f.steps),
        )?;
    }
    Ok(())
}

/// The fitted growth exponent of every method, per measured family.
fn write_growth_exponents(out: &mut dyn Write, points: &[Point]) -> std::io::Result<()> {
    writeln!(
        out,
        "fitted growth exponent (time ~ triangles^k, least squares on log-log):"
    )?;
    for (fam, desc) in FAMILIES {
        if !points.iter().any(|p| p.family == fam) {
            continue;
        }
        let ks: Vec<String> = METHODS
            .iter()
            .map(|&(method, _, _, time)| {
                format!(
                    "{method} k = {}",
                    num(loglog_slope(&family_points(points, fam, time)), 2)
                )
            })
            .collect();
        writeln!(out, "  {desc}: {}", ks.join(", "))?;
    }
    Ok(())
}
