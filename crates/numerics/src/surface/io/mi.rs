//! Molecular Imaging / Agilent PicoView `.mi` reader (image files).
//!
//! Layout (as SurfaceTopography's `MI.py` and Gwyddion's `mifile.c` read it): text lines of a
//! 14-character key field and a value, the first `fileType      Image`; global keys (`xPixels`,
//! `yPixels`, `xLength` / `yLength` in metres, `scanUp`), then one block per channel starting at
//! `bufferLabel` (with `direction`, `bufferRange`, `bufferUnit`); then the line
//! `data          BINARY` (int16) or `data          BINARY_32` (int32), followed by the
//! channels' little-endian integers, `xPixels × yPixels` each, in header order, one scan line
//! after the other. A raw value `r` of `b` bits is `z = r / 2^(b−1) · bufferRange` in
//! `bufferUnit`. With `scanUp TRUE` the first line stored is the bottom one: the rows are
//! flipped so that row 0 is the top line, as PicoView shows it. ASCII data and spectroscopy
//! files are not read.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::limits::check_points;
use super::reader::{pick_channel, Parser, Reader};
use super::text_units::length_unit_to_metres;
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"fileType      Image";
/// Width of the key field of a header line.
const KEY_WIDTH: usize = 14;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "mi",
    description: "Molecular Imaging / Agilent PicoView `.mi` image",
    extensions: &["mi"],
    magic: Some(matches_magic),
    parser: Parser::Channels(parse_channel),
};

/// `true` when `head` starts with `fileType      Image`.
fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

/// One `bufferLabel` block of the header.
struct Buffer {
    label: String,
    fields: BTreeMap<String, String>,
}

/// The parsed header: global keys, channel blocks, sample size and the data offset.
struct Header {
    global: BTreeMap<String, String>,
    buffers: Vec<Buffer>,
    sample_bytes: usize,
    data_start: usize,
}

fn header(bytes: &[u8]) -> Result<Header, ParseError> {
    let mut global = BTreeMap::new();
    let mut buffers: Vec<Buffer> = Vec::new();
    let mut pos = 0;
    loop {
        let end = bytes[pos..]
            .iter()
            .position(|&b| b == b'\n')
            .map(|i| pos + i)
            .ok_or_else(|| ParseError::truncated("MI header: no `data` line"))?;
        let line = String::from_utf8_lossy(&bytes[pos..end]);
        let line = line.trim_end_matches('\r');
        pos = end + 1;
        let split = line
            .char_indices()
            .nth(KEY_WIDTH)
            .map_or(line.len(), |(i, _)| i);
        let (key, value) = (line[..split].trim(), line[split..].trim());
        match key {
            "data" => {
                let sample_bytes = match value {
                    "BINARY" => 2,
                    "BINARY_32" => 4,
                    other => {
                        return Err(ParseError::unsupported(format!(
                            "MI `data {other}` (BINARY and BINARY_32 are read)"
                        )))
                    }
                };
                return Ok(Header {
                    global,
                    buffers,
                    sample_bytes,
                    data_start: pos,
                });
            }
            "bufferLabel" => buffers.push(Buffer {
                label: value.to_string(),
                fields: BTreeMap::new(),
            }),
            "" => {}
            _ => {
                let map = buffers.last_mut().map_or(&mut global, |b| &mut b.fields);
                map.insert(key.to_string(), value.to_string());
            }
        }
    }
}

/// Channel names: the labels, with the scan direction added to a label used more than once
/// ("Friction (Trace)", "Friction (Retrace)").
fn channel_names(buffers: &[Buffer]) -> Vec<String> {
    buffers
        .iter()
        .map(|b| {
            let repeated = buffers.iter().filter(|o| o.label == b.label).count() > 1;
            match b.fields.get("direction") {
                Some(d) if repeated => format!("{} ({d})", b.label),
                _ => b.label.clone(),
            }
        })
        .collect()
}

fn number(map: &BTreeMap<String, String>, key: &str) -> Result<f64, ParseError> {
    let v = map
        .get(key)
        .ok_or_else(|| ParseError::malformed(format!("MI header has no `{key}`")))?;
    v.parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
        .ok_or_else(|| ParseError::malformed(format!("MI `{key} {v}` is not a number")))
}

fn count(map: &BTreeMap<String, String>, key: &str) -> Result<usize, ParseError> {
    let v = map.get(key).map(String::as_str).unwrap_or_default();
    v.parse::<usize>()
        .map_err(|_| ParseError::malformed(format!("MI `{key} {v}` is not a count")))
}

/// Parses the channel named `channel` (default: `Topography`, else the first channel).
fn parse_channel(bytes: &[u8], channel: Option<&str>) -> Result<Topography, ParseError> {
    if !matches_magic(bytes) {
        return Err(ParseError::malformed(
            "MI file does not start with `fileType      Image` (spectroscopy is not read)",
        ));
    }
    let h = header(bytes)?;
    let names = channel_names(&h.buffers);
    let index = pick_channel(&names, channel, &["Topography"])?;
    let buffer = &h.buffers[index];
    let name = &names[index];
    let unit = buffer.fields.get("bufferUnit").cloned().unwrap_or_default();
    let z_factor = length_unit_to_metres(&unit).ok_or_else(|| {
        ParseError::unsupported(format!(
            "MI channel `{name}` is in `{unit}`, not a length: not a topography"
        ))
    })?;
    let (nx, ny) = (count(&h.global, "xPixels")?, count(&h.global, "yPixels")?);
    let data = channel_data(bytes, &h, index, name, nx, ny)?;
    let scale = number(&buffer.fields, "bufferRange")? * z_factor
        / 2f64.powi(8 * h.sample_bytes as i32 - 1);
    let values: Vec<f64> = data
        .chunks_exact(h.sample_bytes)
        .map(|c| {
            let raw = if h.sample_bytes == 2 {
                f64::from(i16::from_le_bytes([c[0], c[1]]))
            } else {
                f64::from(i32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            };
            raw * scale
        })
        .collect();
    let values = if h.global.get("scanUp").is_some_and(|v| v == "TRUE") {
        values.chunks(nx.max(1)).rev().flatten().copied().collect()
    } else {
        values
    };
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("MI array shape: {e}")))?;
    let (lx, ly) = (number(&h.global, "xLength")?, number(&h.global, "yLength")?);
    let map = HeightMap::new(heights, lx / nx as f64, ly / ny as f64)
        .map_err(|e| ParseError::malformed(format!("MI channel `{name}`: {e}")))?;
    Ok(Topography {
        data: TopographyData::Areal(map),
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        channel: Some(name.clone()),
        channels: names,
        metadata: metadata(&h.global, unit),
    })
}

/// The raw samples of channel `index` (`name`): the file must hold every channel's
/// `nx × ny` samples after the header.
fn channel_data<'a>(
    bytes: &'a [u8],
    h: &Header,
    index: usize,
    name: &str,
    nx: usize,
    ny: usize,
) -> Result<&'a [u8], ParseError> {
    let points = check_points(nx, ny, "MI header (xPixels × yPixels)")?;
    let block = points * h.sample_bytes;
    let end = block
        .checked_mul(h.buffers.len())
        .and_then(|t| t.checked_add(h.data_start));
    if end.is_none_or(|end| end > bytes.len()) {
        return Err(ParseError::truncated(format!(
            "MI data: {} channels of {nx} × {ny} samples of {} bytes after byte {}, file of {} \
             bytes",
            h.buffers.len(),
            h.sample_bytes,
            h.data_start,
            bytes.len()
        )));
    }
    index
        .checked_mul(block)
        .and_then(|o| o.checked_add(h.data_start))
        .and_then(|start| bytes.get(start..start.checked_add(block)?))
        .ok_or_else(|| {
            ParseError::truncated(format!(
                "MI channel `{name}`: {nx} × {ny} samples of {} bytes",
                h.sample_bytes
            ))
        })
}

/// The vendor, software version, date and mode of the global keys, and the height unit.
fn metadata(global: &BTreeMap<String, String>, unit: String) -> BTreeMap<String, String> {
    let mut metadata = BTreeMap::new();
    metadata.insert(super::METADATA_VENDOR.into(), "Molecular Imaging".into());
    for (key, meta) in [
        ("version", "software_version"),
        ("dateAcquired", "date"),
        ("mode", "operating_mode"),
    ] {
        if let Some(v) = global.get(key) {
            metadata.insert(meta.into(), v.clone());
        }
    }
    metadata.insert("original_z_unit".into(), unit);
    metadata
}
