//! End-to-end tests of `dymsum query` and `dymsum cobst`: output formats,
//! agreement with the library, exit codes (0 ok, 1 bad input, 2 usage).

mod common;

use std::path::Path;

use common::{assert_fails, model, ok, run, stderr, temp_dir};
use dymsum::query::{orientations_about_axis, ConvexPair};
use dymsum::{DVec3, Pose, Rotation};

/// A JSON array of numbers.
fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn query_json_lines_match_the_library() {
    let poses = [
        "0,0,0,1,0,0,0",
        "1.2,0.3,-0.1,0.9,0.1,0.3,0.2",
        "2.5,0,0,1,0,0,0",
        "-0.3,2.2,0.4,0.5,0.5,0.5,0.5",
    ];
    let mut args = vec!["query", "gs2", "box:1,2,0.5", "--json"];
    for p in &poses {
        args.push("--pose-xyz-wxyz");
        args.push(p);
    }
    let text = ok(&args);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), poses.len());
    let (robot, obstacle) = (model("gs2"), model("box:1,2,0.5"));
    let pair = ConvexPair::new(&robot, &obstacle).unwrap();
    for (line, p) in lines.iter().zip(&poses) {
        assert!(
            line.starts_with("{\"pose_xyz_wxyz\":[") && line.contains("],\"collides\":"),
            "key order: {line}"
        );
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
        keys.sort_unstable();
        let mut want_keys = [
            "pose_xyz_wxyz",
            "collides",
            "depth",
            "distance",
            "direction",
            "point_on_robot",
            "point_on_obstacle",
        ];
        want_keys.sort_unstable();
        assert_eq!(keys, want_keys, "{line}");
        assert!(line.contains("],\"point_on_robot\":["), "key order: {line}");
        let n: Vec<f64> = p.split(',').map(|x| x.parse().unwrap()).collect();
        let pose = Pose::new(
            Rotation::from_wxyz(n[3], n[4], n[5], n[6]).unwrap(),
            DVec3::new(n[0], n[1], n[2]),
        );
        let want = pair.query(pose, Pose::IDENTITY).unwrap();
        assert_eq!(
            v["collides"].as_bool().unwrap(),
            want.intersects(),
            "{line}"
        );
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-15 * y.abs().max(1.0);
        assert!(close(v["depth"].as_f64().unwrap(), want.depth()), "{line}");
        assert!(
            close(v["distance"].as_f64().unwrap(), want.distance()),
            "{line}"
        );
        // One meaning in both cases: from the robot (A) towards the
        // obstacle (B), the library's contact normal or separation direction.
        let towards_b = match &want {
            dymsum::query::Proximity::Penetrating(c) => c.normal,
            dymsum::query::Proximity::Separated(s) => s.direction,
        };
        let d: Vec<f64> = numbers(&v["direction"]);
        assert!(
            (DVec3::new(d[0], d[1], d[2]) - towards_b).length() <= 1e-15,
            "{line}"
        );
        // Witness points: the library's, and consistent with the numbers
        // (apart: the obstacle's point is `distance` along `direction` from
        // the robot's; colliding: the robot's point is `depth` along
        // `direction` from the obstacle's).
        let pr = numbers(&v["point_on_robot"]);
        let po = numbers(&v["point_on_obstacle"]);
        let (pr, po) = (
            DVec3::new(pr[0], pr[1], pr[2]),
            DVec3::new(po[0], po[1], po[2]),
        );
        let (wa, wb) = match &want {
            dymsum::query::Proximity::Penetrating(c) => (c.point_on_a, c.point_on_b),
            dymsum::query::Proximity::Separated(s) => (s.point_on_a, s.point_on_b),
        };
        assert!(
            (pr - wa).length() <= 1e-12 && (po - wb).length() <= 1e-12,
            "{line}"
        );
        let dir = DVec3::new(d[0], d[1], d[2]);
        let gap = if want.intersects() {
            pr - po - dir * want.depth()
        } else {
            po - pr - dir * want.distance()
        };
        assert!(gap.length() <= 1e-9, "{line}: witness gap {gap}");
        let pose_back: Vec<f64> = numbers(&v["pose_xyz_wxyz"]);
        for (x, y) in pose_back.iter().zip(&n) {
            assert!(close(*x, *y), "{line}");
        }
    }
    // Both outcomes appear.
    assert!(text.contains("\"collides\":true") && text.contains("\"collides\":false"));
}

#[test]
fn query_direction_points_from_robot_to_obstacle_touching_or_apart() {
    // Just overlapping, and just apart: the same direction, no `-0.0`.
    let text = ok(&[
        "query",
        "box",
        "box",
        "--json",
        "--pose-xyz-wxyz",
        "0.99,0,0,1,0,0,0",
        "--pose-xyz-wxyz",
        "1.01,-0,0,1,0,0,0",
    ]);
    assert!(!text.contains("-0.0"), "{text}");
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines[0]["collides"], true);
    assert_eq!(lines[1]["collides"], false);
    for v in &lines {
        assert_eq!(numbers(&v["direction"]), [-1.0, 0.0, 0.0], "{text}");
    }
    // The human form says the same, and the old flag still works.
    let text = ok(&[
        "query",
        "box",
        "box",
        "--pose",
        "0.99,0,0,1,0,0,0",
        "--pose",
        "1.01,0,0,1,0,0,0",
    ]);
    assert!(!text.contains("-0.0"), "{text}");
    assert_eq!(
        text.matches("direction robot to obstacle (-1.000000, 0.000000, 0.000000)")
            .count(),
        2,
        "{text}"
    );
}

#[test]
fn query_human_output_and_errors() {
    let text = ok(&[
        "query",
        "box",
        "box",
        "--pose",
        "0.5,0,0,1,0,0,0",
        "--pose",
        "3,0,0,1,0,0,0",
    ]);
    assert!(text.contains("collides, depth 0.500000000"), "{text}");
    assert!(text.contains("apart, distance 2.000000000"), "{text}");
    // Usage errors: exit 2.
    for bad in ["1,2,3", "0,0,0,0,0,0,0", "0,0,0,1,0,0,nan"] {
        let o = run(&["query", "box", "box", "--pose", bad]);
        assert_eq!(o.status.code(), Some(2), "{bad}: {}", stderr(&o));
    }
    assert_eq!(run(&["query", "box", "box"]).status.code(), Some(2));
    // Bad input: exit 1, naming the operand.
    let o = run(&["query", "no_such.off", "box", "--pose", "0,0,0,1,0,0,0"]);
    assert_fails(&o, 1, "ROBOT");
}

#[test]
fn query_unions_of_pieces() {
    // Robot: two unit boxes (one at the origin, one translated is not
    // expressible by name, so use two different boxes centred alike).
    let text = ok(&[
        "query",
        "box:4,0.2,0.2+box:0.2,0.2,4",
        "box:0.5",
        "--pose",
        "0,1,0,1,0,0,0",
        "--pose",
        "0,0,0,1,0,0,0",
        "--json",
    ]);
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines[0]["collides"], false);
    assert!(
        (lines[0]["distance"].as_f64().unwrap() - 0.65).abs() < 1e-12,
        "{text}"
    );
    assert_eq!(lines[1]["collides"], true);
    // The depth of the cross against the cube: out along ±y, 0.25 + 0.1,
    // from the merged C-obstacle mesh (no witness points).
    let depth = lines[1]["depth"].as_f64().unwrap();
    assert!((depth - 0.35).abs() < 1e-12, "{text}");
    let dir = numbers(&lines[1]["direction"]);
    assert!((dir[1].abs() - 1.0).abs() < 1e-12, "{text}");
    assert!(lines[1]["point_on_robot"].is_null(), "{text}");
}

#[test]
fn cobst_axis_writes_slices_and_index() {
    let dir = temp_dir("axis");
    let out = dir.join("slices");
    ok(&[
        "cobst",
        "gs1",
        "box:2,1,1",
        "--axis",
        "0,0,1",
        "--slices",
        "12",
        "--out",
        out.to_str().unwrap(),
    ]);
    let index: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("index.json")).unwrap()).unwrap();
    let entries = index.as_array().unwrap();
    assert_eq!(entries.len(), 12);
    let turns = orientations_about_axis(DVec3::Z, 12).unwrap();
    let (robot, obstacle) = (model("gs1"), model("box:2,1,1"));
    let slices = dymsum::query::cobstacle_slices(&robot, &obstacle, &turns).unwrap();
    for (k, e) in entries.iter().enumerate() {
        assert_eq!(e["slice"].as_u64().unwrap() as usize, k);
        let file = format!("slice_{k:05}.off");
        assert_eq!(e["file"].as_str().unwrap(), file);
        let q: Vec<f64> = numbers(&e["orientation_wxyz"]);
        // serde_json parses floats to within an ulp (no float_roundtrip).
        for (x, y) in q.iter().zip(turns[k].wxyz()) {
            assert!((x - y).abs() <= 1e-15, "{q:?}");
        }
        let mesh = dymsum_io::formats::read_mesh(&out.join(&file)).unwrap();
        assert_eq!(e["faces"].as_u64().unwrap() as usize, mesh.faces.len());
        assert_eq!(mesh.faces.len(), slices[k].faces.len());
    }
    dymsum_testkit::files::remove_dir(&dir);
}

#[test]
fn cobst_orientation_file_and_its_errors() {
    let dir = temp_dir("file");
    let good = dir.join("o.txt");
    std::fs::write(
        &good,
        "# orientations\n1,0,0,0\n\n0.7071 0 0 0.7071  # quarter turn\n",
    )
    .unwrap();
    let out = dir.join("s");
    // `dymsum cobst box gs1 ARGS --out OUT`.
    let cobst = |args: &[&str]| {
        let mut all = vec!["cobst", "box", "gs1"];
        all.extend_from_slice(args);
        all.extend(["--out", out.to_str().unwrap()]);
        run(&all)
    };
    let good = good.to_str().unwrap();
    let o = cobst(&["--orientations-wxyz", good]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(Path::new(&out.join("slice_00001.off")).is_file());
    assert!(!Path::new(&out.join("slice_00002.off")).exists());
    let bad = dir.join("bad.txt");
    std::fs::write(&bad, "1,0,0,0\n1,0,0\n").unwrap();
    let o = cobst(&["--orientations-wxyz", bad.to_str().unwrap()]);
    assert_fails(&o, 1, "line 2");
    // Neither source, or both: usage errors.
    let o = cobst(&[]);
    assert_eq!(o.status.code(), Some(2));
    let o = cobst(&[
        "--axis",
        "0,0,1",
        "--slices",
        "3",
        "--orientations-wxyz",
        good,
    ]);
    assert_eq!(o.status.code(), Some(2));
    let o = cobst(&["--axis", "0,0,0", "--slices", "3"]);
    assert_eq!(o.status.code(), Some(2));
    dymsum_testkit::files::remove_dir(&dir);
}

/// `dymsum motion`: the JSON answer equals the library's check, a contact
/// bracket is within the tolerance and really in contact, free motions are
/// free, and bad input is an error naming it.
#[test]
fn motion_answers_match_the_library() {
    use dymsum::query::{ConvexUnion, Motion, MotionCheck, MotionChecker};
    let (robot, obstacle) = (model("box:4,0.1,0.1"), model("box:0.2,0.2,2"));
    let checker =
        MotionChecker::new(&ConvexUnion::from(robot), &[ConvexUnion::from(obstacle)]).unwrap();
    let pose = |x: f64, y: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, y, 0.0));
    for (from, to, a, b) in [
        (
            "0,1,0,1,0,0,0",
            "0,-1,0,1,0,0,0",
            pose(0.0, 1.0),
            pose(0.0, -1.0),
        ),
        (
            "0,3,0,1,0,0,0",
            "3,3,0,1,0,0,0",
            pose(0.0, 3.0),
            pose(3.0, 3.0),
        ),
    ] {
        let text = ok(&[
            "motion",
            "box:4,0.1,0.1",
            "box:0.2,0.2,2",
            "--from-xyz-wxyz",
            from,
            "--to-xyz-wxyz",
            to,
            "--tolerance",
            "1e-6",
            "--json",
        ]);
        let v: serde_json::Value = serde_json::from_str(text.trim()).unwrap();
        match checker.check(a, b, 1e-6).unwrap() {
            MotionCheck::Free => {
                assert_eq!(v["free"], true, "{text}");
                assert!(v["t_contact"].is_null() && v["contact_pose_xyz_wxyz"].is_null());
            }
            MotionCheck::Collides { t_safe, t_contact } => {
                assert_eq!(v["free"], false, "{text}");
                assert_eq!(v["t_safe"].as_f64(), t_safe);
                assert_eq!(v["t_contact"].as_f64(), Some(t_contact));
                assert!(t_contact - t_safe.unwrap() <= 1e-6);
                assert!(checker
                    .collides_at(Motion::new(a, b).at(t_contact))
                    .unwrap());
                let p = numbers(&v["contact_pose_xyz_wxyz"]);
                assert!((p[1] - 0.15).abs() < 1e-6, "{p:?}");
            }
        }
    }
    let o = run(&[
        "motion",
        "box",
        "box",
        "--from-xyz-wxyz",
        "3,0,0,1,0,0,0",
        "--to-xyz-wxyz",
        "4,0,0,1,0,0,0",
        "--tolerance",
        "0",
    ]);
    assert_fails(&o, 1, "tolerance");
    let o = run(&[
        "motion",
        "box",
        "box",
        "--from-xyz-wxyz",
        "3,0,0,1,0,0",
        "--to-xyz-wxyz",
        "4,0,0,1,0,0,0",
    ]);
    assert_fails(&o, 2, "7 comma-separated");
    // Starting in contact: no certified time, contact at t = 0.
    let text = ok(&[
        "motion",
        "box",
        "box",
        "--from-xyz-wxyz",
        "0.5,0,0,1,0,0,0",
        "--to-xyz-wxyz",
        "4,0,0,1,0,0,0",
    ]);
    assert!(text.contains("free up to t = none"), "{text}");
    assert!(!stderr(&o).is_empty());
}

/// `count + 1` evenly spaced values from `lo` to `hi`.
fn dense(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    (0..=count)
        .map(|j| lo + (hi - lo) * j as f64 / count as f64)
        .collect()
}

/// `x` strictly outside a convex mesh (an exact `orient` per face).
fn outside(mesh: &dymsum::PolygonMesh, x: DVec3) -> bool {
    mesh.faces.iter().any(|f| {
        let p = |i: usize| DVec3::from(mesh.vertices[f[i]]);
        dymsum::kernel::predicates::orient(p(0), p(1), p(2), x) == dymsum::kernel::Sign::Positive
    })
}

/// `a` and `b` equal within an ulp (serde_json parses without
/// `float_roundtrip`).
fn near(a: f64, b: f64) -> bool {
    (a - b).abs() <= 2.0 * f64::EPSILON * a.abs().max(b.abs())
}

/// The index entry's keys, sorted.
fn keys(e: &serde_json::Value) -> Vec<String> {
    let mut k: Vec<String> = e.as_object().unwrap().keys().cloned().collect();
    k.sort_unstable();
    k
}

#[test]
fn cobst_certified_meshes_hold_every_slice_between_their_angles() {
    let dir = temp_dir("certified_off");
    let out = dir.join("slabs");
    let n = 8;
    let text = ok(&[
        "cobst",
        "gs1",
        "box:2,1,1",
        "--axis",
        "0,0,1",
        "--slices",
        "8",
        "--certified",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        text.starts_with("Certified C-obstacle slabs of gs1 among box:2,1,1: 8 slabs"),
        "{text}"
    );
    let index: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("index.json")).unwrap()).unwrap();
    let entries = index.as_array().unwrap();
    assert_eq!(entries.len(), n);
    let names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(names.len(), n + 1, "{names:?}");
    let (robot, obstacle) = (model("gs1"), model("box:2,1,1"));
    let cobst = dymsum::CObstacle::new(&robot, &obstacle).unwrap();
    let angles = dymsum::query::full_turn_angles(n);
    let turns = dymsum::query::rotations_about_axis(DVec3::Z, &angles).unwrap();
    let slabs = cobst.certified_slabs(&turns).unwrap();
    let mut poking_out = 0;
    for (k, e) in entries.iter().enumerate() {
        let file = format!("slab_{k:05}.off");
        assert_eq!(
            keys(e),
            [
                "faces",
                "file",
                "from_angle",
                "from_wxyz",
                "margin",
                "planes",
                "slab",
                "to_angle",
                "to_wxyz"
            ]
        );
        assert_eq!(e["slab"].as_u64().unwrap() as usize, k);
        assert_eq!(e["file"].as_str().unwrap(), file);
        assert!(near(e["from_angle"].as_f64().unwrap(), angles[k]), "{e}");
        assert!(near(e["to_angle"].as_f64().unwrap(), angles[k + 1]), "{e}");
        for (x, y) in numbers(&e["from_wxyz"]).iter().zip(turns[k].wxyz()) {
            assert!((x - y).abs() <= 1e-15, "{e}");
        }
        for (x, y) in numbers(&e["to_wxyz"]).iter().zip(turns[k + 1].wxyz()) {
            assert!((x - y).abs() <= 1e-15, "{e}");
        }
        assert_eq!(e["planes"].as_u64().unwrap() as usize, slabs[k].len());
        assert!(
            near(e["margin"].as_f64().unwrap(), slabs[k].margin()),
            "{e}"
        );
        // The mesh as written (OFF: shortest round-trip decimals), checked
        // exactly, holds every vertex of the slices at 13 angles across its
        // interval; between the ends, some poke out of the end slices' hull.
        let mesh = dymsum_io::formats::read_mesh(&out.join(&file)).unwrap();
        assert_eq!(dymsum::sum::validate::check_convex_mesh(&mesh), Ok(()));
        assert_eq!(e["faces"].as_u64().unwrap() as usize, mesh.faces.len());
        let samples =
            dymsum::query::rotations_about_axis(DVec3::Z, &dense(angles[k], angles[k + 1], 12))
                .unwrap();
        for (j, slice) in cobst.slices(&samples).enumerate() {
            for v in &slice.unwrap().vertices {
                let x = DVec3::from(*v);
                assert!(
                    !outside(&mesh, x),
                    "slab {k}, sample {j}: {x:?} outside the mesh"
                );
                assert!(slabs[k].contains(x), "slab {k}, sample {j}: {x:?} outside");
                let hull = slabs[k].hull();
                poking_out += usize::from(hull.faces().any(|f| {
                    let p = |i: usize| hull.vertex(f[i] as usize);
                    dymsum::kernel::predicates::orient(p(0), p(1), p(2), x)
                        == dymsum::kernel::Sign::Positive
                }));
            }
        }
    }
    assert!(
        poking_out > 100,
        "only {poking_out} slice vertices outside the hull of the end slices"
    );
    dymsum_testkit::files::remove_dir(&dir);
}

#[test]
fn cobst_certified_halfspaces_hold_every_slice_on_the_shortest_paths() {
    let dir = temp_dir("certified_json");
    let out = dir.join("slabs");
    // Identity, a turn by 1 rad about (1, 1, 0), then 0.8 rad more about z.
    let axis = DVec3::new(1.0, 1.0, 0.0);
    let first = Rotation::from_axis_angle(axis, 1.0).unwrap();
    let second = first.then(&Rotation::from_axis_angle(DVec3::Z, 0.8).unwrap());
    let turns = [Rotation::IDENTITY, first, second];
    let file = dir.join("turns.txt");
    let lines: Vec<String> = turns
        .iter()
        .map(|r| {
            let [w, x, y, z] = r.wxyz();
            format!("{w:?},{x:?},{y:?},{z:?}\n")
        })
        .collect();
    std::fs::write(&file, lines.concat()).unwrap();
    ok(&[
        "cobst",
        "box:2,0.5,0.5",
        "gs2",
        "--orientations-wxyz",
        file.to_str().unwrap(),
        "--certified",
        "--format",
        "halfspaces",
        "--out",
        out.to_str().unwrap(),
    ]);
    let index: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("index.json")).unwrap()).unwrap();
    let entries = index.as_array().unwrap();
    assert_eq!(entries.len(), 2);
    let (robot, obstacle) = (model("box:2,0.5,0.5"), model("gs2"));
    let cobst = dymsum::CObstacle::new(&robot, &obstacle).unwrap();
    let slabs = cobst.certified_slabs(&turns).unwrap();
    // The rotations on each shortest path, as dymsum computes them.
    let paths: [Vec<Rotation>; 2] = [
        dymsum::query::rotations_about_axis(axis, &dense(0.0, 1.0, 16)).unwrap(),
        dense(0.0, 0.8, 16)
            .iter()
            .map(|&t| first.then(&Rotation::from_axis_angle(DVec3::Z, t).unwrap()))
            .collect(),
    ];
    for (k, e) in entries.iter().enumerate() {
        assert_eq!(
            keys(e),
            ["file", "from_wxyz", "margin", "planes", "slab", "to_wxyz"]
        );
        let name = format!("slab_{k:05}.json");
        assert_eq!(e["file"].as_str().unwrap(), name);
        let h: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join(&name)).unwrap()).unwrap();
        assert_eq!(keys(&h), ["normals", "offsets"]);
        let normals: Vec<DVec3> = h["normals"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| {
                let n = numbers(n);
                assert_eq!(n.len(), 3);
                DVec3::new(n[0], n[1], n[2])
            })
            .collect();
        let offsets = numbers(&h["offsets"]);
        assert_eq!(normals.len(), offsets.len());
        assert_eq!(normals.len(), e["planes"].as_u64().unwrap() as usize);
        assert_eq!(normals.len(), slabs[k].len());
        for (i, n) in normals.iter().enumerate() {
            assert!((n.length() - 1.0).abs() < 1e-12, "{n:?}");
            let lib = slabs[k].normals()[i];
            assert!(
                (0..3).all(|c| near(n[c], lib[c])),
                "normal {i}: {n:?} != {lib:?}"
            );
            assert!(near(offsets[i], slabs[k].offsets()[i]), "offset {i}");
        }
        // Every vertex of every sampled slice: inside the library's slab
        // (exactly), and inside the half-spaces as written, in floats with a
        // margin far below the sagitta (the test fails without it).
        let mut deepest = f64::INFINITY;
        for (j, slice) in cobst.slices(&paths[k]).enumerate() {
            for v in &slice.unwrap().vertices {
                let x = DVec3::from(*v);
                assert!(slabs[k].contains(x), "slab {k}, sample {j}: {x:?} outside");
                for (n, d) in normals.iter().zip(&offsets) {
                    deepest = deepest.min(d - n.dot(x));
                    assert!(n.dot(x) <= d + 1e-12, "slab {k}, sample {j}: {x:?}");
                }
            }
        }
        assert!(deepest < slabs[k].margin(), "slab {k}: {deepest} {e}");
    }
    dymsum_testkit::files::remove_dir(&dir);
}

#[test]
fn cobst_certified_unions_and_refusals() {
    let dir = temp_dir("certified_union");
    let out = dir.join("slabs");
    ok(&[
        "cobst",
        "box:4,0.2,0.2+box:0.2,0.2,4",
        "box:0.5",
        "--axis",
        "1,0,0",
        "--slices",
        "3",
        "--certified",
        "--format",
        "halfspaces",
        "--out",
        out.to_str().unwrap(),
    ]);
    let index: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("index.json")).unwrap()).unwrap();
    for (k, e) in index.as_array().unwrap().iter().enumerate() {
        let files: Vec<&str> = e["files"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f.as_str().unwrap())
            .collect();
        assert_eq!(
            files,
            [
                format!("slab_{k:05}_r0_o0.json"),
                format!("slab_{k:05}_r1_o0.json")
            ]
        );
        assert!(e.get("file").is_none(), "{e}");
        let mut planes = 0;
        for f in &files {
            let h: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(out.join(f)).unwrap()).unwrap();
            planes += h["offsets"].as_array().unwrap().len();
        }
        assert_eq!(e["planes"].as_u64().unwrap() as usize, planes);
    }
    // --force clears the slabs, and only them.
    std::fs::write(out.join("notes.txt"), "keep").unwrap();
    let o = run(&[
        "cobst",
        "box",
        "gs1",
        "--axis",
        "0,0,1",
        "--slices",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_fails(&o, 1, "slab_* files");
    std::fs::remove_file(out.join("notes.txt")).unwrap();
    ok(&[
        "cobst",
        "box",
        "gs1",
        "--axis",
        "0,0,1",
        "--slices",
        "2",
        "--out",
        out.to_str().unwrap(),
        "--force",
    ]);
    assert!(!out.join("slab_00000_r0_o0.json").exists());
    assert!(out.join("slice_00001.off").is_file());
    // `cobst box gs1 ARGS --out FRESH`.
    let fresh = dir.join("fresh");
    let cobst = |args: &[&str]| {
        let mut all = vec!["cobst", "box", "gs1"];
        all.extend_from_slice(args);
        all.extend(["--out", fresh.to_str().unwrap()]);
        run(&all)
    };
    // --format halfspaces without --certified: one JSON of planes per
    // slice (issue 22; tests/cobst_map_cli.rs checks their values).
    let o = cobst(&["--axis", "0,0,1", "--slices", "3", "--format", "halfspaces"]);
    assert!(o.status.success());
    assert!(fresh.join("slice_00002.json").is_file());
    std::fs::remove_dir_all(&fresh).unwrap();
    let o = cobst(&[
        "--axis",
        "0,0,1",
        "--slices",
        "3",
        "--certified",
        "--format",
        "obj",
    ]);
    assert_fails(&o, 2, "--format");
    // A slab covers at most a half turn; it lies between two orientations.
    let o = cobst(&["--axis", "0,0,1", "--slices", "1", "--certified"]);
    assert_fails(&o, 1, "more than π");
    let one = dir.join("one.txt");
    std::fs::write(&one, "1,0,0,0\n").unwrap();
    let o = cobst(&["--orientations-wxyz", one.to_str().unwrap(), "--certified"]);
    assert_fails(&o, 1, "at least 2");
    assert!(!fresh.join("index.json").exists());
    dymsum_testkit::files::remove_dir(&dir);
}

/// `n` rotations within angle `radius` of `centre`: `E·centre` with `E` a
/// turn about a random axis by a random angle in `[0, radius]`, every third
/// by `radius` itself (the cell's rim).
fn cell_samples(
    centre: Rotation,
    radius: f64,
    n: usize,
    r: &mut rand_chacha::ChaCha8Rng,
) -> Vec<Rotation> {
    use rand::Rng;
    (0..n)
        .map(|i| {
            let axis = loop {
                let v = DVec3::new(
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                );
                if (0.1..=1.0).contains(&v.length()) {
                    break v;
                }
            };
            let angle = if i % 3 == 0 {
                radius
            } else {
                r.random_range(0.0..=radius)
            };
            let rot = Rotation::from_axis_angle(axis, angle)
                .unwrap()
                .then(&centre);
            assert!(centre.angle_to(&rot) <= radius + 1e-12);
            rot
        })
        .collect()
}

#[test]
fn cobst_certified_cells_hold_every_slice_within_the_radius() {
    use rand::SeedableRng;
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(20);
    let dir = temp_dir("certified_cells");
    let (robot, obstacle) = (model("box:2,0.5,0.5"), model("gs2"));
    let cobst = dymsum::CObstacle::new(&robot, &obstacle).unwrap();
    let reach = robot
        .vertices()
        .iter()
        .map(|v| v.length())
        .fold(0.0, f64::max);
    // Three centres about different axes, written as w,x,y,z lines.
    let centres = [
        Rotation::IDENTITY,
        Rotation::from_axis_angle(DVec3::new(1.0, 1.0, 0.0), 1.0).unwrap(),
        Rotation::from_axis_angle(DVec3::new(-0.3, 0.2, 1.0), 2.5).unwrap(),
    ];
    let file = dir.join("centres.txt");
    let lines: Vec<String> = centres
        .iter()
        .map(|c| {
            let [w, x, y, z] = c.wxyz();
            format!("{w:?},{x:?},{y:?},{z:?}\n")
        })
        .collect();
    std::fs::write(&file, lines.concat()).unwrap();
    let rho = 0.2;
    for format in ["off", "halfspaces"] {
        let out = dir.join(format);
        let text = ok(&[
            "cobst",
            "box:2,0.5,0.5",
            "gs2",
            "--orientations-wxyz",
            file.to_str().unwrap(),
            "--certified",
            "--cell-radius",
            "0.2",
            "--format",
            format,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(
            text.starts_with(
                "Certified C-obstacle slabs of box:2,0.5,0.5 among gs2: 3 slabs for cells of \
                 radius 0.2 rad (1 piece pair)"
            ),
            "{text}"
        );
        let index: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("index.json")).unwrap())
                .unwrap();
        let entries = index.as_array().unwrap();
        assert_eq!(entries.len(), centres.len());
        let slabs = cobst.certified_slabs_in_cells(&centres, rho).unwrap();
        let (mut beyond_centre_slice, mut deepest) = (0usize, f64::NEG_INFINITY);
        for (k, e) in entries.iter().enumerate() {
            let mut want = vec!["centre_wxyz", "file", "margin", "planes", "radius", "slab"];
            if format == "off" {
                want.push("faces");
                want.sort_unstable();
            }
            assert_eq!(keys(e), want, "{e}");
            assert_eq!(e["slab"].as_u64().unwrap() as usize, k);
            assert_eq!(e["radius"].as_f64().unwrap(), rho);
            for (x, y) in numbers(&e["centre_wxyz"]).iter().zip(centres[k].wxyz()) {
                assert!((x - y).abs() <= 1e-15, "{e}");
            }
            let slab = &slabs[k];
            assert_eq!(e["planes"].as_u64().unwrap() as usize, slab.len());
            assert!(near(e["margin"].as_f64().unwrap(), slab.margin()), "{e}");
            // The margin is r·ρ plus rounding terms far below it.
            assert!(slab.margin() >= reach * rho && slab.margin() <= reach * rho * (1.0 + 1e-9));
            let name = e["file"].as_str().unwrap();
            let ext = if format == "off" { "off" } else { "json" };
            assert_eq!(name, format!("slab_{k:05}.{ext}"));
            // The file as written: the mesh, or the half-spaces (the
            // library's, within the JSON parser's last bit).
            let (mesh, planes) = if format == "off" {
                let mesh = dymsum_io::formats::read_mesh(&out.join(name)).unwrap();
                assert_eq!(dymsum::sum::validate::check_convex_mesh(&mesh), Ok(()));
                assert_eq!(e["faces"].as_u64().unwrap() as usize, mesh.faces.len());
                (Some(mesh), Vec::new())
            } else {
                let h: serde_json::Value =
                    serde_json::from_str(&std::fs::read_to_string(out.join(name)).unwrap())
                        .unwrap();
                let normals = h["normals"].as_array().unwrap();
                let offsets = numbers(&h["offsets"]);
                assert_eq!(normals.len(), slab.len());
                let planes: Vec<(DVec3, f64)> = normals
                    .iter()
                    .zip(offsets)
                    .map(|(n, d)| {
                        let n = numbers(n);
                        (DVec3::new(n[0], n[1], n[2]), d)
                    })
                    .collect();
                for (i, (n, d)) in planes.iter().enumerate() {
                    let lib = slab.normals()[i];
                    assert!((0..3).all(|c| near(n[c], lib[c])), "normal {i}");
                    assert!(near(*d, slab.offsets()[i]), "offset {i}");
                }
                (None, planes)
            };
            // Every vertex of every slice at random rotations in the cell:
            // inside the slab exactly, inside the mesh as written exactly,
            // inside the half-spaces as written (floats, 1e-12 far below
            // r·ρ ≈ 0.21).
            let samples = cell_samples(centres[k], rho, 24, &mut r);
            let hull = slab.hull();
            for (j, slice) in cobst.slices(&samples).enumerate() {
                for v in &slice.unwrap().vertices {
                    let x = DVec3::from(*v);
                    assert!(slab.contains(x), "slab {k}, sample {j}: {x:?} outside");
                    if let Some(m) = &mesh {
                        assert!(
                            !outside(m, x),
                            "slab {k}, sample {j}: {x:?} outside the mesh"
                        );
                    }
                    for (n, d) in &planes {
                        assert!(n.dot(x) <= d + 1e-12, "slab {k}, sample {j}: {x:?}");
                        // How far into the r·ρ margin the slice reaches.
                        deepest = deepest.max(n.dot(x) - (d - slab.margin()));
                    }
                    // Without the r·ρ term the slab would be the centre
                    // slice's hull: count the vertices outside it.
                    beyond_centre_slice += usize::from(hull.faces().any(|f| {
                        let p = |i: usize| hull.vertex(f[i] as usize);
                        dymsum::kernel::predicates::orient(p(0), p(1), p(2), x)
                            == dymsum::kernel::Sign::Positive
                    }));
                }
            }
        }
        assert!(
            beyond_centre_slice > 1000,
            "{format}: only {beyond_centre_slice} sampled slice vertices outside the centre slices"
        );
        if format == "halfspaces" {
            // Sampled slices reach well into the margin (about 93% of it):
            // planes pushed out by half of r·ρ would not hold them.
            assert!(deepest > 0.5 * reach * rho, "{deepest}");
        }
    }
    dymsum_testkit::files::remove_dir(&dir);
}

#[test]
fn cobst_certified_cells_about_an_axis_and_refusals() {
    let dir = temp_dir("certified_cells_axis");
    let out = dir.join("slabs");
    ok(&[
        "cobst",
        "gs1",
        "box:2,1,1",
        "--axis",
        "0,0,1",
        "--slices",
        "6",
        "--certified",
        "--cell-radius",
        "0.5",
        "--format",
        "halfspaces",
        "--out",
        out.to_str().unwrap(),
    ]);
    let index: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("index.json")).unwrap()).unwrap();
    let entries = index.as_array().unwrap();
    assert_eq!(entries.len(), 6);
    let (robot, obstacle) = (model("gs1"), model("box:2,1,1"));
    let cobst = dymsum::CObstacle::new(&robot, &obstacle).unwrap();
    let centres = orientations_about_axis(DVec3::Z, 6).unwrap();
    let slabs = cobst.certified_slabs_in_cells(&centres, 0.5).unwrap();
    for (k, e) in entries.iter().enumerate() {
        assert_eq!(
            keys(e),
            [
                "angle",
                "centre_wxyz",
                "file",
                "margin",
                "planes",
                "radius",
                "slab"
            ]
        );
        let angle = std::f64::consts::TAU * k as f64 / 6.0;
        assert!(near(e["angle"].as_f64().unwrap(), angle), "{e}");
        for (x, y) in numbers(&e["centre_wxyz"]).iter().zip(centres[k].wxyz()) {
            assert!((x - y).abs() <= 1e-15, "{e}");
        }
        assert_eq!(e["planes"].as_u64().unwrap() as usize, slabs[k].len());
        // The turns about z by angle ± 0.5 lie in the cell.
        let turns =
            dymsum::query::rotations_about_axis(DVec3::Z, &dense(angle - 0.5, angle + 0.5, 10))
                .unwrap();
        for slice in cobst.slices(&turns) {
            assert!(slice
                .unwrap()
                .vertices
                .iter()
                .all(|&v| slabs[k].contains(DVec3::from(v))));
        }
    }
    // Bad radii: negative, NaN, π or more, not a number: usage errors
    // that name the flag and the range.
    let fresh = dir.join("fresh");
    for bad in ["-0.1", "NaN", "3.141592653589793", "4", "inf", "abc"] {
        let o = run(&[
            "cobst",
            "box",
            "gs1",
            "--axis",
            "0,0,1",
            "--slices",
            "4",
            "--certified",
            "--cell-radius",
            bad,
            "--out",
            fresh.to_str().unwrap(),
        ]);
        assert_fails(&o, 2, "--cell-radius");
        let err = stderr(&o);
        assert!(
            err.contains("0 ≤ RHO < π") || err.contains("not a number"),
            "{bad}: {err}"
        );
    }
    // --cell-radius needs --certified.
    let o = run(&[
        "cobst",
        "box",
        "gs1",
        "--axis",
        "0,0,1",
        "--slices",
        "4",
        "--cell-radius",
        "0.1",
        "--out",
        fresh.to_str().unwrap(),
    ]);
    assert_fails(&o, 2, "--certified");
    assert!(!fresh.exists());
    dymsum_testkit::files::remove_dir(&dir);
}

/// An axis-aligned box as an OFF file.
fn box_off(dir: &Path, name: &str, lo: [f64; 3], hi: [f64; 3]) -> String {
    let mut text = String::from("OFF\n8 6 0\n");
    for i in 0..8 {
        let pick = |k: usize| if i >> k & 1 == 0 { lo[k] } else { hi[k] };
        text.push_str(&format!("{} {} {}\n", pick(0), pick(1), pick(2)));
    }
    for f in [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ] {
        text.push_str(&format!("4 {} {} {} {}\n", f[0], f[1], f[2], f[3]));
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// Issue 26 §1: `--to-xyz-wxyz 0,0,0,-8.598507252118853e-15,0,0,1` (a turn
/// by 180° + 1e-12° about z) turns the short way, clockwise, through a
/// block only that arc sweeps; the mirrored end and the exact half turns
/// (`w = ±0`, the second quaternion kept as given) turn the other way.
/// Also the budget flag and the smallest tolerance.
#[test]
fn regression_motion_half_turn_takes_the_arc_of_the_quaternions_as_given() {
    let dir = temp_dir("half-turn");
    let bar = box_off(&dir, "bar.off", [0.0, -0.05, -0.05], [2.0, 0.05, 0.05]);
    let block = box_off(&dir, "block.off", [-0.1, -1.6, -1.0], [0.1, -1.4, 1.0]);
    let free = |to: &str| -> bool {
        let text = ok(&[
            "motion",
            &bar,
            &block,
            "--from-xyz-wxyz",
            "0,0,0,1,0,0,0",
            "--to-xyz-wxyz",
            to,
            "--json",
        ]);
        let v: serde_json::Value = serde_json::from_str(text.trim()).unwrap();
        v["free"].as_bool().unwrap()
    };
    assert!(!free("0,0,0,-8.598507252118853e-15,0,0,1"));
    assert!(free("0,0,0,8.598507252118853e-15,0,0,1"));
    assert!(!free("0,0,0,-1e-300,0,0,1"));
    assert!(free("0,0,0,1e-300,0,0,1"));
    assert!(free("0,0,0,0,0,0,1") && free("0,0,0,-0,0,0,1"));
    assert!(!free("0,0,0,0,0,0,-1") && !free("0,0,0,-0,0,0,-1"));
    // A budget of one interval cannot decide the sweeping motion.
    let o = run(&[
        "motion",
        &bar,
        &block,
        "--from-xyz-wxyz",
        "0,0,0,1,0,0,0",
        "--to-xyz-wxyz",
        "0,0,0,-1e-300,0,0,1",
        "--budget",
        "1",
    ]);
    assert_fails(&o, 1, "budget of 1 intervals");
    let o = run(&[
        "motion",
        &bar,
        &block,
        "--from-xyz-wxyz",
        "0,0,0,1,0,0,0",
        "--to-xyz-wxyz",
        "0,0,0,1,0,0,0",
        "--budget",
        "0",
    ]);
    assert_fails(&o, 2, "budget");
    let o = run(&[
        "motion",
        &bar,
        &block,
        "--from-xyz-wxyz",
        "0,0,0,1,0,0,0",
        "--to-xyz-wxyz",
        "3,0,0,1,0,0,0",
        "--tolerance",
        "1e-300",
    ]);
    assert_fails(&o, 1, "3.637978807091713e-12");
    std::fs::remove_dir_all(&dir).ok();
}

// Issue 28, "Bodies as they come": `query --collision-only` and `motion`
// take a mesh file of any topology (open, double-sided, non-manifold,
// non-convex, unwelded) as triangles, say on standard error what the
// cleaning did, and `query` without `--collision-only` refuses it.

/// A polygon mesh as an OFF file.
fn mesh_off(dir: &Path, name: &str, v: &[[f64; 3]], f: &[Vec<usize>]) -> String {
    let mut text = format!("OFF\n{} {} 0\n", v.len(), f.len());
    for p in v {
        text.push_str(&format!("{} {} {}\n", p[0], p[1], p[2]));
    }
    for face in f {
        let ids: Vec<String> = face.iter().map(|i| i.to_string()).collect();
        text.push_str(&format!("{} {}\n", face.len(), ids.join(" ")));
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// A box 4 wide (x and y in [-2, 2]) and 2 high (z in [0, 2]): its corners
/// and its faces, outward, the floor first and the lid last.
fn box_4x4x2() -> (Vec<[f64; 3]>, Vec<Vec<usize>>) {
    let v = vec![
        [-2.0, -2.0, 0.0],
        [2.0, -2.0, 0.0],
        [2.0, 2.0, 0.0],
        [-2.0, 2.0, 0.0],
        [-2.0, -2.0, 2.0],
        [2.0, -2.0, 2.0],
        [2.0, 2.0, 2.0],
        [-2.0, 2.0, 2.0],
    ];
    let f = [
        [0, 3, 2, 1],
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
        [4, 5, 6, 7],
    ];
    (v, f.iter().map(|q| q.to_vec()).collect())
}

/// Every face followed by its back (as double-sided exports write them).
fn double_sided(faces: &[Vec<usize>]) -> Vec<Vec<usize>> {
    faces
        .iter()
        .flat_map(|f| [f.clone(), f.iter().rev().copied().collect()])
        .collect()
}

/// The answers of `query --collision-only`: each line's last word.
fn answers(o: &std::process::Output) -> Vec<String> {
    common::stdout(o)
        .lines()
        .map(|l| l.rsplit(": ").next().unwrap().to_string())
        .collect()
}

/// `dymsum motion ARGS --json`, parsed.
fn motion_json(args: &[&str]) -> serde_json::Value {
    let mut all = vec!["motion"];
    all.extend_from_slice(args);
    all.push("--json");
    serde_json::from_str(ok(&all).trim()).unwrap()
}

#[test]
fn triangle_bodies_a_double_sided_open_box_in_query_and_motion() {
    let dir = temp_dir("open-box");
    let (v, f) = box_4x4x2();
    let open = mesh_off(&dir, "open_box.off", &v, &double_sided(&f[..5]));
    let note = "note: OBSTACLE (open_box.off) taken as triangles (1 surface, 10 triangles; 10 \
                back-to-back triangles dropped)\n";
    // A cube of side 0.5 inside (a surface has no inside: apart), resting
    // on the floor (touching: collides), a hair above it, against a wall,
    // and above the open top.
    let o = run(&[
        "query",
        "box:0.5",
        &open,
        "--collision-only",
        "--pose-xyz-wxyz",
        "0,0,1,1,0,0,0",
        "--pose-xyz-wxyz",
        "0,0,0.25,1,0,0,0",
        "--pose-xyz-wxyz",
        "0,0,0.2500001,1,0,0,0",
        "--pose-xyz-wxyz",
        "1.75,0,1,1,0,0,0",
        "--pose-xyz-wxyz",
        "0,0,3,1,0,0,0",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        common::stdout(&o),
        "t = (0, 0, 1), q = (1, 0, 0, 0): apart\n\
         t = (0, 0, 0.25), q = (1, 0, 0, 0): collides\n\
         t = (0, 0, 0.2500001), q = (1, 0, 0, 0): apart\n\
         t = (1.75, 0, 1), q = (1, 0, 0, 0): collides\n\
         t = (0, 0, 3), q = (1, 0, 0, 0): apart\n"
    );
    assert_eq!(stderr(&o), note);
    // JSON: the pose and the answer only.
    let text = ok(&[
        "query",
        "box:0.5",
        &open,
        "--collision-only",
        "--json",
        "--pose-xyz-wxyz",
        "0,0,0.25,1,0,0,0",
    ]);
    assert_eq!(
        text,
        "{\"pose_xyz_wxyz\":[0.0,0.0,0.25,1.0,0.0,0.0,0.0],\"collides\":true}\n"
    );
    // The box as the robot, the cube fixed: the same contacts.
    let o = run(&[
        "query",
        &open,
        "box:0.5",
        "--collision-only",
        "--pose-xyz-wxyz",
        "0,0,-1,1,0,0,0",
        "--pose-xyz-wxyz",
        "0,0,-0.25,1,0,0,0",
    ]);
    assert_eq!(answers(&o), ["apart", "collides"], "{}", stderr(&o));
    // Depth and distance of triangles: refused, the problem first, the fix
    // last, after the note.
    let o = run(&[
        "query",
        "box:0.5",
        &open,
        "--pose-xyz-wxyz",
        "0,0,1,1,0,0,0",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr(&o),
        format!(
            "{note}error: OBSTACLE (open_box.off) is a triangle mesh (1 surface: not a closed \
             solid): distance and penetration depth need bodies given as convex pieces; fix: add \
             `--collision-only` for the exact collision yes/no, or give the body's convex pieces \
             as files joined with `+` or as OBJ objects\n"
        )
    );
    assert!(common::stdout(&o).is_empty());
    // A decomposition asked for keeps its meaning: the open box is refused
    // as before, never taken as triangles.
    let o = run(&[
        "query",
        "box:0.5",
        &open,
        "--collision-only",
        "--decomposition",
        "vhacd",
        "--pose-xyz-wxyz",
        "0,0,1,1,0,0,0",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(!stderr(&o).contains("triangles"), "{}", stderr(&o));
    // Out through the open top: certified free.
    let up = [
        "box:0.5",
        &open,
        "--from-xyz-wxyz",
        "0,0,1,1,0,0,0",
        "--to-xyz-wxyz",
        "0,0,4,1,0,0,0",
    ];
    let o = run(&[&["motion"][..], &up[..]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        common::stdout(&o),
        "free: no contact at any t in [0, 1] (certified)\n"
    );
    assert_eq!(stderr(&o), note);
    // Through a wall: the first contact, x + 0.25 = 2 at t = 1.75 / 4,
    // bracketed within the tolerance.
    let wall = [
        "box:0.5",
        &open,
        "--from-xyz-wxyz",
        "0,0,1,1,0,0,0",
        "--to-xyz-wxyz",
        "4,0,1,1,0,0,0",
    ];
    let text = ok(&[&["motion"][..], &wall[..]].concat());
    assert!(
        text.starts_with("collides: certified free up to t = 0.43749")
            && text.contains(", in contact at t = 0.437500000\n")
            && text.ends_with(
                "pose at contact (x,y,z,w,qx,qy,qz): 1.750000,0.000000,1.000000,1.000000,0.000000,\
                 0.000000,0.000000\n"
            ),
        "{text}"
    );
    let j = motion_json(&wall);
    let (t_safe, t_contact) = (
        j["t_safe"].as_f64().unwrap(),
        j["t_contact"].as_f64().unwrap(),
    );
    assert!(t_safe < t_contact && t_contact - t_safe <= 1e-6, "{j}");
    assert!((t_contact - 0.4375).abs() <= 1e-6, "{j}");
    // A budget of one interval decides nothing: an error, never a guess.
    let o = run(&[&["motion"][..], &wall[..], &["--budget", "1"][..]].concat());
    assert_fails(&o, 1, "budget of 1 intervals");
    // With its lid the double-sided box is a solid, and exactly convex: the
    // cube inside it collides, and the depth is known (the convex path).
    let closed = mesh_off(&dir, "closed_box.off", &v, &double_sided(&f));
    let o = run(&[
        "query",
        "box:0.5",
        &closed,
        "--pose-xyz-wxyz",
        "0,0,1,1,0,0,0",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        common::stdout(&o).contains(": collides, depth 1.250000000"),
        "{}",
        common::stdout(&o)
    );
    assert_eq!(
        stderr(&o),
        "note: OBSTACLE (closed_box.off) cleaned as triangles (1 solid, 12 triangles; 12 \
         back-to-back triangles dropped): exactly convex, taken as one convex piece\n"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A closed non-convex mesh (the L of `examples/data/Lmesh.off`) is a
/// solid: contact includes lying inside it.
#[test]
fn triangle_bodies_a_non_convex_solid_holds_its_inside() {
    let l = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/data/Lmesh.off")
        .to_str()
        .unwrap()
        .to_string();
    // Deep inside the L's corner, in its notch, and touching its inner wall.
    let o = run(&[
        "query",
        "box:0.2",
        &l,
        "--collision-only",
        "--pose-xyz-wxyz",
        "0.5,0.5,0.5,1,0,0,0",
        "--pose-xyz-wxyz",
        "2,2,0.5,1,0,0,0",
        "--pose-xyz-wxyz",
        "2,1.1,0.5,1,0,0,0",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(answers(&o), ["collides", "apart", "collides"]);
    assert_eq!(
        stderr(&o),
        "note: OBSTACLE (Lmesh.off) taken as triangles (1 solid, 20 triangles; nothing to \
         clean)\n"
    );
    // From the notch diagonally into the corner: contact at x = y = 1.1.
    let v = motion_json(&[
        "box:0.2",
        &l,
        "--from-xyz-wxyz",
        "2,2,0.5,1,0,0,0",
        "--to-xyz-wxyz",
        "0.5,0.5,0.5,1,0,0,0",
    ]);
    assert_eq!(v["free"], false, "{v}");
    assert!(
        (v["t_contact"].as_f64().unwrap() - 0.6).abs() <= 1e-6,
        "{v}"
    );
    // A solid may also be taken apart for the depth (named in the fix).
    let o = run(&["query", &l, "box", "--pose-xyz-wxyz", "5,5,5,1,0,0,0"]);
    assert_fails(
        &o,
        1,
        "error: ROBOT (Lmesh.off) is a triangle mesh (1 solid, not convex): distance and \
         penetration depth need bodies given as convex pieces; fix: add `--collision-only` for \
         the exact collision yes/no, give the body's convex pieces as files joined with `+` or \
         as OBJ objects, or take it apart with `--decomposition vhacd` (approximate)\n",
    );
}

/// A non-manifold soup: three pages sharing one edge (a book), one page
/// listed twice, a zero-area sliver and a loose triangle away from it.
#[test]
fn triangle_bodies_a_non_manifold_soup() {
    let dir = temp_dir("soup");
    let v = [
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [-1.0, 0.0, 0.0],
        [-1.0, 0.0, 1.0],
        [0.0, 1.0, 0.0],
        [0.0, 1.0, 1.0],
        [5.0, 0.0, 0.0],
        [6.0, 0.0, 0.0],
        [5.0, 1.0, 0.0],
        [0.0, 0.0, 0.5],
    ];
    let f = vec![
        vec![0, 2, 3, 1],
        vec![0, 4, 5, 1],
        vec![0, 6, 7, 1],
        vec![0, 6, 7, 1],
        vec![0, 11, 1],
        vec![8, 9, 10],
    ];
    let soup = mesh_off(&dir, "soup.off", &v, &f);
    let o = run(&[
        "query",
        "box:0.2",
        &soup,
        "--collision-only",
        "--json",
        "--pose-xyz-wxyz",
        "0.5,0.5,0.5,1,0,0,0",
        "--pose-xyz-wxyz",
        "0.5,0.1,0.5,1,0,0,0",
        "--pose-xyz-wxyz",
        "0.5,0.1000001,0.5,1,0,0,0",
        "--pose-xyz-wxyz",
        "5.2,0.2,0.1,1,0,0,0",
        "--pose-xyz-wxyz",
        "5.2,0.2,0.1000001,1,0,0,0",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let collides: Vec<bool> = common::stdout(&o)
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap()["collides"] == true)
        .collect();
    assert_eq!(collides, [false, true, false, true, false]);
    assert_eq!(
        stderr(&o),
        "note: OBSTACLE (soup.off) taken as triangles (2 surfaces, 7 triangles; 2 duplicate \
         triangles dropped, 1 zero-area triangle dropped)\n"
    );
    // Between two pages, parallel to them: free; across the third page:
    // contact when the cube's face reaches x = 0.
    let between = [
        "box:0.2",
        &soup,
        "--from-xyz-wxyz",
        "0.5,0.5,0.5,1,0,0,0",
        "--to-xyz-wxyz",
        "0.5,0.5,3,1,0,0,0",
    ];
    assert_eq!(motion_json(&between)["free"], true);
    let across = [
        "box:0.2",
        &soup,
        "--from-xyz-wxyz",
        "0.5,0.5,0.5,1,0,0,0",
        "--to-xyz-wxyz",
        "-0.5,0.5,0.5,1,0,0,0",
    ];
    let v = motion_json(&across);
    assert!(
        (v["t_contact"].as_f64().unwrap() - 0.4).abs() <= 1e-6,
        "{v}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The triangles of `faces` (fans), each followed by its back (a
/// double-sided export), each with its own three corners (unwelded, as STL
/// stores them).
fn double_sided_triangles(v: &[[f64; 3]], faces: &[Vec<usize>]) -> Vec<[[f64; 3]; 3]> {
    faces
        .iter()
        .flat_map(|f| (1..f.len() - 1).map(move |k| [v[f[0]], v[f[k]], v[f[k + 1]]]))
        .flat_map(|[a, b, c]| [[a, b, c], [a, c, b]])
        .collect()
}

#[test]
fn triangle_bodies_from_unwelded_stl_and_off_files() {
    let dir = temp_dir("unwelded");
    let (v, f) = box_4x4x2();
    let tris = double_sided_triangles(&v, &f[..5]);
    // ASCII STL.
    let mut ascii = String::from("solid open_box\n");
    for t in &tris {
        ascii.push_str("facet normal 0 0 0\nouter loop\n");
        for p in t {
            ascii.push_str(&format!("vertex {} {} {}\n", p[0], p[1], p[2]));
        }
        ascii.push_str("endloop\nendfacet\n");
    }
    ascii.push_str("endsolid open_box\n");
    std::fs::write(dir.join("ascii.stl"), ascii).unwrap();
    // Binary STL.
    let mut binary = vec![0u8; 80];
    binary.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for t in &tris {
        binary.extend_from_slice(&[0u8; 12]);
        for p in t {
            for c in p {
                binary.extend_from_slice(&(*c as f32).to_le_bytes());
            }
        }
        binary.extend_from_slice(&[0u8; 2]);
    }
    std::fs::write(dir.join("binary.stl"), binary).unwrap();
    // OFF with every triangle's corners listed again.
    let corners: Vec<[f64; 3]> = tris.iter().flatten().copied().collect();
    let faces: Vec<Vec<usize>> = (0..tris.len())
        .map(|k| vec![3 * k, 3 * k + 1, 3 * k + 2])
        .collect();
    mesh_off(&dir, "unwelded.off", &corners, &faces);
    assert_eq!(tris.len(), 20);
    let poses = [
        "0,0,1,1,0,0,0",
        "0,0,0.25,1,0,0,0",
        "1.75,0,1,1,0,0,0",
        "1.7,0,1,1,0,0,0",
    ];
    for (file, cleaned) in [
        ("ascii.stl", "10 back-to-back triangles dropped"),
        ("binary.stl", "10 back-to-back triangles dropped"),
        (
            "unwelded.off",
            "10 back-to-back triangles dropped, 52 vertices merged",
        ),
    ] {
        let path = dir.join(file);
        let mut args = vec![
            "query",
            "box:0.5",
            path.to_str().unwrap(),
            "--collision-only",
        ];
        for p in &poses {
            args.extend(["--pose-xyz-wxyz", p]);
        }
        let o = run(&args);
        assert!(o.status.success(), "{file}: {}", stderr(&o));
        assert_eq!(
            answers(&o),
            ["apart", "collides", "collides", "apart"],
            "{file}"
        );
        assert_eq!(
            stderr(&o),
            format!(
                "note: OBSTACLE ({file}) taken as triangles (1 surface, 10 triangles; \
                 {cleaned})\n"
            )
        );
        let v = motion_json(&[
            "box:0.5",
            path.to_str().unwrap(),
            "--from-xyz-wxyz",
            "0,0,1,1,0,0,0",
            "--to-xyz-wxyz",
            "4,0,1,1,0,0,0",
        ]);
        assert!(
            (v["t_contact"].as_f64().unwrap() - 0.4375).abs() <= 1e-6,
            "{file}: {v}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
