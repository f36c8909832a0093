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
//! (see [`slabs`]).
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
use dymsum::query::orientations_about_axis;
use dymsum::{DVec3, Rotation};
use serde::Serialize;

use super::short_name;
use super::solid::{convex_operands, load_pieces};
use crate::stats::{human_us, micros};
use dymsum_io::cmap::Form;
use dymsum_io::staging::{is_temp_name, StagedDir};

mod certified;
pub mod slabs;
mod write;

use certified::run_certified;
use write::{write_index, write_map, write_merged_slices, write_slices};

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
/// ROBOT or OBSTACLE cannot be loaded ([`crate::commands::solid::load_pieces`]); the
/// orientations are missing or invalid ([`read_orientations`], a zero
/// axis, neither `--orientations-wxyz` nor `--axis` with `--slices`); `--out`
/// is not a directory, is not empty (without `--force`), or cannot be
/// created, listed or cleared of earlier slices; a slice fails ([`dymsum::query::QueryError`]) or
/// cannot be written; or `out` cannot be written.
pub fn run(a: &CobstArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    super::stdin_for_one_operand(&[(&a.robot, "ROBOT"), (&a.obstacle, "OBSTACLE")])?;
    let robot = load_pieces(
        &a.robot,
        "ROBOT",
        convex_operands(a.body.strict),
        a.body.decomposition,
    )?;
    let obstacle = load_pieces(
        &a.obstacle,
        "OBSTACLE",
        convex_operands(a.body.strict),
        a.body.decomposition,
    )?;
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
