//! The kinetic schedule of FindErrors (issue 10 §1): which face normals a
//! step must visit, without looking at the others.
//!
//! Every face normal carries a lazy margin (see [`super::margins`]): at the
//! accumulated rotation `margin_at` it was at least `margin` (less its
//! direction error `δ`) from the boundary of its cell. Since a normal moves
//! by at most the accumulated step angle, it cannot have left its cell, nor
//! crossed an arc, while the accumulated rotation (plus the current step's
//! drift off the great arc, `θ²/4 + slack`) stays below its *deadline*
//! `margin_at + margin − δ`. FindErrors used to test that inequality for
//! every normal (`O(m + n)` per step); the schedule keeps the deadlines in
//! a calendar queue instead ([`Deadlines`]: buckets about one step wide),
//! so a step pops exactly the normals
//! whose deadline falls inside it (`after + drift ≥ deadline`, the same test
//! as before, evaluated on fewer normals) and re-keys them after their
//! visit. Normals certified through persistent exact ties about a
//! coordinate axis ([`super::ties`]) are keyed by the later of their two
//! deadlines while the run of steps about that axis lasts; when the run
//! ends, those keys fall back to the plain margin deadline before anything
//! is popped.
//!
//! # Correctness
//! A normal that is not popped has `deadline > after + drift`, which is the
//! old skip test: its margin certifies it stayed in its cell and crossed no
//! arc during the step. Every normal the old scan would visit is popped, and
//! each popped normal goes through the unchanged per-normal decision, so the
//! facets found are the same (the oracle suites check every step against a
//! fresh `walk`). Deadlines are compared in floats like the old test; the
//! accumulated rotation is rebased to 0 now and then ([`REBASE_AFTER`]) so
//! that each comparison's rounding stays far below the slack that covers
//! it, and it is summed rounded up (module docs of `dynamic`, "The
//! accumulated rotation counts up"): roundings of a plain sum add up step
//! after step, and the slack covers only one.
//!
//! # Complexity
//! `O(k + 1)` per step for `k` popped normals (plus the visits themselves),
//! and `O(n)` for the normals beyond the calendar's ring once per half turn
//! of the ring (256 steps); a rebuild after a from-scratch recomputation,
//! a change of the step size by more than 16× or a rebase is `O(n)`. No
//! allocation after the rebuild: the lists are intrusive (per-normal
//! arrays) and the due list is a reused buffer of capacity `n`.

/// When the accumulated rotation exceeds this (radians), it is rebased to 0
/// (every deadline shifted by the same amount), so a long motion keeps the
/// deadlines' rounding at about `1e-13`.
pub(super) const REBASE_AFTER: f64 = 1024.0;

/// Number of buckets of the calendar (a power of two).
const BUCKETS: usize = 512;
/// The list of the deadlines beyond the ring (after the ring's buckets).
const FAR: u32 = BUCKETS as u32;
/// No item / in no list.
const NIL: u32 = u32::MAX;

/// Deadlines of `n` items in a calendar queue: buckets of width `width`
/// (about one step's angle) in a ring of [`BUCKETS`], the deadlines beyond
/// the ring in a `far` list re-filed when the ring has turned half way.
/// Every list is intrusive and doubly linked through per-item arrays, so an
/// item is in exactly one list (or none while popped), re-keying moves it
/// in O(1), and nothing is allocated after [`Deadlines::rebuild`].
#[derive(Clone, Debug, Default)]
pub(super) struct Deadlines {
    /// Key of each item (`+∞` while popped and not re-keyed).
    key: Vec<f64>,
    /// Neighbours of each item in its list.
    next: Vec<u32>,
    prev: Vec<u32>,
    /// The list each item is in: a ring slot, [`FAR`], or [`NIL`].
    list: Vec<u32>,
    /// First item of each list: the ring's slots, then the far list.
    head: Vec<u32>,
    /// Bucket width (radians of accumulated rotation).
    width: f64,
    /// First bucket not yet fully popped; bucket `b` (an absolute index
    /// `floor(key / width)`) lives in slot `b % BUCKETS` for `b` below
    /// `ring_end`, in the far list beyond.
    cur: i64,
    ring_end: i64,
}

impl Deadlines {
    /// All `n` items with the keys `key(i)`, with buckets about `width`
    /// wide (the step angle expected), in O(n).
    pub(super) fn rebuild(&mut self, n: usize, width: f64, key: impl Fn(usize) -> f64) {
        self.key.clear();
        self.key.extend((0..n).map(key));
        self.width = width.clamp(1e-12, 1.0);
        self.refile();
    }

    /// Files every item anew under its key (O(n), no allocation once the
    /// arrays have their size).
    fn refile(&mut self) {
        let n = self.key.len();
        for v in [&mut self.next, &mut self.prev, &mut self.list] {
            v.clear();
            v.resize(n, NIL);
        }
        self.head.clear();
        self.head.resize(BUCKETS + 1, NIL);
        let least = self.key.iter().copied().fold(f64::INFINITY, f64::min);
        self.cur = if least.is_finite() {
            self.index(least)
        } else {
            0
        };
        self.ring_end = self.cur.saturating_add(BUCKETS as i64);
        for i in 0..n as u32 {
            self.place(i);
        }
    }

    /// The absolute bucket index of a key (saturating; NaN goes first).
    fn index(&self, key: f64) -> i64 {
        let q = key / self.width;
        if q.is_nan() {
            return i64::MIN;
        }
        // `floor` without the libm call: truncate (saturating), then step
        // down for negative non-integers.
        let b = q as i64;
        if (b as f64) > q {
            // Saturating: below the range (`-∞` included) `b` is already
            // `i64::MIN`, and `i64::MIN - 1` would wrap to `i64::MAX` (an
            // overdue item filed beyond the ring, never popped).
            b.saturating_sub(1)
        } else {
            b
        }
    }

    fn link(&mut self, i: u32, list: u32) {
        let h = self.head[list as usize];
        self.next[i as usize] = h;
        self.prev[i as usize] = NIL;
        if h != NIL {
            self.prev[h as usize] = i;
        }
        self.head[list as usize] = i;
        self.list[i as usize] = list;
    }

    fn unlink(&mut self, i: u32) {
        let list = self.list[i as usize];
        if list == NIL {
            return;
        }
        let (p, n) = (self.prev[i as usize], self.next[i as usize]);
        if p != NIL {
            self.next[p as usize] = n;
        } else {
            self.head[list as usize] = n;
        }
        if n != NIL {
            self.prev[n as usize] = p;
        }
        self.list[i as usize] = NIL;
    }

    /// Files item `i` under its current key: the slot of bucket
    /// `max(index(key), cur)`, or the far list beyond the ring.
    fn place(&mut self, i: u32) {
        let b = self.index(self.key[i as usize]).max(self.cur);
        let list = if b < self.ring_end {
            (b as u64 % BUCKETS as u64) as u32
        } else {
            FAR
        };
        self.link(i, list);
    }

    /// Sets the key of item `i`.
    pub(super) fn set(&mut self, i: u32, key: f64) {
        self.unlink(i);
        self.key[i as usize] = key;
        self.place(i);
    }

    /// Appends to `out` every item whose key is at most `limit` (in no
    /// particular order) and gives each the key `+∞` until the caller
    /// re-keys it. `step` is the step's angle: when it differs from the
    /// bucket width by more than 16× the calendar is re-filed to it first.
    ///
    /// Every item whose key is at most `limit` is found: an item sits in the
    /// slot of `max(index(key), cur)` at the time it was filed (or in the
    /// far list, beyond the ring, until the ring turns past it), so it is in
    /// one of the slots from `cur` to `index(limit)`, which are all visited
    /// (each slot at most once: a slot pops every due item in it, whatever
    /// turn of the ring its bucket belongs to).
    pub(super) fn pop_due(&mut self, limit: f64, step: f64, out: &mut Vec<u32>) {
        if step > 16.0 * self.width || step < self.width / 16.0 {
            self.width = step.clamp(1e-12, 1.0);
            self.refile();
        }
        let last = self.index(limit);
        if last >= self.ring_end - BUCKETS as i64 / 2 {
            self.turn_ring(last);
        }
        let slots = last.saturating_sub(self.cur).clamp(0, BUCKETS as i64 - 1) + 1;
        for b in self.cur..self.cur.saturating_add(slots) {
            let mut i = self.head[(b as u64 % BUCKETS as u64) as usize];
            while i != NIL {
                let next = self.next[i as usize];
                // A NaN key is due (never skipped).
                let key = self.key[i as usize];
                if key <= limit || key.is_nan() {
                    self.unlink(i);
                    self.key[i as usize] = f64::INFINITY;
                    out.push(i);
                }
                i = next;
            }
        }
        self.cur = self.cur.max(last);
    }

    /// Moves the ring's end to `last + BUCKETS`: the far items now inside
    /// it go to their slots (due ones to slots that this pop visits).
    /// Slots of the new window alias older buckets only where those are
    /// visited by this pop, which keeps every item that is not due.
    fn turn_ring(&mut self, last: i64) {
        self.ring_end = last.saturating_add(BUCKETS as i64);
        let mut i = self.head[FAR as usize];
        while i != NIL {
            let next = self.next[i as usize];
            let b = self.index(self.key[i as usize]).max(self.cur);
            if b < self.ring_end {
                self.unlink(i);
                self.link(i, (b as u64 % BUCKETS as u64) as u32);
            }
            i = next;
        }
    }

    /// Subtracts `s` from every key and re-files them (no allocation).
    pub(super) fn shift(&mut self, s: f64) {
        for k in &mut self.key {
            *k -= s;
        }
        self.refile();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// The tests' random numbers (`crate::kernel::test_rng`; reproducible).
    pub(super) struct R(crate::kernel::test_rng::Xorshift);

    impl R {
        /// The stream from `seed` (nonzero).
        pub(super) fn new(seed: u64) -> R {
            R(crate::kernel::test_rng::Xorshift::new(seed))
        }

        pub(super) fn f(&mut self) -> f64 {
            self.0.unit()
        }
        pub(super) fn i(&mut self, n: usize) -> usize {
            (self.f() * n as f64) as usize % n
        }
        pub(super) fn axis(&mut self) -> DVec3 {
            DVec3::new(self.f() - 0.5, self.f() - 0.5, self.f() - 0.5).normalize()
        }
    }

    /// Pops the items due at `limit` into `due` and checks them against a
    /// plain scan of `keys`.
    fn pop_checked(
        d: &mut Deadlines,
        keys: &[f64],
        limit: f64,
        step: f64,
        due: &mut Vec<u32>,
        ctx: &str,
    ) {
        due.clear();
        d.pop_due(limit, step, due);
        let mut got = due.clone();
        got.sort_unstable();
        let want: Vec<u32> = (0..keys.len() as u32)
            .filter(|&i| keys[i as usize] <= limit)
            .collect();
        assert_eq!(got, want, "{ctx}");
    }

    /// Against a plain scan of the keys: random keys, random re-keying up
    /// and down, limits that advance by random steps of several sizes (so
    /// the ring turns and the calendar is rebuilt), and a rebase.
    #[test]
    fn pops_exactly_the_due_items() {
        let mut r = R::new(0x9e37_79b9_7f4a_7c15);
        let mut next = || r.f();
        let n = 300;
        let mut keys: Vec<f64> = (0..n).map(|_| next() * 10.0).collect();
        let mut d = Deadlines::default();
        d.rebuild(n, 0.01, |i| keys[i]);
        let mut due = Vec::new();
        let mut limit = 0.0;
        for round in 0..3000 {
            let step = [0.01, 0.01, 0.002, 0.3][round / 700 % 4] * (0.5 + next());
            // The limit mostly advances, sometimes falls back a little (the
            // drift term of a step is not monotone).
            limit += if next() < 0.1 { -step / 2.0 } else { step };
            pop_checked(
                &mut d,
                &keys,
                limit,
                step,
                &mut due,
                &format!("round {round}"),
            );
            for &i in &due {
                keys[i as usize] = limit + next() * next() * 20.0 - 0.001;
                d.set(i, keys[i as usize]);
            }
            for _ in 0..3 {
                let i = (next() * n as f64) as usize;
                keys[i] = limit + next() * 3.0;
                d.set(i as u32, keys[i]);
            }
            if round % 1000 == 999 {
                d.shift(limit);
                keys.iter_mut().for_each(|k| *k -= limit);
                limit = 0.0;
            }
        }
    }

    /// A key below `i64::MIN` buckets (here `-inf` and `-1e30`; e.g. a face
    /// whose direction error is infinite or huge) is due at once; `index`
    /// must not overflow (`i64::MIN - 1` wraps to `i64::MAX` in release,
    /// which filed such an item beyond the ring for ever).
    #[test]
    fn keys_below_the_bucket_range_are_due() {
        for bad in [f64::NEG_INFINITY, -1e30] {
            let keys = [1.0, bad, 2.0, 0.5];
            let mut d = Deadlines::default();
            d.rebuild(keys.len(), 1e-3, |i| keys[i]);
            let mut due = Vec::new();
            d.pop_due(0.1, 1e-3, &mut due);
            assert_eq!(due, vec![1], "key {bad} at rebuild");
            // Re-keyed to such a key after a pop: due at the next step.
            d.set(1, bad);
            due.clear();
            d.pop_due(0.101, 1e-3, &mut due);
            assert_eq!(due, vec![1], "key {bad} after set");
        }
    }

    /// Adversarial calendar: steps jumping by 1000x every round, keys far
    /// below the cursor, infinite keys, limits falling back by more than a
    /// bucket, rebases; against a plain scan.
    #[test]
    fn review_adversarial_calendar() {
        let mut r = R::new(0x1234_5678_9abc_def1);
        let mut next = || r.f();
        for n in [1usize, 2, 7, 100, 1000] {
            let mut keys: Vec<f64> = (0..n).map(|_| next() * 3.0).collect();
            let mut d = Deadlines::default();
            d.rebuild(n, 1e-3, |i| keys[i]);
            let mut due = Vec::new();
            let mut limit = 0.0;
            for round in 0..20000 {
                let step = [1e-7, 1e-4, 1e-1, 0.9, 1e-12, 0.0][(next() * 6.0) as usize % 6]
                    * (0.5 + next());
                let r = next();
                limit += if r < 0.05 {
                    -50.0 * step - 1e-3 * next()
                } else {
                    step
                };
                let ctx = format!("n {n} round {round} limit {limit} step {step}");
                pop_checked(&mut d, &keys, limit, step, &mut due, &ctx);
                for &i in &due {
                    let r = next();
                    keys[i as usize] = if r < 0.02 {
                        f64::INFINITY
                    } else if r < 0.1 {
                        limit - next() * 10.0
                    } else {
                        limit
                            + next()
                                * next()
                                * [1e-6, 1e-2, 1.0, 100.0][(next() * 4.0) as usize % 4]
                    };
                    d.set(i, keys[i as usize]);
                }
                if n > 1 && next() < 0.3 {
                    let i = (next() * n as f64) as usize % n;
                    keys[i] = limit + next() * 5.0;
                    d.set(i as u32, keys[i]);
                }
                if round % 997 == 996 {
                    d.shift(limit);
                    keys.iter_mut().for_each(|k| *k -= limit);
                    limit = 0.0;
                }
            }
        }
    }
}

#[cfg(test)]
mod review_motion_tests {
    use crate::dynamic::{DynamicConfig, DynamicSum};
    use crate::kernel::rotation::Pose;
    use crate::kernel::rotation::Rotation;
    use crate::polytope::Polytope;
    use crate::sum::{minkowski_sum_posed, Method};
    use glam::DVec3;

    use super::tests::R;

    /// Never falls back to a from-scratch sum.
    const INC: DynamicConfig = DynamicConfig {
        max_step_angle: f64::INFINITY,
        fallback_fraction: f64::INFINITY,
    };

    fn poly(r: &mut R, grid: bool, n: usize) -> Polytope {
        loop {
            let pts: Vec<[f64; 3]> = (0..n)
                .map(|_| {
                    if grid {
                        [r.i(4) as f64, r.i(4) as f64, r.i(4) as f64]
                    } else {
                        let v = r.axis();
                        [v.x, v.y, v.z]
                    }
                })
                .collect();
            if let Ok(p) = Polytope::from_points(&pts) {
                return p;
            }
        }
    }

    fn check(d: &DynamicSum, ctx: &str) {
        let want = minkowski_sum_posed(d.p(), d.pose_p(), d.q(), d.pose_q(), Method::Walk)
            .unwrap()
            .facets();
        assert_eq!(d.facets(), want, "{ctx}");
    }

    /// The schedule pops every normal the old scan would visit, on motions
    /// mixing step sizes (>16x jumps), coordinate-axis runs, both bodies
    /// moving, and long runs past the rebase.
    #[test]
    fn schedule_pops_what_the_scan_visits() {
        for seed in 1..25u64 {
            let mut r = R::new(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
            let (gp, gq) = (seed % 2 == 0, seed % 3 == 0);
            let p = poly(&mut r, gp, 40);
            let q = poly(&mut r, gq, 40);
            let cfg = if seed % 4 == 0 {
                DynamicConfig::default()
            } else {
                INC
            };
            let mut d =
                DynamicSum::with_config(&p, Pose::IDENTITY, &q, Pose::IDENTITY, cfg).unwrap();
            let sizes = [1e-6, 1e-4, 3e-3, 0.05, 0.5];
            let axes = [DVec3::X, DVec3::Y, DVec3::Z];
            for block in 0..120 {
                let s = sizes[r.i(sizes.len())];
                let axis = if r.f() < 0.5 { axes[r.i(3)] } else { r.axis() };
                let both = r.f() < 0.2;
                let len = if s >= 0.5 && seed % 5 == 0 {
                    2200
                } else {
                    1 + r.i(60)
                };
                for k in 0..len {
                    let a = if r.f() < 0.1 { s } else { s * (0.5 + r.f()) };
                    let step = Rotation::from_axis_angle(axis, a).unwrap();
                    let mut pp = d.pose_p();
                    pp.rotation = pp.rotation.then(&step);
                    let mut pq = d.pose_q();
                    if both {
                        pq.rotation = pq
                            .rotation
                            .then(&Rotation::from_axis_angle(DVec3::Z, -0.3 * a).unwrap());
                    }
                    d.set_pose(pp, pq);
                    if len < 100 || k % 97 == 0 {
                        check(&d, &format!("seed {seed} block {block} k {k}"));
                    }
                }
            }
        }
        let sched =
            crate::dynamic::find_errors::SCHEDULED_STEPS.load(std::sync::atomic::Ordering::Relaxed);
        let ties =
            crate::dynamic::find_errors::TIE_SKIPS.load(std::sync::atomic::Ordering::Relaxed);
        eprintln!("scheduled side-steps {sched}, tie-only skips {ties}");
        assert!(sched > 0);
    }

    /// Runs about coordinate axes from exact poses (persistent ties),
    /// interrupted by generic jumps and resumed on the same axis.
    #[test]
    fn schedule_with_tie_runs() {
        for seed in 1..40u64 {
            let mut r = R::new(seed.wrapping_mul(0x2545_f491_4f6c_dd1d) | 1);
            let np = 12 + r.i(40);
            let p = poly(&mut r, true, np);
            let q = if seed % 3 == 0 {
                Polytope::from_points(&[
                    [0., 0., 0.],
                    [1., 0., 0.],
                    [0., 1., 0.],
                    [1., 1., 0.],
                    [0., 0., 1.],
                    [1., 0., 1.],
                    [0., 1., 1.],
                    [1., 1., 1.],
                ])
                .unwrap()
            } else {
                let nq = 12 + r.i(40);
                poly(&mut r, true, nq)
            };
            let cfg = if seed % 2 == 0 {
                DynamicConfig::default()
            } else {
                INC
            };
            let mut d =
                DynamicSum::with_config(&p, Pose::IDENTITY, &q, Pose::IDENTITY, cfg).unwrap();
            let axes = [DVec3::X, DVec3::Y, DVec3::Z];
            let mut ang = [0.0f64; 3];
            for block in 0..150 {
                let k = r.i(3);
                let s = [1e-4, 1e-3, 0.01, std::f64::consts::FRAC_PI_2 / 32.0][r.i(4)];
                let len = 1 + r.i(80);
                for j in 0..len {
                    ang[k] += s * if r.f() < 0.3 { 1.0 } else { 0.5 + r.f() };
                    let rot = Rotation::from_axis_angle(axes[k], ang[k]).unwrap();
                    let mut pose = Pose::IDENTITY;
                    pose.rotation = rot;
                    d.set_pose(pose, Pose::IDENTITY);
                    check(
                        &d,
                        &format!(
                            "ties seed {seed} block {block} j {j} axis {k} ang {}",
                            ang[k]
                        ),
                    );
                }
            }
        }
        let ties =
            crate::dynamic::find_errors::TIE_SKIPS.load(std::sync::atomic::Ordering::Relaxed);
        eprintln!("tie-only skips {ties}");
    }

    /// A run about z long enough to cross the rebase with big steps, then
    /// small steps about z in the same run (tie keys across the shift).
    #[test]
    fn tie_run_across_rebase() {
        for seed in 1..6u64 {
            let mut r = R::new(seed.wrapping_mul(0x2545_f491_4f6c_dd1d) | 1);
            let np = 12 + r.i(40);
            let p = poly(&mut r, true, np);
            let nq = 12 + r.i(40);
            let q = poly(&mut r, true, nq);
            let mut d =
                DynamicSum::with_config(&p, Pose::IDENTITY, &q, Pose::IDENTITY, INC).unwrap();
            let mut ang = 0.0f64;
            for round in 0..3 {
                for j in 0..2200 {
                    ang += 0.5 * (0.9 + 0.1 * r.f());
                    let mut pose = Pose::IDENTITY;
                    pose.rotation = Rotation::from_axis_angle(DVec3::Z, ang).unwrap();
                    d.set_pose(pose, Pose::IDENTITY);
                    if j % 50 == 0 {
                        check(&d, &format!("rebase seed {seed} round {round} big {j}"));
                    }
                }
                for j in 0..3000 {
                    ang += [1e-4, 1e-3, 0.02][j / 1000] * (0.5 + r.f());
                    let mut pose = Pose::IDENTITY;
                    pose.rotation = Rotation::from_axis_angle(DVec3::Z, ang).unwrap();
                    d.set_pose(pose, Pose::IDENTITY);
                    check(&d, &format!("rebase seed {seed} round {round} small {j}"));
                }
            }
        }
    }

    /// Steps below the drift slack (theta < 1e-10) alternating with large
    /// ones every step (the calendar re-files every step), and exact
    /// quarter-turn landings about z.
    #[test]
    fn tiny_and_alternating_steps() {
        for seed in 1..30u64 {
            let mut r = R::new(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
            let np = 8 + r.i(50);
            let p = poly(&mut r, seed % 2 == 0, np);
            let nq = 8 + r.i(50);
            let q = poly(&mut r, seed % 3 != 0, nq);
            let cfg = if seed % 2 == 0 {
                DynamicConfig::default()
            } else {
                INC
            };
            let mut d =
                DynamicSum::with_config(&p, Pose::IDENTITY, &q, Pose::IDENTITY, cfg).unwrap();
            let axis = r.axis();
            for j in 0..3000 {
                let a = match (j / 300) % 4 {
                    0 => 1e-13 * (1.0 + r.f()),
                    1 => {
                        if j % 2 == 0 {
                            1e-11
                        } else {
                            0.3
                        }
                    }
                    2 => [1e-12, 1e-9, 1e-6, 1e-3][j % 4],
                    _ => 1e-10 * r.f(),
                };
                let step = if (j / 300) % 4 == 3 && j % 7 == 0 {
                    Rotation::from_axis_angle(DVec3::Z, std::f64::consts::FRAC_PI_2).unwrap()
                } else {
                    Rotation::from_axis_angle(axis, a).unwrap()
                };
                let mut pp = d.pose_p();
                pp.rotation = pp.rotation.then(&step);
                d.set_pose(pp, d.pose_q());
                if j % 3 == 0 {
                    check(&d, &format!("tiny seed {seed} j {j}"));
                }
            }
        }
    }
}
