//! The tidy view of a kind table: `<table>_by_scenario`, one row per scenario, node of the kind
//! and load step, carrying the scenario's parameters, so "μ_s per scenario, model and load" is
//! a filter and a plot, not a join.
//!
//! A row holds, in this order: `scenario`; the scenario's parameters as `param_<name>` (with
//! unit: `param_sq_m`), named apart from the measured columns (`sq_m` of a surface is its
//! measured Sq, `param_sq_m` the value the study asked for); `node` (the study's node name);
//! `key`; `step` for a kind with load steps; the node's own parameters; its metrics; `status`
//! and `message`. A kind with load steps ([`crate::task::NodeTask::step_table`]) gives one row
//! per row of its step table, whose columns hold every metric at that step (the last step's
//! equal the kind table's row); an instance without that table gives one row. An instance
//! shared by several scenarios appears once per scenario. Rows go by scenario, then by the
//! study's order of node names, then by step.

use std::borrow::Cow;

use crate::artifact::{ColumnData, Table};
use crate::columns::{KEY, MESSAGE, NODE, SCENARIO, STATUS, STEP};
use crate::execute::RunReport;
use crate::plan::Plan;
use crate::units::Dimension;
use crate::value::Value;

use super::row_table::{field_cell, text, Cell, RowTable};
use super::ColumnType;

/// The suffix of a kind table's tidy view (`friction_by_scenario`).
pub const BY_SCENARIO_SUFFIX: &str = "by_scenario";

/// The prefix of the scenario parameters' columns in the tidy views.
pub const PARAMETER_PREFIX: &str = "param_";

/// The rows of `<table>_by_scenario`.
pub(super) fn by_scenario_table(plan: &Plan, report: &RunReport, table: &str) -> RowTable {
    let types: Vec<ColumnType> = (0..plan.scenarios.names.len())
        .map(|c| ColumnType::of(plan, c))
        .collect();
    let parameter_columns: Vec<String> = plan
        .scenarios
        .names
        .iter()
        .map(|name| format!("{PARAMETER_PREFIX}{name}"))
        .collect();
    let mut t = RowTable::default();
    for (s, row) in plan.scenarios.rows.iter().enumerate() {
        let mut scenario_cells: Vec<Cell> = vec![(
            Cow::Borrowed(SCENARIO),
            Dimension::Dimensionless,
            Some(Value::Int(s as i64)),
        )];
        for ((name, value), ty) in parameter_columns.iter().zip(row).zip(&types) {
            let (dimension, cell) = ty.cell(value);
            scenario_cells.push((Cow::Borrowed(name.as_str()), dimension, Some(cell)));
        }
        for (n, &instance) in plan.scenario_nodes[s].iter().enumerate() {
            let node = &plan.nodes[instance];
            if node.task.table() != table {
                continue;
            }
            let Some(outcome) = report.outcomes.get(instance).and_then(Option::as_ref) else {
                continue;
            };
            let mut head = scenario_cells.clone();
            head.push(text(NODE, plan.node_names[n].as_str()));
            head.push(text(KEY, node.key.to_hex()));
            let params = node.task.params();
            let tail = [
                text(STATUS, outcome.label()),
                text(MESSAGE, outcome.message()),
            ];
            let steps = node
                .task
                .step_table()
                .and_then(|name| outcome.tables.get(name));
            match steps {
                Some(steps) => {
                    for step in 0..steps.rows() {
                        let cells = head.iter().cloned().chain(step_cells(steps, step));
                        let cells = cells.chain(params.iter().map(field_cell));
                        t.push_row(cells.chain(step_metrics(steps, step)).chain(tail.clone()));
                    }
                }
                None => {
                    let cells = head.into_iter().chain(params.iter().map(field_cell));
                    let metrics = outcome.metrics.iter().map(field_cell);
                    t.push_row(cells.chain(metrics).chain(tail));
                }
            }
        }
    }
    t
}

/// The step table's `step` column (its index), first.
fn step_cells(steps: &Table, row: usize) -> impl Iterator<Item = Cell<'_>> {
    steps
        .columns
        .iter()
        .filter(|c| c.name == STEP)
        .map(move |c| (Cow::Borrowed(STEP), c.dimension, Some(cell(&c.data, row))))
}

/// The metrics of one step: every column of the step table but `step`.
fn step_metrics(steps: &Table, row: usize) -> impl Iterator<Item = Cell<'_>> {
    steps
        .columns
        .iter()
        .filter(|c| c.name != STEP)
        .map(move |c| {
            (
                Cow::Borrowed(c.name.as_ref()),
                c.dimension,
                Some(cell(&c.data, row)),
            )
        })
}

/// Value `row` of a long-table column.
fn cell(data: &ColumnData, row: usize) -> Value {
    match data {
        ColumnData::Float(v) => Value::Float(v[row]),
        ColumnData::Int(v) => Value::Int(v[row]),
        ColumnData::Bool(v) => Value::Bool(v[row]),
        ColumnData::Text(v) => Value::Text(v[row].clone()),
    }
}
