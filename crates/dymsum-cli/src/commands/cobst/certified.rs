//! `dymsum cobst --certified`: certified slabs between consecutive
//! orientations or in cells, as meshes, half-spaces or a map container.

use super::slabs::{write_slabs, Cells, SlabFormat};
use super::write::piece_names;
use super::{commit_out_dir, prepare_out_dir, read_orientations, CobstArgs, CobstFormat, MAP_FILE};
use crate::commands::short_name;
use crate::stats::{human_us, micros};
use anyhow::{anyhow, bail, Context};
use dymsum::query::{full_turn_angles, orientations_about_axis, rotations_about_axis, CObstacle};
use dymsum::{Polytope, Rotation};
use dymsum_io::cmap::{Form, MapBuilder};
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// `dymsum cobst --certified`: the slabs between consecutive orientations
/// (`--slices N` about `--axis`: the angles `2πk/N` for `k = 0..=N`, so the
/// `N` slabs close the turn), or with `--cell-radius` the slabs of the
/// cells about each orientation (`--slices N`: the angles `2πk/N` for
/// `k = 0..N`).
pub(super) fn run_certified(
    a: &CobstArgs,
    bodies: (&[Polytope], &[Polytope]),
    out: &mut dyn Write,
) -> anyhow::Result<()> {
    let (orientations, angles) = match (&a.orientations, a.axis, a.slices) {
        (Some(file), _, _) => (read_orientations(file)?, None),
        (None, Some(axis), Some(n)) => {
            let mut angles = full_turn_angles(n as usize);
            if a.cell_radius.is_some() {
                // One cell per orientation: the full turn's end is its start.
                angles.pop();
                let turns = orientations_about_axis(axis, n as usize)
                    .ok_or_else(|| anyhow!("--axis must be a non-zero vector"))?;
                (turns, Some(angles))
            } else {
                let turns = rotations_about_axis(axis, &angles).context("--axis with --slices")?;
                (turns, Some(angles))
            }
        }
        _ => bail!("give --axis X,Y,Z with --slices N, or --orientations-wxyz FILE"),
    };
    if a.format == CobstFormat::NpzMesh {
        bail!(
            "--format npz-mesh with --certified: the map holds slabs as half-spaces only; \
             use --format npz, or --format off for one mesh per slab"
        );
    }
    if a.format == CobstFormat::Npz && a.cell_radius.is_some() {
        bail!(
            "--format npz with --cell-radius: the map container holds slabs between \
             consecutive orientations only; use --format halfspaces or off for cell slabs"
        );
    }
    let cells = match a.cell_radius {
        Some(radius) => Cells::Around {
            centres: &orientations,
            angles: angles.as_deref(),
            radius,
        },
        None => Cells::Between {
            orientations: &orientations,
            angles: angles.as_deref(),
        },
    };
    let staged = prepare_out_dir(&a.out, a.force)?;
    let dir = staged.path();
    let start = Instant::now();
    let what = || {
        format!(
            "slabs of {} against {}",
            short_name(&a.robot),
            short_name(&a.obstacle)
        )
    };
    let (planes, margins) = match a.format {
        CobstFormat::Npz => write_slab_map(dir, bodies, &orientations).with_context(what)?,
        f => {
            let f = if f == CobstFormat::Off {
                SlabFormat::Off
            } else {
                SlabFormat::Halfspaces
            };
            let w = write_slabs(dir, bodies, cells, f).with_context(what)?;
            (w.planes, w.margins)
        }
    };
    commit_out_dir(staged)?;
    let elapsed = micros(start.elapsed());
    let planes = &planes;
    let (lo, hi) = (
        planes.iter().min().copied().unwrap_or(0),
        planes.iter().max().copied().unwrap_or(0),
    );
    let margin = margins.iter().copied().fold(0.0, f64::max);
    let pairs = bodies.0.len() * bodies.1.len();
    writeln!(
        out,
        "Certified C-obstacle slabs of {} among {}: {} slab{}{} ({} piece pair{}), {lo}–{hi} \
         planes per slab, margin ≤ {margin:.3e}, written to {} in {}",
        short_name(&a.robot),
        short_name(&a.obstacle),
        planes.len(),
        if planes.len() == 1 { "" } else { "s" },
        a.cell_radius
            .map(|r| format!(" for cells of radius {r} rad"))
            .unwrap_or_default(),
        pairs,
        if pairs == 1 { "" } else { "s" },
        a.out.display(),
        human_us(elapsed),
    )?;
    Ok(())
}

/// The certified slabs of every piece pair between consecutive
/// `orientations`, as half-spaces in `dir/map.npz`; returns the planes
/// (summed over the pairs) and the largest margin of each slab.
pub(super) fn write_slab_map(
    dir: &Path,
    (robot, obstacle): (&[Polytope], &[Polytope]),
    orientations: &[Rotation],
) -> anyhow::Result<(Vec<usize>, Vec<f64>)> {
    let n = orientations.len().saturating_sub(1);
    let mut map = MapBuilder::new(
        Form::HalfSpaces,
        true,
        orientations,
        n,
        piece_names("r", robot.len()),
        piece_names("o", obstacle.len()),
    );
    let (mut planes, mut margins) = (vec![0usize; n], vec![0.0f64; n]);
    for (i, r) in robot.iter().enumerate() {
        for (j, o) in obstacle.iter().enumerate() {
            let slabs = CObstacle::new(r, o)
                .and_then(|c| c.certified_slabs_par(orientations))
                .with_context(|| {
                    format!("certified slabs (robot piece {i}, obstacle piece {j})")
                })?;
            map.add_pair(i, j);
            for (k, slab) in slabs.iter().enumerate() {
                map.push_planes(slab.normals(), slab.offsets());
                planes[k] += slab.len();
                margins[k] = margins[k].max(slab.margin());
            }
        }
    }
    map.write(&dir.join(MAP_FILE))?;
    Ok((planes, margins))
}
