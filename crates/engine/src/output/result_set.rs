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
//! Before computing, a run checks that it may write there ([`check_target`]: the folder and the
//! one it is made in writable by this user), so a run never computes for hours to fail at the end.
//!
//! A set dropped without being published (a failed write) deletes its staging folder. One left by
//! a killed process is deleted by the next run into the same target when it is stale: made on
//! this host by a process that no longer runs, or older than a day (another host's). One that
//! cannot be deleted (a folder made read-only) is made writable first, as it is a run's own
//! leftover; what still cannot be deleted is named, with the command that deletes it, in one
//! warning ([`remove_stale_stagings`], [`ResultSet::warnings`]).

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
    /// The study file the run read, recorded in `timings.parquet` ([`super::results_origin`]).
    study_file: Option<PathBuf>,
    /// What the user should know and nothing failed of: leftovers that could not be deleted.
    warnings: Vec<String>,
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
        let warnings = remove_stale(&parent, &name).into_iter().collect();
        let staging = parent.join(format!(".{name}.staging.{}", owner_suffix()));
        fs::create_dir(&staging).map_err(write_err(&staging))?;
        Ok(Self {
            target,
            staging,
            files: Vec::new(),
            study_file: None,
            warnings,
            published: false,
        })
    }

    /// Records the study file the set comes from (its absolute path) in `timings.parquet`, so
    /// a later run of another study file into the same folder can tell ([`super::results_origin`]).
    pub fn from_study_file(mut self, path: &Path) -> Self {
        self.study_file = Some(fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()));
        self
    }

    /// The study file recorded by [`ResultSet::from_study_file`].
    pub(super) fn study_file(&self) -> Option<&Path> {
        self.study_file.as_deref()
    }

    /// Warnings so far (folders of earlier runs that could not be deleted), one sentence each.
    pub fn warnings(&self) -> &[String] {
        &self.warnings
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
    pub fn publish(self) -> Result<Vec<PathBuf>, OutputError> {
        self.publish_with_warnings().map(|(files, _)| files)
    }

    /// [`ResultSet::publish`], also returning the warnings ([`ResultSet::warnings`], and the
    /// replaced set when it could not be deleted).
    pub fn publish_with_warnings(mut self) -> Result<(Vec<PathBuf>, Vec<String>), OutputError> {
        File::open(&self.staging)
            .and_then(|d| d.sync_all())
            .map_err(write_err(&self.staging))?;
        let (parent, name) = split(&self.target)?;
        let mut last = None;
        for _ in 0..PUBLISH_ATTEMPTS {
            match self.try_publish(&parent, &name) {
                Ok(replaced) => {
                    self.published = true;
                    let _ = File::open(&parent).and_then(|d| d.sync_all());
                    if let Some(left) = replaced.and_then(|old| remove_leftover(&old).err()) {
                        self.warnings.push(cannot_remove(&self.target, &[left]));
                    }
                    let files = self.files.iter().map(|f| self.target.join(f)).collect();
                    return Ok((files, std::mem::take(&mut self.warnings)));
                }
                Err(e) => last = Some(e),
            }
        }
        let e = last.unwrap_or_else(|| std::io::Error::other("no attempt made"));
        Err(write_err(&self.target)(e))
    }

    /// One attempt: a plain rename when the target is absent, else an exchange (or, without
    /// one, rename aside and in). Returns where the replaced set now is, to be deleted. An error
    /// that another run's publication can explain is retried by the caller.
    fn try_publish(&self, parent: &Path, name: &str) -> std::io::Result<Option<PathBuf>> {
        match fs::rename(&self.staging, &self.target) {
            Ok(()) => return Ok(None),
            Err(e) if !self.target.exists() => return Err(e),
            Err(_) => {}
        }
        match exchange(&self.staging, &self.target) {
            // The staging name now holds the replaced set.
            Ok(()) => return Ok(Some(self.staging.clone())),
            Err(e) if e.kind() != ErrorKind::Unsupported => return Err(e),
            Err(_) => {}
        }
        self.replace_by_renames(parent, name)
    }

    /// Renames the target aside and the staging folder in: where the folders cannot be
    /// exchanged. Returns the folder aside.
    fn replace_by_renames(&self, parent: &Path, name: &str) -> std::io::Result<Option<PathBuf>> {
        let aside = parent.join(format!(".{name}.old.{}", owner_suffix()));
        fs::rename(&self.target, &aside)?;
        match fs::rename(&self.staging, &self.target) {
            Ok(()) => Ok(Some(aside)),
            Err(e) => {
                let _ = remove_leftover(&aside);
                Err(e)
            }
        }
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
/// (a `timings.parquet`, no sub-folder), and that this user may write there ([`check_writable`]).
/// Cheap; a run calls it before computing as well.
pub fn check_target(target: &Path) -> Result<(), OutputError> {
    check_shape(target)?;
    check_writable(target)
}

/// The shape half of [`check_target`].
fn check_shape(target: &Path) -> Result<(), OutputError> {
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

/// Checks that this user may publish a set at `target`: create the staging folder beside it (in
/// the folder that holds it, or the nearest existing folder above, where the missing ones are
/// made), and delete the files of the set it replaces (`target` itself, when it exists). The
/// system's own test (`access(2)`: permission bits, ACLs, read-only file systems) where there is
/// one, else the read-only attribute.
fn check_writable(target: &Path) -> Result<(), OutputError> {
    let (parent, _) = split(target)?;
    let mut holder = parent.as_path();
    while !holder.exists() {
        holder = match holder.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
    }
    let refuse = |folder: &Path, why: String, fix: String| OutputError::Write {
        path: target.to_path_buf(),
        message: format!(
            "{why} ({}): {fix}, or choose another results folder (--out); nothing was computed",
            writable(folder)
                .err()
                .map_or_else(String::new, |e| e.to_string())
        ),
    };
    if writable(holder).is_err() {
        return Err(refuse(
            holder,
            format!(
                "the folder {} it is made in is not writable by this user",
                holder.display()
            ),
            format!("make it writable (`chmod u+w {}`)", quote(holder)),
        ));
    }
    if target.is_dir() && writable(target).is_err() {
        return Err(refuse(
            target,
            String::from(
                "the folder is read-only for this user, and a run replaces it whole, deleting \
                 the files of the set it replaces",
            ),
            format!("make it writable (`chmod -R u+w {}`)", quote(target)),
        ));
    }
    Ok(())
}

/// `Ok` when this user may create and delete entries in the folder `dir`.
#[cfg(target_os = "linux")]
fn writable(dir: &Path) -> std::io::Result<()> {
    use rustix::fs::{access, Access};
    access(dir, Access::WRITE_OK | Access::EXEC_OK).map_err(std::io::Error::from)
}

#[cfg(not(target_os = "linux"))]
fn writable(dir: &Path) -> std::io::Result<()> {
    if fs::metadata(dir)?.permissions().readonly() {
        Err(std::io::Error::from(ErrorKind::PermissionDenied))
    } else {
        Ok(())
    }
}

/// A path for a shell command line, in single quotes when it needs them.
fn quote(path: &Path) -> String {
    let text = path.display().to_string();
    if text
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || "/._-+=:,@%".contains(c))
    {
        text
    } else {
        format!("'{}'", text.replace('\'', r"'\''"))
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

/// Deletes the stale staging and set-aside folders of earlier runs into `target` (see
/// `remove_stale`); a run calls it before computing. Returns a warning naming what could not be
/// deleted, with the command that deletes it.
pub fn remove_stale_stagings(target: &Path) -> Result<Option<String>, OutputError> {
    let target = resolve(target)?;
    let (parent, name) = split(&target)?;
    Ok(remove_stale(&parent, &name))
}

/// Deletes the staging and set-aside folders of runs into `<parent>/<name>` that are stale: made
/// on this host by a process that no longer runs, or older than a day. Returns a warning naming
/// those that could not be deleted.
fn remove_stale(parent: &Path, name: &str) -> Option<String> {
    let entries = fs::read_dir(parent).ok()?;
    let host = hostname();
    let mut left = Vec::new();
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
            if let Err(e) = remove_leftover(&entry.path()) {
                left.push(e);
            }
        }
    }
    (!left.is_empty()).then(|| cannot_remove(&parent.join(name), &left))
}

/// A folder a run left (a staging folder, a replaced set) that could not be deleted, and why.
#[derive(Debug)]
struct Leftover {
    path: PathBuf,
    error: std::io::Error,
}

/// Deletes a folder a run left. A set the user made read-only cannot be emptied as it is; as it
/// is asperity's own leftover, its folders are made writable by their owner and the deletion is
/// tried again.
fn remove_leftover(path: &Path) -> Result<(), Leftover> {
    let first = match fs::remove_dir_all(path) {
        Ok(()) => return Ok(()),
        Err(e) if e.kind() == ErrorKind::NotFound => return Ok(()),
        Err(e) => e,
    };
    if first.kind() == ErrorKind::PermissionDenied
        && make_folders_writable(path)
            .and_then(|()| fs::remove_dir_all(path))
            .is_ok()
    {
        return Ok(());
    }
    Err(Leftover {
        path: path.to_path_buf(),
        error: first,
    })
}

/// Gives the owner write and search permission on `dir` and every folder below it.
fn make_folders_writable(dir: &Path) -> std::io::Result<()> {
    let meta = fs::symlink_metadata(dir)?;
    if !meta.is_dir() {
        return Ok(());
    }
    let mut permissions = meta.permissions();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        permissions.set_mode(permissions.mode() | 0o700);
    }
    #[cfg(not(unix))]
    permissions.set_readonly(false);
    fs::set_permissions(dir, permissions)?;
    for entry in fs::read_dir(dir)? {
        make_folders_writable(&entry?.path())?;
    }
    Ok(())
}

/// One sentence for the leftovers of runs into `target` that could not be deleted.
fn cannot_remove(target: &Path, left: &[Leftover]) -> String {
    let paths: Vec<String> = left.iter().map(|l| quote(&l.path)).collect();
    format!(
        "cannot delete {} left by earlier runs into {} ({}): delete {} with `rm -rf {}`",
        if left.len() == 1 {
            String::from("a folder")
        } else {
            format!("{} folders", left.len())
        },
        target.display(),
        left.first()
            .map_or_else(String::new, |l| l.error.to_string()),
        if left.len() == 1 { "it" } else { "them" },
        paths.join(" ")
    )
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
        let aside = set.replace_by_renames(&dir, "out").unwrap().unwrap();
        remove_leftover(&aside).unwrap();
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
