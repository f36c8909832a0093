//! Issue 8 §5 through the binary: failed writes lose nothing, cobst refuses
//! stale output directories, FIFOs and devices are refused, OBJ bodies are
//! the same in every command, flags and orientation files are strict, and
//! each OS error is said once with its path.

mod common;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::{assert_fails, ok, run, run_in, stderr, temp_dir, BIN};
use dymsum_testkit::files::names;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The arguments `cobst cube gs1 --axis 0,0,1 --slices N --out OUT EXTRA...`.
fn cobst_about_z<'a>(slices: &'a str, out: &'a Path, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "cobst", "cube", "gs1", "--axis", "0,0,1", "--slices", slices,
    ];
    args.extend(["--out", s(out)]);
    args.extend_from_slice(extra);
    args
}

#[test]
fn failed_sum_keeps_the_earlier_output_and_leaves_no_temp() {
    let dir = temp_dir("keep");
    let out = dir.join("sum.stl");
    ok(&["sum", "cube", "gs1", "-o", s(&out)]);
    let good = std::fs::read(&out).unwrap();
    // Coordinates beyond f32: the STL cannot be written.
    let o = run(&[
        "sum",
        "cube",
        "gs1",
        "-o",
        s(&out),
        "--translate-p=1e39,0,0",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(std::fs::read(&out).unwrap(), good);
    assert_eq!(names(&dir), ["sum.stl"]);
}

/// One rule for every writer: a missing output folder is created (with its
/// missing parents), for files (`sum -o`, `render -o`, `models --write`,
/// `animate --csv`) and folders (`--frames-dir`, `cobst --out`, `bench
/// --out`) alike.
#[test]
fn every_writer_creates_missing_output_folders() {
    let dir = temp_dir("missing");
    let at = |name: &str| dir.join(name).join("deeper");
    let file = |name: &str, f: &str| at(name).join(f).to_str().unwrap().to_string();
    ok(&["sum", "cube", "gs1", "-o", &file("sum", "x.off")]);
    ok(&[
        "render",
        "cube",
        "gs1",
        "-o",
        &file("render", "x.svg"),
        "--size",
        "32",
    ]);
    ok(&["models", "--write", "gs1", &file("models", "gs1.ply")]);
    let (csv, frames) = (file("csv", "run.csv"), s(&at("frames")).to_string());
    ok(&[
        "animate",
        "cube",
        "gs1",
        "--steps-per-rev",
        "100",
        "--steps",
        "2",
        "--csv",
        &csv,
        "--frames-dir",
        &frames,
    ]);
    ok(&cobst_about_z("2", &at("cobst"), &[]));
    for (name, f) in [
        ("sum", "x.off"),
        ("render", "x.svg"),
        ("models", "gs1.ply"),
        ("csv", "run.csv"),
        ("frames", "step_000002.off"),
        ("cobst", "index.json"),
    ] {
        assert!(at(name).join(f).is_file(), "{name}: {f}");
    }
    // A file in the way of the folder: exit 1, the path and the OS error
    // said once, nothing written.
    let blocker = dir.join("blocker");
    std::fs::write(&blocker, "x").unwrap();
    for args in [
        vec!["sum", "cube", "gs1", "-o", "BLOCKED/x.off"],
        vec!["render", "cube", "gs1", "-o", "BLOCKED/x.svg"],
        vec![
            "animate",
            "cube",
            "gs1",
            "--steps-per-rev",
            "9",
            "--steps",
            "1",
            "--csv",
            "BLOCKED/r.csv",
        ],
    ] {
        let args: Vec<String> = args
            .iter()
            .map(|a| match a.strip_prefix("BLOCKED/") {
                Some(f) => s(&blocker.join("sub").join(f)).to_string(),
                None => a.to_string(),
            })
            .collect();
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = run(&args);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        let err = stderr(&o);
        assert!(
            err.contains("creating the output folder") && err.contains("blocker"),
            "{err}"
        );
        assert_eq!(
            err.matches("Not a directory").count() + err.matches("File exists").count(),
            1,
            "{err}"
        );
    }
    assert_eq!(std::fs::read(&blocker).unwrap(), b"x");
}

#[test]
fn failed_animate_keeps_the_earlier_csv() {
    let dir = temp_dir("csv");
    let csv = dir.join("run.csv");
    ok(&[
        "animate",
        "cube",
        "gs1",
        "--steps-per-rev",
        "100",
        "--steps",
        "5",
        "--csv",
        s(&csv),
    ]);
    let good = std::fs::read(&csv).unwrap();
    assert_eq!(String::from_utf8_lossy(&good).lines().count(), 6);
    // The frames directory cannot be created (a file is in the way).
    let blocker = dir.join("frames");
    std::fs::write(&blocker, "not a directory").unwrap();
    let o = run(&[
        "animate",
        "cube",
        "gs1",
        "--steps-per-rev",
        "100",
        "--steps",
        "9",
        "--csv",
        s(&csv),
        "--frames-dir",
        s(&blocker),
        "--every",
        "1",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(std::fs::read(&csv).unwrap(), good);
    assert_eq!(names(&dir), ["frames", "run.csv"]);
}

#[test]
fn cobst_refuses_a_non_empty_directory_and_force_clears_only_its_own_files() {
    let dir = temp_dir("cobst");
    let out = dir.join("slices");
    ok(&cobst_about_z("3", &out, &[]));
    assert_eq!(
        names(&out),
        [
            "index.json",
            "slice_00000.off",
            "slice_00001.off",
            "slice_00002.off"
        ]
    );
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let o = run(&cobst_about_z("1", &out, &[]));
    assert_fails(&o, 1, "not empty");
    assert!(stderr(&o).contains("--force"), "{}", stderr(&o));
    assert_eq!(names(&out).len(), 5);
    ok(&cobst_about_z("1", &out, &["--force"]));
    assert_eq!(names(&out), ["index.json", "notes.txt", "slice_00000.off"]);
    let index = std::fs::read_to_string(out.join("index.json")).unwrap();
    assert_eq!(index.matches("\"slice\"").count(), 1);
    // An empty existing directory is fine without --force.
    let empty = dir.join("empty");
    std::fs::create_dir(&empty).unwrap();
    ok(&cobst_about_z("2", &empty, &[]));
}

/// Runs the binary with a deadline: a hang is a failure, not a stuck test.
fn run_with_deadline(args: &[&str], secs: u64) -> std::process::Output {
    let mut child = Command::new(BIN)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if start.elapsed() > Duration::from_secs(secs) {
            child.kill().unwrap();
            panic!("dymsum {args:?} did not finish within {secs} s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[test]
fn fifo_and_device_operands_are_refused_promptly() {
    let dir = temp_dir("fifo");
    let fifo = dir.join("pipe.off");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let zero = dir.join("x.stl");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let quats = dir.join("quats.txt");
    assert!(Command::new("mkfifo")
        .arg(&quats)
        .status()
        .unwrap()
        .success());
    for args in [
        vec!["info", s(&fifo)],
        vec!["info", s(&zero)],
        vec!["query", s(&zero), "cube", "--pose", "0,0,0,1,0,0,0"],
        vec!["sum", s(&fifo), "cube", "-o", "/dev/null/never.off"],
        vec![
            "cobst",
            "cube",
            "cube",
            "--orientations-wxyz",
            s(&quats),
            "--out",
            "/dev/null/never",
        ],
    ] {
        let o = run_with_deadline(&args, 20);
        assert_fails(&o, 1, "not a regular file");
    }
}

#[test]
fn steps_per_rev_with_a_non_finite_step_angle_is_a_usage_error() {
    for x in ["1e-320", "4.9e-324", "1e-309"] {
        let o = run(&[
            "animate",
            "cube",
            "gs1",
            "--steps-per-rev",
            x,
            "--steps",
            "1",
        ]);
        assert_fails(&o, 2, "not finite");
    }
    let o = run(&[
        "bench",
        "rotation",
        "--steps-per-rev",
        "100,1e-320",
        "--out",
        "/dev/null/x",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn huge_and_tiny_quaternions_are_normalised_not_called_zero() {
    let dir = temp_dir("quat");
    let reference = dir.join("ref.off");
    ok(&[
        "sum",
        "cone",
        "gs1",
        "-o",
        s(&reference),
        "--rotate-p-wxyz",
        "1,0,0,1",
    ]);
    for q in ["1e200,0,0,1e200", "1e-200,0,0,1e-200", "1e308,0,0,1e308"] {
        let out = dir.join("q.off");
        ok(&["sum", "cone", "gs1", "-o", s(&out), "--rotate-p-wxyz", q]);
        let a = common::model(s(&reference));
        let b = common::model(s(&out));
        assert_eq!(a.vertex_count(), b.vertex_count(), "{q}");
        assert_eq!(a.face_count(), b.face_count(), "{q}");
    }
    let o = run(&[
        "sum",
        "cone",
        "gs1",
        "-o",
        "x.off",
        "--rotate-p-wxyz",
        "0,0,0,0",
    ]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn orientation_lines_with_empty_fields_are_errors_with_the_line() {
    let dir = temp_dir("orient");
    for (line, field) in [
        ("1,,0,0,0", "field 2"),
        (",1,0,0", "field 1"),
        ("1,0,0,", "field 4"),
    ] {
        let file = dir.join("q.txt");
        std::fs::write(&file, format!("# header\n1,0,0,0\n{line}\n")).unwrap();
        let o = run(&[
            "cobst",
            "cube",
            "gs1",
            "--orientations-wxyz",
            s(&file),
            "--out",
            s(&dir.join("out")),
        ]);
        assert_eq!(o.status.code(), Some(1), "{line}");
        let err = stderr(&o);
        assert!(err.contains("line 3"), "{err}");
        assert!(err.contains(field), "{err}");
    }
    // Whitespace separated still works.
    let file = dir.join("ws.txt");
    std::fs::write(&file, "1 0 0 0\n0.7 0 0 0.7\n").unwrap();
    ok(&[
        "cobst",
        "cube",
        "gs1",
        "--orientations-wxyz",
        s(&file),
        "--out",
        s(&dir.join("ws")),
    ]);
}

use dymsum_testkit::cube_obj;

#[test]
fn obj_point_cloud_object_is_a_body_in_query() {
    let dir = temp_dir("cloud");
    let robot = dir.join("robot.obj");
    let text = format!(
        "o a\n{}o b\n{}o pts\nv 10 10 10\nv 11 10 10\nv 10 11 10\nv 10 10 11\n",
        cube_obj(0.0, 0, false),
        cube_obj(50.0, 8, false)
    );
    std::fs::write(&robot, text).unwrap();
    // Moved by -10.2, only the point-cloud object reaches the obstacle.
    let out = ok(&[
        "query",
        s(&robot),
        "box:1,1,1",
        "--pose=-10.2,-10.2,-10.2,1,0,0,0",
        "--json",
    ]);
    assert!(out.contains("\"collides\":true"), "{out}");
    let out = ok(&[
        "query",
        s(&robot),
        "box:1,1,1",
        "--pose=20,20,20,1,0,0,0",
        "--json",
    ]);
    assert!(out.contains("\"collides\":false"), "{out}");
    // One body asked for: refused, naming the bodies.
    let o = run(&["info", s(&robot)]);
    assert_fails(&o, 1, "a body of 3 convex pieces (`a`, `b`, `pts`)");
}

#[test]
fn obj_groups_of_one_mesh_are_one_body_in_every_command() {
    let dir = temp_dir("groups");
    let grouped = dir.join("grouped.obj");
    let plain = dir.join("plain.obj");
    std::fs::write(&grouped, cube_obj(0.0, 0, true)).unwrap();
    std::fs::write(&plain, cube_obj(0.0, 0, false)).unwrap();
    let info = |p: &Path| {
        ok(&["info", s(p), "--json"])
            .lines()
            .filter(|l| !l.contains("\"spec\"") && !l.contains("source"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(info(&grouped), info(&plain));
    for (name, p) in [("g", &grouped), ("p", &plain)] {
        ok(&[
            "sum",
            s(p),
            "gs1",
            "-o",
            s(&dir.join(format!("{name}.off"))),
        ]);
        ok(&[
            "cobst",
            s(p),
            "gs1",
            "--axis",
            "0,0,1",
            "--slices",
            "2",
            "--out",
            s(&dir.join(format!("{name}_slices"))),
        ]);
    }
    assert_eq!(
        std::fs::read(dir.join("g.off")).unwrap(),
        std::fs::read(dir.join("p.off")).unwrap()
    );
    assert_eq!(names(&dir.join("g_slices")), names(&dir.join("p_slices")));
    assert_eq!(names(&dir.join("g_slices")).len(), 3);
    let q = |p: &Path| ok(&["query", s(p), "gs1", "--pose", "1.5,0,0,1,0,0,0", "--json"]);
    assert_eq!(q(&grouped), q(&plain));
}

#[test]
fn missing_operand_and_unreadable_file_say_the_os_error_once() {
    let dir = temp_dir("perm");
    let f = dir.join("locked.off");
    std::fs::write(&f, "OFF\n").unwrap();
    let o = run_in(Some(&dir), &["info", "nope/cube.off"]);
    assert_fails(&o, 1, "does not exist");
    // A directory with a mesh extension.
    let d = dir.join("d.off");
    std::fs::create_dir(&d).unwrap();
    let o = run(&["info", s(&d)]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("d.off") && err.contains("directory"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
}

#[test]
fn huge_numbers_are_printed_in_scientific_form() {
    let out = ok(&["query", "cube", "cube", "--pose=1e300,0,0,1,0,0,0"]);
    assert!(
        out.starts_with("t = (1e300, 0, 0), q = (1, 0, 0, 0)"),
        "{out}"
    );
    assert!(out.len() < 200, "{out}");
    let out = ok(&["info", "box:1e100"]);
    assert!(
        out.contains("diameter:         1.7320508075688773e100"),
        "{out}"
    );
    assert!(out.lines().all(|l| l.len() < 120), "{out}");
    let o = run(&["info", "box:1e300"]);
    assert_fails(&o, 1, "got 1e300");
    assert!(stderr(&o).len() < 200, "{}", stderr(&o));
}

/// Runs the binary with `input` on standard input.
fn run_with_stdin(args: &[&str], input: &[u8]) -> std::process::Output {
    use std::io::Write;
    let mut child = Command::new(BIN)
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // A command that refuses its arguments exits before reading standard
    // input: writing may then fail with a broken pipe, which is fine.
    if let Err(e) = child.stdin.take().unwrap().write_all(input) {
        assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "{e}");
    }
    child.wait_with_output().unwrap()
}

#[test]
fn models_write_then_sum_through_standard_input_and_output() {
    let dir = temp_dir("stdio");
    // `models --write NAME -` prints the model as dymsum uses it.
    let box_off = run(&["models", "--write", "box:1,2,3", "-"]);
    assert_eq!(box_off.status.code(), Some(0), "{}", stderr(&box_off));
    let mesh = dymsum_io::formats::read_mesh_bytes(
        &box_off.stdout,
        dymsum_io::formats::Format::Off,
        "stdout",
    )
    .unwrap();
    assert_eq!((mesh.vertices.len(), mesh.faces.len()), (8, 6));
    // `sum - Q -o -`: P from stdin, the sum's OFF on stdout, summary on stderr.
    let o = run_with_stdin(&["sum", "-", "box:2,2,2", "-o", "-"], &box_off.stdout);
    assert_fails(&o, 0, "stdin ⊕ box:2,2,2");
    let sum =
        dymsum_io::formats::read_mesh_bytes(&o.stdout, dymsum_io::formats::Format::Off, "stdout")
            .unwrap();
    dymsum::sum::validate::check_convex_mesh(&sum).unwrap();
    // box 1×2×3 ⊕ box 2×2×2 is the box 3×4×5.
    assert_eq!((sum.vertices.len(), sum.faces.len()), (8, 6));
    assert!((sum.signed_volume() - 60.0).abs() < 1e-12);
    // The same through files.
    let file = dir.join("b.ply");
    ok(&["models", "--write", "box:1,2,3", s(&file)]);
    let back = dymsum_io::formats::read_mesh(&file).unwrap();
    assert_eq!((back.vertices.len(), back.faces.len()), (8, 6));
}

#[test]
fn standard_input_serves_one_operand_and_empty_input_is_an_error() {
    let cube = run(&["models", "--write", "box:1,1,1", "-"]).stdout;
    let o = run_with_stdin(&["sum", "-", "-", "-o", "-"], &cube);
    assert_fails(
        &o,
        1,
        "Q: standard input (`-`) can be read by one operand only",
    );
    // Said before anything is read: empty standard input gives the same
    // error (not "no vertices"), in every command with two operands.
    for args in [
        vec!["sum", "-", "-", "-o", "x.off"],
        vec!["render", "-", "-", "-o", "x.svg"],
        vec!["animate", "-", "-", "--steps-per-rev", "9", "--steps", "1"],
        vec!["query", "-", "-", "--pose-xyz-wxyz", "0,0,0,1,0,0,0"],
        vec![
            "cobst", "-", "-", "--axis", "0,0,1", "--slices", "2", "--out", "never",
        ],
    ] {
        let o = run_with_stdin(&args, b"");
        assert_fails(&o, 1, "can be read by one operand only");
        assert!(!stderr(&o).contains("no vertices"), "{}", stderr(&o));
    }
    let o = run_with_stdin(&["info", "-"], b"");
    assert_fails(&o, 1, "standard input");
    let o = run(&["models", "--write", "nosuch", "-"]);
    assert_fails(&o, 1, "unknown model");
}

#[test]
fn completions_are_generated_for_every_shell() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let text = ok(&["completions", shell]);
        assert!(text.contains("dymsum") && text.contains("cobst"), "{shell}");
    }
    let o = run(&["completions", "tcsh"]);
    assert_eq!(o.status.code(), Some(2));
}
