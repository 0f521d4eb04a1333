//! Which numbers are plotted: a metric is one numeric column of a node table (`contacts`,
//! `friction`, `surfaces`) for one named node, looked up per scenario through the scenario's
//! `<node>_key` column.

use std::collections::BTreeMap;

use crate::vocabulary::{kinds, metrics, tables};

use super::error::ReportError;
use super::quantity::base_name;
use super::scenarios::{NodeLink, ScenarioSet};
use super::table::ResultTable;

/// The node tables the report reads, with their node kind (the cache folder of their entries).
pub const NODE_TABLES: [(&str, &str); 3] = [
    (tables::SURFACES, kinds::SURFACE),
    (tables::CONTACTS, kinds::CONTACT),
    (tables::FRICTION, kinds::FRICTION),
];

/// Columns plotted without being asked for: μ_s, A_t,rel and θ.
pub const DEFAULT_METRICS: [(&str, &str); 3] = [
    (tables::FRICTION, metrics::MU_S),
    (tables::CONTACTS, metrics::AREA_FRACTION),
    (tables::CONTACTS, metrics::STRESS_RATIO),
];

/// A node table with its key index.
#[derive(Debug, Clone)]
pub struct NodeTable {
    pub table: ResultTable,
    pub kind: String,
    pub index: BTreeMap<String, usize>,
}

/// One plotted quantity of one node, per scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct Metric {
    pub table: String,
    pub node: String,
    pub column: String,
    /// The column without its unit suffix (`area_fraction`).
    pub base: String,
    /// SI unit, `""` when dimensionless.
    pub unit: String,
    /// Distinguishing text values of the node's rows (`statistical, KE`), may be empty.
    pub detail: String,
    /// The value per scenario (`None`: failed, skipped or not computed).
    pub values: Vec<Option<f64>>,
}

impl Metric {
    /// The metric `column` of `link`'s instances in `table`.
    pub fn resolve(table: &NodeTable, link: &NodeLink, column: &str) -> Option<Self> {
        let data = table.table.numbers(column)?;
        let rows: Vec<Option<usize>> = link
            .keys
            .iter()
            .map(|k| k.as_ref().and_then(|k| table.index.get(k).copied()))
            .collect();
        let values = rows
            .iter()
            .map(|r| r.and_then(|r| data.get(r).copied().flatten()))
            .collect();
        let mut detail: Vec<String> = Vec::new();
        for name in ["method", "model"] {
            if let Some(texts) = table.table.texts(name) {
                for text in rows
                    .iter()
                    .flatten()
                    .filter_map(|&r| texts.get(r).cloned().flatten())
                {
                    if !detail.contains(&text) {
                        detail.push(text);
                    }
                }
            }
        }
        let unit = table.table.unit(column).to_string();
        Some(Self {
            table: table.table.name.clone(),
            node: link.node.clone(),
            column: column.to_string(),
            base: base_name(column, &unit).to_string(),
            unit,
            detail: detail.join(", "),
            values,
        })
    }
}

/// The default metrics plus the requested ones (`column`, `column` without unit suffix, or
/// `table.column`), for every node linked to the table. An unknown request is an error listing
/// the numeric columns.
pub fn select_metrics(
    tables: &[NodeTable],
    scenarios: &ScenarioSet,
    requested: &[String],
) -> Result<Vec<Metric>, ReportError> {
    let mut wanted: Vec<(String, String)> = DEFAULT_METRICS
        .iter()
        .map(|(t, c)| (t.to_string(), c.to_string()))
        .collect();
    for request in requested {
        let (table_filter, name) = match request.split_once('.') {
            Some((t, c)) if NODE_TABLES.iter().any(|n| n.0 == t) => (Some(t), c),
            _ => (None, request.as_str()),
        };
        let mut found = false;
        for t in tables {
            if table_filter.is_some_and(|f| f != t.table.name) {
                continue;
            }
            for column in t.table.numeric_columns() {
                if column == name || base_name(column, t.table.unit(column)) == name {
                    found = true;
                    let entry = (t.table.name.clone(), column.to_string());
                    if !wanted.contains(&entry) {
                        wanted.push(entry);
                    }
                }
            }
        }
        if !found {
            let known: Vec<String> = tables
                .iter()
                .flat_map(|t| {
                    t.table
                        .numeric_columns()
                        .map(|c| format!("{}.{c}", t.table.name))
                        .collect::<Vec<_>>()
                })
                .collect();
            return Err(ReportError::UnknownMetric {
                name: request.clone(),
                known: known.join(", "),
            });
        }
    }
    let mut metrics = Vec::new();
    for (table_name, column) in &wanted {
        let Some(table) = tables.iter().find(|t| &t.table.name == table_name) else {
            continue;
        };
        for link in scenarios.links_into(&table.index) {
            if let Some(m) = Metric::resolve(table, link, column) {
                metrics.push(m);
            }
        }
    }
    Ok(metrics)
}
