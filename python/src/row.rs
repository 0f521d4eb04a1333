//! Table rows as Python dicts: a node's metrics ([`Field`]s) keyed by their column names, so a
//! Python result and the table row of the same computation share their keys.

use asperity::engine::value::{column_name, Field, Value};
use asperity::nodes::coefficient_fields;
use asperity::units::Dimension;
use asperity::vocabulary::{spot_columns, summit_columns};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Sets `field` in `d` under its column name (with its SI unit); a list as a Python list, as
/// polars reads the table's list column.
pub fn set_field(d: &Bound<'_, PyDict>, field: Field) -> PyResult<()> {
    let key = field.column_name();
    match field.value {
        Value::Float(v) => d.set_item(key, v),
        Value::Int(v) => d.set_item(key, v),
        Value::Bool(v) => d.set_item(key, v),
        Value::Text(v) => d.set_item(key, v),
        Value::Floats(v) => d.set_item(key, v),
        Value::Texts(v) => d.set_item(key, v),
    }
}

/// The key of a quantity `name` of `dimension`: its column name (`friction_force_N`).
pub fn key(name: &str, dimension: Dimension) -> String {
    column_name(name, dimension)
}

/// The key of a per-spot list: the spot table's column after `spot_` (`spot_area_m2`).
pub fn spot(column: &str, dimension: Dimension) -> String {
    format!(
        "{}{}",
        spot_columns::LIST_PREFIX,
        column_name(column, dimension)
    )
}

/// The key of a per-summit list: the summit table's column after `summit_` (`summit_radius_m`).
pub fn summit(column: &str, dimension: Dimension) -> String {
    format!(
        "{}{}",
        summit_columns::LIST_PREFIX,
        column_name(column, dimension)
    )
}

/// Sets every field of `fields` in `d`.
pub fn set_fields(d: &Bound<'_, PyDict>, fields: impl IntoIterator<Item = Field>) -> PyResult<()> {
    fields.into_iter().try_for_each(|f| set_field(d, f))
}

/// μ_s as the friction tables report it (`coefficient_fields`: `mu_s` never negative, the
/// model's value in `mu_s_computed`, `mu_s_floored` when it was negative); without a
/// compressive net force (`None`) both coefficients are None and nothing is floored.
pub fn set_coefficient(d: &Bound<'_, PyDict>, mu_s: Option<f64>) -> PyResult<()> {
    match mu_s {
        Some(mu) => set_fields(d, coefficient_fields(mu)),
        None => coefficient_fields(0.0).into_iter().try_for_each(|f| {
            let key = f.column_name();
            match f.value {
                Value::Bool(_) => d.set_item(key, false),
                _ => d.set_item(key, None::<f64>),
            }
        }),
    }
}
