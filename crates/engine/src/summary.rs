//! Grouped summaries of node metrics over scenarios: "per grade, mean ± standard deviation".
//!
//! A study's `summaries:` section names groups of scenarios (by the values of some parameters)
//! and node metrics; each summary becomes a table `summary_<name>` with one row per group, in the
//! order groups first appear in the scenarios, holding for every metric the number of scenarios
//! with a value, the mean and the sample standard deviation
//!
//! ```text
//! mean = Σ xᵢ / n,   std = √( Σ (xᵢ − mean)² / (n − 1) )   (null for n < 2)
//! ```
//!
//! Sums run in scenario order, so the numbers are deterministic. A scenario whose node instance
//! failed or has no value contributes nothing (its group's `n` is smaller than `scenarios`).

use crate::columns::{SCENARIOS, SUMMARY_STATISTICS};
use crate::execute::RunReport;
use crate::plan::Plan;
use crate::units::Dimension;
use crate::value::{column_name, ParamValue, Value};

pub use crate::study::{split_metric, SummarySpec, RUN_TIME_METRIC};

/// A summary that cannot be computed from the run (a metric no node instance produced).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("summary '{summary}': {message}")]
pub struct SummaryError {
    pub summary: String,
    pub message: String,
}

/// One column of a summary table: name (with unit), dimension, cells.
pub type SummaryColumn = (String, Dimension, Vec<Option<Value>>);

/// Scenarios grouped by the values of the `by` parameters: (values, member scenarios), in the
/// order groups first appear.
type Groups = Vec<(Vec<ParamValue>, Vec<usize>)>;

/// Computes the columns of summary `name` over the plan's scenarios.
pub fn summary_columns(
    name: &str,
    spec: &SummarySpec,
    plan: &Plan,
    report: &RunReport,
) -> Result<Vec<SummaryColumn>, SummaryError> {
    let err = |message: String| SummaryError {
        summary: name.to_string(),
        message,
    };
    let by: Vec<usize> = spec
        .by
        .iter()
        .map(|p| {
            plan.scenarios
                .names
                .iter()
                .position(|n| *n == p.value)
                .ok_or_else(|| err(format!("'{}' is not a parameter of the study", p.value)))
        })
        .collect::<Result<_, _>>()?;
    let groups = group_scenarios(plan, &by);
    let mut columns = group_columns(plan, &by, &groups);
    for metric in &spec.metrics {
        push_metric_statistics(&mut columns, &metric.value, plan, report, &groups).map_err(err)?;
    }
    Ok(columns)
}

/// The scenarios grouped by their values of the parameters at `by`.
fn group_scenarios(plan: &Plan, by: &[usize]) -> Groups {
    let mut groups: Groups = Vec::new();
    for (s, row) in plan.scenarios.rows.iter().enumerate() {
        let values: Vec<ParamValue> = by.iter().map(|&c| row[c].clone()).collect();
        match groups.iter_mut().find(|(v, _)| *v == values) {
            Some((_, members)) => members.push(s),
            None => groups.push((values, vec![s])),
        }
    }
    groups
}

/// The columns that name the groups: each `by` parameter and the number of scenarios.
fn group_columns(plan: &Plan, by: &[usize], groups: &Groups) -> Vec<SummaryColumn> {
    let mut columns: Vec<SummaryColumn> = Vec::new();
    for (k, &c) in by.iter().enumerate() {
        let param = &plan.scenarios.names[c];
        let dim = groups
            .first()
            .map_or(Dimension::Dimensionless, |g| param_cell(&g.0[k]).1);
        let cells = groups
            .iter()
            .map(|(values, _)| Some(param_cell(&values[k]).0))
            .collect();
        columns.push((column_name(param, dim), dim, cells));
    }
    columns.push((
        String::from(SCENARIOS),
        Dimension::Dimensionless,
        groups
            .iter()
            .map(|(_, m)| Some(Value::Int(m.len() as i64)))
            .collect(),
    ));
    columns
}

/// Count, mean and standard deviation of `node.metric` per group; an error names a metric the
/// node does not have (with the node's metrics).
fn push_metric_statistics(
    columns: &mut Vec<SummaryColumn>,
    metric: &str,
    plan: &Plan,
    report: &RunReport,
    groups: &Groups,
) -> Result<(), String> {
    let (node, field) =
        split_metric(metric).ok_or_else(|| format!("'{metric}' is not node.metric"))?;
    let n = plan
        .node_names
        .iter()
        .position(|x| x == node)
        .ok_or_else(|| format!("no node '{node}'"))?;
    let mut dimension = None;
    let mut available: Vec<String> = Vec::new();
    let samples: Vec<Vec<f64>> = groups
        .iter()
        .map(|(_, members)| {
            members
                .iter()
                .filter_map(|&s| {
                    let instance = plan.scenario_nodes[s][n];
                    let outcome = report.outcomes.get(instance)?.as_ref()?;
                    if available.is_empty() {
                        available = outcome.metrics.iter().map(|f| f.name.to_string()).collect();
                    }
                    let f = outcome.metrics.iter().find(|f| f.name == field)?;
                    dimension = Some(f.dimension);
                    match f.value {
                        Value::Float(x) if x.is_finite() => Some(x),
                        Value::Int(i) => Some(i as f64),
                        _ => None,
                    }
                })
                .collect()
        })
        .collect();
    match dimension {
        Some(dim) => push_statistics(columns, node, field, dim, &samples),
        // No instance of the node has a result (all failed): empty statistics.
        None if available.is_empty() => {
            push_statistics(columns, node, field, Dimension::Dimensionless, &samples)
        }
        None => {
            return Err(format!(
                "node '{node}' has no numeric metric '{field}'{}; metrics: {}",
                crate::study::did_you_mean(field, available.iter().map(String::as_str)),
                available.join(", ")
            ))
        }
    }
    Ok(())
}

fn push_statistics(
    columns: &mut Vec<SummaryColumn>,
    node: &str,
    field: &str,
    dim: Dimension,
    samples: &[Vec<f64>],
) {
    let count = samples
        .iter()
        .map(|x| Some(Value::Int(x.len() as i64)))
        .collect();
    let mean = samples.iter().map(|x| mean(x).map(Value::Float)).collect();
    let std = samples
        .iter()
        .map(|x| sample_std(x).map(Value::Float))
        .collect();
    let [n, mean_name, std_name] = SUMMARY_STATISTICS.map(|s| format!("{node}_{field}_{s}"));
    columns.push((n, Dimension::Dimensionless, count));
    columns.push((column_name(&mean_name, dim), dim, mean));
    columns.push((column_name(&std_name, dim), dim, std));
}

/// A group's parameter value as a cell (a list as a list: [`ParamValue::list_cell`]) and the
/// dimension of its column.
fn param_cell(value: &ParamValue) -> (Value, Dimension) {
    if let Some(list) = value.list_cell() {
        return list;
    }
    let cell = match value {
        ParamValue::Int(i) => Value::Int(*i),
        ParamValue::Bool(b) => Value::Bool(*b),
        ParamValue::Text(s) => Value::Text(s.clone()),
        other => other
            .as_dimensioned()
            .map_or_else(|| Value::Text(other.to_string()), |d| Value::Float(d.si)),
    };
    (cell, value.dimension())
}

fn mean(x: &[f64]) -> Option<f64> {
    (!x.is_empty()).then(|| x.iter().sum::<f64>() / x.len() as f64)
}

fn sample_std(x: &[f64]) -> Option<f64> {
    let m = mean(x)?;
    (x.len() >= 2)
        .then(|| (x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (x.len() - 1) as f64).sqrt())
}
