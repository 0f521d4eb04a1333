//! FRT MicroProf `.frt` reader (Fries Research & Technology profilometers).
//!
//! Layout (little-endian; as Gwyddion's `microprof.c` and SurfaceTopography's `FRT.py` read
//! it): the magic `FRTM_GLIDERV` and a 4-character version (`1.00`, `1.01`), a u16 block count,
//! then the blocks, each `u16 id · size · body` with a u32 size (1.00) or a u64 size (1.01).
//! Block `0x66` holds `nx`, `ny` (u32) and the bits per sample (u32: 16 = u16, 32 = i32);
//! `0x67` the map's physical size `Lx`, `Ly` (f64, m); `0x6c` a u32 range and the height scale
//! (f64, m per count); `0x0b` the heights, `nx × ny` samples one row of `nx` after the other;
//! `0x8e` the serial number (u32 length, text). A raw value of 1 marks an invalid point (`NaN`);
//! raw 0 is a valid height, as SurfaceTopography reads it.
//!
//! Every block must lie inside the file (a cut file is an error); a file may end, as some
//! writers leave it, right after a block although the count announces more.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{ByteCursor, Endian};
use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"FRTM_GLIDERV";
/// Raw value of an invalid point.
const INVALID_RAW: i64 = 1;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "frt",
    description: "FRT MicroProf `.frt`",
    extensions: &["frt"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` starts with `FRTM_GLIDERV`.
fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

/// The blocks of the file by id (the first of each id), as byte slices.
fn blocks(bytes: &[u8]) -> Result<BTreeMap<u16, &[u8]>, ParseError> {
    let le = Endian::Little;
    let mut c = ByteCursor::new(bytes);
    c.take(MAGIC.len(), "FRT magic")?;
    let version = c.text(4, "FRT version")?;
    let wide = match version.as_str() {
        "1.00" => false,
        "1.01" => true,
        other => {
            return Err(ParseError::unsupported(format!(
                "FRT version `{other}` (1.00 and 1.01 are read)"
            )))
        }
    };
    let count = c.u16(le, "FRT block count")?;
    let mut found = BTreeMap::new();
    for i in 0..count {
        if c.remaining() == 0 {
            break;
        }
        let what = format!("FRT block {i} of {count}");
        let id = c.u16(le, &what)?;
        let size = if wide {
            let lo = u64::from(c.u32(le, &what)?);
            let hi = u64::from(c.u32(le, &what)?);
            lo | hi << 32
        } else {
            u64::from(c.u32(le, &what)?)
        };
        let size = usize::try_from(size).unwrap_or(usize::MAX);
        let body = c.take(size, &format!("{what} (id {id:#06x}, {size} bytes)"))?;
        found.entry(id).or_insert(body);
    }
    Ok(found)
}

/// The block `id`, at least `min` bytes long.
fn block<'a>(
    blocks: &BTreeMap<u16, &'a [u8]>,
    id: u16,
    min: usize,
    what: &str,
) -> Result<ByteCursor<'a>, ParseError> {
    match blocks.get(&id) {
        Some(b) if b.len() >= min => Ok(ByteCursor::new(b)),
        Some(b) => Err(ParseError::malformed(format!(
            "FRT {what} block {id:#06x} has {} bytes, fewer than {min}",
            b.len()
        ))),
        None => Err(ParseError::malformed(format!(
            "FRT file has no {what} block ({id:#06x})"
        ))),
    }
}

/// Parses an FRT file: heights in metres, raw 1 = invalid.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let le = Endian::Little;
    let blocks = blocks(bytes)?;
    let mut grid = block(&blocks, 0x66, 12, "grid")?;
    let nx = grid.u32(le, "FRT nx")? as usize;
    let ny = grid.u32(le, "FRT ny")? as usize;
    let bits = grid.u32(le, "FRT bits per sample")?;
    let mut size = block(&blocks, 0x67, 16, "size")?;
    let (lx, ly) = (size.f64(le, "FRT Lx")?, size.f64(le, "FRT Ly")?);
    let mut scale = block(&blocks, 0x6c, 12, "height scale")?;
    scale.u32(le, "FRT range")?;
    let factor = scale.f64(le, "FRT height scale")?;
    if !(factor.is_finite() && factor > 0.0) {
        return Err(ParseError::malformed(format!(
            "FRT height scale {factor} m per count is not positive"
        )));
    }
    let sample = match bits {
        16 => 2,
        32 => 4,
        other => {
            return Err(ParseError::unsupported(format!(
                "FRT {other} bits per sample (16 and 32 are read)"
            )))
        }
    };
    let points = check_points(nx, ny, "FRT grid block (nx × ny)")?;
    let data = blocks
        .get(&0x0b)
        .ok_or_else(|| ParseError::malformed("FRT file has no height block (0x000b)"))?;
    if data.len() != points * sample {
        return Err(ParseError::malformed(format!(
            "FRT height block has {} bytes, not {nx} × {ny} × {sample}",
            data.len()
        )));
    }
    let values: Vec<f64> = data
        .chunks_exact(sample)
        .map(|c| {
            let raw = if sample == 2 {
                i64::from(u16::from_le_bytes([c[0], c[1]]))
            } else {
                i64::from(i32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            };
            if raw == INVALID_RAW {
                f64::NAN
            } else {
                raw as f64 * factor
            }
        })
        .collect();
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("FRT array shape: {e}")))?;
    let map = HeightMap::new(heights, lx / nx as f64, ly / ny as f64)
        .map_err(|e| ParseError::malformed(format!("FRT: {e} (size {lx} × {ly} m)")))?;
    let mut metadata = BTreeMap::new();
    metadata.insert(super::METADATA_VENDOR.into(), "FRT".into());
    metadata.insert(super::METADATA_INSTRUMENT.into(), "MicroProf".into());
    if let Some(serial) = serial(&blocks) {
        metadata.insert("serial_number".into(), serial);
    }
    Ok(Topography {
        data: TopographyData::Areal(map),
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        channel: None,
        channels: Vec::new(),
        metadata,
    })
}

/// The serial number of block `0x8e` (u32 length, then the text), when present and readable.
fn serial(blocks: &BTreeMap<u16, &[u8]>) -> Option<String> {
    let mut c = ByteCursor::new(blocks.get(&0x8e)?);
    let len = c.u32(Endian::Little, "FRT serial length").ok()? as usize;
    let text = c.text(len, "FRT serial").ok()?;
    let text = text.trim_matches(char::from(0)).trim().to_string();
    (!text.is_empty()).then_some(text)
}
