//! Gwyddion Simple Field `.gsf` reader.
//!
//! Layout (Gwyddion user guide, "Gwyddion Simple Field", version 1.0): the text line
//! `Gwyddion Simple Field 1.0`, then `Key = Value` lines (`XRes`, `YRes` mandatory; `XReal`,
//! `YReal` in `XYUnits`, default 1; `ZUnits`; `Title`; offsets), then 1–4 NUL bytes so that the
//! binary part starts at a multiple of 4 bytes, then `XRes · YRes` little-endian float32 values,
//! row by row, x fastest. Non-finite values are missing points (`NaN`).
//!
//! Also hosts `length_unit_factor`, the metre factor of a length unit string, shared by the
//! Gwyddion and Nanoscope readers.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"Gwyddion Simple Field 1.0\n";

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "gsf",
    description: "Gwyddion Simple Field `.gsf`",
    extensions: &["gsf"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` starts with the GSF magic line.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

/// Metres per `unit` for a length unit string (`m`, `mm`, `um`, `µm`, `~m` (Nanoscope's µm),
/// `nm`, `pm`, `Å`); `None` for anything else, including an empty (unitless) string.
pub(super) fn length_unit_factor(unit: &str) -> Option<f64> {
    match unit.trim() {
        "m" => Some(1.0),
        "cm" => Some(1e-2),
        "mm" => Some(1e-3),
        "um" | "µm" | "μm" | "~m" | "micron" | "microns" => Some(1e-6),
        "nm" => Some(1e-9),
        "pm" => Some(1e-12),
        "Å" | "A" | "Angstrom" => Some(1e-10),
        _ => None,
    }
}

/// Metre factor of the `XYUnits`/`ZUnits` value; a missing key means metres.
fn unit_factor(unit: Option<&String>, key: &str) -> Result<f64, ParseError> {
    let unit = unit.map(String::as_str).unwrap_or("m");
    length_unit_factor(unit)
        .ok_or_else(|| ParseError::unsupported(format!("GSF {key} `{unit}` is not a length unit")))
}

/// Parses a Gwyddion Simple Field file into heights in metres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let (mut fields, data_start) = read_header(bytes)?;
    let res = |key: &str| -> Result<usize, ParseError> {
        let v = fields
            .get(key)
            .ok_or_else(|| ParseError::malformed(format!("GSF header has no {key}")))?;
        v.parse::<usize>().ok().filter(|&n| n > 0).ok_or_else(|| {
            ParseError::malformed(format!("GSF {key} = `{v}` is not a positive integer"))
        })
    };
    let real = |key: &str| -> Result<f64, ParseError> {
        match fields.get(key) {
            None => Ok(1.0),
            Some(v) => v
                .parse::<f64>()
                .map_err(|_| ParseError::malformed(format!("GSF {key} = `{v}` is not a number"))),
        }
    };
    let (nx, ny) = (res("XRes")?, res("YRes")?);
    let xy_factor = unit_factor(fields.get("XYUnits"), "XYUnits")?;
    let z_factor = unit_factor(fields.get("ZUnits"), "ZUnits")?;
    let dx = real("XReal")? * xy_factor / nx as f64;
    let dy = real("YReal")? * xy_factor / ny as f64;
    // The format lets XReal/YReal default to 1: a file without them has no lateral calibration.
    let spacing = if fields.contains_key("XReal") && fields.contains_key("YReal") {
        ScaleSource::File
    } else {
        ScaleSource::Assumed
    };
    let height_unit = if fields.contains_key("ZUnits") {
        ScaleSource::File
    } else {
        ScaleSource::Assumed
    };
    let values = read_heights(bytes, data_start, nx, ny, z_factor)?;
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("GSF array shape: {e}")))?;
    let map =
        HeightMap::new(heights, dx, dy).map_err(|e| ParseError::malformed(format!("GSF: {e}")))?;
    let channel = fields.remove("Title");
    fields.retain(|k, _| !matches!(k.as_str(), "XRes" | "YRes"));
    Ok(Topography {
        spacing,
        height_unit,
        data: TopographyData::Areal(map),
        channel,
        channels: Vec::new(),
        metadata: fields,
    })
}

/// The `Key = Value` fields of the header and the byte where the data start (the first
/// multiple of 4 after the header's NUL padding begins).
fn read_header(bytes: &[u8]) -> Result<(BTreeMap<String, String>, usize), ParseError> {
    if !bytes.starts_with(MAGIC) {
        return Err(ParseError::malformed(
            "missing `Gwyddion Simple Field 1.0` line",
        ));
    }
    let header_end = bytes
        .iter()
        .position(|&b| b == 0)
        .ok_or_else(|| ParseError::truncated("GSF header (no NUL padding before the data)"))?;
    let data_start = (header_end / 4 + 1) * 4;
    let header = String::from_utf8_lossy(&bytes[MAGIC.len()..header_end]);
    let mut fields = BTreeMap::new();
    for line in header.lines().map(str::trim).filter(|l| !l.is_empty()) {
        let (key, value) = line.split_once('=').ok_or_else(|| {
            ParseError::malformed(format!("GSF header line without `=`: `{line}`"))
        })?;
        fields.insert(key.trim().to_string(), value.trim().to_string());
    }
    Ok((fields, data_start))
}

/// The `nx × ny` float32 heights at `data_start`, in metres (non-finite values are `NaN`).
fn read_heights(
    bytes: &[u8],
    data_start: usize,
    nx: usize,
    ny: usize,
    z_factor: f64,
) -> Result<Vec<f64>, ParseError> {
    let n_bytes = nx
        .checked_mul(ny)
        .and_then(|n| n.checked_mul(4))
        .ok_or_else(|| ParseError::malformed(format!("GSF grid {nx} × {ny} overflows")))?;
    let data = data_start
        .checked_add(n_bytes)
        .and_then(|end| bytes.get(data_start..end))
        .ok_or_else(|| {
            ParseError::truncated(format!(
                "GSF data of {nx} × {ny} float32 at byte {data_start}"
            ))
        })?;
    check_points(nx, ny, "GSF header (XRes × YRes)")?;
    Ok(data
        .chunks_exact(4)
        .map(|c| {
            let v = f32::from_le_bytes([c[0], c[1], c[2], c[3]]);
            if v.is_finite() {
                f64::from(v) * z_factor
            } else {
                f64::NAN
            }
        })
        .collect())
}
