//! The transactional output folder of `tribo run`: everything is written into a fresh
//! `.NAME.tmp-PID` beside the target folder NAME, which replaces the target only once it
//! is complete, so that a folder never mixes files of two runs and an interrupted run
//! leaves the previous results as they were.
//!
//! The replacement swaps the two folders in one step where the system can
//! (`renameat2(RENAME_EXCHANGE)`, Linux), else moves the old one aside as `.NAME.old-PID`
//! first; the old one is deleted after. Folders `.NAME.tmp-PID` and `.NAME.old-PID` left by
//! a process that no longer runs (killed) are deleted by the next run (on Linux, where a
//! process's liveness can be asked; elsewhere they stay). SIGINT and SIGTERM delete the
//! folder of the run in progress (`signals.rs` calls `cancel`).

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

/// The temporary folder of the run in progress. Held while the outputs are written and
/// swapped in, so that a signal waits for a commit under way instead of cutting it.
static ACTIVE: Mutex<Option<PathBuf>> = Mutex::new(None);

fn active() -> MutexGuard<'static, Option<PathBuf>> {
    ACTIVE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Deletes the temporary folder of the run in progress, if any (on SIGINT / SIGTERM).
/// Returns with the lock held, so that no commit starts before the process ends.
pub fn cancel() -> MutexGuard<'static, Option<PathBuf>> {
    let mut a = active();
    if let Some(temp) = a.take() {
        let _ = std::fs::remove_dir_all(temp);
    }
    a
}

/// A fresh temporary folder for `target`, replacing it on `commit`, deleted if dropped.
pub struct Staging {
    target: PathBuf,
    temp: PathBuf,
    done: bool,
}

/// The parent folder and the file name of a path ("." for a bare name).
fn split(path: &Path) -> Result<(PathBuf, String)> {
    let name = path.file_name().ok_or_else(|| {
        Error::model(format!(
            "{}: the output folder needs a name (not '..' or '/')",
            path.display()
        ))
    })?;
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok((parent, name.to_string_lossy().into_owned()))
}

/// A target that may be replaced: absent, or a folder that is empty or holds a
/// results.json (a folder of other files is never deleted).
fn check_target(target: &Path) -> Result<()> {
    let Ok(meta) = std::fs::symlink_metadata(target) else {
        return Ok(());
    };
    let refuse = |why: &str| {
        Err(Error::model(format!(
            "{}: {why}; the run replaces its output folder as a whole: remove it or choose \
             another folder with -o",
            target.display()
        )))
    };
    if !meta.is_dir() {
        return refuse("exists and is not a folder");
    }
    let mut entries = std::fs::read_dir(target).map_err(|e| Error::io(target, e))?;
    if entries.next().is_some() && !target.join("results.json").is_file() {
        return refuse("is a folder of other files (no results.json of an earlier run)");
    }
    Ok(())
}

/// Whether process `pid` still runs (true when that cannot be known).
fn alive(pid: u32) -> bool {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        let Ok(pid) = i32::try_from(pid) else {
            return true;
        };
        // SAFETY: signal 0 only checks that the process exists.
        let r = unsafe { libc::kill(pid, 0) };
        r == 0 || std::io::Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
    }
    #[cfg(not(all(target_os = "linux", target_env = "gnu")))]
    {
        let _ = pid;
        true
    }
}

/// Deletes `.NAME.tmp-PID` and `.NAME.old-PID` in `parent` whose process is gone.
fn remove_stale(parent: &Path, name: &str) {
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    let me = std::process::id();
    for e in entries.flatten() {
        let file = e.file_name().to_string_lossy().into_owned();
        let pid = [".tmp-", ".old-"].iter().find_map(|kind| {
            file.strip_prefix(&format!(".{name}{kind}"))
                .and_then(|p| p.parse::<u32>().ok())
        });
        if pid.is_some_and(|p| p != me && !alive(p)) {
            let _ = std::fs::remove_dir_all(e.path());
        }
    }
}

/// Swaps folders `a` and `b` in one step; Err where the system cannot.
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        use std::os::unix::ffi::OsStrExt;
        let c = |p: &Path| std::ffi::CString::new(p.as_os_str().as_bytes());
        let (ca, cb) = (c(a)?, c(b)?);
        // SAFETY: two NUL-terminated paths relative to the working directory.
        let r = unsafe {
            libc::renameat2(
                libc::AT_FDCWD,
                ca.as_ptr(),
                libc::AT_FDCWD,
                cb.as_ptr(),
                libc::RENAME_EXCHANGE,
            )
        };
        if r == 0 {
            Ok(())
        } else {
            Err(std::io::Error::last_os_error())
        }
    }
    #[cfg(not(all(target_os = "linux", target_env = "gnu")))]
    {
        let _ = (a, b);
        Err(std::io::ErrorKind::Unsupported.into())
    }
}

impl Staging {
    /// Checks that `target` may be replaced, deletes stale temporary folders beside it and
    /// creates this run's.
    pub fn begin(target: &Path) -> Result<Staging> {
        check_target(target)?;
        let (parent, name) = split(target)?;
        std::fs::create_dir_all(&parent).map_err(|e| Error::io(&parent, e))?;
        remove_stale(&parent, &name);
        let temp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
        // (one left by an earlier process that had this process's id)
        let _ = std::fs::remove_dir_all(&temp);
        let mut a = active();
        std::fs::create_dir(&temp).map_err(|e| Error::io(&temp, e))?;
        *a = Some(temp.clone());
        Ok(Staging {
            target: target.to_path_buf(),
            temp,
            done: false,
        })
    }

    /// Runs `write` on the temporary folder, then puts that folder in place of the target.
    /// A signal meanwhile waits until this is done.
    pub fn commit<T>(mut self, write: impl FnOnce(&Path) -> Result<T>) -> Result<T> {
        let mut a = active();
        if a.is_none() {
            // cancelled by a signal: the process is ending
            return Err(Error::model(format!(
                "{}: the run was interrupted",
                self.target.display()
            )));
        }
        let out = write(&self.temp).and_then(|o| self.replace().map(|()| o));
        if out.is_err() {
            let _ = std::fs::remove_dir_all(&self.temp);
        }
        // in place, or deleted: nothing left for `drop` or a signal
        self.done = true;
        *a = None;
        out
    }

    fn replace(&self) -> Result<()> {
        let (target, temp) = (&self.target, &self.temp);
        let io = |e| Error::io(target, e);
        if std::fs::symlink_metadata(target).is_err() {
            return std::fs::rename(temp, target).map_err(io);
        }
        // the old folder is now at `temp`, or moved aside as `old`
        if exchange(temp, target).is_ok() {
            let _ = std::fs::remove_dir_all(temp);
            return Ok(());
        }
        let (parent, name) = split(target)?;
        let old = parent.join(format!(".{name}.old-{}", std::process::id()));
        std::fs::rename(target, &old).map_err(io)?;
        if let Err(e) = std::fs::rename(temp, target) {
            let _ = std::fs::rename(&old, target);
            return Err(io(e));
        }
        let _ = std::fs::remove_dir_all(&old);
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.done {
            let mut a = active();
            let _ = std::fs::remove_dir_all(&self.temp);
            *a = None;
        }
    }
}
