//! Replacing a set of files in a folder so that a kill loses nothing.
//!
//! A run that writes several files into a folder (`dymsum cobst --out DIR`:
//! `slice_*` files and `index.json`, or `map.npz`) and replaces an earlier
//! run's set must never destroy the earlier set before the new one is
//! complete. [`StagedDir`] builds the new set beside the old one, in a
//! hidden staging folder inside the target folder
//! (`DIR/.dymsum-staging-PID-N`, on the same file system, so every move is a
//! rename), and swaps it in at the end ([`StagedDir::commit`]):
//!
//! 1. the staged names are recorded in `.manifest` inside the staging
//!    folder (written atomically, synced);
//! 2. the staging folder is renamed `DIR/.dymsum-ready-PID-N`: **the commit
//!    point** (one atomic rename). Before it the earlier set is untouched;
//!    from it on the new set is complete on disk;
//! 3. each staged file is renamed into `DIR` (over an earlier file of the
//!    same name; `index.json` last);
//! 4. the earlier run's files that the new set does not replace (the
//!    caller's `replaces` predicate, e.g. `slice_*.off` and `index.json`)
//!    are removed;
//! 5. the ready folder is removed.
//!
//! A process killed during steps 1–2 leaves the earlier set intact and a
//! staging folder, which the next run removes; killed during steps 3–5 it
//! leaves the new set complete, split between `DIR` and the ready folder,
//! and the next run finishes the swap (steps 3–5 again, from the manifest)
//! before anything else: [`recover`]. Both look at the owner's process id
//! in the folder's name and touch nothing a running process owns
//! ([`crate::atomic::owner_alive`]); they also remove the temporary files
//! of killed writers ([`crate::atomic::remove_stale_temps`]). Temporary
//! entries ([`is_temp_name`]) are never counted as content of the folder.
//!
//! ```
//! use dymsum_io::staging::{recover, StagedDir};
//! let dir = std::env::temp_dir().join(format!("dymsum-staging-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! std::fs::write(dir.join("slice_00000.off"), "old 0").unwrap();
//! std::fs::write(dir.join("slice_00001.off"), "old 1").unwrap();
//! let own = |name: &str| name.starts_with("slice_");
//! recover(&dir, &own).unwrap();
//! let staged = StagedDir::create(&dir).unwrap();
//! std::fs::write(staged.path().join("slice_00000.off"), "new 0").unwrap();
//! // Until the commit the earlier files are untouched.
//! assert_eq!(std::fs::read_to_string(dir.join("slice_00000.off")).unwrap(), "old 0");
//! staged.commit(&own).unwrap();
//! assert_eq!(std::fs::read_to_string(dir.join("slice_00000.off")).unwrap(), "new 0");
//! assert!(!dir.join("slice_00001.off").exists());
//! assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```

use crate::atomic::{owner_alive, remove_stale_temps_with, temp_owner, write_atomic, FileError};
use std::collections::BTreeSet;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// The name prefix of a staging folder: `.dymsum-staging-PID-N`.
pub const STAGING_PREFIX: &str = ".dymsum-staging-";
/// The name prefix of a complete staged set being swapped in:
/// `.dymsum-ready-PID-N`.
pub const READY_PREFIX: &str = ".dymsum-ready-";
/// The list of staged names inside a staging or ready folder.
const MANIFEST: &str = ".manifest";
/// Moved last: the entry point of a folder of slices.
const INDEX: &str = "index.json";

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// The owner process id of a staging or ready folder's name.
fn folder_owner(name: &str) -> Option<(bool, u32)> {
    let (ready, rest) = if let Some(r) = name.strip_prefix(STAGING_PREFIX) {
        (false, r)
    } else if let Some(r) = name.strip_prefix(READY_PREFIX) {
        (true, r)
    } else {
        return None;
    };
    let (pid, n) = rest.split_once('-')?;
    if pid.is_empty()
        || n.is_empty()
        || !pid.bytes().all(|b| b.is_ascii_digit())
        || !n.bytes().all(|b| b.is_ascii_digit())
    {
        return None;
    }
    Some((ready, pid.parse().ok()?))
}

/// Whether `name` is a temporary entry of a dymsum writer: a temporary file
/// ([`crate::atomic::temp_owner`]) or a staging or ready folder. Such
/// entries never count as content of a folder.
///
/// ```
/// use dymsum_io::staging::is_temp_name;
/// assert!(is_temp_name(".map.tmp-12-0.npz"));
/// assert!(is_temp_name(".dymsum-staging-12-0"));
/// assert!(is_temp_name(".dymsum-ready-12-3"));
/// assert!(!is_temp_name("map.npz"));
/// ```
pub fn is_temp_name(name: &str) -> bool {
    temp_owner(name).is_some() || folder_owner(name).is_some()
}

/// One step of [`StagedDir::commit`], for tests that abort the swap at
/// each step (see the module docs for their order).
#[doc(hidden)]
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Step {
    /// Writing the manifest.
    Manifest,
    /// Renaming the staging folder to its ready name (the commit point).
    Ready,
    /// Moving one staged file into the folder.
    Move(String),
    /// Removing one earlier file the new set does not replace.
    Remove(String),
    /// Removing the emptied ready folder.
    Done,
}

/// A staging folder for a new set of files in `dir` (module docs). Dropped
/// without a commit (an error while writing), it is removed and `dir` is
/// left as it was.
#[derive(Debug)]
pub struct StagedDir {
    dir: PathBuf,
    staging: PathBuf,
    /// Whether dropping removes the staging folder.
    armed: bool,
}

impl StagedDir {
    /// Creates the staging folder `dir/.dymsum-staging-PID-N` (`dir` must
    /// exist).
    ///
    /// # Errors
    /// [`FileError::Write`] naming the staging folder when it cannot be
    /// created (permissions, a read-only or full file system).
    pub fn create(dir: &Path) -> Result<StagedDir, FileError> {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let staging = dir.join(format!("{STAGING_PREFIX}{}-{n}", std::process::id()));
        std::fs::create_dir(&staging).map_err(|source| FileError::Write {
            path: staging.clone(),
            source,
        })?;
        Ok(StagedDir {
            dir: dir.to_path_buf(),
            staging,
            armed: true,
        })
    }

    /// Where to write the new files (plain names, no subfolders).
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// Swaps the staged files into the folder and removes the earlier files
    /// that `replaces` (by name) and the new set does not overwrite (module
    /// docs, steps 1–5).
    ///
    /// # Errors
    /// [`FileError`] naming the entry concerned when the staging folder
    /// cannot be listed, holds a subfolder or a name that is not UTF-8, or
    /// a rename or removal fails. Before the commit point the earlier files
    /// are intact (and the staging folder is removed); after it the new set
    /// is complete and the next [`recover`] finishes the swap.
    pub fn commit(self, replaces: &dyn Fn(&str) -> bool) -> Result<(), FileError> {
        self.commit_with(replaces, &mut |_| Ok(()))
    }

    /// [`StagedDir::commit`], calling `step` before each step; an error
    /// from `step` stops the swap there as a kill would (nothing cleaned
    /// up) and is returned.
    ///
    /// # Errors
    /// Those of [`StagedDir::commit`], and `step`'s.
    #[doc(hidden)]
    pub fn commit_with(
        mut self,
        replaces: &dyn Fn(&str) -> bool,
        step: &mut dyn FnMut(&Step) -> io::Result<()>,
    ) -> Result<(), FileError> {
        let names = staged_names(&self.staging)?;
        let mut killed = |s: &Step, path: &Path| -> Result<(), FileError> {
            step(s).map_err(|source| FileError::Write {
                path: path.to_path_buf(),
                source,
            })
        };
        let manifest = self.staging.join(MANIFEST);
        if let Err(e) = killed(&Step::Manifest, &manifest) {
            self.armed = false;
            return Err(e);
        }
        write_atomic(&manifest, |w| {
            for n in &names {
                writeln!(w, "{n}")?;
            }
            Ok(())
        })?;
        let ready = self.staging.with_file_name(
            self.staging
                .file_name()
                .and_then(|n| n.to_str())
                .and_then(|n| n.strip_prefix(STAGING_PREFIX))
                .map(|rest| format!("{READY_PREFIX}{rest}"))
                .expect("a staging folder is named by StagedDir::create"),
        );
        if let Err(e) = killed(&Step::Ready, &ready) {
            self.armed = false;
            return Err(e);
        }
        std::fs::rename(&self.staging, &ready).map_err(|source| FileError::Write {
            path: ready.clone(),
            source,
        })?;
        // The commit point is passed: from here on the ready folder is
        // finished, by this run or the next.
        self.armed = false;
        sync_dir(&self.dir);
        finish(&self.dir, &ready, replaces, &mut killed)
    }
}

impl Drop for StagedDir {
    fn drop(&mut self) {
        if self.armed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

/// The files in a staging folder, in the order they are moved: by name,
/// `index.json` last.
fn staged_names(staging: &Path) -> Result<Vec<String>, FileError> {
    let err = |source| FileError::Read {
        path: staging.to_path_buf(),
        source,
    };
    let mut names = Vec::new();
    for e in std::fs::read_dir(staging).map_err(err)? {
        let e = e.map_err(err)?;
        let path = e.path();
        let Some(name) = e.file_name().to_str().map(str::to_string) else {
            return Err(FileError::Write {
                path,
                source: io::Error::new(io::ErrorKind::InvalidData, "the name is not UTF-8"),
            });
        };
        if name == MANIFEST || temp_owner(&name).is_some() {
            continue;
        }
        if !e.file_type().map_err(err)?.is_file() {
            return Err(FileError::Write {
                path,
                source: io::Error::new(io::ErrorKind::InvalidData, "not a plain file"),
            });
        }
        names.push(name);
    }
    names.sort_by(|a, b| (a == INDEX, a).cmp(&(b == INDEX, b)));
    Ok(names)
}

/// Steps 3–5 of the swap for the ready folder `ready` in `dir`.
fn finish(
    dir: &Path,
    ready: &Path,
    replaces: &dyn Fn(&str) -> bool,
    step: &mut dyn FnMut(&Step, &Path) -> Result<(), FileError>,
) -> Result<(), FileError> {
    let manifest = ready.join(MANIFEST);
    let text = std::fs::read_to_string(&manifest).map_err(|source| FileError::Read {
        path: manifest.clone(),
        source,
    })?;
    let names: Vec<&str> = text.lines().filter(|l| !l.is_empty()).collect();
    for name in &names {
        let (from, to) = (ready.join(name), dir.join(name));
        step(&Step::Move((*name).to_string()), &to)?;
        match std::fs::rename(&from, &to) {
            Ok(()) => {}
            // Moved before a kill.
            Err(e) if e.kind() == io::ErrorKind::NotFound && !from.exists() => {}
            Err(source) => return Err(FileError::Write { path: to, source }),
        }
    }
    let keep: BTreeSet<&str> = names.iter().copied().collect();
    let err = |source| FileError::Read {
        path: dir.to_path_buf(),
        source,
    };
    let mut old = Vec::new();
    for e in std::fs::read_dir(dir).map_err(err)? {
        let e = e.map_err(err)?;
        if let Some(name) = e.file_name().to_str() {
            if replaces(name) && !keep.contains(name) && e.file_type().is_ok_and(|t| t.is_file()) {
                old.push(name.to_string());
            }
        }
    }
    old.sort();
    for name in old {
        let path = dir.join(&name);
        step(&Step::Remove(name), &path)?;
        match std::fs::remove_file(&path) {
            Ok(()) => {}
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(source) => return Err(FileError::Write { path, source }),
        }
    }
    step(&Step::Done, ready)?;
    std::fs::remove_dir_all(ready).map_err(|source| FileError::Write {
        path: ready.to_path_buf(),
        source,
    })?;
    sync_dir(dir);
    Ok(())
}

/// Syncs a folder's entries (the renames in it), where the platform allows
/// opening a folder; best effort.
fn sync_dir(dir: &Path) {
    if let Ok(f) = std::fs::File::open(dir) {
        let _ = f.sync_all();
    }
}

/// What [`recover`] did in a folder.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Recovered {
    /// Temporary files and staging folders of killed runs, removed.
    pub removed: Vec<PathBuf>,
    /// Swaps of killed runs finished (their ready folders).
    pub finished: Vec<PathBuf>,
    /// Temporary entries of running processes, left alone.
    pub live: Vec<PathBuf>,
}

/// Cleans up after killed runs in `dir` before a new run uses it (module
/// docs): finishes the swaps of killed runs (`replaces` as for
/// [`StagedDir::commit`]), removes their staging folders and their
/// temporary files ([`crate::atomic::remove_stale_temps`]), and leaves
/// running processes' entries alone.
///
/// # Errors
/// [`FileError`] naming the entry concerned when `dir` cannot be listed or
/// an entry cannot be removed, or a swap cannot be finished.
pub fn recover(dir: &Path, replaces: &dyn Fn(&str) -> bool) -> Result<Recovered, FileError> {
    recover_with(dir, replaces, &owner_alive)
}

pub(crate) fn recover_with(
    dir: &Path,
    replaces: &dyn Fn(&str) -> bool,
    alive: &dyn Fn(u32) -> bool,
) -> Result<Recovered, FileError> {
    let mut out = Recovered::default();
    let err = |source| FileError::Read {
        path: dir.to_path_buf(),
        source,
    };
    let mut folders = Vec::new();
    for e in std::fs::read_dir(dir).map_err(err)? {
        let e = e.map_err(err)?;
        if let Some((ready, pid)) = e.file_name().to_str().and_then(folder_owner) {
            if e.file_type().is_ok_and(|t| t.is_dir()) {
                folders.push((ready, pid, e.path()));
            }
        }
    }
    folders.sort();
    for (ready, pid, path) in folders {
        if alive(pid) {
            out.live.push(path);
        } else if ready {
            finish(dir, &path, replaces, &mut |_, _| Ok(()))?;
            out.finished.push(path);
        } else {
            std::fs::remove_dir_all(&path).map_err(|source| FileError::Write {
                path: path.clone(),
                source,
            })?;
            out.removed.push(path);
        }
    }
    let temps = remove_stale_temps_with(dir, alive)?;
    out.removed.extend(temps.removed);
    out.live.extend(temps.live);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    fn temp_dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("dymsum-staging-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    /// Every entry of `dir` (files only, with contents; folders by name).
    fn contents(dir: &Path) -> BTreeMap<String, String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| {
                let e = e.unwrap();
                let name = e.file_name().into_string().unwrap();
                let body = if e.file_type().unwrap().is_dir() {
                    "<dir>".to_string()
                } else {
                    std::fs::read_to_string(e.path()).unwrap()
                };
                (name, body)
            })
            .collect()
    }

    fn own(name: &str) -> bool {
        name == "index.json" || name == "map.npz" || name.starts_with("slice_")
    }

    fn set(entries: &[(&str, &str)]) -> BTreeMap<String, String> {
        entries
            .iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect()
    }

    /// A killed swap: the folder's own files are the old set or (after the
    /// next run's recovery) the new one, with `notes.txt` kept; no
    /// temporary entry is left after the recovery.
    #[test]
    fn an_abort_at_each_step_of_the_swap_keeps_the_old_set_or_completes_the_new() {
        let old = set(&[
            ("index.json", "old index"),
            ("notes.txt", "mine"),
            ("slice_00000.off", "old 0"),
            ("slice_00001.off", "old 1"),
            ("slice_00002.off", "old 2"),
        ]);
        let new = set(&[
            ("index.json", "new index"),
            ("notes.txt", "mine"),
            ("slice_00000.off", "new 0"),
            ("slice_00001.off", "new 1"),
        ]);
        let mut steps_seen = 0;
        for k in 0.. {
            let dir = temp_dir(&format!("abort-{k}"));
            for (n, b) in &old {
                std::fs::write(dir.join(n), b).unwrap();
            }
            let staged = StagedDir::create(&dir).unwrap();
            for (n, b) in &new {
                if own(n) {
                    std::fs::write(staged.path().join(n), b).unwrap();
                }
            }
            let mut seen = Vec::new();
            let r = staged.commit_with(&own, &mut |s| {
                seen.push(s.clone());
                if seen.len() > k {
                    Err(io::Error::other("killed"))
                } else {
                    Ok(())
                }
            });
            let committed = seen.iter().any(|s| matches!(s, Step::Move(_)));
            let mut now = contents(&dir);
            now.retain(|n, _| !is_temp_name(n));
            if r.is_ok() {
                assert_eq!(now, new, "step {k}");
                assert_eq!(contents(&dir), new, "no temporary entry left");
                steps_seen = seen.len();
                std::fs::remove_dir_all(&dir).unwrap();
                break;
            }
            if !committed {
                // Killed before the commit point: the old set, untouched.
                assert_eq!(now, old, "step {k} ({:?})", seen.last());
            }
            // The next run (this process's entries count as a dead owner's).
            let rec = recover_with(&dir, &own, &|_| false).unwrap();
            assert!(rec.live.is_empty());
            let after = contents(&dir);
            assert!(
                after == old || after == new,
                "step {k} ({:?}): {after:?}",
                seen.last()
            );
            assert_eq!(after == new, committed, "step {k}");
            std::fs::remove_dir_all(&dir).unwrap();
        }
        // Manifest, ready, 3 moves, 1 removal, done.
        assert_eq!(steps_seen, 7);
    }

    #[test]
    fn live_owners_entries_are_kept_and_dead_owners_removed() {
        let dir = temp_dir("owners");
        std::fs::write(dir.join(".map.tmp-11-0.npz"), "dead").unwrap();
        std::fs::write(dir.join(".map.tmp-22-k3_x.npz"), "live").unwrap();
        std::fs::create_dir(dir.join(".dymsum-staging-11-4")).unwrap();
        std::fs::create_dir(dir.join(".dymsum-staging-22-5")).unwrap();
        std::fs::write(dir.join("map.npz"), "kept").unwrap();
        std::fs::write(dir.join(".tmp-11-0"), "not a temp name").unwrap();
        let rec = recover_with(&dir, &own, &|pid| pid == 22).unwrap();
        assert_eq!(rec.removed.len(), 2);
        assert_eq!(rec.live.len(), 2);
        assert_eq!(
            contents(&dir).into_keys().collect::<Vec<_>>(),
            [
                ".dymsum-staging-22-5",
                ".map.tmp-22-k3_x.npz",
                ".tmp-11-0",
                "map.npz"
            ]
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_dropped_staging_folder_leaves_the_folder_as_it_was() {
        let dir = temp_dir("drop");
        std::fs::write(dir.join("map.npz"), "old").unwrap();
        {
            let staged = StagedDir::create(&dir).unwrap();
            std::fs::write(staged.path().join("map.npz"), "half").unwrap();
        }
        assert_eq!(contents(&dir), set(&[("map.npz", "old")]));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
