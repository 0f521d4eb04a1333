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
//! the separate `timings.parquet` ([`write_timings`]), the one file that differs between runs.
//! Each file is written to a temporary name and renamed.

use std::collections::BTreeMap;
use std::fs::File;
use std::path::{Path, PathBuf};

use indexmap::IndexMap;
use polars::io::parquet::write::KeyValueMetadata;
use polars::prelude::{
    Column as PlColumn, DataFrame, NamedFrom, ParquetCompression, ParquetWriter, Series,
};

use crate::artifact::{ColumnData, Table};
use crate::execute::{NodeOutcome, NodeStatus, RunReport};
use crate::plan::Plan;
use crate::study::{Located, SCENARIOS_TABLE};
use crate::summary::{summary_columns, SummarySpec, RUN_TIME_METRIC};
use crate::units::Dimension;
use crate::value::{column_name, Field, ParamValue, Value};

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

/// Writes the requested tables into `dir`; returns the files written.
pub fn write_tables(
    dir: &Path,
    plan: &Plan,
    report: &RunReport,
    tables: &[String],
    meta: &OutputMetadata,
) -> Result<Vec<PathBuf>, OutputError> {
    std::fs::create_dir_all(dir).map_err(|e| OutputError::Write {
        path: dir.to_path_buf(),
        message: e.to_string(),
    })?;
    let mut written = Vec::new();
    for table in tables {
        if table == SCENARIOS_TABLE {
            let t = scenarios_table(plan, report);
            written.push(write_parquet(dir, SCENARIOS_TABLE, t, meta)?);
            continue;
        }
        let (main, long) = kind_tables(plan, report, table);
        written.push(write_parquet(dir, table, main, meta)?);
        for (name, t) in long {
            written.push(write_parquet(dir, &format!("{table}_{name}"), t, meta)?);
        }
    }
    Ok(written)
}

/// Writes one `summary_<name>` table per study summary into `dir`; returns the files written.
pub fn write_summaries(
    dir: &Path,
    plan: &Plan,
    report: &RunReport,
    summaries: &IndexMap<String, Located<SummarySpec>>,
    meta: &OutputMetadata,
) -> Result<Vec<PathBuf>, OutputError> {
    let mut written = Vec::new();
    for (name, spec) in summaries {
        let table = format!("summary_{name}");
        let columns =
            summary_columns(name, &spec.value, plan, report).map_err(|e| OutputError::Write {
                path: dir.join(format!("{table}.parquet")),
                message: e.to_string(),
            })?;
        let rows = columns.first().map_or(0, |c| c.2.len());
        written.push(write_parquet(
            dir,
            &table,
            RowTable { columns, rows },
            meta,
        )?);
    }
    Ok(written)
}

/// A table being assembled row by row; columns appear in first-seen order, missing cells are null.
#[derive(Default)]
struct RowTable {
    columns: Vec<(String, Dimension, Vec<Option<Value>>)>,
    rows: usize,
}

impl RowTable {
    fn push_row(&mut self, cells: Vec<(String, Dimension, Option<Value>)>) {
        for (name, dim, value) in cells {
            let col = match self.columns.iter().position(|c| c.0 == name) {
                Some(i) => i,
                None => {
                    self.columns.push((name, dim, vec![None; self.rows]));
                    self.columns.len() - 1
                }
            };
            self.columns[col].2.push(value);
        }
        self.rows += 1;
        for c in &mut self.columns {
            c.2.resize(self.rows, None);
        }
    }
}

fn field_cell(f: &Field) -> (String, Dimension, Option<Value>) {
    (f.column_name(), f.dimension, Some(f.value.clone()))
}

fn text(name: &str, value: impl Into<String>) -> (String, Dimension, Option<Value>) {
    (
        name.to_string(),
        Dimension::Dimensionless,
        Some(Value::Text(value.into())),
    )
}

fn scenarios_table(plan: &Plan, report: &RunReport) -> RowTable {
    let mut t = RowTable::default();
    for (s, row) in plan.scenarios.rows.iter().enumerate() {
        let mut cells = vec![(
            String::from("scenario"),
            Dimension::Dimensionless,
            Some(Value::Int(s as i64)),
        )];
        for (name, value) in plan.scenarios.names.iter().zip(row) {
            let dim = value.dimension();
            cells.push((
                column_name(name, dim),
                dim,
                Some(scenario_value(plan, name, value)),
            ));
        }
        let mut status = "ok";
        for (n, name) in plan.node_names.iter().enumerate() {
            let instance = plan.scenario_nodes[s][n];
            cells.push(text(
                &format!("{name}_key"),
                plan.nodes[instance].key.to_hex(),
            ));
            match report.outcomes.get(instance).and_then(Option::as_ref) {
                Some(o) if o.status.label() != "ok" => status = "failed",
                None if status == "ok" => status = "not_computed",
                _ => {}
            }
        }
        cells.push(text("status", status));
        t.push_row(cells);
    }
    t
}

/// Parameter values are written with one type per column: a column whose values mix integers and
/// floats is written as floats; anything else mixed as text.
fn scenario_value(plan: &Plan, name: &str, value: &ParamValue) -> Value {
    let col = plan.scenarios.names.iter().position(|n| n == name);
    let all_int = col.is_some_and(|c| {
        plan.scenarios
            .rows
            .iter()
            .all(|r| matches!(r[c], ParamValue::Int(_)))
    });
    let all_numeric = col.is_some_and(|c| {
        plan.scenarios
            .rows
            .iter()
            .all(|r| r[c].as_dimensioned().is_some() && r[c].dimension() == value.dimension())
    });
    match value {
        ParamValue::Int(i) if all_int => Value::Int(*i),
        v if all_numeric => Value::Float(v.as_dimensioned().map_or(f64::NAN, |d| d.si)),
        ParamValue::Text(s) => Value::Text(s.clone()),
        ParamValue::Bool(b) if col.is_some() => Value::Bool(*b),
        other => Value::Text(other.to_string()),
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
        let mut cells = vec![
            text("key", key.clone()),
            text("nodes", node.names.join(",")),
            (
                String::from("kind_version"),
                Dimension::Dimensionless,
                Some(Value::Int(i64::from(node.task.version()))),
            ),
        ];
        for (role, u) in &node.upstream {
            cells.push(text(&format!("{role}_key"), plan.nodes[*u].key.to_hex()));
        }
        cells.extend(node.task.params().iter().map(field_cell));
        cells.extend(outcome.metrics.iter().map(field_cell));
        cells.push(text("status", outcome.status.label()));
        cells.push(text("message", outcome.status.message()));
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

/// Writes `timings.parquet`: one row per instance the run needed, in the kind tables' row order,
/// with `key`, `kind`, `nodes`, `status`, `from_cache` and `compute_seconds` (the time of the
/// computation that produced the result, also when it was read from the cache). It describes the
/// run, not the results, and is the one output that is not byte-reproducible.
pub fn write_timings(
    dir: &Path,
    plan: &Plan,
    report: &RunReport,
    meta: &OutputMetadata,
) -> Result<PathBuf, OutputError> {
    let mut t = RowTable::default();
    for i in row_order(plan) {
        let Some(outcome) = report.outcomes.get(i).and_then(Option::as_ref) else {
            continue;
        };
        let node = &plan.nodes[i];
        t.push_row(vec![
            text("key", node.key.to_hex()),
            text("kind", node.task.kind()),
            text("nodes", node.names.join(",")),
            text("status", outcome.status.label()),
            (
                String::from("from_cache"),
                Dimension::Dimensionless,
                Some(Value::Bool(matches!(outcome.status, NodeStatus::Cached))),
            ),
            (
                String::from(RUN_TIME_METRIC),
                Dimension::Dimensionless,
                Some(Value::Float(outcome.compute_seconds)),
            ),
        ]);
    }
    write_parquet(dir, TIMINGS_TABLE, t, meta)
}

fn add_long_tables(long: &mut BTreeMap<String, RowTable>, key: &str, outcome: &NodeOutcome) {
    for (name, t) in &outcome.tables {
        let target = long.entry(name.clone()).or_default();
        append_long(target, key, t);
    }
}

fn append_long(target: &mut RowTable, key: &str, t: &Table) {
    for r in 0..t.rows() {
        let mut cells = vec![text("key", key)];
        for c in &t.columns {
            let v = match &c.data {
                ColumnData::Float(v) => v.get(r).map(|x| Value::Float(*x)),
                ColumnData::Int(v) => v.get(r).map(|x| Value::Int(*x)),
                ColumnData::Bool(v) => v.get(r).map(|x| Value::Bool(*x)),
                ColumnData::Text(v) => v.get(r).map(|x| Value::Text(x.clone())),
            };
            cells.push((c.column_name(), c.dimension, v));
        }
        target.push_row(cells);
    }
}

fn to_series(name: &str, values: &[Option<Value>]) -> Series {
    let first = values.iter().flatten().next();
    match first {
        Some(Value::Int(_)) if values.iter().flatten().all(|v| matches!(v, Value::Int(_))) => {
            let v: Vec<Option<i64>> = values
                .iter()
                .map(|x| match x {
                    Some(Value::Int(i)) => Some(*i),
                    _ => None,
                })
                .collect();
            Series::new(name.into(), v)
        }
        Some(Value::Float(_) | Value::Int(_))
            if values
                .iter()
                .flatten()
                .all(|v| matches!(v, Value::Float(_) | Value::Int(_))) =>
        {
            let v: Vec<Option<f64>> = values
                .iter()
                .map(|x| match x {
                    Some(Value::Float(f)) => Some(*f),
                    Some(Value::Int(i)) => Some(*i as f64),
                    _ => None,
                })
                .collect();
            Series::new(name.into(), v)
        }
        Some(Value::Bool(_)) if values.iter().flatten().all(|v| matches!(v, Value::Bool(_))) => {
            let v: Vec<Option<bool>> = values
                .iter()
                .map(|x| match x {
                    Some(Value::Bool(b)) => Some(*b),
                    _ => None,
                })
                .collect();
            Series::new(name.into(), v)
        }
        _ => {
            let v: Vec<Option<String>> = values
                .iter()
                .map(|x| x.as_ref().map(ToString::to_string))
                .collect();
            Series::new(name.into(), v)
        }
    }
}

fn write_parquet(
    dir: &Path,
    name: &str,
    table: RowTable,
    meta: &OutputMetadata,
) -> Result<PathBuf, OutputError> {
    let path = dir.join(format!("{name}.parquet"));
    let err = |message: String| OutputError::Write {
        path: path.clone(),
        message,
    };
    let units: BTreeMap<&str, &str> = table
        .columns
        .iter()
        .map(|(n, d, _)| (n.as_str(), d.si_symbol()))
        .collect();
    let columns: Vec<PlColumn> = table
        .columns
        .iter()
        .map(|(n, _, v)| PlColumn::from(to_series(n, v)))
        .collect();
    let mut df = DataFrame::new(table.rows, columns).map_err(|e| err(e.to_string()))?;
    let metadata = KeyValueMetadata::from_static(vec![
        (String::from("asperity.study"), meta.study.clone()),
        (
            String::from("asperity.study_file_blake3"),
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
        (
            String::from("asperity.units"),
            serde_json::to_string(&units).map_err(|e| err(e.to_string()))?,
        ),
    ]);
    let tmp = dir.join(format!(".{name}.parquet.tmp"));
    let file = File::create(&tmp).map_err(|e| err(e.to_string()))?;
    ParquetWriter::new(file)
        .with_compression(ParquetCompression::Uncompressed)
        .with_key_value_metadata(Some(metadata))
        .finish(&mut df)
        .map_err(|e| err(e.to_string()))?;
    std::fs::rename(&tmp, &path).map_err(|e| err(e.to_string()))?;
    Ok(path)
}
