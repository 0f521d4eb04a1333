//! Node fields that are either a literal or a `${parameter}` reference, their typed conversion
//! and the errors of one field (resolution under a scenario: [`crate::resolve`]).

use std::marker::PhantomData;
use std::path::PathBuf;

use serde::{Deserialize, Deserializer};

use crate::syntax::located::{Located, SourceLocation};
use crate::syntax::raw::RawValue;
use crate::units::{plain_number_as, Dimension, DimensionMarker, Quantity};
use crate::value::ParamValue;

/// A field that is a literal value or a `${name}` reference to a study parameter. Conversion and
/// range checks happen when the node is instantiated, so every error names this field's location.
#[derive(Debug, Clone, PartialEq)]
pub struct Param<T> {
    form: ParamForm,
    location: SourceLocation,
    _type: PhantomData<T>,
}

/// How a field is written, told apart once when the study is read.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum ParamForm {
    /// A literal: its value, parsed once (units, numbers) rather than under every scenario, and
    /// its text when it is written as text.
    Literal {
        value: Result<ParamValue, String>,
        text: Option<String>,
    },
    /// `${name}`: the parameter name.
    Reference(String),
    /// Text with `${name}` inside.
    Interpolated(String),
}

impl<T> Param<T> {
    /// How the field is written.
    pub(crate) fn form(&self) -> &ParamForm {
        &self.form
    }

    /// Where the field is written.
    pub fn location(&self) -> SourceLocation {
        self.location
    }

    /// The referenced parameter name, if the field is `${name}`.
    pub fn reference(&self) -> Option<&str> {
        match &self.form {
            ParamForm::Reference(name) => Some(name),
            _ => None,
        }
    }
}

impl<'de, T> Deserialize<'de> for Param<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let located = Located::<RawValue>::deserialize(deserializer)?;
        let reference = located.value.as_reference().map(str::to_string);
        let form = match (reference, located.value) {
            (Some(name), _) => ParamForm::Reference(name),
            (None, RawValue::Text(text)) if text.contains("${") => ParamForm::Interpolated(text),
            (None, raw) => ParamForm::Literal {
                value: raw.to_param_value(),
                text: match raw {
                    RawValue::Text(text) => Some(text),
                    _ => None,
                },
            },
        };
        Ok(Self {
            form,
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
            Some(v) if v.dimension == D::DIMENSION => Ok(Quantity::from_si(v.si)),
            Some(v) if v.dimension == Dimension::Dimensionless => {
                plain_number_as(v.si, D::DIMENSION)
                    .map(Quantity::from_si)
                    .map_err(|e| e.to_string())
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

/// `true` for a valid parameter name: a letter or `_`, then letters, digits or `_`.
pub fn is_parameter_name(name: &str) -> bool {
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
