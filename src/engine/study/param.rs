//! Node fields that are either a literal or a `${parameter}` reference, and their resolution
//! under one scenario.

use std::cell::RefCell;
use std::collections::HashMap;
use std::marker::PhantomData;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::{Deserialize, Deserializer};

use crate::engine::node::NodeTask;
use crate::engine::study::located::{Located, SourceLocation};
use crate::engine::study::raw::RawValue;
use crate::engine::value::ParamValue;
use crate::units::{Dimension, DimensionMarker, Quantity};

/// A field that is a literal value or a `${name}` reference to a study parameter. Conversion and
/// range checks happen when the node is instantiated, so every error names this field's location.
#[derive(Debug, Clone, PartialEq)]
pub struct Param<T> {
    raw: RawValue,
    location: SourceLocation,
    _type: PhantomData<T>,
}

impl<T> Param<T> {
    /// Where the field is written.
    pub fn location(&self) -> SourceLocation {
        self.location
    }

    /// The referenced parameter name, if the field is `${name}`.
    pub fn reference(&self) -> Option<&str> {
        self.raw.as_reference()
    }
}

impl<'de, T> Deserialize<'de> for Param<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let located = Located::<RawValue>::deserialize(deserializer)?;
        Ok(Self {
            raw: located.value,
            location: located.location,
            _type: PhantomData,
        })
    }
}

impl<T: schemars::JsonSchema> schemars::JsonSchema for Param<T> {
    fn inline_schema() -> bool {
        true
    }

    fn schema_name() -> std::borrow::Cow<'static, str> {
        format!("ParamOf{}", T::schema_name()).into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let literal = generator.subschema_for::<T>();
        schemars::json_schema!({
            "anyOf": [
                literal,
                {
                    "type": "string",
                    "pattern": r"^\$\{\s*[A-Za-z_][A-Za-z0-9_]*\s*\}$",
                    "description": "A reference to a study parameter, e.g. '${sq}'."
                }
            ]
        })
    }
}

/// Conversion of a parameter value into a typed field value.
pub trait FromParamValue: Sized {
    /// Converts, or says what was expected.
    fn from_param(value: &ParamValue) -> Result<Self, String>;
}

impl FromParamValue for f64 {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        match value {
            ParamValue::Int(i) => Ok(*i as f64),
            ParamValue::Number(x) => Ok(*x),
            other => Err(format!(
                "expected a plain number, got {other} ({})",
                other.type_name()
            )),
        }
    }
}

fn integer(value: &ParamValue) -> Result<i64, String> {
    match value {
        ParamValue::Int(i) => Ok(*i),
        ParamValue::Number(x) if x.fract() == 0.0 && x.abs() < 9.0e15 => Ok(*x as i64),
        other => Err(format!(
            "expected a whole number, got {other} ({})",
            other.type_name()
        )),
    }
}

impl FromParamValue for i64 {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        integer(value)
    }
}

impl FromParamValue for u64 {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        let i = integer(value)?;
        u64::try_from(i).map_err(|_| format!("expected a non-negative whole number, got {i}"))
    }
}

impl FromParamValue for usize {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        let i = integer(value)?;
        usize::try_from(i).map_err(|_| format!("expected a non-negative whole number, got {i}"))
    }
}

impl FromParamValue for bool {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        match value {
            ParamValue::Bool(b) => Ok(*b),
            other => Err(format!("expected true or false, got {other}")),
        }
    }
}

impl FromParamValue for String {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        match value {
            ParamValue::Text(s) => Ok(s.clone()),
            other => Err(format!(
                "expected text, got {other} ({})",
                other.type_name()
            )),
        }
    }
}

impl FromParamValue for PathBuf {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        String::from_param(value).map(PathBuf::from)
    }
}

impl<D: DimensionMarker> FromParamValue for Quantity<D> {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        match value.as_dimensioned() {
            Some(v) if v.dimension == D::DIMENSION || v.dimension == Dimension::Dimensionless => {
                Ok(Quantity::from_si(v.si))
            }
            _ => Err(format!(
                "expected a {} such as '{}' (units: {}), got {value}, which is a {}",
                D::DIMENSION.name(),
                D::DIMENSION.example(),
                D::DIMENSION.accepted_units(),
                value.type_name()
            )),
        }
    }
}

impl<T: FromParamValue, const N: usize> FromParamValue for [T; N] {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        match value {
            ParamValue::List(items) if items.len() == N => {
                let converted = items
                    .iter()
                    .map(T::from_param)
                    .collect::<Result<Vec<T>, String>>()?;
                converted
                    .try_into()
                    .map_err(|_| format!("expected a list of {N} values"))
            }
            other => Err(format!("expected a list of {N} values, got {other}")),
        }
    }
}

/// An error in one field of one node, found while instantiating it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{field}: {message}")]
pub struct SpecError {
    pub location: SourceLocation,
    pub field: String,
    pub message: String,
}

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
            location: param.location,
            field: field.to_string(),
            message,
        };
        let (value, origin) = match (&param.raw, param.raw.as_reference()) {
            (_, Some(name)) => {
                let index = self.parameter_index(name).map_err(&error)?;
                (
                    self.values[index].clone(),
                    format!(" (from parameter '{name}')"),
                )
            }
            (RawValue::Text(text), None) if text.contains("${") => {
                let (substituted, names) = self.interpolate(text).map_err(&error)?;
                let origin = format!(
                    " ('{text}' with parameter{} {})",
                    if names.len() == 1 { "" } else { "s" },
                    names.join(", ")
                );
                let value = RawValue::Text(substituted.clone())
                    .to_param_value()
                    .unwrap_or(ParamValue::Text(substituted));
                (value, origin)
            }
            (raw, None) => match (raw.to_param_value(), raw) {
                (Ok(value), _) => (value, String::new()),
                // Text that is not a valid quantity ("3 um.x3p") is still text to a text field.
                (Err(m), RawValue::Text(t)) => {
                    let text = ParamValue::Text(t.clone());
                    if T::from_param(&text).is_err() {
                        return Err(error(m));
                    }
                    (text, String::new())
                }
                (Err(m), _) => return Err(error(m)),
            },
        };
        let typed = match (T::from_param(&value), &value) {
            (Ok(typed), _) => typed,
            // Text that reads like a quantity ("01-upper.x3p") is still text to a text field.
            (Err(m), ParamValue::Quantity(_) | ParamValue::Number(_) | ParamValue::Int(_)) => {
                match &param.raw {
                    RawValue::Text(_) => T::from_param(&ParamValue::Text(
                        self.text_as_written(&param.raw).map_err(&error)?,
                    ))
                    .map_err(|_| error(format!("{m}{origin}")))?,
                    _ => return Err(error(format!("{m}{origin}"))),
                }
            }
            (Err(m), _) => return Err(error(format!("{m}{origin}"))),
        };
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

    /// A text field as written, after substitution.
    fn text_as_written(&self, raw: &RawValue) -> Result<String, String> {
        match raw {
            RawValue::Text(t) if t.contains("${") => self.interpolate(t).map(|(s, _)| s),
            RawValue::Text(t) => Ok(t.clone()),
            other => Err(format!("expected text, got {other:?}")),
        }
    }

    /// The `i`-th upstream task (in [`crate::engine::node::NodeSpec::upstream`] order).
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

fn is_parameter_name(name: &str) -> bool {
    let mut chars = name.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// " (did you mean 'x'?)" when a candidate is close to `name`, else "".
pub fn did_you_mean<'a>(name: &str, candidates: impl Iterator<Item = &'a str>) -> String {
    candidates
        .map(|c| (edit_distance(name, c), c))
        .filter(|(d, c)| *d <= 2.max(c.len() / 3))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| format!(" (did you mean '{c}'?)"))
        .unwrap_or_default()
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            let cost = usize::from(ca != *cb);
            cur[j + 1] = (prev[j] + cost).min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggests_close_names() {
        let c = ["hurst", "sq", "correlation_length"];
        assert_eq!(
            did_you_mean("hurts", c.into_iter()),
            " (did you mean 'hurst'?)"
        );
        assert_eq!(did_you_mean("zzzzzz", c.into_iter()), "");
        assert_eq!(
            did_you_mean("corelation_length", c.into_iter()),
            " (did you mean 'correlation_length'?)"
        );
    }
}
