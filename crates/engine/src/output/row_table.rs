//! A table assembled row by row and its conversion into typed Parquet columns.

use std::borrow::Cow;
use std::collections::HashMap;

use polars::prelude::{NamedFrom, PlSmallStr, Series};

use crate::units::Dimension;
use crate::value::{column_name, Field, Value};

/// One cell of a row: the column's name without unit, its dimension and the value.
pub(super) type Cell<'a> = (Cow<'a, str>, Dimension, Option<Value>);

/// One column: name with unit, dimension, cells.
pub(super) type RowColumn = (String, Dimension, Vec<Option<Value>>);

/// A table being assembled row by row; columns appear in first-seen order, missing cells are null.
#[derive(Default)]
pub(super) struct RowTable {
    pub columns: Vec<RowColumn>,
    pub rows: usize,
    /// The column of each cell name and dimension seen so far (the column's name is the cell's
    /// name with its unit, made once per column rather than per cell).
    index: HashMap<String, Vec<(Dimension, usize)>>,
    /// The cell name and dimension that made each column: rows (and the long tables of one kind)
    /// mostly repeat the previous row's cells in the same order, so the column after the last one
    /// filled is tried first.
    sources: Vec<(String, Dimension)>,
    next: usize,
}

impl RowTable {
    /// A table of whole columns.
    pub fn from_columns(columns: Vec<RowColumn>) -> Self {
        let rows = columns.first().map_or(0, |c| c.2.len());
        Self {
            columns,
            rows,
            ..Self::default()
        }
    }

    pub fn push_row<'a>(&mut self, cells: impl IntoIterator<Item = Cell<'a>>) {
        self.next = 0;
        for (name, dim, value) in cells {
            let col = self.column_after_last(&name, dim);
            self.columns[col].2.push(value);
        }
        self.rows += 1;
        for c in &mut self.columns {
            c.2.resize(self.rows, None);
        }
    }

    /// Appends `rows` rows given column by column, as [`RowTable::push_row`] would row by row: a
    /// column given twice keeps its first cells, cells beyond `rows` are dropped, missing ones
    /// are null.
    pub fn push_columns<'a>(
        &mut self,
        rows: usize,
        columns: impl IntoIterator<Item = (Cow<'a, str>, Dimension, Vec<Option<Value>>)>,
    ) {
        if rows == 0 {
            return;
        }
        let start = self.rows;
        self.next = 0;
        for (name, dim, mut cells) in columns {
            let col = self.column_after_last(&name, dim);
            let column = &mut self.columns[col].2;
            if column.len() == start {
                cells.resize(rows, None);
                column.extend(cells);
            }
        }
        self.rows += rows;
        for c in &mut self.columns {
            c.2.resize(self.rows, None);
        }
    }

    /// The column of cells called `name` with dimension `dim`, tried first against the column
    /// after the last one filled; that column is the last one filled then.
    fn column_after_last(&mut self, name: &str, dim: Dimension) -> usize {
        let col = match self.sources.get(self.next) {
            Some((n, d)) if n == name && *d == dim => self.next,
            _ => self.column(name, dim),
        };
        self.next = col + 1;
        col
    }

    /// The column of cells called `name` with dimension `dim`, added when new.
    fn column(&mut self, name: &str, dim: Dimension) -> usize {
        if let Some(&(_, col)) = self
            .index
            .get(name)
            .and_then(|seen| seen.iter().find(|(d, _)| *d == dim))
        {
            return col;
        }
        let full = column_name(name, dim);
        let col = match self.columns.iter().position(|c| c.0 == full) {
            Some(col) => col,
            None => {
                self.columns.push((full, dim, vec![None; self.rows]));
                self.sources.push((name.to_string(), dim));
                self.columns.len() - 1
            }
        };
        self.index
            .entry(name.to_string())
            .or_default()
            .push((dim, col));
        col
    }
}

/// A field as a cell.
pub(super) fn field_cell(f: &Field) -> Cell<'_> {
    (
        Cow::Borrowed(f.name.as_ref()),
        f.dimension,
        Some(f.value.clone()),
    )
}

/// A text cell.
pub(super) fn text<'a>(name: impl Into<Cow<'a, str>>, value: impl Into<String>) -> Cell<'a> {
    (
        name.into(),
        Dimension::Dimensionless,
        Some(Value::Text(value.into())),
    )
}

/// A cell of a list of texts.
pub(super) fn texts<'a>(name: impl Into<Cow<'a, str>>, values: Vec<String>) -> Cell<'a> {
    (
        name.into(),
        Dimension::Dimensionless,
        Some(Value::Texts(values)),
    )
}

/// The typed Parquet column of `values`: integers, floats (integers mixed in), booleans, lists
/// of floats (`List(Float64)`), lists of texts (`List(String)`; lists of floats mixed in, their
/// items as text), or text.
pub(super) fn to_series(name: &str, values: Vec<Option<Value>>) -> Series {
    let all = |f: fn(&Value) -> bool| values.iter().flatten().all(f);
    match values.iter().flatten().next() {
        Some(Value::Floats(_)) if all(|v| matches!(v, Value::Floats(_))) => {
            let v: Vec<Option<Series>> = values
                .iter()
                .map(|x| match x {
                    Some(Value::Floats(f)) => Some(Series::new(PlSmallStr::EMPTY, f.as_slice())),
                    _ => None,
                })
                .collect();
            Series::new(name.into(), v)
        }
        Some(Value::Floats(_) | Value::Texts(_))
            if all(|v| matches!(v, Value::Floats(_) | Value::Texts(_))) =>
        {
            let v: Vec<Option<Series>> = values
                .iter()
                .map(|x| {
                    let texts: Vec<String> = match x {
                        Some(Value::Texts(t)) => t.clone(),
                        Some(Value::Floats(f)) => f.iter().map(ToString::to_string).collect(),
                        _ => return None,
                    };
                    Some(Series::new(PlSmallStr::EMPTY, texts))
                })
                .collect();
            Series::new(name.into(), v)
        }
        Some(Value::Int(_)) if all(|v| matches!(v, Value::Int(_))) => {
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
            if all(|v| matches!(v, Value::Float(_) | Value::Int(_))) =>
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
        Some(Value::Bool(_)) if all(|v| matches!(v, Value::Bool(_))) => {
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
                .into_iter()
                .map(|x| {
                    x.map(|v| match v {
                        Value::Text(s) => s,
                        other => other.to_string(),
                    })
                })
                .collect();
            Series::new(name.into(), v)
        }
    }
}

#[cfg(test)]
mod tests {
    use polars::prelude::DataType;

    use super::*;

    /// A list column keeps an empty list apart from a null (a row the column does not apply to),
    /// and its items' type: floats as `List(Float64)`, texts as `List(String)`.
    #[test]
    fn lists_become_list_columns_with_empty_lists_and_nulls_apart() {
        let texts = to_series(
            "w",
            vec![
                Some(Value::Texts(Vec::new())),
                None,
                Some(Value::Texts(vec![String::from("a, b"), String::from("c")])),
            ],
        );
        assert_eq!(texts.dtype(), &DataType::List(Box::new(DataType::String)));
        let lists = texts.list().unwrap();
        assert_eq!(lists.get_as_series(0).unwrap().len(), 0);
        assert!(lists.get_as_series(1).is_none());
        assert_eq!(lists.get_as_series(2).unwrap().len(), 2);
        let floats = to_series("p", vec![None, Some(Value::Floats(vec![5e6, 1e7]))]);
        assert_eq!(floats.dtype(), &DataType::List(Box::new(DataType::Float64)));
        let list = floats.list().unwrap().get_as_series(1).unwrap();
        assert_eq!(list.f64().unwrap().get(1), Some(1e7));
    }
}
