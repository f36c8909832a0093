//! Robot part meshes, part against part (issue 35): the pairs and their
//! states for `parts_vs_parry` and `examples/parts_probe.rs`. The meshes
//! are read from the folder `DYMSUM_PARTS` names (any `*.stl`, `*.obj`,
//! `*.off`, `*.ply`: e.g. every mesh of `ros-industrial/universal_robot`
//! and `ros-industrial/abb`, copied flat), else the built-in room's.
//!
//! A pair's states: the body's centre is put on the obstacle's, turned by
//! a seeded random rotation, then moved along a seeded random direction;
//! *random* states move it a uniform fraction of the two diagonals,
//! *near-contact* states are the two ends of a bisection of that fraction
//! between colliding and free, to 2⁻⁴⁰ of it.

use std::path::{Path, PathBuf};

use dymsum::query::{MeshBody, SceneChecker};
use dymsum::{DVec3, PolygonMesh, Pose};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::random_rotation;

/// A mesh file's name and mesh.
pub struct Part {
    /// The file's name.
    pub name: String,
    /// Its mesh as read.
    pub mesh: PolygonMesh,
}

/// The meshes of folder `dir` (sorted by name; unreadable files skipped
/// with a note on stderr).
pub fn parts(dir: &Path) -> Vec<Part> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    files.sort();
    files
        .into_iter()
        .filter(|p| {
            p.extension().is_some_and(|e| {
                ["stl", "obj", "off", "ply"]
                    .contains(&e.to_ascii_lowercase().to_str().unwrap_or(""))
            })
        })
        .filter_map(|p| match dymsum_io::formats::read_mesh(&p) {
            Ok(mesh) if !mesh.faces.is_empty() => Some(Part {
                name: p.file_name()?.to_string_lossy().into_owned(),
                mesh,
            }),
            Ok(_) => None,
            Err(e) => {
                eprintln!("skipped {}: {e}", p.display());
                None
            }
        })
        .collect()
}

/// The box centre and diagonal of a mesh.
fn centre_and_diagonal(m: &PolygonMesh) -> (DVec3, f64) {
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for p in &m.vertices {
        lo = lo.min(DVec3::from(*p));
        hi = hi.max(DVec3::from(*p));
    }
    ((lo + hi) * 0.5, (hi - lo).length())
}

/// The pairs of `all` to measure, as indices: the one named by `pair`
/// (`"a,b"`: the first parts whose names contain `a` and `b`), else
/// `count` pairs drawn with `seed` (the samples the benchmarks and
/// docs/BENCHMARKS.md name by their seed).
///
/// # Panics
/// Where `pair` has no comma, or names a part `all` does not hold.
pub fn picked_pairs(
    all: &[Part],
    pair: Option<&str>,
    seed: u64,
    count: usize,
) -> Vec<(usize, usize)> {
    if let Some(p) = pair {
        let (a, b) = p.split_once(',').expect("PAIR=a,b");
        let find = |s: &str| all.iter().position(|q| q.name.contains(s)).expect("a part");
        return vec![(find(a), find(b))];
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|_| {
            (
                rng.random_range(0..all.len()),
                rng.random_range(0..all.len()),
            )
        })
        .collect()
}

/// The states of a pair (module docs): `(random, near)`.
///
/// # Panics
/// When a state check fails (not expected: finite states).
pub fn pair_states(
    checker: &SceneChecker,
    body: &PolygonMesh,
    obstacle: &PolygonMesh,
    n: usize,
    seed: u64,
) -> (Vec<Pose>, Vec<Pose>) {
    let (cb, db) = centre_and_diagonal(body);
    let (co, d_o) = centre_and_diagonal(obstacle);
    let reach = db + d_o;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mut random, mut near) = (Vec::new(), Vec::new());
    for k in 0..n {
        let r = random_rotation(seed * 7_919 + k as u64);
        let dir = loop {
            let d = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            if (0.01..=1.0).contains(&d.length_squared()) {
                break d.normalize();
            }
        };
        let at = |s: f64| Pose::new(r, co - r.apply(cb) + dir * (s * reach));
        random.push(at(rng.random_range(0.0..0.6)));
        let (mut lo, mut hi) = (0.0, 1.0);
        if !checker.collides_at(at(lo)).unwrap() || checker.collides_at(at(hi)).unwrap() {
            continue;
        }
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if checker.collides_at(at(mid)).unwrap() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        near.push(at(lo));
        near.push(at(hi));
    }
    (random, near)
}

/// dymsum's checker of `body` against `obstacle`.
///
/// # Panics
/// When a mesh has no triangle of positive area.
pub fn part_checker(body: &PolygonMesh, obstacle: &PolygonMesh) -> SceneChecker {
    let b = MeshBody::new(body).expect("a body mesh");
    let o = MeshBody::new(obstacle).expect("an obstacle mesh");
    SceneChecker::new(&b, &[o]).expect("a checker")
}
