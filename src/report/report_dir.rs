//! A report folder that holds exactly one run. A run writes into a staging folder beside the
//! target, `.NAME.accelbench-partial`, and [`ReportDir::publish`] renames it into place at the
//! end, replacing an older report there whole (its charts and pictures with it), so a reused
//! `--out` never mixes two runs' files. While a run holds the folder, a lock file beside it,
//! `.NAME.accelbench-lock` (made with `create_new`, holding the process id), refuses a second run
//! on the same folder; a lock whose process no longer exists (one killed by SIGKILL) is taken
//! over.
//!
//! Invariants: the target is replaced only by a finished report, and only when it is empty or
//! an accelbench report (it has `meta.json`), never a folder of other files; between the two
//! renames of [`ReportDir::publish`] the target is briefly absent, never half written.

use super::ReportError;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The claim of one run on a report folder: its lock, and the staging folder it writes into.
/// Dropped without [`ReportDir::publish`] (the run failed before writing a report), it removes
/// the staging folder and leaves the target as it was; either way it releases the lock.
#[derive(Debug)]
pub struct ReportDir {
    target: PathBuf,
    staging: PathBuf,
    lock: PathBuf,
    published: bool,
}

/// `dir/.NAME.accelbench-KIND` beside `target`.
fn sibling(target: &Path, kind: &str) -> PathBuf {
    let name = target.file_name().unwrap_or_default().to_string_lossy();
    let parent = target.parent().filter(|p| !p.as_os_str().is_empty());
    parent
        .unwrap_or(Path::new("."))
        .join(format!(".{name}.accelbench-{kind}"))
}

fn write_err(path: &Path, message: String) -> ReportError {
    ReportError::Write {
        path: path.to_owned(),
        message,
    }
}

impl ReportDir {
    /// Takes `target` for one run: checks that it can become a report folder, takes the lock
    /// (or fails saying which run holds it), and makes an empty staging folder.
    pub fn claim(target: &Path) -> Result<ReportDir, ReportError> {
        let target = match target.file_name() {
            Some(_) => target.to_owned(),
            // `.`, `..`, `/`: the folder's own name is needed for its siblings.
            None => target
                .canonicalize()
                .map_err(|e| write_err(target, format!("cannot find the folder ({e})")))?,
        };
        check_replaceable(&target)?;
        if let Some(parent) = target.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent)
                .map_err(|e| write_err(&target, format!("cannot create the folder ({e})")))?;
        }
        let lock = sibling(&target, "lock");
        take_lock(&lock, &target)?;
        let claim = ReportDir {
            staging: sibling(&target, "partial"),
            target,
            lock,
            published: false,
        };
        // Left by a run that was killed: ours now that we hold the lock.
        let _ = std::fs::remove_dir_all(&claim.staging);
        std::fs::create_dir(&claim.staging)
            .and_then(|()| std::fs::write(claim.staging.join(".write-check"), b""))
            .and_then(|()| std::fs::remove_file(claim.staging.join(".write-check")))
            .map_err(|e| write_err(&claim.target, format!("cannot write beside it ({e})")))?;
        Ok(claim)
    }

    /// Where the run writes its report until [`ReportDir::publish`].
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// Moves the finished report into place, replacing what the target held.
    pub fn publish(mut self) -> Result<(), ReportError> {
        let old = sibling(&self.target, "old");
        let _ = std::fs::remove_dir_all(&old);
        if self.target.exists() {
            std::fs::rename(&self.target, &old).map_err(|e| {
                write_err(
                    &self.target,
                    format!("cannot move the older report aside ({e})"),
                )
            })?;
        }
        if let Err(e) = std::fs::rename(&self.staging, &self.target) {
            let _ = std::fs::rename(&old, &self.target);
            return Err(write_err(
                &self.target,
                format!("cannot move the report into place ({e})"),
            ));
        }
        self.published = true;
        // The older report is gone from the target already; a leftover here is only clutter.
        let _ = std::fs::remove_dir_all(&old);
        Ok(())
    }
}

impl Drop for ReportDir {
    fn drop(&mut self) {
        if !self.published {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
        let _ = std::fs::remove_file(&self.lock);
    }
}

/// Fails unless `target` is absent, an empty folder, or an accelbench report.
fn check_replaceable(target: &Path) -> Result<(), ReportError> {
    if !target.exists() {
        return Ok(());
    }
    if !target.is_dir() {
        return Err(write_err(
            target,
            "it is a file, not a folder: give --out a folder (new, or an older report)".into(),
        ));
    }
    let mut entries = std::fs::read_dir(target)
        .map_err(|e| write_err(target, format!("cannot read the folder ({e})")))?;
    if entries.next().is_none() || target.join("meta.json").is_file() {
        return Ok(());
    }
    Err(write_err(
        target,
        "the folder holds files but no accelbench report (no meta.json), and a run replaces its \
         --out folder whole: give a new folder, or an older report's"
            .into(),
    ))
}

/// Creates the lock file `lock` holding our process id, taking over one whose process is gone.
fn take_lock(lock: &Path, target: &Path) -> Result<(), ReportError> {
    for _ in 0..2 {
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(lock)
        {
            Ok(mut f) => {
                return writeln!(f, "{}", std::process::id())
                    .map_err(|e| write_err(lock, format!("cannot write the lock file ({e})")));
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                let holder = std::fs::read_to_string(lock)
                    .ok()
                    .and_then(|s| s.trim().parse::<u32>().ok());
                match holder {
                    Some(pid) if !process_exists(pid) => {
                        let _ = std::fs::remove_file(lock);
                    }
                    _ => return Err(busy(target, lock, holder)),
                }
            }
            Err(e) => {
                return Err(write_err(
                    lock,
                    format!("cannot create the lock file ({e})"),
                ));
            }
        }
    }
    Err(busy(target, lock, None))
}

fn busy(target: &Path, lock: &Path, holder: Option<u32>) -> ReportError {
    let who = holder.map_or("another run".to_owned(), |p| {
        format!("another run (process {p})")
    });
    write_err(
        target,
        format!(
            "{who} is writing this report folder: wait for it to end, or give another --out \
             (if no run is active, delete the lock file {})",
            lock.display()
        ),
    )
}

/// Whether a process with id `pid` exists (on other systems than Unix: assumed to).
fn process_exists(pid: u32) -> bool {
    #[cfg(unix)]
    {
        let Ok(pid) = libc::pid_t::try_from(pid) else {
            return false;
        };
        if pid <= 0 {
            return false;
        }
        // SAFETY: signal 0 sends nothing; it only checks that the process exists.
        let r = unsafe { libc::kill(pid, 0) };
        r == 0 || std::io::Error::last_os_error().raw_os_error() == Some(libc::EPERM)
    }
    #[cfg(not(unix))]
    {
        let _ = pid;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_published_report_replaces_the_older_one_whole() {
        let tmp = tempfile::tempdir().unwrap();
        let target = tmp.path().join("r");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("meta.json"), "{}").unwrap();
        std::fs::write(target.join("stale.svg"), "").unwrap();
        let claim = ReportDir::claim(&target).unwrap();
        assert!(
            ReportDir::claim(&target).is_err(),
            "the lock refuses a second claim"
        );
        std::fs::write(claim.path().join("meta.json"), "{\"new\":1}").unwrap();
        claim.publish().unwrap();
        assert!(!target.join("stale.svg").exists());
        assert_eq!(
            std::fs::read_to_string(target.join("meta.json")).unwrap(),
            "{\"new\":1}"
        );
        let left: Vec<_> = std::fs::read_dir(tmp.path()).unwrap().collect();
        assert_eq!(left.len(), 1, "only the report is left: {left:?}");
    }

    #[test]
    fn an_unpublished_claim_leaves_the_target_as_it_was() {
        let tmp = tempfile::tempdir().unwrap();
        let target = tmp.path().join("r");
        drop(ReportDir::claim(&target).unwrap());
        assert!(!target.exists());
        assert_eq!(std::fs::read_dir(tmp.path()).unwrap().count(), 0);
    }

    #[test]
    fn a_folder_of_other_files_is_not_replaced() {
        let tmp = tempfile::tempdir().unwrap();
        std::fs::write(tmp.path().join("notes.txt"), "mine").unwrap();
        let e = ReportDir::claim(tmp.path()).unwrap_err().to_string();
        assert!(e.contains("no accelbench report"), "{e}");
    }
}
