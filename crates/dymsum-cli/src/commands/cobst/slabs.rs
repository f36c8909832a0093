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
//!
//! With `--cell-radius RHO`, slab `k` is instead the slab of the orientation
//! cell about orientation `k` ([`dymsum::CObstacle::certified_slabs_in_cells_par`]):
//! it contains every slice for every rotation within angle `RHO` of it
//! (one slab per orientation; its index entry has `"centre_wxyz"` and
//! `"radius"` in place of the ends, with `--axis` also `"angle"`).

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

/// The orientations the slabs cover.
#[derive(Clone, Copy, Debug)]
pub enum Cells<'a> {
    /// Slab `k` between `orientations[k]` and `orientations[k + 1]`
    /// (`angles`, when given, their angles about the axis).
    Between {
        /// The orientations.
        orientations: &'a [Rotation],
        /// Their angles about `--axis`.
        angles: Option<&'a [f64]>,
    },
    /// Slab `k` of the rotations within angle `radius` of `centres[k]`.
    Around {
        /// The cells' centres.
        centres: &'a [Rotation],
        /// Their angles about `--axis`.
        angles: Option<&'a [f64]>,
        /// The cells' radius (radians).
        radius: f64,
    },
}

impl Cells<'_> {
    /// The number of slabs.
    fn len(&self) -> usize {
        match self {
            Cells::Between { orientations, .. } => orientations.len().saturating_sub(1),
            Cells::Around { centres, .. } => centres.len(),
        }
    }

    /// The slabs of one piece pair.
    fn slabs(&self, c: &CObstacle) -> Result<Vec<Slab>, dymsum::QueryError> {
        match *self {
            Cells::Between { orientations, .. } => c.certified_slabs_par(orientations),
            Cells::Around {
                centres, radius, ..
            } => c.certified_slabs_in_cells_par(centres, radius),
        }
    }

    /// The index entry of slab `k`, less what was written.
    fn entry(&self, k: usize) -> IndexEntry {
        let mut e = IndexEntry {
            slab: k,
            ..IndexEntry::default()
        };
        match *self {
            Cells::Between {
                orientations,
                angles,
            } => {
                e.from_wxyz = Some(orientations[k].wxyz().map(plain));
                e.to_wxyz = Some(orientations[k + 1].wxyz().map(plain));
                e.from_angle = angles.map(|a| plain(a[k]));
                e.to_angle = angles.map(|a| plain(a[k + 1]));
            }
            Cells::Around {
                centres,
                angles,
                radius,
            } => {
                e.centre_wxyz = Some(centres[k].wxyz().map(plain));
                e.angle = angles.map(|a| plain(a[k]));
                e.radius = Some(radius);
            }
        }
        e
    }
}

/// One entry of `index.json`.
#[derive(Default, Serialize)]
struct IndexEntry {
    slab: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    from_wxyz: Option<[f64; 4]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    to_wxyz: Option<[f64; 4]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    from_angle: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    to_angle: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    centre_wxyz: Option<[f64; 4]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    angle: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    radius: Option<f64>,
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

/// Computes the slabs of `cells` for every piece pair and writes them into
/// `dir` in `format`, with their index.
///
/// # Errors
/// A slab fails ([`dymsum::QueryError`], named by piece pair and slab) or a
/// file cannot be written.
pub fn write_slabs(
    dir: &Path,
    (robot, obstacle): (&[Polytope], &[Polytope]),
    cells: Cells<'_>,
    format: SlabFormat,
) -> anyhow::Result<Written> {
    let union = robot.len() > 1 || obstacle.len() > 1;
    let n = cells.len();
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
                .and_then(|c| cells.slabs(&c))
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
    write_index(dir, cells, format, &written, union)?;
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
    cells: Cells<'_>,
    format: SlabFormat,
    w: &Written,
    union: bool,
) -> anyhow::Result<()> {
    let index: Vec<IndexEntry> = (0..w.planes.len())
        .map(|k| IndexEntry {
            planes: w.planes[k],
            faces: (format == SlabFormat::Off).then_some(w.faces[k]),
            margin: w.margins[k],
            file: (!union).then(|| w.files[k][0].clone()),
            files: union.then(|| w.files[k].clone()),
            ..cells.entry(k)
        })
        .collect();
    let json = serde_json::to_string_pretty(&index)? + "\n";
    dymsum_io::atomic::write_atomic_bytes(&dir.join("index.json"), json.as_bytes())?;
    Ok(())
}
