//! NanoFocus `.nms` reader (µsurf confocal microscopes, `OM_MS_2.0` files).
//!
//! Layout (fixed offsets, little-endian, as SurfaceTopography's `NMS.py` reads it): `zmin`,
//! `zmax` as f64 at byte 16 (µm), `nx`, `ny` as u32 at byte 1368, `dx`, `dy` as f64 at byte
//! 1376, then after the 3468-byte header `nx × ny` u16 heights, one row of `nx` after the other,
//! with `z = zmin + r / 65534 · (zmax − zmin)` (a further u8 block, probably the intensity, is
//! not read). The format has no magic number: it is recognised by its extension, and the header
//! is checked for plausibility (positive finite spacing, `zmin ≤ zmax`, the data inside the
//! file).
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
/// Raw value of `zmax`.
const RAW_SPAN: f64 = 65534.0;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "nms",
    description: "NanoFocus `.nms` (µsurf confocal)",
    extensions: &["nms"],
    magic: None,
    parser: Parser::Single(parse),
};

/// Parses an NMS file: heights in metres, spacing from the header in nanometres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let le = Endian::Little;
    let mut c = ByteCursor::new(bytes);
    c.seek(OFFSET_Z, "NMS z range")?;
    let (zmin, zmax) = (c.f64(le, "NMS zmin")?, c.f64(le, "NMS zmax")?);
    c.seek(OFFSET_POINTS, "NMS grid size")?;
    let nx = c.u32(le, "NMS nx")? as usize;
    let ny = c.u32(le, "NMS ny")? as usize;
    c.seek(OFFSET_SPACING, "NMS spacing")?;
    let (dx, dy) = (c.f64(le, "NMS dx")?, c.f64(le, "NMS dy")?);
    if !(zmin.is_finite() && zmax.is_finite() && zmin <= zmax) {
        return Err(ParseError::malformed(format!(
            "NMS z range [{zmin}, {zmax}] µm is not a range"
        )));
    }
    if !(dx.is_finite() && dy.is_finite() && dx > 0.0 && dy > 0.0) {
        return Err(ParseError::malformed(format!(
            "NMS spacing {dx} × {dy} nm is not positive"
        )));
    }
    let points = check_points(nx, ny, "NMS header (nx × ny)")?;
    c.seek(HEADER_SIZE, "NMS header")?;
    let data = c.take(points * 2, &format!("NMS heights ({nx} × {ny} u16)"))?;
    let step = (zmax - zmin) / RAW_SPAN;
    let values: Vec<f64> = data
        .chunks_exact(2)
        .map(|b| (zmin + f64::from(u16::from_le_bytes([b[0], b[1]])) * step) * 1e-6)
        .collect();
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("NMS array shape: {e}")))?;
    let map = HeightMap::new(heights, dx * 1e-9, dy * 1e-9)
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
