//! An output folder that a person can trust: whole files or none, one run at a
//! time, and nothing left over from the same command's earlier run.
//!
//! * Every file is written under a temporary name in the same folder and renamed into place
//!   when complete, so a file is never seen half-written (a rename within a folder is atomic).
//! * A run holds `.slideroute.lock` (its process id) while it writes; a second run into the same
//!   folder is refused. A lock left by a run that no longer exists is taken over.
//! * The folder keeps a record of what each command wrote into it ([`RECORD`]: the command and
//!   the file, one per line). When a run is done, the files the same command wrote there before
//!   and did not write this time are removed (say, the pictures after `--no-plots`); another
//!   command's files, and files slideroute did not write, are never touched — whatever their
//!   names. A file named in the record that is no longer a plain file (a link put in its place)
//!   is left alone.

use std::path::{Path, PathBuf};

/// The record of what each command wrote into a folder: lines `COMMAND<TAB>FILE` (the file
/// relative to the folder).
pub const RECORD: &str = ".slideroute-outputs";

const LOCK: &str = ".slideroute.lock";

/// A locked output folder, the command writing into it and the files written so far (relative
/// name, bytes).
#[derive(Debug)]
pub struct Folder {
    dir: PathBuf,
    command: &'static str,
    written: Vec<(String, u64)>,
}

/// The entries of a folder's [`RECORD`] (command, file): none where there is no record, or it
/// is not a plain file.
fn read_record(dir: &Path) -> Vec<(String, String)> {
    let path = dir.join(RECORD);
    let plain = std::fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_file());
    if !plain {
        return Vec::new();
    }
    std::fs::read_to_string(&path)
        .unwrap_or_default()
        .lines()
        .filter_map(|line| line.split_once('\t'))
        .filter(|(_, file)| recordable(file))
        .map(|(c, f)| (c.to_string(), f.to_string()))
        .collect()
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

fn alive(pid: u32) -> bool {
    // Linux and the BSDs with procfs; elsewhere a lock is taken as held.
    !Path::new("/proc/self").exists() || Path::new(&format!("/proc/{pid}")).exists()
}

impl Folder {
    /// Creates `dir` if needed and locks it for `command` (`run`, `sweep`, …: the name its
    /// files are recorded under); the error says why not, naming the folder.
    pub fn open(dir: &Path, command: &'static str) -> Result<Folder, String> {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("{}: cannot create: {e}", dir.display()))?;
        let lock = dir.join(LOCK);
        for _ in 0..2 {
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&lock)
            {
                Ok(mut f) => {
                    use std::io::Write;
                    let _ = write!(f, "{}", std::process::id());
                    return Ok(Folder {
                        dir: dir.to_path_buf(),
                        command,
                        written: Vec::new(),
                    });
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let holder = std::fs::read_to_string(&lock)
                        .ok()
                        .and_then(|s| s.trim().parse::<u32>().ok());
                    match holder {
                        Some(pid) if alive(pid) => {
                            return Err(format!(
                                "{}: another slideroute run (process {pid}) is writing into this \
                                 folder; wait for it or choose another --out",
                                dir.display()
                            ));
                        }
                        // Left by a run that no longer exists (or unreadable): take it over.
                        _ => {
                            let _ = std::fs::remove_file(&lock);
                        }
                    }
                }
                Err(e) => return Err(format!("{}: cannot lock: {e}", lock.display())),
            }
        }
        Err(format!("{}: cannot lock the folder", dir.display()))
    }

    /// Writes `name` (relative; its folder is created) through `write`, which is given the
    /// temporary path to write to; renames it into place when `write` succeeded. Returns the
    /// final path.
    pub fn write_with(
        &mut self,
        name: &str,
        write: impl FnOnce(&Path) -> Result<(), String>,
    ) -> Result<PathBuf, String> {
        let path = self.dir.join(name);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)
                .map_err(|e| format!("{}: cannot create: {e}", parent.display()))?;
        }
        let file_name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let tmp = path.with_file_name(format!(".{file_name}.{}.tmp", std::process::id()));
        let result = write(&tmp).and_then(|()| {
            std::fs::rename(&tmp, &path)
                .map_err(|e| format!("{}: cannot write: {e}", path.display()))
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

    /// [`Folder::write_with`] for bytes already in hand.
    pub fn write_bytes(&mut self, name: &str, bytes: &[u8]) -> Result<PathBuf, String> {
        self.write_with(name, |tmp| {
            std::fs::write(tmp, bytes).map_err(|e| format!("{}: cannot write: {e}", tmp.display()))
        })
    }

    /// A private folder inside this one (removed when the run ends) for writers that want a
    /// path of their own to write into; [`Folder::adopt`] moves their files into place.
    pub fn staging(&self) -> Result<PathBuf, String> {
        let d = self
            .dir
            .join(format!(".slideroute-staging.{}", std::process::id()));
        std::fs::create_dir_all(&d).map_err(|e| format!("{}: cannot create: {e}", d.display()))?;
        Ok(d)
    }

    /// Moves a finished file `from` (in [`Folder::staging`]) into place as `name`.
    fn adopt(&mut self, name: &str, from: &Path) -> Result<PathBuf, String> {
        self.write_with(name, |tmp| {
            std::fs::rename(from, tmp).map_err(|e| format!("{}: cannot move: {e}", from.display()))
        })
    }

    /// [`Folder::adopt`] for each of `staged`, under its own file name.
    pub fn adopt_all(&mut self, staged: Vec<PathBuf>) -> Result<Vec<PathBuf>, String> {
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

    /// Removes the files this command wrote here before ([`RECORD`]) that this run did not
    /// write, and their folders if that leaves them empty; records what this run wrote beside
    /// the other commands' files that are still there; then unlocks.
    pub fn finish(self) -> Result<(), String> {
        let wrote = |name: &str| self.written.iter().any(|(n, _)| n == name);
        let mut kept: Vec<(String, String)> = Vec::new();
        for (command, name) in read_record(&self.dir) {
            let path = self.dir.join(&name);
            if command == self.command {
                if !wrote(&name) && plain_file(&path) {
                    std::fs::remove_file(&path).map_err(|e| {
                        format!(
                            "{}: cannot remove this command's earlier file: {e}",
                            path.display()
                        )
                    })?;
                    if let Some(parent) = path.parent().filter(|p| *p != self.dir) {
                        let _ = std::fs::remove_dir(parent); // only if empty
                    }
                }
            } else if !wrote(&name) && plain_file(&path) && !kept.iter().any(|(_, n)| *n == name) {
                kept.push((command, name));
            }
        }
        let mut record = String::new();
        for (command, name) in kept
            .iter()
            .map(|(c, n)| (c.as_str(), n.as_str()))
            .chain(self.written.iter().map(|(n, _)| (self.command, n.as_str())))
        {
            record.push_str(&format!("{command}\t{name}\n"));
        }
        let path = self.dir.join(RECORD);
        let tmp = self
            .dir
            .join(format!(".{RECORD}.{}.tmp", std::process::id()));
        std::fs::write(&tmp, record)
            .and_then(|()| std::fs::rename(&tmp, &path))
            .map_err(|e| {
                let _ = std::fs::remove_file(&tmp);
                format!("{}: cannot write: {e}", path.display())
            })
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(
            self.dir
                .join(format!(".slideroute-staging.{}", std::process::id())),
        );
        let _ = std::fs::remove_file(self.dir.join(LOCK));
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
        let first = Folder::open(&d, "run").unwrap();
        let e = Folder::open(&d, "run").unwrap_err();
        assert!(e.contains("another slideroute run"), "{e}");
        drop(first);
        assert!(Folder::open(&d, "run").is_ok());
        // A lock whose process is gone (pid 0 is never a user process's).
        std::fs::write(d.join(LOCK), "4294967295").unwrap();
        assert!(Folder::open(&d, "run").is_ok());
        let _ = std::fs::remove_dir_all(&d);
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
        let mut f = Folder::open(&d, "run").unwrap();
        // A failed write leaves neither the file nor its temporary.
        assert!(f.write_with("route.csv", |_| Err("no".into())).is_err());
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
        let mut f = Folder::open(&d, "sweep").unwrap();
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
        let f = Folder::open(&d, "run").unwrap();
        f.finish().unwrap();
        assert!(target.join("theirs.csv").exists());
        let _ = std::fs::remove_dir_all(&d);
        let _ = std::fs::remove_dir_all(&target);
    }
}
