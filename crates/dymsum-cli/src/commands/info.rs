//! `dymsum info FILE|NAME [--json]`: counts, volume and what validation
//! changed (the convexity report).

use std::io::Write;

use clap::Args;
use dymsum::polytope::ConvexityReport;
use dymsum_io::Loaded;
use serde::Serialize;

use super::solid::load_single_body;
use crate::stats::short;

/// `dymsum info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// A mesh file or a built-in model name.
    #[arg(value_name = "FILE|NAME")]
    pub spec: String,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Refuse meshes that are convex only within tolerance.
    #[arg(long)]
    pub strict: bool,
}

/// The machine-readable form of `dymsum info`.
#[derive(Debug, Serialize)]
pub struct Info {
    /// The operand as given.
    pub spec: String,
    /// `"file foo.off"` or `"built-in ellipse"`.
    pub source: String,
    /// `"mesh"` or `"points"` (a point cloud, whose hull was taken).
    pub input_kind: &'static str,
    /// Vertices of the input.
    pub input_vertices: usize,
    /// Faces (polygons) of the input.
    pub input_faces: usize,
    /// Triangles of the input's fan triangulation.
    pub input_triangles: usize,
    /// Vertices of the polytope.
    pub vertices: usize,
    /// Edges of the polytope.
    pub edges: usize,
    /// Maximal faces of the polytope.
    pub faces: usize,
    /// Volume.
    pub volume: f64,
    /// Bounding-box diagonal.
    pub diameter: f64,
    /// The convexity report (`null` for a point cloud).
    pub convexity: Option<ConvexityReport>,
}

impl Info {
    /// Gathers the information about a loaded operand.
    pub fn new(spec: &str, l: &Loaded) -> Info {
        let p = &l.polytope;
        Info {
            spec: spec.to_string(),
            source: l.source.clone(),
            input_kind: if l.is_point_cloud() { "points" } else { "mesh" },
            input_vertices: l.input.vertices.len(),
            input_faces: l.input.faces.len(),
            input_triangles: l.input.triangle_count(),
            vertices: p.vertex_count(),
            edges: p.edge_count(),
            faces: p.face_count(),
            volume: p.volume(),
            diameter: p.diameter(),
            convexity: l.report.clone(),
        }
    }
}

/// Runs `dymsum info`.
///
/// # Errors
/// The input cannot be loaded ([`super::solid::load_single_body`]), or writing the report to
/// `out` fails.
pub fn run(a: &InfoArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    let loaded = load_single_body(&a.spec, "input", a.strict, "info")?;
    let info = Info::new(&a.spec, &loaded);
    if a.json {
        serde_json::to_writer_pretty(&mut *out, &info)?;
        writeln!(out)?;
        return Ok(());
    }
    write_counts(out, &info)?;
    if let Some(c) = &info.convexity {
        write_convexity(out, c)?;
    }
    Ok(())
}

/// One `key: value` line of the text report.
fn row(out: &mut dyn Write, k: &str, v: String) -> std::io::Result<()> {
    writeln!(out, "{k:<18}{v}")
}

/// The source, counts, input, volume and diameter lines.
fn write_counts(out: &mut dyn Write, info: &Info) -> std::io::Result<()> {
    row(out, "source:", info.source.clone())?;
    row(out, "vertices:", info.vertices.to_string())?;
    row(out, "edges:", info.edges.to_string())?;
    row(out, "faces:", info.faces.to_string())?;
    row(
        out,
        "input:",
        if info.input_kind == "points" {
            format!(
                "{} points (a point cloud: the polytope is its exact hull)",
                info.input_vertices
            )
        } else {
            format!(
                "{} vertices, {} faces, {} triangles",
                info.input_vertices, info.input_faces, info.input_triangles
            )
        },
    )?;
    row(out, "volume:", short(info.volume))?;
    row(
        out,
        "diameter:",
        format!("{} (bounding-box diagonal)", short(info.diameter)),
    )
}

/// What validation found and changed: the convexity lines.
fn write_convexity(out: &mut dyn Write, c: &ConvexityReport) -> std::io::Result<()> {
    let verdict = if c.exactly_convex {
        "exactly convex (kept as is; coplanar faces merged)".to_string()
    } else if c.replaced_by_hull {
        "convex within tolerance: replaced by hull (the exact hull of its vertices)".to_string()
    } else {
        "convex".to_string()
    };
    row(out, "convexity:", verdict)?;
    row(
        out,
        "max deviation:",
        if c.max_deviation == 0.0 {
            format!("0 (tolerance {:.3e})", c.tolerance)
        } else {
            format!("{:.3e} (tolerance {:.3e})", c.max_deviation, c.tolerance)
        },
    )?;
    row(out, "dropped vertices:", c.dropped_vertices.to_string())?;
    row(
        out,
        "orientation:",
        if c.inward_oriented {
            "inward in the input (flipped to outward)".to_string()
        } else {
            "outward".to_string()
        },
    )
}
