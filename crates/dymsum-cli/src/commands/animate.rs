//! `dymsum animate P Q --steps-per-rev X --steps N --seed S [--csv FILE]
//! [--frames-dir DIR --every K]`: P turns under the paper's motion while Q
//! stays at its input pose; DYMSUM keeps the sum up to date.
//!
//! CSV columns: `step,qw,qx,qy,qz,fv_errors,ee_errors,removed,added,facets,update_us`,
//! one row per step (1..=N); the quaternion is P's orientation (applied to
//! its input coordinates) after the step, `update_us` the DYMSUM update time
//! in microseconds. Frames `DIR/step_NNNNNN.off` hold the merged sum after the
//! update of the row with the same step number, every K-th step and the last.
//!
//! With a non-convex operand (a union of convex pieces or a closed mesh of
//! convex components, as `dymsum sum` takes them), one dynamic sum per
//! piece pair is updated by DYMSUM each step (the CSV row adds up the
//! pairs' counts, `update_us` their total time), and each frame is the
//! union of the current pair sums, merged by `boolmesh` and validated.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context};
use clap::Args;
use dymsum::sum::{minkowski_sum_posed, Method};
use dymsum::{DynamicSum, Pose, UpdateReport};
use dymsum_io::atomic::AtomicFile;
use dymsum_io::formats::{write_mesh_with, Format};
use indicatif::ProgressBar;

use super::solid::{convex_operands, load_solid};
use super::{load, short_name};
use crate::random_motion::PaperMotion;
use crate::stats::{human_us, mean, median, micros};
use crate::values::parse_steps_per_rev;
use dymsum::nonconvex::DynamicUnionSum;
use dymsum::ConvexUnion;

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
    /// Write one CSV row per step to this file (its folder is created if missing).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Write the merged sum as DIR/step_NNNNNN.off every K-th step and after the last
    /// (DIR is created if missing).
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

/// The CSV header, exactly.
pub const CSV_HEADER: &str = "step,qw,qx,qy,qz,fv_errors,ee_errors,removed,added,facets,update_us";

/// Runs with at least this many steps show a progress bar (on a terminal).
const PROGRESS_MIN_STEPS: u64 = 2000;

/// A progress bar for long runs (on a terminal); hidden for short ones.
fn progress_bar(len: u64) -> ProgressBar {
    if len < PROGRESS_MIN_STEPS {
        return ProgressBar::hidden();
    }
    crate::progress::bar(len, "animate", "steps")
}

/// The frame file for a step: `DIR/step_NNNNNN.off`.
pub fn frame_path(dir: &Path, step: u64) -> PathBuf {
    dir.join(format!("step_{step:06}.off"))
}

/// Runs `dymsum animate`.
///
/// # Errors
/// P or Q cannot be loaded; the CSV file or the frames directory cannot be
/// created or written (an earlier CSV is kept); a DYMSUM update or a
/// frame's mesh fails; or, as an internal error, the final dynamic facets
/// differ from a fresh `walk` sum.
pub fn run(a: &AnimateArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    super::stdin_for_one_operand(&[(&a.p, "P"), (&a.q, "Q")])?;
    let (ps, qs) = (
        load_solid(&a.p, "P", convex_operands(a.strict), None)?,
        load_solid(&a.q, "Q", convex_operands(a.strict), None)?,
    );
    if !(ps.is_convex() && qs.is_convex()) {
        return run_union(a, ps.pieces, qs.pieces, out);
    }
    let p = load(&a.p, "P", a.strict)?;
    let q = load(&a.q, "Q", a.strict)?;
    let mut csv = open_csv(a.csv.as_deref())?;
    if let Some(dir) = &a.frames_dir {
        super::create_output_dir(dir)?;
    }

    let mut dynamic = DynamicSum::new(&p.polytope, Pose::IDENTITY, &q.polytope, Pose::IDENTITY)
        .context("initial sum")?;
    let totals = animate(a, &mut dynamic, csv.as_mut())?;
    if let Some(w) = csv {
        w.commit().context("the CSV file")?;
    }

    // The dynamic facet set must equal a fresh static sum at the final pose.
    let fresh = minkowski_sum_posed(
        &p.polytope,
        dynamic.pose_p(),
        &q.polytope,
        dynamic.pose_q(),
        Method::Walk,
    )
    .context("static check sum")?;
    if fresh.facets() != dynamic.facets() {
        bail!(
            "internal error: after {} steps the dynamic facets differ from a fresh walk sum \
             (please report: seed {}, {} steps per turn)",
            a.steps,
            a.seed,
            a.steps_per_rev
        );
    }
    write_summary(out, a, &totals, dynamic.facet_count())
}

/// Opens the CSV file, if asked for, and writes its header. It is written
/// under a temporary name and renamed at the end: a failed run leaves an
/// earlier CSV intact.
fn open_csv(path: Option<&Path>) -> anyhow::Result<Option<AtomicFile>> {
    let Some(path) = path else {
        return Ok(None);
    };
    super::create_parent_dir(path)?;
    let mut w = AtomicFile::create(path).context("the CSV file")?;
    writeln!(w, "{CSV_HEADER}")?;
    Ok(Some(w))
}

/// What a run adds up to.
struct Totals {
    /// Each update's time (µs).
    times: Vec<f64>,
    /// Frames written.
    frames: usize,
    /// fv-errors over all updates.
    fv_errors: usize,
    /// ee-errors over all updates.
    ee_errors: usize,
}

impl Totals {
    /// Nothing yet, with room for `steps` update times.
    fn for_steps(steps: u64) -> Totals {
        Totals {
            times: Vec::with_capacity(steps.min(1 << 24) as usize),
            frames: 0,
            fv_errors: 0,
            ee_errors: 0,
        }
    }
}

/// Turns P `a.steps` steps under the paper's motion, timing each DYMSUM
/// update, with a CSV row per step (if `csv`) and the frames due.
fn animate(
    a: &AnimateArgs,
    dynamic: &mut DynamicSum,
    mut csv: Option<&mut AtomicFile>,
) -> anyhow::Result<Totals> {
    let mut motion = PaperMotion::new(a.steps_per_rev, a.seed);
    let bar = progress_bar(a.steps);
    let mut totals = Totals::for_steps(a.steps);
    for step in 1..=a.steps {
        let rot = motion.next_step();
        let start = Instant::now();
        let report = dynamic.rotate_p_by(rot);
        let us = micros(start.elapsed());
        totals.times.push(us);
        totals.fv_errors += report.fv_errors;
        totals.ee_errors += report.ee_errors;
        if let Some(w) = csv.as_deref_mut() {
            write_csv_row(w, step, dynamic, &report, us)?;
        }
        if let Some(dir) = &a.frames_dir {
            if step % a.every == 0 || step == a.steps {
                let mesh = super::validated(dynamic.mesh_with_precision(), "the frame")?;
                write_mesh_with(&frame_path(dir, step), &mesh, Format::Off)
                    .with_context(|| format!("frame of step {step}"))?;
                totals.frames += 1;
            }
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(totals)
}

/// The CSV row of `step` (see [`CSV_HEADER`]).
fn write_csv_row(
    w: &mut dyn Write,
    step: u64,
    dynamic: &DynamicSum,
    report: &UpdateReport,
    us: f64,
) -> std::io::Result<()> {
    let [qw, qx, qy, qz] = dynamic.pose_p().rotation.wxyz();
    writeln!(
        w,
        "{step},{qw},{qx},{qy},{qz},{},{},{},{},{},{us:.3}",
        report.fv_errors,
        report.ee_errors,
        report.removed.len(),
        report.added.len(),
        dynamic.facet_count(),
    )
}

/// The closing lines: times, errors, facets and the files written.
fn write_summary(
    out: &mut dyn Write,
    a: &AnimateArgs,
    totals: &Totals,
    facets: usize,
) -> anyhow::Result<()> {
    writeln!(
        out,
        "{} ⊕ {}: {} steps at {} steps per turn (seed {}): DYMSUM update mean {}, median {}; \
         {} fv-errors, {} ee-errors in all; {facets} facets at the end (verified against walk)",
        short_name(&a.p),
        short_name(&a.q),
        a.steps,
        a.steps_per_rev,
        a.seed,
        human_us(mean(&totals.times)),
        human_us(median(&totals.times)),
        totals.fv_errors,
        totals.ee_errors,
    )?;
    if let Some(path) = &a.csv {
        writeln!(out, "wrote {} ({} rows)", path.display(), a.steps)?;
    }
    if let Some(dir) = &a.frames_dir {
        writeln!(out, "wrote {} frames to {}", totals.frames, dir.display())?;
    }
    Ok(())
}

/// `dymsum animate` with a non-convex operand: one dynamic sum per piece
/// pair, frames merged.
fn run_union(
    a: &AnimateArgs,
    p: Vec<dymsum::Polytope>,
    q: Vec<dymsum::Polytope>,
    out: &mut dyn Write,
) -> anyhow::Result<()> {
    let pu = ConvexUnion::new(p).context("P has no pieces")?;
    let qu = ConvexUnion::new(q).context("Q has no pieces")?;
    let mut csv = open_csv(a.csv.as_deref())?;
    if let Some(dir) = &a.frames_dir {
        super::create_output_dir(dir)?;
    }
    let mut dynamic =
        DynamicUnionSum::new(&pu, Pose::IDENTITY, &qu, Pose::IDENTITY).context("initial sums")?;
    let mut motion = PaperMotion::new(a.steps_per_rev, a.seed);
    let bar = progress_bar(a.steps);
    let mut totals = Totals::for_steps(a.steps);
    for step in 1..=a.steps {
        let rot = motion.next_step();
        let start = Instant::now();
        let reports = dynamic.rotate_a_by(rot);
        let us = micros(start.elapsed());
        totals.times.push(us);
        let fv: usize = reports.iter().map(|r| r.fv_errors).sum();
        let ee: usize = reports.iter().map(|r| r.ee_errors).sum();
        totals.fv_errors += fv;
        totals.ee_errors += ee;
        if let Some(w) = csv.as_mut() {
            let first = dynamic.pairs().next().map(|(_, s)| s.pose_p());
            let [qw, qx, qy, qz] = first.unwrap_or(Pose::IDENTITY).rotation.wxyz();
            let removed: usize = reports.iter().map(|r| r.removed.len()).sum();
            let added: usize = reports.iter().map(|r| r.added.len()).sum();
            let facets: usize = dynamic.pairs().map(|(_, s)| s.facet_count()).sum();
            writeln!(
                w,
                "{step},{qw},{qx},{qy},{qz},{fv},{ee},{removed},{added},{facets},{us:.3}"
            )?;
        }
        if let Some(dir) = &a.frames_dir {
            if step % a.every == 0 || step == a.steps {
                let union = dynamic
                    .union(true)
                    .with_context(|| format!("the merged frame of step {step}"))?;
                write_mesh_with(&frame_path(dir, step), union.mesh(), Format::Off)
                    .with_context(|| format!("frame of step {step}"))?;
                totals.frames += 1;
            }
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    if let Some(w) = csv {
        w.commit().context("the CSV file")?;
    }
    // Every pair's dynamic facets must equal a fresh static sum.
    for ((i, j), s) in dynamic.pairs() {
        let fresh = minkowski_sum_posed(s.p(), s.pose_p(), s.q(), s.pose_q(), Method::Walk)
            .context("static check sum")?;
        if fresh.facets() != s.facets() {
            bail!(
                "internal error: after {} steps the dynamic facets of pieces {i} and {j} differ \
                 from a fresh walk sum (please report: seed {}, {} steps per turn)",
                a.steps,
                a.seed,
                a.steps_per_rev
            );
        }
    }
    let facets: usize = dynamic.pairs().map(|(_, s)| s.facet_count()).sum();
    writeln!(
        out,
        "{} ⊕ {}: {} piece pairs, each updated by DYMSUM; frames merged by boolmesh",
        short_name(&a.p),
        short_name(&a.q),
        dynamic.pair_count()
    )?;
    write_summary(out, a, &totals, facets)
}
