//! `dymsum cobst ... --certified [--format off|halfspaces]`: certified
//! C-obstacle slabs ([`dymsum::query::Slab`]) instead of slices.
//!
//! Slab `k` contains every slice for the orientations between orientation
//! `k` and orientation `k + 1`: with `--axis` and `--slices N`, the turns by
//! every angle in `[2πk/N, 2π(k+1)/N]` (`N` slabs over the full turn, the
//! last ending where the first starts); with `--orientations-wxyz FILE`,
//! the rotations on the shortest path between consecutive orientations
//! (one slab fewer than orientations). Writes `DIR/slab_NNNNN.off` (the
//! slab's mesh, which contains the half-spaces' polytope) or
//! `DIR/slab_NNNNN.json` (`{"normals": [[x, y, z], ...], "offsets": [d,
//! ...]}`: the slab is `{x : n_i·x ≤ d_i}`, unit normals, offsets rounded
//! outward, every float in its shortest round-trip decimal form), and
//! `DIR/index.json`, an array of `{"slab": k, "from_wxyz": [w, x, y, z],
//! "to_wxyz": [...], "planes": n, "margin": m, "file": ...}` (with `--axis`
//! also `"from_angle"` and `"to_angle"`, radians; with `--format off` also
//! `"faces"`). Unions of convex pieces get one slab per piece pair,
//! `slab_NNNNN_rI_oJ.*`, listed under `"files"` (`"planes"` and `"faces"`
//! their totals, `"margin"` the largest). Every file is written
//! atomically.

use std::path::Path;

use anyhow::Context;
use clap::ValueEnum;
use dymsum::query::{slab_meshes_par, Slab};
use dymsum::{CObstacle, Polytope, Rotation};
use serde::Serialize;

/// How `cobst --certified` writes a slab.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SlabFormat {
    /// The slab's mesh, `slab_NNNNN.off`.
    Off,
    /// Its half-spaces, `slab_NNNNN.json`: `{"normals": [[x, y, z], ...],
    /// "offsets": [d, ...]}`.
    Halfspaces,
}

impl SlabFormat {
    fn extension(self) -> &'static str {
        match self {
            SlabFormat::Off => "off",
            SlabFormat::Halfspaces => "json",
        }
    }
}

/// One slab file of `--format halfspaces`.
#[derive(Serialize)]
struct Halfspaces {
    normals: Vec<[f64; 3]>,
    offsets: Vec<f64>,
}

/// One entry of `index.json`.
#[derive(Serialize)]
struct IndexEntry {
    slab: usize,
    from_wxyz: [f64; 4],
    to_wxyz: [f64; 4],
    #[serde(skip_serializing_if = "Option::is_none")]
    from_angle: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    to_angle: Option<f64>,
    planes: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    faces: Option<usize>,
    margin: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    file: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    files: Option<Vec<String>>,
}

/// What was written: per slab its planes, faces, largest margin and files.
pub struct Written {
    /// Planes of each slab (summed over piece pairs).
    pub planes: Vec<usize>,
    /// Faces of each slab's meshes (summed; `--format off` only).
    pub faces: Vec<usize>,
    /// The largest margin of each slab over its piece pairs.
    pub margins: Vec<f64>,
    files: Vec<Vec<String>>,
}

/// `-0.0` written as `0`.
fn plain(x: f64) -> f64 {
    x + 0.0
}

/// Computes the slabs between consecutive `orientations` for every piece
/// pair and writes them into `dir` in `format`, with their index
/// (`angles`, when given, are the orientations' angles about the axis).
///
/// # Errors
/// A slab fails ([`dymsum::QueryError`], named by piece pair and slab) or a
/// file cannot be written.
pub fn write_slabs(
    dir: &Path,
    (robot, obstacle): (&[Polytope], &[Polytope]),
    orientations: &[Rotation],
    angles: Option<&[f64]>,
    format: SlabFormat,
) -> anyhow::Result<Written> {
    let union = robot.len() > 1 || obstacle.len() > 1;
    let n = orientations.len().saturating_sub(1);
    let mut written = Written {
        planes: vec![0; n],
        faces: vec![0; n],
        margins: vec![0.0; n],
        files: vec![Vec::new(); n],
    };
    let bar = crate::progress::bar(
        (robot.len() * obstacle.len()) as u64,
        "cobst --certified",
        "piece pairs",
    );
    for (i, r) in robot.iter().enumerate() {
        for (j, o) in obstacle.iter().enumerate() {
            let pair = if union {
                format!(" (robot piece {i}, obstacle piece {j})")
            } else {
                String::new()
            };
            let slabs = CObstacle::new(r, o)
                .and_then(|c| c.certified_slabs_par(orientations))
                .with_context(|| format!("certified slabs{pair}"))?;
            let meshes = match format {
                SlabFormat::Off => {
                    Some(slab_meshes_par(&slabs).with_context(|| format!("slab meshes{pair}"))?)
                }
                SlabFormat::Halfspaces => None,
            };
            for (k, slab) in slabs.iter().enumerate() {
                let name = if union {
                    format!("slab_{k:05}_r{i}_o{j}.{}", format.extension())
                } else {
                    format!("slab_{k:05}.{}", format.extension())
                };
                let path = dir.join(&name);
                match &meshes {
                    Some(m) => {
                        dymsum_io::formats::write_mesh(&path, &m[k])?;
                        written.faces[k] += m[k].faces.len();
                    }
                    None => write_halfspaces(&path, slab)?,
                }
                written.planes[k] += slab.len();
                written.margins[k] = written.margins[k].max(slab.margin());
                written.files[k].push(name);
            }
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    write_index(dir, orientations, angles, format, &written, union)?;
    Ok(written)
}

/// Writes one slab's half-spaces as JSON.
fn write_halfspaces(path: &Path, slab: &Slab) -> anyhow::Result<()> {
    let h = Halfspaces {
        normals: slab
            .normals()
            .iter()
            .map(|n| n.to_array().map(plain))
            .collect(),
        offsets: slab.offsets().iter().map(|&d| plain(d)).collect(),
    };
    let json = serde_json::to_string(&h)? + "\n";
    dymsum_io::atomic::write_atomic_bytes(path, json.as_bytes())?;
    Ok(())
}

/// Writes `index.json`.
fn write_index(
    dir: &Path,
    orientations: &[Rotation],
    angles: Option<&[f64]>,
    format: SlabFormat,
    w: &Written,
    union: bool,
) -> anyhow::Result<()> {
    let index: Vec<IndexEntry> = (0..w.planes.len())
        .map(|k| IndexEntry {
            slab: k,
            from_wxyz: orientations[k].wxyz().map(plain),
            to_wxyz: orientations[k + 1].wxyz().map(plain),
            from_angle: angles.map(|a| plain(a[k])),
            to_angle: angles.map(|a| plain(a[k + 1])),
            planes: w.planes[k],
            faces: (format == SlabFormat::Off).then_some(w.faces[k]),
            margin: w.margins[k],
            file: (!union).then(|| w.files[k][0].clone()),
            files: union.then(|| w.files[k].clone()),
        })
        .collect();
    let json = serde_json::to_string_pretty(&index)? + "\n";
    dymsum_io::atomic::write_atomic_bytes(&dir.join("index.json"), json.as_bytes())?;
    Ok(())
}
