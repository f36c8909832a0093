//! `dymsum models`: the built-in model catalogue as a table, or with
//! `--write NAME FILE` one model written as a mesh file, exactly as dymsum
//! uses it (after validation: maximal faces, outward, the exact hull where
//! the built-in mesh is convex only within tolerance).

use std::io::Write;
use std::path::PathBuf;

use anyhow::{anyhow, Context};
use clap::Args;
use dymsum_io::models::catalogue;

/// Arguments of `dymsum models`.
#[derive(Debug, Args)]
pub struct ModelsArgs {
    /// Write the model NAME (any spec `dymsum models` accepts, e.g. `ellipse`,
    /// `box:1,2,3`, `tcube:10`) to FILE, in the format its extension names
    /// (`-`: OFF on standard output), instead of listing the models.
    #[arg(long, num_args = 2, value_names = ["NAME", "FILE"])]
    pub write: Option<Vec<String>>,
}

/// Runs `dymsum models`.
///
/// # Errors
/// With `--write NAME FILE`: FILE has no mesh extension, NAME is no model
/// or has bad parameters ([`dymsum_io::models::ModelError`]), the model's
/// mesh fails its exact check (internal), or the file cannot be written.
/// Always: writing to `out` fails.
pub fn run(a: &ModelsArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    match a.write.as_deref() {
        Some([name, file]) => write_model(name, file, out),
        Some(_) => Err(anyhow!("--write takes NAME FILE")),
        None => list(out),
    }
}

fn write_model(name: &str, file: &str, out: &mut dyn Write) -> anyhow::Result<()> {
    let path: PathBuf = crate::values::parse_output_path(file).map_err(|e| anyhow!("FILE: {e}"))?;
    // Only a model (never a file of that name); an unknown name or a bad
    // parameter says why.
    let model = dymsum_io::models::model(name).map_err(|e| anyhow!("NAME: {e}"))?;
    let loaded = dymsum_io::load_mesh(model, format!("built-in {name}"), super::policy(false))
        .map_err(|e| anyhow!(e.for_operand("NAME")))?;
    let mesh = loaded.polytope.to_mesh();
    dymsum::sum::validate::check_convex_mesh(&mesh)
        .map_err(|e| anyhow!("internal: the mesh of model {name} is not valid: {e}"))?;
    super::write_mesh_or_stdout(&path, &mesh, out)
        .with_context(|| format!("writing model {name}"))?;
    if path.as_os_str() != super::STDIO {
        writeln!(
            out,
            "{name}: {} vertices, {} faces written to {}",
            mesh.vertices.len(),
            mesh.faces.len(),
            path.display()
        )?;
    }
    Ok(())
}

fn list(out: &mut dyn Write) -> anyhow::Result<()> {
    let cat = catalogue();
    let width = cat.iter().map(|m| m.name.len()).max().unwrap_or(4).max(4);
    writeln!(out, "{:<width$}  {:>9}  DESCRIPTION", "NAME", "PAPER TRI")?;
    for m in &cat {
        let tris = m
            .paper_triangles
            .map(|t| t.to_string())
            .unwrap_or_else(|| "-".to_string());
        writeln!(out, "{:<width$}  {:>9}  {}", m.name, tris, m.description)?;
    }
    let paper = cat.iter().filter(|m| m.paper_triangles.is_some()).count();
    writeln!(
        out,
        "\n{paper} models from the paper (PAPER TRI = triangles in the paper's Table 1); \
         families take parameters after colons, e.g. tcube:10, box:1,2,3, random:1000:7. \
         `dymsum models --write NAME FILE` writes one as a mesh file."
    )?;
    Ok(())
}
