//! Which study file wrote a results folder: the metadata of its `timings.parquet`.
//!
//! Every table carries the study's name and the blake3 of the study file's bytes; `timings.parquet`
//! (the one file that describes the run rather than the results) also carries the study file's
//! absolute path, so a run can tell an earlier run of the same file (perhaps edited since, so its
//! hash differs) from a run of another file that happens to use the same `study:` name.

use std::fs::File;
use std::path::{Path, PathBuf};

use polars::prelude::{ParquetReader, SerReader};

use super::TIMINGS_TABLE;

/// Metadata key of the study name (every table).
pub const STUDY_KEY: &str = "asperity.study";
/// Metadata key of the blake3 of the study file's bytes (every table).
pub const STUDY_FILE_HASH_KEY: &str = "asperity.study_file_blake3";
/// Metadata key of the study file's absolute path (`timings.parquet` only: a path is where the
/// run happened, not a result, and would make the result tables differ between folders).
pub const STUDY_FILE_KEY: &str = "asperity.study_file";

/// What a results folder's `timings.parquet` says about the study that wrote it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ResultsOrigin {
    pub study: Option<String>,
    pub study_file_hash: Option<String>,
    /// Absent in results written before the path was recorded.
    pub study_file: Option<PathBuf>,
}

/// The origin of the results folder `target`; `None` when it holds no readable
/// `timings.parquet` (absent, empty, or not written by asperity).
pub fn results_origin(target: &Path) -> Option<ResultsOrigin> {
    let file = File::open(target.join(format!("{TIMINGS_TABLE}.parquet"))).ok()?;
    let metadata = ParquetReader::new(file).get_metadata().ok()?.clone();
    let mut origin = ResultsOrigin {
        study: None,
        study_file_hash: None,
        study_file: None,
    };
    for kv in metadata.key_value_metadata().iter().flatten() {
        let Some(value) = kv.value.clone() else {
            continue;
        };
        match kv.key.as_str() {
            STUDY_KEY => origin.study = Some(value),
            STUDY_FILE_HASH_KEY => origin.study_file_hash = Some(value),
            STUDY_FILE_KEY => origin.study_file = Some(PathBuf::from(value)),
            _ => {}
        }
    }
    Some(origin)
}
