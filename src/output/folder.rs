//! An output folder that a person can trust: whole files or none, one run at a
//! time, and nothing left over from the same command's earlier run.
//!
//! * Every file is written under a temporary name in the same folder and renamed into place
//!   when complete, so a file is never seen half-written (a rename within a folder is atomic).
//!   A temporary name is not predictable (a random suffix) and is created new, so that a link
//!   planted at it is never followed; so is the private staging folder.
//! * A run holds the operating system's lock on `.slideroute.lock` (its process id written in
//!   it for the message) while it writes; a second run into the same folder is refused. The lock
//!   goes with the process, however it ends; a file left by a run that no longer exists is taken
//!   over.
//! * The folder keeps a record of what each command wrote into it ([`RECORD`]: the command and
//!   the file, one per line, its manifest marked). Before a run renames its first file in, it
//!   removes its command's earlier manifest (`summary.json`, `check.json`, …), and the record
//!   names each file before it is renamed in; the manifest is written last
//!   ([`OutputFolder::write_manifest`]), after the files of the command's earlier run that this one
//!   did not write are removed. So a folder with a command's manifest holds exactly the files
//!   it names (from that command), and a run killed part way leaves a folder without one,
//!   whose every file the next run of that command knows and replaces or removes. Another
//!   command's files, and files slideroute did not write, are never touched — whatever their
//!   names.
//! * Nothing is written, read for removal or removed through a link: a link (or anything but a
//!   plain file or a real folder) where an output or its folder goes is refused, naming it.

use super::OutputError;
use std::path::{Path, PathBuf};

/// The record of what each command wrote into a folder: lines `COMMAND<TAB>FILE` (the file
/// relative to the folder).
pub(crate) const RECORD: &str = ".slideroute-outputs";

const LOCK: &str = ".slideroute.lock";

/// An output folder a person can trust, locked while one command writes into it: each file
/// appears whole or not at all, a second run into the same folder is refused, and the files this
/// command wrote there before and did not write again are removed when it finishes (another
/// command's files, and files slideroute did not write, are never touched). Nothing is written or
/// removed through a link.
///
/// ```
/// use slideroute::output::OutputFolder;
/// let dir = std::env::temp_dir().join(format!("slideroute-doc-folder-{}", std::process::id()));
/// let mut folder = OutputFolder::open(&dir, "notes")?;
/// // A second run into the folder while this one holds it is refused.
/// assert!(OutputFolder::open(&dir, "notes").is_err());
/// folder.write_bytes("notes.txt", b"whole or not at all\n")?;
/// assert_eq!(folder.written(), [("notes.txt".to_string(), 20)]);
/// folder.finish()?;
/// assert_eq!(std::fs::read_to_string(dir.join("notes.txt"))?, "whole or not at all\n");
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct OutputFolder {
    dir: PathBuf,
    command: &'static str,
    written: Vec<(String, u64)>,
    /// The open lock file, locked (the lock is the operating system's, released when it closes).
    lock: std::fs::File,
    /// The private staging folder, once made.
    staging: Option<PathBuf>,
    /// The files of this run that are manifests.
    manifests: Vec<String>,
    /// Whether this run has begun to replace the folder's files: this command's earlier
    /// manifests are gone, and the record names every file renamed in.
    opened_up: bool,
    /// Whether this command's earlier files that this run did not write are gone.
    stale_removed: bool,
}

/// A suffix no other process can guess: the process id and a number from the standard
/// library's randomly seeded hasher.
fn unguessable() -> String {
    use std::hash::{BuildHasher, Hasher};
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u128(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos()),
    );
    format!("{}.{:016x}", std::process::id(), h.finish())
}

/// Creates a new empty file at `dir/.{stem}.{unguessable}.tmp` (never an existing file or a
/// link: created new) and gives its path.
fn new_temporary(dir: &Path, stem: &str) -> std::io::Result<PathBuf> {
    let mut last = None;
    for _ in 0..16 {
        let tmp = dir.join(format!(".{stem}.{}.tmp", unguessable()));
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
        {
            Ok(_) => return Ok(tmp),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or_else(|| std::io::Error::other("no temporary name")))
}

/// Writes the file `path` through `write`, which is given a temporary path beside it (made new,
/// never a link) and renamed over `path` when `write` succeeded: the file is whole, or as it
/// was. For a single file a caller names (a picture), outside any [`OutputFolder`].
#[cfg(feature = "plots")]
pub(crate) fn write_whole(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), OutputError> {
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let stem = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| OutputError::Write(format!("{}: not a file name", path.display())))?;
    let tmp = new_temporary(parent, &stem)
        .map_err(|e| OutputError::Write(format!("{}: cannot write: {e}", parent.display())))?;
    let result = write(&tmp).and_then(|()| {
        std::fs::rename(&tmp, path).map_err(|e| format!("{}: cannot write: {e}", path.display()))
    });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(OutputError::Write)
}

/// Whether `name` is one of slideroute's temporaries (`.NAME.PID.HEX.tmp`) or staging folders
/// (`.slideroute-staging.PID.HEX`): what a run killed while it wrote leaves behind.
fn leftover(name: &str) -> bool {
    let tail = |rest: &str| {
        rest.rsplit_once('.').is_some_and(|(pid, hex)| {
            let pid = pid.rsplit('.').next().unwrap_or("");
            !pid.is_empty()
                && pid.bytes().all(|b| b.is_ascii_digit())
                && hex.len() == 16
                && hex.bytes().all(|b| b.is_ascii_hexdigit())
        })
    };
    if let Some(rest) = name.strip_prefix(".slideroute-staging.") {
        return tail(rest);
    }
    name.starts_with('.') && name.strip_suffix(".tmp").is_some_and(tail)
}

/// Removes what runs killed while they wrote into `dir` left there — temporaries, staging
/// folders — and in its folders one level down: plain files and real folders only, never a
/// link. Called with the lock held, so that no other run is writing there.
fn remove_leftovers(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let (Ok(kind), name) = (entry.file_type(), entry.file_name()) else {
            continue;
        };
        let name = name.to_string_lossy();
        let path = entry.path();
        if kind.is_file() && leftover(&name) {
            let _ = std::fs::remove_file(&path);
        } else if kind.is_dir() && leftover(&name) {
            let _ = std::fs::remove_dir_all(&path);
        } else if kind.is_dir() && !name.starts_with('.') {
            for inner in std::fs::read_dir(&path).into_iter().flatten().flatten() {
                let inner_name = inner.file_name();
                if inner.file_type().is_ok_and(|k| k.is_file())
                    && leftover(&inner_name.to_string_lossy())
                {
                    let _ = std::fs::remove_file(inner.path());
                }
            }
        }
    }
}

/// The lock file's identity (device, inode), to tell that the path still names the file locked.
#[cfg(unix)]
fn identity(m: &std::fs::Metadata) -> (u64, u64) {
    use std::os::unix::fs::MetadataExt;
    (m.dev(), m.ino())
}

#[cfg(not(unix))]
fn identity(_: &std::fs::Metadata) -> (u64, u64) {
    (0, 0)
}

/// One line of a folder's [`RECORD`]: the command, the file (relative to the folder), and
/// whether the file is that command's manifest (`summary.json`, `check.json`, …: written last,
/// removed first).
#[derive(Debug, Clone, PartialEq)]
struct Entry {
    command: String,
    file: String,
    manifest: bool,
}

/// The entries of a folder's [`RECORD`]: none where there is no record, or it is not a plain
/// file. A line is `COMMAND<TAB>FILE`, with `<TAB>manifest` after a manifest.
fn read_record(dir: &Path) -> Vec<Entry> {
    let path = dir.join(RECORD);
    let plain = std::fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_file());
    if !plain {
        return Vec::new();
    }
    std::fs::read_to_string(&path)
        .unwrap_or_default()
        .lines()
        .filter_map(|line| {
            let (command, rest) = line.split_once('\t')?;
            let (file, manifest) = match rest.split_once('\t') {
                Some((file, "manifest")) => (file, true),
                Some(_) => return None,
                None => (rest, false),
            };
            recordable(file).then(|| Entry {
                command: command.to_string(),
                file: file.to_string(),
                manifest,
            })
        })
        .collect()
}

/// Writes `entries` as `dir`'s [`RECORD`], whole (a temporary renamed into place).
fn write_record(dir: &Path, entries: &[Entry]) -> Result<(), String> {
    let mut text = String::new();
    for e in entries {
        text.push_str(&e.command);
        text.push('\t');
        text.push_str(&e.file);
        if e.manifest {
            text.push_str("\tmanifest");
        }
        text.push('\n');
    }
    let path = dir.join(RECORD);
    let tmp =
        new_temporary(dir, RECORD).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    std::fs::write(&tmp, text)
        .and_then(|()| std::fs::rename(&tmp, &path))
        .map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            format!("{}: cannot write: {e}", path.display())
        })
}

/// Whether `name` is a path a record may name: relative, inside the folder, no `..`.
fn recordable(name: &str) -> bool {
    let p = Path::new(name);
    !name.is_empty()
        && p.components()
            .all(|c| matches!(c, std::path::Component::Normal(_)))
}

/// Whether `path` is a plain file (not a link, not a folder).
fn plain_file(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_file())
}

/// Why `name` (relative to `dir`) is no place for an output: a link, or something other than a
/// real folder, on the way to it (a link at `out/paper` would take `paper/route.csv` into
/// another folder), or a link or folder where the file itself goes. `None` where the way is
/// real folders (or nothing yet) and the place a plain file or free.
fn not_a_place_for_output(dir: &Path, name: &str) -> Option<String> {
    let mut at = dir.to_path_buf();
    let parts: Vec<&std::ffi::OsStr> = Path::new(name).iter().collect();
    for (k, part) in parts.iter().enumerate() {
        at.push(part);
        let Ok(m) = std::fs::symlink_metadata(&at) else {
            return None; // Nothing there yet: made new below, by this run.
        };
        let last = k + 1 == parts.len();
        let kind = m.file_type();
        if kind.is_symlink() {
            return Some(format!(
                "{}: is a link where slideroute writes its output; it is not followed: remove \
                 it or choose another --out",
                at.display()
            ));
        }
        if (last && !kind.is_file()) || (!last && !kind.is_dir()) {
            return Some(format!(
                "{}: is not a {} where slideroute writes its output: remove it or choose \
                 another --out",
                at.display(),
                if last { "plain file" } else { "folder" }
            ));
        }
    }
    None
}

impl OutputFolder {
    /// Creates `dir` if needed and locks it for `command` (`run`, `sweep`, …: the name its
    /// files are recorded under); the error says why not, naming the folder.
    pub fn open(dir: &Path, command: &'static str) -> Result<OutputFolder, OutputError> {
        OutputFolder::lock(dir, command).map_err(OutputError::Write)
    }

    /// [`OutputFolder::open`], its failure in words.
    fn lock(dir: &Path, command: &'static str) -> Result<OutputFolder, String> {
        if std::fs::metadata(dir).is_ok_and(|m| !m.is_dir()) {
            return Err(format!(
                "{}: is a file, not a folder: --out names the folder the outputs go into",
                dir.display()
            ));
        }
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("{}: cannot create: {e}", dir.display()))?;
        let path = dir.join(LOCK);
        let cannot = |e: std::io::Error| format!("{}: cannot lock: {e}", path.display());
        for _ in 0..8 {
            // Never through a link put in the lock's place.
            if std::fs::symlink_metadata(&path).is_ok_and(|m| !m.file_type().is_file()) {
                return Err(format!(
                    "{}: is not a plain file (a link or a folder where the lock goes); remove \
                     it or choose another --out",
                    path.display()
                ));
            }
            let mut file = std::fs::OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .map_err(cannot)?;
            match file.try_lock() {
                Ok(()) => {}
                Err(std::fs::TryLockError::WouldBlock) => {
                    let holder = std::fs::read_to_string(&path).unwrap_or_default();
                    let holder = holder.trim();
                    let who = if holder.parse::<u32>().is_ok() {
                        format!(" (process {holder})")
                    } else {
                        String::new()
                    };
                    return Err(format!(
                        "{}: another slideroute run{who} is writing into this folder; wait for \
                         it or choose another --out",
                        dir.display()
                    ));
                }
                Err(std::fs::TryLockError::Error(e)) => return Err(cannot(e)),
            }
            // Locked: the path must still name this file (a run that just finished removes
            // its lock file; then lock the new one).
            let same = match (file.metadata(), std::fs::symlink_metadata(&path)) {
                (Ok(a), Ok(b)) => identity(&a) == identity(&b),
                _ => false,
            };
            if !same {
                continue;
            }
            use std::io::{Seek, Write};
            let _ = file.set_len(0);
            let _ = file.rewind();
            let _ = write!(file, "{}", std::process::id());
            remove_leftovers(dir);
            return Ok(OutputFolder {
                dir: dir.to_path_buf(),
                command,
                written: Vec::new(),
                lock: file,
                staging: None,
                manifests: Vec::new(),
                opened_up: false,
                stale_removed: false,
            });
        }
        Err(format!("{}: cannot lock the folder", dir.display()))
    }

    /// The folder `name` inside this one, opened for `command` as [`OutputFolder::open`] does; refused
    /// where a link (or a file) stands at its name: it is not followed.
    pub(crate) fn open_inside(
        &self,
        name: &str,
        command: &'static str,
    ) -> Result<OutputFolder, OutputError> {
        let dir = self.dir.join(name);
        match std::fs::symlink_metadata(&dir) {
            Ok(m) if m.file_type().is_symlink() || !m.is_dir() => Err(OutputError::Write(format!(
                "{}: is {} where slideroute writes its output; it is not followed: remove it or \
                 choose another --out",
                dir.display(),
                if m.file_type().is_symlink() {
                    "a link"
                } else {
                    "not a folder"
                }
            ))),
            _ => OutputFolder::open(&dir, command),
        }
    }

    /// Writes `name` (relative; its folder is created) through `write`, which is given the
    /// temporary path to write to; renames it into place when `write` succeeded. Returns the
    /// final path.
    pub fn write_with<E: Into<OutputError>>(
        &mut self,
        name: &str,
        write: impl FnOnce(&Path) -> Result<(), E>,
    ) -> Result<PathBuf, OutputError> {
        let path = self.dir.join(name);
        if let Some(why) = not_a_place_for_output(&self.dir, name) {
            return Err(OutputError::Write(why));
        }
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)
                .map_err(|e| format!("{}: cannot create: {e}", parent.display()))?;
        }
        let file_name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let parent = path.parent().unwrap_or(&self.dir);
        let tmp = new_temporary(parent, &file_name)
            .map_err(|e| format!("{}: cannot write: {e}", parent.display()))?;
        let result = write(&tmp).map_err(Into::into).and_then(|()| {
            self.about_to_place(name)
                .and_then(|()| {
                    std::fs::rename(&tmp, &path)
                        .map_err(|e| format!("{}: cannot write: {e}", path.display()))
                })
                .map_err(OutputError::Write)
        });
        if result.is_err() {
            let _ = std::fs::remove_file(&tmp);
        }
        result?;
        let bytes = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        self.written.retain(|(n, _)| n != name);
        self.written.push((name.to_string(), bytes));
        Ok(path)
    }

    /// [`OutputFolder::write_with`] for bytes already in hand.
    pub fn write_bytes(&mut self, name: &str, bytes: &[u8]) -> Result<PathBuf, OutputError> {
        self.write_with(name, |tmp| {
            std::fs::write(tmp, bytes).map_err(|e| format!("{}: cannot write: {e}", tmp.display()))
        })
    }

    /// A private folder inside this one (made new under a name no one can guess, removed when
    /// the run ends) for writers that want a path of their own to write into;
    /// [`OutputFolder::adopt`] moves their files into place.
    pub(crate) fn staging(&mut self) -> Result<PathBuf, String> {
        if let Some(d) = &self.staging {
            return Ok(d.clone());
        }
        let d = self
            .dir
            .join(format!(".slideroute-staging.{}", unguessable()));
        std::fs::create_dir(&d).map_err(|e| format!("{}: cannot create: {e}", d.display()))?;
        self.staging = Some(d.clone());
        Ok(d)
    }

    /// Moves a finished file `from` (in [`OutputFolder::staging`]) into place as `name`.
    pub(crate) fn adopt(&mut self, name: &str, from: &Path) -> Result<PathBuf, OutputError> {
        self.write_with(name, |tmp| {
            std::fs::rename(from, tmp).map_err(|e| format!("{}: cannot move: {e}", from.display()))
        })
    }

    /// [`OutputFolder::adopt`] for each of `staged`, under its own file name (the pictures').
    #[cfg(any(feature = "plots", test))]
    pub(crate) fn adopt_all(&mut self, staged: Vec<PathBuf>) -> Result<Vec<PathBuf>, OutputError> {
        staged
            .iter()
            .map(|from| {
                let name = from
                    .file_name()
                    .map(|n| n.to_string_lossy().into_owned())
                    .unwrap_or_default();
                self.adopt(&name, from)
            })
            .collect()
    }

    /// The files written so far: relative name and size in bytes.
    pub fn written(&self) -> &[(String, u64)] {
        &self.written
    }

    /// Before `name` is renamed into place: the first time, this command's earlier manifests
    /// are removed (from then on until this run's manifest is written, the folder has none of
    /// this command's: recognisably incomplete, should the run be killed); and the record is
    /// made to name `name`, so that whatever a killed run renamed in is known to the next run,
    /// which removes it if it does not write it again.
    fn about_to_place(&mut self, name: &str) -> Result<(), String> {
        let mut record = read_record(&self.dir);
        if !self.opened_up {
            for e in record
                .iter()
                .filter(|e| e.command == self.command && e.manifest)
            {
                let path = self.dir.join(&e.file);
                if not_a_place_for_output(&self.dir, &e.file).is_none() && plain_file(&path) {
                    std::fs::remove_file(&path).map_err(|err| {
                        format!(
                            "{}: cannot remove this command's earlier summary: {err}",
                            path.display()
                        )
                    })?;
                }
            }
            self.opened_up = true;
        }
        let manifest = self.manifests.iter().any(|m| m == name);
        let listed = record
            .iter_mut()
            .find(|e| e.command == self.command && e.file == name);
        match listed {
            Some(e) if e.manifest == manifest => return Ok(()),
            Some(e) => e.manifest = manifest,
            None => record.push(Entry {
                command: self.command.to_string(),
                file: name.to_string(),
                manifest,
            }),
        }
        write_record(&self.dir, &record)
    }

    /// Writes `bytes` as `name`, this command's manifest (what produced the folder and the
    /// files in it): first the files this command wrote here before and did not write this
    /// time are removed, so that the manifest, written last, names exactly the files beside it.
    pub(crate) fn write_manifest(
        &mut self,
        name: &str,
        bytes: &[u8],
    ) -> Result<PathBuf, OutputError> {
        self.remove_stale()?;
        // Known as a manifest before it is placed: the record marks it so from the start.
        self.manifests.push(name.to_string());
        let written = self.write_bytes(name, bytes);
        if written.is_err() {
            self.manifests.retain(|m| m != name);
        }
        written
    }

    /// Removes the files this command wrote here before ([`RECORD`]) that this run did not
    /// write (and will not: called once its files are written), and their folders if that
    /// leaves them empty. Never through a link, never anything but a plain file.
    fn remove_stale(&mut self) -> Result<(), String> {
        if self.stale_removed {
            return Ok(());
        }
        for e in read_record(&self.dir) {
            let path = self.dir.join(&e.file);
            let wrote = self.written.iter().any(|(n, _)| *n == e.file);
            if e.command == self.command
                && !wrote
                && not_a_place_for_output(&self.dir, &e.file).is_none()
                && plain_file(&path)
            {
                std::fs::remove_file(&path).map_err(|err| {
                    format!(
                        "{}: cannot remove this command's earlier file: {err}",
                        path.display()
                    )
                })?;
                if let Some(parent) = path.parent().filter(|p| *p != self.dir) {
                    let _ = std::fs::remove_dir(parent); // only if empty
                }
            }
        }
        self.stale_removed = true;
        Ok(())
    }

    /// Removes this command's earlier files that this run did not write (where no manifest
    /// did); records what this run wrote (its manifests marked) beside the other commands'
    /// files that are still there; then unlocks.
    pub fn finish(mut self) -> Result<(), OutputError> {
        self.remove_stale()?;
        let mut kept: Vec<Entry> = Vec::new();
        for e in read_record(&self.dir) {
            let wrote = self.written.iter().any(|(n, _)| *n == e.file);
            let real = not_a_place_for_output(&self.dir, &e.file).is_none();
            if e.command != self.command
                && !wrote
                && real
                && plain_file(&self.dir.join(&e.file))
                && !kept.iter().any(|k| k.file == e.file)
            {
                kept.push(e);
            }
        }
        kept.extend(self.written.iter().map(|(n, _)| Entry {
            command: self.command.to_string(),
            file: n.clone(),
            manifest: self.manifests.contains(n),
        }));
        write_record(&self.dir, &kept).map_err(OutputError::Write)
    }
}

impl Drop for OutputFolder {
    fn drop(&mut self) {
        if let Some(d) = &self.staging {
            // A link put in its place is removed, not followed.
            let _ = std::fs::remove_dir_all(d);
        }
        // The lock file goes while still locked (a run waiting on it then finds the path gone
        // and locks a new one); the lock goes with the file's closing.
        let _ = std::fs::remove_file(self.dir.join(LOCK));
        let _ = self.lock.unlock();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("slideroute-folder-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn a_second_run_into_a_locked_folder_is_refused_and_a_stale_lock_is_taken_over() {
        let d = temp("lock");
        let first = OutputFolder::open(&d, "run").unwrap();
        let e = OutputFolder::open(&d, "run").unwrap_err().to_string();
        assert!(e.contains("another slideroute run"), "{e}");
        drop(first);
        assert!(OutputFolder::open(&d, "run").is_ok());
        // A lock file left by a run that no longer holds it (killed, say).
        std::fs::write(d.join(LOCK), "4294967295").unwrap();
        let f = OutputFolder::open(&d, "run").unwrap();
        // Its process id is in the lock from the start, for the message.
        assert_eq!(
            std::fs::read_to_string(d.join(LOCK)).unwrap(),
            std::process::id().to_string()
        );
        let e = OutputFolder::open(&d, "run").unwrap_err().to_string();
        assert!(
            e.contains(&format!("(process {})", std::process::id())),
            "{e}"
        );
        drop(f);
        assert!(!d.join(LOCK).exists());
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn an_out_that_is_a_file_is_refused_as_one_and_left_as_it_was() {
        // Before: `out: cannot create: File exists (os error 17)`.
        let d = temp("is-a-file");
        std::fs::write(&d, "mine").unwrap();
        let e = OutputFolder::open(&d, "run").unwrap_err().to_string();
        assert!(
            e.ends_with("is a file, not a folder: --out names the folder the outputs go into"),
            "{e}"
        );
        assert_eq!(std::fs::read_to_string(&d).unwrap(), "mine");
        let _ = std::fs::remove_file(&d);
    }

    #[test]
    fn runs_started_together_into_one_folder_never_hold_it_at_once() {
        let d = temp("race");
        std::fs::create_dir_all(&d).unwrap();
        let holders = std::sync::atomic::AtomicUsize::new(0);
        let most = std::sync::atomic::AtomicUsize::new(0);
        std::thread::scope(|s| {
            for _ in 0..8 {
                s.spawn(|| {
                    for _ in 0..50 {
                        if let Ok(f) = OutputFolder::open(&d, "run") {
                            let now = holders.fetch_add(1, std::sync::atomic::Ordering::SeqCst) + 1;
                            most.fetch_max(now, std::sync::atomic::Ordering::SeqCst);
                            std::thread::yield_now();
                            holders.fetch_sub(1, std::sync::atomic::Ordering::SeqCst);
                            drop(f);
                        }
                    }
                });
            }
        });
        assert_eq!(most.into_inner(), 1);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn what_a_killed_run_left_is_removed_by_the_next_and_nothing_else() {
        let d = temp("leftovers");
        std::fs::create_dir_all(d.join("paper")).unwrap();
        let left = [
            ".route.csv.4242.00ff00ff00ff00ff.tmp",
            "paper/.route.csv.7.0123456789abcdef.tmp",
            ".slideroute-outputs.99.fedcba9876543210.tmp",
        ];
        let kept = [
            ".route.csv.4242.tmp",
            "notes.tmp",
            ".mine.tmp",
            ".route.csv.4242.00ff00ff00ff00fg.tmp",
            "paper/route.csv",
        ];
        for f in left.iter().chain(&kept) {
            std::fs::write(d.join(f), "x").unwrap();
        }
        std::fs::create_dir_all(d.join(".slideroute-staging.4242.0011223344556677")).unwrap();
        std::fs::write(
            d.join(".slideroute-staging.4242.0011223344556677/plan.svg"),
            "x",
        )
        .unwrap();
        let f = OutputFolder::open(&d, "run").unwrap();
        for g in left {
            assert!(!d.join(g).exists(), "{g}");
        }
        assert!(!d.join(".slideroute-staging.4242.0011223344556677").exists());
        for g in kept {
            assert!(d.join(g).exists(), "{g}");
        }
        drop(f);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[cfg(unix)]
    #[test]
    fn links_planted_at_temporary_names_and_the_lock_are_not_followed() {
        let d = temp("planted");
        let target = temp("planted-target");
        std::fs::create_dir_all(&d).unwrap();
        std::fs::create_dir_all(&target).unwrap();
        std::fs::write(target.join("theirs"), "theirs").unwrap();
        // The names temporaries used to have, and the staging folder's.
        let pid = std::process::id();
        for name in [
            format!(".route.csv.{pid}.tmp"),
            format!(".{RECORD}.{pid}.tmp"),
            format!(".slideroute-staging.{pid}"),
        ] {
            std::os::unix::fs::symlink(target.join("theirs"), d.join(name)).unwrap();
        }
        let mut f = OutputFolder::open(&d, "run").unwrap();
        f.write_bytes("route.csv", b"ours").unwrap();
        let staged = f.staging().unwrap();
        std::fs::write(staged.join("plan.svg"), "ours").unwrap();
        f.adopt_all(vec![staged.join("plan.svg")]).unwrap();
        f.finish().unwrap();
        assert_eq!(
            std::fs::read_to_string(target.join("theirs")).unwrap(),
            "theirs"
        );
        assert_eq!(
            std::fs::read_to_string(d.join("route.csv")).unwrap(),
            "ours"
        );
        assert!(
            std::fs::symlink_metadata(d.join("route.csv"))
                .unwrap()
                .is_file()
        );
        assert_eq!(std::fs::read_to_string(d.join("plan.svg")).unwrap(), "ours");
        // A link where the lock goes: refused, the link's target untouched.
        let other = temp("planted-lock");
        std::fs::create_dir_all(&other).unwrap();
        std::os::unix::fs::symlink(target.join("theirs"), other.join(LOCK)).unwrap();
        let e = OutputFolder::open(&other, "run").unwrap_err().to_string();
        assert!(e.contains("not a plain file"), "{e}");
        assert_eq!(
            std::fs::read_to_string(target.join("theirs")).unwrap(),
            "theirs"
        );
        for p in [&d, &target, &other] {
            let _ = std::fs::remove_dir_all(p);
        }
    }

    #[test]
    fn files_appear_whole_and_only_this_commands_earlier_files_are_removed() {
        let d = temp("replace");
        std::fs::create_dir_all(d.join("paper")).unwrap();
        // An earlier run wrote plan.svg and paper/route.csv, a sweep sweep.csv; the person
        // put notes.txt and a summary.json of their own.
        for old in [
            "plan.svg",
            "paper/route.csv",
            "sweep.csv",
            "notes.txt",
            "summary.json",
        ] {
            std::fs::write(d.join(old), "old").unwrap();
        }
        std::fs::write(
            d.join(RECORD),
            "run\tplan.svg\nrun\tpaper/route.csv\nsweep\tsweep.csv\nrun\t../outside\n",
        )
        .unwrap();
        let mut f = OutputFolder::open(&d, "run").unwrap();
        // A failed write leaves neither the file nor its temporary.
        assert!(
            f.write_with("route.csv", |_| Err("no".to_string()))
                .is_err()
        );
        assert!(!d.join("route.csv").exists());
        f.write_bytes("route.csv", b"t_s\n0\n").unwrap();
        assert_eq!(f.written(), &[("route.csv".to_string(), 6)]);
        f.finish().unwrap();
        let mut left: Vec<String> = std::fs::read_dir(&d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(
            left,
            [
                RECORD,
                "notes.txt",
                "route.csv",
                "summary.json",
                "sweep.csv"
            ]
        );
        assert_eq!(
            std::fs::read_to_string(d.join(RECORD)).unwrap(),
            "sweep\tsweep.csv\nrun\troute.csv\n"
        );
        // A sweep into the same folder keeps the run's route.
        let mut f = OutputFolder::open(&d, "sweep").unwrap();
        f.write_bytes("sweep.csv", b"x\n").unwrap();
        f.finish().unwrap();
        assert!(d.join("route.csv").exists());
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_recorded_file_replaced_by_a_link_is_left_alone() {
        let d = temp("link");
        let target = temp("link-target");
        std::fs::create_dir_all(&d).unwrap();
        std::fs::create_dir_all(&target).unwrap();
        std::fs::write(target.join("theirs.csv"), "theirs").unwrap();
        #[cfg(unix)]
        std::os::unix::fs::symlink(target.join("theirs.csv"), d.join("route.csv")).unwrap();
        std::fs::write(d.join(RECORD), "run\troute.csv\n").unwrap();
        let f = OutputFolder::open(&d, "run").unwrap();
        f.finish().unwrap();
        assert!(target.join("theirs.csv").exists());
        let _ = std::fs::remove_dir_all(&d);
        let _ = std::fs::remove_dir_all(&target);
    }

    #[cfg(unix)]
    #[test]
    fn a_link_where_an_output_goes_is_refused_and_nothing_is_written_or_removed_through_it() {
        // `ln -s OTHER out/paper; slideroute run --out out` deleted OTHER/route.csv, and a link
        // at `out/case-2` took `check`'s route into its target.
        let (d, other) = (temp("link-way"), temp("link-way-other"));
        std::fs::create_dir_all(&d).unwrap();
        std::fs::create_dir_all(&other).unwrap();
        std::fs::write(other.join("route.csv"), "theirs").unwrap();
        std::os::unix::fs::symlink(&other, d.join("paper")).unwrap();
        std::os::unix::fs::symlink(other.join("route.csv"), d.join("summary.json")).unwrap();
        // A record of an earlier run naming files under that folder.
        std::fs::write(d.join(RECORD), "run\tpaper/route.csv\n").unwrap();
        let mut f = OutputFolder::open(&d, "run").unwrap();
        let e = f
            .write_bytes("paper/route.csv", b"ours")
            .unwrap_err()
            .to_string();
        assert!(e.contains("paper: is a link"), "{e}");
        let e = f
            .write_bytes("summary.json", b"ours")
            .unwrap_err()
            .to_string();
        assert!(e.contains("summary.json: is a link"), "{e}");
        let e = f.open_inside("paper", "check").unwrap_err().to_string();
        assert!(e.contains("paper: is a link"), "{e}");
        f.write_bytes("route.csv", b"ours").unwrap();
        f.finish().unwrap();
        assert_eq!(
            std::fs::read_to_string(other.join("route.csv")).unwrap(),
            "theirs"
        );
        assert_eq!(std::fs::read_dir(&other).unwrap().count(), 1);
        // A real folder on the way is written into.
        let d2 = temp("link-way-real");
        let mut f = OutputFolder::open(&d2, "run").unwrap();
        f.write_bytes("paper/route.csv", b"ours").unwrap();
        f.finish().unwrap();
        assert!(d2.join("paper/route.csv").is_file());
        for dir in [&d, &other, &d2] {
            let _ = std::fs::remove_dir_all(dir);
        }
    }

    #[test]
    fn a_run_killed_while_it_replaces_files_leaves_no_manifest_and_the_next_cleans_up() {
        // A SIGKILL after the new route.csv was renamed in, before summary.json, left the new
        // route beside the old summary and pictures.
        let d = temp("killed-mid-way");
        let mut f = OutputFolder::open(&d, "run").unwrap();
        f.write_bytes("route.csv", b"old").unwrap();
        f.write_bytes("plan.svg", b"old").unwrap();
        f.write_manifest("summary.json", b"old").unwrap();
        f.finish().unwrap();
        // The next run renames its first file in and is killed (dropped unfinished).
        let mut f = OutputFolder::open(&d, "run").unwrap();
        f.write_bytes("route.csv", b"new").unwrap();
        assert!(
            !d.join("summary.json").exists(),
            "the old summary went first"
        );
        f.write_bytes("extra.svg", b"new").unwrap();
        drop(f);
        assert!(!d.join("summary.json").exists());
        let record = std::fs::read_to_string(d.join(RECORD)).unwrap();
        assert!(record.contains("run\textra.svg\n"), "{record}");
        // A third run writes the route and its summary only: what neither it nor the record's
        // other commands wrote is gone, and the summary names exactly the files beside it.
        let mut f = OutputFolder::open(&d, "run").unwrap();
        f.write_bytes("route.csv", b"third").unwrap();
        let manifest: Vec<String> = f.written().iter().map(|(n, _)| n.clone()).collect();
        f.write_manifest("summary.json", manifest.join(",").as_bytes())
            .unwrap();
        assert!(!d.join("plan.svg").exists() && !d.join("extra.svg").exists());
        f.finish().unwrap();
        let mut beside: Vec<String> = std::fs::read_dir(&d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| !n.starts_with('.'))
            .collect();
        beside.sort();
        assert_eq!(beside, ["route.csv", "summary.json"]);
        assert_eq!(
            std::fs::read_to_string(d.join("summary.json")).unwrap(),
            "route.csv"
        );
        assert_eq!(
            std::fs::read_to_string(d.join(RECORD)).unwrap(),
            "run\troute.csv\nrun\tsummary.json\tmanifest\n"
        );
        // Killed after its manifest was placed, before it finished: the record already marks
        // the manifest, so the next run's first file removes it first.
        let mut f = OutputFolder::open(&d, "run").unwrap();
        f.write_bytes("plan.svg", b"fourth").unwrap();
        f.write_manifest("summary.json", b"fourth").unwrap();
        drop(f);
        let record = std::fs::read_to_string(d.join(RECORD)).unwrap();
        assert!(record.contains("run\tsummary.json\tmanifest\n"), "{record}");
        let mut f = OutputFolder::open(&d, "run").unwrap();
        f.write_bytes("route.csv", b"fifth").unwrap();
        assert!(!d.join("summary.json").exists());
        drop(f);
        let _ = std::fs::remove_dir_all(&d);
    }
}
