//! `dymsum cobst ROBOT OBSTACLE (--axis X,Y,Z --slices N | --orientations-wxyz FILE) --out DIR`:
//! configuration-space obstacle slices of a robot translating among an
//! obstacle, one per robot orientation `R`: `O ⊕ (−R·A)`.
//!
//! Slices are computed by DYMSUM from slice to slice, the orientation list
//! split into contiguous chunks over the cores (identical to the sequential
//! result). Writes `DIR/slice_NNNNN.off` and `DIR/index.json`, an array of
//! `{"slice": k, "orientation_wxyz": [w,x,y,z], "faces": n, "file": "slice_NNNNN.off"}`
//! (every quaternion flag and field names its order: scalar first here;
//! `--orientations` is a hidden alias of `--orientations-wxyz`).
//! Every file is written atomically (temporary name, then rename).
//!
//! A non-empty output directory is refused unless `--force` is given, so
//! slices of an earlier run never sit next to new ones unnoticed; with
//! `--force`, the files an earlier run may have written there
//! (`slice_*`, `slab_*`, `index.json`, `map.npz`) are replaced and nothing
//! else is touched.
//!
//! Nothing is lost on a kill: the new files are written into a hidden
//! staging folder inside `--out` and swapped in only once all are complete
//! ([`dymsum_io::staging`]); until then the earlier run's files are
//! untouched. A run first cleans up after killed runs there (their
//! temporary files and staging folders, recognised by the owner's process
//! id; a running process's are left alone) and never counts temporary
//! entries when deciding that the folder is not empty.
//!
//! With `--certified`, certified slabs are written instead of slices: each
//! contains every slice between two consecutive orientations, or with
//! `--cell-radius RHO` every slice within angle `RHO` of one orientation
//! (see [`super::slabs`]).
//!
//! With a union of convex pieces as robot or obstacle (`a.off+b.off`, or an
//! OBJ file with several objects), a slice is the union of the piece-pair
//! sums: they are written as `slice_NNNNN_rI_oJ.off` and the index entry
//! lists them under `"files"` (with `"faces"` their total). With `--merge`,
//! each slice is written instead as one closed mesh `slice_NNNNN.off`: one
//! dynamic sum per piece pair turned from slice to slice by DYMSUM, their
//! union redone per slice by `boolmesh` and validated
//! ([`dymsum::ConvexUnion::cobstacle_union_slices`]).

use std::io::{BufRead, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{anyhow, bail, Context};
use clap::Args;
use dymsum::query::{full_turn_angles, orientations_about_axis, rotations_about_axis, CObstacle};
use dymsum::{ConvexUnion, DVec3, DynamicSum, Polytope, Rotation};
use serde::Serialize;

use super::short_name;
use super::slabs::{write_slabs, Cells, SlabFormat};
use super::solid::load_pieces;
use crate::stats::{human_us, micros};
use dymsum_io::cmap::{Form, MapBuilder};
use dymsum_io::staging::{is_temp_name, StagedDir};

/// Arguments of `dymsum cobst`.
#[derive(Debug, Args)]
pub struct CobstArgs {
    /// The robot: a mesh file or built-in model name (or convex pieces
    /// joined with `+`, or an OBJ file with several objects). Its reference
    /// point is its origin.
    #[arg(value_name = "ROBOT")]
    pub robot: String,
    /// The obstacle: as ROBOT.
    #[arg(value_name = "OBSTACLE")]
    pub obstacle: String,
    /// Rotation axis for evenly spaced orientations (with --slices).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_axis, allow_hyphen_values = true,
          requires = "slices", required_unless_present = "orientations")]
    pub axis: Option<DVec3>,
    /// Number of slices: angles 2πk/N, k = 0..N (with --axis).
    #[arg(long, value_name = "N", requires = "axis",
          value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub slices: Option<u32>,
    /// A file of orientations, one quaternion `w,x,y,z` (or whitespace
    /// separated) per line; `#` starts a comment.
    #[arg(long = "orientations-wxyz", alias = "orientations", value_name = "FILE",
          conflicts_with_all = ["axis", "slices"])]
    pub orientations: Option<PathBuf>,
    /// Output directory (created if missing). A non-empty directory is
    /// refused unless --force is given.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Write into a non-empty --out directory: replace the slices and
    /// index an earlier run left there (`slice_*`, `slab_*`, `index.json`,
    /// `map.npz`) once the new ones are complete; other files are kept.
    #[arg(long)]
    pub force: bool,
    /// How meshes are taken: `--strict`, `--decomposition`.
    #[command(flatten)]
    pub body: super::solid::BodyOptions,
    /// Write certified slabs instead of slices: slab k contains every slice
    /// for the orientations between orientation k and the next (with
    /// --slices N: the N slabs of the full turn; with --orientations-wxyz:
    /// the shortest turn between consecutive orientations).
    #[arg(long)]
    pub certified: bool,
    /// What to write: `off`, one mesh per slice (or slab), `slice_NNNNN.off`;
    /// `halfspaces`, one JSON of unit outward normals and offsets per slice
    /// (or slab), `slice_NNNNN.json` (the region is {x : n·x ≤ d}; for
    /// slices read straight from the sum's facets, no mesh built); `npz`,
    /// the whole map as half-spaces in one NumPy archive `DIR/map.npz`;
    /// `npz-mesh`, the meshes in `DIR/map.npz` (slices only).
    #[arg(long, value_enum, value_name = "FORMAT", default_value_t = CobstFormat::Off)]
    pub format: CobstFormat,
    /// With --certified: one slab per orientation instead, containing every
    /// slice for every rotation within angle RHO (radians, 0 ≤ RHO < π) of
    /// it, about any axis (an orientation cell in SO(3)): its slice with
    /// every face plane pushed out by r·RHO (r: the robot's largest
    /// distance from its origin) and the rounding terms.
    #[arg(long = "cell-radius", value_name = "RHO", value_parser = parse_cell_radius,
          allow_hyphen_values = true, requires = "certified")]
    pub cell_radius: Option<f64>,
    /// Write each slice of a union robot or obstacle as one closed mesh
    /// (`slice_NNNNN.off`): the validated union of its piece-pair slices
    /// (each pair turned by DYMSUM, the union redone per slice). With
    /// --format off only, not with --certified.
    #[arg(long, conflicts_with = "certified")]
    pub merge: bool,
}

/// Parses a cell radius: an angle in radians, `0 ≤ RHO < π` (a cell of
/// radius π or more would be all of SO(3), beyond the `r·ρ` bound's reach).
fn parse_cell_radius(s: &str) -> Result<f64, String> {
    let rho: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a number (an angle in radians)"))?;
    if !(0.0..std::f64::consts::PI).contains(&rho) {
        return Err(format!(
            "the cell radius must be an angle in radians with 0 ≤ RHO < π (3.14159…), got {rho}"
        ));
    }
    Ok(rho)
}

/// `dymsum cobst --format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum CobstFormat {
    /// One OFF mesh per slice or slab, and `index.json`.
    Off,
    /// One JSON of half-spaces per slice or slab, and `index.json`.
    Halfspaces,
    /// The map as half-spaces in `DIR/map.npz`.
    Npz,
    /// The map as meshes in `DIR/map.npz`.
    NpzMesh,
}

/// Parses a non-zero axis `X,Y,Z`.
fn parse_axis(s: &str) -> Result<DVec3, String> {
    let v = crate::values::parse_vector(s)?;
    if v.length() == 0.0 || !v.length().is_finite() {
        return Err("the axis must be a non-zero vector".into());
    }
    Ok(v)
}

/// Reads an orientation file: one quaternion per line (`w,x,y,z` or
/// whitespace separated), blank lines and `#` comments ignored. Errors name
/// the file and line.
///
/// # Errors
/// The file cannot be read (missing, not a regular file); a line is not
/// UTF-8, has an empty field, has other than 4 numbers, holds a value that
/// is not a finite number, or a zero quaternion; or the file holds no
/// orientation at all.
pub fn read_orientations(path: &Path) -> anyhow::Result<Vec<Rotation>> {
    let bytes = dymsum_io::atomic::read_regular_file(path).context("orientation file")?;
    let mut out = Vec::new();
    for (i, line) in bytes.as_slice().lines().enumerate() {
        let at = || format!("{} line {}", path.display(), i + 1);
        let line = line.map_err(|_| anyhow!("{}: not valid UTF-8 text", at()))?;
        let text = line.split('#').next().unwrap_or("").trim();
        if text.is_empty() {
            continue;
        }
        // Comma separated (each field non-empty) or whitespace separated.
        let parts: Vec<&str> = if text.contains(',') {
            let fields: Vec<&str> = text.split(',').map(str::trim).collect();
            if let Some(k) = fields.iter().position(|f| f.is_empty()) {
                bail!(
                    "{}: field {} of `{text}` is empty (expected w,x,y,z)",
                    at(),
                    k + 1
                );
            }
            fields
        } else {
            text.split_whitespace().collect()
        };
        if parts.len() != 4 {
            bail!(
                "{}: expected a quaternion w,x,y,z (4 numbers), got {} in `{text}`",
                at(),
                parts.len()
            );
        }
        let mut q = [0.0; 4];
        for (slot, p) in q.iter_mut().zip(&parts) {
            *slot = match p.parse::<f64>() {
                Ok(x) if x.is_finite() => x,
                Ok(_) => bail!("{}: `{p}` is not a finite number", at()),
                Err(_) => bail!("{}: `{p}` is not a number", at()),
            };
        }
        let r = Rotation::from_wxyz(q[0], q[1], q[2], q[3])
            .ok_or_else(|| anyhow!("{}: the quaternion is zero", at()))?;
        out.push(r);
    }
    if out.is_empty() {
        bail!("orientation file {}: no orientations", path.display());
    }
    Ok(out)
}

/// The container `--format npz` and `npz-mesh` write into `--out`.
pub const MAP_FILE: &str = "map.npz";

/// `true` for the names cobst writes: `index.json`, `map.npz`,
/// `slice_*.off`, `slice_*.json`, `slab_*.off` and `slab_*.json`.
fn is_own_output(name: &str) -> bool {
    name == "index.json"
        || name == MAP_FILE
        || (name.starts_with("slice_") && (name.ends_with(".off") || name.ends_with(".json")))
        || (name.starts_with("slab_") && (name.ends_with(".off") || name.ends_with(".json")))
}

/// Creates the output directory, or checks an existing one: cleaned up
/// after killed runs ([`dymsum_io::staging::recover`]), then empty (its
/// temporary entries aside) or `force` given. Returns the staging folder
/// the new files are written into; [`StagedDir::commit`] swaps them in,
/// replacing an earlier run's files (only those, [`is_own_output`]).
fn prepare_out_dir(dir: &Path, force: bool) -> anyhow::Result<StagedDir> {
    if !dir.exists() {
        super::create_output_dir(dir)?;
    } else if !dir.is_dir() {
        bail!("--out {}: exists and is not a directory", dir.display());
    }
    dymsum_io::staging::recover(dir, &is_own_output)
        .with_context(|| format!("--out {}: cleaning up after an earlier run", dir.display()))?;
    let mut entries = 0usize;
    for e in std::fs::read_dir(dir).with_context(|| format!("--out {}", dir.display()))? {
        let e = e.with_context(|| format!("--out {}", dir.display()))?;
        if !e.file_name().to_str().is_some_and(is_temp_name) {
            entries += 1;
        }
    }
    if entries > 0 && !force {
        bail!(
            "--out {}: the directory is not empty ({entries} entries); slices of an earlier run \
             would mix with the new ones. Choose an empty or new directory, or add --force to \
             replace the earlier slice_*/slab_* files and index.json there (once the new ones \
             are complete)",
            dir.display(),
        );
    }
    StagedDir::create(dir).with_context(|| format!("--out {}", dir.display()))
}

/// Swaps the files written into `staged` into `--out` (replacing an earlier
/// run's, [`is_own_output`]).
fn commit_out_dir(staged: StagedDir) -> anyhow::Result<()> {
    staged.commit(&is_own_output)?;
    Ok(())
}

/// One entry of `index.json`.
#[derive(Serialize)]
struct IndexEntry {
    slice: usize,
    orientation_wxyz: [f64; 4],
    faces: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    file: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    files: Option<Vec<String>>,
}

/// Runs `dymsum cobst`.
///
/// # Errors
/// ROBOT or OBSTACLE cannot be loaded ([`super::query::load_body`]); the
/// orientations are missing or invalid ([`read_orientations`], a zero
/// axis, neither `--orientations-wxyz` nor `--axis` with `--slices`); `--out`
/// is not a directory, is not empty (without `--force`), or cannot be
/// created, listed or cleared of earlier slices; a slice fails ([`dymsum::query::QueryError`]) or
/// cannot be written; or `out` cannot be written.
pub fn run(a: &CobstArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    super::stdin_for_one_operand(&[(&a.robot, "ROBOT"), (&a.obstacle, "OBSTACLE")])?;
    let robot = load_pieces(&a.robot, "ROBOT", a.body.strict, a.body.decomposition)?;
    let obstacle = load_pieces(&a.obstacle, "OBSTACLE", a.body.strict, a.body.decomposition)?;
    if a.certified {
        return run_certified(a, (&robot, &obstacle), out);
    }
    let orientations = chosen_orientations(a)?;
    let staged = prepare_out_dir(&a.out, a.force)?;
    let dir = staged.path();
    let mut union = robot.len() > 1 || obstacle.len() > 1;
    if a.merge && a.format != CobstFormat::Off {
        bail!("--merge writes one mesh per slice: use it with --format off");
    }
    let start = Instant::now();
    let slices = if a.merge {
        union = false;
        write_merged_slices(a, dir, &robot, &obstacle, &orientations)?
    } else {
        match a.format {
            CobstFormat::Npz | CobstFormat::NpzMesh => {
                let form = if a.format == CobstFormat::Npz {
                    Form::HalfSpaces
                } else {
                    Form::Mesh
                };
                write_map(a, dir, (&robot, &obstacle), &orientations, form)?
            }
            _ => write_slices(a, dir, &robot, &obstacle, &orientations)?,
        }
    };
    let elapsed = micros(start.elapsed());
    if !matches!(a.format, CobstFormat::Npz | CobstFormat::NpzMesh) {
        write_index(dir, &orientations, &slices, union)?;
    }
    commit_out_dir(staged)?;
    let faces = &slices.faces;
    let (lo, hi) = (
        faces.iter().min().copied().unwrap_or(0),
        faces.iter().max().copied().unwrap_or(0),
    );
    let pairs = robot.len() * obstacle.len();
    let (unit, target) = match a.format {
        CobstFormat::Off => ("faces", a.out.clone()),
        CobstFormat::Halfspaces => ("planes", a.out.clone()),
        CobstFormat::Npz => ("planes", a.out.join(MAP_FILE)),
        CobstFormat::NpzMesh => ("faces", a.out.join(MAP_FILE)),
    };
    writeln!(
        out,
        "C-obstacle of {} among {}: {} slices ({} piece pair{}), {lo}–{hi} {unit} per slice, \
         written to {} in {}",
        short_name(&a.robot),
        short_name(&a.obstacle),
        orientations.len(),
        pairs,
        if pairs == 1 { "" } else { "s" },
        target.display(),
        human_us(elapsed),
    )?;
    Ok(())
}

/// `dymsum cobst --certified`: the slabs between consecutive orientations
/// (`--slices N` about `--axis`: the angles `2πk/N` for `k = 0..=N`, so the
/// `N` slabs close the turn), or with `--cell-radius` the slabs of the
/// cells about each orientation (`--slices N`: the angles `2πk/N` for
/// `k = 0..N`).
fn run_certified(
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
fn write_slab_map(
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

/// The robot orientations asked for: from `--orientations-wxyz FILE`, or
/// `--slices N` evenly spaced turns about `--axis`.
fn chosen_orientations(a: &CobstArgs) -> anyhow::Result<Vec<Rotation>> {
    Ok(match (&a.orientations, a.axis, a.slices) {
        (Some(file), _, _) => read_orientations(file)?,
        (None, Some(axis), Some(n)) => orientations_about_axis(axis, n as usize)
            .ok_or_else(|| anyhow!("--axis must be a non-zero vector"))?,
        _ => bail!("give --axis X,Y,Z with --slices N, or --orientations-wxyz FILE"),
    })
}

/// What was written for each slice, over all piece pairs.
struct Slices {
    /// Faces of each slice (summed over its piece pairs).
    faces: Vec<usize>,
    /// The files of each slice, one per piece pair.
    files: Vec<Vec<String>>,
}

/// Writes one OFF file per slice and piece pair into `dir`, the staging folder (named
/// `slice_K.off`, or `slice_K_rI_oJ.off` when a body has several pieces).
fn write_slices(
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
fn write_merged_slices(
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
fn write_slice_halfspaces(
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
fn write_map(
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
fn piece_names(prefix: &str, n: usize) -> Vec<String> {
    (0..n).map(|i| format!("{prefix}{i}")).collect()
}

/// Writes slice `k`, the sum's mesh, to `path`; returns its face count.
fn write_slice(sum: &DynamicSum, k: usize, path: &Path) -> anyhow::Result<usize> {
    let mesh = sum
        .try_to_mesh()
        .map_err(|e| anyhow::Error::new(e).context(format!("slice {k}")))?;
    dymsum_io::formats::write_mesh(path, &mesh)?;
    Ok(mesh.faces.len())
}

/// Writes `index.json` into `dir`: per slice its orientation, face count
/// and file (`files` when a body has several pieces).
fn write_index(
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
