//! The writers of `dymsum cobst`: slices as OFF files (per piece pair, or
//! merged per slice), as half-spaces, as a map container, and the index.

use super::{CobstArgs, CobstFormat, IndexEntry, MAP_FILE};
use crate::commands::short_name;
use anyhow::{anyhow, Context};
use dymsum::query::CObstacle;
use dymsum::{ConvexUnion, DynamicSum, Polytope, Rotation};
use dymsum_io::cmap::{Form, MapBuilder};
use serde::Serialize;
use std::path::Path;

/// What was written for each slice, over all piece pairs.
pub(super) struct Slices {
    /// Faces of each slice (summed over its piece pairs).
    pub(super) faces: Vec<usize>,
    /// The files of each slice, one per piece pair.
    pub(super) files: Vec<Vec<String>>,
}

/// Writes one OFF file per slice and piece pair into `dir`, the staging folder (named
/// `slice_K.off`, or `slice_K_rI_oJ.off` when a body has several pieces).
pub(super) fn write_slices(
    a: &CobstArgs,
    dir: &Path,
    robot: &[Polytope],
    obstacle: &[Polytope],
    orientations: &[Rotation],
) -> anyhow::Result<Slices> {
    let union = robot.len() > 1 || obstacle.len() > 1;
    let n = orientations.len();
    let bar = crate::progress::bar((n * robot.len() * obstacle.len()) as u64, "cobst", "slices");
    let mut slices = Slices {
        faces: vec![0usize; n],
        files: vec![Vec::new(); n],
    };
    for (i, r) in robot.iter().enumerate() {
        for (j, o) in obstacle.iter().enumerate() {
            let cob = CObstacle::new(r, o).context("reflecting the robot")?;
            let written = cob
                .map_par(orientations, |k, _, sum| {
                    let ext = if a.format == CobstFormat::Halfspaces {
                        "json"
                    } else {
                        "off"
                    };
                    let name = if union {
                        format!("slice_{k:05}_r{i}_o{j}.{ext}")
                    } else {
                        format!("slice_{k:05}.{ext}")
                    };
                    let path = dir.join(&name);
                    let res = if a.format == CobstFormat::Halfspaces {
                        write_slice_halfspaces(sum, &cob, k, &path)
                    } else {
                        write_slice(sum, k, &path)
                    };
                    let res = res.map(|f| (f, name));
                    bar.inc(1);
                    res
                })
                .with_context(|| {
                    format!(
                        "slices of {} against {}",
                        short_name(&a.robot),
                        short_name(&a.obstacle)
                    )
                })?;
            for (k, w) in written.into_iter().enumerate() {
                let (f, name) = w?;
                slices.faces[k] += f;
                slices.files[k].push(name);
            }
        }
    }
    bar.finish_and_clear();
    Ok(slices)
}

/// Writes each slice as the validated union of its piece-pair slices,
/// one closed mesh `slice_K.off` (`--merge`).
pub(super) fn write_merged_slices(
    a: &CobstArgs,
    dir: &Path,
    robot: &[Polytope],
    obstacle: &[Polytope],
    orientations: &[Rotation],
) -> anyhow::Result<Slices> {
    let what = || {
        format!(
            "merged slices of {} against {}",
            short_name(&a.robot),
            short_name(&a.obstacle)
        )
    };
    let union = |pieces: &[Polytope], name: &str| {
        ConvexUnion::new(pieces.to_vec()).ok_or_else(|| anyhow!("{name} has no pieces"))
    };
    let merged = union(robot, "ROBOT")?
        .cobstacle_union_slices(&union(obstacle, "OBSTACLE")?, orientations)
        .with_context(what)?;
    let mut slices = Slices {
        faces: Vec::with_capacity(merged.len()),
        files: Vec::with_capacity(merged.len()),
    };
    for (k, slice) in merged.iter().enumerate() {
        let name = format!("slice_{k:05}.off");
        dymsum_io::formats::write_mesh(&dir.join(&name), slice.mesh())
            .with_context(|| format!("slice {k}"))?;
        slices.faces.push(slice.mesh().faces.len());
        slices.files.push(vec![name]);
    }
    Ok(slices)
}

/// Writes slice `k`'s half-spaces (read from the sum's facets) to `path`
/// as JSON `{"normals": [[x, y, z], ...], "offsets": [d, ...]}`; returns
/// the number of planes.
pub(super) fn write_slice_halfspaces(
    sum: &DynamicSum,
    cob: &CObstacle,
    k: usize,
    path: &Path,
) -> anyhow::Result<usize> {
    let h = cob
        .halfspaces_of(sum)
        .map_err(|e| anyhow::Error::new(e).context(format!("slice {k}")))?;
    #[derive(Serialize)]
    struct Json {
        normals: Vec<[f64; 3]>,
        offsets: Vec<f64>,
    }
    let json = Json {
        normals: h
            .normals()
            .iter()
            .map(|n| n.to_array().map(|x| x + 0.0))
            .collect(),
        offsets: h.offsets().iter().map(|&d| d + 0.0).collect(),
    };
    let text = serde_json::to_string(&json)? + "\n";
    dymsum_io::atomic::write_atomic_bytes(path, text.as_bytes())?;
    Ok(h.len())
}

/// Computes every slice of every piece pair (in parallel over the
/// orientations, DYMSUM within each chunk) and writes them as one map
/// container `DIR/map.npz` of `form`.
pub(super) fn write_map(
    a: &CobstArgs,
    dir: &Path,
    (robot, obstacle): (&[Polytope], &[Polytope]),
    orientations: &[Rotation],
    form: Form,
) -> anyhow::Result<Slices> {
    let n = orientations.len();
    let mut map = MapBuilder::new(
        form,
        false,
        orientations,
        n,
        piece_names("r", robot.len()),
        piece_names("o", obstacle.len()),
    );
    let mut slices = Slices {
        faces: vec![0usize; n],
        files: vec![Vec::new(); n],
    };
    let bar = crate::progress::bar(
        (robot.len() * obstacle.len()) as u64,
        "cobst",
        "piece pairs",
    );
    for (i, r) in robot.iter().enumerate() {
        for (j, o) in obstacle.iter().enumerate() {
            let pair = format!(
                "slices of {} against {} (robot piece {i}, obstacle piece {j})",
                short_name(&a.robot),
                short_name(&a.obstacle)
            );
            let cob = CObstacle::new(r, o).context("reflecting the robot")?;
            map.add_pair(i, j);
            match form {
                Form::HalfSpaces => {
                    let hs = cob.halfspace_slices_par(orientations).context(pair)?;
                    for (k, h) in hs.iter().enumerate() {
                        slices.faces[k] += h.len();
                        map.push_halfspaces(h);
                    }
                }
                Form::Mesh => {
                    let meshes = cob.slices_par(orientations).context(pair)?;
                    for (k, m) in meshes.iter().enumerate() {
                        slices.faces[k] += m.faces.len();
                        map.push_mesh(m);
                    }
                }
            }
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    map.write(&dir.join(MAP_FILE))?;
    Ok(slices)
}

/// `prefix0`, `prefix1`, ...: the names of a body's pieces in a map.
pub(super) fn piece_names(prefix: &str, n: usize) -> Vec<String> {
    (0..n).map(|i| format!("{prefix}{i}")).collect()
}

/// Writes slice `k`, the sum's mesh, to `path`; returns its face count.
pub(super) fn write_slice(sum: &DynamicSum, k: usize, path: &Path) -> anyhow::Result<usize> {
    let mesh = sum
        .try_to_mesh()
        .map_err(|e| anyhow::Error::new(e).context(format!("slice {k}")))?;
    dymsum_io::formats::write_mesh(path, &mesh)?;
    Ok(mesh.faces.len())
}

/// Writes `index.json` into `dir`: per slice its orientation, face count
/// and file (`files` when a body has several pieces).
pub(super) fn write_index(
    dir: &Path,
    orientations: &[Rotation],
    slices: &Slices,
    union: bool,
) -> anyhow::Result<()> {
    let index: Vec<IndexEntry> = orientations
        .iter()
        .enumerate()
        .map(|(k, r)| IndexEntry {
            slice: k,
            orientation_wxyz: r.wxyz().map(|x| x + 0.0),
            faces: slices.faces[k],
            file: (!union).then(|| slices.files[k][0].clone()),
            files: union.then(|| slices.files[k].clone()),
        })
        .collect();
    let json = serde_json::to_string_pretty(&index)? + "\n";
    dymsum_io::atomic::write_atomic_bytes(&dir.join("index.json"), json.as_bytes())?;
    Ok(())
}
