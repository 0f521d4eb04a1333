//! What a node spec sees while it is instantiated for one scenario: the scenario's parameter
//! values, the upstream tasks, the study's folder and the tables it writes, and the resolution
//! of `Param` fields (whole `${name}` references, `${name}` inside strings, literals) into typed,
//! checked values.

use std::borrow::Cow;
use std::cell::RefCell;
use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};

use crate::syntax::{did_you_mean, is_parameter_name, FromParamValue, Param, ParamForm, SpecError};
use crate::task::NodeTask;
use crate::value::ParamValue;

/// Where a resolved value came from, as error messages say it.
enum Origin<'a> {
    Literal,
    Parameter(&'a str),
    /// The text as written and the parameters substituted into it.
    Interpolated(&'a str, Vec<String>),
}

impl fmt::Display for Origin<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::Literal => Ok(()),
            Origin::Parameter(name) => write!(f, " (from parameter '{name}')"),
            Origin::Interpolated(text, names) => write!(
                f,
                " ('{text}' with parameter{} {})",
                if names.len() == 1 { "" } else { "s" },
                names.join(", ")
            ),
        }
    }
}

/// What a node spec sees while it is instantiated for one scenario.
pub struct ResolveContext<'a> {
    pub(crate) names: &'a [String],
    pub(crate) values: &'a [ParamValue],
    pub(crate) upstream: &'a [Arc<dyn NodeTask>],
    pub(crate) study_dir: &'a Path,
    pub(crate) used: &'a RefCell<Vec<bool>>,
    pub(crate) file_hashes: &'a FileHashes,
    pub(crate) tables: &'a [String],
}

impl ResolveContext<'_> {
    /// Resolves a field to its value for this scenario.
    pub fn resolve<T: FromParamValue>(
        &self,
        param: &Param<T>,
        field: &str,
    ) -> Result<T, SpecError> {
        self.resolve_checked(param, field, |_| Ok(()))
    }

    /// Resolves a field and checks its range; `check` returns the expectation on failure
    /// (e.g. "must be > 0 m").
    pub fn resolve_checked<T: FromParamValue>(
        &self,
        param: &Param<T>,
        field: &str,
        check: impl Fn(&T) -> Result<(), String>,
    ) -> Result<T, SpecError> {
        let error = |message: String| SpecError {
            location: param.location(),
            field: field.to_string(),
            message,
        };
        // The parsed value, the names of the parameters it came from and the text as written
        // (after substitution).
        let (parsed, from, written) = match param.form() {
            ParamForm::Literal { value, text } => (
                value.as_ref().map(Cow::Borrowed).map_err(String::clone),
                Origin::Literal,
                text.as_deref().map(Cow::Borrowed),
            ),
            ParamForm::Reference(name) => {
                let index = self.parameter_index(name).map_err(&error)?;
                let value = Cow::Borrowed(&self.values[index]);
                (Ok(value), Origin::Parameter(name), None)
            }
            ParamForm::Interpolated(text) => {
                let (substituted, names) = self.interpolate(text).map_err(&error)?;
                let parsed = ParamValue::from_text(&substituted).map(Cow::Owned);
                let origin = Origin::Interpolated(text, names);
                (parsed, origin, Some(Cow::Owned(substituted)))
            }
        };
        // Text that reads like a quantity ("01-upper.x3p") or is not a valid one ("3 um.x3p")
        // is still text to a text field.
        let as_text = || {
            let text = ParamValue::Text(written?.into_owned());
            T::from_param(&text)
                .ok()
                .map(|typed| (typed, Cow::Owned(text)))
        };
        let (typed, value) = match parsed.map(|v| (T::from_param(&v), v)) {
            Ok((Ok(typed), v)) => (typed, v),
            Ok((Err(m), _)) | Err(m) => match as_text() {
                Some(text) => text,
                None => return Err(error(format!("{m}{from}"))),
            },
        };
        check(&typed).map_err(|m| error(format!("{value} {m}{from}")))?;
        Ok(typed)
    }

    /// The index of parameter `name` (marked as used), or an error with a suggestion.
    fn parameter_index(&self, name: &str) -> Result<usize, String> {
        let index = self.names.iter().position(|n| n == name).ok_or_else(|| {
            format!(
                "unknown parameter '${{{name}}}'{}; declared parameters: {}",
                did_you_mean(name, self.names.iter().map(String::as_str)),
                if self.names.is_empty() {
                    String::from("none")
                } else {
                    self.names.join(", ")
                }
            )
        })?;
        self.used.borrow_mut()[index] = true;
        Ok(index)
    }

    /// `text` with every `${name}` replaced by the scenario's value of `name` (text as is,
    /// numbers as written, quantities in SI); returns the names used.
    fn interpolate(&self, text: &str) -> Result<(String, Vec<String>), String> {
        let mut out = String::with_capacity(text.len());
        let mut names = Vec::new();
        let mut rest = text;
        while let Some(start) = rest.find("${") {
            out.push_str(&rest[..start]);
            let after = &rest[start + 2..];
            let end = after.find('}').ok_or_else(|| {
                format!("'{text}': '${{' without a closing '}}'; write ${{name}}")
            })?;
            let name = after[..end].trim();
            if !is_parameter_name(name) {
                return Err(format!(
                    "'{text}': '${{{name}}}' is not a parameter name (letters, digits, '_')"
                ));
            }
            let value = &self.values[self.parameter_index(name)?];
            match value {
                ParamValue::Text(s) => out.push_str(s),
                ParamValue::List(_) => {
                    return Err(format!(
                        "'{text}': parameter '{name}' is a list ({value}); only a single value \
                         can be written into text"
                    ))
                }
                other => out.push_str(&other.to_string()),
            }
            if !names.iter().any(|n| n == name) {
                names.push(name.to_string());
            }
            rest = &after[end + 1..];
        }
        out.push_str(rest);
        Ok((out, names))
    }

    /// The `i`-th upstream task (in the order of the spec's `upstream`).
    pub fn upstream(&self, i: usize) -> Option<&Arc<dyn NodeTask>> {
        self.upstream.get(i)
    }

    /// Whether the study writes `table` (its `outputs`, with the tables its summaries read), so a
    /// node can leave out what only that table would show. What a node computes must then be
    /// said by its parameters: whatever it leaves out is left out of its key too.
    pub fn writes_table(&self, table: &str) -> bool {
        self.tables.iter().any(|t| t == table)
    }

    /// The folder of the study file: relative paths in a study are relative to it.
    pub fn study_dir(&self) -> &Path {
        self.study_dir
    }

    /// blake3 hex digest of a file's content (memoised per plan, read once even when scenarios
    /// resolved in parallel ask for it together): content, not path or modification time,
    /// identifies input files.
    pub fn file_content_hash(&self, path: &Path) -> Result<String, String> {
        let slot = self
            .file_hashes
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .entry(path.to_path_buf())
            .or_default()
            .clone();
        slot.get_or_init(|| hash_file(path)).clone()
    }
}

/// The file hashes of a plan, by path.
pub(crate) type FileHashes = Mutex<HashMap<PathBuf, Arc<OnceLock<Result<String, String>>>>>;

fn hash_file(path: &Path) -> Result<String, String> {
    crate::regular_file::hash_regular(path)
        .map_err(|m| format!("cannot read {}: {m}", path.display()))
}
