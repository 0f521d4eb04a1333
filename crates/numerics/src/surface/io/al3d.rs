//! Alicona Imaging `.al3d` reader.
//!
//! Layout (Alicona "AL3D file format" specification v1.0, 2003): the 17-byte magic
//! `AliconaImaging\0\r\n`, then 52-byte tags `key[20] · value[30] · "\r\n"` (NUL-padded text).
//! The first two tags are `Version` and `TagCount`; `TagCount` more tags follow (`Cols`,
//! `Rows`, `PixelSizeXMeter`, `PixelSizeYMeter`, `DepthImageOffset`, `TextureImageOffset`,
//! `InvalidPixelValue`, …). The depth image is little-endian float32 in metres at
//! `DepthImageOffset`, row by row, x fastest; rows are padded to a multiple of 8 values. Points
//! equal to `InvalidPixelValue` (or non-finite) are missing → `NaN`.
//!
//! Row stride: when a texture follows the depth image, the stride is taken from the gap between
//! the two offsets (`(TextureImageOffset − DepthImageOffset) / (4·Rows)`); otherwise it is `Cols`
//! rounded up to a multiple of 8 if the file is long enough, else `Cols`.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"AliconaImaging\0\r\n";
const TAG_SIZE: usize = 52;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "al3d",
    description: "Alicona `.al3d`",
    extensions: &["al3d"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` starts with the AL3D magic.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

fn read_tag(bytes: &[u8], index: usize) -> Result<(String, String), ParseError> {
    let start = MAGIC.len() + index * TAG_SIZE;
    let tag = bytes
        .get(start..start + TAG_SIZE)
        .ok_or_else(|| ParseError::truncated(format!("AL3D tag {index} at byte {start}")))?;
    if &tag[50..52] != b"\r\n" {
        return Err(ParseError::malformed(format!(
            "AL3D tag {index} does not end with CR LF"
        )));
    }
    let text = |b: &[u8]| {
        let end = b.iter().position(|&c| c == 0).unwrap_or(b.len());
        String::from_utf8_lossy(&b[..end]).trim().to_string()
    };
    Ok((text(&tag[..20]), text(&tag[20..50])))
}

/// Parses an AL3D file into heights in metres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let tags = read_tags(bytes)?;
    let get = |key: &str| -> Result<&String, ParseError> {
        tags.get(key)
            .ok_or_else(|| ParseError::malformed(format!("AL3D header has no `{key}` tag")))
    };
    let int = |key: &str| -> Result<usize, ParseError> {
        let v = get(key)?;
        v.parse().map_err(|_| {
            ParseError::malformed(format!("AL3D {key} `{v}` is not a non-negative integer"))
        })
    };
    let real = |key: &str| -> Result<f64, ParseError> {
        let v = get(key)?;
        v.parse()
            .map_err(|_| ParseError::malformed(format!("AL3D {key} `{v}` is not a number")))
    };
    let (nx, ny) = (int("Cols")?, int("Rows")?);
    let (dx, dy) = (real("PixelSizeXMeter")?, real("PixelSizeYMeter")?);
    let depth = DepthImage {
        nx,
        ny,
        offset: int("DepthImageOffset")?,
        texture_offset: int("TextureImageOffset").unwrap_or(0),
        invalid: match tags.get("InvalidPixelValue") {
            Some(v) => v.parse::<f64>().ok().map(|x| x as f32),
            None => None,
        },
    };
    let values = depth.heights(bytes)?;
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("AL3D array shape: {e}")))?;
    let map =
        HeightMap::new(heights, dx, dy).map_err(|e| ParseError::malformed(format!("AL3D: {e}")))?;
    let mut metadata = BTreeMap::new();
    metadata.insert("vendor".into(), "Alicona".into());
    for key in [
        "Version",
        "CreatingApplication",
        "NumberOfPlanes",
        "DepthResShiftVal",
    ] {
        if let Some(v) = tags.get(key) {
            metadata.insert(key.into(), v.clone());
        }
    }
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: Some("depth".into()),
        channels: Vec::new(),
        metadata,
    })
}

/// Every tag of the header: `Version` and `TagCount` first, then `TagCount` more.
fn read_tags(bytes: &[u8]) -> Result<BTreeMap<String, String>, ParseError> {
    if !bytes.starts_with(MAGIC) {
        return Err(ParseError::malformed("missing `AliconaImaging` magic"));
    }
    let mut tags = BTreeMap::new();
    for (index, expected) in [(0, "Version"), (1, "TagCount")] {
        let (key, value) = read_tag(bytes, index)?;
        if key != expected {
            return Err(ParseError::malformed(format!(
                "AL3D tag {index} is `{key}`, expected `{expected}`"
            )));
        }
        tags.insert(key, value);
    }
    let count_text = tags.get("TagCount").cloned().unwrap_or_default();
    let count: usize = count_text.parse().map_err(|_| {
        ParseError::malformed(format!("AL3D TagCount `{count_text}` is not an integer"))
    })?;
    if count.saturating_add(2).saturating_mul(TAG_SIZE) > bytes.len() {
        return Err(ParseError::truncated(format!(
            "AL3D header of {count} tags"
        )));
    }
    for index in 2..count + 2 {
        let (key, value) = read_tag(bytes, index)?;
        tags.insert(key, value);
    }
    Ok(tags)
}

/// Where the depth image lies and how its points are stored.
struct DepthImage {
    nx: usize,
    ny: usize,
    /// `DepthImageOffset`, bytes.
    offset: usize,
    /// `TextureImageOffset` (0: no texture).
    texture_offset: usize,
    /// `InvalidPixelValue`, as the float32 the points hold.
    invalid: Option<f32>,
}

impl DepthImage {
    /// The heights (metres, `NaN` for invalid points), row by row without the row padding.
    fn heights(&self, bytes: &[u8]) -> Result<Vec<f64>, ParseError> {
        let (nx, ny, offset) = (self.nx, self.ny, self.offset);
        if nx == 0 || ny == 0 || offset == 0 {
            return Err(ParseError::unsupported("AL3D file without a depth image"));
        }
        let available = bytes.len().saturating_sub(offset) / 4;
        if nx.checked_mul(ny).is_none_or(|n| n > available) {
            return Err(ParseError::truncated(format!(
                "AL3D depth image of {nx} × {ny} float32 at byte {offset}"
            )));
        }
        let stride = self.row_stride(available)?;
        let n_values = stride * ny;
        if n_values > available {
            return Err(ParseError::truncated(format!(
                "AL3D depth image of {ny} rows × {stride} float32 at byte {offset}"
            )));
        }
        let data = &bytes[offset..offset + 4 * n_values];
        check_points(nx, ny, "AL3D header (Cols × Rows)")?;
        let mut values = Vec::with_capacity(nx * ny);
        for row in data.chunks_exact(4 * stride) {
            values.extend(row[..4 * nx].chunks_exact(4).map(|c| {
                let v = f32::from_le_bytes([c[0], c[1], c[2], c[3]]);
                if !v.is_finite() || Some(v) == self.invalid {
                    f64::NAN
                } else {
                    f64::from(v)
                }
            }));
        }
        Ok(values)
    }

    /// Values per stored row: from the gap to the texture, else `Cols` padded to a multiple of
    /// 8 when the file holds it, else `Cols`; never fewer than `Cols`.
    fn row_stride(&self, available: usize) -> Result<usize, ParseError> {
        let (nx, ny, offset, texture) = (self.nx, self.ny, self.offset, self.texture_offset);
        let padded = nx.div_ceil(8) * 8;
        let stride = if texture > offset && (texture - offset) % (4 * ny) == 0 {
            (texture - offset) / (4 * ny)
        } else if padded.checked_mul(ny).is_some_and(|n| n <= available) {
            padded
        } else {
            nx
        };
        if stride < nx {
            return Err(ParseError::malformed(format!(
                "AL3D depth rows of {stride} values are shorter than Cols = {nx}"
            )));
        }
        Ok(stride)
    }
}
