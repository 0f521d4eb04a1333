//! Cache management: list entries, their sizes, verify every checksum, garbage-collect.
//!
//! Walks `<root>/entries/<kind>/<key[..2]>/<key>/`. Removal renames an entry into `tmp/` first
//! (like [`Cache::discard`]), so a concurrent run either sees the whole entry or none of it and
//! recomputes; garbage collection never touches an entry a given study can reach. Besides the
//! entries, verification checks the folder structure and garbage collection repairs it
//! ([`crate::cache::structure`]).

use std::collections::HashSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use crate::cache::{remove_any, Cache, CacheError, Manifest};

pub use crate::cache::structure::{check as check_structure, Damage, Repair};
use crate::hash::NodeKey;

/// One entry found on disk.
#[derive(Debug, Clone, PartialEq)]
pub struct EntryInfo {
    pub kind: String,
    /// The key (the entry's directory name).
    pub key: String,
    pub dir: PathBuf,
    /// Total size of the entry's files, bytes.
    pub bytes: u64,
    /// The manifest, when it parses (its checksum is checked by [`verify_entry`], not here).
    pub manifest: Option<Manifest>,
    /// Creation time: the manifest's `created_unix`, else the directory's modification time,
    /// seconds since the Unix epoch.
    pub created_unix: u64,
}

/// Every entry of the cache, sorted by kind then key.
pub fn list_entries(cache: &Cache) -> Result<Vec<EntryInfo>, CacheError> {
    let entries_dir = cache.root().join("entries");
    let mut out = Vec::new();
    for kind_dir in sorted_subdirs(&entries_dir)? {
        let kind = file_name(&kind_dir);
        for prefix_dir in sorted_subdirs(&kind_dir)? {
            for dir in sorted_subdirs(&prefix_dir)? {
                let manifest = fs::read(dir.join("manifest.json"))
                    .ok()
                    .and_then(|b| serde_json::from_slice::<Manifest>(&b).ok());
                let created_unix = manifest.as_ref().map_or_else(
                    || {
                        fs::metadata(&dir)
                            .and_then(|m| m.modified())
                            .ok()
                            .and_then(|t| t.duration_since(UNIX_EPOCH).ok())
                            .map_or(0, |d| d.as_secs())
                    },
                    |m| m.created_unix,
                );
                out.push(EntryInfo {
                    kind: kind.clone(),
                    key: file_name(&dir),
                    bytes: dir_size(&dir),
                    manifest,
                    created_unix,
                    dir,
                });
            }
        }
    }
    Ok(out)
}

/// What a payload file of an entry holds, for `cache du`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum PayloadClass {
    /// An array (`.npy.zst`, `.npy`).
    Array,
    /// A long table (`<table>.parquet`; `tables.json` in entries of format 1).
    Table,
    /// The entry's `summary.bin`.
    Summary,
}

/// The payload files an entry's manifest lists, each file once (an array equal to another of
/// its entry names the same file): class, name (the array's or the table's, or the file's) and
/// bytes. The manifest and its checksum file are not payloads.
pub fn payload_usage(manifest: &Manifest) -> Vec<(PayloadClass, String, u64)> {
    let mut seen = HashSet::new();
    let mut usage = Vec::new();
    for payload in &manifest.payloads {
        if !seen.insert(payload.file.as_str()) {
            continue;
        }
        let (class, name) = match payload.array_name() {
            Some(array) => (PayloadClass::Array, array),
            None => match payload.file.strip_suffix(".parquet") {
                Some(table) => (PayloadClass::Table, table),
                None if payload.file == "tables.json" => (PayloadClass::Table, "tables.json"),
                None => (PayloadClass::Summary, payload.file.as_str()),
            },
        };
        usage.push((class, name.to_string(), payload.bytes));
    }
    usage
}

/// Verifies one entry fully (manifest checksum, every payload's size and checksum, arrays
/// decoded, the summary). `Ok(())` when it is sound; the reason otherwise.
pub fn verify_entry(cache: &Cache, entry: &EntryInfo) -> Result<(), String> {
    let key = NodeKey::from_hex(&entry.key)
        .ok_or_else(|| format!("directory name '{}' is not a node key", entry.key))?;
    if cache.entry_dir(&entry.kind, &key) != entry.dir {
        return Err(String::from(
            "entry is not under its key's prefix directory",
        ));
    }
    match cache.verify(&entry.kind, &key) {
        Ok(true) => Ok(()),
        Ok(false) => Err(String::from("entry vanished while being verified")),
        Err(CacheError::Corrupt { reason, .. }) => Err(reason),
        Err(e) => Err(e.to_string()),
    }
}

/// Which entries garbage collection removes. Criteria combine: an entry is removed only when
/// it matches every criterion given; with no criterion nothing is removed.
#[derive(Debug, Clone, Default)]
pub struct GcCriteria {
    /// Keys (hex) to keep: every instance of the given studies. `None`: no study was given.
    pub keep: Option<HashSet<String>>,
    /// Remove only entries created more than this long ago.
    pub older_than: Option<Duration>,
}

impl GcCriteria {
    /// `true` when `entry` is garbage under these criteria at time `now`.
    pub fn is_garbage(&self, entry: &EntryInfo, now: SystemTime) -> bool {
        if self.keep.is_none() && self.older_than.is_none() {
            return false;
        }
        let unreachable = self
            .keep
            .as_ref()
            .is_none_or(|keep| !keep.contains(&entry.key));
        let old = self.older_than.is_none_or(|age| {
            let now = now.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs());
            now.saturating_sub(entry.created_unix) > age.as_secs()
        });
        unreachable && old
    }
}

/// What garbage collection removed (or, in a dry run, would remove).
#[derive(Debug, Clone, Default)]
pub struct GcReport {
    pub removed: Vec<EntryInfo>,
    pub kept: usize,
    pub freed_bytes: u64,
    /// Structural damage found, stray temporary files and folders included; repaired unless in a
    /// dry run (see each one's [`Repair`]).
    pub damage: Vec<Damage>,
}

/// Repairs the structure ([`check_structure`]), removes the entries matching `criteria`, then
/// empty prefix folders; a dry run changes nothing.
pub fn collect_garbage(
    cache: &Cache,
    criteria: &GcCriteria,
    dry_run: bool,
) -> Result<GcReport, CacheError> {
    let now = SystemTime::now();
    let mut report = GcReport {
        damage: check_structure(cache)?,
        ..GcReport::default()
    };
    if !dry_run {
        for damage in &report.damage {
            crate::cache::structure::repair(cache, damage)?;
        }
    }
    for entry in list_entries(cache)? {
        if !criteria.is_garbage(&entry, now) {
            report.kept += 1;
            continue;
        }
        if !dry_run {
            remove_entry(cache, &entry)?;
        }
        report.freed_bytes += entry.bytes;
        report.removed.push(entry);
    }
    if !dry_run {
        remove_empty_dirs(&cache.root().join("entries"))?;
    }
    Ok(report)
}

/// Removes one entry: renamed into `tmp/` first, then deleted.
pub fn remove_entry(cache: &Cache, entry: &EntryInfo) -> Result<(), CacheError> {
    let grave =
        cache
            .root()
            .join("tmp")
            .join(format!("discarded.{}.gc.{}", entry.key, std::process::id()));
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| CacheError::Io { path, source }
    };
    match fs::rename(&entry.dir, &grave) {
        Ok(()) => remove_any(&grave).map_err(io(&grave)),
        Err(_) if !entry.dir.exists() => Ok(()),
        Err(e) => Err(io(&entry.dir)(e)),
    }
}

fn remove_empty_dirs(entries_dir: &Path) -> Result<(), CacheError> {
    for kind_dir in sorted_subdirs(entries_dir)? {
        for prefix_dir in sorted_subdirs(&kind_dir)? {
            // Fails (harmlessly) when not empty or when a writer just published into it.
            let _ = fs::remove_dir(&prefix_dir);
        }
        let _ = fs::remove_dir(&kind_dir);
    }
    Ok(())
}

fn sorted_subdirs(dir: &Path) -> Result<Vec<PathBuf>, CacheError> {
    let read = match fs::read_dir(dir) {
        Ok(r) => r,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(source) => {
            return Err(CacheError::Io {
                path: dir.to_path_buf(),
                source,
            })
        }
    };
    let mut v: Vec<PathBuf> = read
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
        .map(|e| e.path())
        .collect();
    v.sort();
    Ok(v)
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default()
}

fn dir_size(dir: &Path) -> u64 {
    fs::read_dir(dir)
        .map(|r| {
            r.flatten()
                .filter_map(|e| e.metadata().ok())
                .filter(|m| m.is_file())
                .map(|m| m.len())
                .sum()
        })
        .unwrap_or(0)
}

/// Parses an age such as `30d`, `12h`, `90m`, `45s` or `2w` (a bare number is seconds).
pub fn parse_age(text: &str) -> Result<Duration, String> {
    let t = text.trim();
    let split = t.find(|c: char| !c.is_ascii_digit()).unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let n: u64 = number
        .parse()
        .map_err(|_| format!("invalid age '{text}': expected e.g. 30d, 12h, 90m"))?;
    let unit_seconds = match unit.trim() {
        "" | "s" => 1,
        "m" | "min" => 60,
        "h" => 3600,
        "d" => 86_400,
        "w" => 7 * 86_400,
        other => {
            return Err(format!(
                "invalid age unit '{other}' in '{text}' (s, m, h, d, w)"
            ))
        }
    };
    n.checked_mul(unit_seconds)
        .map(Duration::from_secs)
        .ok_or_else(|| format!("age '{text}' is too large"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ages_parse_with_units() {
        assert_eq!(parse_age("45"), Ok(Duration::from_secs(45)));
        assert_eq!(parse_age("90m"), Ok(Duration::from_secs(5400)));
        assert_eq!(parse_age("2d"), Ok(Duration::from_secs(172_800)));
        assert_eq!(parse_age("1w"), Ok(Duration::from_secs(604_800)));
        for bad in ["", "d", "3y", "-1d", "99999999999999999999d"] {
            assert!(parse_age(bad).is_err(), "{bad}");
        }
    }

    fn entry(key: &str, created_unix: u64) -> EntryInfo {
        EntryInfo {
            kind: String::from("surface"),
            key: key.to_string(),
            dir: PathBuf::new(),
            bytes: 1,
            manifest: None,
            created_unix,
        }
    }

    #[test]
    fn gc_criteria_combine_and_default_to_keeping_everything() {
        let now = UNIX_EPOCH + Duration::from_secs(10_000);
        let old = entry("aa", 1_000);
        let new = entry("bb", 9_990);
        assert!(!GcCriteria::default().is_garbage(&old, now));
        let by_age = GcCriteria {
            keep: None,
            older_than: Some(Duration::from_secs(100)),
        };
        assert!(by_age.is_garbage(&old, now) && !by_age.is_garbage(&new, now));
        let keep_old = GcCriteria {
            keep: Some(HashSet::from([String::from("aa")])),
            older_than: None,
        };
        assert!(!keep_old.is_garbage(&old, now) && keep_old.is_garbage(&new, now));
        let both = GcCriteria {
            keep: Some(HashSet::from([String::from("aa")])),
            older_than: Some(Duration::from_secs(100)),
        };
        assert!(!both.is_garbage(&old, now) && !both.is_garbage(&new, now));
    }
}
