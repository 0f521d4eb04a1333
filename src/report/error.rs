//! Why a report could not be written.

use std::path::PathBuf;

/// Report failures. Missing optional inputs (a node table, a cache entry, fields that were not
/// stored) are not errors: they are listed in the page as skipped.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    #[error("{path}: {message}")]
    Table { path: PathBuf, message: String },
    #[error("{path} has no column '{column}'")]
    MissingColumn { path: PathBuf, column: String },
    #[error(
        "'{0}' is not a results folder: it has no scenarios.parquet (run `asperity run` first)"
    )]
    NotAResultsDir(PathBuf),
    #[error("unknown --replicate parameter '{name}'; the parameters are: {known}")]
    UnknownReplicate { name: String, known: String },
    #[error("unknown --metric '{name}'; numeric columns of the node tables: {known}")]
    UnknownMetric { name: String, known: String },
    #[error("--scenario {index} is out of range: the study has {count} scenario(s)")]
    ScenarioOutOfRange { index: usize, count: usize },
    #[error("cannot encode an image: {0}")]
    Image(String),
}
