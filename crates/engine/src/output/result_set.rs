//! A results folder written whole or not at all.
//!
//! A run's tables go into a fresh staging folder beside the target,
//! `.<name>.staging.<host>.<pid>.<nonce>` (same parent, so same filesystem), every file and the
//! folder fsynced; [`ResultSet::publish`] then puts the staging folder in the target's place in
//! one step: on Linux `renameat2(RENAME_EXCHANGE)` swaps the two folders atomically and the old
//! one (now under the staging name) is deleted; elsewhere, or on a filesystem without exchange,
//! the old folder is renamed aside (`.<name>.old.<host>.<pid>.<nonce>`) and the new one renamed
//! in, a short moment in which the target is absent. Either way a reader finds the complete set
//! of one run, never a mix, and runs publishing into one folder at once all succeed: the last
//! one's set stays.
//!
//! The folder is replaced whole, so files a user put into it (a `report.html`, notes) go with it.
//! Hence only a folder that looks like a results folder is replaced: absent, empty, or holding a
//! `timings.parquet` (every run writes one) and no sub-folder ([`check_target`]); anything else is
//! refused before the run computes.
//!
//! A set dropped without being published (a failed write) deletes its staging folder. One left by
//! a killed process is deleted by the next run into the same target when it is stale: made on
//! this host by a process that no longer runs, or older than a day (another host's).

use std::fs::{self, File};
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{SystemTime, UNIX_EPOCH};

use crate::cache::{hostname, process_alive, FOREIGN_TMP_MAX_AGE};

use super::{OutputError, TIMINGS_TABLE};

/// Publication attempts before giving up: each lost race (another run published in between) costs
/// one.
const PUBLISH_ATTEMPTS: usize = 16;

/// The tables of one run, staged in a private folder until [`ResultSet::publish`].
#[derive(Debug)]
pub struct ResultSet {
    target: PathBuf,
    staging: PathBuf,
    /// File names written so far, in the order they were written.
    files: Vec<String>,
    published: bool,
}

impl ResultSet {
    /// Stages a new set for the folder `target`: checks that `target` may be replaced
    /// ([`check_target`]), removes stale staging folders of earlier runs into it and creates a
    /// fresh one.
    pub fn stage(target: &Path) -> Result<Self, OutputError> {
        let target = resolve(target)?;
        check_target(&target)?;
        let (parent, name) = split(&target)?;
        fs::create_dir_all(&parent).map_err(write_err(&parent))?;
        remove_stale(&parent, &name);
        let staging = parent.join(format!(".{name}.staging.{}", owner_suffix()));
        fs::create_dir(&staging).map_err(write_err(&staging))?;
        Ok(Self {
            target,
            staging,
            files: Vec::new(),
            published: false,
        })
    }

    /// The folder the set is published to.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// The private folder the tables are written into.
    pub(super) fn staging(&self) -> &Path {
        &self.staging
    }

    /// Records that `file` (a name in the staging folder) was written.
    pub(super) fn record(&mut self, file: String) {
        self.files.push(file);
    }

    /// Puts the staged set in the target's place (see the module documentation) and deletes the
    /// set it replaces. Returns the published files, in the order they were written.
    pub fn publish(mut self) -> Result<Vec<PathBuf>, OutputError> {
        File::open(&self.staging)
            .and_then(|d| d.sync_all())
            .map_err(write_err(&self.staging))?;
        let (parent, name) = split(&self.target)?;
        let mut last = None;
        for _ in 0..PUBLISH_ATTEMPTS {
            match self.try_publish(&parent, &name) {
                Ok(()) => {
                    self.published = true;
                    let _ = File::open(&parent).and_then(|d| d.sync_all());
                    return Ok(self.files.iter().map(|f| self.target.join(f)).collect());
                }
                Err(e) => last = Some(e),
            }
        }
        let e = last.unwrap_or_else(|| std::io::Error::other("no attempt made"));
        Err(write_err(&self.target)(e))
    }

    /// One attempt: a plain rename when the target is absent, else an exchange (or, without
    /// one, rename aside and in). An error that another run's publication can explain is
    /// retried by the caller.
    fn try_publish(&self, parent: &Path, name: &str) -> std::io::Result<()> {
        match fs::rename(&self.staging, &self.target) {
            Ok(()) => return Ok(()),
            Err(e) if !self.target.exists() => return Err(e),
            Err(_) => {}
        }
        match exchange(&self.staging, &self.target) {
            Ok(()) => {
                // The staging name now holds the replaced set.
                let _ = fs::remove_dir_all(&self.staging);
                return Ok(());
            }
            Err(e) if e.kind() != ErrorKind::Unsupported => return Err(e),
            Err(_) => {}
        }
        self.replace_by_renames(parent, name)
    }

    /// Renames the target aside, the staging folder in, and deletes the set aside: where the
    /// folders cannot be exchanged.
    fn replace_by_renames(&self, parent: &Path, name: &str) -> std::io::Result<()> {
        let aside = parent.join(format!(".{name}.old.{}", owner_suffix()));
        fs::rename(&self.target, &aside)?;
        let moved_in = fs::rename(&self.staging, &self.target);
        let _ = fs::remove_dir_all(&aside);
        moved_in
    }
}

impl Drop for ResultSet {
    /// A set that was not published leaves nothing behind.
    fn drop(&mut self) {
        if !self.published {
            let _ = fs::remove_dir_all(&self.staging);
        }
    }
}

/// Checks that `target` may be replaced by a run's results: absent, empty, or a results folder
/// (a `timings.parquet`, no sub-folder). Cheap; a run calls it before computing as well.
pub fn check_target(target: &Path) -> Result<(), OutputError> {
    let refuse = |why: String| OutputError::Write {
        path: target.to_path_buf(),
        message: format!(
            "{why}; a run replaces its results folder whole, so it writes only into an absent, \
             empty or earlier results folder: choose another output folder (--out) or move \
             this one away"
        ),
    };
    let entries = match fs::read_dir(target) {
        Ok(entries) => entries,
        Err(e) if e.kind() == ErrorKind::NotFound => return Ok(()),
        Err(_) if target.exists() && !target.is_dir() => {
            return Err(refuse(String::from("it is a file, not a folder")))
        }
        Err(e) => return Err(write_err(target)(e)),
    };
    let mut empty = true;
    let mut timings = false;
    for entry in entries.flatten() {
        empty = false;
        let name = entry.file_name().to_string_lossy().to_string();
        if entry.file_type().is_ok_and(|t| t.is_dir()) {
            return Err(refuse(format!(
                "it holds the folder '{name}', which a results folder never does"
            )));
        }
        timings |= name == format!("{TIMINGS_TABLE}.parquet");
    }
    if empty || timings {
        Ok(())
    } else {
        Err(refuse(format!(
            "it holds files but no {TIMINGS_TABLE}.parquet, so it is not a results folder"
        )))
    }
}

/// Identifies one published set: it changes whenever a run publishes into the folder, so a
/// reader that finds the same generation before and after reading has read one set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Generation(u64, u64);

impl Generation {
    /// The generation of the folder at `path` (following a symbolic link to it).
    pub fn of(path: &Path) -> std::io::Result<Self> {
        let meta = fs::metadata(path)?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            Ok(Self(meta.dev(), meta.ino()))
        }
        #[cfg(not(unix))]
        {
            let modified = meta
                .modified()?
                .duration_since(UNIX_EPOCH)
                .unwrap_or_default();
            Ok(Self(modified.as_secs(), u64::from(modified.subsec_nanos())))
        }
    }
}

/// `target`, or the folder it links to: a symbolic link is kept and its folder replaced.
fn resolve(target: &Path) -> Result<PathBuf, OutputError> {
    match fs::symlink_metadata(target) {
        Ok(m) if m.file_type().is_symlink() => fs::canonicalize(target).map_err(write_err(target)),
        _ => Ok(target.to_path_buf()),
    }
}

/// The parent folder (`.` for a bare name) and the file name of `target`.
fn split(target: &Path) -> Result<(PathBuf, String), OutputError> {
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .ok_or_else(|| OutputError::Write {
            path: target.to_path_buf(),
            message: String::from("an output folder needs a name (not `.`, `..` or `/`)"),
        })?;
    let parent = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok((parent, name))
}

/// `<host>.<pid>.<nonce>`: unique per process and call, and telling who made the folder.
fn owner_suffix() -> String {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let nanos = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let count = COUNTER.fetch_add(1, Ordering::Relaxed);
    format!("{}.{}.{nanos}-{count}", hostname(), std::process::id())
}

/// Deletes the staging and set-aside folders of runs into `<parent>/<name>` that are stale: made
/// on this host by a process that no longer runs, or older than a day.
fn remove_stale(parent: &Path, name: &str) {
    let Ok(entries) = fs::read_dir(parent) else {
        return;
    };
    let host = hostname();
    let prefixes = [format!(".{name}.staging."), format!(".{name}.old.")];
    for entry in entries.flatten() {
        let file = entry.file_name().to_string_lossy().to_string();
        let Some(suffix) = prefixes.iter().find_map(|p| file.strip_prefix(p.as_str())) else {
            continue;
        };
        // `<host>.<pid>.<nonce>`; the host name may hold dots.
        let mut parts = suffix.rsplitn(3, '.');
        let (_, pid, made_on) = (parts.next(), parts.next(), parts.next());
        let stale = match (made_on, pid.and_then(|p| p.parse::<u32>().ok())) {
            (Some(h), Some(pid)) if h == host => !process_alive(pid),
            _ => entry
                .metadata()
                .and_then(|m| m.modified())
                .ok()
                .and_then(|t| t.elapsed().ok())
                .is_some_and(|age| age > FOREIGN_TMP_MAX_AGE),
        };
        if stale {
            let _ = fs::remove_dir_all(entry.path());
        }
    }
}

/// Swaps the folders `a` and `b` in one step. `Unsupported` where the platform or filesystem
/// cannot.
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    use rustix::fs::{renameat_with, RenameFlags, CWD};
    renameat_with(CWD, a, CWD, b, RenameFlags::EXCHANGE).map_err(|e| {
        if e == rustix::io::Errno::INVAL || e == rustix::io::Errno::NOSYS {
            std::io::Error::from(ErrorKind::Unsupported)
        } else {
            std::io::Error::from(e)
        }
    })
}

#[cfg(not(target_os = "linux"))]
fn exchange(_: &Path, _: &Path) -> std::io::Result<()> {
    Err(std::io::Error::from(ErrorKind::Unsupported))
}

fn write_err(path: &Path) -> impl FnOnce(std::io::Error) -> OutputError + '_ {
    move |e| OutputError::Write {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("asperity-set-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// A staged set holding `timings.parquet` with `text`.
    fn staged(target: &Path, text: &str) -> ResultSet {
        let mut set = ResultSet::stage(target).unwrap();
        fs::write(set.staging().join("timings.parquet"), text).unwrap();
        set.record(String::from("timings.parquet"));
        set
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().to_string())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn replacing_by_renames_publishes_the_new_set_and_leaves_nothing() {
        let dir = scratch("renames");
        let target = dir.join("out");
        staged(&target, "old").publish().unwrap();
        let set = staged(&target, "new");
        set.replace_by_renames(&dir, "out").unwrap();
        assert_eq!(
            fs::read_to_string(target.join("timings.parquet")).unwrap(),
            "new"
        );
        drop(set);
        assert_eq!(names(&dir), ["out"]);
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn an_unpublished_set_and_stale_stagings_leave_nothing() {
        let dir = scratch("unpublished");
        let target = dir.join("out");
        staged(&target, "old").publish().unwrap();
        drop(staged(&target, "failed"));
        assert_eq!(names(&dir), ["out"]);
        // A staging folder of a process of this host that no longer runs.
        let dead = dir.join(format!(".out.staging.{}.4294967.1-0", hostname()));
        fs::create_dir(&dead).unwrap();
        let set = staged(&target, "new");
        assert!(!dead.exists());
        set.publish().unwrap();
        assert_eq!(names(&dir), ["out"]);
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn only_results_folders_are_replaced() {
        let dir = scratch("targets");
        assert!(check_target(&dir.join("absent")).is_ok());
        fs::create_dir(dir.join("empty")).unwrap();
        assert!(check_target(&dir.join("empty")).is_ok());
        fs::write(dir.join("file"), "x").unwrap();
        let e = check_target(&dir.join("file")).unwrap_err().to_string();
        assert!(e.contains("is a file"), "{e}");
        fs::create_dir(dir.join("other")).unwrap();
        fs::write(dir.join("other/notes.txt"), "x").unwrap();
        let e = check_target(&dir.join("other")).unwrap_err().to_string();
        assert!(e.contains("no timings.parquet"), "{e}");
        fs::write(dir.join("other/timings.parquet"), "x").unwrap();
        assert!(check_target(&dir.join("other")).is_ok());
        fs::create_dir(dir.join("other/plots")).unwrap();
        let e = check_target(&dir.join("other")).unwrap_err().to_string();
        assert!(e.contains("'plots'"), "{e}");
        let _ = fs::remove_dir_all(&dir);
    }
}
