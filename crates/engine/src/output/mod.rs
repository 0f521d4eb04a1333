//! Parquet output: `scenarios.parquet`, one table per node kind (`surfaces.parquet`, …) and the
//! kinds' long tables (`<table>_<name>.parquet`), each with units in column names (`sq_m`) and in
//! the file metadata, plus the study name, study-file hash and tool version.
//!
//! **Byte-reproducible.** The tables hold results only: cached values are written exactly as
//! computed and nothing of the run (times, dates, thread count, cache state) enters them, so the
//! same study, inputs and version give identical bytes, computed or cached. Rows are in a stable
//! order: `scenarios` by scenario; a kind table by the first scenario that uses an instance, then
//! by the study file's order of the node names (an instance shared by several scenarios or names
//! appears once, where it first appears); a long table follows its kind table. Run timings go to
//! the separate `timings.parquet` ([`ResultSet::write_timings`]), the one file that differs
//! between runs.
//!
//! **All or nothing.** The tables of a run are written into a [`ResultSet`], a private staging
//! folder, and published in one step (`result_set.rs`): a reader finds the complete set of one
//! run or the previous one, never a mix, and a failed write leaves the previous set untouched.

mod by_scenario;
mod origin;
mod result_set;
mod row_table;

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

use indexmap::IndexMap;
use polars::io::parquet::write::KeyValueMetadata;
use polars::prelude::{Column as PlColumn, DataFrame, ParquetCompression, ParquetWriter};
use rayon::prelude::*;

use crate::artifact::{ColumnData, Table};
use crate::columns::{
    key_column, FROM_CACHE, KEY, KIND, KIND_VERSION, MESSAGE, NODES, SCENARIO, STATUS,
};
use crate::execute::{NodeOutcome, NodeStatus, RunReport};
use crate::plan::Plan;
use crate::study::{Located, SCENARIOS_TABLE};
use crate::summary::{summary_columns, SummarySpec, RUN_TIME_METRIC};
use crate::units::Dimension;
use crate::value::{ParamValue, Value};

use row_table::{field_cell, text, texts, to_series, RowTable};

pub use by_scenario::{BY_SCENARIO_SUFFIX, PARAMETER_PREFIX};
pub use origin::{results_origin, ResultsOrigin, STUDY_FILE_HASH_KEY, STUDY_FILE_KEY, STUDY_KEY};
pub use result_set::{check_target, remove_stale_stagings, Generation, ResultSet};

/// Identification written into every file's metadata.
#[derive(Debug, Clone)]
pub struct OutputMetadata {
    pub study: String,
    pub study_file_hash: String,
    pub tool_version: String,
    /// Command-line parameter overrides (`--set name=value`) the run applied, in order.
    pub overrides: Vec<(String, String)>,
}

/// Output failures.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("cannot write {path}: {message}")]
    Write { path: PathBuf, message: String },
}

impl ResultSet {
    /// Writes the requested tables (in parallel, one file per task), in the order of `tables`,
    /// each kind table followed by its long tables and its tidy view
    /// (`<table>_by_scenario`, `by_scenario.rs`).
    pub fn write_tables(
        &mut self,
        plan: &Plan,
        report: &RunReport,
        tables: &[String],
        meta: &OutputMetadata,
    ) -> Result<(), OutputError> {
        let dirs = (self.staging(), self.target());
        let written: Vec<Vec<Result<String, OutputError>>> = tables
            .par_iter()
            .map(|table| {
                let files: Vec<(String, RowTable)> = if table == SCENARIOS_TABLE {
                    vec![(table.clone(), scenarios_table(plan, report))]
                } else {
                    let (main, long) = kind_tables(plan, report, table);
                    let tidy = by_scenario::by_scenario_table(plan, report, table);
                    std::iter::once((table.clone(), main))
                        .chain(long.into_iter().map(|(n, t)| (format!("{table}_{n}"), t)))
                        .chain([(format!("{table}_{BY_SCENARIO_SUFFIX}"), tidy)])
                        .collect()
                };
                files
                    .into_par_iter()
                    .map(|(name, t)| write_parquet(dirs, &name, t, meta, &[]))
                    .collect()
            })
            .collect();
        for file in written.into_iter().flatten() {
            self.record(file?);
        }
        Ok(())
    }

    /// Writes one `summary_<name>` table per study summary.
    pub fn write_summaries(
        &mut self,
        plan: &Plan,
        report: &RunReport,
        summaries: &IndexMap<String, Located<SummarySpec>>,
        meta: &OutputMetadata,
    ) -> Result<(), OutputError> {
        for (name, spec) in summaries {
            let table = format!("summary_{name}");
            let columns = summary_columns(name, &spec.value, plan, report).map_err(|e| {
                OutputError::Write {
                    path: self.target().join(format!("{table}.parquet")),
                    message: e.to_string(),
                }
            })?;
            let dirs = (self.staging(), self.target());
            let file = write_parquet(dirs, &table, RowTable::from_columns(columns), meta, &[])?;
            self.record(file);
        }
        Ok(())
    }

    /// Writes `timings.parquet`: one row per instance the run needed, in the kind tables' row
    /// order, with `key`, `kind`, `nodes`, `status`, `from_cache` and `compute_seconds` (the time
    /// of the computation that produced the result, also when it was read from the cache). It
    /// describes the run, not the results, and is the one output that is not byte-reproducible.
    pub fn write_timings(
        &mut self,
        plan: &Plan,
        report: &RunReport,
        meta: &OutputMetadata,
    ) -> Result<(), OutputError> {
        let dirs = (self.staging(), self.target());
        let study_file = self
            .study_file()
            .map(|p| (STUDY_FILE_KEY, p.to_string_lossy().into_owned()));
        let table = timings_table(plan, report);
        let file = write_parquet(dirs, TIMINGS_TABLE, table, meta, study_file.as_slice())?;
        self.record(file);
        Ok(())
    }
}

fn scenarios_table(plan: &Plan, report: &RunReport) -> RowTable {
    let types: Vec<ColumnType> = (0..plan.scenarios.names.len())
        .map(|c| ColumnType::of(plan, c))
        .collect();
    let key_columns: Vec<String> = plan
        .node_names
        .iter()
        .map(|name| key_column(name))
        .collect();
    let mut t = RowTable::default();
    for (s, row) in plan.scenarios.rows.iter().enumerate() {
        let mut cells = vec![(
            Cow::Borrowed(SCENARIO),
            Dimension::Dimensionless,
            Some(Value::Int(s as i64)),
        )];
        for ((name, value), ty) in plan.scenarios.names.iter().zip(row).zip(&types) {
            let (dimension, cell) = ty.cell(value);
            cells.push((Cow::Borrowed(name.as_str()), dimension, Some(cell)));
        }
        let mut labels = Vec::with_capacity(key_columns.len());
        for (&instance, key_column) in plan.scenario_nodes[s].iter().zip(&key_columns) {
            cells.push(text(key_column, plan.nodes[instance].key.to_hex()));
            let outcome = report.outcomes.get(instance).and_then(Option::as_ref);
            labels.push(outcome.map_or("not_computed", NodeOutcome::label));
        }
        cells.push(text(STATUS, scenario_status(&labels)));
        t.push_row(cells);
    }
    t
}

/// A scenario's status from its instances' labels: `failed` when one failed or was skipped, else
/// `flagged` when one is flagged, else `not_computed` when one was not needed, else `ok`.
fn scenario_status(labels: &[&str]) -> &'static str {
    let any = |label: &str| labels.contains(&label);
    if any("failed") || any("skipped") {
        "failed"
    } else if any("flagged") {
        "flagged"
    } else if any("not_computed") {
        "not_computed"
    } else {
        "ok"
    }
}

/// Parameter values are written with one type per column: a column whose values mix integers and
/// floats is written as floats; a list as a list column ([`ParamValue::list_cell`]: its numbers
/// in SI units with their unit in the column name, or its items as texts); anything else mixed
/// as text.
struct ColumnType {
    all_int: bool,
    /// Numbers or quantities of one dimension.
    all_numeric: bool,
}

impl ColumnType {
    /// The type of parameter column `c`.
    fn of(plan: &Plan, c: usize) -> Self {
        let rows = &plan.scenarios.rows;
        let dimension = rows.first().map(|r| r[c].dimension());
        Self {
            all_int: rows.iter().all(|r| matches!(r[c], ParamValue::Int(_))),
            all_numeric: rows
                .iter()
                .all(|r| r[c].as_dimensioned().is_some() && Some(r[c].dimension()) == dimension),
        }
    }

    /// The cell of `value` and the dimension of its column.
    fn cell(&self, value: &ParamValue) -> (Dimension, Value) {
        if let Some((list, dimension)) = value.list_cell() {
            return (dimension, list);
        }
        let cell = match value {
            ParamValue::Int(i) if self.all_int => Value::Int(*i),
            v if self.all_numeric => Value::Float(v.as_dimensioned().map_or(f64::NAN, |d| d.si)),
            ParamValue::Text(s) => Value::Text(s.clone()),
            ParamValue::Bool(b) => Value::Bool(*b),
            other => Value::Text(other.to_string()),
        };
        (value.dimension(), cell)
    }
}

fn kind_tables(
    plan: &Plan,
    report: &RunReport,
    table: &str,
) -> (RowTable, BTreeMap<String, RowTable>) {
    let mut main = RowTable::default();
    let mut long: BTreeMap<String, RowTable> = BTreeMap::new();
    for i in row_order(plan) {
        let node = &plan.nodes[i];
        if node.task.table() != table {
            continue;
        }
        let Some(outcome) = report.outcomes.get(i).and_then(Option::as_ref) else {
            continue;
        };
        let key = node.key.to_hex();
        let params = node.task.params();
        let mut cells =
            Vec::with_capacity(5 + node.upstream.len() + params.len() + outcome.metrics.len());
        cells.extend([
            text(KEY, key.clone()),
            texts(NODES, node.names.clone()),
            (
                Cow::Borrowed(KIND_VERSION),
                Dimension::Dimensionless,
                Some(Value::Int(i64::from(node.task.version()))),
            ),
        ]);
        for (role, u) in &node.upstream {
            cells.push(text(key_column(role), plan.nodes[*u].key.to_hex()));
        }
        cells.extend(params.iter().map(field_cell));
        cells.extend(outcome.metrics.iter().map(field_cell));
        cells.push(text(STATUS, outcome.label()));
        cells.push(text(MESSAGE, outcome.message()));
        main.push_row(cells);
        add_long_tables(&mut long, &key, outcome);
    }
    (main, long)
}

/// Instances in the documented row order: by the first scenario that uses them, then by the
/// study file's order of node names.
fn row_order(plan: &Plan) -> Vec<usize> {
    let mut seen = vec![false; plan.nodes.len()];
    let mut order = Vec::with_capacity(plan.nodes.len());
    for row in &plan.scenario_nodes {
        for &instance in row {
            if let Some(false) = seen.get(instance) {
                seen[instance] = true;
                order.push(instance);
            }
        }
    }
    order.extend((0..plan.nodes.len()).filter(|&i| !seen[i]));
    order
}

/// The name of the run-timing table.
pub const TIMINGS_TABLE: &str = "timings";

/// The rows of `timings.parquet` ([`ResultSet::write_timings`]).
fn timings_table(plan: &Plan, report: &RunReport) -> RowTable {
    let mut t = RowTable::default();
    for i in row_order(plan) {
        let Some(outcome) = report.outcomes.get(i).and_then(Option::as_ref) else {
            continue;
        };
        let node = &plan.nodes[i];
        t.push_row(vec![
            text(KEY, node.key.to_hex()),
            text(KIND, node.task.kind()),
            texts(NODES, node.names.clone()),
            text(STATUS, outcome.label()),
            (
                Cow::Borrowed(FROM_CACHE),
                Dimension::Dimensionless,
                Some(Value::Bool(matches!(outcome.status, NodeStatus::Cached))),
            ),
            (
                Cow::Borrowed(RUN_TIME_METRIC),
                Dimension::Dimensionless,
                Some(Value::Float(outcome.compute_seconds)),
            ),
        ]);
    }
    t
}

fn add_long_tables(long: &mut BTreeMap<String, RowTable>, key: &str, outcome: &NodeOutcome) {
    for (name, t) in &outcome.tables {
        let target = long.entry(name.clone()).or_default();
        append_long(target, key, t);
    }
}

fn append_long(target: &mut RowTable, key: &str, t: &Table) {
    let rows = t.rows();
    let key_cells = vec![Some(Value::Text(key.to_string())); rows];
    let columns = t.columns.iter().map(|c| {
        let cells: Vec<Option<Value>> = match &c.data {
            ColumnData::Float(v) => v.iter().map(|x| Some(Value::Float(*x))).collect(),
            ColumnData::Int(v) => v.iter().map(|x| Some(Value::Int(*x))).collect(),
            ColumnData::Bool(v) => v.iter().map(|x| Some(Value::Bool(*x))).collect(),
            ColumnData::Text(v) => v.iter().map(|x| Some(Value::Text(x.clone()))).collect(),
        };
        (Cow::Borrowed(c.name.as_ref()), c.dimension, cells)
    });
    let key_column = (Cow::Borrowed(KEY), Dimension::Dimensionless, key_cells);
    target.push_columns(rows, std::iter::once(key_column).chain(columns));
}

/// Writes `<name>.parquet` into the staging folder, fsynced, with `extra` metadata besides
/// `meta`; returns its file name. Errors name the file as it is published, in the target folder.
fn write_parquet(
    (staging, target): (&Path, &Path),
    name: &str,
    table: RowTable,
    meta: &OutputMetadata,
    extra: &[(&str, String)],
) -> Result<String, OutputError> {
    let file_name = format!("{name}.parquet");
    let path = staging.join(&file_name);
    let err = |message: String| OutputError::Write {
        path: target.join(&file_name),
        message,
    };
    let units: BTreeMap<&str, &str> = table
        .columns
        .iter()
        .map(|(n, d, _)| (n.as_str(), d.si_symbol()))
        .collect();
    let units = serde_json::to_string(&units).map_err(|e| err(e.to_string()))?;
    let rows = table.rows;
    let columns: Vec<PlColumn> = table
        .columns
        .into_iter()
        .map(|(n, _, v)| PlColumn::from(to_series(&n, v)))
        .collect();
    let mut df = DataFrame::new(rows, columns).map_err(|e| err(e.to_string()))?;
    let mut pairs = vec![
        (String::from(STUDY_KEY), meta.study.clone()),
        (
            String::from(STUDY_FILE_HASH_KEY),
            meta.study_file_hash.clone(),
        ),
        (
            String::from("asperity.tool_version"),
            meta.tool_version.clone(),
        ),
        (String::from("asperity.table"), name.to_string()),
        (
            String::from("asperity.overrides"),
            serde_json::to_string(&meta.overrides.iter().cloned().collect::<IndexMap<_, _>>())
                .map_err(|e| err(e.to_string()))?,
        ),
        (String::from("asperity.units"), units),
    ];
    pairs.extend(extra.iter().map(|(k, v)| (k.to_string(), v.clone())));
    let metadata = KeyValueMetadata::from_static(pairs);
    // Encoded in memory first, so that a failing write (a full disk) reports the operating
    // system's error rather than the encoder's loss of its stream.
    let mut bytes = Vec::new();
    ParquetWriter::new(&mut bytes)
        .with_compression(ParquetCompression::Uncompressed)
        .with_key_value_metadata(Some(metadata))
        .finish(&mut df)
        .map_err(|e| err(e.to_string()))?;
    let mut file = File::create(&path).map_err(|e| err(e.to_string()))?;
    file.write_all(&bytes).map_err(|e| err(e.to_string()))?;
    file.sync_all().map_err(|e| err(e.to_string()))?;
    Ok(file_name)
}
