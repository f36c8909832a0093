//! Shared set-up for the criterion benches (see `benches/`) and the
//! `bench_table` binary that turns criterion's JSON output into the markdown
//! tables of `docs/BENCHMARKS.md`.
//!
//! * [`load`]: a built-in model by name, as a [`Polytope`].
//! * [`paper_motion`]: the paper's motion (§5) for P, seeded, so every run
//!   sees the same poses.
//! * [`random_rotation`]: one seeded, uniformly random orientation.
//! * [`contact`]: the contact-tracking workload and its parry3d-f64 twin.
//! * [`scenes`]: triangle-mesh scenes (OMPL.app's problems or a built-in
//!   room) for dymsum's scene checker and parry's BVH mesh–mesh test.
//! * [`collect_results`] / [`markdown_report`]: read
//!   `target/criterion/**/new/{benchmark,estimates}.json` and print tables.
#![warn(clippy::missing_errors_doc, clippy::missing_panics_doc)]

pub mod contact;
pub mod motion;
pub mod parts;
pub mod scenes;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use dymsum::polytope::MeshPolicy;
use dymsum::{DynamicSum, Polytope, Pose, Rotation};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The operand pairs of issue 2 §7 and issue 3 §6, as `(P, Q)` model names.
pub const PAIRS: [(&str, &str); 4] = [
    ("cube", "cube"),
    ("gs4", "gs4"),
    ("ellipse", "ellipse"),
    ("ti", "vrod"),
];

/// Seed of the fixed orientation of P in the static benches.
pub const STATIC_SEED: u64 = 2;
/// Seed of the paper's motion in the dynamic bench.
pub const MOTION_SEED: u64 = 5;
/// Steps per full turn in the dynamic bench (the paper's default, §5.2).
pub const STEPS_PER_REV: f64 = 500.0;
/// Length of the precomputed pose sequence of the dynamic bench.
pub const MOTION_STEPS: usize = 1000;

/// Criterion group names used by the benches (and by [`markdown_report`]).
pub const STATIC_GROUP: &str = "static_methods";
/// See [`STATIC_GROUP`].
pub const DYNAMIC_GROUP: &str = "dynamic_update";

/// `"p+q"`, the label of a pair in bench ids and tables.
pub fn pair_label(p: &str, q: &str) -> String {
    format!("{p}+{q}")
}

/// A built-in model (`cube`, `gs4`, `ellipse`, `ti`, `vrod`, ...) or a mesh
/// file, as a polytope, through [`dymsum_io::load_polytope`] under the
/// default mesh policy (a mesh convex within tolerance is replaced by the
/// exact hull of its vertices).
///
/// # Panics
/// If the operand cannot be loaded: a bench cannot go on.
pub fn load(spec: &str) -> Polytope {
    dymsum_io::load_polytope(spec, MeshPolicy::default())
        .unwrap_or_else(|e| panic!("cannot load {spec:?}: {e}"))
        .polytope
}

/// Criterion's sample size for a bench whose single call took `one_call`:
/// 20 normally, criterion's minimum of 10 for calls slower than 100 ms (so
/// a multi-second `brute` stays within the run's time budget).
pub fn sample_size_for(one_call: std::time::Duration) -> usize {
    if one_call > std::time::Duration::from_millis(100) {
        10
    } else {
        20
    }
}

/// A uniformly random orientation (Shoemake's method), from ChaCha8 seeded
/// with `seed`.
///
/// # Panics
/// Never: Shoemake's quaternion has unit length up to rounding, so it is
/// neither zero nor non-finite (the only inputs [`Rotation::from_wxyz`]
/// refuses).
pub fn random_rotation(seed: u64) -> Rotation {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let u1: f64 = rng.random();
    let u2: f64 = rng.random::<f64>() * std::f64::consts::TAU;
    let u3: f64 = rng.random::<f64>() * std::f64::consts::TAU;
    let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
    Rotation::from_wxyz(b * u3.cos(), a * u2.sin(), a * u2.cos(), b * u3.sin())
        .expect("a unit quaternion")
}

/// The paper's motion (§5): P turns about a random unit axis, held for a
/// random number of 1 to 50 steps, then a new axis is drawn; every step
/// turns by `2π / steps_per_rev`. Returns P's absolute orientation after
/// each of the `steps` steps, starting from the identity (so entry 0 is one
/// step away from [`Rotation::IDENTITY`], and entry `i` one step from entry
/// `i - 1`). Deterministic: ChaCha8 seeded with `seed`. The steps are
/// those of the CLI's [`dymsum_cli::random_motion::PaperMotion`] (one definition
/// of the motion for the CLI's experiments and the benchmarks).
///
/// # Panics
/// If `steps_per_rev` is not a finite positive number. (The random axes
/// are unit vectors, so building each step's rotation cannot fail.)
pub fn paper_motion(steps_per_rev: f64, steps: usize, seed: u64) -> Vec<Rotation> {
    assert!(
        steps_per_rev.is_finite() && steps_per_rev > 0.0,
        "steps_per_rev must be positive"
    );
    let mut motion = dymsum_cli::random_motion::PaperMotion::new(steps_per_rev, seed);
    let mut current = Rotation::IDENTITY;
    (0..steps)
        .map(|_| {
            current = current.then(&motion.next_step());
            current
        })
        .collect()
}

/// Times `iters` DYMSUM updates of `dy` along `timed` (P's poses, Q kept),
/// cyclically from `*next`: when the sequence is exhausted, P jumps back to
/// `start` (a large step, recomputed) *outside* the timed region, so every
/// timed update is one genuine step of the motion. For criterion's
/// `iter_custom`.
pub fn time_cyclic_updates(
    dy: &mut DynamicSum,
    start: Pose,
    timed: &[Pose],
    next: &mut usize,
    iters: u64,
) -> std::time::Duration {
    let mut total = std::time::Duration::ZERO;
    let mut left = iters;
    while left > 0 {
        if *next == timed.len() {
            dy.set_pose_p(start);
            *next = 0;
        }
        let run = left.min((timed.len() - *next) as u64) as usize;
        let clock = std::time::Instant::now();
        for pose in &timed[*next..*next + run] {
            std::hint::black_box(dy.set_pose_p(*pose));
        }
        total += clock.elapsed();
        *next += run;
        left -= run as u64;
    }
    total
}

// ---------------------------------------------------------------------------
// Reading criterion's output.

/// One benchmark's estimates, as criterion wrote them (nanoseconds).
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// `median.point_estimate` (ns per iteration).
    pub median_ns: f64,
    /// `mean.point_estimate` (ns per iteration).
    pub mean_ns: f64,
}

/// Results keyed by `(group_id, function_id, value_str)`.
pub type Results = BTreeMap<(String, String, String), Estimate>;

/// The criterion output directory: `$CARGO_TARGET_DIR/criterion` if set,
/// else `<workspace>/target/criterion`.
pub fn default_criterion_dir() -> PathBuf {
    if let Some(t) = std::env::var_os("CARGO_TARGET_DIR") {
        return PathBuf::from(t).join("criterion");
    }
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../target/criterion")
        .components()
        .collect()
}

fn json_f64(v: &serde_json::Value, path: &[&str]) -> Option<f64> {
    let mut cur = v;
    for k in path {
        cur = cur.get(k)?;
    }
    cur.as_f64()
}

fn json_str(v: &serde_json::Value, key: &str) -> Option<String> {
    v.get(key)?.as_str().map(str::to_owned)
}

/// Reads every `new/benchmark.json` + `new/estimates.json` pair below `dir`.
/// A `new/` directory whose JSON files are missing or malformed is skipped.
///
/// # Errors
/// The [`std::io::Error`] of the first directory below `dir` (or `dir`
/// itself) that cannot be listed: missing, not a directory, permissions.
pub fn collect_results(dir: &Path) -> std::io::Result<Results> {
    let mut out = Results::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d)? {
            let path = entry?.path();
            if !path.is_dir() {
                continue;
            }
            if path.file_name().is_some_and(|n| n == "new") {
                if let Some((key, est)) = read_one(&path) {
                    out.insert(key, est);
                }
            } else if path.file_name().is_some_and(|n| n != "report") {
                stack.push(path);
            }
        }
    }
    Ok(out)
}

fn read_one(new_dir: &Path) -> Option<((String, String, String), Estimate)> {
    let bench: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(new_dir.join("benchmark.json")).ok()?)
            .ok()?;
    let est: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(new_dir.join("estimates.json")).ok()?)
            .ok()?;
    let key = (
        json_str(&bench, "group_id")?,
        json_str(&bench, "function_id").unwrap_or_default(),
        json_str(&bench, "value_str").unwrap_or_default(),
    );
    let e = Estimate {
        median_ns: json_f64(&est, &["median", "point_estimate"])?,
        mean_ns: json_f64(&est, &["mean", "point_estimate"])?,
    };
    Some((key, e))
}

/// A duration in nanoseconds, printed in µs with 3 significant-ish digits.
pub fn fmt_us(ns: f64) -> String {
    let us = ns / 1000.0;
    if us >= 1000.0 {
        format!("{us:.0}")
    } else if us >= 100.0 {
        format!("{us:.1}")
    } else if us >= 10.0 {
        format!("{us:.2}")
    } else {
        format!("{us:.3}")
    }
}

fn fmt_ratio(num: Option<f64>, den: Option<f64>) -> String {
    match (num, den) {
        (Some(n), Some(d)) if d > 0.0 => format!("{:.1}×", n / d),
        _ => "–".into(),
    }
}

fn cell(x: Option<f64>) -> String {
    x.map(fmt_us).unwrap_or_else(|| "–".into())
}

fn verdict(label: &str, num: Option<f64>, den: Option<f64>, target: f64) -> String {
    match (num, den) {
        (Some(n), Some(d)) if d > 0.0 => {
            let r = n / d;
            let ok = if r >= target { "met" } else { "NOT met" };
            format!("- {label}: {r:.1}× (target ≥ {target}×): **{ok}**\n")
        }
        _ => format!("- {label}: not measured\n"),
    }
}

/// The markdown tables of `docs/BENCHMARKS.md` (medians in µs, ratios of
/// medians) and the verdicts on the ellipse+ellipse targets.
pub fn markdown_report(results: &Results) -> String {
    let get = |group: &str, func: &str, pair: &str| {
        results
            .get(&(group.to_owned(), func.to_owned(), pair.to_owned()))
            .map(|e| e.median_ns)
    };
    let mut s = String::new();

    s.push_str("### `static_methods` (issue 2 §7): one static sum at a fixed random pose\n\n");
    s.push_str(
        "Median time per call in µs. `walk`, `brute`, `hull` = one `minkowski_sum_posed` \
         call (facet set only); `walk+merge` = the same `walk` call plus `.try_to_mesh()`.\n\n",
    );
    s.push_str(
        "| P+Q | walk | walk+merge | brute | hull | walk vs brute (brute÷walk) \
         | walk vs hull (hull÷walk) |\n",
    );
    s.push_str("| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (p, q) in PAIRS {
        let pair = pair_label(p, q);
        let walk = get(STATIC_GROUP, "walk", &pair);
        let merge = get(STATIC_GROUP, "walk+merge", &pair);
        let brute = get(STATIC_GROUP, "brute", &pair);
        let hull = get(STATIC_GROUP, "hull", &pair);
        s.push_str(&format!(
            "| {pair} | {} | {} | {} | {} | {} | {} |\n",
            cell(walk),
            cell(merge),
            cell(brute),
            cell(hull),
            fmt_ratio(brute, walk),
            fmt_ratio(hull, walk)
        ));
    }
    s.push('\n');
    let pair = pair_label("ellipse", "ellipse");
    let walk = get(STATIC_GROUP, "walk", &pair);
    s.push_str(&verdict(
        "ellipse+ellipse, walk vs brute",
        get(STATIC_GROUP, "brute", &pair),
        walk,
        10.0,
    ));
    s.push_str(&verdict(
        "ellipse+ellipse, walk vs hull",
        get(STATIC_GROUP, "hull", &pair),
        walk,
        30.0,
    ));
    s.push('\n');

    s.push_str(&format!(
        "### `dynamic_update` (issue 3 §6): per-step time under the paper's motion, \
         {STEPS_PER_REV} steps per turn\n\n"
    ));
    s.push_str(
        "Median time per step in µs, over the same cyclic sequence of \
         poses for all three columns. `dymsum` = one `DynamicSum::set_pose_p`; \
         `walk`/`brute` = one static `minkowski_sum_posed` at that pose.\n\n",
    );
    s.push_str(
        "| P+Q | dymsum | walk | brute | dymsum vs walk (walk÷dymsum) \
         | dymsum vs brute (brute÷dymsum) |\n",
    );
    s.push_str("| --- | ---: | ---: | ---: | ---: | ---: |\n");
    for (p, q) in PAIRS {
        let pair = pair_label(p, q);
        let dy = get(DYNAMIC_GROUP, "dymsum", &pair);
        let walk = get(DYNAMIC_GROUP, "walk", &pair);
        let brute = get(DYNAMIC_GROUP, "brute", &pair);
        s.push_str(&format!(
            "| {pair} | {} | {} | {} | {} | {} |\n",
            cell(dy),
            cell(walk),
            cell(brute),
            fmt_ratio(walk, dy),
            fmt_ratio(brute, dy)
        ));
    }
    s.push('\n');
    let dy = get(DYNAMIC_GROUP, "dymsum", &pair);
    s.push_str(&verdict(
        "ellipse+ellipse, dymsum vs walk",
        get(DYNAMIC_GROUP, "walk", &pair),
        dy,
        5.0,
    ));
    s.push_str(&verdict(
        "ellipse+ellipse, dymsum vs brute",
        get(DYNAMIC_GROUP, "brute", &pair),
        dy,
        200.0,
    ));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn motion_is_deterministic_and_steps_are_small() {
        let a = paper_motion(500.0, 300, 9);
        let b = paper_motion(500.0, 300, 9);
        assert_eq!(a, b);
        let step = std::f64::consts::TAU / 500.0;
        assert!((Rotation::IDENTITY.angle_to(&a[0]) - step).abs() < 1e-9);
        for w in a.windows(2) {
            assert!((w[0].angle_to(&w[1]) - step).abs() < 1e-9);
        }
        assert_ne!(paper_motion(500.0, 300, 10), a);
    }

    #[test]
    fn random_rotation_is_seeded() {
        assert_eq!(random_rotation(1), random_rotation(1));
        assert_ne!(random_rotation(1), random_rotation(2));
    }
}
