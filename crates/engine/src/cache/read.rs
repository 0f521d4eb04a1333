//! Reading an entry's payloads, each checked against the size and checksum listed for it: the
//! arrays, the table files against the summary's schemas, and an entry of format 1 through its
//! manifest and `tables.json`.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::Read;
use std::path::Path;

use crate::artifact::{Artifact, Table};
use crate::npy;

use super::summary::{self, TableFile, SUMMARY_FILE};
use super::{table_file, EntryManifest, EntryRead, ManifestRead, Payload};

/// The arrays (`arrays`) and the tables (`tables`) of an entry's payloads, each payload read
/// checked against its listed size and checksum; payloads that are neither are read and checked
/// whenever `tables` is. Errors say what is corrupt.
pub(super) fn read_payloads(
    dir: &Path,
    payloads: &[Payload],
    arrays: bool,
    tables: bool,
) -> Result<Artifact, String> {
    let mut artifact = Artifact::default();
    // Arrays decoded so far by file: an array equal to an earlier one names its file.
    let mut decoded: BTreeMap<&str, ndarray::ArrayD<f64>> = BTreeMap::new();
    for payload in payloads {
        let array = payload.array_name();
        if (array.is_some() && !arrays) || (array.is_none() && !tables) {
            continue;
        }
        if let (Some(name), Some(array)) = (array, decoded.get(&*payload.file)) {
            artifact.arrays.insert(name.to_string(), array.clone());
            continue;
        }
        let bytes = read_payload(dir, payload)?;
        if let Some(name) = array {
            let npy_bytes = if payload.file.ends_with(".zst") {
                zstd::stream::decode_all(bytes.as_slice())
                    .map_err(|e| format!("{}: {e}", payload.file))?
            } else {
                bytes
            };
            let array = npy::decode(&npy_bytes).map_err(|e| e.to_string())?;
            decoded.insert(&payload.file, array.clone());
            artifact.arrays.insert(name.to_string(), array);
        } else if payload.file == "tables.json" {
            artifact.tables = serde_json::from_slice::<BTreeMap<String, Table>>(&bytes)
                .map_err(|e| format!("tables.json: {e}"))?;
        }
    }
    Ok(artifact)
}

/// The bytes of `payload`, checked against its listed size and checksum.
fn read_payload(dir: &Path, payload: &Payload) -> Result<Vec<u8>, String> {
    let bytes = read_file(&dir.join(&payload.file), payload.bytes as usize)
        .map_err(|e| format!("{}: {e}", payload.file))?;
    if bytes.len() as u64 != payload.bytes
        || blake3::hash(&bytes).to_hex().as_str() != payload.blake3
    {
        return Err(format!("{}: checksum mismatch", payload.file));
    }
    Ok(bytes)
}

/// An entry of format 1 read through its manifest: the metrics and flags from the manifest, the
/// tables from `tables.json` (checked against the manifest). A later format keeps its metrics
/// only in its summary: without a summary this version reads, it is unreadable.
pub(super) fn first_format_entry(dir: &Path, read: ManifestRead) -> Result<EntryRead, String> {
    if read.format > 1 {
        return Err(unreadable_summary(read.format));
    }
    let tables = read_payloads(dir, &read.payloads, false, true)?.tables;
    Ok(EntryRead {
        manifest: EntryManifest {
            upstream: read.upstream,
            compute_seconds: read.compute_seconds,
        },
        artifact: Artifact {
            metrics: read.metrics,
            tables,
            flags: read.flags,
            ..Artifact::default()
        },
        payloads: read.payloads,
    })
}

pub(super) fn unreadable_summary(format: u32) -> String {
    format!(
        "an entry of format {format} without a {SUMMARY_FILE} of version {} (written by \
         another version of asperity)",
        summary::VERSION
    )
}

/// Reads the tables kept in files of their own into `artifact`, each file checked against the
/// size and checksum its summary lists and decoded against its schema.
pub(super) fn read_table_files(
    dir: &Path,
    files: &[TableFile],
    artifact: &mut Artifact,
) -> Result<(), String> {
    for file in files {
        let bytes = read_payload(dir, &file.payload)?;
        let table = table_file::decode(&bytes, &file.schema, file.rows)
            .map_err(|e| format!("{}: {e}", file.payload.file))?;
        artifact.tables.insert(file.name.clone(), table);
    }
    Ok(())
}

/// Room for a manifest or a summary (a few kB) and for a checksum file (64 hex digits) read whole.
pub(super) const READ_CAPACITY: usize = 16 << 10;
pub(super) const CHECKSUM_CAPACITY: usize = 80;

/// Reads a whole file into a buffer made for `expected` bytes. Through [`Read::take`], which
/// does not ask the file for its size as `fs::read` does: one system call less per file, and a
/// cached rerun reads a few files per node.
pub(super) fn read_file(path: &Path, expected: usize) -> std::io::Result<Vec<u8>> {
    let mut bytes = Vec::with_capacity(expected + 1);
    File::open(path)?.take(u64::MAX).read_to_end(&mut bytes)?;
    Ok(bytes)
}
