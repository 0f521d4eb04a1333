//! Igor Pro binary wave (`.ibw`) reader, as written by Asylum Research (Oxford Instruments) AFMs.
//!
//! Layout (WaveMetrics Technical Note 003, "Igor Binary Format"; Gwyddion's `igorfile.c`):
//! version 5 only (older versions hold no 2-D data). A 64-byte `BinHeader5` (version, checksum,
//! `wfmSize`, then the sizes of the blocks after the data: formula, note, extended data units,
//! extended units of the 4 dimensions, labels of the 4 dimensions, string indices, options) and
//! a 320-byte `WaveHeader5` (`npnts` at 12, `type` at 16, `bname[32]` at 28, `nDim[4]` at 68,
//! `sfA[4]` at 84, `sfB[4]` at 116, `dataUnits[4]` at 148, `dimUnits[4][4]` at 152), then the
//! data. The byte order is the one in which the version reads 5; the 16-bit words of both
//! headers sum to 0 (the checksum), which rejects damaged headers.
//!
//! The data are a `nDim[0] × nDim[1] × layers` array, dimension 0 fastest: each layer is one
//! channel, `nDim[0]` points along x and `nDim[1]` along y, spacings `sfA[0]`, `sfA[1]` in the
//! dimension units. Channel names are the dimension-2 labels (32 bytes each, label 0 names the
//! dimension itself); an unnamed layer `k` is `no name (k)`, as SurfaceTopography names it.
//! One data unit covers every layer, so a layer whose name says it is not a height (`Phase`,
//! `Potential`, `Current`, `Frequency`, …: Asylum saves them under the wave's unit `m`) is
//! refused rather than read as metres. A wave without units gets 1 m per index step and metres
//! ([`ScaleSource::Assumed`]).

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{check_block_size, decode_samples, ByteCursor, Endian, SampleType};
use super::limits::check_points;
use super::reader::{pick_channel, Parser, Reader};
use super::text_units::length_unit_to_metres;
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const BIN_HEADER: usize = 64;
const WAVE_HEADER: usize = 320;
const LABEL: usize = 32;
/// Channels read when none is named (Asylum's height and Z-sensor images), else the first.
const DEFAULT_CHANNELS: [&str; 4] = [
    "HeightTrace",
    "ZSensorTrace",
    "HeightRetrace",
    "ZSensorRetrace",
];
/// Words in a channel name that mark a quantity other than a height.
const NOT_HEIGHT: &[&str] = &[
    "Phase",
    "Potential",
    "Current",
    "Frequency",
    "Drive",
    "Bias",
    "Voltage",
    "Dissipation",
];

/// The headers of a version-5 wave.
struct Wave<'a> {
    endian: Endian,
    sample: SampleType,
    dims: [usize; 4],
    spacing: [f64; 2],
    data_unit: String,
    dim_units: [String; 2],
    name: String,
    /// The wave data.
    data: &'a [u8],
    channels: Vec<String>,
    note: String,
}

/// The byte order in which the version field reads 5.
fn endian_of(head: &[u8]) -> Option<Endian> {
    match head.get(..2)? {
        [5, 0] => Some(Endian::Little),
        [0, 5] => Some(Endian::Big),
        _ => None,
    }
}

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "ibw",
    description: "Igor Pro binary wave `.ibw` (Asylum Research AFM; one channel per layer)",
    extensions: &["ibw"],
    magic: Some(matches_magic),
    parser: Parser::Channels(parse_channel),
};

/// `true` when the headers at the start of `head` are a version-5 wave with a valid checksum.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    endian_of(head).is_some_and(|e| checksum_ok(head, e))
}

fn checksum_ok(bytes: &[u8], endian: Endian) -> bool {
    let Some(headers) = bytes.get(..BIN_HEADER + WAVE_HEADER) else {
        return false;
    };
    let sum = headers.chunks_exact(2).fold(0u16, |acc, w| {
        let word = match endian {
            Endian::Little => u16::from_le_bytes([w[0], w[1]]),
            Endian::Big => u16::from_be_bytes([w[0], w[1]]),
        };
        acc.wrapping_add(word)
    });
    sum == 0
}

fn sample_type(code: u16) -> Result<SampleType, ParseError> {
    Ok(match code {
        0x02 => SampleType::F32,
        0x04 => SampleType::F64,
        0x08 => SampleType::I8,
        0x10 => SampleType::I16,
        0x20 => SampleType::I32,
        0x48 => SampleType::U8,
        0x50 => SampleType::U16,
        0x60 => SampleType::U32,
        0x00 => return Err(ParseError::unsupported("IBW text wave (no numbers)")),
        c if c & 0x01 != 0 => return Err(ParseError::unsupported("IBW complex wave")),
        c => {
            return Err(ParseError::malformed(format!(
                "IBW wave type {c:#x} is unknown"
            )))
        }
    })
}

/// NUL-terminated Latin-1 text.
fn text(raw: &[u8]) -> String {
    let end = raw.iter().position(|&b| b == 0).unwrap_or(raw.len());
    raw[..end]
        .iter()
        .map(|&b| char::from(b))
        .collect::<String>()
        .trim()
        .to_string()
}

/// The byte order of a version-5 wave whose headers are complete and pass their checksum.
fn checked_endian(bytes: &[u8]) -> Result<Endian, ParseError> {
    let endian = endian_of(bytes).ok_or_else(|| {
        ParseError::malformed("IBW version is not 5 (only version-5 waves hold 2-D data)")
    })?;
    if bytes.len() < BIN_HEADER + WAVE_HEADER {
        return Err(ParseError::truncated(format!(
            "IBW headers need {} bytes, the file has {}",
            BIN_HEADER + WAVE_HEADER,
            bytes.len()
        )));
    }
    if !checksum_ok(bytes, endian) {
        return Err(ParseError::malformed(
            "IBW header checksum does not match (damaged header)",
        ));
    }
    Ok(endian)
}

fn read_wave(bytes: &[u8]) -> Result<Wave<'_>, ParseError> {
    let endian = checked_endian(bytes)?;
    let mut c = ByteCursor::new(bytes);
    c.seek(4, "IBW wfmSize")?;
    let mut size =
        || -> Result<usize, ParseError> { Ok(c.u32(endian, "IBW block size")? as usize) };
    let wfm_size = size()?;
    let mut blocks = [0usize; 14];
    for b in &mut blocks {
        *b = size()?;
    }
    let [formula, note_size, data_e_units, de0, de1, de2, de3, l0, l1, l2, ..] = blocks;
    let w = BIN_HEADER;
    c.seek(w + 16, "IBW type")?;
    let sample = sample_type(c.u16(endian, "IBW type")?)?;
    c.seek(w + 28, "IBW name")?;
    let name = text(c.take(32, "IBW name")?);
    c.seek(w + 68, "IBW nDim")?;
    let mut dims = [0usize; 4];
    for d in &mut dims {
        *d = c.u32(endian, "IBW nDim")? as usize;
    }
    let spacing = [c.f64(endian, "IBW sfA")?, c.f64(endian, "IBW sfA")?];
    c.seek(w + 148, "IBW units")?;
    let data_unit = text(c.take(4, "IBW dataUnits")?);
    let dim_units = [
        text(c.take(4, "IBW dimUnits")?),
        text(c.take(4, "IBW dimUnits")?),
    ];
    let data_bytes = wfm_size.checked_sub(WAVE_HEADER).ok_or_else(|| {
        ParseError::malformed(format!(
            "IBW wfmSize {wfm_size} is smaller than the wave header"
        ))
    })?;
    c.seek(BIN_HEADER + WAVE_HEADER, "IBW data")?;
    let data = c.take(data_bytes, "IBW wave data")?;
    c.take(formula, "IBW formula")?;
    let note = text(c.take(note_size, "IBW note")?);
    let data_unit = match data_e_units {
        0 => data_unit,
        n => text(c.take(n, "IBW extended data units")?),
    };
    let dim_e = [
        text(c.take(de0, "IBW x units")?),
        text(c.take(de1, "IBW y units")?),
    ];
    c.take(de2 + de3, "IBW extended units")?;
    let dim_units = [0, 1].map(|d| {
        if dim_e[d].is_empty() {
            dim_units[d].clone()
        } else {
            dim_e[d].clone()
        }
    });
    c.take(l0 + l1, "IBW dimension labels")?;
    let labels = c.take(l2, "IBW layer labels")?;
    let layers = dims[2].max(1);
    let n = check_points(dims[0], dims[1], "IBW nDim")?;
    let total = n
        .checked_mul(layers)
        .ok_or_else(|| ParseError::malformed(format!("IBW nDim {} overflows", dims_text(&dims))))?;
    check_block_size(total, sample.size(), data.len(), "IBW wave data")?;
    let channels = channel_names_from(labels, layers);
    Ok(Wave {
        endian,
        sample,
        dims,
        spacing,
        data_unit,
        dim_units,
        name,
        data,
        channels,
        note,
    })
}

/// `256 × 256 × 8 × 0`.
fn dims_text(dims: &[usize; 4]) -> String {
    dims.map(|d| d.to_string()).join(" × ")
}

/// Layer names from the dimension-2 labels; unnamed layers are `no name (k)`.
fn channel_names_from(labels: &[u8], layers: usize) -> Vec<String> {
    let mut unnamed = 0;
    (0..layers.min(1 << 16))
        .map(|i| {
            let start = (i + 1) * LABEL;
            let name = labels
                .get(start..start + LABEL)
                .map(text)
                .unwrap_or_default();
            if name.is_empty() {
                unnamed += 1;
                format!("no name ({unnamed})")
            } else {
                name
            }
        })
        .collect()
}

/// Metres per unit, `None` for an empty unit (not stated); `what` names the field.
fn unit_factor(unit: &str, what: &str) -> Result<Option<f64>, ParseError> {
    if unit.is_empty() {
        return Ok(None);
    }
    length_unit_to_metres(unit)
        .map(Some)
        .ok_or_else(|| ParseError::unsupported(format!("IBW {what} unit `{unit}` is not a length")))
}

/// Parses the channel named `channel` (ASCII case ignored; the default one for `None`),
/// heights in metres.
fn parse_channel(bytes: &[u8], channel: Option<&str>) -> Result<Topography, ParseError> {
    let wave = read_wave(bytes)?;
    let [nx, ny, _, d3] = wave.dims;
    if nx < 2 || ny < 2 || d3 > 1 {
        return Err(ParseError::unsupported(format!(
            "IBW wave of {} points is not a stack of 2-D images",
            dims_text(&wave.dims)
        )));
    }
    let index = pick_channel(&wave.channels, channel, &DEFAULT_CHANNELS)?;
    let name = &wave.channels[index];
    if let Some(word) = NOT_HEIGHT.iter().find(|w| name.contains(**w)) {
        let heights: Vec<String> = wave
            .channels
            .iter()
            .filter(|c| !NOT_HEIGHT.iter().any(|w| c.contains(w)))
            .map(|c| format!("`{c}`"))
            .collect();
        return Err(ParseError::unsupported(format!(
            "IBW channel `{name}` is a {} signal, not a height; set `channel:` to a height \
             channel ({})",
            word.to_lowercase(),
            heights.join(", ")
        )));
    }
    let n = nx * ny;
    let start = index * n * wave.sample.size();
    let layer = &wave.data[start..];
    let z_unit = unit_factor(&wave.data_unit, "data")?;
    let x_unit = unit_factor(&wave.dim_units[0], "x")?;
    let y_unit = unit_factor(&wave.dim_units[1], "y")?;
    let z = z_unit.unwrap_or(1.0);
    let values = decode_samples(layer, n, wave.sample, wave.endian, "IBW layer")?
        .into_iter()
        .map(|v| if v.is_finite() { v * z } else { f64::NAN })
        .collect();
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("IBW array shape: {e}")))?;
    let dx = wave.spacing[0] * x_unit.unwrap_or(1.0);
    let dy = wave.spacing[1] * y_unit.or(x_unit).unwrap_or(1.0);
    let map =
        HeightMap::new(heights, dx, dy).map_err(|e| ParseError::malformed(format!("IBW: {e}")))?;
    let source = |known: bool| {
        if known {
            ScaleSource::File
        } else {
            ScaleSource::Assumed
        }
    };
    Ok(Topography {
        spacing: source(x_unit.is_some()),
        height_unit: source(z_unit.is_some()),
        data: TopographyData::Areal(map),
        channel: Some(name.clone()),
        channels: wave.channels.clone(),
        metadata: metadata(&wave),
    })
}

/// The wave name and the instrument lines of the note (`key: value`, CR-separated).
fn metadata(wave: &Wave) -> BTreeMap<String, String> {
    let mut metadata = BTreeMap::new();
    metadata.insert("wave_name".into(), wave.name.clone());
    for line in wave.note.split(['\r', '\n']) {
        let Some((key, value)) = line.split_once(':') else {
            continue;
        };
        let name = match key.trim() {
            "MicroscopeModel" => "instrument",
            "IgorFileVersion" => "igor_version",
            "Version" => "software_version",
            "Date" => "date",
            "ImagingMode" => "imaging_mode",
            _ => continue,
        };
        metadata.insert(name.into(), value.trim().to_string());
    }
    if metadata.contains_key("instrument") {
        metadata.insert("vendor".into(), "Asylum Research".into());
    }
    metadata
}
