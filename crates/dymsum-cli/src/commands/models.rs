//! `dymsum models`: the built-in model catalogue as a table.

use std::io::Write;

use dymsum_io::models::catalogue;

/// Runs `dymsum models`.
pub fn run(out: &mut dyn Write) -> anyhow::Result<()> {
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
         families take parameters after colons, e.g. tcube:10, box:1,2,3, random:1000:7."
    )?;
    Ok(())
}
