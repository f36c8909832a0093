//! One mesh, one answer, whichever door it comes in by (issue 33 §3): the
//! command line's `query --collision-only` and `motion` take a mesh file
//! exactly as Rust's `Body::from_mesh` (and so Python's `MotionChecker`,
//! python/tests/test_front_doors.py) does: the same cleaning, the same
//! meaning of inside, the same note of what was done. A mesh convex only
//! within rounding is taken exactly unless `--hull` asks for its hull, and
//! then the deviation is reported.

mod common;

use std::path::Path;

use common::{model, run, stderr, stdout, temp_dir};
use dymsum::query::{Body, ConvexUnion, MotionCheck, Validator};
use dymsum::{DVec3, PolygonMesh, Pose, Rotation};
use dymsum_testkit::{box_corners, CUBE_QUADS};

/// A mesh as an OFF file (coordinates written exactly: Rust's shortest
/// round-trip text).
fn mesh_off(dir: &Path, name: &str, m: &PolygonMesh) -> String {
    let mut text = format!("OFF\n{} {} 0\n", m.vertices.len(), m.faces.len());
    for p in &m.vertices {
        text.push_str(&format!("{:?} {:?} {:?}\n", p[0], p[1], p[2]));
    }
    for face in &m.faces {
        let ids: Vec<String> = face.iter().map(|i| i.to_string()).collect();
        text.push_str(&format!("{} {}\n", face.len(), ids.join(" ")));
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// Boxes in one mesh, each closed with its own corners; `outward[i]` false
/// makes box `i` an inward shell (a cavity).
fn boxes(cells: &[([f64; 3], [f64; 3])], outward: &[bool]) -> PolygonMesh {
    let mut m = PolygonMesh::new(Vec::new(), Vec::new());
    for (i, (lo, hi)) in cells.iter().enumerate() {
        let base = m.vertices.len();
        m.vertices.extend(box_corners(*lo, *hi));
        for q in CUBE_QUADS {
            let q: Vec<usize> = q.iter().map(|v| v + base).collect();
            m.faces.push(if outward[i] {
                q
            } else {
                q.into_iter().rev().collect()
            });
        }
    }
    m
}

/// The family: touching solids, a cavity, a T-junction, a fin, an open
/// double-sided box, inward input, and a box with a 1e-6 dent in its top
/// (convex only within rounding).
fn family() -> Vec<(&'static str, PolygonMesh)> {
    let unit = ([0.0; 3], [2.0; 3]);
    let mut t_junction = boxes(&[([0.0; 3], [4.0, 2.0, 2.0])], &[true]);
    t_junction.vertices.push([2.0, 0.0, 2.0]); // on the top front edge
    t_junction.faces.retain(|f| f != &[4, 5, 7, 6]);
    t_junction
        .faces
        .extend([vec![4, 8, 6], vec![8, 7, 6], vec![8, 5, 7]]);
    let mut fin = boxes(&[unit], &[true]);
    fin.vertices.push([1.0, -2.0, 3.0]);
    fin.faces.push(vec![4, 5, 8]);
    let mut open = boxes(&[unit], &[true]);
    open.faces.retain(|f| f != &[4, 5, 7, 6]);
    let backs: Vec<Vec<usize>> = open
        .faces
        .iter()
        .map(|f| f.iter().rev().copied().collect())
        .collect();
    open.faces.extend(backs);
    // The top face fanned about its centre, pushed down by 1e-6.
    let mut dented = boxes(&[unit], &[true]);
    dented.vertices.push([1.0, 1.0, 2.0 - 1e-6]);
    dented.faces.retain(|f| f != &[4, 5, 7, 6]);
    dented
        .faces
        .extend([vec![4, 5, 8], vec![5, 7, 8], vec![7, 6, 8], vec![6, 4, 8]]);
    vec![
        (
            "touching",
            boxes(&[unit, ([2.0, 0.0, 0.0], [4.0, 2.0, 2.0])], &[true, true]),
        ),
        (
            "cavity",
            boxes(
                &[([0.0; 3], [4.0; 3]), ([1.0; 3], [3.0; 3])],
                &[true, false],
            ),
        ),
        ("t_junction", t_junction),
        ("fin", fin),
        ("open", open),
        (
            "inward",
            boxes(&[unit, ([2.0, 0.0, 0.0], [4.0, 2.0, 2.0])], &[false, false]),
        ),
        ("dented", dented),
    ]
}

/// Probe translations: inside, in cavities, against walls, in the dent.
const PROBES: [[f64; 3]; 8] = [
    [1.0, 1.0, 1.0],
    [3.0, 1.0, 1.0],
    [2.0, 2.0, 2.0],
    [0.5, 2.0, 2.0],
    [5.0, 1.0, 1.0],
    [1.0, -1.0, 2.5],
    [1.0, 1.0, 2.0 + 0.125],
    [1.0, 1.0, 2.125 - 0.5e-6],
];

fn pose_arg(t: [f64; 3]) -> String {
    format!("{:?},{:?},{:?},1,0,0,0", t[0], t[1], t[2])
}

fn at(t: [f64; 3]) -> Pose {
    Pose::new(Rotation::IDENTITY, DVec3::from(t))
}

/// The robot: the built-in `box:0.25` (a cube of half-size 0.125).
fn probe_body() -> Body {
    Body::Convex(ConvexUnion::from(model("box:0.25")))
}

#[test]
fn query_and_motion_answer_as_the_library_on_the_family() {
    let dir = temp_dir("front-doors");
    for (name, mesh) in family() {
        let file = mesh_off(&dir, &format!("{name}.off"), &mesh);
        let library = Validator::new(&probe_body(), &[Body::from_mesh(&mesh).unwrap()]).unwrap();
        // States.
        let mut args = vec![
            "query".to_string(),
            "box:0.25".into(),
            file.clone(),
            "--collision-only".into(),
        ];
        for p in PROBES {
            args.push("--pose-xyz-wxyz".into());
            args.push(pose_arg(p));
        }
        let args: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        let o = run(&args);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let cli: Vec<bool> = stdout(&o)
            .lines()
            .map(|l| l.ends_with(": collides"))
            .collect();
        let lib: Vec<bool> = PROBES
            .iter()
            .map(|&p| library.collides_at(at(p)).unwrap())
            .collect();
        assert_eq!(
            cli, lib,
            "{name}: the command line and the library disagree"
        );
        // The note says what the cleaning did, in the library's counts.
        let r = Body::from_mesh(&mesh).unwrap().to_mesh_body().report();
        let note = stderr(&o);
        assert!(
            note.contains(&format!("{} triangles", r.triangles))
                || note.contains("exactly convex shells (their union"),
            "{name}: {note}"
        );
        // Motions: from far outside to each probe.
        for p in PROBES {
            let to = pose_arg(p);
            let from = pose_arg([-3.0, 1.0, 1.0]);
            let o = run(&[
                "motion",
                "box:0.25",
                &file,
                "--from-xyz-wxyz",
                &from,
                "--to-xyz-wxyz",
                &to,
                "--json",
            ]);
            assert!(o.status.success(), "{name} {p:?}: {}", stderr(&o));
            let v: serde_json::Value = serde_json::from_str(stdout(&o).trim()).unwrap();
            let lib = library.check(at([-3.0, 1.0, 1.0]), at(p), 1e-6).unwrap();
            match lib {
                MotionCheck::Free => assert_eq!(v["free"], true, "{name} {p:?}"),
                MotionCheck::Collides { t_contact, .. } => {
                    // Both bracket the first contact to the tolerance (the
                    // command line may take the convex path, or print
                    // fewer digits).
                    assert_eq!(v["free"], false, "{name} {p:?}");
                    let cli = v["t_contact"].as_f64().unwrap();
                    assert!(
                        (cli - t_contact).abs() <= 2e-6,
                        "{name} {p:?}: {cli} {t_contact}"
                    );
                }
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_dent_is_kept_unless_hull_is_asked_for() {
    let dir = temp_dir("front-doors-dent");
    let (_, dented) = family().pop().unwrap();
    let file = mesh_off(&dir, "dented.off", &dented);
    // A probe sitting in the dent: under the hull's top face (z = 2) but
    // above the dented one.
    let probe = pose_arg([1.0, 1.0, 2.125 - 0.5e-6]);
    let query = |extra: &[&str]| {
        let mut args = vec![
            "query",
            "box:0.25",
            &file,
            "--collision-only",
            "--pose-xyz-wxyz",
            &probe,
        ];
        args.extend_from_slice(extra);
        run(&args)
    };
    let exact = query(&[]);
    assert!(exact.status.success(), "{}", stderr(&exact));
    assert!(stdout(&exact).ends_with(": apart\n"), "{}", stdout(&exact));
    assert!(
        stderr(&exact).contains("taken as triangles (1 solid, 14 triangles"),
        "{}",
        stderr(&exact)
    );
    let hull = query(&["--hull"]);
    assert!(hull.status.success(), "{}", stderr(&hull));
    assert!(stdout(&hull).ends_with(": collides\n"), "{}", stdout(&hull));
    let note = stderr(&hull);
    assert!(
        note.contains("replaced by the exact hull of its vertices (--hull)")
            && note.contains("largest deviation 1.000e-6"),
        "{note}"
    );
    // `--hull` and `--strict` contradict each other.
    let both = query(&["--hull", "--strict"]);
    assert_eq!(both.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_obstacle_is_placed_by_its_pose() {
    // The touching boxes given in their own frame, placed by a quarter turn
    // about z and a translation (exact: the same as moving the vertices by
    // hand), in query and motion alike.
    let dir = temp_dir("front-doors-placed");
    let (_, mesh) = family().swap_remove(0);
    let file = mesh_off(&dir, "own_frame.off", &mesh);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let pose = Pose::new(
        Rotation::from_wxyz(h, 0.0, 0.0, h).unwrap(),
        DVec3::new(10.0, 0.0, 0.0),
    );
    let moved = PolygonMesh::new(
        mesh.vertices
            .iter()
            .map(|&v| pose.apply(DVec3::from(v)).to_array())
            .collect(),
        mesh.faces.clone(),
    );
    let by_hand = mesh_off(&dir, "moved.off", &moved);
    let place = format!("10,0,0,{h:?},0,0,{h:?}");
    for p in [
        [9.0, 1.0, 1.0],
        [9.0, 3.0, 1.0],
        [9.0, 5.0, 1.0],
        [11.0, 1.0, 1.0],
    ] {
        let at = pose_arg(p);
        let placed = run(&[
            "query",
            "box:0.25",
            &file,
            "--collision-only",
            "--obstacle-xyz-wxyz",
            &place,
            "--pose-xyz-wxyz",
            &at,
        ]);
        let moved = run(&[
            "query",
            "box:0.25",
            &by_hand,
            "--collision-only",
            "--pose-xyz-wxyz",
            &at,
        ]);
        assert!(placed.status.success(), "{}", stderr(&placed));
        assert_eq!(stdout(&placed), stdout(&moved), "{p:?}");
    }
    let motion = |obstacle: &str, extra: &[&str]| {
        let (from, to) = (pose_arg([9.0, 8.0, 1.0]), pose_arg([9.0, -8.0, 1.0]));
        let mut args = vec![
            "motion",
            "box:0.25",
            obstacle,
            "--from-xyz-wxyz",
            &from,
            "--to-xyz-wxyz",
            &to,
            "--json",
        ];
        args.extend_from_slice(extra);
        stdout(&run(&args))
    };
    let placed = motion(&file, &["--obstacle-xyz-wxyz", &place]);
    assert!(placed.contains("\"free\":false"), "{placed}");
    assert_eq!(placed, motion(&by_hand, &[]));
    std::fs::remove_dir_all(&dir).ok();
}
