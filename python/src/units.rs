//! Quantities at the Python boundary, read by the study files' own parser
//! (`asperity::units`): a plain number is SI, a string carries its unit (`"0.5 um"`,
//! `"20 MPa"`, `"90 deg"`) and must have the dimension the argument expects.

use asperity::units::{parse_quantity_as, Dimension};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::guard::value_error;

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(parse_quantity, m)?)?;
    m.add_function(wrap_pyfunction!(is_column_name, m)?)?;
    m.add_function(wrap_pyfunction!(list_column, m)?)?;
    let dimensions = PyDict::new(m.py());
    for d in Dimension::ALL {
        dimensions.set_item(d.name(), (d.si_symbol(), d.example(), d.accepted_units()))?;
    }
    m.add("DIMENSIONS", dimensions)?;
    Ok(())
}

/// Whether `name` is a column of the one vocabulary with its unit suffix
/// (`asperity::nodes::is_known_column`): what every result's keys are checked against.
#[pyfunction]
fn is_column_name(name: &str) -> bool {
    asperity::nodes::is_known_column(name)
}

/// `"float"` or `"text"` when the vocabulary declares `name` a list column
/// (`asperity::nodes::list_column`: `nominal_pressures_Pa`, `twin_warnings`), else `None`: what
/// the tests check the tables' column types and the results' values against.
#[pyfunction]
fn list_column(name: &str) -> Option<&'static str> {
    asperity::nodes::list_column(name).map(|items| items.name())
}

/// The dimension called `name` (as `Dimension::name` writes it: "length", "pressure", …).
fn dimension(name: &str) -> PyResult<Dimension> {
    Dimension::from_name(name.as_bytes()).ok_or_else(|| {
        let known: Vec<_> = Dimension::ALL.iter().map(|d| d.name()).collect();
        value_error(
            "dimension",
            format!(
                "'{name}' is not a dimension; expected one of: {}",
                known.join(", ")
            ),
        )
    })
}

/// `text` ("<number> [unit]") in SI units of `dimension`; an error naming `parameter`.
#[pyfunction]
fn parse_quantity(parameter: &str, text: &str, dimension_name: &str) -> PyResult<f64> {
    parse_quantity_as(text, dimension(dimension_name)?).map_err(|e| value_error(parameter, e))
}
