//! SDF reader (ISO 25178-71 "surface data file", formerly the SURFSTAND/EUR 15178 format).
//!
//! * ASCII (`aISO-1.0`, and the `aISO-2.0` dialect of the 2026 revision): a `Key = Value`
//!   header ended by a line `*`, then NumPoints × NumProfiles numbers (x fastest, one profile
//!   after another) ended by a line `*`, then an optional free-form trailer. `BAD` marks a
//!   non-measured point. Any line ending (LF or CRLF) is accepted.
//! * Binary (`bISO-1.0`): the same header as fixed-width little-endian fields (81 bytes:
//!   version 8, ManufacID 10, CreateDate 12, ModDate 12, NumPoints u16, NumProfiles u16,
//!   Xscale, Yscale, Zscale, Zresolution f64, Compression u8, DataType u8, CheckType u8), then
//!   the raw samples. Floating-point `NaN` samples are non-measured points.
//!
//! Heights are z = value · Zscale (m); spacings are Xscale, Yscale (m). `DataType` codes:
//! 0 uint8, 1 uint16, 2 uint32, 3 float32, 4 int8, 5 int16, 6 int32, 7 float64.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{check_block_size, decode_samples, ByteCursor, Endian, SampleType};
use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "sdf",
    description: "ISO 25178-71 SDF (ASCII `aISO-1.0`/`aISO-2.0` or binary `bISO-1.0`)",
    extensions: &["sdf"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` for an ASCII or binary ISO SDF header.
pub(crate) fn matches_magic(head: &[u8]) -> bool {
    let head = strip_bom(head);
    head.starts_with(b"aISO-") || head.starts_with(b"bISO-")
}

/// Parses an SDF file (ASCII or binary).
pub(crate) fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let body = strip_bom(bytes);
    if body.starts_with(b"bISO-") {
        parse_binary(body)
    } else if body.starts_with(b"aISO-") {
        parse_ascii(body)
    } else {
        Err(ParseError::malformed(
            "sdf: file does not start with aISO-/bISO- version string",
        ))
    }
}

fn strip_bom(b: &[u8]) -> &[u8] {
    b.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(b)
}

/// Header values common to the ASCII and binary variants.
#[derive(Debug)]
struct SdfHeader {
    version: String,
    num_points: usize,
    num_profiles: usize,
    x_scale: f64,
    y_scale: f64,
    z_scale: f64,
    data_type: u8,
    metadata: BTreeMap<String, String>,
}

impl SdfHeader {
    fn check(&self) -> Result<(), ParseError> {
        for (name, v) in [("Xscale", self.x_scale), ("Yscale", self.y_scale)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(ParseError::malformed(format!(
                    "sdf: {name} = {v} is not > 0"
                )));
            }
        }
        if !(self.z_scale.is_finite() && self.z_scale != 0.0) {
            return Err(ParseError::malformed(format!(
                "sdf: Zscale = {} is not a finite non-zero factor",
                self.z_scale
            )));
        }
        if self.num_points == 0 || self.num_profiles == 0 {
            return Err(ParseError::malformed(format!(
                "sdf: empty grid, NumPoints = {}, NumProfiles = {}",
                self.num_points, self.num_profiles
            )));
        }
        Ok(())
    }

    fn sample_type(&self) -> Result<SampleType, ParseError> {
        Ok(match self.data_type {
            0 => SampleType::U8,
            1 => SampleType::U16,
            2 => SampleType::U32,
            3 => SampleType::F32,
            4 => SampleType::I8,
            5 => SampleType::I16,
            6 => SampleType::I32,
            7 => SampleType::F64,
            other => {
                return Err(ParseError::malformed(format!(
                    "sdf: DataType {other} (expected 0–7)"
                )))
            }
        })
    }

    /// Builds the topography from values in file units (`NaN` = non-measured).
    fn into_topography(self, values: Vec<f64>) -> Result<Topography, ParseError> {
        let z: Vec<f64> = values
            .into_iter()
            .map(|v| {
                let z = v * self.z_scale;
                if z.is_finite() {
                    z
                } else {
                    f64::NAN
                }
            })
            .collect();
        let mut metadata = self.metadata;
        metadata.insert("sdf_version".into(), self.version);
        let shape = (self.num_profiles, self.num_points);
        let grid = Array2::from_shape_vec(shape, z)
            .map_err(|e| ParseError::malformed(format!("sdf: grid shape: {e}")))?;
        let map = HeightMap::new(grid, self.x_scale, self.y_scale)
            .map_err(|e| ParseError::malformed(format!("sdf: {e}")))?;
        Ok(Topography {
            spacing: ScaleSource::File,
            height_unit: ScaleSource::File,
            data: TopographyData::Areal(map),
            channel: None,
            channels: Vec::new(),
            metadata,
        })
    }
}

fn parse_ascii(bytes: &[u8]) -> Result<Topography, ParseError> {
    let text = String::from_utf8_lossy(bytes);
    let mut lines = text.lines();
    let version = lines.next().unwrap_or_default().trim().to_string();
    let fields = ascii_fields(&mut lines)?;
    let header = ascii_header(version, &fields)?;
    header.check()?;
    header.sample_type()?;
    // Each value takes at least two bytes ("0 "), so a header claiming more cannot be right.
    let n = header
        .num_points
        .checked_mul(header.num_profiles)
        .filter(|&n| n <= bytes.len() / 2 + 1)
        .ok_or_else(|| {
            ParseError::truncated(format!(
                "sdf: header claims {} × {} values, a {} byte file cannot hold them",
                header.num_points,
                header.num_profiles,
                bytes.len()
            ))
        })?;
    check_points(
        header.num_points,
        header.num_profiles,
        "sdf header (NumPoints × NumProfiles)",
    )?;
    let values = ascii_values(lines, n)?;
    header.into_topography(values)
}

/// The `Key = Value` lines of an ASCII header, up to its closing `*` line.
fn ascii_fields<'a>(
    lines: &mut impl Iterator<Item = &'a str>,
) -> Result<BTreeMap<String, String>, ParseError> {
    let mut fields: BTreeMap<String, String> = BTreeMap::new();
    for line in lines.by_ref() {
        let line = line.trim();
        if line == "*" {
            return Ok(fields);
        }
        if line.is_empty() {
            continue;
        }
        let (key, value) = line.split_once('=').ok_or_else(|| {
            ParseError::malformed(format!("sdf: header line {line:?} is not `Key = Value`"))
        })?;
        fields.insert(key.trim().to_string(), value.trim().to_string());
    }
    Err(ParseError::truncated(
        "sdf: header not terminated by a `*` line",
    ))
}

/// The header values of an ASCII file's fields (uncompressed only; DataType 7 by default).
fn ascii_header(
    version: String,
    fields: &BTreeMap<String, String>,
) -> Result<SdfHeader, ParseError> {
    let int = |key: &str| -> Result<usize, ParseError> {
        let v = fields
            .get(key)
            .ok_or_else(|| ParseError::malformed(format!("sdf: header lacks {key}")))?;
        v.parse()
            .map_err(|_| ParseError::malformed(format!("sdf: {key} = {v:?} is not a count")))
    };
    let float = |key: &str| -> Result<f64, ParseError> {
        let v = fields
            .get(key)
            .ok_or_else(|| ParseError::malformed(format!("sdf: header lacks {key}")))?;
        v.parse()
            .map_err(|_| ParseError::malformed(format!("sdf: {key} = {v:?} is not a number")))
    };
    let compression = fields.get("Compression").map_or("0", String::as_str);
    if compression != "0" {
        return Err(ParseError::unsupported(format!(
            "sdf: Compression = {compression}"
        )));
    }
    Ok(SdfHeader {
        version,
        num_points: int("NumPoints")?,
        num_profiles: int("NumProfiles")?,
        x_scale: float("Xscale")?,
        y_scale: float("Yscale")?,
        z_scale: float("Zscale")?,
        data_type: fields
            .get("DataType")
            .map_or(Ok(7), |v| v.parse::<u8>())
            .map_err(|_| ParseError::malformed("sdf: DataType is not a small integer"))?,
        metadata: fields
            .iter()
            .map(|(k, v)| (format!("sdf_{k}"), v.clone()))
            .collect(),
    })
}

/// The `n` values of the data section (`BAD`: `NaN`), which a `*` line must close.
fn ascii_values<'a>(
    lines: impl Iterator<Item = &'a str>,
    n: usize,
) -> Result<Vec<f64>, ParseError> {
    let mut values = Vec::with_capacity(n);
    let mut data_closed = false;
    for line in lines {
        let line = line.trim();
        if line == "*" {
            data_closed = true;
            break;
        }
        for token in line.split_whitespace() {
            if values.len() == n {
                return Err(ParseError::malformed(format!(
                    "sdf: more than NumPoints × NumProfiles = {n} values before the closing `*`"
                )));
            }
            let v = if token.eq_ignore_ascii_case("BAD") {
                f64::NAN
            } else {
                token.parse::<f64>().map_err(|_| {
                    ParseError::malformed(format!("sdf: data value {token:?} is not a number"))
                })?
            };
            values.push(v);
        }
    }
    if values.len() < n {
        return Err(ParseError::truncated(format!(
            "sdf: {} of NumPoints × NumProfiles = {n} values present",
            values.len()
        )));
    }
    if !data_closed {
        return Err(ParseError::truncated(
            "sdf: data section not terminated by a `*` line",
        ));
    }
    Ok(values)
}

fn parse_binary(bytes: &[u8]) -> Result<Topography, ParseError> {
    let le = Endian::Little;
    let mut c = ByteCursor::new(bytes);
    let version = c.text(8, "sdf version")?;
    let mut metadata = BTreeMap::new();
    metadata.insert("sdf_ManufacID".into(), c.text(10, "sdf ManufacID")?);
    metadata.insert("sdf_CreateDate".into(), c.text(12, "sdf CreateDate")?);
    metadata.insert("sdf_ModDate".into(), c.text(12, "sdf ModDate")?);
    let num_points = usize::from(c.u16(le, "sdf NumPoints")?);
    let num_profiles = usize::from(c.u16(le, "sdf NumProfiles")?);
    let x_scale = c.f64(le, "sdf Xscale")?;
    let y_scale = c.f64(le, "sdf Yscale")?;
    let z_scale = c.f64(le, "sdf Zscale")?;
    let z_resolution = c.f64(le, "sdf Zresolution")?;
    metadata.insert("sdf_Zresolution".into(), z_resolution.to_string());
    let compression = c.u8("sdf Compression")?;
    let data_type = c.u8("sdf DataType")?;
    let _check_type = c.u8("sdf CheckType")?;
    if compression != 0 {
        return Err(ParseError::unsupported(format!(
            "sdf: Compression = {compression}"
        )));
    }
    let header = SdfHeader {
        version,
        num_points,
        num_profiles,
        x_scale,
        y_scale,
        z_scale,
        data_type,
        metadata,
    };
    header.check()?;
    let ty = header.sample_type()?;
    let n = num_points * num_profiles;
    let data = c.take(
        check_block_size(n, ty.size(), c.remaining(), "sdf binary data")?,
        "sdf binary data",
    )?;
    check_binary_trailer(&bytes[bytes.len() - c.remaining()..], n, ty.size())?;
    let values = decode_samples(data, n, ty, le, "sdf binary data")?;
    header.into_topography(values)
}

/// What follows the `count` samples of `size` bytes of a binary file is its optional trailer,
/// text (`Key = Value` lines, ISO 25178-71): binary bytes there mean NumPoints, NumProfiles or
/// DataType declares fewer data bytes than the file holds, a damaged header.
fn check_binary_trailer(rest: &[u8], count: usize, size: usize) -> Result<(), ParseError> {
    let text = |b: &u8| b.is_ascii_graphic() || b" \t\r\n".contains(b) || *b >= 0x80;
    match rest.iter().position(|b| !text(b)) {
        None => Ok(()),
        Some(at) => Err(ParseError::malformed(format!(
            "sdf: the header declares {count} points of {size} B, but the {} bytes after them \
             are no text trailer (a binary byte {:#04x} at {at} bytes past the data): \
             NumPoints, NumProfiles or DataType is damaged",
            rest.len(),
            rest[at]
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_with_bad_point_and_crlf() {
        let text = "aISO-1.0\r\nNumPoints = 2\r\nNumProfiles = 2\r\nXscale = 1e-6\r\n\
                    Yscale = 2e-6\r\nZscale = 0.25\r\nDataType = 6\r\n*\r\n1 BAD\r\n3 4\r\n*\r\n";
        let t = parse(text.as_bytes()).unwrap();
        let TopographyData::Areal(m) = t.data else {
            panic!("expected an areal map")
        };
        assert_eq!((m.nx(), m.ny(), m.dx(), m.dy()), (2, 2, 1e-6, 2e-6));
        assert!(m.heights()[[0, 1]].is_nan());
        assert_eq!(m.heights()[[1, 0]], 0.75);
    }

    #[test]
    fn ascii_missing_values_is_truncated() {
        let text = "aISO-1.0\nNumPoints = 2\nNumProfiles = 2\nXscale = 1\nYscale = 1\nZscale = 1\n*\n1 2 3\n";
        let err = parse(text.as_bytes()).unwrap_err();
        assert!(matches!(err, ParseError::Truncated { .. }), "{err}");
    }
}
