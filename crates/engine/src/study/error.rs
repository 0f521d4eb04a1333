//! Study errors: every one names the file, the line and column, what it concerns, and a fix.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::syntax::did_you_mean;
use crate::syntax::SourceLocation;

/// A problem in a study file.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyError {
    pub path: PathBuf,
    pub location: SourceLocation,
    /// What the error concerns: `nodes.lower.surface`, `parameters.sq`, `outputs`, ….
    pub context: String,
    pub message: String,
    /// The offending source line with a caret under the column.
    pub snippet: Option<String>,
}

impl std::error::Error for StudyError {}

impl fmt::Display for StudyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        if self.location.is_known() {
            write!(f, ":{}", self.location)?;
        }
        if self.context.is_empty() {
            write!(f, ": {}", self.message)?;
        } else {
            write!(f, ": {}: {}", self.context, self.message)?;
        }
        if let Some(snippet) = &self.snippet {
            write!(f, "\n{snippet}")?;
        }
        Ok(())
    }
}

impl StudyError {
    /// An error at `location` of the study whose text is `source`.
    pub fn at(
        path: &Path,
        source: &str,
        location: SourceLocation,
        context: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        Self {
            path: path.to_path_buf(),
            location,
            context: context.into(),
            message: message.into(),
            snippet: snippet(source, location),
        }
    }

    /// Converts a YAML/serde error, adding "did you mean" to unknown fields and variants.
    pub(crate) fn from_yaml(path: &Path, source: &str, error: &serde_saphyr::Error) -> Self {
        let location = error
            .location()
            .map(SourceLocation::from)
            .unwrap_or_default();
        let inner = error.without_snippet();
        let message = match super::yaml_budget::breach(error) {
            Some(breach) => super::yaml_budget::budget_message(breach),
            None => Self::yaml_message(inner),
        };
        Self::at(path, source, location, "", message)
    }

    /// The message of a YAML/serde error other than a breached parser limit.
    fn yaml_message(inner: &serde_saphyr::Error) -> String {
        match inner {
            serde_saphyr::Error::SerdeUnknownField {
                field, expected, ..
            } => format!(
                "unknown key '{field}'{}; expected one of: {}",
                did_you_mean(field, expected.iter().copied()),
                expected.join(", ")
            ),
            serde_saphyr::Error::SerdeUnknownVariant {
                variant, expected, ..
            } => format!(
                "unknown '{variant}'{}; expected one of: {}",
                did_you_mean(variant, expected.iter().copied()),
                expected.join(", ")
            ),
            serde_saphyr::Error::DuplicateMappingKey { key, .. } => format!(
                "duplicate key{}: each key may appear only once in a mapping",
                key.as_ref().map(|k| format!(" '{k}'")).unwrap_or_default()
            ),
            serde_saphyr::Error::MultipleDocuments { .. } => String::from(
                "a study file holds exactly one YAML document; remove the '---' separator and what follows",
            ),
            serde_saphyr::Error::SerdeMissingField { field, .. } => format!(
                "missing required key '{field}' in the mapping that ends here; see docs/study-format.md"
            ),
            other => strip_location_suffix(&other.to_string()),
        }
    }
}

/// Drops a trailing " at line L, column C" (we print the location ourselves); anything else is
/// kept as it is.
fn strip_location_suffix(message: &str) -> String {
    if let Some(i) = message.rfind(" at line ") {
        let tail = &message[i + " at line ".len()..];
        let is_location = tail
            .split(", column ")
            .all(|part| !part.is_empty() && part.chars().all(|c| c.is_ascii_digit()));
        if is_location && tail.contains(", column ") {
            return message[..i].to_string();
        }
    }
    message.to_string()
}

/// At most this many characters of a source line are shown around the column.
const SNIPPET_WIDTH: usize = 100;

/// The source line of `location` with a caret under its column.
fn snippet(source: &str, location: SourceLocation) -> Option<String> {
    if !location.is_known() {
        return None;
    }
    let line = source
        .lines()
        .nth(usize::try_from(location.line).ok()?.checked_sub(1)?)?;
    let number = location.line.to_string();
    let pad = " ".repeat(number.len());
    let column = usize::try_from(location.column)
        .unwrap_or(1)
        .saturating_sub(1);
    // Long lines are cut to a window around the column.
    let start = column.saturating_sub(SNIPPET_WIDTH / 2);
    let mut shown: String = line.chars().skip(start).take(SNIPPET_WIDTH).collect();
    let mut caret_at = column - start;
    if start > 0 {
        shown.insert(0, '…');
        caret_at += 1;
    }
    let caret: String = shown
        .chars()
        .take(caret_at)
        .map(|c| if c == '\t' { '\t' } else { ' ' })
        .collect();
    Some(format!("{pad} |\n{number} | {shown}\n{pad} | {caret}^"))
}
