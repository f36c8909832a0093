//! End-to-end tests of `dymsum render`: SVG and PNG are written with the
//! requested size, deterministically, and `--highlight-after` highlights
//! exactly the added facets that face the viewer — counted here
//! independently through the library with the documented rule:
//! a facet is highlighted iff it is in `UpdateReport::added` and its outward
//! unit normal `n` has `n · v > 1e-9`, `v = (cos el cos az, cos el sin az,
//! sin el)` the unit vector towards the viewer.

mod common;

use std::path::Path;

use common::{fixture, model, run, temp_dir};
use dymsum::sum::Facet;
use dymsum::{DVec3, DynamicSum, Polytope, Pose, Rotation};

/// A π/40 turn about the y axis (the paper's Fig. 1), as `W,X,Y,Z`.
fn pi_over_40_about_y() -> String {
    let h = std::f64::consts::PI / 80.0;
    format!("{},0,{},0", h.cos(), h.sin())
}

/// Runs `dymsum render ARGS -o OUT` and asserts success.
fn render(args: &[&str], out: &Path) -> String {
    let mut all: Vec<&str> = vec!["render"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", out.to_str().unwrap()]);
    let o = run(&all);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "dymsum {all:?} failed: {err}");
    assert!(!err.contains("panicked"), "{err}");
    String::from_utf8(o.stdout).unwrap()
}

fn assert_exit(args: &[&str], code: i32) {
    let o = run(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(code), "dymsum {args:?}: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!err.is_empty(), "dymsum {args:?}: no message");
}

fn count(svg: &str, needle: &str) -> usize {
    svg.matches(needle).count()
}

fn rotation(wxyz: &str) -> Rotation {
    let v: Vec<f64> = wxyz.split(',').map(|s| s.trim().parse().unwrap()).collect();
    Rotation::from_wxyz(v[0], v[1], v[2], v[3]).unwrap()
}

/// The unit vector towards the viewer for a view in degrees.
fn toward(azimuth: f64, elevation: f64) -> DVec3 {
    let (sa, ca) = azimuth.to_radians().sin_cos();
    let (se, ce) = elevation.to_radians().sin_cos();
    DVec3::new(ce * ca, ce * sa, se)
}

/// Outward unit normal of a facet of the posed sum (zero for a degenerate
/// ee-facet), computed from the public API.
fn facet_normal(p: &Polytope, pp: &Pose, q: &Polytope, pq: &Pose, facet: Facet) -> DVec3 {
    let np = |f: u32| pp.rotation.apply(p.unit_normal(f as usize));
    let nq = |g: u32| pq.rotation.apply(q.unit_normal(g as usize));
    match facet {
        Facet::Fv { p_face, .. } => np(p_face).normalize_or_zero(),
        Facet::Vf { q_face, .. } => nq(q_face).normalize_or_zero(),
        Facet::Ee { p_edge, q_edge } => {
            let (e, e2) = (p.edge(p_edge as usize), q.edge(q_edge as usize));
            let d1 = pp.apply(p.vertex(e.vertices[1] as usize))
                - pp.apply(p.vertex(e.vertices[0] as usize));
            let d2 = pq.apply(q.vertex(e2.vertices[1] as usize))
                - pq.apply(q.vertex(e2.vertices[0] as usize));
            let n = d1.cross(d2).normalize_or_zero();
            let inside = np(e.faces[0]) + np(e.faces[1]) + nq(e2.faces[0]) + nq(e2.faces[1]);
            if n.dot(inside) < 0.0 {
                -n
            } else {
                n
            }
        }
    }
}

/// `(added, highlighted)`: the facets the turn adds and those of them that
/// face the viewer.
fn expected(p: &str, q: &str, rotate_p: &str, after: &str, view: (f64, f64)) -> (usize, usize) {
    let (p, q) = (model(p), model(q));
    let pose = Pose::new(rotation(rotate_p), DVec3::ZERO);
    let mut s = DynamicSum::new(&p, pose, &q, Pose::IDENTITY).unwrap();
    let report = s.rotate_p_by(rotation(after));
    let (pp, pq) = (s.pose_p(), s.pose_q());
    let v = toward(view.0, view.1);
    let front = report
        .added
        .iter()
        .filter(|&&f| facet_normal(&p, &pp, &q, &pq, f).dot(v) > 1e-9)
        .count();
    (report.added.len(), front)
}

/// Width and height from a PNG's IHDR chunk, after checking the signature.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    assert_eq!(&bytes[12..16], b"IHDR");
    let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    (w, h)
}

/// Decoded RGB pixels of a PNG written by `dymsum render`.
fn png_pixels(path: &Path) -> Vec<[u8; 3]> {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf[..info.buffer_size()]
        .chunks(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect()
}

fn reddish(px: &[[u8; 3]]) -> usize {
    px.iter()
        .filter(|c| c[0] as i32 > c[1] as i32 + 60 && c[0] as i32 > c[2] as i32 + 60)
        .count()
}

const POSE: &str = "0.9,0.2,0.3,0.1";

#[test]
fn writes_svg_and_png_of_the_requested_size() {
    let dir = temp_dir("size");
    let svg = dir.join("s.svg");
    let stdout = render(&["cube", "gs2", "--size", "240"], &svg);
    assert!(stdout.contains("faces"), "{stdout}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<?xml"));
    assert!(text.contains(r#"width="240" height="240" viewBox="0 0 240 240""#));
    assert!(text.trim_end().ends_with("</svg>"));
    let faces = count(&text, r#"class="face""#);
    assert!(faces > 10, "{faces} faces drawn");
    assert_eq!(
        count(&text, r#"class="edge""#),
        faces,
        "one outline per face"
    );
    // Upper-case extension, non-square view, PNG.
    let png = dir.join("s.PNG");
    render(&["cube", "gs2", "--size", "123", "--view", "-60,45"], &png);
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(png_size(&bytes), (123, 123));
    let px = png_pixels(&png);
    assert_eq!(px.len(), 123 * 123);
    // Corners are background, the centre is the (shaded, not white) sum.
    assert_eq!(px[0], [255, 255, 255]);
    assert_ne!(px[61 * 123 + 61], [255, 255, 255]);
}

#[test]
fn front_faces_are_the_faces_facing_the_viewer() {
    // A unit cube seen from azimuth 30°, elevation 20°: three faces.
    let dir = temp_dir("cube");
    let svg = dir.join("c.svg");
    render(&["box", "box"], &svg);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(count(&text, r#"class="face""#), 3);
    // Straight from above: one.
    render(&["box", "box", "--view", "0,90"], &svg);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(count(&text, r#"class="face""#), 1);
}

#[test]
fn output_is_deterministic() {
    let dir = temp_dir("det");
    let turn = pi_over_40_about_y();
    for ext in ["svg", "png"] {
        let a = dir.join(format!("a.{ext}"));
        let b = dir.join(format!("b.{ext}"));
        let args = [
            "ellipse",
            "gs4",
            "--rotate-p-wxyz",
            POSE,
            "--highlight-after-wxyz",
            &turn,
            "--size",
            "300",
        ];
        let out_a = render(&args, &a);
        let out_b = render(&args, &b);
        let (ba, bb) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
        assert!(!ba.is_empty());
        assert!(ba == bb, "{ext}: two runs differ");
        assert_eq!(
            out_a.replace("a.", "x."),
            out_b.replace("b.", "x."),
            "stdout differs"
        );
    }
}

#[test]
fn highlights_exactly_the_added_front_facets() {
    let dir = temp_dir("hl");
    let turn = pi_over_40_about_y();
    // (P, Q, --rotate-p, --highlight-after, --view)
    let cases = [
        // The paper's Fig. 1, from the default view and from below.
        ["ellipse", "gs4", POSE, &turn, "30,20"],
        ["ellipse", "gs4", POSE, &turn, "-120,-35"],
        // Degenerate start (parallel faces everywhere), small turn.
        ["cube", "cube", "1,0,0,0", "0.999,0.01,0.02,0.03", "30,20"],
        // A large turn: recomputed from scratch, still reported.
        ["random:60:3", "gs2", POSE, "0.5,0.5,-0.5,0.5", "10,60"],
    ];
    for [p, q, rot, after, view_arg] in cases {
        let v: Vec<f64> = view_arg.split(',').map(|x| x.parse().unwrap()).collect();
        let view = (v[0], v[1]);
        let (added, front) = expected(p, q, rot, after, view);
        let svg = dir.join("h.svg");
        let stdout = render(
            &[
                p,
                q,
                "--rotate-p-wxyz",
                rot,
                "--highlight-after-wxyz",
                after,
                "--view",
                view_arg,
            ],
            &svg,
        );
        let text = std::fs::read_to_string(&svg).unwrap();
        let got = count(&text, r#"class="changed""#);
        assert_eq!(
            got, front,
            "{p} ⊕ {q} after {after} from {view_arg}: {added} added"
        );
        assert!(front > 0, "{p} ⊕ {q}: nothing to highlight");
        assert!(front < added, "{p} ⊕ {q}: some added facets face away");
        assert!(
            stdout.contains(&format!("added {added} facets, {front} highlighted")),
            "{stdout}"
        );
    }
}

#[test]
fn no_highlight_without_the_flag_or_without_a_turn() {
    let dir = temp_dir("none");
    let svg = dir.join("n.svg");
    render(&["ellipse", "gs4", "--rotate-p-wxyz", POSE], &svg);
    let plain = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(count(&plain, r#"class="changed""#), 0);
    render(
        &[
            "ellipse",
            "gs4",
            "--rotate-p-wxyz",
            POSE,
            "--highlight-after-wxyz",
            "1,0,0,0",
        ],
        &svg,
    );
    let still = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(count(&still, r#"class="changed""#), 0);
    assert_eq!(plain, still, "an identity turn changes nothing");

    // In the PNG: red only with a real turn.
    let a = dir.join("a.png");
    let b = dir.join("b.png");
    render(
        &["ellipse", "gs4", "--rotate-p-wxyz", POSE, "--size", "200"],
        &a,
    );
    let turn = pi_over_40_about_y();
    render(
        &[
            "ellipse",
            "gs4",
            "--rotate-p-wxyz",
            POSE,
            "--size",
            "200",
            "--highlight-after-wxyz",
            &turn,
        ],
        &b,
    );
    assert_eq!(reddish(&png_pixels(&a)), 0);
    assert!(reddish(&png_pixels(&b)) > 50);
}

#[test]
fn translation_and_files_are_accepted() {
    let dir = temp_dir("files");
    let svg = dir.join("t.svg");
    let cube = fixture("cube.off");
    render(
        &[
            &cube,
            "tetra",
            "--translate-p",
            "-5,2,1e1",
            "--highlight-after-wxyz",
            "0.9,0.1,0,0",
        ],
        &svg,
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(count(&text, r#"class="face""#) > 0);
}

#[test]
fn bad_arguments_exit_2() {
    let dir = temp_dir("usage");
    let svg = dir.join("u.svg");
    let o = svg.to_str().unwrap();
    for args in [
        vec!["render", "cube", "cube", "-o", "x.txt"],
        vec!["render", "cube", "cube", "-o", "noext"],
        vec!["render", "cube", "cube"],
        vec!["render", "cube", "-o", o],
        vec!["render", "cube", "cube", "-o", o, "--size", "0"],
        vec!["render", "cube", "cube", "-o", o, "--size", "big"],
        vec!["render", "cube", "cube", "-o", o, "--view", "10"],
        vec!["render", "cube", "cube", "-o", o, "--view", "0,91"],
        vec!["render", "cube", "cube", "-o", o, "--view", "nan,0"],
        vec!["render", "cube", "cube", "-o", o, "--rotate-p-wxyz", "1,2"],
        vec![
            "render",
            "cube",
            "cube",
            "-o",
            o,
            "--highlight-after-wxyz",
            "0,0,0,0",
        ],
        vec![
            "render",
            "cube",
            "cube",
            "-o",
            o,
            "--translate-p",
            "1,2,inf",
        ],
        vec!["render", "cube", "cube", "-o", o, "--bogus"],
    ] {
        assert_exit(&args, 2);
    }
    assert!(!svg.exists(), "nothing written on a usage error");
}

#[test]
fn bad_inputs_exit_1() {
    let dir = temp_dir("input");
    let svg = dir.join("i.svg");
    let o = svg.to_str().unwrap();
    let missing = dir.join("missing.off");
    let dent = fixture("cube_dent.off");
    let open = fixture("cube_open.off");
    // A file where the output folder should be (a missing folder is created).
    std::fs::write(dir.join("file"), "x").unwrap();
    let nodir = dir.join("file/dir/x.svg");
    for args in [
        vec!["render", "nosuchmodel", "cube", "-o", o],
        vec!["render", "cube", missing.to_str().unwrap(), "-o", o],
        vec!["render", &dent, "cube", "-o", o],
        vec!["render", "cube", &open, "-o", o],
        vec!["render", "cube", "cube", "-o", nodir.to_str().unwrap()],
    ] {
        assert_exit(&args, 1);
    }
    assert!(!svg.exists(), "nothing written on bad input");
}
