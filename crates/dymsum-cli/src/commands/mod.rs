//! One module per subcommand. Each takes its parsed arguments and the
//! output stream and returns `anyhow::Result`; errors are bad *input*
//! (exit 1), with messages naming the operand and the cause.

pub mod animate;
pub mod bench;
pub mod cobst;
pub mod completions;
pub mod demo;
pub mod info;
pub mod models;
pub mod motion;
pub mod query;
pub mod render;
pub mod solid;
pub mod sum;

use std::io::Write;
use std::path::Path;

use anyhow::{anyhow, Context};
use dymsum::polytope::MeshPolicy;
use dymsum_io::{load_polytope, Loaded};

pub use crate::values::STDIO;

/// The mesh policy for the `--strict` flag.
pub fn policy(strict: bool) -> MeshPolicy {
    if strict {
        MeshPolicy::strict()
    } else {
        MeshPolicy::default()
    }
}

/// Loads operand `operand` (`"P"`, `"Q"`, `"input"`) from a file or model
/// name, with an error message like
/// `P (file cube_open.off): open mesh: edge (3, 7) borders only one face`.
/// `-` reads an OFF mesh from standard input (once per run).
///
/// # Errors
/// A message prefixed with `operand` and the origin: any
/// [`dymsum_io::LoadError`] of [`load_polytope`] (not found, unreadable,
/// unparsable, several OBJ bodies, bad model parameters, not a convex
/// body), or for `-` a second operand reading standard input, a read
/// error, or OFF content that does not parse or build.
pub fn load(spec: &str, operand: &str, strict: bool) -> anyhow::Result<Loaded> {
    if spec == STDIO {
        let bytes = read_stdin_once(operand)?;
        return dymsum_io::load_polytope_bytes(
            &bytes,
            dymsum_io::formats::Format::Off,
            "standard input",
            policy(strict),
        )
        .map_err(|e| anyhow!(e.for_operand(operand)))
        .inspect(|l| log_loaded(operand, l));
    }
    let loaded =
        load_polytope(spec, policy(strict)).map_err(|e| anyhow!(e.for_operand(operand)))?;
    log_loaded(operand, &loaded);
    Ok(loaded)
}

fn log_loaded(operand: &str, l: &Loaded) {
    log::debug!(
        "{operand}: {} -> {} vertices, {} faces, {} edges",
        l.source,
        l.polytope.vertex_count(),
        l.polytope.face_count(),
        l.polytope.edge_count()
    );
    if let Some(r) = &l.report {
        log::debug!(
            "{operand}: input {} vertices, {} faces; exactly convex: {}, replaced by hull: {}, \
             max deviation {:e} (tolerance {:e})",
            r.input_vertices,
            r.input_faces,
            r.exactly_convex,
            r.replaced_by_hull,
            r.max_deviation,
            r.tolerance
        );
    }
}

/// The error for a second operand that reads standard input.
fn stdin_taken(operand: &str) -> anyhow::Error {
    anyhow!("{operand}: standard input (`-`) can be read by one operand only")
}

/// Refuses `-` (standard input) for more than one of `operands` (spec,
/// name), before any of them is read: `dymsum sum - -` says so whatever
/// standard input holds, even nothing.
///
/// # Errors
/// The second operand given as `-`, named.
pub fn stdin_for_one_operand(operands: &[(&str, &str)]) -> anyhow::Result<()> {
    let mut readers = operands.iter().filter(|(spec, _)| *spec == STDIO);
    match (readers.next(), readers.next()) {
        (Some(_), Some((_, second))) => Err(stdin_taken(second)),
        _ => Ok(()),
    }
}

/// Reads all of standard input, refusing a second reader in the same run
/// (the first took every byte).
fn read_stdin_once(operand: &str) -> anyhow::Result<Vec<u8>> {
    use std::io::Read;
    use std::sync::atomic::{AtomicBool, Ordering};
    static TAKEN: AtomicBool = AtomicBool::new(false);
    if TAKEN.swap(true, Ordering::SeqCst) {
        return Err(stdin_taken(operand));
    }
    let mut bytes = Vec::new();
    std::io::stdin()
        .lock()
        .read_to_end(&mut bytes)
        .map_err(|e| anyhow!("{operand}: reading standard input: {e}"))?;
    Ok(bytes)
}

/// The one rule for every output of the command line (`sum -o`, `render
/// -o`, `models --write`, `animate --csv` and `--frames-dir`, `cobst
/// --out`, `bench --out`): a missing output folder is created, with its
/// missing parents (as `mkdir -p`). An existing folder is used as it is,
/// once the temporary files that killed writers left there (their owner
/// process is dead) are removed; a running writer's are kept
/// ([`dymsum_io::atomic::remove_stale_temps`]).
///
/// # Errors
/// The folder cannot be created (a file is in the way, permissions),
/// naming the folder.
pub fn create_output_dir(dir: &Path) -> anyhow::Result<()> {
    if !(dir.as_os_str().is_empty() || dir.is_dir()) {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("creating the output folder {}", dir.display()))?;
    }
    // Best effort: a folder that cannot be listed or cleaned is reported by
    // the write itself, if it fails.
    let here = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let _ = dymsum_io::atomic::remove_stale_temps(here);
    Ok(())
}

/// [`create_output_dir`] for the folder of an output file.
///
/// # Errors
/// As [`create_output_dir`].
pub fn create_parent_dir(file: &Path) -> anyhow::Result<()> {
    match file.parent() {
        Some(dir) => create_output_dir(dir),
        None => Ok(()),
    }
}

/// Writes a mesh to `path`, atomically, in the format its extension names
/// (its folder created if missing, [`create_output_dir`]), or as OFF to
/// `out` when `path` is `-`.
///
/// # Errors
/// The folder cannot be created; [`dymsum_io::formats::FormatError`] from
/// encoding or writing the file (unknown extension, a mesh that cannot be
/// encoded, an I/O failure; an earlier file at `path` is kept), or the I/O
/// error of writing to `out`.
pub fn write_mesh_or_stdout(
    path: &Path,
    mesh: &dymsum::PolygonMesh,
    out: &mut dyn Write,
) -> anyhow::Result<()> {
    if path.as_os_str() == STDIO {
        let bytes = dymsum_io::formats::write_mesh_bytes(mesh, dymsum_io::formats::Format::Off)?;
        out.write_all(&bytes)?;
        return Ok(());
    }
    create_parent_dir(path)?;
    dymsum_io::formats::write_mesh(path, mesh)?;
    Ok(())
}

/// The validated mesh of a sum, with a warning on stderr when its
/// coordinates are coarse relative to its size. Errors keep their type, so
/// an internal one ([`dymsum::sum::MeshError::is_internal`]) exits with 3.
///
/// # Errors
/// The [`dymsum::sum::MeshError`] in `mesh`, unchanged in type, with the
/// context "the mesh of `what`".
pub fn validated(
    mesh: Result<dymsum::sum::SumMesh, dymsum::sum::MeshError>,
    what: &str,
) -> anyhow::Result<dymsum::PolygonMesh> {
    let m = mesh.map_err(|e| anyhow::Error::new(e).context(format!("the mesh of {what}")))?;
    log::debug!(
        "{what}: {} vertices, {} faces; {}{}",
        m.mesh.vertices.len(),
        m.mesh.faces.len(),
        m.precision,
        if m.hull_fallback {
            "; merged faces bent by rounding: exact hull of the rounded vertices"
        } else {
            ""
        }
    );
    if m.precision.is_coarse() {
        eprintln!(
            "warning: {what}: coordinates lose precision: {}",
            m.precision
        );
    }
    Ok(m.mesh)
}

/// A short display name for an operand: the model name, or the file name.
pub fn short_name(spec: &str) -> String {
    if spec == STDIO {
        return "stdin".to_string();
    }
    let path = std::path::Path::new(spec);
    if path.is_file() {
        path.file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_else(|| spec.to_string())
    } else {
        spec.trim().to_string()
    }
}
