//! Reader errors: a [`ParseError`] says what is wrong with the bytes, a [`ReadError`] adds the file.

use std::path::PathBuf;

/// What is wrong with the content of a topography file.
#[derive(Debug, thiserror::Error)]
pub enum ParseError {
    /// The file ends before `what` could be read.
    #[error("file is truncated: {what}")]
    Truncated { what: String },
    /// The content contradicts the format (bad header value, wrong size, bad number, …).
    #[error("{what}")]
    Malformed { what: String },
    /// A valid file that uses a feature this reader does not implement.
    #[error("unsupported: {what}")]
    Unsupported { what: String },
    /// The channel asked for is not in the file.
    #[error(
        "the file has no channel `{wanted}`; it holds {}; set `channel:` to one of them \
         (or leave it out for the height channel)",
        quoted_list(available)
    )]
    UnknownChannel {
        wanted: String,
        available: Vec<String>,
    },
}

/// `` `a`, `b`, `c` `` (or "no channel").
fn quoted_list(names: &[String]) -> String {
    if names.is_empty() {
        return "no channel".to_string();
    }
    names
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

impl ParseError {
    pub(crate) fn truncated(what: impl Into<String>) -> Self {
        Self::Truncated { what: what.into() }
    }
    pub(crate) fn malformed(what: impl Into<String>) -> Self {
        Self::Malformed { what: what.into() }
    }
    pub(crate) fn unsupported(what: impl Into<String>) -> Self {
        Self::Unsupported { what: what.into() }
    }
}

/// A topography file could not be read. Each message holds its cause, which is therefore not
/// also exposed as [`std::error::Error::source`]: a printer of error chains (anyhow's `{:#}`)
/// would repeat it ("missing magic: missing magic").
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    #[error("cannot read {}: {cause}", path.display())]
    Io {
        path: PathBuf,
        cause: std::io::Error,
    },
    #[error(
        "cannot read {}: it is {kind}, not a regular file; give the path of a topography file",
        path.display()
    )]
    NotRegular { path: PathBuf, kind: &'static str },
    #[error(
        "cannot read {}: {size} bytes is more than a topography file may hold ({} bytes)",
        path.display(),
        super::MAX_FILE_BYTES
    )]
    TooLarge { path: PathBuf, size: u64 },
    #[error(
        "{}: unknown topography format (checked magic bytes and extension); supported: {}",
        path.display(),
        super::supported_formats()
    )]
    UnknownFormat { path: PathBuf },
    #[error("{} ({format}): {cause}", path.display())]
    Parse {
        path: PathBuf,
        format: &'static str,
        cause: ParseError,
    },
}
