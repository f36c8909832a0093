//! End-to-end tests of `dymsum bench` (table1, rotation, size): the files
//! each experiment writes, their columns and numbers, and the exit codes.
//! Tiny step counts keep every test to a few seconds.

mod common;

use std::path::{Path, PathBuf};

use common::{run, temp_dir};

fn ok(args: &[&str]) -> String {
    let o = run(args);
    assert!(
        o.status.success(),
        "dymsum {args:?} failed ({:?}):\n{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

/// Runs `dymsum bench EXPERIMENT ARGS --out DIR` with DIR a fresh
/// directory named after the experiment, asserts success and returns DIR
/// and stdout.
fn bench(experiment: &str, args: &[&str]) -> (PathBuf, String) {
    let dir = temp_dir(experiment);
    let mut all = vec!["bench", experiment];
    all.extend_from_slice(args);
    all.extend(["--out", dir.to_str().unwrap()]);
    let stdout = ok(&all);
    (dir, stdout)
}

/// Reads a CSV file: header and rows.
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header, rows)
}

fn assert_png(path: &Path) {
    let bytes = std::fs::read(path).unwrap();
    assert!(
        bytes.starts_with(&[0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n']),
        "{} is not a PNG",
        path.display()
    );
    assert!(bytes.len() > 1000, "{} is too small", path.display());
}

fn assert_svg(path: &Path) {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains("<svg"), "{} is not an SVG", path.display());
    assert!(text.contains("<text"), "{} has no labels", path.display());
    assert!(
        text.contains("DYMSUM"),
        "{} has no DYMSUM series",
        path.display()
    );
}

#[test]
fn table1_writes_91_rows_with_the_exact_columns() {
    let (dir, stdout) = bench(
        "table1",
        &["--steps", "2", "--static-poses", "1", "--hull-poses", "1"],
    );
    let (header, rows) = read_csv(&dir.join("table1.csv"));
    assert_eq!(
        header.join(","),
        "p,q,p_input_facets,p_faces,q_input_facets,q_faces,dymsum_us,walk_us,brute_us,hull_us,\
         speedup_brute,speedup_walk,paper_speedup"
    );
    assert_eq!(rows.len(), 91);
    let mut pairs = std::collections::HashSet::new();
    for r in &rows {
        assert_eq!(r.len(), 13, "{r:?}");
        assert!(
            pairs.insert((r[0].clone(), r[1].clone())),
            "duplicate {r:?}"
        );
        for c in &r[2..6] {
            assert!(c.parse::<usize>().unwrap() > 0, "{r:?}");
        }
        for c in &r[6..13] {
            let x: f64 = c.parse().unwrap_or_else(|_| panic!("`{c}` in {r:?}"));
            // hull may be NaN if it failed; the others are measured.
            assert!(x.is_nan() || x > 0.0, "{r:?}");
        }
        for i in [6, 7, 8, 10, 11, 12] {
            assert!(r[i].parse::<f64>().unwrap().is_finite(), "{r:?}");
        }
    }
    let ee = rows
        .iter()
        .find(|r| r[0] == "ellipse" && r[1] == "ellipse")
        .expect("ellipse+ellipse row");
    assert_eq!(ee[12].parse::<f64>().unwrap(), 176.34);
    assert_eq!(ee[2], "960");
    let cube_cone = rows
        .iter()
        .find(|r| r[0] == "cube" && r[1] == "cone")
        .unwrap();
    assert_eq!(cube_cone[12].parse::<f64>().unwrap(), 8.58);
    // speedup_brute = brute_us / dymsum_us.
    for r in &rows {
        let f = |i: usize| r[i].parse::<f64>().unwrap();
        let rel = (f(10) - f(8) / f(6)).abs() / f(10);
        assert!(rel < 0.02, "{r:?}");
    }
    let md = std::fs::read_to_string(dir.join("table1.md")).unwrap();
    assert!(md.contains("| **ellipse** |"));
    assert!(md.contains("176"));
    // The terminal table is in the paper's layout, with the verification.
    assert!(stdout.contains("v-rod"), "{stdout}");
    assert!(stdout.contains("/176"), "{stdout}");
    assert!(stdout.contains(" 0 mismatches"), "{stdout}");
}

#[test]
fn rotation_writes_csv_and_plots() {
    let (dir, stdout) = bench(
        "rotation",
        &[
            "--steps-per-rev",
            "10,500,100000",
            "--pairs",
            "cube+cube,gs1+hp",
            "--steps",
            "20",
            "--static-poses",
            "2",
        ],
    );
    let (header, rows) = read_csv(&dir.join("rotation.csv"));
    assert_eq!(
        header[..7].join(","),
        "p,q,steps_per_rev,steps,dymsum_us,walk_us,brute_us"
    );
    assert_eq!(rows.len(), 6);
    for r in &rows {
        for c in &r[2..7] {
            assert!(c.parse::<f64>().unwrap() > 0.0, "{r:?}");
        }
        assert_eq!(
            r[header.iter().position(|h| h == "mismatches").unwrap()],
            "0"
        );
    }
    assert_svg(&dir.join("rotation.svg"));
    assert_png(&dir.join("rotation.png"));
    assert!(stdout.contains(" 0 mismatches"), "{stdout}");
}

#[test]
fn size_writes_csv_plots_and_exponents() {
    let (dir, stdout) = bench(
        "size",
        &[
            "--tcube",
            "1,2,3",
            "--sphere",
            "1,2,3",
            "--steps",
            "20",
            "--static-poses",
            "2",
            "--brute-max-faces",
            "100",
        ],
    );
    let (header, rows) = read_csv(&dir.join("size.csv"));
    assert_eq!(header[..4].join(","), "family,model,input_triangles,faces");
    assert_eq!(rows.len(), 6);
    let triangles: Vec<&str> = rows.iter().map(|r| r[2].as_str()).collect();
    assert_eq!(triangles, ["12", "48", "108", "20", "80", "180"]);
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    for r in &rows {
        for c in &r[5..7] {
            assert!(c.parse::<f64>().unwrap() > 0.0, "{r:?}");
        }
        // brute only up to 100 faces: sphere:3 has 180.
        let brute = r[col("brute_us")].parse::<f64>().unwrap_or(f64::NAN);
        assert_eq!(brute > 0.0, r[3].parse::<usize>().unwrap() <= 100, "{r:?}");
        assert!(
            r[col("changes_per_step")].parse::<f64>().unwrap() >= 0.0,
            "{r:?}"
        );
    }
    // The spheres change facets at every step of 2π/500.
    let sphere3 = &rows[5];
    assert!(sphere3[col("dymsum_ns_per_change")].parse::<f64>().unwrap() > 0.0);
    for name in ["size_vs_brute", "size_dymsum", "size_per_change"] {
        assert_svg(&dir.join(format!("{name}.svg")));
        assert_png(&dir.join(format!("{name}.png")));
    }
    assert!(stdout.contains("fitted growth exponent"), "{stdout}");
    assert!(
        stdout.contains("geodesic sphere sphere:N: DYMSUM k = "),
        "{stdout}"
    );
    assert!(stdout.contains(" 0 mismatches"), "{stdout}");
}

#[test]
fn bad_flags_are_usage_errors() {
    let dir = temp_dir("bad");
    let out = dir.to_str().unwrap();
    for args in [
        &["bench"][..],
        &["bench", "table2"],
        &["bench", "table1", "--steps", "0"],
        &["bench", "table1", "--steps", "many"],
        &["bench", "table1", "--static-poses", "-3"],
        &["bench", "table1", "--frobnicate"],
        &["bench", "rotation", "--steps-per-rev", "0"],
        &["bench", "rotation", "--steps-per-rev", "10,x"],
        &["bench", "rotation", "--pairs", "ellipse"],
        &["bench", "size", "--tcube", "0"],
        &["bench", "size", "--sphere", "1,2,abc"],
    ] {
        let mut a = args.to_vec();
        a.extend(["--out", out]);
        let o = run(&a);
        assert_eq!(o.status.code(), Some(2), "dymsum {a:?}: {:?}", o);
        assert!(!o.stderr.is_empty());
    }
    // An unknown model is bad input (exit 1), named in the message.
    let o = run(&["bench", "rotation", "--pairs", "nosuch+cube", "--out", out]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("nosuch"));
}
