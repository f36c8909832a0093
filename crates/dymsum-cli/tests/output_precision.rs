//! Issue 8 §1/§3 through the binary: every written sum is an exactly convex
//! closed mesh that the strict reader accepts; coordinates that cannot hold
//! the sum faithfully are warned about (coarse) or refused (collapsed) with
//! exit 1 and nothing written; queries stay finite far from the origin.

mod common;

use common::{assert_fails, ok, run, stderr, temp_dir};
use dymsum::polytope::MeshPolicy;
use dymsum_io::formats::read_mesh;

fn s(p: &std::path::Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn coarse_output_is_written_valid_with_a_warning() {
    let dir = temp_dir("coarse");
    let out = dir.join("far.off");
    // A unit-sized sum at 1e15: f64 keeps a step of 1/8 there.
    let o = run(&[
        "sum",
        "cube",
        "cube",
        "-o",
        s(&out),
        "--translate-p=1e15,0,0",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("warning: the sum: coordinates lose precision"),
        "{err}"
    );
    let mesh = read_mesh(&out).unwrap();
    dymsum::sum::validate::check_convex_mesh(&mesh).unwrap();
    dymsum::Polytope::from_mesh(&mesh, MeshPolicy::strict()).unwrap();
    ok(&["info", s(&out), "--strict"]);
}

#[test]
fn exact_output_has_no_warning() {
    let dir = temp_dir("fine");
    let out = dir.join("near.off");
    let o = run(&["sum", "cube", "cube", "-o", s(&out), "--translate-p=3,0,0"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
}

#[test]
fn collapsed_output_is_refused_and_not_written() {
    let dir = temp_dir("collapsed");
    for t in ["--translate-p=1e17,0,0", "--translate-p=1e308,0,0"] {
        let out = dir.join("gone.off");
        let o = run(&["sum", "cube", "cube", "-o", s(&out), t]);
        // Bad input for f64 output (exit 1), not an internal error (exit 3).
        assert_fails(&o, 1, "lose all precision");
        assert!(!out.exists(), "{t}: nothing may be written");
    }
}

fn json_distance(x: &str) -> f64 {
    let pose = format!("{x},0,0,1,0,0,0");
    let o = run(&["query", "cube", "cube", "--pose", &pose, "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(!text.contains("null"), "{text}");
    let v: serde_json::Value = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    v["distance"].as_f64().unwrap()
}

#[test]
fn query_far_from_the_origin_is_finite() {
    // The gap is the offset minus the cube's width; at 1e15 f64 rounds to
    // steps of 1/8, so the same width must come out to within a few steps.
    let width = 100.0 - json_distance("100");
    assert!(width > 0.0 && width < 10.0, "{width}");
    let d = json_distance("1e15");
    assert!(
        d.is_finite() && (d - (1e15 - width)).abs() <= 0.5,
        "{d} vs width {width}"
    );
}
