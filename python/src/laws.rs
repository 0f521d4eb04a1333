//! The friction law registry (`friction::LAWS`) as Python sees it: each law's name, summary,
//! basis, methods and parameters with their defaults, ranges and units. The Python package's
//! docstrings name the laws from this list, and a law's parameters given from Python are read
//! here: a number is SI, a string is a choice or a quantity with its unit (`"90 deg"`).

use asperity::friction::laws::{
    LawDescriptor, NumberRange, ParameterKind, ParameterSpec, ParameterValue, Unit, LAWS,
};
use asperity::units::{parse_quantity_as, Dimension};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::guard::value_error;

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(friction_laws, m)?)?;
    Ok(())
}

/// A law parameter as Python gives it: a number (SI), or a string (a choice's option, or a
/// quantity with its unit).
#[derive(FromPyObject)]
pub enum Parameter {
    Number(f64),
    Text(String),
}

/// The dimension of a parameter's unit.
fn dimension_of(unit: Unit) -> Dimension {
    match unit {
        Unit::Dimensionless => Dimension::Dimensionless,
        Unit::Pressure => Dimension::Pressure,
        Unit::Angle => Dimension::Angle,
    }
}

/// A range with its unit, as messages and docs write it: `(0, 1)`, `> 0 Pa`,
/// `[-6.283185307179586, 6.283185307179586] rad`.
fn range_text(range: &NumberRange, unit: Unit) -> String {
    match dimension_of(unit).si_symbol() {
        "" => range.describe(),
        symbol => format!("{} {symbol}", range.describe()),
    }
}

/// `value` as the parameter `spec` of law `law`, checked against its kind and range; errors
/// name `parameters.<name>`, the value given and the expected unit or range.
pub fn parameter_value(
    law: &str,
    spec: &'static ParameterSpec,
    value: Parameter,
) -> PyResult<ParameterValue> {
    let field = format!("parameters.{}", spec.name);
    match (spec.kind, value) {
        (ParameterKind::Choice { options, .. }, Parameter::Text(text)) => {
            spec.choice(&text).map_err(|_| {
                value_error(
                    &field,
                    format!(
                        "'{text}' is not an option of '{law}'; expected one of: {}",
                        options.join(", ")
                    ),
                )
            })
        }
        (ParameterKind::Choice { options, .. }, Parameter::Number(v)) => Err(value_error(
            &field,
            format!(
                "{v} is a number; '{law}' expects one of: {}",
                options.join(", ")
            ),
        )),
        (ParameterKind::Number { range, unit, .. }, value) => {
            let dimension = dimension_of(unit);
            let (si, given) = match value {
                Parameter::Number(v) => (v, with_unit(v, dimension)),
                Parameter::Text(text) => {
                    let si =
                        parse_quantity_as(&text, dimension).map_err(|e| value_error(&field, e))?;
                    (si, format!("'{text}' ({})", with_unit(si, dimension)))
                }
            };
            spec.number(si).map_err(|_| {
                value_error(
                    &field,
                    format!(
                        "{given} is out of range: must be {}",
                        range_text(&range, unit)
                    ),
                )
            })
        }
    }
}

/// `v` with the SI symbol of `dimension` ("0.5", "2e+06 Pa", "7 rad").
fn with_unit(v: f64, dimension: Dimension) -> String {
    match dimension.si_symbol() {
        "" => format!("{v}"),
        symbol => format!("{v} {symbol}"),
    }
}

/// One parameter's declaration as a dict.
fn parameter_dict<'py>(py: Python<'py>, spec: &ParameterSpec) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", spec.name)?;
    d.set_item("column", spec.column)?;
    d.set_item("description", spec.description)?;
    match spec.kind {
        ParameterKind::Number {
            default,
            range,
            unit,
        } => {
            d.set_item("kind", "number")?;
            d.set_item("default", default)?;
            d.set_item("unit", dimension_of(unit).si_symbol())?;
            d.set_item("range", range_text(&range, unit))?;
            d.set_item("options", Vec::<&str>::new())?;
        }
        ParameterKind::Choice { options, default } => {
            d.set_item("kind", "choice")?;
            d.set_item("default", default)?;
            d.set_item("unit", "")?;
            d.set_item("range", format!("one of: {}", options.join(", ")))?;
            d.set_item("options", options.to_vec())?;
        }
    }
    Ok(d)
}

fn law_dict<'py>(py: Python<'py>, law: &LawDescriptor) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", law.name)?;
    d.set_item("summary", law.summary)?;
    d.set_item("basis", law.basis.name())?;
    d.set_item(
        "methods",
        law.methods.iter().map(|m| m.name()).collect::<Vec<_>>(),
    )?;
    let parameters = law
        .parameters
        .iter()
        .map(|p| parameter_dict(py, p))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("parameters", parameters)?;
    Ok(d)
}

/// Every law of the registry, in its order (the first is a study's default model).
#[pyfunction]
fn friction_laws(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyDict>>> {
    LAWS.iter().map(|law| law_dict(py, law)).collect()
}
