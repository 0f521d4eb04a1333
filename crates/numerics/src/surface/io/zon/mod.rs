//! Keyence `.zon` reader (VR-series wide-area 3D profilometers).
//!
//! There is no official documentation; the layout below was reverse engineered by the community
//! (gabeguss/Keyence issue 2; SurfaceTopography's ZON reader) and checked on `test_1.zon`:
//!
//! * magic `KPK0` or `KPK1`, a little-endian `u32` thumbnail size, a BMP thumbnail, then a
//!   (ZIP64) archive (module `archive`; entries stored, i.e. method 0) whose members are named
//!   by UUIDs. In `KPK1` files each member's content is itself a zstd frame.
//! * `4cdb0c75-5706-48cc-a9a1-adf395d609ae`: height array; `686613b8-…`: XML calibration
//!   with `<MeterPerPixel>` (lateral, square pixels) and `<MeterPerUnit>` (height per count);
//!   `9e7ca6dd-…` (optional): per-pixel status bytes, where `status & 0x03 ≠ 0` marks a pixel
//!   without a valid height (→ `NaN`); `cbc1d39b-…`: device XML; `1d35862b-…`: scan date XML.
//! * An array member is `width: i32 · height: i32 · element size: i32 · row bytes: i32`
//!   (little-endian), then `height` rows of `row bytes`, x fastest; heights are `i32` counts.
//!
//! Heights in metres: `z = count · MeterPerUnit`. A `KPK1` member is decoded by streaming, so
//! memory grows only with data actually produced, and at most 1 GiB per member.

use std::collections::BTreeMap;
use std::io::Read;

use ndarray::Array2;

mod archive;

use super::limits::{check_points, MAX_POINTS};
use super::reader::{Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const HEIGHT_UUID: &str = "4cdb0c75-5706-48cc-a9a1-adf395d609ae";
const STATUS_UUID: &str = "9e7ca6dd-0e6a-4d7b-8986-f0a7b773c916";
const CALIBRATION_UUID: &str = "686613b8-27b5-4a29-8ffc-438c2780873e";
const DEVICE_UUID: &str = "cbc1d39b-215f-4d56-a20e-cf8e5f570755";
const SCAN_UUID: &str = "1d35862b-3b48-4df2-9235-833ef590b043";
/// Status bits that mark a pixel without a valid height.
const INVALID_STATUS_BITS: u8 = 0x03;
/// Largest decompressed array member accepted: 8 bytes for each of [`MAX_POINTS`] (1 GiB,
/// room for padded rows), bounding the memory a corrupted or hostile zstd frame can make us
/// allocate.
const MAX_MEMBER_BYTES: u64 = MAX_POINTS as u64 * 8;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "zon",
    description: "Keyence `.zon`",
    extensions: &["zon"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` starts with a ZON magic.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(b"KPK0") || head.starts_with(b"KPK1")
}

/// A reader of a member's content, zstd-decoded for `KPK1` files.
fn member_reader<'a>(
    content: &'a [u8],
    zstd: bool,
    name: &str,
) -> Result<Box<dyn Read + 'a>, ParseError> {
    if zstd {
        let decoder = zstd::stream::read::Decoder::with_buffer(content)
            .map_err(|e| ParseError::malformed(format!("ZON member `{name}`: zstd: {e}")))?;
        Ok(Box::new(decoder))
    } else {
        Ok(Box::new(content))
    }
}

/// A whole (small, XML) member, at most `limit` bytes.
fn read_member(content: &[u8], zstd: bool, name: &str, limit: u64) -> Result<Vec<u8>, ParseError> {
    let mut out = Vec::new();
    member_reader(content, zstd, name)?
        .take(limit)
        .read_to_end(&mut out)
        .map_err(|e| ParseError::malformed(format!("ZON member `{name}`: {e}")))?;
    Ok(out)
}

/// A decoded array member: dimensions, element size, row stride and the raw rows.
struct ArrayMember {
    nx: usize,
    ny: usize,
    element: usize,
    row_bytes: usize,
    data: Vec<u8>,
}

fn read_array(
    content: &[u8],
    zstd: bool,
    name: &str,
    element: usize,
) -> Result<ArrayMember, ParseError> {
    let mut reader = member_reader(content, zstd, name)?;
    let mut header = [0u8; 16];
    reader
        .read_exact(&mut header)
        .map_err(|e| ParseError::truncated(format!("ZON array `{name}` header: {e}")))?;
    let field =
        |i: usize| i32::from_le_bytes([header[i], header[i + 1], header[i + 2], header[i + 3]]);
    let (nx, ny, elem, row_bytes) = (field(0), field(4), field(8), field(12));
    let malformed = || {
        ParseError::malformed(format!(
            "ZON array `{name}`: {nx} × {ny}, {elem}-byte elements, {row_bytes} bytes per row"
        ))
    };
    let as_usize = |v: i32| usize::try_from(v).ok().filter(|&v| v > 0);
    let (nx, ny, elem_u, row_u) = match (
        as_usize(nx),
        as_usize(ny),
        as_usize(elem),
        as_usize(row_bytes),
    ) {
        (Some(a), Some(b), Some(c), Some(d)) => (a, b, c, d),
        _ => return Err(malformed()),
    };
    check_points(nx, ny, &format!("ZON array `{name}`"))?;
    if elem_u != element || row_u < nx * elem_u {
        return Err(malformed());
    }
    let total = (ny as u64) * (row_u as u64);
    if total > MAX_MEMBER_BYTES {
        return Err(ParseError::malformed(format!(
            "ZON array `{name}` of {total} bytes exceeds the {MAX_MEMBER_BYTES}-byte limit"
        )));
    }
    let mut data = Vec::new();
    reader
        .take(total)
        .read_to_end(&mut data)
        .map_err(|e| ParseError::malformed(format!("ZON array `{name}`: {e}")))?;
    if data.len() as u64 != total {
        return Err(ParseError::truncated(format!(
            "ZON array `{name}`: {} of {total} bytes",
            data.len()
        )));
    }
    Ok(ArrayMember {
        nx,
        ny,
        element,
        row_bytes: row_u,
        data,
    })
}

/// Text between `<tag>` and `</tag>` in a small XML document.
fn xml_text<'a>(doc: &'a str, tag: &str) -> Option<&'a str> {
    let open = format!("<{tag}>");
    let start = doc.find(&open)? + open.len();
    let end = start + doc[start..].find(&format!("</{tag}>"))?;
    Some(doc[start..end].trim())
}

/// The members of an opened archive and whether their contents are zstd frames.
struct Opened<'a> {
    members: archive::Members<'a>,
    zstd: bool,
}

impl<'a> Opened<'a> {
    /// The stored content of the member `uuid` (`what` names it for errors).
    fn member(&self, uuid: &str, what: &str) -> Result<&'a [u8], ParseError> {
        match (
            self.members.stored.get(uuid),
            self.members.other_method.get(uuid),
        ) {
            (Some(content), _) => Ok(*content),
            (None, Some(method)) => Err(ParseError::unsupported(format!(
                "ZON {what} member `{uuid}` uses ZIP compression method {method} (only stored \
                 members)"
            ))),
            (None, None) => Err(ParseError::malformed(format!(
                "ZON archive has no {what} member `{uuid}`"
            ))),
        }
    }

    /// `MeterPerPixel` and `MeterPerUnit` of the calibration member.
    fn calibration(&self) -> Result<(f64, f64), ParseError> {
        let calibration = read_member(
            self.member(CALIBRATION_UUID, "calibration")?,
            self.zstd,
            CALIBRATION_UUID,
            1 << 20,
        )?;
        let calibration = String::from_utf8_lossy(&calibration);
        let number = |tag: &str| -> Result<f64, ParseError> {
            let text = xml_text(&calibration, tag)
                .ok_or_else(|| ParseError::malformed(format!("ZON calibration has no <{tag}>")))?;
            text.parse::<f64>().map_err(|_| {
                ParseError::malformed(format!("ZON <{tag}> `{text}` is not a number"))
            })
        };
        Ok((number("MeterPerPixel")?, number("MeterPerUnit")?))
    }

    /// The status map, when the archive has one; it must match the height map's size.
    fn status(&self, height: &ArrayMember) -> Result<Option<ArrayMember>, ParseError> {
        let has_status = self.members.stored.contains_key(STATUS_UUID)
            || self.members.other_method.contains_key(STATUS_UUID);
        if !has_status {
            return Ok(None);
        }
        let s = read_array(
            self.member(STATUS_UUID, "status")?,
            self.zstd,
            STATUS_UUID,
            1,
        )?;
        if (s.nx, s.ny) != (height.nx, height.ny) {
            return Err(ParseError::malformed(format!(
                "ZON status map {} × {} does not match the height map {} × {}",
                s.nx, s.ny, height.nx, height.ny
            )));
        }
        Ok(Some(s))
    }

    /// The vendor, the calibration, and the device and scan date when the archive has them.
    fn metadata(&self, pixel: f64, per_count: f64) -> Result<BTreeMap<String, String>, ParseError> {
        let mut metadata = BTreeMap::new();
        metadata.insert("vendor".into(), "Keyence".into());
        metadata.insert("meter_per_pixel".into(), pixel.to_string());
        metadata.insert("meter_per_unit".into(), per_count.to_string());
        for (uuid, tag, key) in [
            (DEVICE_UUID, "DeviceModelName", "instrument"),
            (DEVICE_UUID, "DeviceSerialId", "serial_number"),
            (SCAN_UUID, "ScanDateTime", "acquisition_time"),
        ] {
            if let Some(content) = self.members.stored.get(uuid) {
                let doc = read_member(content, self.zstd, uuid, 1 << 20)?;
                if let Some(v) = xml_text(&String::from_utf8_lossy(&doc), tag) {
                    metadata.insert(key.into(), v.to_string());
                }
            }
        }
        Ok(metadata)
    }
}

/// Parses a Keyence `.zon` file into heights in metres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let zstd = match bytes.get(0..4) {
        Some(b"KPK0") => false,
        Some(b"KPK1") => true,
        _ => return Err(ParseError::malformed("missing `KPK0`/`KPK1` magic")),
    };
    let opened = Opened {
        members: archive::members(bytes)?,
        zstd,
    };
    let (pixel, per_count) = opened.calibration()?;
    let height = read_array(
        opened.member(HEIGHT_UUID, "height")?,
        zstd,
        HEIGHT_UUID,
        4,
    )?;
    let status = opened.status(&height)?;
    let values = heights(&height, status.as_ref(), per_count);
    let heights = Array2::from_shape_vec((height.ny, height.nx), values)
        .map_err(|e| ParseError::malformed(format!("ZON array shape: {e}")))?;
    let map = HeightMap::new(heights, pixel, pixel)
        .map_err(|e| ParseError::malformed(format!("ZON: {e}")))?;
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: Some("height".into()),
        channels: Vec::new(),
        metadata: opened.metadata(pixel, per_count)?,
    })
}

/// The heights in metres, row by row: `count · per_count`, `NaN` where the status marks the
/// pixel invalid.
fn heights(height: &ArrayMember, status: Option<&ArrayMember>, per_count: f64) -> Vec<f64> {
    let (nx, ny) = (height.nx, height.ny);
    let mut values = Vec::with_capacity(nx * ny);
    for iy in 0..ny {
        let row = &height.data[iy * height.row_bytes..iy * height.row_bytes + nx * height.element];
        let status_row = status.map(|s| &s.data[iy * s.row_bytes..iy * s.row_bytes + nx]);
        for (ix, c) in row.chunks_exact(4).enumerate() {
            let invalid = status_row.is_some_and(|s| s[ix] & INVALID_STATUS_BITS != 0);
            values.push(if invalid {
                f64::NAN
            } else {
                f64::from(i32::from_le_bytes([c[0], c[1], c[2], c[3]])) * per_count
            });
        }
    }
    values
}
