//! End-to-end tests of the `dymsum` binary: every subcommand and flag, the
//! exit codes (0 ok, 1 bad input, 2 usage) and the error messages.

mod common;

use common::{fixture, ok, run, run_in, stderr, stdout, temp_dir};
use dymsum::polytope::MeshPolicy;
use dymsum::Polytope;
use dymsum_io::formats::read_mesh;

/// The paper's 13 models.
const PAPER_MODELS: [&str; 13] = [
    "cone", "cube", "cylinder", "dd", "ellipse", "gs1", "gs2", "gs3", "gs4", "hp", "t", "ti",
    "vrod",
];

/// Asserts exit code 1 (bad input) with every `needles` in stderr, no panic.
fn bad_input(args: &[&str], needles: &[&str]) -> String {
    let o = run(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "dymsum {args:?}: {err}");
    assert!(err.starts_with("error: "), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    for n in needles {
        assert!(err.contains(n), "dymsum {args:?}: `{n}` not in: {err}");
    }
    err
}

/// Asserts exit code 2 (usage error).
fn usage_error(args: &[&str]) -> String {
    let o = run(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "dymsum {args:?}: {err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

// ---------------------------------------------------------------- sum

#[test]
fn sum_with_each_method_agrees() {
    let dir = temp_dir("methods");
    let mut lines = Vec::new();
    for method in ["walk", "brute", "hull"] {
        let out = dir.join(format!("{method}.off"));
        let line = ok(&[
            "sum",
            "gs1",
            "dd",
            "-o",
            out.to_str().unwrap(),
            "--method",
            method,
        ]);
        assert_eq!(line.lines().count(), 1, "one summary line: {line}");
        assert!(
            line.starts_with(&format!("gs1 ⊕ dd ({method}): ")),
            "{line}"
        );
        assert!(
            line.contains(" fv + ")
                && line.contains(" ee = ")
                && line.contains("faces after merging")
        );
        // The counts (everything before the time) agree between methods.
        let counts = line
            .split(": ")
            .nth(1)
            .unwrap()
            .rsplit_once(", ")
            .unwrap()
            .0
            .to_string();
        lines.push(counts);
        let mesh = read_mesh(&out).unwrap();
        let (sum, _) = Polytope::from_mesh(&mesh, MeshPolicy::default()).unwrap();
        assert!(sum.sanity_check().is_ok());
    }
    assert_eq!(lines[0], lines[1]);
    assert_eq!(lines[0], lines[2]);
}

#[test]
fn sum_writes_every_format() {
    let dir = temp_dir("formats");
    let mut meshes = Vec::new();
    for ext in ["off", "obj", "ply", "stl"] {
        let out = dir.join(format!("sum.{ext}"));
        ok(&["sum", "cube", "tetra", "-o", out.to_str().unwrap()]);
        let mesh = read_mesh(&out).unwrap();
        assert!(mesh.faces.len() >= 4, "{ext}");
        let (p, _) = Polytope::from_mesh(&mesh, MeshPolicy::default()).unwrap();
        assert!(p.sanity_check().is_ok(), "{ext}");
        meshes.push(mesh);
    }
    // The text and PLY formats are lossless and keep the polygons; STL
    // stores f32 triangles, so only its volume is compared.
    assert_eq!(meshes[0], meshes[1]);
    assert_eq!(meshes[0], meshes[2]);
    let (v0, v3) = (meshes[0].signed_volume(), meshes[3].signed_volume());
    assert!((v0 - v3).abs() < 1e-5 * v0, "{v0} vs {v3}");
}

#[test]
fn sum_of_exact_cubes_is_a_cube() {
    let dir = temp_dir("cubes");
    let out = dir.join("cc.off");
    let cube = fixture("cube.off");
    let line = ok(&["sum", &cube, &cube, "-o", out.to_str().unwrap(), "--strict"]);
    assert!(line.starts_with("cube.off ⊕ cube.off (walk): "), "{line}");
    assert!(line.contains("6 faces after merging"), "{line}");
    let mesh = read_mesh(&out).unwrap();
    assert_eq!(mesh.faces.len(), 6);
    assert!((mesh.signed_volume() - 8.0).abs() < 1e-12);
}

#[test]
fn sum_rotate_and_translate() {
    let dir = temp_dir("pose");
    let cube = fixture("cube.off");
    // A quarter turn about z (not normalised: 1,0,0,1) keeps the sum a box.
    let out = dir.join("turned.off");
    let line = ok(&[
        "sum",
        &cube,
        &cube,
        "-o",
        out.to_str().unwrap(),
        "--rotate-p-wxyz",
        "1,0,0,1",
        "--translate-p",
        "10,-20,30",
    ]);
    assert!(line.contains("6 faces after merging"), "{line}");
    let mesh = read_mesh(&out).unwrap();
    // The turned cube spans x in [-1, 0]; plus [0, 1]: x in [-1, 1], shifted by 10.
    let xs: Vec<f64> = mesh.vertices.iter().map(|v| v[0]).collect();
    let min_x = xs.iter().cloned().fold(f64::INFINITY, f64::min);
    let max_x = xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    assert_eq!((min_x, max_x), (9.0, 11.0));
    let min_z = mesh
        .vertices
        .iter()
        .map(|v| v[2])
        .fold(f64::INFINITY, f64::min);
    assert_eq!(min_z, 30.0);
    // A general rotation with a negative component gives more faces.
    let out2 = dir.join("general.obj");
    let line = ok(&[
        "sum",
        &cube,
        &cube,
        "-o",
        out2.to_str().unwrap(),
        "--rotate-p-wxyz",
        "-0.3,0.5,0.2,0.7",
    ]);
    let faces: usize = line
        .split(", ")
        .find(|s| s.contains(" faces after merging"))
        .and_then(|s| s.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap();
    assert!(faces > 6, "{line}");
}

#[test]
fn sum_accepts_point_clouds() {
    let dir = temp_dir("points");
    let out = dir.join("s.off");
    let line = ok(&[
        "sum",
        &fixture("tetra_points.obj"),
        "random:40:1",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(
        line.starts_with("tetra_points.obj ⊕ random:40:1 (walk)"),
        "{line}"
    );
}

// ---------------------------------------------------------------- info

#[test]
fn info_text_reports_convexity() {
    let text = ok(&["info", &fixture("cube.off")]);
    for needle in [
        "vertices:         8",
        "edges:            12",
        "faces:            6",
        "volume:",
        "diameter:",
        "exactly convex",
        "input:            8 vertices, 6 faces, 12 triangles",
    ] {
        assert!(text.contains(needle), "`{needle}` in {text}");
    }
}

/// Exactly convex means zero deviation, printed as `0`, for every
/// exactly convex paper model (their float distances to the hull planes
/// used to show as `5.551e-17`).
#[test]
fn exactly_convex_models_have_zero_deviation() {
    for name in PAPER_MODELS {
        let text = ok(&["info", name]);
        if text.contains("exactly convex") {
            assert!(
                text.contains("max deviation:    0 (tolerance"),
                "{name}: {text}"
            );
        } else {
            assert!(!text.contains("max deviation:    0 "), "{name}: {text}");
        }
    }
}

#[test]
fn info_json_parses() {
    let text = ok(&["info", "gs2", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["source"], "built-in gs2");
    assert_eq!(v["input_triangles"], 180);
    assert_eq!(v["input_kind"], "mesh");
    let (vs, es, fs) = (
        v["vertices"].as_u64().unwrap() as i64,
        v["edges"].as_u64().unwrap() as i64,
        v["faces"].as_u64().unwrap() as i64,
    );
    assert_eq!(vs - es + fs, 2);
    assert!(v["volume"].as_f64().unwrap() > 0.0);
    assert!(v["diameter"].as_f64().unwrap() > 0.0);
    let c = &v["convexity"];
    for key in [
        "exactly_convex",
        "replaced_by_hull",
        "max_deviation",
        "tolerance",
        "dropped_vertices",
        "inward_oriented",
    ] {
        assert!(!c[key].is_null(), "{key} in {c}");
    }
    // gs2 is exactly convex: no deviation at all (not rounding noise).
    assert_eq!(c["exactly_convex"], true);
    assert_eq!(c["max_deviation"].as_f64(), Some(0.0), "{c}");
    let pts: serde_json::Value =
        serde_json::from_str(&ok(&["info", "random:30:2", "--json"])).unwrap();
    assert_eq!(pts["input_kind"], "points");
    assert!(pts["convexity"].is_null());
}

#[test]
fn strict_refuses_the_rounded_fogel_cube() {
    let text = ok(&["info", "cube"]);
    assert!(text.contains("replaced by hull"), "{text}");
    let json: serde_json::Value = serde_json::from_str(&ok(&["info", "cube", "--json"])).unwrap();
    assert_eq!(json["convexity"]["replaced_by_hull"], true);
    assert_eq!(json["convexity"]["exactly_convex"], false);
    bad_input(
        &["info", "cube", "--strict"],
        &["input (built-in cube): strict mode"],
    );
    let dir = temp_dir("strict");
    let out = dir.join("s.off");
    ok(&["sum", "cube", "hp", "-o", out.to_str().unwrap()]);
    bad_input(
        &["sum", "cube", "hp", "-o", out.to_str().unwrap(), "--strict"],
        &["P (built-in cube): strict mode"],
    );
    // An exactly convex mesh passes --strict.
    ok(&["info", &fixture("cube.off"), "--strict"]);
}

// ---------------------------------------------------------------- models

#[test]
fn models_lists_the_paper_models() {
    let text = ok(&["models"]);
    assert!(text.lines().next().unwrap().starts_with("NAME"));
    let tris = [78, 12, 140, 32, 960, 80, 180, 320, 500, 10, 60, 236, 324];
    for (name, t) in PAPER_MODELS.iter().zip(tris) {
        let line = text
            .lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("{name} not listed"));
        assert_eq!(
            line.split_whitespace().nth(1),
            Some(t.to_string().as_str()),
            "{line}"
        );
    }
    assert!(text.contains("tcube:K"));
    assert!(text.contains("13 models from the paper"));
}

// ---------------------------------------------------------------- animate

#[test]
fn animate_writes_csv_and_frames() {
    let dir = temp_dir("animate");
    let csv = dir.join("run.csv");
    let frames = dir.join("frames");
    let text = ok(&[
        "animate",
        "gs1",
        "dd",
        "--steps-per-rev",
        "100",
        "--steps",
        "25",
        "--seed",
        "3",
        "--csv",
        csv.to_str().unwrap(),
        "--frames-dir",
        frames.to_str().unwrap(),
        "--every",
        "10",
    ]);
    assert!(text.contains("25 steps"), "{text}");
    let data = std::fs::read_to_string(&csv).unwrap();
    let mut lines = data.lines();
    assert_eq!(
        lines.next(),
        Some("step,qw,qx,qy,qz,fv_errors,ee_errors,removed,added,facets,update_us")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 25);
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(r.len(), 11);
        assert_eq!(r[0], (i + 1).to_string());
        let q: Vec<f64> = r[1..5].iter().map(|x| x.parse().unwrap()).collect();
        let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!((norm - 1.0).abs() < 1e-12);
        for x in &r[5..10] {
            x.parse::<usize>().unwrap();
        }
        assert!(r[10].parse::<f64>().unwrap() >= 0.0);
    }
    // The turn accumulates: the last orientation is not the identity.
    assert_ne!(rows[24][1], "1");
    let mut names: Vec<String> = std::fs::read_dir(&frames)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        ["step_000010.off", "step_000020.off", "step_000025.off"]
    );
    // The last frame is the sum at the last row's pose: an exactly convex
    // closed mesh (a face bent by rounding may come out triangulated, so the
    // face count is bounded by Euler's formula, not by the facet count).
    let last = read_mesh(&frames.join("step_000025.off")).unwrap();
    dymsum::sum::validate::check_convex_mesh(&last).unwrap();
    assert!(last.vertices.len() >= 4 && last.faces.len() <= 2 * last.vertices.len() - 4);
}

#[test]
fn animate_is_deterministic_per_seed() {
    let dir = temp_dir("seed");
    let csv = |name: &str, seed: &str| {
        let path = dir.join(name);
        ok(&[
            "animate",
            "hp",
            "t",
            "--steps-per-rev",
            "50",
            "--steps",
            "40",
            "--seed",
            seed,
            "--csv",
            path.to_str().unwrap(),
        ]);
        // Drop the timing column.
        std::fs::read_to_string(path)
            .unwrap()
            .lines()
            .map(|l| l.rsplit_once(',').unwrap().0.to_string())
            .collect::<Vec<_>>()
    };
    assert_eq!(csv("a.csv", "9"), csv("b.csv", "9"));
    assert_ne!(csv("c.csv", "9"), csv("d.csv", "10"));
}

// ---------------------------------------------------------------- demo

#[test]
fn demo_runs_and_writes_demo_sum() {
    let dir = temp_dir("demo");
    let o = run_in(Some(&dir), &["demo", "--seconds", "0.3"]);
    let text = stdout(&o);
    assert!(o.status.success(), "{}\n{text}", stderr(&o));
    assert!(
        text.contains("verified: dynamic facets == static walk facets"),
        "{text}"
    );
    for row in ["DYMSUM", "walk", "brute"] {
        assert!(
            text.lines().any(|l| l.starts_with(row)),
            "{row} row in {text}"
        );
    }
    assert!(text.contains("subsample"), "{text}");
    let mesh = read_mesh(&dir.join("demo_sum.off")).unwrap();
    let (sum, _) = Polytope::from_mesh(&mesh, MeshPolicy::default()).unwrap();
    assert!(sum.sanity_check().is_ok());
}

// ---------------------------------------------------------------- bad input: exit 1

#[test]
fn missing_file_is_named() {
    let dir = temp_dir("missing");
    let out = dir.join("s.off");
    bad_input(
        &[
            "sum",
            "no_such_cube.off",
            "gs1",
            "-o",
            out.to_str().unwrap(),
        ],
        &["P: file `no_such_cube.off` does not exist"],
    );
    bad_input(
        &["sum", "gs1", "nowhere/x.obj", "-o", out.to_str().unwrap()],
        &["Q: file `nowhere/x.obj` does not exist"],
    );
    assert!(!out.exists());
}

#[test]
fn unknown_model_suggests_a_name() {
    let dir = temp_dir("unknown");
    let out = dir.join("s.off");
    bad_input(
        &["sum", "gs1", "elipse", "-o", out.to_str().unwrap()],
        &[
            "Q: `elipse` is neither an existing file nor a built-in model",
            "`ellipse`",
        ],
    );
    bad_input(&["info", "tcube:100000"], &["built-in tcube:100000", "K"]);
}

#[test]
fn bad_meshes_name_the_operand_and_cause() {
    let dir = temp_dir("badmesh");
    let out = dir.join("s.off");
    let o = out.to_str().unwrap();
    let open = fixture("cube_open.off");
    bad_input(
        &["sum", &open, "gs1", "-o", o],
        &[
            &format!("P (file {open}): open mesh: edge ("),
            "borders only one face",
        ],
    );
    let dent = fixture("cube_dent.off");
    bad_input(
        &["sum", "gs1", &dent, "-o", o],
        &[&format!("Q (file {dent}): non-convex mesh: vertex 6")],
    );
    let nan = fixture("cube_nan.off");
    bad_input(
        &["info", &nan],
        &[&format!("(file {nan}): line 8: non-finite coordinate")],
    );
    bad_input(
        &["sum", &fixture("three_points.obj"), "gs1", "-o", o],
        &["P (file ", "three_points.obj): too few points: 3"],
    );
    bad_input(
        &["info", &fixture("flat_points.obj")],
        &["flat_points.obj): ", "coplanar"],
    );
    bad_input(
        &[
            "animate",
            &open,
            "gs1",
            "--steps-per-rev",
            "10",
            "--steps",
            "3",
        ],
        &["P (file ", "open mesh"],
    );
}

#[test]
fn unwritable_output_is_exit_1() {
    let dir = temp_dir("unwritable");
    // A file where the output folder should be.
    std::fs::write(dir.join("file"), "x").unwrap();
    let out = dir.join("file/s.off");
    bad_input(
        &["sum", "gs1", "dd", "-o", out.to_str().unwrap()],
        &["creating the output folder", "file"],
    );
}

// ---------------------------------------------------------------- bad flags: exit 2

#[test]
fn bad_flags_are_usage_errors() {
    let dir = temp_dir("flags");
    let out = dir.join("s.off");
    let o = out.to_str().unwrap();
    let err = usage_error(&["sum", "gs1", "dd", "-o", o, "--rotate-p-wxyz", "1,2"]);
    assert!(err.contains("--rotate-p-wxyz"), "{err}");
    usage_error(&["sum", "gs1", "dd", "-o", o, "--rotate-p-wxyz", "NaN,0,0,1"]);
    usage_error(&["sum", "gs1", "dd", "-o", o, "--rotate-p-wxyz", "0,0,0,0"]);
    usage_error(&["sum", "gs1", "dd", "-o", o, "--translate-p", "1,2,inf"]);
    usage_error(&["sum", "gs1", "dd", "-o", o, "--translate-p", "1,2"]);
    usage_error(&["sum", "gs1", "dd", "-o", o, "--method", "fast"]);
    usage_error(&[
        "sum",
        "gs1",
        "dd",
        "-o",
        &dir.join("s.txt").to_string_lossy(),
    ]);
    usage_error(&["sum", "gs1", "dd"]);
    usage_error(&["sum", "gs1"]);
    usage_error(&["frobnicate"]);
    usage_error(&["info"]);
    // `dymsum animate gs1 dd ARGS`.
    let animate = |args: &[&str]| {
        let mut all = vec!["animate", "gs1", "dd"];
        all.extend_from_slice(args);
        usage_error(&all)
    };
    animate(&["--steps-per-rev", "0", "--steps", "3"]);
    animate(&["--steps-per-rev", "nan", "--steps", "3"]);
    animate(&["--steps-per-rev", "10", "--steps", "-3"]);
    animate(&["--steps-per-rev", "10"]);
    animate(&["--steps-per-rev", "10", "--steps", "3", "--every", "2"]);
    animate(&[
        "--steps-per-rev",
        "10",
        "--steps",
        "3",
        "--frames-dir",
        o,
        "--every",
        "0",
    ]);
    usage_error(&["demo", "--seconds", "-1"]);
    usage_error(&["demo", "--seconds", "abc"]);
    assert!(!out.exists());
}

/// The flags renamed to say their quaternion order keep their old spelling
/// as a hidden alias: same result, not listed in `--help`.
#[test]
fn old_quaternion_flag_spellings_still_work() {
    let dir = temp_dir("aliases");
    let (a, b) = (dir.join("a.off"), dir.join("b.off"));
    let sum = |flag: &str, out: &std::path::Path| {
        ok(&[
            "sum",
            "gs1",
            "dd",
            "-o",
            out.to_str().unwrap(),
            flag,
            "0.9,0.1,0.2,0.3",
        ]);
        std::fs::read(out).unwrap()
    };
    assert_eq!(sum("--rotate-p", &a), sum("--rotate-p-wxyz", &b));
    let (a, b) = (dir.join("a.svg"), dir.join("b.svg"));
    let render = |old: bool, out: &std::path::Path| {
        let (r, h) = if old {
            ("--rotate-p", "--highlight-after")
        } else {
            ("--rotate-p-wxyz", "--highlight-after-wxyz")
        };
        let o = out.to_str().unwrap();
        ok(&[
            "render",
            "gs1",
            "dd",
            "-o",
            o,
            r,
            "0.9,0.1,0.2,0.3",
            h,
            "0.99,0,0.1,0",
            "--size",
            "64",
        ]);
        std::fs::read(out).unwrap()
    };
    assert_eq!(render(true, &a), render(false, &b));
    let quats = dir.join("q.txt");
    std::fs::write(&quats, "1,0,0,0\n0.9,0.1,0.2,0.3\n").unwrap();
    let cobst = |flag: &str, out: &str| {
        let out = dir.join(out);
        ok(&[
            "cobst",
            "gs1",
            "dd",
            flag,
            quats.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        std::fs::read(out.join("index.json")).unwrap()
    };
    assert_eq!(
        cobst("--orientations", "s1"),
        cobst("--orientations-wxyz", "s2")
    );
    for (sub, old) in [
        ("sum", "--rotate-p "),
        ("render", "--highlight-after "),
        ("cobst", "--orientations "),
        ("query", "--pose "),
    ] {
        let help = ok(&[sub, "--help"]);
        assert!(!help.contains(old), "{sub} --help lists {old}: {help}");
        assert!(help.contains("wxyz"), "{help}");
    }
}

#[test]
fn help_and_version_exit_0() {
    let text = ok(&["--help"]);
    for sub in ["sum", "info", "models", "animate", "demo"] {
        assert!(text.contains(sub), "{sub} in {text}");
    }
    ok(&["sum", "--help"]);
    assert!(ok(&["--version"]).starts_with("dymsum "));
}
