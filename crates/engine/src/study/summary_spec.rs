//! The `summaries:` section as written: groups of scenarios and the node metrics to aggregate
//! (computed after a run by [`crate::summary`]).

use serde::Deserialize;

use super::names::{check_length, Columns};
use super::{valid_node_name, CheckError, StudyFile};
use crate::columns::{SCENARIOS, SUMMARY_STATISTICS};
use crate::node::NodeSpec;
use crate::syntax::{did_you_mean, Located};

/// `summaries: {name: {by: [...], metrics: [...]}}` in a study file.
#[derive(Debug, Clone, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SummarySpec {
    /// Parameters whose value combinations form the groups (one row each). Omitted or empty: one
    /// group of all scenarios.
    #[serde(default)]
    pub by: Vec<Located<String>>,
    /// Metrics to aggregate, as `node.metric` with the metric's name as in the node's table but
    /// without its unit suffix (`contact.area_fraction`, `contact.mean_contact_pressure`). Run
    /// times are not results: they are in `timings.parquet`, not in summaries.
    pub metrics: Vec<Located<String>>,
}

/// The run-time column of `timings.parquet`, refused as a summary metric (see [`SummarySpec`]).
pub const RUN_TIME_METRIC: &str = crate::columns::COMPUTE_SECONDS;

/// A metric reference `node.metric`, split.
pub fn split_metric(reference: &str) -> Option<(&str, &str)> {
    reference
        .split_once('.')
        .filter(|(node, metric)| !node.is_empty() && !metric.is_empty())
}

/// Checks the `summaries` section; returns the tables of the nodes it uses (they must be
/// computed, so they are written too).
pub(super) fn check_summaries<N: NodeSpec>(file: &StudyFile<N>) -> Result<Vec<String>, CheckError> {
    let p = &file.parameters;
    let parameters: Vec<&str> = p
        .product
        .keys()
        .chain(p.zip.iter().flat_map(|g| g.value.keys()))
        .chain(p.latin_hypercube.iter().flat_map(|l| l.value.ranges.keys()))
        .map(String::as_str)
        .collect();
    let mut tables = Vec::new();
    for (name, summary) in &file.summaries {
        let context = format!("summaries.{name}");
        if !valid_node_name(name) {
            return Err((
                summary.location,
                context,
                String::from("summary names start with a letter and contain only letters, digits, '_' and '-' (the table is summary_<name>)"),
            ));
        }
        check_length(name, "summary names").map_err(|m| (summary.location, context.clone(), m))?;
        check_groups(&summary.value, &context, &parameters)?;
        if summary.value.metrics.is_empty() {
            return Err((
                summary.location,
                format!("{context}.metrics"),
                String::from("lists no metric; write node.metric, e.g. contact.area_fraction"),
            ));
        }
        for metric in &summary.value.metrics {
            let table = metric_table(file, metric, &context)?;
            if !tables.contains(&table) {
                tables.push(table);
            }
        }
        check_columns(&summary.value, &context)?;
    }
    Ok(tables)
}

/// Every `by` entry of a summary names a parameter of the study.
fn check_groups(spec: &SummarySpec, context: &str, parameters: &[&str]) -> Result<(), CheckError> {
    let Some(by) = spec
        .by
        .iter()
        .find(|by| !parameters.contains(&by.value.as_str()))
    else {
        return Ok(());
    };
    Err((
        by.location,
        format!("{context}.by"),
        format!(
            "'{}' is not a parameter{}; parameters: {}",
            by.value,
            did_you_mean(&by.value, parameters.iter().copied()),
            if parameters.is_empty() {
                String::from("none")
            } else {
                parameters.join(", ")
            }
        ),
    ))
}

/// The table of the node a summary metric `node.metric` reads; an error for a reference that is
/// not `node.metric`, a run time or an unknown node.
fn metric_table<N: NodeSpec>(
    file: &StudyFile<N>,
    metric: &Located<String>,
    context: &str,
) -> Result<String, CheckError> {
    let fail = |message: String| Err((metric.location, format!("{context}.metrics"), message));
    let Some((node, field)) = split_metric(&metric.value) else {
        return fail(format!(
            "'{}' is not node.metric; write e.g. contact.area_fraction",
            metric.value
        ));
    };
    if field == RUN_TIME_METRIC {
        return fail(format!(
            "'{}': run times are not results (they differ between runs and would make this \
             table differ too); every run writes them per node instance to timings.parquet \
             (join on its `key` column)",
            metric.value
        ));
    }
    let Some(spec) = file.nodes.get(node) else {
        let nodes: Vec<&str> = file.nodes.keys().map(String::as_str).collect();
        return fail(format!(
            "no node '{node}'{}; nodes: {}",
            did_you_mean(node, nodes.iter().copied()),
            nodes.join(", ")
        ));
    };
    Ok(spec.value.table().to_string())
}

/// The columns of one summary table must be distinct: each `by` parameter and each metric once,
/// and no parameter or metric whose columns (`<parameter>`, `scenarios`,
/// `<node>_<metric>_n|mean|std`, with unit suffixes) clash with another's.
fn check_columns(spec: &SummarySpec, context: &str) -> Result<(), CheckError> {
    let mut columns = Columns::default();
    columns.fixed(SCENARIOS, "the number of scenarios in a group");
    for (i, by) in spec.by.iter().enumerate() {
        if spec.by[..i].iter().any(|b| b.value == by.value) {
            return Err((
                by.location,
                format!("{context}.by"),
                format!("'{}' is listed twice; list each parameter once", by.value),
            ));
        }
        columns
            .add(&by.value, format!("parameter '{}'", by.value))
            .map_err(|m| (by.location, format!("{context}.by"), clash(&m)))?;
    }
    for (i, metric) in spec.metrics.iter().enumerate() {
        if spec.metrics[..i].iter().any(|m| m.value == metric.value) {
            return Err((
                metric.location,
                format!("{context}.metrics"),
                format!("'{}' is listed twice; list each metric once", metric.value),
            ));
        }
        let stem = metric.value.replacen('.', "_", 1);
        for statistic in SUMMARY_STATISTICS {
            columns
                .add(
                    &format!("{stem}_{statistic}"),
                    format!("metric '{}'", metric.value),
                )
                .map_err(|m| (metric.location, format!("{context}.metrics"), clash(&m)))?;
        }
    }
    Ok(())
}

/// The message of a column clash in a summary table.
fn clash(clause: &str) -> String {
    format!("{clause} in the summary table; rename the parameter or leave one of them out")
}
