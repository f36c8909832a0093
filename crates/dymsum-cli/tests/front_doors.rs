//! One mesh, one answer, whichever door it comes in by (issues 33 §3 and
//! 34): the same mesh files (`tests/fixtures/front_doors`) are taken by
//! Rust's ladder (`Body::from_mesh_with`), by the one loader
//! (`dymsum_io::body`, which reads each file once), by the command line's
//! `query` and `motion`, and by Python's `MotionChecker`
//! (python/tests/test_front_doors.py reads the same files, as paths and as
//! arrays): the same body kind (convex pieces, how many, or triangles),
//! the same answers, the same note of what was done. A mesh convex only
//! within rounding is taken exactly unless `--hull` asks for its hull, and
//! then the deviation is reported.

mod common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use common::{fixture, model, run, stderr, stdout, temp_dir};
use dymsum::body::{BodyOptions, Rung};
use dymsum::query::{Body, ConvexUnion, MotionCheck, Validator};
use dymsum::{DVec3, PolygonMesh, Pose, Rotation};
use dymsum_io::body::{body_from, read_operands_from, Files, LoadOptions, Reader, Taken};
use dymsum_io::formats::FormatError;

/// The family, one file each (`tests/fixtures/front_doors`), with the
/// body each door must take: its convex pieces, or 0 for triangles.
///
/// * `touching.off`: two cubes sharing a face, each closed with its own
///   corners (a solid of two exactly convex shells: their union);
/// * `cavity.off`: a box with an inward box inside (a cavity: triangles);
/// * `t_junction.off`: a box whose top is split at a vertex lying on an
///   edge (the edge split by the cleaning: one exactly convex solid);
/// * `fin.off`: a cube with a triangle sticking out of its top edge;
/// * `open.off`: a cube without its lid, every face double-sided;
/// * `inward.off`: the touching cubes given inward;
/// * `dented.off`: a cube whose top is fanned about its centre, pushed
///   down by 1e-6 (convex only within rounding: triangles, unless `--hull`);
/// * `objects.obj`: two separate cubes as OBJ objects `a` and `b` (convex
///   pieces);
/// * `lidless_objects.obj`: the same, `b` without its lid (no convex
///   piece: the whole file by the ladder, as triangles).
const FAMILY: [(&str, usize); 9] = [
    ("touching.off", 2),
    ("cavity.off", 0),
    ("t_junction.off", 1),
    ("fin.off", 0),
    ("open.off", 0),
    ("inward.off", 0),
    ("dented.off", 0),
    ("objects.obj", 2),
    ("lidless_objects.obj", 0),
];

/// A family file's path and its mesh as read whole.
fn family_file(name: &str) -> (String, PolygonMesh) {
    let path = fixture(&format!("front_doors/{name}"));
    let mesh = dymsum_io::formats::read_mesh(Path::new(&path)).unwrap();
    (path, mesh)
}

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

/// A body's kind: its convex pieces on the convex path, 0 for triangles.
fn kind(body: &Body) -> usize {
    match body {
        Body::Convex(u) => u.pieces().len(),
        Body::Mesh(m) => usize::from(m.as_convex().is_some()),
    }
}

/// Reads the file system and counts the reads per path.
#[derive(Default)]
struct Counting(HashMap<PathBuf, usize>);

impl Reader for Counting {
    fn read_file(&mut self, path: &Path) -> Result<Vec<u8>, FormatError> {
        *self.0.entry(path.to_path_buf()).or_default() += 1;
        Files.read_file(path)
    }
}

#[test]
fn the_loader_reads_each_file_once_and_takes_it_as_the_ladder_does() {
    for (name, pieces) in FAMILY {
        let (path, mesh) = family_file(name);
        let (body, _) = Body::from_mesh_with(&mesh, &BodyOptions::default()).unwrap();
        assert_eq!(kind(&body), pieces, "{name}: the ladder");
        let mut counting = Counting::default();
        let parts = read_operands_from(&path, &mut counting).unwrap();
        let loaded = body_from(&parts, &LoadOptions::default()).unwrap();
        // The convex pieces the subcommands that need them take come from
        // the same reading.
        let _ = dymsum_io::body::convex_pieces(&parts, &LoadOptions::default());
        assert_eq!(kind(&loaded.body), pieces, "{name}: the loader");
        assert_eq!(
            counting.0,
            HashMap::from([(PathBuf::from(&path), 1)]),
            "{name}: each file read once"
        );
    }
}

#[test]
fn query_and_motion_answer_as_the_library_on_the_family() {
    for (name, pieces) in FAMILY {
        let (file, mesh) = family_file(name);
        let (body, _) = Body::from_mesh_with(&mesh, &BodyOptions::default()).unwrap();
        let library = Validator::new(&probe_body(), &[body]).unwrap();
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
        // The note says which rung took the mesh, and what the cleaning
        // did in the library's counts.
        let loaded = dymsum_io::load_body(&file, &LoadOptions::default()).unwrap();
        let note = stderr(&o);
        let expected = match &loaded.taken {
            Taken::Ladder(r) | Taken::ObjectsByLadder { report: r, .. } => match r.rung {
                Rung::Convex => "exactly convex, taken as one convex piece".to_string(),
                Rung::ConvexShells => format!("taken as {pieces} exactly convex shells"),
                Rung::Triangles => format!(
                    "taken as triangles ({}",
                    dymsum_cli::commands::solid::triangle_components(&r.cleaning.unwrap())
                ),
                Rung::Hull => unreachable!("no --hull"),
            },
            Taken::Pieces(n) => {
                assert_eq!(*n, pieces, "{name}");
                assert!(note.is_empty(), "{name}: {note}");
                String::new()
            }
        };
        assert!(note.contains(&expected), "{name}: {note}");
        if let Taken::Ladder(r) | Taken::ObjectsByLadder { report: r, .. } = &loaded.taken {
            if let Some(c) = r.cleaning.filter(|_| r.rung == Rung::Triangles) {
                assert!(
                    note.contains(&format!(", {} triangles", c.triangles)),
                    "{name}: {note}"
                );
            }
        }
        // The body's kind: without `--collision-only`, the distance is
        // given for convex pieces and refused for triangles.
        let far = pose_arg([10.0, 10.0, 10.0]);
        let o = run(&["query", "box:0.25", &file, "--pose-xyz-wxyz", &far]);
        assert_eq!(o.status.success(), pieces > 0, "{name}: {}", stderr(&o));
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
                    // command line prints fewer digits).
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
}

#[test]
fn a_dent_is_kept_unless_hull_is_asked_for() {
    let (file, _) = family_file("dented.off");
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
}

#[test]
fn an_obstacle_is_placed_by_its_pose() {
    // The touching boxes given in their own frame, placed by a quarter turn
    // about z and a translation (exact: the same as moving the vertices by
    // hand), in query and motion alike.
    let dir = temp_dir("front-doors-placed");
    let (file, mesh) = family_file("touching.off");
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
