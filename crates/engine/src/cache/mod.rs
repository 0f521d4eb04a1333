//! The content-addressed cache: one directory per node key, published atomically, verified on
//! every read.
//!
//! Layout: `<root>/entries/<kind>/<key[..2]>/<key>/` holds `manifest.json`, `manifest.blake3`
//! (the manifest's own checksum) and the payloads: `<array>.npy.zst` (a NumPy `.npy` file,
//! zstd-compressed: lossless, and a contact's mostly-zero pressure maps shrink by orders of
//! magnitude; `zstd -d` gives the `.npy`), `<table>.parquet` for each large long table
//! (`cache/table_file.rs`) and `summary.bin` (what a read returns — metrics, flags, the small
//! tables and the list of the other payloads — in one self-checksummed binary file:
//! `cache/summary.rs`); an array equal to an earlier one of the entry is not written again, its
//! manifest payload names the earlier file. A node kind may keep some or all of its arrays out of
//! the cache ([`crate::node::ArrayStorage`]): the caller says which arrays [`Cache::store`] keeps.
//!
//! Entry formats: the manifest's `format` is 2 for entries written so; entries written before
//! (format 1, no `format` field) keep their metrics and flags in the manifest and their tables in
//! `tables.json`, and are read through the manifest (entries written before compression hold
//! plain `<array>.npy`, entries written before summaries no `summary.bin`). A format-2 manifest
//! has no metrics, so an earlier asperity takes such an entry for damaged and recomputes it
//! rather than read it without its tables.
//!
//! An entry is written in `<root>/tmp/` (same filesystem), every file fsynced, then renamed into
//! place in one step; an entry that already exists counts as success, so concurrent runs need no
//! lock. A read verifies everything it reads: the summary against its own checksum (or the
//! manifest against `manifest.blake3`), and the size and blake3 checksum of every payload it
//! reads (a read for metrics and tables leaves the arrays unread); an entry that fails is
//! reported, discarded and recomputed by the caller — never used.

mod names;
mod read;
pub mod structure;
mod summary;
mod table_file;
mod tmp;

use std::collections::{BTreeMap, HashMap, HashSet};
use std::ffi::{OsStr, OsString};
use std::fs::{self, File};
use std::io::{ErrorKind, Write};
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::artifact::Artifact;
use crate::hash::NodeKey;
use crate::npy;
use crate::value::Field;

use read::{
    first_format_entry, read_file, read_payloads, read_table_files, unreadable_summary,
    CHECKSUM_CAPACITY, READ_CAPACITY,
};
use summary::{Summary, SUMMARY_FILE};
use tmp::stale_tmp;
pub(crate) use tmp::{hostname, process_alive, remove_any, FOREIGN_TMP_MAX_AGE};

/// The entry format this version writes (see the module documentation).
pub const ENTRY_FORMAT: u32 = 2;

/// The format of a manifest without a `format` field.
fn first_format() -> u32 {
    1
}

/// What the cache records about one entry (the metrics, flags and tables are in its summary).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// [`ENTRY_FORMAT`] for entries written by this version; 1 for earlier ones.
    #[serde(default = "first_format")]
    pub format: u32,
    pub key: String,
    pub kind: String,
    pub version: u32,
    pub params: Vec<Field>,
    /// `(role, key)` of each upstream node.
    pub upstream: Vec<(String, String)>,
    pub payloads: Vec<Payload>,
    pub compute_seconds: f64,
    pub tool_version: String,
    pub created_unix: u64,
}

/// One payload file of an entry.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Payload {
    pub file: String,
    pub bytes: u64,
    pub blake3: String,
    /// The array this payload holds, when it is not the file's stem: an array identical to an
    /// earlier one of the entry (e.g. the two deformation maps of a pair of equal materials)
    /// names that array's file instead of storing the bytes twice.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub array: Option<String>,
}

impl Payload {
    /// The array name, if this payload is an array.
    pub fn array_name(&self) -> Option<&str> {
        match &self.array {
            Some(name) => Some(name),
            None => self
                .file
                .strip_suffix(".npy.zst")
                .or_else(|| self.file.strip_suffix(".npy")),
        }
    }
}

/// A verified cache entry.
#[derive(Debug, Clone, PartialEq)]
pub struct CachedEntry {
    pub manifest: EntryManifest,
    /// The artifact (metrics, tables and, when requested, arrays).
    pub artifact: Artifact,
}

/// What a read of an entry keeps of its manifest besides the metrics (which go to the artifact)
/// and the payload list (which the read itself uses); the parameters, versions and times are not
/// parsed.
#[derive(Debug, Clone, PartialEq)]
pub struct EntryManifest {
    /// `(role, key)` of each upstream node.
    pub upstream: Vec<(String, String)>,
    pub compute_seconds: f64,
}

/// What a read finds of an entry before its arrays: the manifest part, the metrics and tables,
/// and the payload list (read from a summary only when the arrays are wanted).
struct EntryRead {
    manifest: EntryManifest,
    artifact: Artifact,
    payloads: Vec<Payload>,
}

/// The fields of a manifest a read parses; the metrics and flags are those of a format-1
/// manifest (absent from later ones; a format-1 manifest without flags has none).
#[derive(Deserialize)]
struct ManifestRead {
    #[serde(default = "first_format")]
    format: u32,
    key: String,
    kind: String,
    upstream: Vec<(String, String)>,
    #[serde(default)]
    metrics: Vec<Field>,
    #[serde(default)]
    flags: Vec<String>,
    payloads: Vec<Payload>,
    compute_seconds: f64,
}

/// Cache failures.
#[derive(Debug, thiserror::Error)]
pub enum CacheError {
    #[error("cache {path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("corrupt cache entry {path}: {reason}")]
    Corrupt { path: PathBuf, reason: String },
    /// The cache's folder structure is damaged where a result is to be stored.
    #[error(
        "damaged cache: {path} {reason}, so no result can be stored under it; \
         `asperity cache gc` repairs it"
    )]
    Damaged { path: PathBuf, reason: String },
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> CacheError + '_ {
    move |source| CacheError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// zstd level of array payloads: the fastest, since dense float fields gain little from more.
const ZSTD_LEVEL: i32 = 1;

/// `bytes` as one zstd frame at [`ZSTD_LEVEL`] (the bytes of `zstd::stream::encode_all`), written
/// into a buffer allocated once at the frame's worst-case size instead of one grown by copying.
fn compress(bytes: &[u8]) -> std::io::Result<Vec<u8>> {
    let mut frame = Vec::with_capacity(zstd::zstd_safe::compress_bound(bytes.len()));
    let mut encoder = zstd::stream::Encoder::new(&mut frame, ZSTD_LEVEL)?;
    encoder.write_all(bytes)?;
    encoder.finish()?;
    Ok(frame)
}

/// A cache rooted at a directory.
#[derive(Debug, Clone)]
pub struct Cache {
    root: PathBuf,
}

impl Cache {
    /// Opens (creating if needed) the cache at `root`.
    pub fn open(root: &Path) -> Result<Self, CacheError> {
        for sub in ["entries", "tmp"] {
            let dir = root.join(sub);
            fs::create_dir_all(&dir).map_err(io_err(&dir))?;
        }
        Ok(Self {
            root: root.to_path_buf(),
        })
    }

    /// The cache root.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The directory of the entry for `key` of kind `kind`, made in one allocation with room for
    /// the name of a file in it.
    pub fn entry_dir(&self, kind: &str, key: &NodeKey) -> PathBuf {
        let hex = key.to_hex();
        let mut dir = PathBuf::with_capacity(self.root.as_os_str().len() + kind.len() + 128);
        for part in [self.root.as_os_str(), "entries".as_ref(), kind.as_ref()] {
            dir.push(part);
        }
        dir.push(&hex[..2]);
        dir.push(hex);
        dir
    }

    /// `true` when an entry directory exists (it may still fail verification).
    pub fn contains(&self, kind: &str, key: &NodeKey) -> bool {
        self.entry_dir(kind, key).join("manifest.json").exists()
    }

    /// For each `(kind, key)`, whether its entry directory exists (it may still fail
    /// verification). Each prefix directory (`entries/<kind>/<key[..2]>`) is listed once, in
    /// parallel, rather than every entry queried: a study's worth of entries at once.
    pub fn present(&self, entries: &[(&str, &NodeKey)]) -> Vec<bool> {
        let mut groups: HashMap<(&str, u8), Vec<usize>> = HashMap::new();
        for (i, (kind, key)) in entries.iter().enumerate() {
            groups.entry((kind, key.0[0])).or_default().push(i);
        }
        let found: Vec<Vec<usize>> = groups
            .into_par_iter()
            .map(|((kind, prefix), members)| {
                let dir = self
                    .root
                    .join("entries")
                    .join(kind)
                    .join(format!("{prefix:02x}"));
                let names: HashSet<OsString> = fs::read_dir(dir)
                    .into_iter()
                    .flatten()
                    .flatten()
                    .map(|e| e.file_name())
                    .collect();
                members
                    .into_iter()
                    .filter(|&i| names.contains(OsStr::new(&entries[i].1.to_hex())))
                    .collect()
            })
            .collect();
        let mut present = vec![false; entries.len()];
        for i in found.into_iter().flatten() {
            present[i] = true;
        }
        present
    }

    /// Loads and verifies an entry. `Ok(None)`: not cached. `Err(Corrupt)`: present but failed
    /// verification — call [`Cache::discard`] and recompute. Everything read is verified. An
    /// entry is read from its summary (`summary.bin`, which carries its own checksum) and its
    /// table files, each checked against the size and checksum the summary lists; an entry
    /// written before summaries (or with a summary of another format version) of entry format 1
    /// through its manifest (checked against `manifest.blake3`) and `tables.json`. The arrays are
    /// read only `with_arrays`, each checked against the size and checksum listed for it, so a
    /// damaged array is found when its arrays are next loaded, or by [`Cache::verify`].
    pub fn load(
        &self,
        kind: &str,
        key: &NodeKey,
        with_arrays: bool,
    ) -> Result<Option<CachedEntry>, CacheError> {
        let dir = self.entry_dir(kind, key);
        let corrupt = |reason: String| CacheError::Corrupt {
            path: dir.clone(),
            reason,
        };
        let summary = match read_file(&dir.join(SUMMARY_FILE), READ_CAPACITY) {
            Ok(bytes) => summary::decode(&bytes, key, kind, with_arrays)
                .map_err(|e| corrupt(format!("{SUMMARY_FILE}: {e}")))?,
            Err(e) if e.kind() == ErrorKind::NotFound => None,
            Err(e) => return Err(corrupt(format!("{SUMMARY_FILE}: {e}"))),
        };
        let read = match summary {
            Some(mut d) => {
                read_table_files(&dir, &d.table_files, &mut d.artifact).map_err(corrupt)?;
                EntryRead {
                    manifest: d.manifest,
                    artifact: d.artifact,
                    payloads: d.payloads,
                }
            }
            None => match self.read_manifest(&dir, kind, key)? {
                Some(manifest) => first_format_entry(&dir, manifest).map_err(corrupt)?,
                None => return Ok(None),
            },
        };
        let EntryRead {
            manifest,
            mut artifact,
            payloads,
        } = read;
        if with_arrays {
            artifact.arrays = read_payloads(&dir, &payloads, true, false)
                .map_err(corrupt)?
                .arrays;
        }
        Ok(Some(CachedEntry { manifest, artifact }))
    }

    /// Verifies an entry fully: the manifest against its checksum, every payload it lists
    /// (arrays decoded, tables parsed) and the summary (a summary of another format version is
    /// checked only as a payload, and only an entry of format 1 may have one). `Ok(false)`: not
    /// cached.
    pub fn verify(&self, kind: &str, key: &NodeKey) -> Result<bool, CacheError> {
        let dir = self.entry_dir(kind, key);
        let corrupt = |reason: String| CacheError::Corrupt {
            path: dir.clone(),
            reason,
        };
        let Some(manifest) = self.read_manifest(&dir, kind, key)? else {
            return Ok(false);
        };
        read_payloads(&dir, &manifest.payloads, true, true).map_err(corrupt)?;
        let summary = match read_file(&dir.join(SUMMARY_FILE), READ_CAPACITY) {
            Ok(bytes) => summary::decode(&bytes, key, kind, true)
                .map_err(|e| corrupt(format!("{SUMMARY_FILE}: {e}")))?,
            Err(e) if e.kind() == ErrorKind::NotFound => None,
            Err(e) => return Err(corrupt(format!("{SUMMARY_FILE}: {e}"))),
        };
        match summary {
            Some(mut d) => {
                read_table_files(&dir, &d.table_files, &mut d.artifact).map_err(corrupt)?
            }
            None if manifest.format > 1 => {
                return Err(corrupt(unreadable_summary(manifest.format)));
            }
            None => {}
        }
        Ok(true)
    }

    /// The manifest of the entry in `dir`, checked against `manifest.blake3` and against the key
    /// and kind; `None` when there is no entry.
    fn read_manifest(
        &self,
        dir: &Path,
        kind: &str,
        key: &NodeKey,
    ) -> Result<Option<ManifestRead>, CacheError> {
        let corrupt = |reason: String| CacheError::Corrupt {
            path: dir.to_path_buf(),
            reason,
        };
        // Whether the entry existed is asked before its manifest is read: entries are published
        // whole, by one rename, so a manifest missing from an entry that was already there is
        // damage, while one missing from an entry that was not is just not cached. (Asked after
        // the read, an entry another process published in between would be taken for damaged.)
        let existed = dir.exists();
        let manifest_bytes = match read_file(&dir.join("manifest.json"), READ_CAPACITY) {
            Ok(bytes) => bytes,
            Err(e) if e.kind() == ErrorKind::NotFound && !existed => return Ok(None),
            Err(e) => return Err(corrupt(format!("manifest.json: {e}"))),
        };
        let recorded = read_file(&dir.join("manifest.blake3"), CHECKSUM_CAPACITY)
            .map_err(|e| corrupt(format!("manifest.blake3: {e}")))?;
        if blake3::hash(&manifest_bytes).to_hex().as_bytes() != recorded.trim_ascii() {
            return Err(corrupt(String::from("manifest checksum mismatch")));
        }
        let read: ManifestRead = serde_json::from_slice(&manifest_bytes)
            .map_err(|e| corrupt(format!("manifest.json: {e}")))?;
        if read.key != key.to_hex() || read.kind != kind {
            return Err(corrupt(String::from("manifest names another key or kind")));
        }
        Ok(Some(read))
    }

    /// Publishes an entry atomically: the manifest, the artifact's metrics, flags and tables, and
    /// its arrays for which `keeps_array` is `true` (those the node kind stores). Returns `false`
    /// when another writer published the same key first (which is success: entries with one key
    /// are interchangeable).
    pub fn store(
        &self,
        mut manifest: Manifest,
        artifact: &Artifact,
        keeps_array: &dyn Fn(&str) -> bool,
    ) -> Result<bool, CacheError> {
        let key = NodeKey::from_hex(&manifest.key).ok_or_else(|| CacheError::Corrupt {
            path: self.root.clone(),
            reason: format!("manifest key '{}' is not a node key", manifest.key),
        })?;
        let final_dir = self.entry_dir(&manifest.kind, &key);
        if final_dir.exists() {
            return Ok(false);
        }
        let tmp = self.root.join("tmp").join(format!(
            "{}.{}.{}.{}",
            manifest.key,
            hostname(),
            std::process::id(),
            SystemTime::now()
                .duration_since(UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos())
        ));
        fs::create_dir_all(&tmp).map_err(io_err(&tmp))?;
        let result = self.write_and_publish(
            &tmp,
            &final_dir,
            (&key, &mut manifest),
            artifact,
            keeps_array,
        );
        if result.is_err() || tmp.exists() {
            let _ = fs::remove_dir_all(&tmp);
        }
        result
    }

    fn write_and_publish(
        &self,
        tmp: &Path,
        final_dir: &Path,
        (key, manifest): (&NodeKey, &mut Manifest),
        artifact: &Artifact,
        keeps_array: &dyn Fn(&str) -> bool,
    ) -> Result<bool, CacheError> {
        manifest.format = ENTRY_FORMAT;
        manifest.payloads.clear();
        for (name, array) in artifact.arrays.iter().filter(|(n, _)| keeps_array(n)) {
            let file = format!("{name}.npy.zst");
            let compressed = compress(&npy::encode(array)).map_err(io_err(&tmp.join(&file)))?;
            let checksum = blake3::hash(&compressed).to_hex().to_string();
            let payload = match manifest.payloads.iter().find(|p| p.blake3 == checksum) {
                Some(same) => Payload {
                    array: Some(name.clone()),
                    ..same.clone()
                },
                None => write_synced(tmp, &file, &compressed)?,
            };
            manifest.payloads.push(payload);
        }
        let mut table_files = BTreeMap::new();
        for (name, table) in artifact
            .tables
            .iter()
            .filter(|(_, t)| table_file::is_large(t))
        {
            let invalid = |message: String| CacheError::Io {
                path: tmp.join(name),
                source: std::io::Error::other(message),
            };
            let file = table_file::file_name(name).map_err(invalid)?;
            let bytes = table_file::encode(table).map_err(invalid)?;
            table_files.insert(name.clone(), write_synced(tmp, &file, &bytes)?);
        }
        let summary = summary::encode(&Summary {
            key,
            kind: &manifest.kind,
            upstream: &manifest.upstream,
            payloads: &manifest.payloads,
            compute_seconds: manifest.compute_seconds,
            metrics: &artifact.metrics,
            tables: &artifact.tables,
            table_files: &table_files,
            flags: &artifact.flags,
        });
        manifest.payloads.extend(table_files.into_values());
        manifest
            .payloads
            .push(write_synced(tmp, SUMMARY_FILE, &summary)?);
        let manifest_bytes = serde_json::to_vec_pretty(&manifest).map_err(|e| CacheError::Io {
            path: tmp.join("manifest.json"),
            source: std::io::Error::other(e),
        })?;
        write_synced(tmp, "manifest.json", &manifest_bytes)?;
        let checksum = blake3::hash(&manifest_bytes).to_hex().to_string();
        write_synced(tmp, "manifest.blake3", checksum.as_bytes())?;
        sync_dir(tmp)?;
        let parent = final_dir.parent().unwrap_or(&self.root);
        fs::create_dir_all(parent)
            .map_err(|e| self.damaged_ancestor(parent).unwrap_or(io_err(parent)(e)))?;
        match fs::rename(tmp, final_dir) {
            Ok(()) => {
                sync_dir(parent)?;
                Ok(true)
            }
            Err(_) if final_dir.exists() => Ok(false),
            Err(e) => Err(io_err(final_dir)(e)),
        }
    }

    /// The first of `dir`'s ancestors below the cache root (or `dir` itself) that exists but is
    /// not a folder: what keeps a folder from being created there.
    fn damaged_ancestor(&self, dir: &Path) -> Option<CacheError> {
        let below = dir.strip_prefix(&self.root).ok()?;
        let mut path = self.root.clone();
        for part in below {
            path.push(part);
            match fs::symlink_metadata(&path) {
                Ok(m) if m.is_dir() => {}
                Ok(m) => {
                    let reason = if m.file_type().is_symlink() {
                        "is a link where a folder belongs"
                    } else {
                        "is a file where a folder belongs"
                    };
                    return Some(CacheError::Damaged {
                        path,
                        reason: reason.to_string(),
                    });
                }
                Err(_) => return None,
            }
        }
        None
    }

    /// Removes an entry (after a failed verification). The entry is first renamed away so no
    /// reader sees it half-deleted.
    pub fn discard(&self, kind: &str, key: &NodeKey) -> Result<(), CacheError> {
        let dir = self.entry_dir(kind, key);
        let graveyard = self.root.join("tmp").join(format!(
            "discarded.{}.{}.{}",
            key.to_hex(),
            hostname(),
            std::process::id()
        ));
        match fs::rename(&dir, &graveyard) {
            Ok(()) => remove_any(&graveyard).map_err(io_err(&graveyard)),
            Err(_) if !dir.exists() => Ok(()),
            Err(e) => Err(io_err(&dir)(e)),
        }
    }

    /// Deletes what writers that died left in `tmp/` ([`stale_tmp`] says what is stale). Returns
    /// how many were removed.
    pub fn clean_stale_tmp(&self) -> Result<usize, CacheError> {
        let tmp = self.root.join("tmp");
        let mut removed = 0;
        let entries = fs::read_dir(&tmp).map_err(io_err(&tmp))?;
        for entry in entries.flatten() {
            if stale_tmp(&entry).is_some() && remove_any(&entry.path()).is_ok() {
                removed += 1;
            }
        }
        Ok(removed)
    }
}

fn write_synced(dir: &Path, file: &str, bytes: &[u8]) -> Result<Payload, CacheError> {
    let path = dir.join(file);
    let mut f = File::create(&path).map_err(io_err(&path))?;
    f.write_all(bytes).map_err(io_err(&path))?;
    f.sync_all().map_err(io_err(&path))?;
    Ok(Payload {
        file: file.to_string(),
        bytes: bytes.len() as u64,
        blake3: blake3::hash(bytes).to_hex().to_string(),
        array: None,
    })
}

fn sync_dir(dir: &Path) -> Result<(), CacheError> {
    File::open(dir)
        .and_then(|d| d.sync_all())
        .map_err(io_err(dir))
}
