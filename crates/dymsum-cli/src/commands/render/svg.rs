//! The scene as a plain SVG document (no text, no fonts).

use std::fmt::Write;

use super::scene::{Scene, Shape, BACKGROUND_RGB, CHANGED_EDGE_RGB, EDGE_RGB};

/// A coordinate with two decimals, never `-0.00`.
fn num(x: f64) -> String {
    let s = format!("{x:.2}");
    if s == "-0.00" {
        "0.00".to_string()
    } else {
        s
    }
}

fn hex(c: [u8; 3]) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

fn points(s: &Shape) -> String {
    let mut out = String::with_capacity(s.points.len() * 16);
    for (i, p) in s.points.iter().enumerate() {
        if i > 0 {
            out.push(' ');
        }
        out.push_str(&num(p[0]));
        out.push(',');
        out.push_str(&num(p[1]));
    }
    out
}

/// Escapes text for XML character data.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The SVG document. Faces are `<polygon class="face">`, highlighted facets
/// `<polygon class="changed">`, face outlines `<polygon class="edge">`.
pub fn to_svg(scene: &Scene, title: &str) -> String {
    let n = scene.size;
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{n}" height="{n}" viewBox="0 0 {n} {n}">"#
    );
    let _ = writeln!(s, "<title>{}</title>", escape(title));
    let _ = writeln!(
        s,
        r#"<rect width="{n}" height="{n}" fill="{}"/>"#,
        hex(BACKGROUND_RGB)
    );
    let _ = writeln!(s, r#"<g id="faces" stroke="none">"#);
    for f in &scene.faces {
        let _ = writeln!(
            s,
            r#"<polygon class="face" fill="{}" points="{}"/>"#,
            hex(f.fill),
            points(f)
        );
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r#"<g id="changed" stroke="{}" stroke-width="{}" stroke-linejoin="round">"#,
        hex(CHANGED_EDGE_RGB),
        num(scene.changed_edge_width)
    );
    for f in &scene.changed {
        let _ = writeln!(
            s,
            r#"<polygon class="changed" fill="{}" points="{}"/>"#,
            hex(f.fill),
            points(f)
        );
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r#"<g id="edges" fill="none" stroke="{}" stroke-width="{}" stroke-linejoin="round">"#,
        hex(EDGE_RGB),
        num(scene.edge_width)
    );
    for f in &scene.faces {
        let _ = writeln!(s, r#"<polygon class="edge" points="{}"/>"#, points(f));
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(s, "</svg>");
    s
}
