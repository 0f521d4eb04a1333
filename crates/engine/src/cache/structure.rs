//! The folder structure of a cache, checked and repaired: what `cache verify` reports besides
//! corrupt entries, and what `cache gc` repairs.
//!
//! The rules, from the root down: `entries/` and `tmp/` are folders; `entries/` holds one folder
//! per kind; a kind folder holds prefix folders named by two lowercase hex digits; a prefix folder
//! holds entry folders (whose names and contents the verification of the entry checks); an entry
//! holds files. No link anywhere: asperity writes none, and one leading elsewhere makes the cache
//! depend on files it does not manage. Nothing stale in `tmp/` ([`super::stale_tmp`]).
//!
//! A file squatting a folder's name is removed, not moved aside: the cache holds only what
//! asperity derived and can derive again, a file there was not written by asperity, and kept
//! inside the cache it would be flagged again; `cache verify` and `cache gc --dry-run` name every
//! path before anything is removed. Removing a link never touches what it points to.

use std::fmt;
use std::fs::{self, DirEntry, FileType};
use std::path::{Path, PathBuf};

use super::{remove_any, stale_tmp, Cache, CacheError};

/// One violation of the cache's structure.
#[derive(Debug, Clone, PartialEq)]
pub struct Damage {
    pub path: PathBuf,
    /// What is wrong, as a sentence part: "is a file where a kind folder belongs".
    pub problem: String,
    pub repair: Repair,
}

/// What `cache gc` does about a [`Damage`].
#[derive(Debug, Clone, PartialEq)]
pub enum Repair {
    /// Remove the path (a file, a link, a folder).
    Remove,
    /// Remove the entry folder holding the path (it is recomputed when next needed).
    RemoveEntry(PathBuf),
    /// Nothing: a person has to decide (the reason says what to do).
    Manual(String),
}

impl fmt::Display for Damage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.path.display(), self.problem)
    }
}

impl fmt::Display for Repair {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Repair::Remove => f.write_str("removed"),
            Repair::RemoveEntry(entry) => write!(f, "removed the entry {}", entry.display()),
            Repair::Manual(what) => f.write_str(what),
        }
    }
}

/// Every violation of the structure rules in `cache`, in path order.
pub fn check(cache: &Cache) -> Result<Vec<Damage>, CacheError> {
    let mut found = Vec::new();
    let root = cache.root();
    let canonical_root = fs::canonicalize(root).unwrap_or_else(|_| root.to_path_buf());
    for top in ["entries", "tmp"] {
        let path = root.join(top);
        if fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_symlink()) {
            found.push(Damage {
                problem: link_problem(&path, &canonical_root),
                repair: Repair::Manual(format!(
                    "not repaired: give --cache the folder itself and move its {top}/ into it"
                )),
                path,
            });
        }
    }
    for kind in children(&root.join("entries"))? {
        let Some(kind_dir) = folder(&kind, "a kind folder", &canonical_root, &mut found) else {
            continue;
        };
        for prefix in children(&kind_dir)? {
            let Some(prefix_dir) = folder(&prefix, "a prefix folder", &canonical_root, &mut found)
            else {
                continue;
            };
            if !is_prefix(&prefix.file_name().to_string_lossy()) {
                found.push(Damage {
                    path: prefix_dir,
                    problem: String::from(
                        "is not a prefix folder (two lowercase hex digits) in a kind folder",
                    ),
                    repair: Repair::Remove,
                });
                continue;
            }
            for entry in children(&prefix_dir)? {
                if let Some(entry_dir) = folder(&entry, "an entry", &canonical_root, &mut found) {
                    check_entry(&entry_dir, &canonical_root, &mut found)?;
                }
            }
        }
    }
    for item in children(&root.join("tmp"))? {
        if let Some(why) = stale_tmp(&item) {
            found.push(Damage {
                path: item.path(),
                problem: format!("is a stray temporary file or folder ({why})"),
                repair: Repair::Remove,
            });
        }
    }
    found.sort_by(|a, b| a.path.cmp(&b.path));
    Ok(found)
}

/// Repairs one damage (see [`Repair`]); `Manual` ones are left alone.
pub fn repair(cache: &Cache, damage: &Damage) -> Result<(), CacheError> {
    let remove = |path: &Path| match remove_any(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(CacheError::Io {
            path: path.to_path_buf(),
            source: e,
        }),
        _ => Ok(()),
    };
    match &damage.repair {
        Repair::Remove => remove(&damage.path),
        Repair::RemoveEntry(entry) => {
            // Renamed into tmp/ first, so a reader sees the whole entry or none of it.
            let grave = cache.root().join("tmp").join(format!(
                "discarded.{}.gc.{}",
                entry.file_name().unwrap_or_default().to_string_lossy(),
                std::process::id()
            ));
            match fs::rename(entry, &grave) {
                Ok(()) => remove(&grave),
                Err(_) => remove(entry),
            }
        }
        Repair::Manual(_) => Ok(()),
    }
}

/// The folder `item` when it is one; otherwise records why not (`what` belongs there).
fn folder(
    item: &DirEntry,
    what: &str,
    canonical_root: &Path,
    found: &mut Vec<Damage>,
) -> Option<PathBuf> {
    let path = item.path();
    match item.file_type() {
        Ok(t) if t.is_dir() => Some(path),
        Ok(t) => {
            let problem = if t.is_symlink() {
                format!(
                    "{} where {what} belongs",
                    link_problem(&path, canonical_root)
                )
            } else {
                format!("is {} where {what} belongs", describe(t))
            };
            found.push(Damage {
                path,
                problem,
                repair: Repair::Remove,
            });
            None
        }
        Err(_) => None,
    }
}

/// An entry holds files only: a link or a folder in it damages the entry.
fn check_entry(
    dir: &Path,
    canonical_root: &Path,
    found: &mut Vec<Damage>,
) -> Result<(), CacheError> {
    for item in children(dir)? {
        let Ok(t) = item.file_type() else { continue };
        if t.is_file() {
            continue;
        }
        let path = item.path();
        let problem = if t.is_symlink() {
            format!("{} in an entry", link_problem(&path, canonical_root))
        } else {
            format!("is {} in an entry, which holds files only", describe(t))
        };
        found.push(Damage {
            path,
            problem,
            repair: Repair::RemoveEntry(dir.to_path_buf()),
        });
    }
    Ok(())
}

/// "is a link to T, outside the cache" (or inside it, or dangling).
fn link_problem(path: &Path, canonical_root: &Path) -> String {
    let target = fs::read_link(path).unwrap_or_default();
    match fs::canonicalize(path) {
        Ok(resolved) if !resolved.starts_with(canonical_root) => {
            format!("is a link to {}, outside the cache", target.display())
        }
        Ok(_) => format!(
            "is a link to {} (asperity writes no links)",
            target.display()
        ),
        Err(_) => format!("is a link to {}, which does not exist", target.display()),
    }
}

fn describe(t: FileType) -> &'static str {
    if t.is_file() {
        "a file"
    } else if t.is_dir() {
        "a folder"
    } else {
        "a special file"
    }
}

fn is_prefix(name: &str) -> bool {
    name.len() == 2 && name.bytes().all(|b| matches!(b, b'0'..=b'9' | b'a'..=b'f'))
}

/// The items of folder `dir` (none when it does not exist or is not a folder: the level above
/// reports that), sorted by name.
fn children(dir: &Path) -> Result<Vec<DirEntry>, CacheError> {
    if !fs::symlink_metadata(dir).is_ok_and(|m| m.is_dir()) {
        return Ok(Vec::new());
    }
    let mut items: Vec<DirEntry> = fs::read_dir(dir)
        .map_err(|source| CacheError::Io {
            path: dir.to_path_buf(),
            source,
        })?
        .flatten()
        .collect();
    items.sort_by_key(DirEntry::file_name);
    Ok(items)
}
