//! Atomic file output and bounded file input.
//!
//! [`write_atomic`] writes a file so that nothing is lost on failure: the
//! content goes to a fresh temporary file in the target's own directory
//! (`.STEM.tmp-PID-N.EXT`), is flushed and synced, and only then renamed over the
//! target. A full disk, a failing encoder or a killed process therefore never
//! leaves a truncated target and never destroys an earlier good file; on an
//! error the temporary file is removed and the error names the target path.
//!
//! Temporary names carry their owner's process id, so a later run can tell a
//! killed writer's leftovers from a running writer's file:
//! [`remove_stale_temps`] removes the former only ([`owner_alive`]).
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

/// The parts of a temporary name this crate writes: `.STEM.tmp-PID-N`
/// followed by nothing or `.EXT`, with `N` a token of ASCII letters,
/// digits and `_` (a counter here).
///
/// ```
/// use dymsum_io::atomic::TempName;
/// let t = TempName::parse(".map.tmp-4242-7.npz").unwrap();
/// assert_eq!((t.stem, t.pid, t.ext), ("map", 4242, Some("npz")));
/// assert_eq!(TempName::parse(".notes.tmp-1-k3x_a9").unwrap().ext, None);
/// assert!(TempName::parse("map.npz").is_none());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TempName<'a> {
    /// The target's file stem.
    pub stem: &'a str,
    /// The writer's process id.
    pub pid: u32,
    /// The target's extension, without the dot.
    pub ext: Option<&'a str>,
}

impl<'a> TempName<'a> {
    /// The parts of `name`, `None` when it is not a temporary name.
    pub fn parse(name: &'a str) -> Option<TempName<'a>> {
        let hidden = name.strip_prefix('.')?;
        let at = hidden.rfind(".tmp-")?;
        if at == 0 {
            return None;
        }
        let stem = &hidden[..at];
        let (pid, rest) = hidden[at + 5..].split_once('-')?;
        if pid.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let (token, ext) = match rest.split_once('.') {
            Some((t, e)) => (t, Some(e)),
            None => (rest, None),
        };
        if token.is_empty()
            || !token
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b == b'_')
        {
            return None;
        }
        Some(TempName {
            stem,
            pid: pid.parse().ok()?,
            ext,
        })
    }

    /// Whether this is a temporary file of a writer of `target`: the same
    /// stem and extension ([`AtomicFile`]'s names).
    ///
    /// ```
    /// use dymsum_io::atomic::TempName;
    /// use std::path::Path;
    /// let t = TempName::parse(".map.tmp-17-0.npz").unwrap();
    /// assert!(t.is_temp_of(Path::new("out/map.npz")));
    /// assert!(!t.is_temp_of(Path::new("out/map.off")));
    /// assert!(!t.is_temp_of(Path::new("out/other.npz")));
    /// ```
    pub fn is_temp_of(&self, target: &Path) -> bool {
        let stem = target.file_stem().map(|s| s.to_string_lossy());
        let ext = target.extension().map(|e| e.to_string_lossy());
        stem.as_deref() == Some(self.stem) && ext.as_deref() == self.ext
    }
}

/// The process id in a temporary name this crate writes ([`TempName`]).
/// `None` for any other name.
///
/// ```
/// use dymsum_io::atomic::temp_owner;
/// assert_eq!(temp_owner(".map.tmp-4242-7.npz"), Some(4242));
/// assert_eq!(temp_owner(".slice_00001.tmp-17-0.off"), Some(17));
/// assert_eq!(temp_owner(".map.tmp-99-k3x_a9.npz"), Some(99));
/// assert_eq!(temp_owner("map.npz"), None);
/// assert_eq!(temp_owner(".map.tmp-x-1.npz"), None);
/// ```
pub fn temp_owner(name: &str) -> Option<u32> {
    TempName::parse(name).map(|t| t.pid)
}

/// Whether the process `pid` may still be running: this process, or (on
/// systems with `/proc`, Linux) a process whose `/proc/PID` exists. Where
/// that cannot be told (no `/proc`), every owner counts as alive, so no
/// file is ever removed from under a running writer. A dead owner's id
/// reused by an unrelated process only keeps its file until a later run.
pub fn owner_alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    let proc = Path::new("/proc");
    if !proc.join("self").exists() {
        return true;
    }
    proc.join(pid.to_string()).exists()
}

/// What [`remove_stale_temps`] found in a folder.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StaleTemps {
    /// The temporary files of dead owners, removed.
    pub removed: Vec<PathBuf>,
    /// The temporary files of owners still running, left alone.
    pub live: Vec<PathBuf>,
}

/// Removes the temporary files ([`temp_owner`]'s names) that killed writers
/// left in `dir`, those whose owner process is dead ([`owner_alive`]); a
/// running writer's are left alone and listed. Other entries, folders and
/// anything that cannot be inspected are not touched.
///
/// # Errors
/// [`FileError::Read`] naming `dir` when it cannot be listed;
/// [`FileError::Write`] naming a stale file that cannot be removed.
pub fn remove_stale_temps(dir: &Path) -> Result<StaleTemps, FileError> {
    remove_stale_temps_with(dir, &owner_alive)
}

pub(crate) fn remove_stale_temps_with(
    dir: &Path,
    alive: &dyn Fn(u32) -> bool,
) -> Result<StaleTemps, FileError> {
    remove_stale_temps_matching(dir, alive, &|_| true)
}

/// Removes the temporary files that killed writers of `target` left next
/// to it ([`TempName::is_temp_of`]: the same stem and extension), those
/// whose owner process is dead ([`owner_alive`]); a running writer's, and
/// the temporary files of other targets, are left alone. Called before a
/// new write of `target`, so that repeated kills do not pile files up.
///
/// ```
/// use dymsum_io::atomic::remove_stale_temps_of;
/// let dir = std::env::temp_dir().join(format!("dymsum-stale-of-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let mine = dir.join(format!(".map.tmp-{}-0.npz", std::process::id()));
/// std::fs::write(&mine, b"a running writer's")?;
/// let found = remove_stale_temps_of(&dir.join("map.npz"))?;
/// assert!(found.removed.is_empty() && found.live == [mine.clone()]);
/// assert!(mine.exists());
/// std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`remove_stale_temps`], for `target`'s folder.
pub fn remove_stale_temps_of(target: &Path) -> Result<StaleTemps, FileError> {
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    remove_stale_temps_matching(dir, &owner_alive, &|t| t.is_temp_of(target))
}

fn remove_stale_temps_matching(
    dir: &Path,
    alive: &dyn Fn(u32) -> bool,
    wanted: &dyn Fn(&TempName<'_>) -> bool,
) -> Result<StaleTemps, FileError> {
    let mut out = StaleTemps::default();
    let list_err = |source| FileError::Read {
        path: dir.to_path_buf(),
        source,
    };
    for e in std::fs::read_dir(dir).map_err(list_err)? {
        let e = e.map_err(list_err)?;
        let name = e.file_name();
        let Some(temp) = name.to_str().and_then(TempName::parse) else {
            continue;
        };
        if !wanted(&temp) || !e.file_type().is_ok_and(|t| t.is_file()) {
            continue;
        }
        let path = e.path();
        if alive(temp.pid) {
            out.live.push(path);
        } else {
            match std::fs::remove_file(&path) {
                Ok(()) => out.removed.push(path),
                // Removed meanwhile (by another run): nothing left to do.
                Err(e) if e.kind() == io::ErrorKind::NotFound => {}
                Err(source) => return Err(FileError::Write { path, source }),
            }
        }
    }
    Ok(out)
}

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
    /// must exist), under the first free name `.STEM.tmp-PID-N.EXT`.
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
        // A name already taken (a leftover of an earlier process with this
        // process's id, or anyone's file) is skipped: the counter moves on.
        let mut attempts = 0;
        let (tmp, file) = loop {
            let tmp = temp_path(path);
            match OpenOptions::new().write(true).create_new(true).open(&tmp) {
                Ok(file) => break (tmp, file),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists && attempts < 1000 => {
                    attempts += 1;
                }
                Err(e) => return Err(err(e)),
            }
        };
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

/// Opens a regular file for reading; anything else is refused with
/// [`FileError::NotRegular`] before it is opened ([`ensure_regular_file`]).
/// On Unix the file is opened non-blocking (no effect on a regular file),
/// so a FIFO swapped in between the check and the open cannot block the
/// open, and it is refused by the check of the opened file.
///
/// ```
/// let err = dymsum_io::atomic::open_regular_file(&std::env::temp_dir()).unwrap_err();
/// assert!(err.to_string().contains("not a regular file (a directory)"));
/// ```
///
/// # Errors
/// [`FileError::NotRegular`] when the path (or, checked again after opening,
/// the opened file) is not a regular file; [`FileError::Read`] when it
/// cannot be inspected or opened.
pub fn open_regular_file(path: &Path) -> Result<File, FileError> {
    ensure_regular_file(path)?;
    let read_err = |source| FileError::Read {
        path: path.to_path_buf(),
        source,
    };
    let mut options = OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(read_err)?;
    if !file.metadata().map_err(read_err)?.is_file() {
        return Err(FileError::NotRegular {
            path: path.to_path_buf(),
            kind: "a FIFO, socket or device",
        });
    }
    Ok(file)
}

/// Reads a whole regular file ([`open_regular_file`]). The read is bounded
/// by the size the file had when opened (plus one byte to notice growth),
/// so a file that keeps growing cannot exhaust memory.
///
/// # Errors
/// Those of [`open_regular_file`]; [`FileError::Read`] when the file
/// cannot be read, or grew while being read.
pub fn read_regular_file(path: &Path) -> Result<Vec<u8>, FileError> {
    let file = open_regular_file(path)?;
    let read_err = |source| FileError::Read {
        path: path.to_path_buf(),
        source,
    };
    let len = file.metadata().map_err(read_err)?.len();
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A writer that fails (as a full disk or a kill would stop it) once
    /// `left` more bytes have gone through.
    struct FailAfter<'a> {
        inner: &'a mut dyn Write,
        left: usize,
    }

    impl Write for FailAfter<'_> {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            if self.left == 0 {
                return Err(io::Error::other("injected failure"));
            }
            let n = buf.len().min(self.left);
            self.left -= n;
            self.inner.write(&buf[..n])
        }

        fn flush(&mut self) -> io::Result<()> {
            self.inner.flush()
        }
    }

    #[test]
    fn a_writer_failing_after_k_bytes_for_every_k_keeps_the_old_file_and_no_temp() {
        let dir = std::env::temp_dir().join(format!("dymsum-atomic-k-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("map.npz");
        write_atomic_bytes(&path, b"the old map").unwrap();
        let new: Vec<u8> = (0..=255u8).cycle().take(9000).collect();
        for k in 0..new.len() {
            let err = write_atomic(&path, |w| {
                let mut f = FailAfter { inner: w, left: k };
                // Written in uneven pieces, as encoders do.
                for chunk in new.chunks(37) {
                    f.write_all(chunk)?;
                }
                f.flush()
            })
            .unwrap_err();
            assert!(err.to_string().contains("map.npz"), "{err}");
            assert_eq!(std::fs::read(&path).unwrap(), b"the old map", "k = {k}");
            assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "k = {k}");
        }
        write_atomic(&path, |w| w.write_all(&new)).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), new);
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_write_skips_a_temporary_name_already_taken_and_clears_only_its_targets_stale_temps() {
        let dir = std::env::temp_dir().join(format!("dymsum-atomic-taken-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("map.npz");
        // The names this process's next writes would take, already there
        // (a leftover of an earlier process with this id).
        let next = COUNTER.load(Ordering::Relaxed);
        let pid = std::process::id();
        let taken: Vec<PathBuf> = (next..next + 3)
            .map(|n| dir.join(format!(".map.tmp-{pid}-{n}.npz")))
            .collect();
        for t in &taken {
            std::fs::write(t, b"someone else's").unwrap();
        }
        write_atomic_bytes(&path, b"the map").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"the map");
        for t in &taken {
            assert_eq!(std::fs::read(t).unwrap(), b"someone else's");
        }
        // Stale temporary files of this target go; another target's, and
        // a live owner's, stay.
        let dead = u32::MAX - 1;
        for name in [
            format!(".map.tmp-{dead}-ab_1.npz"),
            format!(".map.tmp-{dead}-0.off"),
            format!(".other.tmp-{dead}-0.npz"),
        ] {
            std::fs::write(dir.join(name), b"partial").unwrap();
        }
        let found =
            remove_stale_temps_matching(&dir, &|p| p != dead, &|t| t.is_temp_of(&path)).unwrap();
        assert_eq!(
            found.removed,
            [dir.join(format!(".map.tmp-{dead}-ab_1.npz"))]
        );
        let (mut live, mut taken) = (found.live.clone(), taken);
        live.sort();
        taken.sort();
        assert_eq!(live, taken);
        assert!(dir.join(format!(".map.tmp-{dead}-0.off")).exists());
        assert!(dir.join(format!(".other.tmp-{dead}-0.npz")).exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn stale_temps_of_dead_owners_are_removed_and_live_ones_kept() {
        let dir = std::env::temp_dir().join(format!("dymsum-atomic-stale-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        for name in [
            ".map.tmp-7-0.npz",
            ".map.tmp-8-ab_1.npz",
            "map.npz",
            ".notes",
        ] {
            std::fs::write(dir.join(name), name).unwrap();
        }
        let found = remove_stale_temps_with(&dir, &|pid| pid == 8).unwrap();
        assert_eq!(found.removed, [dir.join(".map.tmp-7-0.npz")]);
        assert_eq!(found.live, [dir.join(".map.tmp-8-ab_1.npz")]);
        let mut left: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        left.sort();
        assert_eq!(left, [".map.tmp-8-ab_1.npz", ".notes", "map.npz"]);
        // This process is alive; a process that has exited is not.
        assert!(owner_alive(std::process::id()));
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let pid = child.id();
        child.wait().unwrap();
        if Path::new("/proc/self").exists() {
            assert!(!owner_alive(pid) || Path::new("/proc").join(pid.to_string()).exists());
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
