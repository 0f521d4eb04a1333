//! The `summaries:` section as written: groups of scenarios and the node metrics to aggregate
//! (computed after a run by [`crate::summary`]).

use serde::Deserialize;

use crate::syntax::Located;

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
pub const RUN_TIME_METRIC: &str = "compute_seconds";

/// A metric reference `node.metric`, split.
pub fn split_metric(reference: &str) -> Option<(&str, &str)> {
    reference
        .split_once('.')
        .filter(|(node, metric)| !node.is_empty() && !metric.is_empty())
}
