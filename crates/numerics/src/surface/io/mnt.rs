//! Digital Surf MountainsMap `.mnt` reader (a MountainsMap document).
//!
//! Layout (as SurfaceTopography's `MNT.py` reads it, and as `mnt/mnt-1.mnt` of the shared
//! folder shows it): a compound file ([`super::cfb`]) whose stream `ScopedContents` is a `u64`
//! (the stream's length − 8) followed by a tag-length-value tree ([`super::mnt_tlv`]). The
//! main container (tag 1) holds the document container (tag `0x02BD`): a byte (tag 1, the
//! number of document objects) and (tag 2) the document's objects. The object holding the
//! measured image is the container that lists three axis descriptors and the height block:
//!
//! * an axis descriptor is the entries `[axis (u32: 1 x, 2 y, 3 z), name, step (f64, in the
//!   unit that follows), unit, origin unit, unit ratio, origin (f64, in the origin unit), …,
//!   number of points (u32, x and y)]`;
//! * the height block is a container with `[points (u32), data]`, the data a block array of
//!   little-endian `i32` counts, rows of `nx` points one after the other;
//! * the mask of non-measured points, when the image has one, is an object of class 9056
//!   (an object is `[class (a container holding the u32 class number), body, …]`): its body
//!   holds the width and height (u32, tags 1 and 2: the image's `nx`, `ny`), the number of mask
//!   bytes (tag 3) and (tag 5) an array object `[class 9048, [count (u32), data]]`, a block array
//!   of `(nx + 2) × (ny + 2)` bytes, a border of one pixel around the image, rows one after the
//!   other: 9 marks a measured point, any other value (22 in the files seen) a missing one. An
//!   image whose mask object has class 0 (or none) has no missing point.
//! * A block array is a `u64` byte count then blocks of `u64` first element, `u32` elements and
//!   `u32` compressed bytes, each a zlib stream, which must cover the elements exactly once.
//!
//! A height is `z = origin_z + count · step_z` (metres after each unit's factor); the grid
//! spacing is the x and y step. The channel is named by the image's title. The mask's layout
//! is the one SurfaceTopography's `MNT.py` reads (2026), checked on its `mnt-2.mnt`.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::cfb::read_stream;
use super::limits::{check_count, check_points};
use super::mnt_tlv::{children, entries, Entry};
use super::reader::{Parser, Reader};
use super::text_units::length_unit_to_metres;
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

/// The registry entry of this format ([`super::READERS`]). A compound file is recognised by
/// its extension only: the signature is shared by every OLE2 document.
pub(crate) const READER: Reader = Reader {
    name: "mnt",
    description: "Digital Surf MountainsMap `.mnt`",
    extensions: &["mnt"],
    magic: None,
    parser: Parser::Single(parse),
};

/// Deepest container searched for the image (the file's tree is about ten levels deep).
const MAX_DEPTH: usize = 24;
/// Largest ratio of inflated to deflated bytes ([RFC 1951]: 258 bytes per 2-bit code, ~1032).
const MAX_INFLATE_RATIO: usize = 1032;
/// Class number of a mask of non-measured points, and of the byte array it holds.
const CLASS_MASK: u32 = 9056;
const CLASS_MASK_ARRAY: u32 = 9048;
/// Mask value of a measured point.
const MASK_MEASURED: u8 = 9;

/// One axis of the image.
#[derive(Debug, Clone)]
struct Axis {
    step: f64,
    unit: String,
    origin: f64,
    origin_unit: String,
    points: u32,
}

/// The measured image: title, x, y and z axes, point count, compressed data and mask.
struct Image<'a> {
    title: Option<String>,
    axes: [Axis; 3],
    points: usize,
    data: &'a [u8],
    mask: Option<Mask<'a>>,
}

/// The mask image of non-measured points as its object declares it.
struct Mask<'a> {
    /// Width and height without the border (tags 1 and 2).
    width: u32,
    height: u32,
    /// The mask's byte count (tag 3), when the body states it.
    declared: Option<u32>,
    /// The byte array's element count and its block array.
    count: u32,
    data: &'a [u8],
}

/// The number of points the measured image declares, without inflating the heights.
pub(crate) fn declared_points(bytes: &[u8]) -> Option<usize> {
    let stream = read_stream(bytes, "ScopedContents").ok()?;
    Some(locate(&stream).ok()?.points)
}

/// The measured image of the `ScopedContents` stream.
fn locate(stream: &[u8]) -> Result<Image<'_>, ParseError> {
    let declared = stream
        .get(..8)
        .map(|b| u64::from_le_bytes(b.try_into().unwrap_or_default()))
        .ok_or_else(|| ParseError::truncated("MNT ScopedContents: its 8-byte length"))?;
    if declared != stream.len() as u64 - 8 {
        return Err(ParseError::malformed(format!(
            "MNT ScopedContents declares {declared} bytes after its length, holds {}",
            stream.len() - 8
        )));
    }
    let not_tree = || ParseError::malformed("MNT ScopedContents is not a tag-length-value tree");
    let top = entries(&stream[8..]).ok_or_else(not_tree)?;
    let main = entries(find(&top, 1, "main container")?.value).ok_or_else(not_tree)?;
    let document = entries(find(&main, 0x02BD, "document container")?.value).ok_or_else(not_tree)?;
    find_image(find(&document, 2, "document objects")?.value, 0).ok_or_else(|| {
        ParseError::malformed(
            "MNT: no image with x, y and z axes and a height block in the document",
        )
    })
}

/// Parses the heights of a `.mnt` document.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let stream = read_stream(bytes, "ScopedContents")?;
    let image = locate(&stream)?;
    let [x, y, z] = &image.axes;
    let (nx, ny) = (x.points as usize, y.points as usize);
    let points = check_points(nx, ny, "MNT x and y axes")?;
    if points != image.points {
        return Err(ParseError::malformed(format!(
            "MNT axes give {nx} × {ny} points, the height block {}",
            image.points
        )));
    }
    let counts = decode_counts(image.data, points)?;
    let measured = match &image.mask {
        Some(mask) => Some(measured_points(mask, nx, ny)?),
        None => None,
    };
    let metres = |value: f64, unit: &str| {
        length_unit_to_metres(unit)
            .map(|f| value * f)
            .ok_or_else(|| ParseError::unsupported(format!("MNT unit `{unit}` is not a length")))
    };
    let (dx, dy) = (metres(x.step, &x.unit)?, metres(y.step, &y.unit)?);
    let (origin, step) = (metres(z.origin, &z.origin_unit)?, metres(z.step, &z.unit)?);
    let values = counts
        .into_iter()
        .enumerate()
        .map(|(k, c)| {
            if measured.as_ref().is_some_and(|m| !m[k]) {
                f64::NAN
            } else {
                origin + f64::from(c) * step
            }
        })
        .collect();
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("MNT array shape: {e}")))?;
    let map = HeightMap::new(heights, dx, dy)
        .map_err(|e| ParseError::malformed(format!("MNT image: {e}")))?;
    let mut metadata = BTreeMap::new();
    metadata.insert(super::METADATA_VENDOR.into(), "Digital Surf".into());
    Ok(Topography {
        data: TopographyData::Areal(map),
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        channel: image.title,
        channels: Vec::new(),
        metadata,
    })
}

/// The entry tagged `tag` of `list`; `what` names it for the error.
fn find<'a>(list: &[Entry<'a>], tag: u16, what: &str) -> Result<Entry<'a>, ParseError> {
    list.iter().find(|e| e.tag == tag).copied().ok_or_else(|| {
        ParseError::malformed(format!("MNT ScopedContents has no {what} (tag {tag:#06x})"))
    })
}

/// The first container, depth first, that lists the three axes and a height block.
fn find_image(bytes: &[u8], depth: usize) -> Option<Image<'_>> {
    let list = children(bytes)?;
    let block = list.iter().find_map(|e| height_block(e.value));
    let axis = |index: u32| list.iter().find_map(|e| axis(e.value, index));
    if let (Some((points, data)), Some(x), Some(y), Some(z)) = (block, axis(1), axis(2), axis(3)) {
        return Some(Image {
            title: list.first().and_then(Entry::text).filter(|t| !t.is_empty()),
            axes: [x, y, z],
            points,
            data,
            mask: list.iter().find_map(|e| mask(e.value)),
        });
    }
    if depth >= MAX_DEPTH {
        return None;
    }
    list.iter().find_map(|e| find_image(e.value, depth + 1))
}

/// The class number and body of an object (`[class container, body, …]`).
fn object(bytes: &[u8]) -> Option<(u32, &[u8])> {
    let list = entries(bytes)?;
    let [class, body, ..] = list.as_slice() else {
        return None;
    };
    if (class.tag, body.tag) != (1, 2) {
        return None;
    }
    let number = entries(class.value)?;
    let [number] = number.as_slice() else {
        return None;
    };
    Some((number.u32().filter(|_| number.tag == 1)?, body.value))
}

/// The mask object `bytes` holds, when it is one (class 9056 with a byte array); `None` for any
/// other entry.
fn mask(bytes: &[u8]) -> Option<Mask<'_>> {
    let (class, body) = object(bytes)?;
    if class != CLASS_MASK {
        return None;
    }
    let fields = entries(body)?;
    let field = |tag: u16| fields.iter().find(|e| e.tag == tag);
    let (array_class, array) = object(field(5)?.value)?;
    let array = entries(array).filter(|_| array_class == CLASS_MASK_ARRAY)?;
    let [count, data] = array.as_slice() else {
        return None;
    };
    Some(Mask {
        width: field(1)?.u32()?,
        height: field(2)?.u32()?,
        declared: field(3).and_then(Entry::u32),
        count: count.u32().filter(|_| count.tag == 1 && data.tag == 2)?,
        data: data.value,
    })
}

/// Which of the `nx × ny` points the mask marks measured (row by row), after checking the
/// mask's sizes against the image's.
fn measured_points(mask: &Mask<'_>, nx: usize, ny: usize) -> Result<Vec<bool>, ParseError> {
    let bordered = (nx + 2) * (ny + 2);
    let sizes_agree = (mask.width as usize, mask.height as usize) == (nx, ny)
        && mask.count as usize == bordered
        && mask.declared.is_none_or(|d| d as usize == bordered);
    if !sizes_agree {
        let stated = mask.declared.map_or(String::new(), |d| format!(", {d} stated"));
        return Err(ParseError::malformed(format!(
            "MNT mask of non-measured points: {} × {} points in {} bytes{stated}; the image \
             {nx} × {ny} needs ({nx} + 2) × ({ny} + 2) = {bordered}",
            mask.width, mask.height, mask.count
        )));
    }
    let bytes = decode_blocks(mask.data, bordered, 1, "MNT mask")?;
    Ok(bytes
        .chunks_exact(nx + 2)
        .skip(1)
        .take(ny)
        .flat_map(|row| row[1..=nx].iter().map(|&b| b == MASK_MEASURED))
        .collect())
}

/// The point count and data of a height block container, whose byte count is 4 per point.
fn height_block(bytes: &[u8]) -> Option<(usize, &[u8])> {
    let list = entries(bytes)?;
    list.iter().filter(|e| e.tag == 2).find_map(|e| {
        let inner = entries(e.value)?;
        let [count, data] = inner.as_slice() else {
            return None;
        };
        let points = count.u32().filter(|_| count.tag == 1 && data.tag == 2)? as usize;
        let size = u64::from_le_bytes(data.value.get(..8)?.try_into().ok()?);
        (size == 4 * points as u64).then_some((points, data.value))
    })
}

/// The axis descriptor `bytes` holds, when its axis number is `index`.
fn axis(bytes: &[u8], index: u32) -> Option<Axis> {
    let list = entries(bytes)?;
    let tags: Vec<u16> = list.iter().take(9).map(|e| e.tag).collect();
    if tags != [1, 2, 1, 2, 3, 4, 5, 6, 1] || list[0].u32()? != index {
        return None;
    }
    Some(Axis {
        step: list[2].f64().filter(|s| s.is_finite() && *s != 0.0)?,
        unit: list[3].text()?,
        origin_unit: list[4].text()?,
        origin: list[6].f64().filter(|o| o.is_finite())?,
        points: list[8].u32()?,
    })
}

/// The `i32` counts of the height data (`points` of them).
fn decode_counts(data: &[u8], points: usize) -> Result<Vec<i32>, ParseError> {
    let raw = decode_blocks(data, points, 4, "MNT height block")?;
    Ok(raw
        .chunks_exact(4)
        .map(|c| i32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect())
}

/// The bytes of a block array of `count` elements of `size` bytes, from its zlib blocks, which
/// must cover the elements exactly once; `what` names the array.
fn decode_blocks(
    data: &[u8],
    count: usize,
    size: usize,
    what: &str,
) -> Result<Vec<u8>, ParseError> {
    check_count(count, what)?;
    if count.saturating_mul(size) > data.len().saturating_mul(MAX_INFLATE_RATIO) {
        return Err(ParseError::truncated(format!(
            "{what} declares {count} points, more than its {} compressed bytes can hold",
            data.len()
        )));
    }
    let declared = data.get(..8).map(|b| u64::from_le_bytes(b.try_into().unwrap_or_default()));
    if declared != Some((count * size) as u64) {
        return Err(ParseError::malformed(format!(
            "{what} declares {} bytes, {count} points of {size} bytes are {}",
            declared.map_or("no".to_string(), |d| d.to_string()),
            count * size
        )));
    }
    let mut raw = vec![0u8; count * size];
    let mut next = 0usize;
    for (first, n, stream) in blocks(data, what)? {
        if first != next as u64 || n > count - next {
            return Err(ParseError::malformed(format!(
                "{what}: a block of {n} points starts at point {first}, point {next} expected \
                 (of {count})"
            )));
        }
        let out = &mut raw[next * size..(next + n) * size];
        let written = miniz_oxide::inflate::decompress_slice_iter_to_slice(
            out,
            std::iter::once(stream),
            true,
            false,
        );
        if written != Ok(n * size) {
            let why = match written {
                Ok(bytes) => format!("it gives {bytes} bytes, {} expected", n * size),
                Err(status) => format!("zlib status {status:?}"),
            };
            return Err(ParseError::malformed(format!(
                "{what} at point {first}: the zlib stream does not inflate to {n} points ({why})"
            )));
        }
        next += n;
    }
    if next != count {
        return Err(ParseError::truncated(format!(
            "{what}s cover {next} of {count} points"
        )));
    }
    Ok(raw)
}

/// One block of a block array: its first element, its elements and its zlib stream.
type Block<'a> = (u64, usize, &'a [u8]);

/// The blocks of a block array, sorted by first element.
fn blocks<'a>(data: &'a [u8], what: &str) -> Result<Vec<Block<'a>>, ParseError> {
    let mut blocks = Vec::new();
    let mut pos = 8usize;
    while pos < data.len() {
        let head = data
            .get(pos..pos + 16)
            .ok_or_else(|| ParseError::truncated(format!("{what} header at byte {pos}")))?;
        let first = u64::from_le_bytes(head[..8].try_into().unwrap_or_default());
        let n = u32::from_le_bytes(head[8..12].try_into().unwrap_or_default()) as usize;
        let size = u32::from_le_bytes(head[12..].try_into().unwrap_or_default()) as usize;
        let stream = data.get(pos + 16..pos + 16 + size).ok_or_else(|| {
            ParseError::truncated(format!(
                "{what} at byte {pos}: {size} compressed bytes, {} left",
                data.len() - pos - 16
            ))
        })?;
        blocks.push((first, n, stream));
        pos += 16 + size;
    }
    blocks.sort_by_key(|b| b.0);
    Ok(blocks)
}

#[cfg(test)]
mod tests {
    use super::decode_counts as decode;

    /// A height block of `blocks` (first point, points, zlib stream) declaring `points`.
    fn block(points: usize, blocks: &[(u64, u32, &[u8])]) -> Vec<u8> {
        let mut out = (4 * points as u64).to_le_bytes().to_vec();
        for (first, n, stream) in blocks {
            out.extend_from_slice(&first.to_le_bytes());
            out.extend_from_slice(&n.to_le_bytes());
            out.extend_from_slice(&(stream.len() as u32).to_le_bytes());
            out.extend_from_slice(stream);
        }
        out
    }

    /// zlib of the `i32` values 1 and −2 (a stored block).
    const ONE_MINUS_TWO: [u8; 19] = [
        0x78, 0x01, 0x01, 0x08, 0x00, 0xf7, 0xff, 1, 0, 0, 0, 0xfe, 0xff, 0xff, 0xff, 0x0a, 0x02,
        0x03, 0xfd,
    ];

    #[test]
    fn blocks_are_placed_by_their_first_point() {
        let data = block(4, &[(2, 2, &ONE_MINUS_TWO), (0, 2, &ONE_MINUS_TWO)]);
        assert_eq!(decode(&data, 4).unwrap(), [1, -2, 1, -2]);
    }

    #[test]
    fn gaps_overlaps_and_impossible_counts_are_errors() {
        let gap = block(4, &[(0, 2, &ONE_MINUS_TWO)]);
        assert!(decode(&gap, 4)
            .unwrap_err()
            .to_string()
            .contains("cover 2 of 4"));
        let overlap = block(4, &[(0, 2, &ONE_MINUS_TWO), (1, 2, &ONE_MINUS_TWO)]);
        assert!(decode(&overlap, 4).is_err());
        let short = block(2, &[(0, 2, &ONE_MINUS_TWO[..10])]);
        assert!(decode(&short, 2).is_err());
        let lie = block(100_000_000, &[(0, 2, &ONE_MINUS_TWO)]);
        let err = decode(&lie, 100_000_000).unwrap_err().to_string();
        assert!(err.contains("compressed bytes can hold"), "{err}");
    }
}
