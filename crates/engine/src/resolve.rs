//! What a node spec sees while it is instantiated for one scenario: the scenario's parameter
//! values, the upstream tasks and the study's folder, and the resolution of `Param` fields
//! (whole `${name}` references, `${name}` inside strings, literals) into typed, checked values.

use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::syntax::{did_you_mean, is_parameter_name, FromParamValue, Param, RawValue, SpecError};
use crate::task::NodeTask;
use crate::value::ParamValue;

/// What a node spec sees while it is instantiated for one scenario.
pub struct ResolveContext<'a> {
    pub(crate) names: &'a [String],
    pub(crate) values: &'a [ParamValue],
    pub(crate) upstream: &'a [Arc<dyn NodeTask>],
    pub(crate) study_dir: &'a Path,
    pub(crate) used: &'a RefCell<Vec<bool>>,
    pub(crate) file_hashes: &'a RefCell<HashMap<PathBuf, Result<String, String>>>,
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
        // The parsed value, where it came from, and the text as written (after substitution).
        let (parsed, origin, written) = match (param.raw(), param.raw().as_reference()) {
            (_, Some(name)) => {
                let index = self.parameter_index(name).map_err(&error)?;
                let origin = format!(" (from parameter '{name}')");
                (Ok(self.values[index].clone()), origin, None)
            }
            (RawValue::Text(text), None) if text.contains("${") => {
                let (substituted, names) = self.interpolate(text).map_err(&error)?;
                let origin = format!(
                    " ('{text}' with parameter{} {})",
                    if names.len() == 1 { "" } else { "s" },
                    names.join(", ")
                );
                let parsed = RawValue::Text(substituted.clone()).to_param_value();
                (parsed, origin, Some(substituted))
            }
            (RawValue::Text(text), None) => (
                param.raw().to_param_value(),
                String::new(),
                Some(text.clone()),
            ),
            (raw, None) => (raw.to_param_value(), String::new(), None),
        };
        // Text that reads like a quantity ("01-upper.x3p") or is not a valid one ("3 um.x3p")
        // is still text to a text field.
        let as_text = written
            .map(ParamValue::Text)
            .filter(|t| T::from_param(t).is_ok());
        let value = match (parsed, as_text) {
            (Ok(v), Some(text)) if T::from_param(&v).is_err() => text,
            (Ok(v), _) => v,
            (Err(_), Some(text)) => text,
            (Err(m), None) => return Err(error(format!("{m}{origin}"))),
        };
        let typed = T::from_param(&value).map_err(|m| error(format!("{m}{origin}")))?;
        check(&typed).map_err(|m| error(format!("{value} {m}{origin}")))?;
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

    /// The folder of the study file: relative paths in a study are relative to it.
    pub fn study_dir(&self) -> &Path {
        self.study_dir
    }

    /// blake3 hex digest of a file's content (memoised per plan): content, not path or
    /// modification time, identifies input files.
    pub fn file_content_hash(&self, path: &Path) -> Result<String, String> {
        if let Some(h) = self.file_hashes.borrow().get(path) {
            return h.clone();
        }
        // A device or a pipe would be read forever (`/dev/zero`) or block planning (a FIFO).
        let hash = match std::fs::metadata(path) {
            Ok(meta) if !meta.is_file() => Err(format!(
                "cannot read {}: not a regular file (a directory, device or pipe); give the path \
                 of a topography file",
                path.display()
            )),
            _ => std::fs::read(path)
                .map(|bytes| blake3::hash(&bytes).to_hex().to_string())
                .map_err(|e| format!("cannot read {}: {e}", path.display())),
        };
        self.file_hashes
            .borrow_mut()
            .insert(path.to_path_buf(), hash.clone());
        hash
    }
}
