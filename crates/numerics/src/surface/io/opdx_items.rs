//! The item tree of a Bruker OPDx file, flattened to a path → value manifest.
//!
//! Layout (as SurfaceTopography's `OPDx.py` and Gwyddion's `dektakvca.c` read it,
//! little-endian): after the 12-byte magic, a sequence of items, each `name · type (u8) ·
//! value`, where a name is a u32 length and UTF-8 bytes and a "varlen" is a u8 width (1, 2 or
//! 4) followed by an unsigned integer of that width. Types: `0x01` bool, `0x04`–`0x0b`
//! integers (i16 u16 i32 u32 · i64 u64), `0x0c` f32, `0x0d` f64, `0x12` string (varlen, bytes),
//! `0x13` quantity (varlen; f64 value, name, symbol), `0x18` unit (varlen; name, symbol, f64),
//! `0x15` time stamp (9 bytes), `0x0e` type id, `0x40` double array, `0x42` string list and
//! `0x7c` positions (each: type name, varlen length, body), `0x00` matrix (type name, u32,
//! name, varlen length, u32 rows, u32 columns, f32 data), and the containers `0x7d`, `0x46`,
//! `0x47` (varlen length, then items up to the terminator `0x7f`). Paths join the names with
//! `/` ("/1D_Data/Raw/Array").

use std::collections::BTreeMap;

use super::byte_cursor::{ByteCursor, Endian};
use super::ParseError;

/// Deepest container nesting accepted (real files nest 3 levels); bounds the recursion.
const MAX_DEPTH: usize = 16;

/// A value of the manifest; arrays are kept as byte ranges of the file.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Item {
    Int(i64),
    Float(f64),
    Text(String),
    /// A value with its unit's name and symbol ("Micrometer", "µm").
    Quantity {
        value: f64,
        name: String,
        symbol: String,
    },
    TextList(Vec<String>),
    /// f64 values (after the array's 5-byte prefix), as a byte range of the file.
    Doubles {
        start: usize,
        len: usize,
    },
    /// f32 values, `rows × columns`, as a byte range of the file.
    Matrix {
        start: usize,
        len: usize,
        rows: usize,
        columns: usize,
    },
    /// A value this reader does not use.
    Skipped,
}

/// Bytes before the f64 values of a double array.
const DOUBLE_ARRAY_PREFIX: usize = 5;

/// The manifest of the items after `start` (the end of the magic).
pub(super) fn manifest(bytes: &[u8], start: usize) -> Result<BTreeMap<String, Item>, ParseError> {
    let mut c = ByteCursor::new(bytes);
    c.seek(start, "OPDx items")?;
    let mut out = BTreeMap::new();
    while c.remaining() > 0 && read_item(&mut c, "", &mut out, 0)? {}
    Ok(out)
}

fn name(c: &mut ByteCursor<'_>, what: &str) -> Result<String, ParseError> {
    let n = c.u32(Endian::Little, what)? as usize;
    let raw = c.take(n, what)?;
    Ok(String::from_utf8_lossy(raw).into_owned())
}

fn varlen(c: &mut ByteCursor<'_>, what: &str) -> Result<usize, ParseError> {
    let le = Endian::Little;
    Ok(match c.u8(what)? {
        1 => usize::from(c.u8(what)?),
        2 => usize::from(c.u16(le, what)?),
        4 => c.u32(le, what)? as usize,
        w => {
            return Err(ParseError::malformed(format!(
                "OPDx {what}: length of width {w} (1, 2 or 4 expected)"
            )))
        }
    })
}

/// Reads one item into `out`; `false` at a terminator.
fn read_item(
    c: &mut ByteCursor<'_>,
    prefix: &str,
    out: &mut BTreeMap<String, Item>,
    depth: usize,
) -> Result<bool, ParseError> {
    let path = format!("{prefix}/{}", name(c, "OPDx item name")?);
    let kind = c.u8(&format!("OPDx type of {path}"))?;
    match kind {
        0x7f => Ok(false),
        0x7d | 0x46 | 0x47 => {
            read_container(c, &path, out, depth)?;
            Ok(true)
        }
        _ => {
            let item = read_value(c, kind, &path)?;
            out.insert(path, item);
            Ok(true)
        }
    }
}

/// The items of the container `path` (varlen length, then items up to a terminator), which
/// must stay inside its length.
fn read_container(
    c: &mut ByteCursor<'_>,
    path: &str,
    out: &mut BTreeMap<String, Item>,
    depth: usize,
) -> Result<(), ParseError> {
    if depth >= MAX_DEPTH {
        return Err(ParseError::malformed(format!(
            "OPDx containers nested deeper than {MAX_DEPTH} at {path}"
        )));
    }
    let len = varlen(c, path)?;
    let start = c.position();
    c.take(len, path)?;
    c.seek(start, path)?;
    let end = start + len;
    while c.position() < end && read_item(c, path, out, depth + 1)? {}
    if c.position() > end {
        return Err(ParseError::malformed(format!(
            "OPDx container {path}: its items run past its {len} bytes"
        )));
    }
    c.seek(end, path)
}

/// The value of an item of type `kind` that is not a container.
fn read_value(c: &mut ByteCursor<'_>, kind: u8, path: &str) -> Result<Item, ParseError> {
    let what = path;
    Ok(match kind {
        0x01 | 0x04..=0x07 | 0x0a..=0x0d => scalar(c, kind, what)?,
        0x12 => {
            let len = varlen(c, what)?;
            Item::Text(String::from_utf8_lossy(c.take(len, what)?).into_owned())
        }
        0x13 => quantity(c, what)?,
        0x15 => {
            c.take(9, what)?;
            Item::Skipped
        }
        0x18 | 0x0e | 0x7c => {
            if kind != 0x18 {
                name(c, what)?;
            }
            let len = varlen(c, what)?;
            c.take(len, what)?;
            Item::Skipped
        }
        0x40 => doubles(c, what)?,
        0x42 => {
            name(c, what)?;
            let len = varlen(c, what)?;
            let mut list = ByteCursor::new(c.take(len, what)?);
            let mut names = Vec::new();
            while list.remaining() > 0 {
                names.push(name(&mut list, what)?);
            }
            Item::TextList(names)
        }
        0x00 => matrix(c, what)?,
        other => {
            return Err(ParseError::unsupported(format!(
                "OPDx item {path} of type {other:#04x}"
            )))
        }
    })
}

/// A quantity: varlen length, then an f64 value, the unit's name and symbol.
fn quantity(c: &mut ByteCursor<'_>, what: &str) -> Result<Item, ParseError> {
    let len = varlen(c, what)?;
    let mut q = ByteCursor::new(c.take(len, what)?);
    let value = q.f64(Endian::Little, what)?;
    let name = name(&mut q, what)?;
    Ok(Item::Quantity {
        value,
        name,
        symbol: name_or_empty(&mut q),
    })
}

/// A double array: type name, varlen length, a 5-byte prefix, then the f64 values.
fn doubles(c: &mut ByteCursor<'_>, what: &str) -> Result<Item, ParseError> {
    name(c, what)?;
    let len = varlen(c, what)?;
    let start = c.position();
    c.take(len, what)?;
    let len = len
        .checked_sub(DOUBLE_ARRAY_PREFIX)
        .ok_or_else(|| ParseError::malformed(format!("OPDx array {what} of {len} bytes")))?;
    Ok(Item::Doubles {
        start: start + DOUBLE_ARRAY_PREFIX,
        len,
    })
}

/// A boolean, integer or floating-point item of type `kind`.
fn scalar(c: &mut ByteCursor<'_>, kind: u8, what: &str) -> Result<Item, ParseError> {
    let le = Endian::Little;
    Ok(match kind {
        0x01 => Item::Int(i64::from(c.u8(what)?)),
        0x04 => Item::Int(i64::from(c.u16(le, what)? as i16)),
        0x05 => Item::Int(i64::from(c.u16(le, what)?)),
        0x06 => Item::Int(i64::from(c.i32(le, what)?)),
        0x07 => Item::Int(i64::from(c.u32(le, what)?)),
        0x0a | 0x0b => {
            let raw = c.take(8, what)?;
            let v = u64::from_le_bytes(raw.try_into().unwrap_or_default());
            Item::Int(if kind == 0x0a {
                v as i64
            } else {
                i64::try_from(v).unwrap_or(i64::MAX)
            })
        }
        0x0c => Item::Float(f64::from(c.f32(le, what)?)),
        _ => Item::Float(c.f64(le, what)?),
    })
}

/// The symbol of a quantity, empty when the quantity ends before it.
fn name_or_empty(c: &mut ByteCursor<'_>) -> String {
    name(c, "OPDx unit symbol").unwrap_or_default()
}

/// A matrix item: type name, u32, name, varlen length, u32 rows, u32 columns, f32 data.
fn matrix(c: &mut ByteCursor<'_>, what: &str) -> Result<Item, ParseError> {
    let le = Endian::Little;
    name(c, what)?;
    c.u32(le, what)?;
    name(c, what)?;
    let len = varlen(c, what)?;
    let rows = c.u32(le, what)? as usize;
    let columns = c.u32(le, what)? as usize;
    let len = len
        .checked_sub(8)
        .ok_or_else(|| ParseError::malformed(format!("OPDx matrix {what} of {len} bytes")))?;
    let start = c.position();
    c.take(len, what)?;
    Ok(Item::Matrix {
        start,
        len,
        rows,
        columns,
    })
}
