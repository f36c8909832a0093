//! Shared test support for the dymsum crates, written once: random shape
//! generators (including the degenerate kinds), random rotations and axes,
//! the paper's motion, the oracles every dynamic step is checked against
//! (a fresh `walk` sum, the exact diff, the hull of all pairwise vertex
//! sums), and small fixtures (literal meshes, directory listings).
//!
//! A dev-dependency of `dymsum`, `dymsum-io` and `dymsum-cli`, and a
//! dependency of `dymsum-bench`; never published.

pub mod fuzz_solid;
pub mod fuzz_triangles;

use dymsum::{DVec3, Polytope, Rotation};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// The kinds of random polytopes the oracle tests draw from.
#[derive(Clone, Copy, Debug)]
pub enum Kind {
    /// Uniform in a ball.
    Ball,
    /// Integer grid points (many exactly coplanar faces and parallel edges).
    Grid,
    /// Points on a few planes (coplanar clusters).
    Coplanar,
    /// On a sphere.
    Sphere,
    /// Uniform in the cube `[-1, 1]³`.
    Cube,
}

pub fn points(kind: Kind, n: usize, r: &mut ChaCha8Rng) -> Vec<DVec3> {
    (0..n)
        .map(|_| match kind {
            Kind::Ball => loop {
                let p = DVec3::new(
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                );
                if p.length() <= 1.0 {
                    break p;
                }
            },
            Kind::Grid => DVec3::new(
                r.random_range(-2..=2) as f64,
                r.random_range(-2..=2) as f64,
                r.random_range(-2..=2) as f64,
            ),
            Kind::Coplanar => {
                let axis = r.random_range(0..3);
                let mut p = DVec3::new(
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                );
                p[axis] = if r.random_bool(0.5) { 1.0 } else { -1.0 };
                p
            }
            Kind::Cube => DVec3::new(
                r.random_range(-1.0..1.0),
                r.random_range(-1.0..1.0),
                r.random_range(-1.0..1.0),
            ),
            Kind::Sphere => random_unit(r),
        })
        .collect()
}

pub fn random_polytope(kind: Kind, n: usize, r: &mut ChaCha8Rng) -> Polytope {
    loop {
        let pts = points(kind, n, r);
        if let Ok(p) = Polytope::from_dvec3s(&pts) {
            return p;
        }
    }
}

/// A random unit vector, uniform on the sphere: a point of the cube
/// `[−1, 1)³` kept when its length is in `(0.1, 1]`, then normalised (the
/// sphere kind of [`points`]; the tests' seeded draws share it).
pub fn random_unit(r: &mut ChaCha8Rng) -> DVec3 {
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

pub fn random_rotation(r: &mut ChaCha8Rng) -> Rotation {
    loop {
        let q = [
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
        ];
        let l: f64 = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        if l > 0.1 && l <= 1.0 {
            return Rotation::from_wxyz(q[0], q[1], q[2], q[3]).unwrap();
        }
    }
}

pub fn cube_points(lo: f64, hi: f64) -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { lo } else { hi },
                if i & 2 == 0 { lo } else { hi },
                if i & 4 == 0 { lo } else { hi },
            ]
        })
        .collect()
}

/// The eight corners of the box `[lo, hi]`: bit `k` of a corner's index
/// picks `hi[k]` (the numbering [`CUBE_QUADS`] uses).
pub fn box_corners(lo: [f64; 3], hi: [f64; 3]) -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| std::array::from_fn(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
        .collect()
}

/// The axis-aligned box `[lo, hi]` as a polytope (the motion tests', bench's
/// and fuzzers' obstacles).
pub fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> Polytope {
    Polytope::from_points(&box_corners(lo, hi)).expect("a box with lo < hi")
}

/// The grazing family of issue 26 §4, shared by the motion tests and the
/// `motion_grazing` bench: a bar `[0, 2] × [−.05, .05]²` turning about z,
/// and obstacles `gap` beyond the reach of its corners.
pub mod grazing {
    use super::cuboid;
    use dymsum::Polytope;

    /// The turning bar.
    pub fn bar() -> Polytope {
        cuboid([0.0, -0.05, -0.05], [2.0, 0.05, 0.05])
    }

    /// The largest x the bar's corners reach while turning about z.
    pub fn reach() -> f64 {
        (4.0f64 + 0.0025).sqrt()
    }

    /// A thin plate facing the bar's tip (face against corner).
    pub fn plate(gap: f64) -> Polytope {
        let x = reach() + gap;
        cuboid([x, -1.0, -1.0], [x + 0.01, 1.0, 1.0])
    }

    /// A square rod along z with one edge towards the bar's tip (edge
    /// against the bar's corner and edges).
    pub fn rod_edge(gap: f64) -> Polytope {
        let x = reach() + gap;
        let h = 0.05;
        let pts: Vec<[f64; 3]> = [[x, 0.0], [x + h, h], [x + 2.0 * h, 0.0], [x + h, -h]]
            .iter()
            .flat_map(|&[px, py]| [[px, py, -1.0], [px, py, 1.0]])
            .collect();
        Polytope::from_points(&pts).expect("a square rod")
    }
}

pub fn box_points(x: f64, y: f64, z: f64) -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { -x } else { x },
                if i & 2 == 0 { -y } else { y },
                if i & 4 == 0 { -z } else { z },
            ]
        })
        .collect()
}

/// Oracles for the dynamic sum, shared by `dynamic_sums.rs` and
/// `dymsum-io/tests/dynamic_models.rs` (which includes this file by path).
pub mod oracle {
    use super::{random_rotation, rng};
    use dymsum::hull::{convex_hull, PairwiseSums};
    use dymsum::sum::{minkowski_sum_posed, Facet, Method};
    use dymsum::{DVec3, DynamicSum, Polytope, Pose, Rotation, UpdateReport};
    use rand::Rng;
    use rand_chacha::ChaCha8Rng;
    use std::collections::HashSet;
    use std::f64::consts::{FRAC_PI_2, PI, TAU};

    /// A rotation with its exact quaternion printed (for reproductions).
    pub fn show_rot(r: &Rotation) -> String {
        let [w, x, y, z] = r.wxyz();
        format!("wxyz=[{w:e}, {x:e}, {y:e}, {z:e}]")
    }

    /// A pose with its exact numbers printed.
    pub fn show_pose(p: &Pose) -> String {
        format!("{} t={:?}", show_rot(&p.rotation), p.translation.to_array())
    }

    /// The static `walk` facets at the dynamic sum's current poses.
    pub fn walk_facets(d: &DynamicSum) -> Vec<Facet> {
        minkowski_sum_posed(d.p(), d.pose_p(), d.q(), d.pose_q(), Method::Walk)
            .expect("static walk failed")
            .facets()
    }

    /// Checks the update report against the facet sets before and after:
    /// removed ⊆ before, added ∩ before = ∅, before − removed + added = after
    /// (as sets, no duplicates), and the error counts match the removed kinds.
    pub fn check_report(
        before: &[Facet],
        after: &[Facet],
        rep: &UpdateReport,
        ctx: &str,
    ) -> Result<(), String> {
        let b: HashSet<Facet> = before.iter().copied().collect();
        let a: HashSet<Facet> = after.iter().copied().collect();
        if a.len() != after.len() {
            return Err(format!("{ctx}: the facet list has duplicates"));
        }
        let removed: HashSet<Facet> = rep.removed.iter().copied().collect();
        let added: HashSet<Facet> = rep.added.iter().copied().collect();
        if removed.len() != rep.removed.len() {
            return Err(format!(
                "{ctx}: duplicates in report.removed: {:?}",
                rep.removed
            ));
        }
        if added.len() != rep.added.len() {
            return Err(format!(
                "{ctx}: duplicates in report.added: {:?}",
                rep.added
            ));
        }
        if let Some(f) = removed.iter().find(|f| !b.contains(f)) {
            return Err(format!("{ctx}: removed {f:?} was not a facet before"));
        }
        if let Some(f) = added.iter().find(|f| b.contains(f)) {
            return Err(format!("{ctx}: added {f:?} was already a facet"));
        }
        let mut expect: HashSet<Facet> = b.difference(&removed).copied().collect();
        expect.extend(added.iter().copied());
        if expect != a {
            let missing: Vec<_> = a.difference(&expect).collect();
            let extra: Vec<_> = expect.difference(&a).collect();
            return Err(format!(
                "{ctx}: before - removed + added != after; missing from the diff {missing:?}, \
                 spurious {extra:?}"
            ));
        }
        let ee = rep
            .removed
            .iter()
            .filter(|f| matches!(f, Facet::Ee { .. }))
            .count();
        let fv = rep.removed.len() - ee;
        if rep.fv_errors != fv || rep.ee_errors != ee {
            return Err(format!(
                "{ctx}: report counts fv_errors={} ee_errors={}, removed has {fv} fv/vf and {ee} ee",
                rep.fv_errors, rep.ee_errors
            ));
        }
        Ok(())
    }

    fn support(points: &[DVec3], d: DVec3) -> f64 {
        points
            .iter()
            .map(|p| p.dot(d))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// The merged mesh against the exact hull of pairwise sums of the posed
    /// vertices (volume within 1e-9 relative) and the support function in 32
    /// random directions (within 1e-9 times the scale).
    pub fn check_mesh_against_hull(d: &DynamicSum, ctx: &str) -> Result<(), String> {
        let pp: Vec<DVec3> = d
            .p()
            .vertices()
            .iter()
            .map(|&v| d.pose_p().apply(v))
            .collect();
        let qq: Vec<DVec3> = d
            .q()
            .vertices()
            .iter()
            .map(|&v| d.pose_q().apply(v))
            .collect();
        let mesh = d.try_to_mesh().map_err(|e| format!("{ctx}: mesh: {e}"))?;
        let sums = PairwiseSums::new(&pp, &qq);
        let hull = convex_hull(&sums).map_err(|e| format!("{ctx}: hull of sums: {e}"))?;
        let hull_mesh = hull.to_mesh(&sums);
        let (vm, vh) = (mesh.signed_volume(), hull_mesh.signed_volume());
        if (vm - vh).abs() > 1e-9 * vh.abs().max(1e-300) {
            return Err(format!("{ctx}: merged volume {vm} vs hull of sums {vh}"));
        }
        let mv: Vec<DVec3> = mesh.vertices.iter().map(|v| DVec3::from(*v)).collect();
        let scale = pp.iter().map(|v| v.length()).fold(0.0, f64::max)
            + qq.iter().map(|v| v.length()).fold(0.0, f64::max)
            + 1.0;
        let mut r = rng(7);
        for _ in 0..32 {
            let dir = random_rotation(&mut r).apply(DVec3::X);
            let h = support(&pp, dir) + support(&qq, dir);
            let s = support(&mv, dir);
            if (s - h).abs() > 1e-9 * scale {
                return Err(format!(
                    "{ctx}: support in {dir:?}: mesh {s} vs P+Q {h} (scale {scale})"
                ));
            }
        }
        Ok(())
    }

    /// A dynamic sum under test: every update is checked against `walk`
    /// and the report; every `deep_every` updates the sanity check and the
    /// hull-of-sums oracle run too.
    pub struct Checked {
        /// The sum under test.
        pub d: DynamicSum,
        /// Facets after the last update.
        pub prev: Vec<Facet>,
        /// Updates so far.
        pub steps: usize,
        /// Run the deep oracles every this many steps (0: never).
        pub deep_every: usize,
        /// Printed in failures.
        pub label: String,
        /// Updates that were recomputed from scratch.
        pub recomputed: usize,
    }

    impl Checked {
        /// Wraps a dynamic sum, checking its initial state.
        pub fn new(d: DynamicSum, deep_every: usize, label: impl Into<String>) -> Self {
            let label = label.into();
            let prev = d.facets();
            assert_eq!(
                prev,
                walk_facets(&d),
                "{label}: initial state differs from walk"
            );
            Checked {
                d,
                prev,
                steps: 0,
                deep_every,
                label,
                recomputed: 0,
            }
        }

        /// Starts at the given poses with the default configuration.
        pub fn start(
            p: &Polytope,
            pose_p: Pose,
            q: &Polytope,
            pose_q: Pose,
            deep_every: usize,
            label: impl Into<String>,
        ) -> Self {
            Self::new(
                DynamicSum::new(p, pose_p, q, pose_q).expect("DynamicSum::new"),
                deep_every,
                label,
            )
        }

        /// Moves both bodies and checks everything; `Err` describes the
        /// first failure with a reproduction.
        pub fn try_set_pose(&mut self, pose_p: Pose, pose_q: Pose) -> Result<UpdateReport, String> {
            let (old_p, old_q) = (self.d.pose_p(), self.d.pose_q());
            let before_state = self.d.clone();
            self.steps += 1;
            let ctx = format!(
                "{} step {}: from P {} Q {} to P {} Q {}",
                self.label,
                self.steps,
                show_pose(&old_p),
                show_pose(&old_q),
                show_pose(&pose_p),
                show_pose(&pose_q)
            );
            let rep = self.d.set_pose(pose_p, pose_q);
            if let Some(bug) = &rep.recovered {
                return Err(format!(
                    "{ctx}: the repair met an internal inconsistency: {bug}"
                ));
            }
            if rep.recomputed {
                self.recomputed += 1;
            }
            let now = self.d.facets();
            let walk = walk_facets(&self.d);
            if now != walk {
                let now_s: HashSet<Facet> = now.iter().copied().collect();
                let walk_s: HashSet<Facet> = walk.iter().copied().collect();
                let extra: Vec<_> = now_s.difference(&walk_s).collect();
                let missing: Vec<_> = walk_s.difference(&now_s).collect();
                // Does the single step reproduce from a fresh start?
                let mut fresh =
                    DynamicSum::with_config(self.d.p(), old_p, self.d.q(), old_q, self.d.config())
                        .expect("new");
                fresh.set_pose(pose_p, pose_q);
                let fresh_ok = fresh.facets() == walk;
                let state_ok = before_state.facets() == self.prev;
                return Err(format!(
                    "{ctx}: dynamic facets differ from walk (step angle {:e}, recomputed {}, \
                     fv_errors {}, ee_errors {}, rewalked {}); dynamic has extra {extra:?}, \
                     misses {missing:?}; a fresh DynamicSum at the old pose doing the same step \
                     matches walk: {fresh_ok:?}; state before step was consistent: {state_ok}",
                    rep.step_angle, rep.recomputed, rep.fv_errors, rep.ee_errors, rep.rewalked_arcs
                ));
            }
            check_report(&self.prev, &now, &rep, &ctx)?;
            if rep.step_angle.is_nan() || rep.step_angle < 0.0 || rep.step_angle > PI + 1e-12 {
                return Err(format!("{ctx}: bad step angle {}", rep.step_angle));
            }
            let q = pose_p.rotation.quat();
            if (q.length() - 1.0).abs() > 1e-12 {
                return Err(format!("{ctx}: P's quaternion has length {}", q.length()));
            }
            if self.steps.checked_rem(self.deep_every) == Some(0) {
                self.deep_check()?;
            }
            self.prev = now;
            Ok(rep)
        }

        /// [`Checked::try_set_pose`], panicking on failure.
        pub fn set_pose(&mut self, pose_p: Pose, pose_q: Pose) -> UpdateReport {
            self.try_set_pose(pose_p, pose_q)
                .unwrap_or_else(|e| panic!("{e}"))
        }

        /// Moves P only.
        pub fn set_pose_p(&mut self, pose_p: Pose) -> UpdateReport {
            let q = self.d.pose_q();
            self.set_pose(pose_p, q)
        }

        /// Turns P further by `r` (as [`DynamicSum::rotate_p_by`], but
        /// checked; the pose is composed exactly as the library does).
        pub fn rotate_p_by(&mut self, r: Rotation) -> UpdateReport {
            let mut pose = self.d.pose_p();
            pose.rotation = pose.rotation.then(&r);
            self.set_pose_p(pose)
        }

        /// Sanity check and the hull-of-sums oracle now.
        pub fn deep_check(&self) -> Result<(), String> {
            let ctx = format!(
                "{} after step {} at P {} Q {}",
                self.label,
                self.steps,
                show_pose(&self.d.pose_p()),
                show_pose(&self.d.pose_q())
            );
            self.d
                .sanity_check()
                .map_err(|e| format!("{ctx}: sanity_check: {e}"))?;
            check_mesh_against_hull(&self.d, &ctx)
        }
    }

    /// Steps per full turn in the paper's protocol.
    pub const STEPS_PER_TURN: [f64; 6] = [10.0, 100.0, 500.0, 1000.0, 10_000.0, 100_000.0];

    /// A uniformly random unit vector.
    pub fn random_axis(r: &mut ChaCha8Rng) -> DVec3 {
        random_rotation(r).apply(DVec3::new(0.0, 0.0, 1.0))
    }

    /// One move of the paper's motion, mixed with large jumps.
    #[derive(Clone, Copy, Debug)]
    pub enum Move {
        /// Turn further by this rotation (`rotate_p_by`).
        By(Rotation),
        /// Go to this absolute orientation.
        To(Rotation),
    }

    /// The paper's protocol (§5): a random axis held for 1..=50 steps of
    /// 2π/X, X drawn from [`STEPS_PER_TURN`] (or fixed), with jumps of
    /// probability `jump_prob`: random absolute rotations, turns by exactly
    /// π about a random axis, exact quarter turns about coordinate axes
    /// (relative) and exact k·90° orientations about coordinate axes
    /// (absolute: faces exactly parallel for grid polytopes).
    pub struct PaperMotion {
        r: ChaCha8Rng,
        axis: DVec3,
        left: usize,
        angle: f64,
        /// Fixed steps per turn (`None`: drawn per axis).
        pub steps_per_turn: Option<f64>,
        /// Probability of a jump instead of a step.
        pub jump_prob: f64,
    }

    impl PaperMotion {
        /// A motion from a seed.
        pub fn new(seed: u64, steps_per_turn: Option<f64>, jump_prob: f64) -> Self {
            PaperMotion {
                r: rng(seed ^ 0x005e_ed0f_d1ce),
                axis: DVec3::Z,
                left: 0,
                angle: 0.0,
                steps_per_turn,
                jump_prob,
            }
        }

        /// The next move.
        pub fn next_move(&mut self) -> Move {
            let r = &mut self.r;
            if self.jump_prob > 0.0 && r.random_bool(self.jump_prob) {
                let coord = [DVec3::X, DVec3::Y, DVec3::Z][r.random_range(0..3)];
                return match r.random_range(0..4) {
                    0 => Move::To(random_rotation(r)),
                    1 => Move::By(Rotation::from_axis_angle(random_axis(r), PI).unwrap()),
                    2 => Move::By(
                        Rotation::from_axis_angle(coord, FRAC_PI_2 * r.random_range(1..4) as f64)
                            .unwrap(),
                    ),
                    _ => Move::To(
                        Rotation::from_axis_angle(coord, FRAC_PI_2 * r.random_range(0..4) as f64)
                            .unwrap(),
                    ),
                };
            }
            if self.left == 0 {
                self.axis = random_axis(r);
                self.left = r.random_range(1..=50);
                let x = self
                    .steps_per_turn
                    .unwrap_or_else(|| STEPS_PER_TURN[r.random_range(0..STEPS_PER_TURN.len())]);
                self.angle = TAU / x;
            }
            self.left -= 1;
            Move::By(Rotation::from_axis_angle(self.axis, self.angle).unwrap())
        }

        /// Applies the next move to P of a checked sum.
        pub fn apply(&mut self, c: &mut Checked) -> UpdateReport {
            match self.next_move() {
                Move::By(r) => c.rotate_p_by(r),
                Move::To(r) => {
                    let t = c.d.pose_p().translation;
                    c.set_pose_p(Pose::new(r, t))
                }
            }
        }
    }
}

/// Integer grid points (as [`Kind::Grid`]) each moved by a random offset of
/// size up to `eps`: nearly coplanar faces, tiny Gaussian arcs, nearly
/// parallel faces between two such polytopes.
pub fn jittered_grid_polytope(n: usize, eps: f64, r: &mut ChaCha8Rng) -> Polytope {
    loop {
        let pts: Vec<DVec3> = points(Kind::Grid, n, r)
            .into_iter()
            .map(|p| {
                p + DVec3::new(
                    r.random_range(-eps..=eps),
                    r.random_range(-eps..=eps),
                    r.random_range(-eps..=eps),
                )
            })
            .collect();
        if let Ok(p) = Polytope::from_dvec3s(&pts) {
            return p;
        }
    }
}

/// A triangulated sphere-like convex mesh: the hull of `n` points on the
/// unit sphere (golden spiral), fan-triangulated (large meshes for the load
/// tests and the `mesh_load` bench).
pub fn sphere_mesh(n: usize) -> dymsum::PolygonMesh {
    let pts: Vec<[f64; 3]> = (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - z * z).sqrt();
            let t = i as f64 * 2.399_963_229_728_653;
            [r * t.cos(), r * t.sin(), z]
        })
        .collect();
    let m = Polytope::from_points(&pts).expect("sphere hull").to_mesh();
    let faces = m
        .faces
        .iter()
        .flat_map(|f| (1..f.len() - 1).map(move |k| vec![f[0], f[k], f[k + 1]]))
        .collect();
    dymsum::PolygonMesh::new(m.vertices, faces)
}

/// The 6 outward quads of a cube whose vertex `i` is the corner
/// `(i & 1, i >> 1 & 1, i >> 2 & 1)` (the order of [`cube_points`]).
pub const CUBE_QUADS: [[usize; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];

/// The cube `[lo, hi]³` as a quad mesh ([`cube_points`], [`CUBE_QUADS`]).
pub fn cube_mesh_between(lo: f64, hi: f64) -> dymsum::PolygonMesh {
    let faces = CUBE_QUADS.iter().map(|q| q.to_vec()).collect();
    dymsum::PolygonMesh::new(cube_points(lo, hi), faces)
}

/// The unit cube `[0, 1]³` as a polygon mesh: the literal fixture of the
/// format and I/O tests.
pub fn cube_mesh() -> dymsum::PolygonMesh {
    cube_mesh_between(0.0, 1.0)
}

/// The cube `[-1, 1]³` shifted by `offset` along x, as OBJ text: 8 `v`
/// lines (bottom then top, counter-clockwise), then 6 outward `f` lines
/// whose 1-based indices start after `first` earlier vertices, each in its
/// own `g sideK` group if `grouped`.
pub fn cube_obj(offset: f64, first: usize, grouped: bool) -> String {
    const FACES: [[usize; 4]; 6] = [
        [1, 4, 3, 2],
        [5, 6, 7, 8],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 4, 8, 7],
        [4, 1, 5, 8],
    ];
    let mut s = String::new();
    for z in [-1.0, 1.0] {
        for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            s += &format!("v {} {} {}\n", x + offset, y, z);
        }
    }
    for (i, f) in FACES.iter().enumerate() {
        if grouped {
            s += &format!("g side{i}\n");
        }
        let idx: Vec<String> = f.iter().map(|v| (v + first).to_string()).collect();
        s += &format!("f {}\n", idx.join(" "));
    }
    s
}

/// Scratch directories and listings for the tests that write files.
pub mod files {
    use std::path::{Path, PathBuf};
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::{Mutex, Once};

    /// A fresh, empty directory under the system temp dir, named after
    /// `suite`, the process, a counter and `name` (unique per call, so
    /// parallel tests never share one). A leftover of an earlier run with the
    /// same name is removed first. Every directory made here is removed when
    /// the test process exits, passed or failed (an `atexit` handler: a test
    /// that forgets [`remove_dir`] leaves nothing in the temp dir; issue 29).
    pub fn temp_dir(suite: &str, name: &str) -> PathBuf {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "dymsum-{suite}-{}-{}-{name}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        if dir.exists() {
            std::fs::remove_dir_all(&dir).expect("remove a stale scratch directory");
        }
        std::fs::create_dir_all(&dir).expect("create a scratch directory");
        remove_at_exit(&dir);
        dir
    }

    /// The directories [`temp_dir`] made in this process.
    static MADE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

    /// Registers `dir` for removal when the process exits (the handler is
    /// installed once).
    fn remove_at_exit(dir: &Path) {
        static INSTALL: Once = Once::new();
        MADE.lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(dir.to_path_buf());
        INSTALL.call_once(|| {
            extern "C" fn remove_all() {
                let dirs = std::mem::take(&mut *MADE.lock().unwrap_or_else(|e| e.into_inner()));
                for d in dirs {
                    let _ = std::fs::remove_dir_all(d);
                }
            }
            extern "C" {
                fn atexit(f: extern "C" fn()) -> std::ffi::c_int;
            }
            // SAFETY: `atexit` is the C library's; `remove_all` is a plain
            // `extern "C" fn` without arguments that does not unwind (it
            // ignores every error). libtest leaves through `exit` (returning
            // from `main`, or `process::exit` after a failure), which runs it.
            unsafe {
                atexit(remove_all);
            }
        });
    }

    /// Removes a scratch directory made by [`temp_dir`] (best effort at
    /// the end of a test: a failure to clean up is not the test's subject,
    /// so it is reported, not fatal).
    pub fn remove_dir(dir: &Path) {
        if let Err(e) = std::fs::remove_dir_all(dir) {
            eprintln!("note: could not remove {}: {e}", dir.display());
        }
    }

    /// The file names in `dir`, sorted.
    pub fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .expect("list a scratch directory")
            .map(|e| {
                e.expect("read a directory entry")
                    .file_name()
                    .to_string_lossy()
                    .into_owned()
            })
            .collect();
        v.sort();
        v
    }
}

/// Proptest case count: `default`, or the `DYMSUM_PROPTEST_CASES`
/// environment variable for long stress runs.
pub fn proptest_cases(default: u32) -> u32 {
    std::env::var("DYMSUM_PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

/// Small bodies far from the origin (issue 33 §4): the family of motions
/// the test `far_small_motions` checks and the bench of the same name
/// counts and times (one generator, one seed).
pub mod far_small {
    use dymsum::{DVec3, Polytope, Pose, Rotation};
    use rand::Rng;
    use rand_chacha::ChaCha8Rng;

    use super::{cuboid, random_polytope, random_rotation, rng, Kind};

    pub const TOL: f64 = 1e-6;
    /// The body's and the obstacles' size.
    pub const SIZE: f64 = 1e-3;
    pub const OFFSETS: [f64; 4] = [1e3, 1e4, 1e5, 1e6];

    /// One case of the family: a body, one obstacle, and a motion.
    pub struct Case {
        pub kind: &'static str,
        pub offset: f64,
        pub body: Polytope,
        pub obstacle: Polytope,
        pub from: Pose,
        pub to: Pose,
    }

    fn scaled(p: &Polytope, s: f64, shift: DVec3) -> Polytope {
        let pts: Vec<DVec3> = p.vertices().iter().map(|&v| v * s + shift).collect();
        Polytope::from_dvec3s(&pts).unwrap()
    }

    /// A random unit vector ([`super::random_unit`]).
    fn unit(r: &mut ChaCha8Rng) -> DVec3 {
        super::random_unit(r)
    }

    /// A small random turn (at most `max` radians about a random axis).
    fn small_turn(r: &mut ChaCha8Rng, max: f64) -> Rotation {
        Rotation::from_axis_angle(unit(r), r.random_range(-max..max)).unwrap()
    }

    /// The family: `per_kind` motions of each kind at each offset.
    pub fn family(seed: u64, per_kind: usize) -> Vec<Case> {
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
                            let obstacle = scaled(
                                &random_polytope(Kind::Ball, 12, &mut r),
                                SIZE / 2.0,
                                centre,
                            );
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
                            let obstacle = scaled(
                                &random_polytope(Kind::Ball, 12, &mut r),
                                SIZE / 2.0,
                                centre,
                            );
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
}

/// Bodies of triangles built from arbitrary bytes, and the properties every
/// one must have: the stable proptest `crates/dymsum/tests/fuzz_bodies.rs`
/// (in CI) and the cargo-fuzz target `fuzz/fuzz_targets/bodies.rs` (off
/// CI) both run [`fuzz_bodies::check`].
pub mod fuzz_bodies {
    use dymsum::query::{surfaces_touch, MeshBody, SceneChecker};
    use dymsum::solid::soup::clean_soup;
    use dymsum::{DVec3, PolygonMesh, Pose, Rotation};

    /// A soup on a coarse grid (coordinates 0..=4, so coplanar faces,
    /// shared edges, T-junctions and touching parts are common): a first
    /// byte of 128 or more makes closed boxes and fins (`boxes`); else it
    /// sets the vertex count, three bytes each vertex, then three bytes
    /// each triangle.
    pub fn soup(data: &[u8]) -> PolygonMesh {
        let Some((&n, rest)) = data.split_first() else {
            return PolygonMesh::new(Vec::new(), Vec::new());
        };
        if n >= 128 {
            return boxes(n, rest);
        }
        let n = 4 + usize::from(n % 12);
        let mut bytes = rest.iter().copied();
        let mut next = || bytes.next().unwrap_or(0);
        let vertices: Vec<[f64; 3]> = (0..n)
            .map(|_| std::array::from_fn(|_| f64::from(next() % 5)))
            .collect();
        let faces = rest
            .get(3 * n..)
            .unwrap_or(&[])
            .chunks_exact(3)
            .take(48)
            .map(|t| t.iter().map(|&b| usize::from(b) % n).collect())
            .collect();
        PolygonMesh::new(vertices, faces)
    }

    /// Closed boxes on the grid (1 to 4; each outward or inward, some
    /// listed double-sided, so touching solids, nested shells and cavities
    /// are common), then a few loose triangles over their corners (fins).
    fn boxes(n: u8, rest: &[u8]) -> PolygonMesh {
        let mut bytes = rest.iter().copied();
        let mut next = || bytes.next().unwrap_or(0);
        let mut m = PolygonMesh::new(Vec::new(), Vec::new());
        for _ in 0..1 + n % 4 {
            let (lo, size, how) = (
                [next(), next(), next()].map(|b| f64::from(b % 4)),
                [next(), next(), next()].map(|b| f64::from(1 + b % 2)),
                next(),
            );
            let base = m.vertices.len();
            m.vertices.extend(super::box_corners(
                lo,
                std::array::from_fn(|k| lo[k] + size[k]),
            ));
            for q in super::CUBE_QUADS {
                let q: Vec<usize> = q.iter().map(|v| v + base).collect();
                let back: Vec<usize> = q.iter().rev().copied().collect();
                match how % 8 {
                    0..=4 => m.faces.push(q),
                    5 => m.faces.push(back),
                    6 => m.faces.extend([q, back]),
                    _ => m.faces.extend([back.clone(), q, back]),
                }
            }
        }
        let count = m.vertices.len();
        for _ in 0..next() % 4 {
            m.faces
                .push((0..3).map(|_| usize::from(next()) % count).collect());
        }
        m
    }

    /// The generalised winding number of the weighted triangles about `p`
    /// (solid angles summed in floats): an oracle independent of the ray
    /// test, accurate away from the triangles.
    fn winding_number(mesh: &PolygonMesh, weights: &[u32], p: DVec3) -> f64 {
        let mut sum = 0.0;
        for (f, &w) in mesh.faces.iter().zip(weights) {
            let [a, b, c] = [f[0], f[1], f[2]].map(|v| DVec3::from(mesh.vertices[v]) - p);
            let (la, lb, lc) = (a.length(), b.length(), c.length());
            let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
            sum += f64::from(w) * 2.0 * a.dot(b.cross(c)).atan2(den);
        }
        sum / (4.0 * std::f64::consts::PI)
    }

    /// Every property (panics naming the one broken): the body is built or
    /// refused with a typed error, passes its sanity check, answers the
    /// same in both roles, collides whenever its triangles touch a probe,
    /// and otherwise collides exactly when the winding number about the
    /// probe's centre is not zero.
    pub fn check(data: &[u8]) {
        let mesh = soup(data);
        let Ok(body) = MeshBody::new(&mesh) else {
            return; // a typed error (no faces, none left)
        };
        body.sanity_check().expect("sanity");
        let soup = clean_soup(&mesh).expect("cleaned as the body was");
        let h = 1.0 / 16.0;
        let probe_mesh = super::cuboid([-h; 3], [h; 3]).to_mesh();
        let probe = MeshBody::new(&probe_mesh).expect("a cube");
        let among = SceneChecker::new(&probe, std::slice::from_ref(&body)).expect("checker");
        let around = SceneChecker::new(&body, std::slice::from_ref(&probe)).expect("checker");
        let tail = data.iter().rev().take(3).copied().collect::<Vec<u8>>();
        let c: [f64; 3] = std::array::from_fn(|k| {
            f64::from(tail.get(k).copied().unwrap_or(0) % 20) / 4.0 + 0.125
        });
        let at = Pose::new(Rotation::IDENTITY, DVec3::from(c));
        let back = Pose::new(Rotation::IDENTITY, -DVec3::from(c));
        let collides = among.collides_at(at).expect("decided");
        assert_eq!(
            collides,
            around.collides_at(back).expect("decided"),
            "roles at {c:?}"
        );
        let touch = surfaces_touch(&probe_mesh, at, &soup.mesh, Pose::IDENTITY).expect("touch");
        if touch {
            assert!(collides, "touching but free at {c:?}");
            return;
        }
        let w = winding_number(&soup.mesh, &soup.weights, DVec3::from(c));
        assert!(
            (w - w.round()).abs() < 1e-6,
            "the winding number {w} at {c:?} is not an integer: the enclosing part is no cycle"
        );
        assert_eq!(collides, w.round() != 0.0, "winding number {w} at {c:?}");
    }
}
