//! The scene workload of the `scenes_vs_parry` bench (issue 28): a robot
//! and an environment as triangle meshes (OMPL.app's problems, exported as
//! OBJ by `python/benchmarks/export_scenes.py` into a folder named by
//! `DYMSUM_SCENES`, since their licence forbids shipping them; without it,
//! a built-in room of open plates and double-sided boxes), with seeded
//! random states in the problem's bounds, checked by dymsum's
//! [`SceneChecker`] and by parry3d-f64's BVH mesh–mesh `intersection_test`.

use std::path::Path;

use crate::contact::parry_pose;
use crate::random_rotation;
use dymsum::query::{MeshBody, SceneChecker};
use dymsum::{DVec3, PolygonMesh, Pose};
use parry3d_f64::math::Vector;
use parry3d_f64::shape::TriMesh;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// One problem: meshes, bounds, and states.
pub struct Scene {
    /// Its name (the folder's).
    pub name: String,
    /// The robot (its own frame).
    pub robot: PolygonMesh,
    /// The environment (world frame).
    pub env: PolygonMesh,
    /// Random states in the bounds.
    pub states: Vec<Pose>,
}

/// The scenes of `DYMSUM_SCENES` (each a folder with `robot.obj`,
/// `env.obj`, `bounds.txt`), or the built-in room.
///
/// # Panics
/// When a listed folder cannot be read.
pub fn scenes(states: usize) -> Vec<Scene> {
    let Ok(dir) = std::env::var("DYMSUM_SCENES") else {
        return vec![room(states)];
    };
    let only: Option<Vec<String>> = std::env::var("DYMSUM_SCENES_ONLY")
        .ok()
        .map(|s| s.split(',').map(str::to_string).collect());
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .expect("DYMSUM_SCENES names a folder")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| only.as_ref().is_none_or(|o| o.contains(n)))
        .collect();
    names.sort();
    names
        .into_iter()
        .map(|name| {
            let d = Path::new(&dir).join(&name);
            let read = |f: &str| dymsum_io::formats::read_mesh(&d.join(f)).expect("an OBJ file");
            let b: Vec<f64> = std::fs::read_to_string(d.join("bounds.txt"))
                .expect("bounds.txt")
                .split_whitespace()
                .map(|x| x.parse().expect("a number"))
                .collect();
            let (lo, hi) = (DVec3::new(b[0], b[1], b[2]), DVec3::new(b[3], b[4], b[5]));
            Scene {
                states: random_states(states, lo, hi, 7),
                robot: read("robot.obj"),
                env: read("env.obj"),
                name,
            }
        })
        .collect()
}

/// Seeded uniform states: translations in `[lo, hi]`, rotations uniform.
pub fn random_states(n: usize, lo: DVec3, hi: DVec3, seed: u64) -> Vec<Pose> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|k| {
            let t = DVec3::new(
                rng.random_range(lo.x..=hi.x),
                rng.random_range(lo.y..=hi.y),
                rng.random_range(lo.z..=hi.z),
            );
            Pose::new(random_rotation(seed * 1_000_003 + k as u64), t)
        })
        .collect()
}

/// A cuboid's boundary appended to `v`, `f` as triangles, each listed twice,
/// back to back (as exporters write double-sided faces).
fn cuboid_triangles(lo: [f64; 3], hi: [f64; 3], v: &mut Vec<[f64; 3]>, f: &mut Vec<Vec<usize>>) {
    let corners: Vec<[f64; 3]> = (0..8)
        .map(|i| std::array::from_fn(|k| if i >> k & 1 == 0 { lo[k] } else { hi[k] }))
        .collect();
    let mesh = dymsum::Polytope::from_points(&corners)
        .expect("a cuboid")
        .to_mesh();
    let base = v.len();
    v.extend(mesh.vertices);
    for face in &mesh.faces {
        for w in face[1..].windows(2) {
            let t = [base + face[0], base + w[0], base + w[1]];
            f.push(t.to_vec());
            f.push(vec![t[2], t[1], t[0]]);
        }
    }
}

/// A built-in scene: a table of two boxes as the robot, a room of
/// double-sided boxes (its walls and some furniture).
pub fn room(states: usize) -> Scene {
    let (mut rv, mut rf) = (Vec::new(), Vec::new());
    cuboid_triangles([-1.0, -0.5, 0.0], [1.0, 0.5, 0.1], &mut rv, &mut rf);
    cuboid_triangles([-0.1, -0.1, -0.8], [0.1, 0.1, 0.0], &mut rv, &mut rf);
    let (mut ev, mut ef) = (Vec::new(), Vec::new());
    cuboid_triangles([-10.0, -10.0, -0.1], [10.0, 10.0, 0.0], &mut ev, &mut ef);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..40 {
        let c = [
            rng.random_range(-9.0..9.0),
            rng.random_range(-9.0..9.0),
            0.0,
        ];
        let s = [
            rng.random_range(0.2..2.0),
            rng.random_range(0.2..2.0),
            rng.random_range(0.5..3.0),
        ];
        cuboid_triangles(
            [c[0], c[1], 0.0],
            [c[0] + s[0], c[1] + s[1], s[2]],
            &mut ev,
            &mut ef,
        );
    }
    Scene {
        name: "room".into(),
        robot: PolygonMesh::new(rv, rf),
        env: PolygonMesh::new(ev, ef),
        states: random_states(
            states,
            DVec3::new(-10.0, -10.0, 0.0),
            DVec3::new(10.0, 10.0, 3.0),
            7,
        ),
    }
}

/// States within `2⁻⁴⁰` of contact: from each free state towards a
/// colliding one (the next in the list, with the free state's rotation),
/// bisected on the translation; both ends kept, up to `n` states.
///
/// # Panics
/// When a state check fails (not expected: finite states).
pub fn near_contact(checker: &SceneChecker, states: &[Pose], n: usize) -> Vec<Pose> {
    let mut out = Vec::new();
    for w in states.windows(2) {
        if out.len() >= n {
            break;
        }
        let (mut free, far) = (w[0], Pose::new(w[0].rotation, w[1].translation));
        if checker.collides_at(free).unwrap() || !checker.collides_at(far).unwrap() {
            continue;
        }
        let mut hit = far;
        for _ in 0..40 {
            let mid = Pose::new(free.rotation, (free.translation + hit.translation) * 0.5);
            if checker.collides_at(mid).unwrap() {
                hit = mid;
            } else {
                free = mid;
            }
        }
        out.push(free);
        out.push(hit);
    }
    out
}

/// dymsum's checker of a scene.
///
/// # Panics
/// When a mesh has no triangle of positive area.
pub fn dymsum_checker(s: &Scene) -> SceneChecker {
    let robot = MeshBody::new(&s.robot).expect("a robot mesh");
    let env = MeshBody::new(&s.env).expect("an environment mesh");
    SceneChecker::new(&robot, &[env]).expect("a checker")
}

/// parry's triangle mesh of a mesh (fan triangles).
///
/// # Panics
/// When parry refuses the mesh.
pub fn parry_mesh(m: &PolygonMesh) -> TriMesh {
    let v = m
        .vertices
        .iter()
        .map(|p| Vector::new(p[0], p[1], p[2]))
        .collect();
    let mut idx = Vec::new();
    for f in &m.faces {
        for w in f[1..].windows(2) {
            idx.push([f[0] as u32, w[0] as u32, w[1] as u32]);
        }
    }
    TriMesh::new(v, idx).expect("parry takes the mesh")
}

/// parry's answer: the robot at `pose` intersects the environment.
///
/// # Panics
/// When parry does not support the pair (it does, TriMesh–TriMesh).
pub fn parry_collides(robot: &TriMesh, env: &TriMesh, pose: Pose) -> bool {
    parry3d_f64::query::intersection_test(
        &parry_pose(pose),
        robot,
        &parry_pose(Pose::IDENTITY),
        env,
    )
    .expect("TriMesh–TriMesh is supported")
    .intersecting
}
