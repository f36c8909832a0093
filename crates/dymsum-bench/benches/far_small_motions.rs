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
use dymsum::{DVec3, Polytope, Pose, Rotation};
use dymsum_testkit::{cuboid, random_polytope, random_rotation, rng, Kind};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

const TOL: f64 = 1e-6;
/// The body's and the obstacles' size.
const SIZE: f64 = 1e-3;
const OFFSETS: [f64; 4] = [1e3, 1e4, 1e5, 1e6];

/// One case of the family: a body, one obstacle, and a motion.
struct Case {
    kind: &'static str,
    offset: f64,
    body: Polytope,
    obstacle: Polytope,
    from: Pose,
    to: Pose,
}

fn scaled(p: &Polytope, s: f64, shift: DVec3) -> Polytope {
    let pts: Vec<DVec3> = p.vertices().iter().map(|&v| v * s + shift).collect();
    Polytope::from_dvec3s(&pts).unwrap()
}

fn unit(r: &mut ChaCha8Rng) -> DVec3 {
    loop {
        let v = DVec3::new(
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
        );
        let l = v.length();
        if l > 0.1 && l <= 1.0 {
            return v / l;
        }
    }
}

/// A small random turn (at most `max` radians about a random axis).
fn small_turn(r: &mut ChaCha8Rng, max: f64) -> Rotation {
    Rotation::from_axis_angle(unit(r), r.random_range(-max..max)).unwrap()
}

/// The family: `per_kind` motions of each kind at each offset.
fn family(seed: u64, per_kind: usize) -> Vec<Case> {
    let mut r = rng(seed);
    let mut out = Vec::new();
    for &offset in &OFFSETS {
        for kind in ["into", "along", "past"] {
            for _ in 0..per_kind {
                let centre = unit(&mut r) * offset;
                let body = scaled(
                    &random_polytope(Kind::Ball, 12, &mut r),
                    SIZE / 2.0,
                    DVec3::ZERO,
                );
                let case = match kind {
                    "into" => {
                        // From 2–4 sizes away to overlapping the obstacle.
                        let obstacle =
                            scaled(&random_polytope(Kind::Ball, 12, &mut r), SIZE / 2.0, centre);
                        let start = centre + unit(&mut r) * (SIZE * r.random_range(2.0..4.0));
                        let end = centre + unit(&mut r) * (SIZE * r.random_range(0.0..0.3));
                        let q0 = random_rotation(&mut r);
                        let q1 = q0.then(&small_turn(&mut r, 1.0));
                        Case {
                            kind,
                            offset,
                            body,
                            obstacle,
                            from: Pose::new(q0, start),
                            to: Pose::new(q1, end),
                        }
                    }
                    "along" => {
                        // A slide of six sizes over a box's top face, with
                        // a clearance of 1e-8 to 1e-5, turning about the
                        // vertical (which keeps the clearance: a tilt would
                        // dip the body into the face tangentially, a
                        // contact approached within rounding, docs/LIMITS.md).
                        let h = SIZE / 2.0;
                        let lo = [centre.x - h * 4.0, centre.y - h, centre.z - h];
                        let hi = [centre.x + h * 4.0, centre.y + h, centre.z + h];
                        let obstacle = cuboid(lo, hi);
                        let q0 = random_rotation(&mut r);
                        let lowest = body
                            .vertices()
                            .iter()
                            .map(|&v| q0.apply(v).z)
                            .fold(f64::INFINITY, f64::min);
                        let clearance = 10f64.powf(r.random_range(-8.0..-5.0));
                        let z = hi[2] + clearance - lowest;
                        let y = centre.y + r.random_range(-h..h);
                        let from = DVec3::new(centre.x - h * 6.0, y, z);
                        let to = DVec3::new(centre.x + h * 6.0, y + r.random_range(-h..h), z);
                        let yaw = r.random_range(-1.0..1.0);
                        let q1 = q0.then(&Rotation::from_axis_angle(DVec3::Z, yaw).unwrap());
                        Case {
                            kind,
                            offset,
                            body,
                            obstacle,
                            from: Pose::new(q0, from),
                            to: Pose::new(q1, to),
                        }
                    }
                    _ => {
                        // Past the obstacle on a line missing its centre by
                        // 0.5–1.5 times the sum of the reaches (some hit).
                        let obstacle =
                            scaled(&random_polytope(Kind::Ball, 12, &mut r), SIZE / 2.0, centre);
                        let dir = unit(&mut r);
                        let w = unit(&mut r);
                        let side = w - dir * dir.dot(w);
                        let side = if side.length() > 0.1 {
                            side.normalize()
                        } else {
                            dir.any_orthonormal_vector()
                        };
                        let miss = SIZE * r.random_range(0.5..1.5);
                        let q0 = random_rotation(&mut r);
                        let q1 = q0.then(&small_turn(&mut r, 1.5));
                        Case {
                            kind,
                            offset,
                            body,
                            obstacle,
                            from: Pose::new(q0, centre + side * miss - dir * (SIZE * 4.0)),
                            to: Pose::new(q1, centre + side * miss + dir * (SIZE * 4.0)),
                        }
                    }
                };
                out.push(case);
            }
        }
    }
    out
}

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
