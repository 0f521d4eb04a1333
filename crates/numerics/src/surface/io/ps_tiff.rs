//! Park Systems (PSIA) TIFF reader (`.tif`, `.tiff` from Park SmartScan / XEI).
//!
//! The baseline TIFF image is only an 8-bit preview; the measurement sits in four private tags
//! of the first image directory (Gwyddion's `psia.c`, SurfaceTopography's `PS.py`):
//! 50432 magic `0x0E031301`, 50433 version (`0x01000001`: int16 data, `0x01000002`: data type
//! in the header), 50434 the data, 50435 a little-endian header of at least 356 (version 1) or
//! 580 (version 2) bytes. Header fields used, by byte offset: image type (`u32` at 0, 0 = 2-D
//! map), source name (32 UTF-16 characters at 4), `nx`, `ny` (`u32` at 100, 104), scan sizes
//! in µm (`f64` at 140, 148), data gain, z scale and z offset (`f64` at 220, 228, 236), data
//! unit (8 UTF-16 characters at 244), compression (`u32` at 272), and for version 2 the data type
//! (`u32` at 348: 0 int16, 1 int32, 2 float32).
//!
//! Heights: `z = unit · gain · (raw · z_scale + z_offset)` (Gwyddion; a zero z scale means 1);
//! lateral spacing `dx = size_x / nx`. Rows follow one another with x fastest.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{decode_samples, ByteCursor, Endian, SampleType};
use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::text_units::length_unit_to_metres;
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const PARK_MAGIC: u32 = 0x0E03_1301;
const TAG_MAGIC: u16 = 50432;
const TAG_VERSION: u16 = 50433;
const TAG_DATA: u16 = 50434;
const TAG_HEADER: u16 = 50435;
/// Most directory entries read (a TIFF directory has a few dozen).
const MAX_ENTRIES: usize = 4096;

/// One entry of a TIFF image file directory.
struct Entry {
    tag: u16,
    kind: u16,
    count: usize,
    /// Where the entry's 4 value bytes sit in the file: the value itself, or the offset of
    /// the values.
    value_at: usize,
}

fn tiff_endian(head: &[u8]) -> Option<Endian> {
    match head.get(..4)? {
        b"II*\0" => Some(Endian::Little),
        b"MM\0*" => Some(Endian::Big),
        _ => None,
    }
}

/// The entries of the first image directory.
fn first_directory(bytes: &[u8]) -> Result<(Endian, Vec<Entry>), ParseError> {
    let e = tiff_endian(bytes).ok_or_else(|| ParseError::malformed("not a TIFF file"))?;
    let mut c = ByteCursor::new(bytes);
    c.seek(4, "TIFF directory offset")?;
    let offset = c.u32(e, "TIFF directory offset")? as usize;
    c.seek(offset, "TIFF directory")?;
    let n = usize::from(c.u16(e, "TIFF directory entry count")?);
    if n > MAX_ENTRIES {
        return Err(ParseError::malformed(format!(
            "TIFF directory of {n} entries (at most {MAX_ENTRIES} are read)"
        )));
    }
    let mut entries = Vec::with_capacity(n);
    for _ in 0..n {
        let tag = c.u16(e, "TIFF entry tag")?;
        let kind = c.u16(e, "TIFF entry type")?;
        let count = c.u32(e, "TIFF entry count")? as usize;
        let value_at = offset + 2 + 12 * entries.len() + 8;
        c.take(4, "TIFF entry value")?;
        entries.push(Entry {
            tag,
            kind,
            count,
            value_at,
        });
    }
    Ok((e, entries))
}

/// The value bytes of the entry `tag` (inline or at its offset).
fn tag_bytes<'a>(
    bytes: &'a [u8],
    e: Endian,
    entries: &[Entry],
    tag: u16,
) -> Result<&'a [u8], ParseError> {
    let entry = entries
        .iter()
        .find(|en| en.tag == tag)
        .ok_or_else(|| ParseError::malformed(format!("Park TIFF has no tag {tag}")))?;
    let unit = match entry.kind {
        1 | 2 | 6 | 7 => 1,
        3 | 8 => 2,
        4 | 9 | 11 => 4,
        5 | 10 | 12 => 8,
        k => {
            return Err(ParseError::malformed(format!(
                "TIFF tag {tag} has type {k}"
            )))
        }
    };
    let len = entry
        .count
        .checked_mul(unit)
        .ok_or_else(|| ParseError::malformed(format!("TIFF tag {tag} size overflows")))?;
    let mut c = ByteCursor::new(bytes);
    c.seek(entry.value_at, "TIFF entry value")?;
    if len <= 4 {
        return c.take(len, &format!("TIFF tag {tag}"));
    }
    let offset = c.u32(e, "TIFF entry value")? as usize;
    c.seek(offset, &format!("TIFF tag {tag}"))?;
    c.take(len, &format!("TIFF tag {tag} ({len} bytes)"))
}

fn tag_u32(bytes: &[u8], e: Endian, entries: &[Entry], tag: u16) -> Result<u32, ParseError> {
    let raw = tag_bytes(bytes, e, entries, tag)?;
    ByteCursor::new(raw).u32(e, &format!("TIFF tag {tag}"))
}

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "park-tiff",
    description: "Park Systems TIFF (`.tiff`, data in private tags)",
    extensions: &["tif", "tiff"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` is a TIFF whose first directory carries the Park Systems magic tag.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    first_directory(head)
        .and_then(|(e, entries)| tag_u32(head, e, &entries, TAG_MAGIC))
        .is_ok_and(|m| m == PARK_MAGIC)
}

/// `chars` UTF-16LE characters, up to the first NUL, trimmed.
fn utf16(raw: &[u8]) -> String {
    let units = raw
        .chunks_exact(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .take_while(|&u| u != 0);
    char::decode_utf16(units)
        .map(|c| c.unwrap_or(char::REPLACEMENT_CHARACTER))
        .collect::<String>()
        .trim()
        .to_string()
}

/// The Park header (tag 50435), its version and the data bytes (tag 50434).
fn park_tags(bytes: &[u8]) -> Result<(&[u8], u32, &[u8]), ParseError> {
    let (e, entries) = first_directory(bytes)?;
    if tag_u32(bytes, e, &entries, TAG_MAGIC)? != PARK_MAGIC {
        return Err(ParseError::malformed(
            "TIFF without the Park Systems magic tag",
        ));
    }
    let version = tag_u32(bytes, e, &entries, TAG_VERSION)?;
    let min_header = match version {
        0x0100_0001 => 356,
        0x0100_0002 => 580,
        v => {
            return Err(ParseError::unsupported(format!(
                "Park TIFF version {v:#x} (versions 0x1000001 and 0x1000002 are read)"
            )))
        }
    };
    let header = tag_bytes(bytes, e, &entries, TAG_HEADER)?;
    if header.len() < min_header {
        return Err(ParseError::truncated(format!(
            "Park TIFF header of {} bytes, version {version:#x} needs {min_header}",
            header.len()
        )));
    }
    let data = tag_bytes(bytes, e, &entries, TAG_DATA)?;
    Ok((header, version, data))
}

/// Parses a Park Systems TIFF into heights in metres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let (header, version, data) = park_tags(bytes)?;
    let le = Endian::Little;
    let at = |offset: usize| {
        let mut c = ByteCursor::new(header);
        c.seek(offset, "Park header field").map(|()| c)
    };
    let u32_at = |o: usize| at(o)?.u32(le, "Park header field");
    let f64_at = |o: usize| at(o)?.f64(le, "Park header field");
    if u32_at(0)? != 0 {
        return Err(ParseError::unsupported(
            "Park TIFF holding a line profile or spectroscopy (only 2-D maps are read)",
        ));
    }
    if u32_at(272)? != 0 {
        return Err(ParseError::unsupported("compressed Park TIFF data"));
    }
    let (nx, ny) = (u32_at(100)? as usize, u32_at(104)? as usize);
    let n = check_points(nx, ny, "Park TIFF header (nx × ny)")?;
    let sample = match (version, u32_at(348).unwrap_or(0)) {
        (0x0100_0001, _) | (_, 0) => SampleType::I16,
        (_, 1) => SampleType::I32,
        (_, 2) => SampleType::F32,
        (_, t) => return Err(ParseError::malformed(format!("Park TIFF data type {t}"))),
    };
    let unit_name = utf16(&header[244..260]);
    let unit = length_unit_to_metres(&unit_name).ok_or_else(|| {
        ParseError::unsupported(format!(
            "Park TIFF data unit `{unit_name}` is not a length (a topography needs heights)"
        ))
    })?;
    let (gain, scale, offset) = (f64_at(220)?, f64_at(228)?, f64_at(236)?);
    let scale = if scale == 0.0 { 1.0 } else { scale };
    let values = decode_samples(data, n, sample, le, "Park TIFF data")?
        .into_iter()
        .map(|raw| unit * gain * (raw * scale + offset))
        .map(|z| if z.is_finite() { z } else { f64::NAN })
        .collect();
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|err| ParseError::malformed(format!("Park TIFF array shape: {err}")))?;
    let (sx, sy) = (f64_at(140)? * 1e-6, f64_at(148)? * 1e-6);
    let map = HeightMap::new(heights, sx / nx as f64, sy / ny as f64)
        .map_err(|err| ParseError::malformed(format!("Park TIFF: {err}")))?;
    let mut metadata = BTreeMap::new();
    metadata.insert("vendor".into(), "Park Systems".into());
    metadata.insert("image_mode".into(), utf16(&header[68..84]));
    metadata.insert("data_unit".into(), unit_name);
    metadata.insert("data_gain".into(), gain.to_string());
    if version == 0x0100_0002 {
        metadata.insert("cantilever".into(), utf16(&header[376..408]));
    }
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: Some(utf16(&header[4..68])),
        channels: Vec::new(),
        metadata,
    })
}
