//! Wyko / Veeco (Bruker) Vision `.opd` reader (little-endian block directory).
//!
//! Layout (as documented by Gwyddion's `opd` module and Bruker's Vision export notes): two
//! bytes, then a directory of 24-byte entries `name[16] · type: i16 · size: i32 · flags: u16`.
//! The first entry is the directory itself (its `size` is the directory length); the data of
//! the other entries follows the directory back to back, in directory order. An array block
//! (type 3) starts with `nx: u16 · ny: u16 · element size: u16` and stores the values with
//! **y fastest** (one column of `ny` values per x); rows keep the file's y order.
//!
//! The height array is the block named `RAW_DATA`, `RAW DATA`, `OPD` or `Raw` (float32, in
//! waves). Heights in metres: `z = value · λ / mult` with the wavelength `λ` (block
//! `Wavelength`, nm) and `mult` (block `Mult`, default 1). Values with `|value| ≥ 1e38` (the
//! instrument writes `f32::MAX / 2`) or non-finite values are invalid → `NaN`. Pixel size
//! (block `Pixel_size`) is in mm along x; `dy = dx · aspect` (block `Aspect`, default 1).

use std::collections::BTreeMap;

use ndarray::Array2;

use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

/// Size of one directory entry in bytes.
const ENTRY_SIZE: usize = 24;
/// Values at or above this magnitude are invalid points.
const INVALID_MAGNITUDE: f32 = 1e38;
/// Names of the height (OPD) array block.
const HEIGHT_BLOCKS: [&str; 4] = ["RAW_DATA", "RAW DATA", "OPD", "Raw"];

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "opd",
    description: "Wyko/Veeco Vision `.opd`",
    extensions: &["opd"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` starts with the OPD directory entry.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    head.get(2..11) == Some(b"Directory".as_slice())
}

/// One block of the directory with its data.
struct Block<'a> {
    name: String,
    kind: i16,
    data: &'a [u8],
}

fn read_directory(bytes: &[u8]) -> Result<Vec<Block<'_>>, ParseError> {
    let entry = |i: usize| -> Result<(String, i16, i32), ParseError> {
        let start = 2 + i * ENTRY_SIZE;
        let e = bytes
            .get(start..start + ENTRY_SIZE)
            .ok_or_else(|| ParseError::truncated(format!("OPD directory entry {i}")))?;
        let name_end = e[..16].iter().position(|&c| c == 0).unwrap_or(16);
        let name = String::from_utf8_lossy(&e[..name_end]).into_owned();
        let kind = i16::from_le_bytes([e[16], e[17]]);
        let size = i32::from_le_bytes([e[18], e[19], e[20], e[21]]);
        Ok((name, kind, size))
    };
    let (name, _, dir_size) = entry(0)?;
    if name != "Directory" {
        return Err(ParseError::malformed(format!(
            "OPD: first block is `{name}`, expected `Directory`"
        )));
    }
    let dir_size = usize::try_from(dir_size)
        .ok()
        .filter(|s| s % ENTRY_SIZE == 0 && *s >= ENTRY_SIZE)
        .ok_or_else(|| {
            ParseError::malformed(format!(
                "OPD directory size {dir_size} is not a positive multiple of {ENTRY_SIZE}"
            ))
        })?;
    let n_entries = dir_size / ENTRY_SIZE;
    let mut offset = 2 + dir_size;
    let mut blocks = Vec::new();
    for i in 1..n_entries {
        let (name, kind, size) = entry(i)?;
        let size = usize::try_from(size).map_err(|_| {
            ParseError::malformed(format!("OPD block `{name}` has negative size {size}"))
        })?;
        if size == 0 {
            continue;
        }
        let data = offset
            .checked_add(size)
            .and_then(|end| bytes.get(offset..end))
            .ok_or_else(|| {
                ParseError::truncated(format!(
                    "OPD block `{name}` ({size} bytes at byte {offset})"
                ))
            })?;
        offset += size;
        blocks.push(Block { name, kind, data });
    }
    Ok(blocks)
}

fn f32_le(data: &[u8]) -> Option<f32> {
    Some(f32::from_le_bytes(data.get(0..4)?.try_into().ok()?))
}

/// Reads a scalar block as a number (float32 if 4 bytes, u16 if 2 bytes).
fn scalar(blocks: &[Block<'_>], name: &str) -> Result<Option<f64>, ParseError> {
    let Some(b) = blocks.iter().find(|b| b.name == name) else {
        return Ok(None);
    };
    match b.data.len() {
        4 => Ok(f32_le(b.data).map(f64::from)),
        2 => Ok(Some(f64::from(u16::from_le_bytes([b.data[0], b.data[1]])))),
        n => Err(ParseError::malformed(format!(
            "OPD block `{name}` has unexpected size {n}"
        ))),
    }
}

/// Parses a Wyko `.opd` file into heights in metres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let blocks = read_directory(bytes)?;
    let array = blocks
        .iter()
        .find(|b| b.kind == 3 && HEIGHT_BLOCKS.contains(&b.name.as_str()))
        .ok_or_else(|| ParseError::malformed("OPD file has no RAW_DATA/OPD/Raw height array"))?;
    let (nx, ny, values) = height_array(array)?;
    let wavelength_nm = scalar(&blocks, "Wavelength")?
        .ok_or_else(|| ParseError::malformed("OPD file has no Wavelength block"))?;
    let mult = scalar(&blocks, "Mult")?.unwrap_or(1.0);
    let aspect = scalar(&blocks, "Aspect")?.unwrap_or(1.0);
    let pixel_mm = scalar(&blocks, "Pixel_size")?
        .ok_or_else(|| ParseError::malformed("OPD file has no Pixel_size block"))?;
    let factor = wavelength_nm * 1e-9 / mult;
    if !(factor.is_finite() && factor > 0.0) {
        return Err(ParseError::malformed(format!(
            "OPD height factor λ/mult = {wavelength_nm} nm / {mult} is not positive"
        )));
    }
    let dx = pixel_mm * 1e-3;
    let dy = dx * aspect;

    check_points(nx, ny, &format!("OPD array `{}`", array.name))?;
    let mut heights = Array2::<f64>::zeros((ny, nx));
    for (k, c) in values.chunks_exact(4).enumerate() {
        let v = f32::from_le_bytes([c[0], c[1], c[2], c[3]]);
        let (ix, iy) = (k / ny, k % ny);
        heights[[iy, ix]] = if v.is_finite() && v.abs() < INVALID_MAGNITUDE {
            f64::from(v) * factor
        } else {
            f64::NAN
        };
    }
    let map = HeightMap::new(heights, dx, dy).map_err(|e| {
        ParseError::malformed(format!(
            "OPD: {e} (Pixel_size {pixel_mm} mm, Aspect {aspect})"
        ))
    })?;
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: Some(array.name.clone()),
        channels: Vec::new(),
        metadata: metadata(&blocks, wavelength_nm, mult, aspect),
    })
}

/// The size and the float32 values of the height array block (a 6-byte head: nx, ny and the
/// element size as u16, then the values).
fn height_array<'a>(array: &Block<'a>) -> Result<(usize, usize, &'a [u8]), ParseError> {
    let head = array
        .data
        .get(0..6)
        .ok_or_else(|| ParseError::truncated(format!("OPD array `{}` header", array.name)))?;
    let nx = usize::from(u16::from_le_bytes([head[0], head[1]]));
    let ny = usize::from(u16::from_le_bytes([head[2], head[3]]));
    let elem = u16::from_le_bytes([head[4], head[5]]);
    if elem != 4 {
        return Err(ParseError::unsupported(format!(
            "OPD height array with {elem}-byte elements (only float32 is supported)"
        )));
    }
    // The block is at least 6 bytes long (its header was read above).
    let values = &array.data[6..];
    if values.len() != nx * ny * 4 {
        return Err(ParseError::malformed(format!(
            "OPD array `{}` block holds {} bytes, not {nx} × {ny} float32",
            array.name,
            values.len()
        )));
    }
    Ok((nx, ny, values))
}

/// The vendor, the height scale, the text blocks and the magnification.
fn metadata(
    blocks: &[Block<'_>],
    wavelength_nm: f64,
    mult: f64,
    aspect: f64,
) -> BTreeMap<String, String> {
    let mut metadata = BTreeMap::new();
    metadata.insert("vendor".into(), "Wyko/Veeco (Bruker)".into());
    metadata.insert("wavelength_m".into(), (wavelength_nm * 1e-9).to_string());
    metadata.insert("mult".into(), mult.to_string());
    metadata.insert("aspect".into(), aspect.to_string());
    for b in blocks.iter().filter(|b| b.kind == 5) {
        let text = String::from_utf8_lossy(b.data);
        let text = text.trim_end_matches('\0').trim();
        if !text.is_empty() {
            metadata.insert(b.name.clone(), text.to_string());
        }
    }
    if let Some(m) = scalar(blocks, "Magnification").ok().flatten() {
        metadata.insert("magnification".into(), m.to_string());
    }
    metadata
}
