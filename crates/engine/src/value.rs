//! Values that flow through the engine: study parameter values, resolved node parameters and
//! metrics. They carry their physical dimension so tables can name units in column names.

use std::borrow::Cow;
use std::fmt;

use serde::{Deserialize, Serialize};

use crate::units::{format_si, Dimension, DimensionedValue};

/// A parameter value as written in a study (after unit parsing).
#[derive(Debug, Clone, PartialEq)]
pub enum ParamValue {
    Int(i64),
    Number(f64),
    Quantity(DimensionedValue),
    Text(String),
    Bool(bool),
    List(Vec<ParamValue>),
}

impl ParamValue {
    /// Interprets a string: a quantity with units ("1.19 um"), a number, or plain text. Text that
    /// starts like a number but is not a valid quantity ("3 mpa", "1e400 m") is an error, not
    /// silently text.
    pub fn from_text(text: &str) -> Result<Self, String> {
        match crate::units::parse_quantity(text) {
            Ok(v) if v.dimension != Dimension::Dimensionless => Ok(ParamValue::Quantity(v)),
            Ok(v) => Ok(ParamValue::Number(v.si)),
            Err(crate::units::UnitError::NotAQuantity { .. }) => {
                Ok(ParamValue::Text(text.to_string()))
            }
            Err(e) => Err(e.to_string()),
        }
    }

    /// The numeric SI value and dimension, if this is a number or quantity.
    pub fn as_dimensioned(&self) -> Option<DimensionedValue> {
        match self {
            ParamValue::Int(i) => Some(DimensionedValue {
                si: *i as f64,
                dimension: Dimension::Dimensionless,
            }),
            ParamValue::Number(x) => Some(DimensionedValue {
                si: *x,
                dimension: Dimension::Dimensionless,
            }),
            ParamValue::Quantity(q) => Some(*q),
            _ => None,
        }
    }

    /// Short description of the value's type for messages.
    pub fn type_name(&self) -> &'static str {
        match self {
            ParamValue::Int(_) => "integer",
            ParamValue::Number(_) => "number",
            ParamValue::Quantity(q) => q.dimension.name(),
            ParamValue::Text(_) => "text value",
            ParamValue::Bool(_) => "boolean",
            ParamValue::List(_) => "list",
        }
    }

    /// A list as a table cell, with the column's dimension: a list of numbers or quantities of
    /// one dimension is [`Value::Floats`] in SI units (`[5 MPa, 10 MPa]`: `[5e6, 1e7]`, pressure),
    /// any other list [`Value::Texts`] of its items as written (text without quotes); `None` for
    /// a value that is no list.
    pub fn list_cell(&self) -> Option<(Value, Dimension)> {
        let ParamValue::List(items) = self else {
            return None;
        };
        let dimension = items
            .first()
            .map_or(Dimension::Dimensionless, Self::dimension);
        let floats: Option<Vec<f64>> = items
            .iter()
            .map(|item| {
                item.as_dimensioned()
                    .filter(|d| d.dimension == dimension)
                    .map(|d| d.si)
            })
            .collect();
        Some(match floats {
            Some(values) => (Value::Floats(values), dimension),
            None => {
                let texts = items
                    .iter()
                    .map(|item| match item {
                        ParamValue::Text(s) => s.clone(),
                        other => other.to_string(),
                    })
                    .collect();
                (Value::Texts(texts), Dimension::Dimensionless)
            }
        })
    }

    /// The dimension of the value (dimensionless for non-quantities).
    pub fn dimension(&self) -> Dimension {
        match self {
            ParamValue::Quantity(q) => q.dimension,
            _ => Dimension::Dimensionless,
        }
    }
}

impl fmt::Display for ParamValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParamValue::Int(i) => write!(f, "{i}"),
            ParamValue::Number(x) => f.write_str(&crate::units::format_number(*x)),
            ParamValue::Quantity(q) => f.write_str(&format_si(q.si, q.dimension)),
            ParamValue::Text(s) => write!(f, "'{s}'"),
            ParamValue::Bool(b) => write!(f, "{b}"),
            ParamValue::List(items) => write_list(f, items),
        }
    }
}

/// A table cell / key value. Floats are SI.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", content = "value", rename_all = "lowercase")]
pub enum Value {
    /// JSON has no NaN or infinity: serde_json writes them as `null`, which reads back as NaN
    /// (a cache manifest with a NaN metric stays readable).
    Float(#[serde(deserialize_with = "float_or_null")] f64),
    Int(i64),
    Bool(bool),
    Text(String),
    /// A list of floats in SI units (a `List(Float64)` column: `nominal_pressures_Pa`).
    Floats(Vec<f64>),
    /// A list of texts (a `List(String)` column: `twin_warnings`); empty when there are none.
    Texts(Vec<String>),
}

fn float_or_null<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(deserializer)?.unwrap_or(f64::NAN))
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Float(x) => write!(f, "{x}"),
            Value::Int(i) => write!(f, "{i}"),
            Value::Bool(b) => write!(f, "{b}"),
            Value::Text(s) => f.write_str(s),
            Value::Floats(v) => write_list(f, v),
            Value::Texts(v) => write_list(f, v),
        }
    }
}

/// `[a, b, c]`, for messages.
fn write_list<T: fmt::Display>(f: &mut fmt::Formatter<'_>, items: &[T]) -> fmt::Result {
    f.write_str("[")?;
    for (i, item) in items.iter().enumerate() {
        if i > 0 {
            f.write_str(", ")?;
        }
        write!(f, "{item}")?;
    }
    f.write_str("]")
}

/// A named, dimensioned value: one resolved parameter or one metric of a node.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Field {
    /// Name without unit ("sq"); a node kind's names are static text, so making a field does
    /// not allocate one.
    pub name: Cow<'static, str>,
    pub value: Value,
    /// Physical dimension; the SI unit is appended to the column name.
    pub dimension: Dimension,
}

impl Field {
    /// A floating-point field in SI units.
    pub fn float(name: impl Into<Cow<'static, str>>, value: f64, dimension: Dimension) -> Self {
        Self {
            name: name.into(),
            value: Value::Float(value),
            dimension,
        }
    }

    /// A dimensionless integer field.
    pub fn int(name: impl Into<Cow<'static, str>>, value: i64) -> Self {
        Self {
            name: name.into(),
            value: Value::Int(value),
            dimension: Dimension::Dimensionless,
        }
    }

    /// A text field.
    pub fn text(name: impl Into<Cow<'static, str>>, value: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            value: Value::Text(value.into()),
            dimension: Dimension::Dimensionless,
        }
    }

    /// A list of floats in SI units, one dimension for all (`nominal_pressures` of dimension
    /// pressure: the column `nominal_pressures_Pa`, of type `List(Float64)`).
    pub fn floats(
        name: impl Into<Cow<'static, str>>,
        values: Vec<f64>,
        dimension: Dimension,
    ) -> Self {
        Self {
            name: name.into(),
            value: Value::Floats(values),
            dimension,
        }
    }

    /// A list of texts (a `List(String)` column; an empty list when there is nothing to say).
    pub fn texts(name: impl Into<Cow<'static, str>>, values: Vec<String>) -> Self {
        Self {
            name: name.into(),
            value: Value::Texts(values),
            dimension: Dimension::Dimensionless,
        }
    }

    /// A boolean field.
    pub fn bool(name: impl Into<Cow<'static, str>>, value: bool) -> Self {
        Self {
            name: name.into(),
            value: Value::Bool(value),
            dimension: Dimension::Dimensionless,
        }
    }

    /// The table column name: the name plus `_<unit suffix>` (`sq_m`, `load_Pa`,
    /// `gamma_N_per_m`).
    pub fn column_name(&self) -> String {
        column_name(&self.name, self.dimension)
    }
}

/// Column name convention: `<name>_<unit suffix>` ([`Dimension::column_suffix`]), or `<name>`
/// when dimensionless.
pub fn column_name(name: &str, dimension: Dimension) -> String {
    match dimension.column_suffix() {
        "" => name.to_string(),
        unit => format!("{name}_{unit}"),
    }
}

#[cfg(test)]
mod list_tests {
    use super::{ParamValue, Value};
    use crate::units::{Dimension, DimensionedValue};

    /// A list of quantities of one dimension is a list of SI floats with that dimension; any
    /// other list is a list of its items as written; a scalar is no list.
    #[test]
    fn a_list_parameter_is_a_list_cell() {
        let mpa = |x: f64| {
            ParamValue::Quantity(DimensionedValue {
                si: x * 1e6,
                dimension: Dimension::Pressure,
            })
        };
        assert_eq!(
            ParamValue::List(vec![mpa(5.0), mpa(10.0)]).list_cell(),
            Some((Value::Floats(vec![5e6, 1e7]), Dimension::Pressure))
        );
        assert_eq!(
            ParamValue::List(vec![ParamValue::Int(2), ParamValue::Number(0.5)]).list_cell(),
            Some((Value::Floats(vec![2.0, 0.5]), Dimension::Dimensionless))
        );
        let mixed = ParamValue::List(vec![mpa(5.0), ParamValue::Text(String::from("a,b"))]);
        assert_eq!(
            mixed.list_cell(),
            Some((
                Value::Texts(vec![String::from("5e6 Pa"), String::from("a,b")]),
                Dimension::Dimensionless
            ))
        );
        assert_eq!(ParamValue::Int(3).list_cell(), None);
    }
}

#[cfg(test)]
mod nan_tests {
    use super::Value;

    /// A NaN metric is written as `null` and read back as NaN, so an entry holding one stays
    /// readable instead of being discarded as corrupt on every read.
    #[test]
    fn a_nan_float_survives_a_json_round_trip() {
        let json = serde_json::to_string(&Value::Float(f64::NAN)).unwrap();
        assert_eq!(json, r#"{"type":"float","value":null}"#);
        match serde_json::from_str::<Value>(&json).unwrap() {
            Value::Float(x) => assert!(x.is_nan()),
            other => panic!("{other:?}"),
        }
        let one: Value = serde_json::from_str(r#"{"type":"float","value":1.5}"#).unwrap();
        assert_eq!(one, Value::Float(1.5));
    }
}
