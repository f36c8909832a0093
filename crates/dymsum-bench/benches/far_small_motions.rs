//! Small bodies far from the origin (issue 33 §4): the family of
//! `crates/dymsum/tests/far_small_motions.rs` (the same generator and
//! seed), `1e-3`-sized convex bodies at offsets `1e3`–`1e6` moving into,
//! along and past obstacles, through `MotionChecker` (the convex pieces)
//! and `SceneChecker` (the same shapes as triangles), tolerance `1e-6`,
//! the default budget. Prints, per offset and kind and in all, the
//! fraction of motions left undecided (`Undecided` or `BudgetExhausted`)
//! and the median time of one check. The test checks every decided
//! answer against exact state checks; this one only counts and times.
//!
//! `cargo bench -p dymsum-bench --bench far_small_motions`
//! (`FAR_SMALL_PER_KIND=N` motions of each kind at each offset, default 100)

use std::time::Instant;

use dymsum::query::{ConvexUnion, MeshBody, MotionChecker, SceneChecker};
use dymsum_testkit::far_small::{family, TOL};

/// Undecided count and check times (seconds) of one checker on a group.
#[derive(Default)]
struct Tally {
    n: usize,
    undecided: usize,
    times: Vec<f64>,
}

impl Tally {
    fn add(&mut self, decided: bool, seconds: f64) {
        self.n += 1;
        self.undecided += usize::from(!decided);
        self.times.push(seconds);
    }

    fn show(&mut self) -> String {
        self.times.sort_by(f64::total_cmp);
        let median = self.times.get(self.times.len() / 2).copied().unwrap_or(0.0);
        format!(
            "{:>4}/{:<4} undecided ({:>5.2}%), median {:>8.1} µs",
            self.undecided,
            self.n,
            100.0 * self.undecided as f64 / self.n.max(1) as f64,
            median * 1e6
        )
    }
}

fn main() {
    let per_kind = std::env::var("FAR_SMALL_PER_KIND")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100);
    let cases = family(33, per_kind);
    let mut groups: Vec<(String, Tally, Tally)> = Vec::new();
    let mut all = (Tally::default(), Tally::default());
    for c in &cases {
        let body = ConvexUnion::from(c.body.clone());
        let obstacle = ConvexUnion::from(c.obstacle.clone());
        let convex = MotionChecker::new(&body, std::slice::from_ref(&obstacle)).unwrap();
        let scene = SceneChecker::new(
            &MeshBody::from_union(&body),
            &[MeshBody::from_union(&obstacle)],
        )
        .unwrap();
        let clock = Instant::now();
        let a = convex.check(c.from, c.to, TOL);
        let ta = clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        let b = scene.check(c.from, c.to, TOL);
        let tb = clock.elapsed().as_secs_f64();
        let key = format!("{:e} {}", c.offset, c.kind);
        if groups.last().is_none_or(|g| g.0 != key) {
            groups.push((key, Tally::default(), Tally::default()));
        }
        let g = groups.last_mut().unwrap();
        g.1.add(a.is_ok(), ta);
        g.2.add(b.is_ok(), tb);
        all.0.add(a.is_ok(), ta);
        all.1.add(b.is_ok(), tb);
    }
    println!("far_small_motions: {per_kind} motions per offset and kind, tolerance {TOL:e}");
    for (key, a, b) in &mut groups {
        println!("{key:<12} convex {} | scene {}", a.show(), b.show());
    }
    println!(
        "{:<12} convex {} | scene {}",
        "all",
        all.0.show(),
        all.1.show()
    );
}
