//! Long tables of an entry too large for its summary: one Parquet file each, `<table>.parquet`,
//! zstd-compressed, its columns named with their units as in the result tables, so polars or
//! pandas read it as it is. The summary keeps the table's schema (column names, dimensions and
//! types, the row count) and the file's size and checksum; a read checks the file against both.
//!
//! Tables up to [`INLINE_MAX_BYTES`] stay inside the summary (one file per entry for a rerun: a
//! study of many small nodes reads no Parquet at all); larger ones, such as the summits of a
//! 3512² surface (megabytes), are files, compressed and readable outside asperity. The bytes
//! depend only on the table: same values, same file.

use std::io::Cursor;

use polars::prelude::{
    Column as PlColumn, DataFrame, DataType, NamedFrom, ParquetCompression, ParquetReader,
    ParquetWriter, SerReader, Series,
};

use crate::artifact::{Column, ColumnData, Table};

/// Largest table (its values' bytes, 8 per number) kept inside an entry's summary.
pub(super) const INLINE_MAX_BYTES: usize = 64 << 10;

/// Whether `table` is stored in a file of its own rather than inside the summary.
pub(super) fn is_large(table: &Table) -> bool {
    let bytes: usize = table
        .columns
        .iter()
        .map(|c| match &c.data {
            ColumnData::Float(v) => 8 * v.len(),
            ColumnData::Int(v) => 8 * v.len(),
            ColumnData::Bool(v) => v.len(),
            ColumnData::Text(v) => v.iter().map(|s| s.len() + 8).sum(),
        })
        .sum();
    bytes > INLINE_MAX_BYTES
}

/// The file of the table called `name`; an error for a name that is not a plain file stem
/// (ASCII letters, digits, `_` and `-`; the node kinds name their tables so).
pub(super) fn file_name(name: &str) -> Result<String, String> {
    let plain = !name.is_empty()
        && name
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-');
    if plain {
        Ok(format!("{name}.parquet"))
    } else {
        Err(format!(
            "table name '{name}' cannot be a file name (letters, digits, '_' and '-' only)"
        ))
    }
}

/// The Parquet bytes of `table`.
pub(super) fn encode(table: &Table) -> Result<Vec<u8>, String> {
    let columns: Vec<PlColumn> = table
        .columns
        .iter()
        .map(|c| {
            let name = c.column_name();
            PlColumn::from(match &c.data {
                ColumnData::Float(v) => Series::new(name.into(), v),
                ColumnData::Int(v) => Series::new(name.into(), v),
                ColumnData::Bool(v) => Series::new(name.into(), v),
                ColumnData::Text(v) => Series::new(name.into(), v),
            })
        })
        .collect();
    let mut frame = DataFrame::new(table.rows(), columns).map_err(|e| e.to_string())?;
    let mut bytes = Vec::new();
    ParquetWriter::new(&mut bytes)
        .with_compression(ParquetCompression::Zstd(None))
        .finish(&mut frame)
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}

/// The table in the Parquet `bytes`, whose columns must be those of `schema` (names, dimensions
/// and types; its data are empty) with `rows` rows each, without nulls (so no value is skipped
/// when the columns are read as options).
pub(super) fn decode(bytes: &[u8], schema: &Table, rows: usize) -> Result<Table, String> {
    let frame = ParquetReader::new(Cursor::new(bytes))
        .finish()
        .map_err(|e| e.to_string())?;
    if frame.width() != schema.columns.len() || frame.height() != rows {
        return Err(format!(
            "{} columns × {} rows where the summary says {} × {rows}",
            frame.width(),
            frame.height(),
            schema.columns.len()
        ));
    }
    let mut table = Table::default();
    for (read, expected) in frame.columns().iter().zip(&schema.columns) {
        let name = expected.column_name();
        let series = read.as_materialized_series();
        // Entries written before the unit suffixes became identifiers (`area_m^2`, now
        // `area_m2`) name the column with the SI symbol: the same column.
        let legacy = format!("{}_{}", expected.name, expected.dimension.si_symbol());
        let named = series.name().as_str() == name || series.name().as_str() == legacy;
        if !named || series.null_count() > 0 {
            return Err(format!(
                "column '{}' where the summary says '{name}' without nulls",
                series.name()
            ));
        }
        let data = column_data(series, &expected.data).map_err(|e| format!("{name}: {e}"))?;
        table.columns.push(Column {
            name: expected.name.clone(),
            dimension: expected.dimension,
            data,
        });
    }
    Ok(table)
}

/// The values of `series`, of the type of `kind`.
fn column_data(series: &Series, kind: &ColumnData) -> Result<ColumnData, String> {
    let err = |e: polars::error::PolarsError| e.to_string();
    Ok(match (kind, series.dtype()) {
        (ColumnData::Float(_), DataType::Float64) => {
            ColumnData::Float(series.f64().map_err(err)?.into_no_null_iter().collect())
        }
        (ColumnData::Int(_), DataType::Int64) => {
            ColumnData::Int(series.i64().map_err(err)?.into_no_null_iter().collect())
        }
        (ColumnData::Bool(_), DataType::Boolean) => {
            let values = series.bool().map_err(err)?;
            ColumnData::Bool((0..values.len()).filter_map(|i| values.get(i)).collect())
        }
        (ColumnData::Text(_), DataType::String) => {
            let values = series.str().map_err(err)?;
            ColumnData::Text(
                (0..values.len())
                    .filter_map(|i| values.get(i).map(str::to_string))
                    .collect(),
            )
        }
        (_, other) => return Err(format!("type {other} is not the summary's")),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::Dimension;

    fn sample(rows: usize) -> Table {
        let mut t = Table::default();
        let x: Vec<f64> = (0..rows).map(|i| (i as f64).sqrt() * 1e-6).collect();
        t.push_float("x", Dimension::Length, x);
        t.push_float(
            "odd",
            Dimension::Dimensionless,
            (0..rows)
                .map(|i| match i % 4 {
                    0 => f64::NAN,
                    1 => f64::NEG_INFINITY,
                    2 => -0.0,
                    _ => f64::MIN_POSITIVE / 3.0,
                })
                .collect(),
        );
        t.push_int("ix", (0..rows as i64).map(|i| i * 7 - 3).collect());
        t.columns.push(Column {
            name: "ok".into(),
            dimension: Dimension::Dimensionless,
            data: ColumnData::Bool((0..rows).map(|i| i % 3 == 0).collect()),
        });
        t.push_text("note", (0..rows).map(|i| format!("é{i}")).collect());
        t
    }

    fn schema_of(table: &Table) -> Table {
        let mut schema = table.clone();
        for c in &mut schema.columns {
            c.data = match c.data {
                ColumnData::Float(_) => ColumnData::Float(Vec::new()),
                ColumnData::Int(_) => ColumnData::Int(Vec::new()),
                ColumnData::Bool(_) => ColumnData::Bool(Vec::new()),
                ColumnData::Text(_) => ColumnData::Text(Vec::new()),
            };
        }
        schema
    }

    #[test]
    fn a_table_reads_back_bit_for_bit_and_its_bytes_repeat() {
        let table = sample(10_000);
        let bytes = encode(&table).unwrap();
        assert_eq!(bytes, encode(&table.clone()).unwrap());
        let read = decode(&bytes, &schema_of(&table), table.rows()).unwrap();
        assert_eq!(read.columns.len(), table.columns.len());
        for (a, b) in read.columns.iter().zip(&table.columns) {
            assert_eq!((&a.name, a.dimension), (&b.name, b.dimension));
            match (&a.data, &b.data) {
                (ColumnData::Float(x), ColumnData::Float(y)) => {
                    assert!(x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits()))
                }
                (x, y) => assert_eq!(x, y),
            }
        }
        assert!(is_large(&table) && !is_large(&sample(100)));
    }

    #[test]
    fn a_file_that_is_not_the_summarys_table_is_refused() {
        let table = sample(50);
        let bytes = encode(&table).unwrap();
        assert!(decode(&bytes, &schema_of(&table), 49).is_err());
        let mut renamed = schema_of(&table);
        renamed.columns[0].name = "y".into();
        assert!(decode(&bytes, &renamed, 50).is_err());
        let mut retyped = schema_of(&table);
        retyped.columns[2].data = ColumnData::Float(Vec::new());
        assert!(decode(&bytes, &retyped, 50).is_err());
        assert!(decode(&bytes[..bytes.len() - 9], &schema_of(&table), 50).is_err());
        assert!(file_name("summits").is_ok() && file_name("../x").is_err());
    }

    /// An entry written when the area suffix was `m^2` reads under the name `area_m2`.
    #[test]
    fn a_column_named_with_the_si_symbol_reads_as_its_identifier_name() {
        let mut old = Table::default();
        old.push_float("area_m^2", Dimension::Dimensionless, vec![1e-12, 2e-12]);
        let bytes = encode(&old).unwrap();
        let mut now = Table::default();
        now.push_float("area", Dimension::Area, Vec::new());
        let read = decode(&bytes, &now, 2).unwrap();
        assert_eq!(read.columns[0].column_name(), "area_m2");
        assert_eq!(read.columns[0].data, ColumnData::Float(vec![1e-12, 2e-12]));
    }
}
