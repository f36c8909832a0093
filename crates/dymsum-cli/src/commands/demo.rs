//! `dymsum demo [--seconds S]`: the main job on built-in models, no files.
//!
//! ellipse ⊕ gs4, P turning under the paper's motion at 500 steps per turn
//! for S seconds. Every step is a DYMSUM update (timed). The static `walk`
//! and `brute` sums are timed on the same poses, on a subsample of the steps
//! (a method is timed at a step whenever it has so far used at most a
//! quarter of the run, so about every k-th step with k about 4 × the ratio
//! of its cost to DYMSUM's); every sampled pose also checks that DYMSUM, `walk` and
//! `brute` agree facet for facet. At the end the dynamic facet set is
//! compared with a fresh `walk` sum and the merged sum is written to
//! `demo_sum.off` in the current directory.

use std::io::Write;
use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::{bail, Context};
use clap::Args;
use dymsum::sum::{minkowski_sum_posed, Facet, Method};
use dymsum::{DynamicSum, Polytope, Pose};
use dymsum_io::formats::{write_mesh_with, Format};

use super::load;
use crate::random_motion::PaperMotion;
use crate::stats::{mean, median, micros};
use crate::values::parse_seconds;

/// `dymsum demo`.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// How long to run the motion, in seconds.
    #[arg(long, value_name = "S", default_value_t = 3.0, value_parser = parse_seconds)]
    pub seconds: f64,
}

/// The moving operand.
pub const DEMO_P: &str = "ellipse";
/// The fixed operand.
pub const DEMO_Q: &str = "gs4";
/// Steps per full turn (the paper's setting).
pub const STEPS_PER_REV: f64 = 500.0;
/// The motion's seed.
pub const SEED: u64 = 2012;
/// The output file, in the current directory.
pub const OUTPUT: &str = "demo_sum.off";
/// At most this share of the run goes to timing each static method.
const STATIC_SHARE: f64 = 0.25;

/// Times one static sum at a pose (see [`super::bench::measure::time_static`]);
/// returns microseconds and the facets.
fn time_static(
    p: &Polytope,
    pose: Pose,
    q: &Polytope,
    method: Method,
) -> anyhow::Result<(f64, Vec<Facet>)> {
    let (us, facets) = super::bench::measure::time_static(p, pose, q, method);
    let facets = facets.with_context(|| format!("static {} sum", method.name()))?;
    Ok((us, facets))
}

/// Runs `dymsum demo`.
///
/// # Errors
/// Writing to `out` or to `demo_sum.off` fails; or, as internal errors, a
/// built-in model does not load, a sum or update fails, or the dynamic
/// facets differ from a static sum at a checked pose.
pub fn run(a: &DemoArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    let p = load(DEMO_P, "P", false)?;
    let q = load(DEMO_Q, "Q", false)?;
    let (pp, qq) = (&p.polytope, &q.polytope);
    writeln!(
        out,
        "dymsum demo: {DEMO_P} ({} faces) ⊕ {DEMO_Q} ({} faces); P turns {STEPS_PER_REV} steps per turn \
         about random axes (each held 1..=50 steps, seed {SEED}) for {} s",
        pp.face_count(),
        qq.face_count(),
        a.seconds
    )?;
    out.flush()?;

    let mut dynamic =
        DynamicSum::new(pp, Pose::IDENTITY, qq, Pose::IDENTITY).context("initial sum")?;
    // Warm-up (not recorded).
    time_static(pp, Pose::IDENTITY, qq, Method::Walk)?;
    let times = timed_run(&mut dynamic, Duration::from_secs_f64(a.seconds))?;
    let steps = times.dymsum.len();

    // Final check: the dynamic facets equal a fresh static walk sum.
    let fresh = minkowski_sum_posed(pp, dynamic.pose_p(), qq, dynamic.pose_q(), Method::Walk)
        .context("final static walk sum")?;
    if fresh.facets() != dynamic.facets() {
        bail!("internal error: the dynamic facets differ from a fresh walk sum after {steps} steps (please report)");
    }
    let mesh = super::validated(dynamic.mesh_with_precision(), "the sum")?;
    write_mesh_with(Path::new(OUTPUT), &mesh, Format::Off)
        .with_context(|| format!("writing {OUTPUT}"))?;

    writeln!(out)?;
    write_timing_table(out, &times)?;
    writeln!(out)?;
    let (fv, vf, ee) = fresh.counts();
    writeln!(
        out,
        "verified: dynamic facets == static walk facets (final pose: {fv} fv + {vf} vf + {ee} ee = {} facets; \
         and at every sampled pose, DYMSUM == walk and DYMSUM == brute)",
        fv + vf + ee,
    )?;
    writeln!(
        out,
        "wrote {OUTPUT} ({} vertices, {} faces after merging)",
        mesh.vertices.len(),
        mesh.faces.len()
    )?;
    Ok(())
}

/// The timings of a demo run (µs).
struct DemoTimes {
    /// Every DYMSUM update.
    dymsum: Vec<f64>,
    /// `walk` at its sampled poses.
    walk: Vec<f64>,
    /// `brute` at its sampled poses.
    brute: Vec<f64>,
}

/// Turns P under the paper's motion for about `budget` (at least one
/// step), timing every DYMSUM update, and times `walk` and `brute` at a
/// pose whenever each has used at most [`STATIC_SHARE`] of the run so far
/// (about every k-th step, k = its cost / (share × DYMSUM cost)), checking
/// their facets against DYMSUM's there.
fn timed_run(dynamic: &mut DynamicSum, budget: Duration) -> anyhow::Result<DemoTimes> {
    let mut motion = PaperMotion::new(STEPS_PER_REV, SEED);
    let run_start = Instant::now();
    let mut times = DemoTimes {
        dymsum: Vec::new(),
        walk: Vec::new(),
        brute: Vec::new(),
    };
    let mut spent = [Duration::ZERO; 2];
    let mut step = 0usize;
    while step == 0 || run_start.elapsed() < budget {
        step += 1;
        let rot = motion.next_step();
        let start = Instant::now();
        dynamic.rotate_p_by(rot);
        times.dymsum.push(micros(start.elapsed()));
        let elapsed = run_start.elapsed().as_secs_f64();
        for (i, (method, samples)) in [
            (Method::Walk, &mut times.walk),
            (Method::Brute, &mut times.brute),
        ]
        .into_iter()
        .enumerate()
        {
            if spent[i].as_secs_f64() <= STATIC_SHARE * elapsed {
                let t = Instant::now();
                sample(dynamic, step, method, samples)?;
                spent[i] += t.elapsed();
            }
        }
    }
    Ok(times)
}

/// The table of mean and median times and the median speedups, and what it
/// means. The speedup is a ratio of medians, the statistic the README and
/// BENCHMARKS.md quote (a few slow outliers, e.g. a step that rebuilds
/// much of the sum, move a mean far more than a median).
fn write_timing_table(out: &mut dyn Write, times: &DemoTimes) -> std::io::Result<()> {
    let steps = times.dymsum.len();
    let d_median = median(&times.dymsum);
    writeln!(
        out,
        "{:<8} {:>9} {:>12} {:>12} {:>16}",
        "method", "poses", "mean µs", "median µs", "DYMSUM speedup"
    )?;
    writeln!(
        out,
        "{:<8} {:>9} {:>12.1} {:>12.1} {:>16}",
        "DYMSUM",
        steps,
        mean(&times.dymsum),
        d_median,
        "-"
    )?;
    for (name, t) in [("walk", &times.walk), ("brute", &times.brute)] {
        writeln!(
            out,
            "{:<8} {:>9} {:>12.1} {:>12.1} {:>15.1}x",
            name,
            t.len(),
            mean(t),
            median(t),
            median(t) / d_median.max(1e-9)
        )?;
    }
    writeln!(out)?;
    writeln!(
        out,
        "DYMSUM timed on every step; to keep the run short, walk and brute timed on a subsample \
         of the same poses (walk on {} and brute on {} of the {steps} steps, each limited to about {:.0}% of the run). \
         Speedup = median static time / median DYMSUM time.",
        times.walk.len(),
        times.brute.len(),
        STATIC_SHARE * 100.0,
    )
}

/// Times a static method at the dynamic sum's current pose and checks that
/// its facets equal the dynamic ones.
fn sample(
    dynamic: &DynamicSum,
    step: usize,
    method: Method,
    times: &mut Vec<f64>,
) -> anyhow::Result<()> {
    let (p, q, pose) = (dynamic.p(), dynamic.q(), dynamic.pose_p());
    let (t, facets) = time_static(p, pose, q, method)?;
    times.push(t);
    let dyn_facets = dynamic.facets();
    if facets != dyn_facets {
        bail!(
            "internal error at step {step}: DYMSUM and {} disagree ({} vs {} facets; please report)",
            method.name(),
            dyn_facets.len(),
            facets.len(),
        );
    }
    Ok(())
}
