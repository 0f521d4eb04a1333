//! Gwyddion native `.gwy` reader (GWYP serialized object tree, little-endian).
//!
//! Layout (Gwyddion developer documentation, "GWY file format"): the magic `GWYP`, then one
//! serialized object. An object is `type name (NUL-terminated) · u32 byte size · components`;
//! a component is `name (NUL-terminated) · type char · value` with the types `b` bool (1 byte),
//! `c` char, `i` i32, `q` i64, `d` f64, `s` NUL-terminated string, `o` object, and the arrays
//! `C I Q D S O` (u32 element count, then the elements).
//!
//! The top object is a `GwyContainer` whose components are keyed by path; image channels are
//! `GwyDataField` objects at `/N/data` (`xres`, `yres`, `xreal`, `yreal` in base SI units of
//! `si_unit_xy`, `si_unit_z`, `data` as a row-major f64 array, x fastest), titled by
//! `/N/data/title`. By default the channel with the lowest `N` whose z unit is a length is read.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::gsf::length_unit_factor;
use super::limits::check_points;
use super::reader::{pick_channel, Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"GWYP";
/// Deepest object nesting accepted (real files nest 3–4 levels); bounds the recursion.
const MAX_DEPTH: usize = 32;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "gwy",
    description: "Gwyddion native `.gwy`",
    extensions: &["gwy"],
    magic: Some(matches_magic),
    parser: Parser::Channels(parse_channel),
};

/// `true` when `head` starts with the GWY magic.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

/// A serialized Gwyddion object: its type name and named components.
struct GwyObject<'a> {
    type_name: String,
    components: Vec<(String, GwyValue<'a>)>,
}

/// A component value. Arrays keep their raw bytes and are decoded on use.
enum GwyValue<'a> {
    Int(i64),
    Double(f64),
    Str(String),
    Object(GwyObject<'a>),
    DoubleArray(&'a [u8]),
    /// Values this reader never needs (bools, chars, other arrays).
    Other,
}

impl<'a> GwyObject<'a> {
    fn get(&self, name: &str) -> Option<&GwyValue<'a>> {
        self.components
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v)
    }
}

/// A position in the input with bounds-checked reads.
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Cursor<'a> {
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], ParseError> {
        let s = self
            .pos
            .checked_add(n)
            .and_then(|end| self.bytes.get(self.pos..end))
            .ok_or_else(|| ParseError::truncated(format!("GWY {what} at byte {}", self.pos)))?;
        self.pos += n;
        Ok(s)
    }

    fn string(&mut self, what: &str) -> Result<String, ParseError> {
        let rest = self.bytes.get(self.pos..).unwrap_or(&[]);
        let len = rest.iter().position(|&b| b == 0).ok_or_else(|| {
            ParseError::truncated(format!(
                "GWY {what} (unterminated string) at byte {}",
                self.pos
            ))
        })?;
        let s = String::from_utf8_lossy(&rest[..len]).into_owned();
        self.pos += len + 1;
        Ok(s)
    }

    fn u32(&mut self, what: &str) -> Result<usize, ParseError> {
        let b = self.take(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    }

    fn array(&mut self, elem: usize, what: &str) -> Result<&'a [u8], ParseError> {
        let count = self.u32(what)?;
        let n = count.checked_mul(elem).ok_or_else(|| {
            ParseError::malformed(format!("GWY {what}: array of {count} elements overflows"))
        })?;
        self.take(n, what)
    }

    fn object(&mut self, depth: usize) -> Result<GwyObject<'a>, ParseError> {
        if depth > MAX_DEPTH {
            return Err(ParseError::malformed(format!(
                "GWY objects nested deeper than {MAX_DEPTH}"
            )));
        }
        let type_name = self.string("object type name")?;
        let size = self.u32("object size")?;
        let body = self.take(size, &format!("`{type_name}` object of {size} bytes"))?;
        let mut inner = Cursor {
            bytes: body,
            pos: 0,
        };
        let mut components = Vec::new();
        while inner.pos < body.len() {
            let name = inner.string("component name")?;
            let kind = inner.take(1, "component type")?[0];
            let value = inner.value(kind, &name, depth)?;
            components.push((name, value));
        }
        Ok(GwyObject {
            type_name,
            components,
        })
    }

    fn value(&mut self, kind: u8, name: &str, depth: usize) -> Result<GwyValue<'a>, ParseError> {
        let v = match kind {
            b'b' | b'c' => {
                self.take(1, name)?;
                GwyValue::Other
            }
            b'i' => {
                let b = self.take(4, name)?;
                GwyValue::Int(i64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])))
            }
            b'q' => GwyValue::Int(i64::from_le_bytes(
                self.take(8, name)?.try_into().unwrap_or([0; 8]),
            )),
            b'd' => GwyValue::Double(f64::from_le_bytes(
                self.take(8, name)?.try_into().unwrap_or([0; 8]),
            )),
            b's' => GwyValue::Str(self.string(name)?),
            b'o' => GwyValue::Object(self.object(depth + 1)?),
            b'C' => {
                self.array(1, name)?;
                GwyValue::Other
            }
            b'I' => {
                self.array(4, name)?;
                GwyValue::Other
            }
            b'Q' => {
                self.array(8, name)?;
                GwyValue::Other
            }
            b'D' => GwyValue::DoubleArray(self.array(8, name)?),
            b'S' => {
                let count = self.u32(name)?;
                for _ in 0..count {
                    self.string(name)?;
                }
                GwyValue::Other
            }
            b'O' => {
                let count = self.u32(name)?;
                for _ in 0..count {
                    self.object(depth + 1)?;
                }
                GwyValue::Other
            }
            other => {
                return Err(ParseError::malformed(format!(
                    "GWY component `{name}` has unknown type `{}`",
                    char::from(other)
                )))
            }
        };
        Ok(v)
    }
}

fn read_container(bytes: &[u8]) -> Result<GwyObject<'_>, ParseError> {
    if !bytes.starts_with(MAGIC) {
        return Err(ParseError::malformed("missing `GWYP` magic"));
    }
    let mut cursor = Cursor { bytes, pos: 4 };
    let top = cursor.object(0)?;
    if top.type_name != "GwyContainer" {
        return Err(ParseError::malformed(format!(
            "GWY top object is `{}`, expected `GwyContainer`",
            top.type_name
        )));
    }
    Ok(top)
}

/// `(id, title, data field)` of every image channel, ordered by id.
fn channels<'c, 'a>(container: &'c GwyObject<'a>) -> Vec<(u64, String, &'c GwyObject<'a>)> {
    let mut found: Vec<(u64, String, &GwyObject<'a>)> = container
        .components
        .iter()
        .filter_map(|(key, value)| {
            let id = key
                .strip_prefix('/')?
                .strip_suffix("/data")?
                .parse::<u64>()
                .ok()?;
            match value {
                GwyValue::Object(o) if o.type_name == "GwyDataField" => {
                    let title = match container.get(&format!("/{id}/data/title")) {
                        Some(GwyValue::Str(t)) => t.clone(),
                        _ => format!("channel {id}"),
                    };
                    Some((id, title, o))
                }
                _ => None,
            }
        })
        .collect();
    found.sort_by_key(|(id, _, _)| *id);
    found
}

fn unit_string(field: &GwyObject<'_>, key: &str) -> String {
    match field.get(key) {
        Some(GwyValue::Object(u)) => match u.get("unitstr") {
            Some(GwyValue::Str(s)) => s.clone(),
            _ => String::new(),
        },
        _ => String::new(),
    }
}

/// Parses the channel titled `title` (or the default one for `None`), heights in metres.
fn parse_channel(bytes: &[u8], title: Option<&str>) -> Result<Topography, ParseError> {
    let container = read_container(bytes)?;
    let all = channels(&container);
    let names: Vec<String> = all.iter().map(|(_, n, _)| n.clone()).collect();
    let (_, name, field) = match title {
        Some(t) => &all[pick_channel(&names, Some(t), &[])?],
        None => all
            .iter()
            .find(|(_, _, f)| length_unit_factor(&unit_string(f, "si_unit_z")).is_some())
            .ok_or_else(|| {
                ParseError::malformed(format!(
                    "GWY: no channel has heights in a length unit (channels: {names:?})"
                ))
            })?,
    };
    let (nx, ny) = (field_int(field, name, "xres")?, field_int(field, name, "yres")?);
    let (xy_unit, z_unit) = (
        unit_string(field, "si_unit_xy"),
        unit_string(field, "si_unit_z"),
    );
    let xy_factor = length_unit_factor(&xy_unit).ok_or_else(|| {
        ParseError::unsupported(format!("GWY lateral unit `{xy_unit}` is not a length"))
    })?;
    let z_factor = length_unit_factor(&z_unit).ok_or_else(|| {
        ParseError::unsupported(format!(
            "GWY channel `{name}` is in `{z_unit}`, not a length"
        ))
    })?;
    let values = field_heights(field, name, nx, ny, z_factor)?;
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("GWY array shape: {e}")))?;
    let dx = field_real(field, name, "xreal")? * xy_factor / nx as f64;
    let dy = field_real(field, name, "yreal")? * xy_factor / ny as f64;
    let map =
        HeightMap::new(heights, dx, dy).map_err(|e| ParseError::malformed(format!("GWY: {e}")))?;
    let mut metadata = BTreeMap::new();
    metadata.insert("software".into(), "Gwyddion".into());
    for key in ["xoff", "yoff"] {
        if let Ok(v) = field_real(field, name, key) {
            metadata.insert(format!("{key}_m"), (v * xy_factor).to_string());
        }
    }
    if let Some(GwyValue::Str(f)) = container.get("/filename") {
        metadata.insert("original_filename".into(), f.clone());
    }
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: Some(name.clone()),
        channels: names,
        metadata,
    })
}

/// The positive integer `key` of the data field `name`.
fn field_int(field: &GwyObject<'_>, name: &str, key: &str) -> Result<usize, ParseError> {
    match field.get(key) {
        Some(GwyValue::Int(v)) if *v > 0 => usize::try_from(*v)
            .map_err(|_| ParseError::malformed(format!("GWY {key} = {v} too large"))),
        _ => Err(ParseError::malformed(format!(
            "GWY data field `{name}` has no positive {key}"
        ))),
    }
}

/// The real number `key` of the data field `name`.
fn field_real(field: &GwyObject<'_>, name: &str, key: &str) -> Result<f64, ParseError> {
    match field.get(key) {
        Some(GwyValue::Double(v)) => Ok(*v),
        _ => Err(ParseError::malformed(format!(
            "GWY data field `{name}` has no {key}"
        ))),
    }
}

/// The `nx × ny` heights of the data field's array in metres (`z_factor` per stored unit;
/// non-finite values are `NaN`).
fn field_heights(
    field: &GwyObject<'_>,
    name: &str,
    nx: usize,
    ny: usize,
    z_factor: f64,
) -> Result<Vec<f64>, ParseError> {
    let data = match field.get("data") {
        Some(GwyValue::DoubleArray(d)) => *d,
        _ => {
            return Err(ParseError::malformed(format!(
                "GWY data field `{name}` has no data array"
            )))
        }
    };
    if Some(data.len()) != nx.checked_mul(ny).and_then(|n| n.checked_mul(8)) {
        return Err(ParseError::malformed(format!(
            "GWY data array has {} values, expected {nx} × {ny}",
            data.len() / 8
        )));
    }
    check_points(nx, ny, &format!("GWY data field `{name}`"))?;
    Ok(data
        .chunks_exact(8)
        .map(|c| {
            let v = f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]);
            if v.is_finite() {
                v * z_factor
            } else {
                f64::NAN
            }
        })
        .collect())
}
