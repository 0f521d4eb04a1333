//! TrueMap / GelSight `.tmd` reader (TrueGage TrueMap software).
//!
//! Layout (as read by Gwyddion's `rmitmd.c` and SurfaceTopography's `TMD.py`): the 32-byte magic
//! `Binary TrueMap Data File v2.0\r\n\0`, a NUL-terminated comment (Latin-1, "Created by TrueMap
//! v6\r\n" in the files seen), then little-endian `u32 nx`, `u32 ny`, `f32 length_x`,
//! `f32 length_y`, `f32 offset_x`, `f32 offset_y` and `nx·ny` float32 heights, row by row with x
//! fastest. Lengths, offsets and heights are in **millimetres** (Gwyddion and SurfaceTopography
//! ≥ 1.27; SurfaceTopography 1.22 labelled them µm): spacing `dx = length_x / nx`. Non-finite
//! heights are missing points.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{decode_samples, ByteCursor, Endian, SampleType};
use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"Binary TrueMap Data File v2.0";
/// The magic field, padded with CR LF NUL.
const MAGIC_FIELD: usize = 32;
/// Longest comment accepted (TrueMap writes 24 bytes, Gwyddion accepts any length).
const MAX_COMMENT: usize = 4096;
const MM: f64 = 1e-3;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "tmd",
    description: "TrueMap `.tmd` (float32 heights, lengths and heights in mm)",
    extensions: &["tmd"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` starts with the TrueMap v2.0 magic.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

/// Parses a TMD file into heights in metres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    if !bytes.starts_with(MAGIC) {
        return Err(ParseError::malformed(
            "missing `Binary TrueMap Data File v2.0` magic",
        ));
    }
    let mut c = ByteCursor::new(bytes);
    c.seek(MAGIC_FIELD, "TMD comment")?;
    let rest = &bytes[MAGIC_FIELD.min(bytes.len())..];
    let comment_len = rest
        .iter()
        .take(MAX_COMMENT)
        .position(|&b| b == 0)
        .ok_or_else(|| {
            if rest.len() < MAX_COMMENT {
                ParseError::truncated("TMD comment (no terminating NUL)")
            } else {
                ParseError::malformed(format!(
                    "TMD comment has no terminating NUL within {MAX_COMMENT} bytes"
                ))
            }
        })?;
    let comment = c.text(comment_len + 1, "TMD comment")?;
    let e = Endian::Little;
    let nx = c.u32(e, "TMD nx")? as usize;
    let ny = c.u32(e, "TMD ny")? as usize;
    let length_x = f64::from(c.f32(e, "TMD length_x")?);
    let length_y = f64::from(c.f32(e, "TMD length_y")?);
    let offset_x = c.f32(e, "TMD offset_x")?;
    let offset_y = c.f32(e, "TMD offset_y")?;
    if nx < 2 || ny < 2 {
        return Err(ParseError::malformed(format!(
            "TMD grid of {nx} × {ny} points; a topography needs at least 2 × 2"
        )));
    }
    if !(length_x.is_finite() && length_x > 0.0 && length_y.is_finite() && length_y > 0.0) {
        return Err(ParseError::malformed(format!(
            "TMD lengths {length_x} × {length_y} mm must be finite and > 0"
        )));
    }
    let count = check_points(nx, ny, "TMD header (nx × ny)")?;
    let data = c.take(c.remaining(), "TMD heights")?;
    let values = decode_samples(data, count, SampleType::F32, e, "TMD heights (float32)")?;
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|err| ParseError::malformed(format!("TMD array shape: {err}")))?
        .mapv(|z| if z.is_finite() { z * MM } else { f64::NAN });
    let map = HeightMap::new(
        heights,
        length_x * MM / nx as f64,
        length_y * MM / ny as f64,
    )
    .map_err(|err| ParseError::malformed(format!("TMD: {err}")))?;
    let mut metadata = BTreeMap::new();
    metadata.insert("vendor".into(), "TrueMap".into());
    metadata.insert("comment".into(), comment);
    metadata.insert("x_offset_m".into(), (f64::from(offset_x) * MM).to_string());
    metadata.insert("y_offset_m".into(), (f64::from(offset_y) * MM).to_string());
    metadata.insert("original_unit".into(), "mm".into());
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: None,
        channels: Vec::new(),
        metadata,
    })
}
