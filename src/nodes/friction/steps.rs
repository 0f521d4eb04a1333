//! Friction at every load step: the table `curve` (`friction_curve`), one row per load step of
//! every method (each load of a statistical node, each step of the contact a per-summit or
//! per-spot node reads), its columns `step`, every metric of the `friction` row at that step,
//! `step_status` and `step_message`. The `friction` row is the final step (its last row).
//!
//! Each step's values pass the same validity rules as the row ([`crate::nodes::validity`]): an
//! impossible value at any step fails the node naming the step; a flag marks that step's row
//! only (`step_status` `flagged`, its sentences in `step_message`), so the `friction` row keeps
//! the flags of the final step and of the inputs.

use std::borrow::Cow;

use crate::engine::artifact::{Column, ColumnData, Table};
use crate::engine::node::NodeError;
use crate::engine::value::{Field, Value};
use crate::units::Dimension;
use crate::vocabulary::curve_columns::{STEP, STEP_MESSAGE, STEP_STATUS};

/// `ok` or `flagged`, the status of a step's row from its flags.
fn status(flags: &[String]) -> &'static str {
    if flags.is_empty() {
        "ok"
    } else {
        "flagged"
    }
}

/// The `curve` table of `steps`, each the metrics of the row at that step (the same names in
/// the same order at every step) with its flags. An error when a step lacks a metric another
/// has (a column must hold a value at every step).
pub(super) fn step_table(steps: &[(Vec<Field>, Vec<String>)]) -> Result<Table, NodeError> {
    let Some((first, _)) = steps.first() else {
        return Err(NodeError::new("no load step to tabulate"));
    };
    let mut t = Table::default();
    t.push_int(STEP, (0..steps.len() as i64).collect());
    for (c, field) in first.iter().enumerate() {
        let mut values = Vec::with_capacity(steps.len());
        for (i, (metrics, _)) in steps.iter().enumerate() {
            let value = metrics
                .get(c)
                .filter(|f| f.name == field.name)
                .map(|f| &f.value)
                .ok_or_else(|| {
                    NodeError::new(format!(
                        "load step {i} has no `{}` where load step 0 has one",
                        field.name
                    ))
                })?;
            values.push(value);
        }
        t.columns
            .push(column(field.name.clone(), field.dimension, &values)?);
    }
    if let Some((metrics, _)) = steps.iter().find(|(m, _)| m.len() != first.len()) {
        return Err(NodeError::new(format!(
            "a load step has {} metrics where load step 0 has {}",
            metrics.len(),
            first.len()
        )));
    }
    t.push_text(
        STEP_STATUS,
        steps.iter().map(|(_, f)| status(f).to_string()).collect(),
    );
    t.push_text(
        STEP_MESSAGE,
        steps.iter().map(|(_, f)| f.join("; ")).collect(),
    );
    Ok(t)
}

/// One column from the values of a metric at each step (all of the first one's type; a long
/// table holds no lists).
fn column(
    name: Cow<'static, str>,
    dimension: Dimension,
    values: &[&Value],
) -> Result<Column, NodeError> {
    let mixed = || NodeError::new(format!("metric `{name}` changes type between load steps"));
    let data = match values.first() {
        Some(Value::Float(_)) => ColumnData::Float(
            values
                .iter()
                .map(|v| match v {
                    Value::Float(x) => Ok(*x),
                    _ => Err(mixed()),
                })
                .collect::<Result<_, _>>()?,
        ),
        Some(Value::Int(_)) => ColumnData::Int(
            values
                .iter()
                .map(|v| match v {
                    Value::Int(x) => Ok(*x),
                    _ => Err(mixed()),
                })
                .collect::<Result<_, _>>()?,
        ),
        Some(Value::Bool(_)) => ColumnData::Bool(
            values
                .iter()
                .map(|v| match v {
                    Value::Bool(x) => Ok(*x),
                    _ => Err(mixed()),
                })
                .collect::<Result<_, _>>()?,
        ),
        Some(Value::Floats(_) | Value::Texts(_)) => {
            return Err(NodeError::new(format!(
                "metric `{name}` is a list, which a load step's row cannot hold"
            )))
        }
        Some(Value::Text(_)) | None => ColumnData::Text(
            values
                .iter()
                .map(|v| match v {
                    Value::Text(x) => Ok(x.clone()),
                    _ => Err(mixed()),
                })
                .collect::<Result<_, _>>()?,
        ),
    };
    Ok(Column {
        name,
        dimension,
        data,
    })
}

/// An error of load step `step` of `steps`, with the step named in its message.
pub(super) fn at_step(error: NodeError, step: usize, steps: usize) -> NodeError {
    if steps == 1 {
        return error;
    }
    NodeError::new(format!("load step {step} of {steps}: {}", error.message))
}
