//! What a computed node produces and the cache stores: one row of metrics for the kind's table,
//! named arrays (stored as `.npy`) and named long tables (e.g. one row per load step).

use std::borrow::Cow;
use std::collections::BTreeMap;

use ndarray::ArrayD;
use serde::{Deserialize, Serialize};

use crate::units::Dimension;
use crate::value::{column_name, Field};

/// The result of computing one node instance.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Artifact {
    /// One row of the node kind's table (parameters are added by the engine).
    pub metrics: Vec<Field>,
    /// Arrays for downstream nodes or users, stored as `<name>.npy` in the cache.
    pub arrays: BTreeMap<String, ArrayD<f64>>,
    /// Long tables, written as `<kind table>_<name>.parquet` with a `key` column.
    pub tables: BTreeMap<String, Table>,
    /// Sentences saying why the values must be read with care (possible, but outside a model's
    /// assumptions). Non-empty: the row's `status` is `flagged` and its `message` holds them,
    /// joined by "; ". The engine only carries them; the node kinds decide what is flagged.
    pub flags: Vec<String>,
}

impl Artifact {
    /// The metric called `name`, if present.
    pub fn metric(&self, name: &str) -> Option<&Field> {
        self.metrics.iter().find(|f| f.name == name)
    }
}

/// A column-oriented table.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Table {
    pub columns: Vec<Column>,
}

impl Table {
    /// Number of rows (all columns have the same length).
    pub fn rows(&self) -> usize {
        self.columns.first().map_or(0, |c| c.data.len())
    }

    /// Appends a float column in SI units.
    pub fn push_float(
        &mut self,
        name: impl Into<Cow<'static, str>>,
        dimension: Dimension,
        data: Vec<f64>,
    ) {
        self.columns.push(Column {
            name: name.into(),
            dimension,
            data: ColumnData::Float(data),
        });
    }

    /// Appends an integer column.
    pub fn push_int(&mut self, name: impl Into<Cow<'static, str>>, data: Vec<i64>) {
        self.columns.push(Column {
            name: name.into(),
            dimension: Dimension::Dimensionless,
            data: ColumnData::Int(data),
        });
    }

    /// Appends a text column.
    pub fn push_text(&mut self, name: impl Into<Cow<'static, str>>, data: Vec<String>) {
        self.columns.push(Column {
            name: name.into(),
            dimension: Dimension::Dimensionless,
            data: ColumnData::Text(data),
        });
    }
}

/// One column of a [`Table`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Column {
    /// Name without unit; a node kind's names are static text, as for [`Field`].
    pub name: Cow<'static, str>,
    pub dimension: Dimension,
    pub data: ColumnData,
}

impl Column {
    /// Column name with the SI unit appended.
    pub fn column_name(&self) -> String {
        column_name(&self.name, self.dimension)
    }
}

/// Column values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", content = "values", rename_all = "lowercase")]
pub enum ColumnData {
    Float(Vec<f64>),
    Int(Vec<i64>),
    Bool(Vec<bool>),
    Text(Vec<String>),
}

impl ColumnData {
    /// Number of values.
    pub fn len(&self) -> usize {
        match self {
            ColumnData::Float(v) => v.len(),
            ColumnData::Int(v) => v.len(),
            ColumnData::Bool(v) => v.len(),
            ColumnData::Text(v) => v.len(),
        }
    }

    /// `true` when the column has no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
