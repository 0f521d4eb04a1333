//! `summary.bin`: what a read of a cache entry returns (key, kind, upstream keys, compute time,
//! metrics, long tables, flags and the payload list) in one compact, self-verifying file, so that a rerun
//! reads one file per entry instead of the manifest and its checksum file.
//!
//! Layout: the magic `asperity-summary`, the format version (u32), the XXH3-128 checksum of the
//! body (16 bytes: a checksum against damage, fast on files of a few kilobytes; the manifest lists
//! the file with its blake3 as it does every payload), the body. In the body every count and
//! length is an unsigned LEB128 varint and values are written as node keys write them
//! ([`crate::encoding`]): a string is its length and its UTF-8 bytes, an integer 8 bytes, a float
//! its IEEE 754 bits (so values read back exactly as computed, NaN and infinities included), a
//! dimension its name, a list its count and its items. A long table is either inside the summary, column after column, or, when
//! large, a Parquet payload of its own (`table_file.rs`) of which the summary keeps the schema,
//! the row count and the file's size and checksum. The array payload list comes last: a read that
//! leaves the arrays unread does not decode it (the checksum still covers it).

use std::borrow::Cow;
use std::collections::BTreeMap;

use xxhash_rust::xxh3::xxh3_128;

use crate::artifact::{Artifact, Column, ColumnData, Table};
use crate::encoding::{self, Lengths};
use crate::hash::NodeKey;
use crate::units::Dimension;
use crate::value::{Field, Value};

use super::{names, EntryManifest, Payload};

/// The file name of an entry's summary.
pub(super) const SUMMARY_FILE: &str = "summary.bin";

const MAGIC: &[u8; 16] = b"asperity-summary";
/// Version 3 added the flags; version 4 keeps large tables in Parquet payloads (there is no
/// `tables.json` any more). A summary of another version is read through its manifest: for
/// entries written before version 4 (manifest format 1) the manifest holds the metrics and flags
/// and `tables.json` the tables.
pub(super) const VERSION: u32 = 4;
const CHECKSUM: usize = 16;
const HEADER: usize = MAGIC.len() + 4 + CHECKSUM;

/// Everything a summary holds.
pub(super) struct Summary<'a> {
    pub key: &'a NodeKey,
    pub kind: &'a str,
    pub upstream: &'a [(String, String)],
    /// The array payloads.
    pub payloads: &'a [Payload],
    pub compute_seconds: f64,
    pub metrics: &'a [Field],
    pub tables: &'a BTreeMap<String, Table>,
    /// The payload of each table stored as a file of its own, by table name; the others are
    /// written into the summary.
    pub table_files: &'a BTreeMap<String, Payload>,
    pub flags: &'a [String],
}

/// A table stored as a file of its own, as the summary describes it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct TableFile {
    pub name: String,
    pub payload: Payload,
    pub rows: usize,
    /// The columns' names, dimensions and types (their data are empty).
    pub schema: Table,
}

/// A decoded summary: the manifest part, an artifact with the metrics and the tables kept in the
/// summary, the tables kept in files (for the caller to read), and the array payload list when
/// it was asked for (empty otherwise).
pub(super) struct Decoded {
    pub manifest: EntryManifest,
    pub artifact: Artifact,
    pub table_files: Vec<TableFile>,
    pub payloads: Vec<Payload>,
}

/// Encodes a summary, checksum included.
pub(super) fn encode(summary: &Summary<'_>) -> Vec<u8> {
    let mut body = Vec::with_capacity(4096);
    body.extend_from_slice(&summary.key.0);
    put_str(&mut body, summary.kind);
    put_f64(&mut body, summary.compute_seconds);
    put_len(&mut body, summary.upstream.len());
    for (role, key) in summary.upstream {
        put_str(&mut body, role);
        put_str(&mut body, key);
    }
    put_len(&mut body, summary.metrics.len());
    for field in summary.metrics {
        put_str(&mut body, &field.name);
        put_str(&mut body, field.dimension.name());
        put_value(&mut body, &field.value);
    }
    put_len(&mut body, summary.tables.len());
    for (name, table) in summary.tables {
        put_str(&mut body, name);
        match summary.table_files.get(name) {
            Some(payload) => {
                body.push(b'p');
                put_payload(&mut body, payload);
                put_len(&mut body, table.rows());
                put_columns(&mut body, table, false);
            }
            None => {
                body.push(b'i');
                put_columns(&mut body, table, true);
            }
        }
    }
    put_len(&mut body, summary.flags.len());
    for flag in summary.flags {
        put_str(&mut body, flag);
    }
    put_len(&mut body, summary.payloads.len());
    for payload in summary.payloads {
        put_payload(&mut body, payload);
    }
    let mut out = Vec::with_capacity(HEADER + body.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&xxh3_128(&body).to_le_bytes());
    out.extend_from_slice(&body);
    out
}

/// Verifies and decodes the summary of entry `key` of kind `kind`, with its payload list when
/// `payloads`. `Ok(None)`: a summary of another format version (written by another version of
/// asperity), which the caller reads through the manifest instead. Errors say why the file is
/// corrupt.
pub(super) fn decode(
    bytes: &[u8],
    key: &NodeKey,
    kind: &str,
    payloads: bool,
) -> Result<Option<Decoded>, String> {
    if bytes.len() < HEADER || &bytes[..MAGIC.len()] != MAGIC {
        return Err(String::from("not a summary"));
    }
    let (version, rest) = bytes[MAGIC.len()..].split_at(4);
    if version != VERSION.to_le_bytes() {
        return Ok(None);
    }
    let (checksum, body) = rest.split_at(CHECKSUM);
    if xxh3_128(body).to_le_bytes() != checksum {
        return Err(String::from("checksum mismatch"));
    }
    let mut r = Reader(body);
    if r.take(32)? != key.0 || r.str()? != kind {
        return Err(String::from("names another key or kind"));
    }
    let compute_seconds = r.f64()?;
    let upstream = r.list(|r| Ok((r.string()?, r.string()?)))?;
    let metrics = r.list(Reader::field)?;
    let mut tables = BTreeMap::new();
    let mut table_files = Vec::new();
    for _ in 0..r.len()? {
        let name = r.string()?;
        match r.u8()? {
            b'i' => {
                tables.insert(name, r.table(true)?);
            }
            b'p' => table_files.push(TableFile {
                name,
                payload: r.payload()?,
                rows: r.varint()?,
                schema: r.table(false)?,
            }),
            other => return Err(format!("unknown table storage {other}")),
        }
    }
    let flags = r.list(Reader::string)?;
    let payloads = if payloads {
        let list = r.list(Reader::payload)?;
        if !r.0.is_empty() {
            return Err(String::from("trailing bytes"));
        }
        list
    } else {
        Vec::new()
    };
    Ok(Some(Decoded {
        manifest: EntryManifest {
            upstream,
            compute_seconds,
        },
        artifact: Artifact {
            metrics,
            tables,
            flags,
            ..Artifact::default()
        },
        table_files,
        payloads,
    }))
}

fn put_len(out: &mut Vec<u8>, n: usize) {
    encoding::put_len(out, n, Lengths::Varint);
}

fn put_str(out: &mut Vec<u8>, s: &str) {
    encoding::put_str(out, s, Lengths::Varint);
}

fn put_f64(out: &mut Vec<u8>, x: f64) {
    encoding::put_f64(out, x);
}

fn put_value(out: &mut Vec<u8>, value: &Value) {
    encoding::put_value(out, value, Lengths::Varint);
}

fn put_payload(out: &mut Vec<u8>, payload: &Payload) {
    put_str(out, &payload.file);
    out.extend_from_slice(&payload.bytes.to_le_bytes());
    put_str(out, &payload.blake3);
    match &payload.array {
        Some(array) => {
            out.push(1);
            put_str(out, array);
        }
        None => out.push(0),
    }
}

/// A table's columns: name, dimension, type and, `with_values`, the values (else only the
/// schema, the values being in a file of their own).
fn put_columns(out: &mut Vec<u8>, table: &Table, with_values: bool) {
    put_len(out, table.columns.len());
    for column in &table.columns {
        put_str(out, &column.name);
        put_str(out, column.dimension.name());
        let (tag, len) = match &column.data {
            ColumnData::Float(v) => (b'f', v.len()),
            ColumnData::Int(v) => (b'i', v.len()),
            ColumnData::Bool(v) => (b'b', v.len()),
            ColumnData::Text(v) => (b's', v.len()),
        };
        out.push(tag);
        if !with_values {
            continue;
        }
        put_len(out, len);
        match &column.data {
            ColumnData::Float(v) => v.iter().for_each(|x| put_f64(out, *x)),
            ColumnData::Int(v) => v
                .iter()
                .for_each(|i| out.extend_from_slice(&i.to_le_bytes())),
            ColumnData::Bool(v) => out.extend(v.iter().map(|b| u8::from(*b))),
            ColumnData::Text(v) => v.iter().for_each(|s| put_str(out, s)),
        }
    }
}

/// The unread rest of a summary body.
struct Reader<'a>(&'a [u8]);

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], String> {
        if n > self.0.len() {
            return Err(String::from("truncated"));
        }
        let (head, rest) = self.0.split_at(n);
        self.0 = rest;
        Ok(head)
    }

    fn u8(&mut self) -> Result<u8, String> {
        Ok(self.take(1)?[0])
    }

    fn u64(&mut self) -> Result<u64, String> {
        let mut b = [0u8; 8];
        b.copy_from_slice(self.take(8)?);
        Ok(u64::from_le_bytes(b))
    }

    fn f64(&mut self) -> Result<f64, String> {
        self.u64().map(f64::from_bits)
    }

    /// A count or length (a varint), at most the bytes left (every item takes at least one byte).
    fn len(&mut self) -> Result<usize, String> {
        Some(self.varint()?)
            .filter(|&n| n <= self.0.len())
            .ok_or_else(|| String::from("length beyond the end"))
    }

    /// A varint counting something outside the summary (a table file's rows).
    fn varint(&mut self) -> Result<usize, String> {
        let mut n = 0u64;
        for shift in (0..64).step_by(7) {
            let byte = self.u8()?;
            n |= u64::from(byte & 0x7f) << shift;
            if byte < 0x80 {
                return usize::try_from(n).map_err(|_| String::from("count too large"));
            }
        }
        Err(String::from("varint longer than 64 bits"))
    }

    fn str(&mut self) -> Result<&'a str, String> {
        let n = self.len()?;
        std::str::from_utf8(self.take(n)?).map_err(|_| String::from("text is not UTF-8"))
    }

    fn string(&mut self) -> Result<String, String> {
        self.str().map(str::to_string)
    }

    fn list<T>(&mut self, item: impl Fn(&mut Self) -> Result<T, String>) -> Result<Vec<T>, String> {
        let n = self.len()?;
        let mut items = Vec::with_capacity(n);
        for _ in 0..n {
            items.push(item(self)?);
        }
        Ok(items)
    }

    fn field(&mut self) -> Result<Field, String> {
        Ok(Field {
            name: self.name()?,
            dimension: self.dimension()?,
            value: self.value()?,
        })
    }

    /// A metric or column name, shared between reads ([`names`]).
    fn name(&mut self) -> Result<Cow<'static, str>, String> {
        let n = self.len()?;
        names::name(self.take(n)?).map_err(|_| String::from("text is not UTF-8"))
    }

    fn dimension(&mut self) -> Result<Dimension, String> {
        let n = self.len()?;
        let name = self.take(n)?;
        Dimension::from_name(name)
            .ok_or_else(|| format!("unknown dimension '{}'", String::from_utf8_lossy(name)))
    }

    fn payload(&mut self) -> Result<Payload, String> {
        Ok(Payload {
            file: self.string()?,
            bytes: self.u64()?,
            blake3: self.string()?,
            array: match self.u8()? {
                0 => None,
                _ => Some(self.string()?),
            },
        })
    }

    fn value(&mut self) -> Result<Value, String> {
        Ok(match self.u8()? {
            b'f' => Value::Float(self.f64()?),
            b'i' => Value::Int(self.u64()? as i64),
            b'b' => Value::Bool(self.u8()? != 0),
            b's' => Value::Text(self.string()?),
            b'F' => Value::Floats(self.list(Reader::f64)?),
            b'S' => Value::Texts(self.list(Reader::string)?),
            other => return Err(format!("unknown value type {other}")),
        })
    }

    /// A table's columns, with their values when `with_values` (else empty columns: a schema).
    fn table(&mut self, with_values: bool) -> Result<Table, String> {
        let columns = self.list(|r| {
            let name = r.name()?;
            let dimension = r.dimension()?;
            let tag = r.u8()?;
            let data = match (tag, with_values) {
                (b'f', true) => ColumnData::Float(r.list(Reader::f64)?),
                (b'i', true) => ColumnData::Int(r.list(|r| r.u64().map(|i| i as i64))?),
                (b'b', true) => ColumnData::Bool(r.list(|r| r.u8().map(|b| b != 0))?),
                (b's', true) => ColumnData::Text(r.list(Reader::string)?),
                (b'f', false) => ColumnData::Float(Vec::new()),
                (b'i', false) => ColumnData::Int(Vec::new()),
                (b'b', false) => ColumnData::Bool(Vec::new()),
                (b's', false) => ColumnData::Text(Vec::new()),
                (other, _) => return Err(format!("unknown column type {other}")),
            };
            Ok(Column {
                name,
                dimension,
                data,
            })
        })?;
        Ok(Table { columns })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Sample {
        key: NodeKey,
        manifest: EntryManifest,
        payloads: Vec<Payload>,
        metrics: Vec<Field>,
        tables: BTreeMap<String, Table>,
        table_files: BTreeMap<String, Payload>,
        flags: Vec<String>,
    }

    /// A table of `rows` rows, for a table file (whose values the summary does not hold).
    fn long_table(rows: usize) -> Table {
        let mut table = Table::default();
        table.push_float("x", Dimension::Length, vec![0.5; rows]);
        table.push_int("ix", vec![3; rows]);
        table.push_text("note", vec![String::new(); rows]);
        table
    }

    fn sample() -> Sample {
        let mut table = Table::default();
        table.push_float("load", Dimension::Force, vec![1.0, f64::INFINITY]);
        table.push_int("step", vec![1, 2]);
        table.push_text("note", vec![String::new(), String::from("é")]);
        Sample {
            key: NodeKey([7; 32]),
            manifest: EntryManifest {
                upstream: vec![(String::from("lower"), String::from("ab12"))],
                compute_seconds: 0.25,
            },
            payloads: vec![Payload {
                file: String::from("gap.npy.zst"),
                bytes: 600,
                blake3: String::from("00ff"),
                array: Some(String::from("gap")),
            }],
            metrics: vec![
                Field::float("sq", 1.5e-6, Dimension::Length),
                Field::float(
                    "undefined",
                    f64::from_bits(0xfff8_0000_0000_0001),
                    Dimension::Area,
                ),
                Field::int("n", -3),
                Field::bool("ok", true),
                Field::text("model", "kogut_etsion".repeat(20)),
                Field::floats("loads", vec![5e6, f64::NAN, -0.0], Dimension::Pressure),
                Field::texts("warnings", vec![String::from("a; b"), String::new()]),
                Field::texts("none", Vec::new()),
            ],
            tables: [
                (String::from("steps"), table),
                (String::from("summits"), long_table(100_000)),
            ]
            .into(),
            table_files: [(
                String::from("summits"),
                Payload {
                    file: String::from("summits.parquet"),
                    bytes: 900,
                    blake3: String::from("aa11"),
                    array: None,
                },
            )]
            .into(),
            flags: vec![String::from("area fraction 0.6 is beyond … light load")],
        }
    }

    fn encoded(s: &Sample) -> Vec<u8> {
        encode(&Summary {
            key: &s.key,
            kind: "contact",
            upstream: &s.manifest.upstream,
            payloads: &s.payloads,
            compute_seconds: s.manifest.compute_seconds,
            metrics: &s.metrics,
            tables: &s.tables,
            table_files: &s.table_files,
            flags: &s.flags,
        })
    }

    #[test]
    fn a_summary_reads_back_exactly() {
        let s = sample();
        let bytes = encoded(&s);
        for payloads in [true, false] {
            let d = decode(&bytes, &s.key, "contact", payloads)
                .unwrap()
                .unwrap();
            assert_eq!(d.manifest, s.manifest);
            assert_eq!(d.payloads.is_empty(), !payloads);
            if payloads {
                assert_eq!(d.payloads, s.payloads);
            }
            assert_eq!(d.artifact.tables.len(), 1);
            assert_eq!(d.artifact.tables["steps"], s.tables["steps"]);
            let [file] = &d.table_files[..] else {
                panic!("one table file: {:?}", d.table_files)
            };
            assert_eq!(
                (file.name.as_str(), &file.payload, file.rows),
                ("summits", &s.table_files["summits"], 100_000)
            );
            assert_eq!(file.schema.columns.len(), 3);
            assert!(file.schema.columns.iter().all(|c| c.data.is_empty()));
            assert_eq!(file.schema.columns[2].column_name(), "note");
            assert_eq!(d.artifact.flags, s.flags);
            assert_eq!(d.artifact.metrics.len(), s.metrics.len());
            for (a, b) in d.artifact.metrics.iter().zip(&s.metrics) {
                assert_eq!((&a.name, a.dimension), (&b.name, b.dimension));
                match (&a.value, &b.value) {
                    (Value::Float(x), Value::Float(y)) => assert_eq!(x.to_bits(), y.to_bits()),
                    (Value::Floats(x), Value::Floats(y)) => {
                        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                        assert_eq!(bits(x), bits(y));
                    }
                    (x, y) => assert_eq!(x, y),
                }
            }
        }
    }

    #[test]
    fn lengths_are_varints() {
        for n in [0, 1, 127, 128, 300, 16_383, 16_384, 1 << 40] {
            let mut bytes = vec![0; 8];
            put_len(&mut bytes, n);
            bytes.extend(std::iter::repeat_n(0, n.min(1 << 20)));
            let mut r = Reader(&bytes[8..]);
            let read = r.len();
            if n <= 1 << 20 {
                assert_eq!(read, Ok(n), "{n}");
            } else {
                assert!(read.is_err(), "{n}");
            }
        }
    }

    #[test]
    fn any_damage_or_another_entry_is_refused() {
        let s = sample();
        let bytes = encoded(&s);
        for i in [0, 15, HEADER - 1, HEADER + 40, bytes.len() - 1] {
            let mut damaged = bytes.clone();
            damaged[i] ^= 0x10;
            assert!(
                decode(&damaged, &s.key, "contact", false).is_err(),
                "byte {i}"
            );
        }
        assert!(decode(&bytes[..bytes.len() - 1], &s.key, "contact", true).is_err());
        assert!(decode(&bytes, &NodeKey([8; 32]), "contact", true).is_err());
        assert!(decode(&bytes, &s.key, "surface", true).is_err());
    }

    #[test]
    fn another_version_is_left_to_the_manifest() {
        let s = sample();
        let mut bytes = encoded(&s);
        bytes[MAGIC.len()] = 1;
        assert!(matches!(decode(&bytes, &s.key, "contact", true), Ok(None)));
    }
}
