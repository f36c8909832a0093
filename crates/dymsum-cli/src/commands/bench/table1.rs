//! `dymsum bench table1`: the paper's Experiment 1 (§5.1, Table 1).
//!
//! For every unordered pair of the 13 models (91 pairs, each model also
//! with itself; P is the row model of the paper's lower-triangular table,
//! Q the column model), P turns under the paper's motion at 500 steps per
//! turn for `--steps` steps. Every step is a timed DYMSUM update; `walk` is
//! timed at every pose (or `--walk-poses` evenly spaced ones), `brute` at
//! `--static-poses` evenly spaced poses and `hull` at `--hull-poses`
//! (see [`super::measure`]). The report gives the speedups
//! `brute_us / dymsum_us` and `walk_us / dymsum_us` beside the paper's
//! figure (t_bf / t_d).

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use dymsum_io::Loaded;

use super::measure::{measure, Plan, Timings};
use super::paper::{pairs, paper_name, paper_speedup, MODELS};
use super::{command_line, measure_each, num, out_file, sig3, write_csv, write_repeats_line};
use crate::commands::load;
use crate::stats::human_us;

/// Steps per full turn in Experiment 1 (the paper's x = 500).
pub const STEPS_PER_REV: f64 = 500.0;
/// Default number of DYMSUM steps per pair.
pub const DEFAULT_STEPS: usize = 5000;
/// Default number of poses per pair at which `brute` is timed.
pub const DEFAULT_STATIC_POSES: usize = 100;
/// Default number of poses per pair at which `hull` is timed.
pub const DEFAULT_HULL_POSES: usize = 3;

/// The CSV header, exactly.
pub const CSV_HEADER: [&str; 13] = [
    "p",
    "q",
    "p_input_facets",
    "p_faces",
    "q_input_facets",
    "q_faces",
    "dymsum_us",
    "walk_us",
    "brute_us",
    "hull_us",
    "speedup_brute",
    "speedup_walk",
    "paper_speedup",
];

/// `dymsum bench table1`.
#[derive(Debug, Args)]
pub struct Table1Args {
    /// DYMSUM steps per pair (500 steps = one full turn).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_STEPS,
          value_parser = super::parse_count)]
    pub steps: usize,
    /// Repeats of the whole measurement (same motion); each figure is the median of the repeats' means.
    #[arg(long, value_name = "R", default_value_t = 3, value_parser = super::parse_count)]
    pub repeats: usize,
    /// Seed of the motion (the same motion for every pair).
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// Output directory for table1.md and table1.csv (created if missing).
    #[arg(long, value_name = "DIR", default_value = ".")]
    pub out: PathBuf,
    /// Poses per pair, evenly spaced over the run, at which `brute` is timed.
    #[arg(long, value_name = "K", default_value_t = DEFAULT_STATIC_POSES,
          value_parser = super::parse_count)]
    pub static_poses: usize,
    /// Poses per pair at which `hull` is timed (0: not timed).
    #[arg(long, value_name = "K", default_value_t = DEFAULT_HULL_POSES,
          value_parser = super::parse_count0)]
    pub hull_poses: usize,
    /// Poses per pair at which `walk` is timed (default: every step).
    #[arg(long, value_name = "K",
          value_parser = super::parse_count)]
    pub walk_poses: Option<usize>,
}

/// One row of the table.
#[derive(Clone, Debug)]
pub struct Row {
    /// Moving operand (row model).
    pub p: String,
    /// Fixed operand (column model).
    pub q: String,
    /// Triangles of P's input mesh.
    pub p_input_facets: usize,
    /// Faces of P after merging coplanar triangles.
    pub p_faces: usize,
    /// Triangles of Q's input mesh.
    pub q_input_facets: usize,
    /// Faces of Q after merging.
    pub q_faces: usize,
    /// The timings.
    pub t: Timings,
    /// The paper's speedup.
    pub paper: f64,
}

impl Row {
    /// brute_us / dymsum_us.
    pub fn speedup_brute(&self) -> f64 {
        self.t.brute_us() / self.t.dymsum_us()
    }
    /// walk_us / dymsum_us.
    pub fn speedup_walk(&self) -> f64 {
        self.t.walk_us() / self.t.dymsum_us()
    }
    fn csv_record(&self) -> Vec<String> {
        vec![
            self.p.clone(),
            self.q.clone(),
            self.p_input_facets.to_string(),
            self.p_faces.to_string(),
            self.q_input_facets.to_string(),
            self.q_faces.to_string(),
            num(self.t.dymsum_us(), 3),
            num(self.t.walk_us(), 3),
            num(self.t.brute_us(), 3),
            num(self.t.hull_us(), 3),
            num(self.speedup_brute(), 2),
            num(self.speedup_walk(), 2),
            num(self.paper, 2),
        ]
    }
}

/// Runs `dymsum bench table1`.
///
/// # Errors
/// An operand cannot be loaded; the output directory, CSV or markdown files
/// cannot be written; a sum or a DYMSUM update fails (see
/// [`super::measure::measure`]); or, as an internal error, any facet-set
/// comparison disagrees with DYMSUM (reported after the files are written).
pub fn run(a: &Table1Args, out: &mut dyn Write) -> anyhow::Result<()> {
    let started = Instant::now();
    let loaded: Vec<Loaded> = MODELS
        .iter()
        .map(|(m, _)| load(m, "P", false))
        .collect::<anyhow::Result<_>>()?;
    let plan = Plan {
        steps_per_rev: STEPS_PER_REV,
        seed: a.seed,
        steps: a.steps,
        walk_poses: a.walk_poses.unwrap_or(a.steps),
        brute_poses: a.static_poses,
        hull_poses: a.hull_poses,
        repeats: a.repeats,
    };
    write_intro(out, a, &plan)?;

    let rows = measure_each(
        &pairs(),
        |(pn, qn)| format!("{pn} + {qn}"),
        |&(pn, qn)| measure_row(&loaded, pn, qn, &plan),
    )?;
    let elapsed = started.elapsed().as_secs_f64();

    // Files.
    let csv_path = write_csv(
        &a.out,
        "table1.csv",
        &CSV_HEADER,
        rows.iter().map(Row::csv_record),
    )?;
    let md_path = out_file(&a.out, "table1.md")?;
    let md = markdown(a, &plan, &rows, elapsed);
    dymsum_io::atomic::write_atomic_bytes(&md_path, md.as_bytes())?;

    let s = write_report(out, &rows)?;
    writeln!(
        out,
        "wrote {} and {} ({elapsed:.0} s)",
        csv_path.display(),
        md_path.display()
    )?;
    if s.mismatches > 0 {
        anyhow::bail!(
            "internal error: {} of {} facet-set comparisons disagreed with DYMSUM (please report)",
            s.mismatches,
            s.checks
        );
    }
    Ok(())
}

/// The opening paragraph: what is measured, how often.
fn write_intro(out: &mut dyn Write, a: &Table1Args, plan: &Plan) -> std::io::Result<()> {
    writeln!(
        out,
        "dymsum bench table1: 91 pairs of the paper's 13 models; P (row) turns {STEPS_PER_REV} steps per turn \
         (random axis held 1..=50 steps, seed {}), Q (column) fixed.\n\
         DYMSUM timed on all {} steps; walk on {}, brute on {} and hull on {} evenly spaced poses of the same run;",
        a.seed,
        a.steps,
        plan.walk_poses.min(a.steps),
        plan.brute_poses.min(a.steps),
        plan.hull_poses.min(a.steps),
    )?;
    write_repeats_line(out, a.repeats)?;
    out.flush()
}

/// Measures the pair `pn + qn` of the paper's models (`loaded` in the order
/// of [`MODELS`]).
fn measure_row(loaded: &[Loaded], pn: &str, qn: &str, plan: &Plan) -> anyhow::Result<Row> {
    let get = |name: &str| {
        let i = MODELS.iter().position(|(m, _)| *m == name).unwrap_or(0);
        &loaded[i]
    };
    let (p, q) = (get(pn), get(qn));
    let t = measure(&p.polytope, &q.polytope, plan)?;
    Ok(Row {
        p: pn.to_string(),
        q: qn.to_string(),
        p_input_facets: p.input.triangle_count(),
        p_faces: p.polytope.face_count(),
        q_input_facets: q.input.triangle_count(),
        q_faces: q.polytope.face_count(),
        t,
        paper: paper_speedup(pn, qn).unwrap_or(f64::NAN),
    })
}

/// The report after the run: the table of speedups, the summary and the
/// ellipse + ellipse line. Returns the summary.
fn write_report(out: &mut dyn Write, rows: &[Row]) -> std::io::Result<Summary> {
    writeln!(out)?;
    writeln!(
        out,
        "Speedup of DYMSUM over brute force, ours / paper's (brute_us / dymsum_us; the paper's t_bf / t_d):"
    )?;
    write!(out, "{}", layout_text(rows))?;
    writeln!(out)?;
    let s = summary(rows);
    writeln!(out, "{}", s.text())?;
    if let Some(ee) = find(rows, "ellipse", "ellipse") {
        writeln!(
            out,
            "ellipse + ellipse: DYMSUM {} per update, walk {}, brute {}, hull {}: {:.1}x brute (paper {:.2}x), {:.1}x walk",
            human_us(ee.t.dymsum_us()),
            human_us(ee.t.walk_us()),
            human_us(ee.t.brute_us()),
            if ee.t.hull.is_empty() { "-".to_string() } else { human_us(ee.t.hull_us()) },
            ee.speedup_brute(),
            ee.paper,
            ee.speedup_walk(),
        )?;
    }
    Ok(s)
}

/// Totals over the rows.
struct Summary {
    beat: usize,
    total: usize,
    geo_ratio: f64,
    min: (f64, String),
    max: (f64, String),
    checks: usize,
    mismatches: usize,
    recomputed: usize,
    steps: usize,
    hull_errors: usize,
    hull_calls: usize,
    walk_min: (f64, String),
    walk_max: (f64, String),
}

impl Summary {
    fn text(&self) -> String {
        format!(
            "ours >= paper's speedup on {} of {} pairs; geometric mean of ours / paper's: {:.2}; \
             our speedup over brute from {:.2}x ({}) to {:.1}x ({}); over walk from {:.2}x ({}) to {:.2}x ({}).\n\
             verified: {} facet-set comparisons (DYMSUM vs a fresh walk after the last step of every pair, \
             and vs brute and hull at their poses): {} mismatches.\n\
             {} of {} DYMSUM updates fell back to a from-scratch sum; hull failed on {} of {} calls.",
            self.beat,
            self.total,
            self.geo_ratio,
            self.min.0,
            self.min.1,
            self.max.0,
            self.max.1,
            self.walk_min.0,
            self.walk_min.1,
            self.walk_max.0,
            self.walk_max.1,
            self.checks,
            self.mismatches,
            self.recomputed,
            self.steps,
            self.hull_errors,
            self.hull_calls,
        )
    }
}

fn summary(rows: &[Row]) -> Summary {
    let name = |r: &Row| format!("{}+{}", r.p, r.q);
    let ext = |f: &dyn Fn(&Row) -> f64, max: bool| {
        rows.iter()
            .filter(|r| f(r).is_finite())
            .map(|r| (f(r), name(r)))
            .reduce(|a, b| if (b.0 > a.0) == max { b } else { a })
            .unwrap_or((f64::NAN, "-".into()))
    };
    let ratios: Vec<f64> = rows
        .iter()
        .map(|r| r.speedup_brute() / r.paper)
        .filter(|x| x.is_finite() && *x > 0.0)
        .collect();
    Summary {
        beat: rows.iter().filter(|r| r.speedup_brute() >= r.paper).count(),
        total: rows.len(),
        geo_ratio: (ratios.iter().map(|x| x.ln()).sum::<f64>() / ratios.len().max(1) as f64).exp(),
        min: ext(&|r| r.speedup_brute(), false),
        max: ext(&|r| r.speedup_brute(), true),
        walk_min: ext(&|r| r.speedup_walk(), false),
        walk_max: ext(&|r| r.speedup_walk(), true),
        checks: rows.iter().map(|r| r.t.checks).sum(),
        mismatches: rows.iter().map(|r| r.t.mismatches).sum(),
        recomputed: rows.iter().map(|r| r.t.recomputed).sum(),
        steps: rows.iter().map(|r| r.t.steps).sum(),
        hull_errors: rows.iter().map(|r| r.t.hull_errors).sum(),
        hull_calls: rows.iter().map(|r| r.t.hull_calls).sum(),
    }
}

fn find<'r>(rows: &'r [Row], p: &str, q: &str) -> Option<&'r Row> {
    rows.iter().find(|r| r.p == p && r.q == q)
}

/// The paper's layout as plain text: one cell `ours/paper` per pair.
fn layout_text(rows: &[Row]) -> String {
    const W: usize = 11;
    let mut s = String::new();
    for (i, (row, _)) in MODELS.iter().enumerate() {
        s.push_str(&format!("{:<9}", paper_name(row)));
        for (col, _) in MODELS.iter().take(i + 1) {
            let cell = find(rows, row, col)
                .map(|r| format!("{}/{}", sig3(r.speedup_brute()), sig3(r.paper)))
                .unwrap_or_default();
            s.push_str(&format!(" {cell:>W$}"));
        }
        s.push('\n');
    }
    s.push_str(&format!("{:<9}", ""));
    for (m, _) in MODELS {
        s.push_str(&format!(" {:>W$}", paper_name(m)));
    }
    s.push('\n');
    s
}

/// The paper's layout as a Markdown table; `cell` formats one pair.
fn layout_md(rows: &[Row], cell: &dyn Fn(&Row) -> String) -> String {
    let mut s = String::from("| |");
    for (m, _) in MODELS {
        s.push_str(&format!(" {} |", paper_name(m)));
    }
    s.push_str("\n|---|");
    s.push_str(&"---:|".repeat(MODELS.len()));
    s.push('\n');
    for (i, (row, _)) in MODELS.iter().enumerate() {
        s.push_str(&format!("| **{}** |", paper_name(row)));
        for (j, (col, _)) in MODELS.iter().enumerate() {
            let c = if j <= i {
                find(rows, row, col).map(cell).unwrap_or_default()
            } else {
                String::new()
            };
            s.push_str(&format!(" {c} |"));
        }
        s.push('\n');
    }
    s
}

fn markdown(a: &Table1Args, plan: &Plan, rows: &[Row], elapsed: f64) -> String {
    let s = summary(rows);
    let mut md = String::new();
    md.push_str("# Table 1: DYMSUM vs brute force on the paper's 13 models\n\n");
    md.push_str(&format!(
        "Command: `{}` ({elapsed:.0} s).\n\n",
        command_line()
    ));
    md.push_str(&format!(
        "P (row) turns {STEPS_PER_REV} steps per full turn under the paper's motion (a random axis held \
         1 to 50 steps, seed {}); Q (column) is fixed. DYMSUM is timed on all {} steps of every pair; \
         `walk` on {}, `brute` on {} and `hull` on {} evenly spaced poses of the same run \
         (a deterministic subsample: the static methods' times hardly depend on the pose). \
         Times are means in µs per update or per static sum (facet set only, no merging); \
         the whole measurement is repeated {} times with the same motion (fresh DYMSUM state each time) \
         and each figure is the median of the repeats' means.\n\n",
        a.seed,
        a.steps,
        plan.walk_poses.min(a.steps),
        plan.brute_poses.min(a.steps),
        plan.hull_poses.min(a.steps),
        a.repeats,
    ));
    md.push_str(
        "## Speedup over brute force: ours / the paper's\n\n\
         Each cell is `brute_us / dymsum_us` (ours) / the paper's t_bf / t_d (P is the row model, Q the column model).\n\n",
    );
    md.push_str(&layout_md(rows, &|r| {
        format!("{} / {}", sig3(r.speedup_brute()), sig3(r.paper))
    }));
    md.push_str(
        "\n## Speedup over `walk` (ours only: the paper has no output-sensitive static method)\n\n",
    );
    md.push_str(&layout_md(rows, &|r| sig3(r.speedup_walk())));
    md.push_str(&format!(
        "\n## Summary\n\n{}\n",
        s.text().replace('\n', "\n\n")
    ));
    md.push_str("\n## All numbers\n\n| ");
    md.push_str(&CSV_HEADER.join(" | "));
    md.push_str(" |\n|");
    md.push_str(&"---|".repeat(2));
    md.push_str(&"---:|".repeat(CSV_HEADER.len() - 2));
    md.push('\n');
    for r in rows {
        md.push_str("| ");
        md.push_str(&r.csv_record().join(" | "));
        md.push_str(" |\n");
    }
    md
}
