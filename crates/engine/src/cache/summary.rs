//! `summary.bin`: what a read of a cache entry returns (key, kind, upstream keys, payload list,
//! compute time, metrics and long tables) in one compact, self-verifying file, so that a rerun
//! reads one file per entry instead of the manifest, its checksum file and `tables.json`.
//!
//! Layout: the magic `asperity-summary`, the format version (u32), the blake3 checksum of the body
//! (32 bytes), the body. In the body every count and length is a little-endian u64, a string is
//! its length and its UTF-8 bytes, a float its IEEE 754 bits (so values read back exactly as
//! computed, NaN and infinities included), a dimension its name (as in node keys). The file is
//! written with the entry and listed among the manifest's payloads, so the manifest's checksums
//! cover it too.

use std::collections::BTreeMap;

use crate::artifact::{Artifact, Column, ColumnData, Table};
use crate::hash::NodeKey;
use crate::units::Dimension;
use crate::value::{Field, Value};

use super::{EntryManifest, Payload};

/// The file name of an entry's summary.
pub(super) const SUMMARY_FILE: &str = "summary.bin";

const MAGIC: &[u8; 16] = b"asperity-summary";
const VERSION: u32 = 1;
const HEADER: usize = MAGIC.len() + 4 + 32;

/// Everything a summary holds.
pub(super) struct Summary<'a> {
    pub key: &'a NodeKey,
    pub kind: &'a str,
    pub upstream: &'a [(String, String)],
    pub payloads: &'a [Payload],
    pub compute_seconds: f64,
    pub metrics: &'a [Field],
    pub tables: &'a BTreeMap<String, Table>,
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
    put_len(&mut body, summary.payloads.len());
    for payload in summary.payloads {
        put_payload(&mut body, payload);
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
        put_table(&mut body, table);
    }
    let mut out = Vec::with_capacity(HEADER + body.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(blake3::hash(&body).as_bytes());
    out.extend_from_slice(&body);
    out
}

/// Verifies and decodes the summary of entry `key` of kind `kind`: its manifest part and an
/// artifact with its metrics and tables. Errors say why the file is corrupt.
pub(super) fn decode(
    bytes: &[u8],
    key: &NodeKey,
    kind: &str,
) -> Result<(EntryManifest, Artifact), String> {
    if bytes.len() < HEADER || &bytes[..MAGIC.len()] != MAGIC {
        return Err(String::from("not a summary"));
    }
    let (version, rest) = bytes[MAGIC.len()..].split_at(4);
    if version != VERSION.to_le_bytes() {
        return Err(String::from("unknown summary version"));
    }
    let (checksum, body) = rest.split_at(32);
    if blake3::hash(body).as_bytes() != checksum {
        return Err(String::from("checksum mismatch"));
    }
    let mut r = Reader(body);
    if r.take(32)? != key.0 || r.str()? != kind {
        return Err(String::from("names another key or kind"));
    }
    let compute_seconds = r.f64()?;
    let upstream = r.list(|r| Ok((r.string()?, r.string()?)))?;
    let payloads = r.list(Reader::payload)?;
    let metrics = r.list(|r| {
        let name = r.string()?;
        let dimension = r.dimension()?;
        let value = r.value()?;
        Ok(Field {
            name: name.into(),
            value,
            dimension,
        })
    })?;
    let tables = r
        .list(|r| Ok((r.string()?, r.table()?)))?
        .into_iter()
        .collect();
    if !r.0.is_empty() {
        return Err(String::from("trailing bytes"));
    }
    let manifest = EntryManifest {
        upstream,
        payloads,
        compute_seconds,
    };
    let artifact = Artifact {
        metrics,
        tables,
        ..Artifact::default()
    };
    Ok((manifest, artifact))
}

fn put_len(out: &mut Vec<u8>, n: usize) {
    out.extend_from_slice(&(n as u64).to_le_bytes());
}

fn put_str(out: &mut Vec<u8>, s: &str) {
    put_len(out, s.len());
    out.extend_from_slice(s.as_bytes());
}

fn put_f64(out: &mut Vec<u8>, x: f64) {
    out.extend_from_slice(&x.to_bits().to_le_bytes());
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

fn put_value(out: &mut Vec<u8>, value: &Value) {
    match value {
        Value::Float(x) => {
            out.push(b'f');
            put_f64(out, *x);
        }
        Value::Int(i) => {
            out.push(b'i');
            out.extend_from_slice(&i.to_le_bytes());
        }
        Value::Bool(b) => {
            out.push(b'b');
            out.push(u8::from(*b));
        }
        Value::Text(s) => {
            out.push(b's');
            put_str(out, s);
        }
    }
}

fn put_table(out: &mut Vec<u8>, table: &Table) {
    put_len(out, table.columns.len());
    for column in &table.columns {
        put_str(out, &column.name);
        put_str(out, column.dimension.name());
        match &column.data {
            ColumnData::Float(v) => {
                out.push(b'f');
                put_len(out, v.len());
                v.iter().for_each(|x| put_f64(out, *x));
            }
            ColumnData::Int(v) => {
                out.push(b'i');
                put_len(out, v.len());
                v.iter()
                    .for_each(|i| out.extend_from_slice(&i.to_le_bytes()));
            }
            ColumnData::Bool(v) => {
                out.push(b'b');
                put_len(out, v.len());
                out.extend(v.iter().map(|b| u8::from(*b)));
            }
            ColumnData::Text(v) => {
                out.push(b's');
                put_len(out, v.len());
                v.iter().for_each(|s| put_str(out, s));
            }
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

    /// A count or length, at most the bytes left (every item takes at least one byte).
    fn len(&mut self) -> Result<usize, String> {
        let n = self.u64()?;
        usize::try_from(n)
            .ok()
            .filter(|&n| n <= self.0.len())
            .ok_or_else(|| String::from("length beyond the end"))
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

    fn dimension(&mut self) -> Result<Dimension, String> {
        let name = self.str()?;
        Dimension::from_name(name).ok_or_else(|| format!("unknown dimension '{name}'"))
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
            other => return Err(format!("unknown value type {other}")),
        })
    }

    fn table(&mut self) -> Result<Table, String> {
        let columns = self.list(|r| {
            let name = r.string()?;
            let dimension = r.dimension()?;
            let data = match r.u8()? {
                b'f' => ColumnData::Float(r.list(Reader::f64)?),
                b'i' => ColumnData::Int(r.list(|r| r.u64().map(|i| i as i64))?),
                b'b' => ColumnData::Bool(r.list(|r| r.u8().map(|b| b != 0))?),
                b's' => ColumnData::Text(r.list(Reader::string)?),
                other => return Err(format!("unknown column type {other}")),
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

    fn sample() -> (NodeKey, EntryManifest, Vec<Field>, BTreeMap<String, Table>) {
        let manifest = EntryManifest {
            upstream: vec![(String::from("lower"), String::from("ab12"))],
            payloads: vec![Payload {
                file: String::from("gap.npy.zst"),
                bytes: 600,
                blake3: String::from("00ff"),
                array: Some(String::from("gap")),
            }],
            compute_seconds: 0.25,
        };
        let metrics = vec![
            Field::float("sq", 1.5e-6, Dimension::Length),
            Field::float(
                "undefined",
                f64::from_bits(0xfff8_0000_0000_0001),
                Dimension::Area,
            ),
            Field::int("n", -3),
            Field::bool("ok", true),
            Field::text("model", "kogut_etsion"),
        ];
        let mut table = Table::default();
        table.push_float("load", Dimension::Force, vec![1.0, f64::INFINITY]);
        table.push_int("step", vec![1, 2]);
        table.push_text("note", vec![String::new(), String::from("é")]);
        (
            NodeKey([7; 32]),
            manifest,
            metrics,
            [(String::from("steps"), table)].into(),
        )
    }

    fn encoded(
        key: &NodeKey,
        m: &EntryManifest,
        f: &[Field],
        t: &BTreeMap<String, Table>,
    ) -> Vec<u8> {
        encode(&Summary {
            key,
            kind: "contact",
            upstream: &m.upstream,
            payloads: &m.payloads,
            compute_seconds: m.compute_seconds,
            metrics: f,
            tables: t,
        })
    }

    #[test]
    fn a_summary_reads_back_exactly() {
        let (key, manifest, metrics, tables) = sample();
        let bytes = encoded(&key, &manifest, &metrics, &tables);
        let (m, artifact) = decode(&bytes, &key, "contact").unwrap();
        assert_eq!(m, manifest);
        assert_eq!(artifact.tables, tables);
        assert_eq!(artifact.metrics.len(), metrics.len());
        for (a, b) in artifact.metrics.iter().zip(&metrics) {
            assert_eq!((&a.name, a.dimension), (&b.name, b.dimension));
            match (&a.value, &b.value) {
                (Value::Float(x), Value::Float(y)) => assert_eq!(x.to_bits(), y.to_bits()),
                (x, y) => assert_eq!(x, y),
            }
        }
    }

    #[test]
    fn any_damage_or_another_entry_is_refused() {
        let (key, manifest, metrics, tables) = sample();
        let bytes = encoded(&key, &manifest, &metrics, &tables);
        for i in [0, 17, HEADER - 1, HEADER + 40, bytes.len() - 1] {
            let mut damaged = bytes.clone();
            damaged[i] ^= 0x10;
            assert!(decode(&damaged, &key, "contact").is_err(), "byte {i}");
        }
        assert!(decode(&bytes[..bytes.len() - 1], &key, "contact").is_err());
        assert!(decode(&bytes, &NodeKey([8; 32]), "contact").is_err());
        assert!(decode(&bytes, &key, "surface").is_err());
    }
}
