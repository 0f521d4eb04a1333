//! The result tables as the report sees them: Parquet files read into plain columns (numbers as
//! `f64`, text as `String`, nulls as `None`) with the SI unit of each column from the
//! `asperity.units` metadata (docs/study-format.md, "Outputs and tables").

use std::collections::BTreeMap;
use std::fs::File;
use std::path::{Path, PathBuf};

use polars::prelude::{DataType, ParquetReader, SerReader};

use super::error::ReportError;
use crate::units::Dimension;

/// The values of one column.
#[derive(Debug, Clone, PartialEq)]
pub enum ColumnValues {
    /// Numeric (and boolean, as 0/1) columns.
    Number(Vec<Option<f64>>),
    /// Text columns (keys, statuses, names).
    Text(Vec<Option<String>>),
}

/// One result table.
#[derive(Debug, Clone, PartialEq)]
pub struct ResultTable {
    /// The table name (file stem: `scenarios`, `contacts`, `contacts_load_curve`, …).
    pub name: String,
    pub path: PathBuf,
    /// Columns in file order.
    pub columns: Vec<(String, ColumnValues)>,
    /// SI unit per column (`""` when dimensionless), from the `asperity.units` metadata.
    pub units: BTreeMap<String, String>,
    /// The `asperity.study` metadata value, when present.
    pub study: Option<String>,
    pub rows: usize,
}

impl ResultTable {
    /// Reads `<dir>/<name>.parquet`; `Ok(None)` when the file does not exist.
    pub fn read(dir: &Path, name: &str) -> Result<Option<Self>, ReportError> {
        let path = dir.join(format!("{name}.parquet"));
        if !path.exists() {
            return Ok(None);
        }
        let fail = |message: String| ReportError::Table {
            path: path.clone(),
            message,
        };
        let file = File::open(&path).map_err(|e| fail(e.to_string()))?;
        let mut reader = ParquetReader::new(file);
        let mut units = BTreeMap::new();
        let mut study = None;
        let metadata = reader.get_metadata().map_err(|e| fail(e.to_string()))?;
        for kv in metadata.key_value_metadata().iter().flatten() {
            match (kv.key.as_str(), kv.value.as_deref()) {
                ("asperity.units", Some(json)) => {
                    units = serde_json::from_str(json)
                        .map_err(|e| fail(format!("asperity.units metadata: {e}")))?;
                }
                ("asperity.study", Some(name)) => study = Some(name.to_string()),
                _ => {}
            }
        }
        let frame = reader.finish().map_err(|e| fail(e.to_string()))?;
        let mut columns = Vec::new();
        for column in frame.columns() {
            let series = column.as_materialized_series();
            let values = if series.dtype().is_string() {
                let text = series.str().map_err(|e| fail(e.to_string()))?;
                ColumnValues::Text(
                    (0..text.len())
                        .map(|i| text.get(i).map(str::to_string))
                        .collect(),
                )
            } else if series.dtype().is_primitive_numeric() || series.dtype().is_bool() {
                let cast = series
                    .cast(&DataType::Float64)
                    .map_err(|e| fail(e.to_string()))?;
                let numbers = cast.f64().map_err(|e| fail(e.to_string()))?;
                ColumnValues::Number((0..numbers.len()).map(|i| numbers.get(i)).collect())
            } else {
                continue;
            };
            columns.push((column.name().to_string(), values));
        }
        Ok(Some(Self {
            name: name.to_string(),
            path,
            columns,
            units,
            study,
            rows: frame.height(),
        }))
    }

    fn column(&self, name: &str) -> Option<&ColumnValues> {
        self.columns.iter().find(|c| c.0 == name).map(|c| &c.1)
    }

    /// A numeric column, or `None` when absent or not numeric.
    pub fn numbers(&self, name: &str) -> Option<&[Option<f64>]> {
        match self.column(name)? {
            ColumnValues::Number(v) => Some(v),
            ColumnValues::Text(_) => None,
        }
    }

    /// A text column, or `None` when absent or not text.
    pub fn texts(&self, name: &str) -> Option<&[Option<String>]> {
        match self.column(name)? {
            ColumnValues::Text(v) => Some(v),
            ColumnValues::Number(_) => None,
        }
    }

    /// A text column that must exist.
    pub fn require_texts(&self, name: &str) -> Result<&[Option<String>], ReportError> {
        self.texts(name).ok_or_else(|| ReportError::MissingColumn {
            path: self.path.clone(),
            column: name.to_string(),
        })
    }

    /// The SI unit of a column (`""` when dimensionless or unknown): from the `asperity.units`
    /// metadata, or — for a table rewritten without it — from a unit suffix of the name.
    pub fn unit<'a>(&'a self, column: &'a str) -> &'a str {
        if let Some(unit) = self.units.get(column) {
            return unit;
        }
        // Without the metadata: the unit whose column suffix ends the name.
        Dimension::ALL
            .into_iter()
            .find(|d| {
                let suffix = d.column_suffix();
                !suffix.is_empty()
                    && column
                        .strip_suffix(suffix)
                        .is_some_and(|rest| rest.len() > 1 && rest.ends_with('_'))
            })
            .map_or("", Dimension::si_symbol)
    }

    /// Names of the numeric columns.
    pub fn numeric_columns(&self) -> impl Iterator<Item = &str> {
        self.columns
            .iter()
            .filter(|c| matches!(c.1, ColumnValues::Number(_)))
            .map(|c| c.0.as_str())
    }

    /// Row index of each value of the `key` column.
    pub fn key_index(&self) -> Result<BTreeMap<String, usize>, ReportError> {
        Ok(self
            .require_texts("key")?
            .iter()
            .enumerate()
            .filter_map(|(i, k)| k.as_ref().map(|k| (k.clone(), i)))
            .collect())
    }
}
