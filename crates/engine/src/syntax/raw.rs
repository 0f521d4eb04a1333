//! Untyped YAML values for parameter axes and `${param}`-able fields, converted to typed values
//! with messages that say what was expected.

use indexmap::IndexMap;
use serde::Deserialize;

use crate::value::ParamValue;

/// A YAML value as written (no target type yet).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum RawValue {
    Bool(bool),
    Int(i64),
    Float(f64),
    Text(String),
    List(Vec<RawValue>),
    Map(IndexMap<String, RawValue>),
}

impl RawValue {
    /// The `${name}` parameter reference this value is, if any: the whole text is one
    /// reference, so its inside holds no `}` (`"${a}${b}"` is two references in a text).
    pub fn as_reference(&self) -> Option<&str> {
        match self {
            RawValue::Text(s) => s
                .trim()
                .strip_prefix("${")
                .and_then(|rest| rest.strip_suffix('}'))
                .filter(|inside| !inside.contains('}'))
                .map(str::trim),
            _ => None,
        }
    }

    /// Converts to a parameter value (strings with units become quantities).
    pub fn to_param_value(&self) -> Result<ParamValue, String> {
        Ok(match self {
            RawValue::Bool(b) => ParamValue::Bool(*b),
            RawValue::Int(i) => ParamValue::Int(*i),
            RawValue::Float(x) if x.is_finite() => ParamValue::Number(*x),
            RawValue::Float(x) => return Err(format!("{x} is not a finite number")),
            RawValue::Text(s) => ParamValue::from_text(s)?,
            RawValue::List(items) => ParamValue::List(
                items
                    .iter()
                    .map(RawValue::to_param_value)
                    .collect::<Result<_, _>>()?,
            ),
            RawValue::Map(_) => {
                return Err(String::from(
                    "a mapping is not a parameter value; write a number, a quantity such as '1.19 um', text or a list",
                ))
            }
        })
    }
}
