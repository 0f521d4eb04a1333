//! Zygo MetroPro `.dat` reader (binary, big-endian).
//!
//! Layout (Zygo "MetroPro Reference Guide", OMP-0347, section "Data file format"):
//! a fixed header (834 bytes for header formats 1 and 2, 4096 bytes for format 3) starting with
//! a magic number, followed by the intensity array (`ac_n_bytes` bytes, skipped here) and the
//! "connected phase" array of `cn_width × cn_height` big-endian `i32`, rows top to bottom, x fastest.
//! Phase values `≥ 2147483640` mark invalid points (kept as `NaN`).
//!
//! Height in metres (same reference):
//! `z = phase · S · O · λ / R`, with `S` the interferometric scale factor (`intf_scale_factor`,
//! 0.5 for a reflection interferometer), `O` the obliquity factor, `λ` the wavelength in metres
//! (`wavelength_in`) and `R` the phase resolution (`phase_res` 0 → 4096, 1 → 32768,
//! 2 → 131072). When the header's `data_inverted` flag (i16 at byte 232) is set the sign of
//! `z` is flipped. The lateral pixel size is `lateral_res` in metres (square pixels).

use std::collections::BTreeMap;

use ndarray::Array2;

use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

/// Magic numbers of header formats 1, 2 and 3.
const MAGICS: [u32; 3] = [0x881B_036F, 0x881B_0370, 0x881B_0371];
/// Phase values at or above this mark invalid points.
const PHASE_INVALID_MIN: i32 = 2_147_483_640;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "metropro",
    description: "Zygo MetroPro `.dat`",
    extensions: &["dat"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` starts with a MetroPro magic number.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    u32_at(head, 0).is_some_and(|m| MAGICS.contains(&m))
}

fn field<'a>(
    bytes: &'a [u8],
    offset: usize,
    len: usize,
    what: &str,
) -> Result<&'a [u8], ParseError> {
    offset
        .checked_add(len)
        .and_then(|end| bytes.get(offset..end))
        .ok_or_else(|| {
            ParseError::truncated(format!("MetroPro header field `{what}` at byte {offset}"))
        })
}

fn u32_at(bytes: &[u8], offset: usize) -> Option<u32> {
    let b: [u8; 4] = bytes.get(offset..offset + 4)?.try_into().ok()?;
    Some(u32::from_be_bytes(b))
}

fn i32_field(bytes: &[u8], offset: usize, what: &str) -> Result<i32, ParseError> {
    let b = field(bytes, offset, 4, what)?;
    Ok(i32::from_be_bytes([b[0], b[1], b[2], b[3]]))
}

fn u16_field(bytes: &[u8], offset: usize, what: &str) -> Result<u16, ParseError> {
    let b = field(bytes, offset, 2, what)?;
    Ok(u16::from_be_bytes([b[0], b[1]]))
}

fn f32_field(bytes: &[u8], offset: usize, what: &str) -> Result<f64, ParseError> {
    let b = field(bytes, offset, 4, what)?;
    Ok(f64::from(f32::from_be_bytes([b[0], b[1], b[2], b[3]])))
}

fn text_field(bytes: &[u8], offset: usize, len: usize, what: &str) -> Result<String, ParseError> {
    let b = field(bytes, offset, len, what)?;
    let end = b.iter().position(|&c| c == 0).unwrap_or(b.len());
    Ok(String::from_utf8_lossy(&b[..end]).trim().to_string())
}

/// The sizes of the header and of the arrays.
struct Layout {
    header_format: u16,
    header_size: usize,
    /// Bytes of the intensity array, which precedes the phase array.
    intensity_bytes: usize,
    nx: usize,
    ny: usize,
}

/// The height scale of the phase values.
struct Scale {
    scale_factor: f64,
    wavelength: f64,
    obliquity: f64,
    lateral_res: f64,
    phase_res: f64,
    inverted: bool,
}

impl Scale {
    /// Metres per phase unit, `±S·O·λ/R`, finite and non-zero.
    fn factor(&self) -> Result<f64, ParseError> {
        let sign = if self.inverted { -1.0 } else { 1.0 };
        let (s, o, w, r) = (
            self.scale_factor,
            self.obliquity,
            self.wavelength,
            self.phase_res,
        );
        let factor = sign * s * o * w / r;
        if !(factor.is_finite() && factor != 0.0) {
            return Err(ParseError::malformed(format!(
                "MetroPro height factor S·O·λ/R = {s}·{o}·{w} m/{r} is not usable"
            )));
        }
        Ok(factor)
    }
}

/// Parses a MetroPro `.dat` file into heights in metres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let layout = read_layout(bytes)?;
    let scale = read_scale(bytes)?;
    let factor = scale.factor()?;
    let (nx, ny) = (layout.nx, layout.ny);
    let phase_start = layout
        .header_size
        .checked_add(layout.intensity_bytes)
        .ok_or_else(|| ParseError::malformed("MetroPro array offsets overflow"))?;
    let phase = field(bytes, phase_start, nx * ny * 4, "connected phase array")?;
    check_points(nx, ny, "MetroPro header (cn_width × cn_height)")?;
    let heights: Vec<f64> = phase
        .chunks_exact(4)
        .map(|c| {
            let v = i32::from_be_bytes([c[0], c[1], c[2], c[3]]);
            if v >= PHASE_INVALID_MIN {
                f64::NAN
            } else {
                f64::from(v) * factor
            }
        })
        .collect();
    let heights = Array2::from_shape_vec((ny, nx), heights)
        .map_err(|e| ParseError::malformed(format!("MetroPro array shape: {e}")))?;
    let lateral_res = scale.lateral_res;
    let map = HeightMap::new(heights, lateral_res, lateral_res).map_err(|e| {
        ParseError::malformed(format!("MetroPro: {e} (lateral_res {lateral_res} m)"))
    })?;
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: Some("phase".into()),
        channels: Vec::new(),
        metadata: metadata(bytes, &layout, &scale)?,
    })
}

/// The magic number, the header size and the array sizes, which must agree with each other.
fn read_layout(bytes: &[u8]) -> Result<Layout, ParseError> {
    let magic = u32_at(bytes, 0).ok_or_else(|| ParseError::truncated("MetroPro magic number"))?;
    if !MAGICS.contains(&magic) {
        return Err(ParseError::malformed(format!(
            "not a MetroPro file (magic {magic:#010x})"
        )));
    }
    let header_format = u16_field(bytes, 4, "header_format")?;
    let header_size = i32_field(bytes, 6, "header_size")?;
    let header_size = usize::try_from(header_size)
        .ok()
        .filter(|&h| h >= 834)
        .ok_or_else(|| {
            ParseError::malformed(format!("MetroPro header size {header_size} < 834 bytes"))
        })?;
    if bytes.len() < header_size {
        return Err(ParseError::truncated(format!(
            "MetroPro header of {header_size} bytes, file has {}",
            bytes.len()
        )));
    }
    let intensity_bytes = i32_field(bytes, 60, "ac_n_bytes")?;
    let nx = usize::from(u16_field(bytes, 68, "cn_width")?);
    let ny = usize::from(u16_field(bytes, 70, "cn_height")?);
    let phase_bytes = i32_field(bytes, 72, "cn_n_bytes")?;
    let intensity_bytes = usize::try_from(intensity_bytes).map_err(|_| {
        ParseError::malformed(format!("negative intensity array size {intensity_bytes}"))
    })?;
    if nx == 0 || ny == 0 || phase_bytes <= 0 {
        return Err(ParseError::unsupported(
            "MetroPro file holds no phase (height) array",
        ));
    }
    if usize::try_from(phase_bytes).ok() != Some(nx * ny * 4) {
        return Err(ParseError::malformed(format!(
            "MetroPro phase array of {phase_bytes} bytes does not match {nx} × {ny} × 4"
        )));
    }
    Ok(Layout {
        header_format,
        header_size,
        intensity_bytes,
        nx,
        ny,
    })
}

/// The interferometer's scale factor, wavelength, obliquity, pixel size, phase resolution and
/// inversion flag.
fn read_scale(bytes: &[u8]) -> Result<Scale, ParseError> {
    let scale_factor = f32_field(bytes, 164, "intf_scale_factor")?;
    let wavelength = f32_field(bytes, 168, "wavelength_in")?;
    let obliquity = f32_field(bytes, 176, "obliquity_factor")?;
    let lateral_res = f32_field(bytes, 184, "lateral_res")?;
    let phase_res = match u16_field(bytes, 218, "phase_res")? {
        0 => 4096.0,
        1 => 32768.0,
        2 => 131072.0,
        other => {
            return Err(ParseError::malformed(format!(
                "unknown MetroPro phase_res code {other}"
            )))
        }
    };
    let inverted = u16_field(bytes, 232, "data_inverted")? != 0;
    Ok(Scale {
        scale_factor,
        wavelength,
        obliquity,
        lateral_res,
        phase_res,
        inverted,
    })
}

/// The header's descriptive fields and scale values (empty ones left out).
fn metadata(
    bytes: &[u8],
    layout: &Layout,
    scale: &Scale,
) -> Result<BTreeMap<String, String>, ParseError> {
    let mut metadata = BTreeMap::new();
    metadata.insert("vendor".into(), "Zygo".into());
    metadata.insert("header_format".into(), layout.header_format.to_string());
    metadata.insert(
        "software_date".into(),
        text_field(bytes, 12, 30, "swinfo_date")?,
    );
    metadata.insert("comment".into(), text_field(bytes, 80, 82, "comment")?);
    metadata.insert("objective".into(), text_field(bytes, 246, 12, "obj_name")?);
    metadata.insert("part_name".into(), text_field(bytes, 258, 40, "part_name")?);
    metadata.insert(
        "serial_number".into(),
        u16_field(bytes, 242, "sys_serial")?.to_string(),
    );
    metadata.insert("wavelength_m".into(), scale.wavelength.to_string());
    metadata.insert("obliquity_factor".into(), scale.obliquity.to_string());
    metadata.insert("intf_scale_factor".into(), scale.scale_factor.to_string());
    metadata.insert("phase_resolution".into(), scale.phase_res.to_string());
    metadata.insert("lateral_resolution_m".into(), scale.lateral_res.to_string());
    metadata.insert("data_inverted".into(), scale.inverted.to_string());
    metadata.retain(|_, v| !v.is_empty());
    Ok(metadata)
}
