//! An output folder that a person can trust: whole files or none, one run at a
//! time, and nothing left over from an earlier run.
//!
//! * Every file is written under a temporary name in the same folder and renamed into place
//!   when complete, so a file is never seen half-written (a rename within a folder is atomic).
//! * A run holds `.slideroute.lock` (its process id) while it writes; a second run into the same
//!   folder is refused. A lock left by a run that no longer exists is taken over.
//! * When the run is done, the files slideroute writes ([`KNOWN`]) that this run did not write
//!   are removed, so the folder holds one run's outputs; nothing else in it is touched.

use std::path::{Path, PathBuf};

/// Every file a slideroute command writes into an output folder (relative paths).
pub const KNOWN: [&str; 22] = [
    "route.csv",
    "summary.json",
    "plan.svg",
    "profile.svg",
    "angles.svg",
    "reactions.svg",
    "comparison.json",
    "compare-plan.svg",
    "paper/route.csv",
    "paper/summary.json",
    "rigid-body/route.csv",
    "rigid-body/summary.json",
    "sweep.csv",
    "sweep.svg",
    "work-precision.csv",
    "work-precision.svg",
    "work-precision.md",
    "samples.csv",
    "probabilistic.json",
    "route-fan.svg",
    "factor-of-safety.svg",
    "sensitivity.svg",
];

const LOCK: &str = ".slideroute.lock";

/// A locked output folder and the files written into it so far (relative name, bytes).
#[derive(Debug)]
pub struct Folder {
    dir: PathBuf,
    written: Vec<(String, u64)>,
}

fn alive(pid: u32) -> bool {
    // Linux and the BSDs with procfs; elsewhere a lock is taken as held.
    !Path::new("/proc/self").exists() || Path::new(&format!("/proc/{pid}")).exists()
}

impl Folder {
    /// Creates `dir` if needed and locks it; the error says why not, naming the folder.
    pub fn open(dir: &Path) -> Result<Folder, String> {
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

    /// Removes the [`KNOWN`] files this run did not write (an earlier run's), and their
    /// folders if that leaves them empty; then unlocks.
    pub fn finish(self) -> Result<(), String> {
        for name in KNOWN {
            if self.written.iter().any(|(n, _)| n == name) {
                continue;
            }
            let path = self.dir.join(name);
            if path.is_file() {
                std::fs::remove_file(&path).map_err(|e| {
                    format!(
                        "{}: cannot remove an earlier run's file: {e}",
                        path.display()
                    )
                })?;
                if let Some(parent) = path.parent().filter(|p| *p != self.dir) {
                    let _ = std::fs::remove_dir(parent); // only if empty
                }
            }
        }
        Ok(())
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
        let first = Folder::open(&d).unwrap();
        let e = Folder::open(&d).unwrap_err();
        assert!(e.contains("another slideroute run"), "{e}");
        drop(first);
        assert!(Folder::open(&d).is_ok());
        // A lock whose process is gone (pid 0 is never a user process's).
        std::fs::write(d.join(LOCK), "4294967295").unwrap();
        assert!(Folder::open(&d).is_ok());
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn files_appear_whole_and_an_earlier_runs_files_are_removed_but_nothing_else() {
        let d = temp("replace");
        std::fs::create_dir_all(d.join("paper")).unwrap();
        for old in ["plan.svg", "paper/route.csv", "notes.txt"] {
            std::fs::write(d.join(old), "old").unwrap();
        }
        let mut f = Folder::open(&d).unwrap();
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
        assert_eq!(left, ["notes.txt", "route.csv"]);
        let _ = std::fs::remove_dir_all(&d);
    }
}
