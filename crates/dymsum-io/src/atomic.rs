//! Atomic file output and bounded file input.
//!
//! [`write_atomic`] writes a file so that nothing is lost on failure: the
//! content goes to a fresh temporary file in the target's own directory
//! (`.STEM.tmp-PID-N.EXT`), is flushed and synced, and only then renamed over the
//! target. A full disk, a failing encoder or a killed process therefore never
//! leaves a truncated target and never destroys an earlier good file; on an
//! error the temporary file is removed and the error names the target path.
//!
//! [`read_regular_file`] reads a whole file, refusing anything that is not a
//! regular file (a FIFO, a character device such as `/dev/zero`, a
//! directory) before opening it, so reading cannot hang on a pipe or run out
//! of memory on an endless device. Symbolic links are followed: a link to a
//! regular file is read, a link to a device is refused.
//!
//! ```
//! use std::io::Write;
//! let dir = std::env::temp_dir().join(format!("dymsum-atomic-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let path = dir.join("hello.txt");
//! dymsum_io::atomic::write_atomic(&path, |w| w.write_all(b"good")).unwrap();
//! // A writer that fails half-way leaves the earlier content intact.
//! let err = dymsum_io::atomic::write_atomic(&path, |w| {
//!     w.write_all(b"partial")?;
//!     Err(std::io::Error::other("disk full"))
//! })
//! .unwrap_err();
//! assert!(err.to_string().contains("hello.txt"));
//! assert_eq!(std::fs::read(&path).unwrap(), b"good");
//! assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1); // no temporary file left
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```

use std::fs::{File, OpenOptions};
use std::io::{self, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// A failed file operation, naming the file. `Display` is `"{path}: {cause}"`
/// (the OS error said once, with its path).
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// Writing, flushing, syncing or renaming failed; the target is
    /// unchanged and no temporary file is left. Cause: full disk, missing
    /// directory, permissions, or an error from the content producer.
    #[error("{}: {source}", path.display())]
    Write {
        /// The target file.
        path: PathBuf,
        /// The underlying error.
        source: io::Error,
    },
    /// Opening or reading failed. Cause: missing file, permissions.
    #[error("{}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: io::Error,
    },
    /// The path names something other than a regular file (a FIFO, a
    /// device, a socket, a directory), which is refused rather than read:
    /// it could block forever or never end. Fix: copy the data to a file.
    #[error("{}: not a regular file ({kind}); give a mesh file", path.display())]
    NotRegular {
        /// The path given.
        path: PathBuf,
        /// What it is instead (`directory`, `FIFO or device`, ...).
        kind: &'static str,
    },
}

impl FileError {
    /// The file concerned.
    pub fn path(&self) -> &Path {
        match self {
            FileError::Write { path, .. }
            | FileError::Read { path, .. }
            | FileError::NotRegular { path, .. } => path,
        }
    }
}

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// A hidden temporary path next to `path`, unique within this process:
/// `.STEM.tmp-PID-N.EXT` (the extension kept last, for writers that choose
/// an encoding by extension).
fn temp_path(path: &Path) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".to_string());
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let mut name = format!(".{stem}.tmp-{}-{n}", std::process::id());
    if let Some(ext) = path.extension() {
        name.push('.');
        name.push_str(&ext.to_string_lossy());
    }
    path.with_file_name(name)
}

/// A file being written atomically: the content goes to a temporary file
/// next to the target, which [`AtomicFile::commit`] flushes, syncs and
/// renames over the target. Dropped without a commit (an error, a panic),
/// the temporary file is removed and the target is untouched.
///
/// Write errors are reported with the target's path in their text, so
/// callers need not add it again.
#[derive(Debug)]
pub struct AtomicFile {
    path: PathBuf,
    tmp: PathBuf,
    writer: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Creates the temporary file for `path` (in `path`'s directory, which
    /// must exist).
    ///
    /// # Errors
    /// [`FileError::Write`] naming `path` when `path` is a directory, or the
    /// temporary file cannot be created (missing directory, permissions, a
    /// read-only or full file system).
    pub fn create(path: &Path) -> Result<AtomicFile, FileError> {
        let err = |source| FileError::Write {
            path: path.to_path_buf(),
            source,
        };
        if path.is_dir() {
            return Err(err(io::Error::new(
                io::ErrorKind::IsADirectory,
                "is a directory",
            )));
        }
        let tmp = temp_path(path);
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .map_err(err)?;
        Ok(AtomicFile {
            path: path.to_path_buf(),
            tmp,
            writer: Some(BufWriter::new(file)),
        })
    }

    /// The target path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The temporary file's path, for writers that insist on opening a path
    /// themselves (they may truncate and rewrite it; nothing written through
    /// `self` should be mixed with that).
    pub fn temp_path(&self) -> &Path {
        &self.tmp
    }

    fn named(&self, e: io::Error) -> io::Error {
        io::Error::new(e.kind(), format!("{}: {e}", self.path.display()))
    }

    /// Flushes, syncs and renames the temporary file over the target. On
    /// error the temporary file is removed and the target is unchanged.
    ///
    /// # Errors
    /// [`FileError::Write`] naming the target when flushing the buffer,
    /// syncing the temporary file or renaming it over the target fails
    /// (full disk, permissions, the target's directory gone).
    pub fn commit(mut self) -> Result<(), FileError> {
        let result = (|| {
            if let Some(w) = self.writer.take() {
                w.into_inner().map_err(|e| e.into_error())?;
            }
            // Sync what is on disk under the temporary name (whoever wrote it).
            OpenOptions::new().write(true).open(&self.tmp)?.sync_all()?;
            std::fs::rename(&self.tmp, &self.path)
        })();
        result.map_err(|source| FileError::Write {
            path: self.path.clone(),
            source,
        })
        // On error, Drop removes the temporary file.
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self.writer.as_mut() {
            Some(w) => w.write(buf).map_err(|e| self.named(e)),
            None => Err(io::Error::other("file already committed")),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match self.writer.as_mut() {
            Some(w) => w.flush().map_err(|e| self.named(e)),
            None => Ok(()),
        }
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        // After a successful commit the temporary name no longer exists.
        drop(self.writer.take());
        let _ = std::fs::remove_file(&self.tmp);
    }
}

/// Writes `path` atomically: `produce` writes the content to a buffered
/// temporary file in the same directory, which is flushed, synced and then
/// renamed over `path` ([`AtomicFile`]). On any error (from `produce`, the
/// file system or the rename) the temporary file is removed, `path` is left
/// as it was, and the error names `path`.
///
/// # Errors
/// [`FileError::Write`] naming `path`, for any failure: creating the
/// temporary file (as [`AtomicFile::create`]), an error returned by
/// `produce` (kept as the source), or flushing, syncing and renaming (as
/// [`AtomicFile::commit`]).
///
/// # Panics
/// Never: the writer it takes out of the freshly created [`AtomicFile`] is
/// always present (the `expect` states that invariant).
pub fn write_atomic<F>(path: &Path, produce: F) -> Result<(), FileError>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    let mut file = AtomicFile::create(path)?;
    let mut inner = file.writer.take().expect("a fresh AtomicFile has a writer");
    match produce(&mut inner) {
        Ok(()) => {
            file.writer = Some(inner);
            file.commit()
        }
        Err(source) => Err(FileError::Write {
            path: path.to_path_buf(),
            source,
        }),
    }
}

/// [`write_atomic`] of a byte buffer.
///
/// # Errors
/// The same as [`write_atomic`].
pub fn write_atomic_bytes(path: &Path, bytes: &[u8]) -> Result<(), FileError> {
    write_atomic(path, |w| w.write_all(bytes))
}

/// Checks that `path` (symbolic links followed) is a regular file, without
/// opening it (opening a FIFO for reading blocks until a writer appears).
///
/// # Errors
/// [`FileError::Read`] when the path cannot be inspected (missing file,
/// permissions, a dangling link); [`FileError::NotRegular`] when it is a
/// directory, FIFO, socket or device.
pub fn ensure_regular_file(path: &Path) -> Result<(), FileError> {
    let meta = std::fs::metadata(path).map_err(|source| FileError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    if meta.is_file() {
        return Ok(());
    }
    let kind = if meta.is_dir() {
        "a directory"
    } else {
        "a FIFO, socket or device"
    };
    Err(FileError::NotRegular {
        path: path.to_path_buf(),
        kind,
    })
}

/// Reads a whole regular file; anything else is refused with
/// [`FileError::NotRegular`] before it is opened. The read is also bounded
/// by the size the file had when opened (plus one byte to notice growth), so
/// a file that keeps growing cannot exhaust memory.
///
/// # Errors
/// [`FileError::NotRegular`] when the path (or, checked again after opening,
/// the opened file) is not a regular file; [`FileError::Read`] when it
/// cannot be inspected, opened or read, or grew while being read.
pub fn read_regular_file(path: &Path) -> Result<Vec<u8>, FileError> {
    ensure_regular_file(path)?;
    let read_err = |source| FileError::Read {
        path: path.to_path_buf(),
        source,
    };
    let file = File::open(path).map_err(read_err)?;
    let meta = file.metadata().map_err(read_err)?;
    if !meta.is_file() {
        return Err(FileError::NotRegular {
            path: path.to_path_buf(),
            kind: "a FIFO, socket or device",
        });
    }
    let len = meta.len();
    let mut bytes = Vec::with_capacity(usize::try_from(len).unwrap_or(0).min(1 << 30));
    file.take(len.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(read_err)?;
    if bytes.len() as u64 > len {
        return Err(read_err(io::Error::other(
            "the file grew while it was being read",
        )));
    }
    Ok(bytes)
}
