//! NanoFocus `.nms` reader (µsurf confocal microscopes, `OM_MS_2.0` files).
//!
//! Layout (fixed offsets, little-endian, as SurfaceTopography's `NMS.py` reads it): `zmin`,
//! `zmax` as f64 at byte 16 (µm), `nx`, `ny` as u32 at byte 1368, `dx`, `dy` as f64 at byte
//! 1376, then after the 3468-byte header `nx × ny` u16 heights, one row of `nx` after the other,
//! with `z = zmin + r / 65534 · (zmax − zmin)` (a further u8 block, probably the intensity, is
//! not read). The format has no magic number: it is recognised by its extension, and the header
//! is checked for plausibility: its size field (u32 at byte 1352) is 3468, the z range finite,
//! with `zmin < zmax` and within ±1 m, the spacing finite between 1 pm and 1 m, and the file is
//! exactly the header, the heights and the intensity block, so a damaged `nx` or `ny` is
//! refused.
//!
//! The spacing field is read in **nanometres**: the example file's 312.5 gives a 160 µm field of
//! view for 512 points, the µsurf's field with its 100× objective. SurfaceTopography 1.27.1
//! reads it in millimetres (a 160 m map); this is our inference, not a documented unit (see the
//! shared data's SOURCES.md). Every raw value is a measured height, as SurfaceTopography reads
//! them (the example's single 65535 is kept).

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{ByteCursor, Endian};
use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const HEADER_SIZE: usize = 3468;
const OFFSET_Z: usize = 16;
const OFFSET_POINTS: usize = 1368;
const OFFSET_SPACING: usize = 1376;
/// Where the header states its own size (u32, 3468 in every file seen).
const OFFSET_HEADER_SIZE: usize = 1352;
/// Raw value of `zmax`.
const RAW_SPAN: f64 = 65534.0;
/// Largest height the header's z range may hold, µm: no confocal microscope's range reaches a
/// metre, so a larger value is a damaged field.
const Z_LIMIT_UM: f64 = 1e6;
/// Plausible spacing, nm: from 1 pm to 1 m.
const SPACING_RANGE_NM: (f64, f64) = (1e-3, 1e9);

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "nms",
    description: "NanoFocus `.nms` (µsurf confocal)",
    extensions: &["nms"],
    magic: None,
    parser: Parser::Single(parse),
};

/// The header values the heights need.
struct Header {
    zmin: f64,
    zmax: f64,
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
}

/// The z range (µm), grid size and spacing (nm) of the header, each checked: the header's own
/// size field must be 3468, the z range finite, ordered, not empty and within ±1 m, the spacing
/// finite and between 1 pm and 1 m.
fn read_header(bytes: &[u8]) -> Result<Header, ParseError> {
    let le = Endian::Little;
    let mut c = ByteCursor::new(bytes);
    c.seek(OFFSET_Z, "NMS z range")?;
    let (zmin, zmax) = (c.f64(le, "NMS zmin")?, c.f64(le, "NMS zmax")?);
    c.seek(OFFSET_HEADER_SIZE, "NMS header size")?;
    let header_size = c.u32(le, "NMS header size")?;
    c.seek(OFFSET_POINTS, "NMS grid size")?;
    let nx = c.u32(le, "NMS nx")? as usize;
    let ny = c.u32(le, "NMS ny")? as usize;
    c.seek(OFFSET_SPACING, "NMS spacing")?;
    let (dx, dy) = (c.f64(le, "NMS dx")?, c.f64(le, "NMS dy")?);
    if header_size as usize != HEADER_SIZE {
        return Err(ParseError::malformed(format!(
            "NMS header states its size as {header_size} bytes (byte {OFFSET_HEADER_SIZE}), not \
             {HEADER_SIZE}: a damaged header or another layout"
        )));
    }
    let in_limit = |z: f64| z.is_finite() && z.abs() <= Z_LIMIT_UM;
    if !(in_limit(zmin) && in_limit(zmax) && zmin < zmax) {
        return Err(ParseError::malformed(format!(
            "NMS z range [{zmin}, {zmax}] µm (bytes {OFFSET_Z}–{}) is not a range of heights \
             (finite, zmin < zmax, within ±{Z_LIMIT_UM} µm): a damaged header",
            OFFSET_Z + 15
        )));
    }
    let (lo, hi) = SPACING_RANGE_NM;
    if ![dx, dy].iter().all(|d| d.is_finite() && (lo..=hi).contains(d)) {
        return Err(ParseError::malformed(format!(
            "NMS spacing {dx:e} × {dy:e} nm (bytes {OFFSET_SPACING}–{}) is not between {lo:e} \
             and {hi:e} nm: a damaged header",
            OFFSET_SPACING + 15
        )));
    }
    Ok(Header {
        zmin,
        zmax,
        nx,
        ny,
        dx,
        dy,
    })
}

/// The file must be the header, then `points` u16 heights, then as many u8 intensities (the
/// layout of every file seen): any other length means `nx` or `ny` is wrong. (Heights alone
/// are not accepted: a doubled `nx` would read the intensities as heights.)
fn check_file_size(len: usize, points: usize, nx: usize, ny: usize) -> Result<(), ParseError> {
    let heights_end = HEADER_SIZE + 2 * points;
    let expected = heights_end + points;
    if len < heights_end {
        return Err(ParseError::truncated(format!(
            "NMS heights ({nx} × {ny} u16) need {heights_end} bytes, the file has {len}"
        )));
    }
    if len != expected {
        return Err(ParseError::malformed(format!(
            "NMS file of {len} bytes does not hold {nx} × {ny} points (nx, ny at bytes \
             {OFFSET_POINTS}–{}): the header, the u16 heights and the u8 intensities make \
             {expected} bytes; a damaged nx or ny",
            OFFSET_POINTS + 7
        )));
    }
    Ok(())
}

/// Parses an NMS file: heights in metres, spacing from the header in nanometres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let header = read_header(bytes)?;
    let (nx, ny, zmin, zmax) = (header.nx, header.ny, header.zmin, header.zmax);
    let points = check_points(nx, ny, "NMS header (nx × ny)")?;
    check_file_size(bytes.len(), points, nx, ny)?;
    let data = &bytes[HEADER_SIZE..HEADER_SIZE + 2 * points];
    let step = (zmax - zmin) / RAW_SPAN;
    let values: Vec<f64> = data
        .chunks_exact(2)
        .map(|b| (zmin + f64::from(u16::from_le_bytes([b[0], b[1]])) * step) * 1e-6)
        .collect();
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("NMS array shape: {e}")))?;
    let map = HeightMap::new(heights, header.dx * 1e-9, header.dy * 1e-9)
        .map_err(|e| ParseError::malformed(format!("NMS: {e}")))?;
    let mut metadata = BTreeMap::new();
    metadata.insert(super::METADATA_VENDOR.into(), "NanoFocus".into());
    metadata.insert("spacing_unit".into(), "nm (inferred)".into());
    Ok(Topography {
        data: TopographyData::Areal(map),
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        channel: None,
        channels: Vec::new(),
        metadata,
    })
}
