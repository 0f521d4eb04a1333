//! Nanotec WSxM image reader (`.top`, `.stp`, and other single-image WSxM files).
//!
//! Layout (as read by Gwyddion's `wsxmfile.c` and SurfaceTopography's `WSXM.py`): Latin-1 text
//! lines `WSxM file copyright …`, `SxM Image file`, `Image header size: N`, then `[Section]`
//! lines and `key: value` lines up to `[Header end]`; the data start at byte `N`. `[General
//! Info]` gives `Number of columns`, `Number of rows`, `Image Data Type` (`short` = int16,
//! `float` = float32, `double` = float64, all little-endian) and `Z Amplitude: <value> <unit>`;
//! `[Control]` gives `X Amplitude`, `Y Amplitude` (full scan sizes with units). Rows follow one
//! another with x fastest.
//!
//! Height scale:
//! * **integer data** (`short`): counts scaled so that their range spans the Z Amplitude,
//!   `z = count · A / (Maximum − Minimum)` with `[Miscellaneous] Maximum/Minimum` (the count
//!   range; the data's own range when those are missing), as Gwyddion and SurfaceTopography do;
//! * **floating-point data** (`float`, `double`) are already in the unit of the Z Amplitude and
//!   are used as stored (SurfaceTopography ≥ 1.27). Rescaling them by `A / (Maximum − Minimum)`,
//!   as SurfaceTopography 1.22 did, would rest on the 6-digit header values.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{decode_samples, Endian, SampleType};
use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::text_units::length_unit_to_metres;
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"WSxM file copyright";
const IMAGE: &str = "SxM Image file";
const SIZE_KEY: &str = "Image header size:";
/// Largest header accepted, bytes.
const MAX_HEADER: usize = 1 << 20;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "wsxm",
    description: "Nanotec WSxM image `.top`, `.stp`",
    extensions: &["top", "stp"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` starts with the WSxM copyright line.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

/// `Section::key` → value from the header text.
fn header_fields(text: &str) -> Result<BTreeMap<String, String>, ParseError> {
    let mut fields = BTreeMap::new();
    let mut section: Option<&str> = None;
    for line in text.lines().skip(3).map(str::trim) {
        if line.is_empty() {
            continue;
        }
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            if name == "Header end" {
                return Ok(fields);
            }
            section = Some(name);
            continue;
        }
        if let (Some(section), Some((key, value))) = (section, line.split_once(':')) {
            fields.insert(
                format!("{section}::{}", key.trim()),
                value.trim().to_string(),
            );
        }
    }
    Err(ParseError::truncated(
        "WSxM header (no `[Header end]` line before the data)",
    ))
}

/// `"600 nm"` → (600, metres per unit); `what` names the field.
fn amplitude(value: &str, what: &str) -> Result<(f64, f64), ParseError> {
    let (number, unit) = value.split_once(' ').unwrap_or((value, ""));
    let x: f64 = number
        .trim()
        .parse()
        .ok()
        .filter(|x: &f64| x.is_finite() && *x > 0.0)
        .ok_or_else(|| {
            ParseError::malformed(format!("WSxM {what} `{value}` is not a positive number"))
        })?;
    let factor = length_unit_to_metres(unit).ok_or_else(|| {
        ParseError::unsupported(format!(
            "WSxM {what} unit `{}` is not a length (a topography needs heights)",
            unit.trim()
        ))
    })?;
    Ok((x, factor))
}

/// The header fields (`Section::key` → value) and the header size in bytes.
fn read_header(bytes: &[u8]) -> Result<(BTreeMap<String, String>, usize), ParseError> {
    if !bytes.starts_with(MAGIC) {
        return Err(ParseError::malformed("missing `WSxM file copyright` line"));
    }
    let latin1 = |b: &[u8]| -> String { b.iter().map(|&c| char::from(c)).collect() };
    let preamble = latin1(&bytes[..bytes.len().min(512)]);
    let mut lines = preamble.lines().map(str::trim);
    if lines.nth(1) != Some(IMAGE) {
        return Err(ParseError::unsupported(format!(
            "WSxM file whose second line is not `{IMAGE}` (curves and 3-D data are not read)"
        )));
    }
    let size_line = lines.next().unwrap_or_default();
    let header_size = size_line
        .strip_prefix(SIZE_KEY)
        .and_then(|v| v.trim().parse::<usize>().ok())
        .ok_or_else(|| {
            ParseError::malformed(format!(
                "WSxM third line `{size_line}` is not `{SIZE_KEY} N`"
            ))
        })?;
    if header_size > MAX_HEADER {
        return Err(ParseError::malformed(format!(
            "WSxM header size {header_size} is more than {MAX_HEADER} bytes"
        )));
    }
    if header_size > bytes.len() {
        return Err(ParseError::truncated(format!(
            "WSxM header of {header_size} bytes, the file has {}",
            bytes.len()
        )));
    }
    let fields = header_fields(&latin1(&bytes[..header_size]))?;
    Ok((fields, header_size))
}

/// Parses a WSxM image file into heights in metres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let (fields, header_size) = read_header(bytes)?;
    let get = |key: &str| {
        fields
            .get(key)
            .ok_or_else(|| ParseError::malformed(format!("WSxM header has no `{key}`")))
    };
    let count = |key: &str| -> Result<usize, ParseError> {
        let v = get(key)?;
        v.parse()
            .map_err(|_| ParseError::malformed(format!("WSxM {key} `{v}` is not an integer")))
    };
    let nx = count("General Info::Number of columns")?;
    let ny = count("General Info::Number of rows")?;
    let n = check_points(nx, ny, "WSxM header (columns × rows)")?;
    let data_type = get("General Info::Image Data Type")?;
    let sample = match data_type.as_str() {
        "short" => SampleType::I16,
        "float" => SampleType::F32,
        "double" => SampleType::F64,
        other => {
            return Err(ParseError::unsupported(format!(
                "WSxM Image Data Type `{other}` (short, float and double are read)"
            )))
        }
    };
    let (lx, x_unit) = amplitude(get("Control::X Amplitude")?, "X Amplitude")?;
    let (ly, y_unit) = amplitude(get("Control::Y Amplitude")?, "Y Amplitude")?;
    let (z_amplitude, z_unit) = amplitude(get("General Info::Z Amplitude")?, "Z Amplitude")?;
    let raw = decode_samples(
        &bytes[header_size..],
        n,
        sample,
        Endian::Little,
        "WSxM data",
    )?;
    let z_factor = if sample.is_integer() {
        z_unit * z_amplitude / count_range(&fields, &raw)?
    } else {
        z_unit
    };
    let values = raw
        .into_iter()
        .map(|v| {
            if v.is_finite() {
                v * z_factor
            } else {
                f64::NAN
            }
        })
        .collect();
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("WSxM array shape: {e}")))?;
    let map = HeightMap::new(heights, lx * x_unit / nx as f64, ly * y_unit / ny as f64)
        .map_err(|e| ParseError::malformed(format!("WSxM: {e}")))?;
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: fields.get("General Info::Acquisition channel").cloned(),
        channels: Vec::new(),
        metadata: metadata(&fields),
    })
}

/// `Maximum − Minimum` of the integer counts: from the header, else from the data.
fn count_range(fields: &BTreeMap<String, String>, raw: &[f64]) -> Result<f64, ParseError> {
    let header = |key: &str| fields.get(key).and_then(|v| v.parse::<f64>().ok());
    let range = match (
        header("Miscellaneous::Maximum"),
        header("Miscellaneous::Minimum"),
    ) {
        (Some(max), Some(min)) => max - min,
        _ => {
            let (min, max) = raw
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                    (a.min(v), b.max(v))
                });
            max - min
        }
    };
    if range.is_finite() && range > 0.0 {
        Ok(range)
    } else {
        Err(ParseError::malformed(format!(
            "WSxM count range Maximum − Minimum = {range} must be > 0 to scale integer data to \
             the Z Amplitude"
        )))
    }
}

fn metadata(fields: &BTreeMap<String, String>) -> BTreeMap<String, String> {
    let mut metadata = BTreeMap::new();
    metadata.insert("vendor".into(), "Nanotec Electronica (WSxM)".into());
    for (key, name) in [
        ("General Info::Acquisition time", "acquisition_time"),
        ("General Info::Head type", "head_type"),
        ("General Info::Z Amplitude", "z_amplitude"),
        ("Miscellaneous::Comments", "comment"),
        ("Miscellaneous::Dulcinea serial number", "serial_number"),
        ("Miscellaneous::Saved with version", "software_version"),
    ] {
        if let Some(v) = fields.get(key) {
            metadata.insert(name.into(), v.clone());
        }
    }
    metadata
}
