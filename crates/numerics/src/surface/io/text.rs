//! Text and CSV topography reader: matrix grids, x y z triples and 1-D line scans.
//!
//! The file is split into header lines (any line with a non-numeric token) and data lines
//! (only numbers, separated by whitespace, `,` or `;`; empty fields are skipped). Header lines
//! must all come before the data; a text line inside the data block is an error (it usually
//! means corruption), and so is a line before it of 8 or more fields all numbers but one (a
//! damaged first data line). Every data line must have the same number of values.
//!
//! * **2 columns** → a line scan `x, z` (x strictly increasing, may be non-uniform), returned as
//!   [`LineScan`]. Units come from the column-header line just above the data (e.g. the Dektak
//!   CSV `Lateral um,Raw Micrometer`, or `µm µm`), else metres. A single whole number on the
//!   line above the data is a point count, kept as metadata and not checked (the files that
//!   write one miscount).
//! * **3 columns** without a matrix header → an x y z point list on a regular grid
//!   ([`super::xyz`]); scattered points are refused with how to resample them.
//! * anything else → a **matrix**, one row per line (row = y, x fastest). Header styles read:
//!   * `h=305 w=75`, `pixel size=3.69862e-007 m`, `data unit=rad`,
//!     `height conversion factor (-> m)=2.91818e-008` (heights = value × factor);
//!   * Gwyddion ASCII export: `# Width: 10.00 µm`, `# Height: 10.00 µm`, `# Value units: m`,
//!     `# Channel: ZSensor` (dx = Width / columns, dy = Height / rows).
//!
//! Without a spacing in the header the spacing is a placeholder of 1 m per pixel and
//! [`Topography::spacing`] is [`ScaleSource::Assumed`]; without a height unit heights are metres
//! and [`Topography::height_unit`] is [`ScaleSource::Assumed`]. The caller must then supply the
//! real values.
//! `nan` values are missing points.
//!
//! Data lines are kept in one flat vector (no per-line allocation), and more than
//! [`MAX_POINTS`] data lines or `3·MAX_POINTS` values are refused as they are read.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::limits::{check_points, MAX_POINTS};
use super::reader::{Parser, Reader};
use super::text_header::{column_units, TextHeader};
use super::xyz;
use super::{LineScan, ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

/// File extensions handled by this reader.
pub(crate) const EXTENSIONS: &[&str] = &["txt", "csv", "asc", "xyz", "tsv"];

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "text",
    description: "text/CSV: a matrix grid, x y z triples or a 2-column line scan",
    extensions: EXTENSIONS,
    magic: None,
    parser: Parser::Single(parse),
};

/// Parses a text topography file.
pub(crate) fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let text = match std::str::from_utf8(bytes) {
        Ok(s) => std::borrow::Cow::Borrowed(s),
        // Old exporters write `µ` as the Latin-1 byte 0xB5.
        Err(_) => std::borrow::Cow::Owned(bytes.iter().map(|&b| char::from(b)).collect()),
    };
    if text.contains('\0') {
        return Err(ParseError::malformed(
            "text: file contains NUL bytes (binary, not text)",
        ));
    }
    let TextLines {
        header_lines,
        rows,
        columns,
        count_line,
    } = read_lines(&text)?;
    if rows.is_empty() {
        return Err(ParseError::malformed("text: no numeric data lines"));
    }
    let header = TextHeader::parse(&header_lines)?;
    if columns == 2 && !header.describes_matrix() {
        let mut t = line_scan(&rows, header_lines.last().copied())?;
        if let Some(n) = count_line {
            t.metadata.insert("declared_points".into(), n.to_string());
        }
        return Ok(t);
    }
    if columns == 3 && !header.describes_matrix() {
        return xyz::grid(&rows);
    }
    matrix(rows, columns, &header)
}

/// A text file split into its header lines and its data block.
struct TextLines<'a> {
    /// The non-numeric lines above the data.
    header_lines: Vec<&'a str>,
    /// The data lines, flattened: `columns` values each.
    rows: Vec<f64>,
    columns: usize,
    /// A point count written on a line of its own above the data.
    count_line: Option<f64>,
}

/// Splits `text` into header lines and one rectangular block of numeric data lines; a damaged
/// or ragged data line, or more data than a topography holds, is an error naming its line.
fn read_lines(text: &str) -> Result<TextLines<'_>, ParseError> {
    let mut header_lines: Vec<&str> = Vec::new();
    // Data lines, flattened: `columns` values each.
    let mut rows: Vec<f64> = Vec::new();
    let mut columns = 0;
    let mut first_data_line = 0;
    let mut values = Vec::new();
    let mut count_line = None;
    for (index, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        match numeric_row(line, &mut values) {
            Some(()) => {
                if rows.is_empty() {
                    first_data_line = index + 1;
                    columns = values.len();
                } else if is_count_line(&rows, values.len()) {
                    // `23` above the data (a point count, often wrong): a header line.
                    count_line = Some(rows[0]);
                    rows.clear();
                    first_data_line = index + 1;
                    columns = values.len();
                } else if values.len() != columns {
                    return Err(ParseError::malformed(format!(
                        "text: line {} has {} values, the data lines before have {columns}",
                        index + 1,
                        values.len(),
                    )));
                }
                if rows.len() + columns > 3 * MAX_POINTS || rows.len() / columns >= MAX_POINTS {
                    return Err(ParseError::malformed(format!(
                        "text: more than {MAX_POINTS} data lines or {} values at line {}; a \
                         topography holds at most {MAX_POINTS} points",
                        3 * MAX_POINTS,
                        index + 1
                    )));
                }
                rows.extend_from_slice(&values);
            }
            None if rows.is_empty() && damaged_data_line(line) => {
                return Err(ParseError::malformed(format!(
                    "text: line {} ({:?}) holds numbers but one field that is not a number: a \
                     data line with a damaged value, not a header line",
                    index + 1,
                    truncate_for_message(line)
                )))
            }
            None if rows.is_empty() => header_lines.push(line),
            None => {
                return Err(ParseError::malformed(format!(
                    "text: line {} ({:?}) is not numeric, inside the data block that starts at line {first_data_line}",
                    index + 1,
                    truncate_for_message(line)
                )))
            }
        }
    }
    Ok(TextLines {
        header_lines,
        rows,
        columns,
        count_line,
    })
}

/// `true` when the data so far are one line holding one whole number and the next line has
/// more values: a point count written above the data (`xy-2.txt` style), not a data row.
fn is_count_line(rows: &[f64], next_columns: usize) -> bool {
    matches!(rows, [n] if n.fract() == 0.0 && *n >= 0.0) && next_columns > 1
}

/// The numbers of a data line into `out`, `None` when any non-empty field is not a number or
/// there is none.
fn numeric_row(line: &str, out: &mut Vec<f64>) -> Option<()> {
    out.clear();
    for token in line.split(|c: char| c.is_whitespace() || c == ',' || c == ';') {
        if token.is_empty() {
            continue;
        }
        let v: f64 = token.parse().ok()?;
        out.push(if v.is_finite() { v } else { f64::NAN });
    }
    (!out.is_empty()).then_some(())
}

/// `true` for a line of at least 8 fields, all numbers but one: a data line whose value was
/// damaged (a flipped byte), which would otherwise pass as a header line and drop a row.
fn damaged_data_line(line: &str) -> bool {
    let fields: Vec<&str> = line
        .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter(|f| !f.is_empty())
        .collect();
    fields.len() >= 8 && fields.iter().filter(|f| f.parse::<f64>().is_err()).count() == 1
}

fn truncate_for_message(line: &str) -> String {
    line.chars().take(60).collect()
}

/// A line scan from the flattened 2-column data `rows`.
fn line_scan(rows: &[f64], column_header: Option<&str>) -> Result<Topography, ParseError> {
    let (x_factor, z_factor, assumed) = match column_header.and_then(column_units) {
        Some((x, z)) => (x, z, false),
        None => (1.0, 1.0, true),
    };
    let mut x = Vec::with_capacity(rows.len() / 2);
    let mut z = Vec::with_capacity(rows.len() / 2);
    for (i, row) in rows.chunks_exact(2).enumerate() {
        let xi = row[0] * x_factor;
        if xi.is_nan() || x.last().is_some_and(|&prev| xi <= prev) {
            return Err(ParseError::malformed(format!(
                "text: line-scan position {} at data row {} is not increasing",
                row[0],
                i + 1
            )));
        }
        x.push(xi);
        z.push(row[1] * z_factor);
    }
    if x.len() < 2 {
        return Err(ParseError::malformed(
            "text: a line scan needs at least 2 points",
        ));
    }
    let metadata = BTreeMap::new();
    let source = if assumed {
        ScaleSource::Assumed
    } else {
        ScaleSource::File
    };
    Ok(Topography {
        spacing: source,
        height_unit: source,
        data: TopographyData::Line(LineScan { x, z }),
        channel: None,
        channels: Vec::new(),
        metadata,
    })
}

/// A matrix from the flattened data `rows` of `columns` values per line.
fn matrix(rows: Vec<f64>, columns: usize, header: &TextHeader) -> Result<Topography, ParseError> {
    let n_rows = rows.len() / columns;
    check_points(columns, n_rows, "text: the matrix")?;
    if let Some((h, w)) = header.rows_columns {
        if w != columns {
            return Err(ParseError::malformed(format!(
                "text: header says w={w} columns, data lines have {columns}"
            )));
        }
        if h != n_rows {
            return Err(ParseError::truncated(format!(
                "text: header says h={h} rows, file has {n_rows}"
            )));
        }
    }
    let metadata = header.metadata.clone();
    let ((dx, dy), spacing) = match header.spacing(columns, n_rows) {
        Some(s) => (s, ScaleSource::File),
        None => ((1.0, 1.0), ScaleSource::Assumed),
    };
    let (z_factor, height_unit) = match header.height_factor()? {
        Some(f) => (f, ScaleSource::File),
        None => (1.0, ScaleSource::Assumed),
    };
    let mut values = rows;
    values.iter_mut().for_each(|v| *v *= z_factor);
    let grid = Array2::from_shape_vec((n_rows, columns), values)
        .map_err(|e| ParseError::malformed(format!("text: grid shape: {e}")))?;
    let map =
        HeightMap::new(grid, dx, dy).map_err(|e| ParseError::malformed(format!("text: {e}")))?;
    Ok(Topography {
        spacing,
        height_unit,
        data: TopographyData::Areal(map),
        channel: header.channel.clone(),
        channels: Vec::new(),
        metadata,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn xyz_triples_with_a_missing_point() {
        let text = "0 0 1\n1e-6 0 2\n0 2e-6 3\n";
        let t = parse(text.as_bytes()).unwrap();
        let TopographyData::Areal(m) = t.data else {
            panic!("expected an areal map")
        };
        assert_eq!((m.nx(), m.ny(), m.dx(), m.dy()), (2, 2, 1e-6, 2e-6));
        assert_eq!(m.missing_count(), 1);
        assert_eq!(m.heights()[[1, 0]], 3.0);
    }

    #[test]
    fn text_inside_data_is_an_error() {
        let err = parse(b"1 2 3 4\n5 6 x 8\n").unwrap_err();
        assert!(err.to_string().contains("line 2"), "{err}");
        let err = parse(b"1 2 3 4\n5 6 7\n").unwrap_err();
        assert!(err.to_string().contains("3 values"), "{err}");
    }
}
