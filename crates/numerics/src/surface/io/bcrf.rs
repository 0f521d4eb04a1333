//! Image Metrology SPIP BCR-STM / BCRF reader (`.bcr`, `.bcrf`).
//!
//! Layout (Image Metrology's "BCR-STM file format" reference, as read by Gwyddion's `bcrfile.c`
//! and SurfaceTopography's `BCR.py`): a text header of `headersize` characters (2048 by
//! default), Latin-1 or, for the `*_unicode` variants, UTF-16LE (2 bytes per character). Its
//! first line is `fileformat = bcrstm` (int16 data), `bcrf` (float32 data) or either with
//! `_unicode`; then `key = value` lines, `%` and `#` lines being comments. The `xpixels ×
//! ypixels` samples follow the header, row by row with x fastest, little-endian when
//! `intelmode = 1`.
//!
//! * Lateral: `xlength`, `ylength` are the full scan sizes in `xunit`/`yunit` (default nm):
//!   `dx = xlength / xpixels`.
//! * Heights: `z = value · bit2nm · zunit` (zunit default nm), SurfaceTopography's rule: float
//!   data are in `zunit` (µm in the files seen, with `bit2nm = 1`), integer data count steps.
//! * Void points: with a non-zero `voidpixels`, int16 32767 and float values above 1.7·10³⁸
//!   (the 3.402823·10³⁸ marker) are missing (Gwyddion's test); non-finite values always are.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{decode_samples, Endian, SampleType};
use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::text_units::length_unit_to_metres;
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &str = "fileformat = bcr";
const DEFAULT_HEADER_CHARS: usize = 2048;
/// Largest header accepted, characters.
const MAX_HEADER_CHARS: usize = 1 << 20;

/// How the header text is encoded.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Encoding {
    Latin1,
    Utf16Le,
}

fn encoding_of(head: &[u8]) -> Option<Encoding> {
    let utf16: Vec<u8> = MAGIC.bytes().flat_map(|b| [b, 0]).collect();
    if head.starts_with(MAGIC.as_bytes()) {
        Some(Encoding::Latin1)
    } else if head.starts_with(&utf16) {
        Some(Encoding::Utf16Le)
    } else {
        None
    }
}

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "bcrf",
    description: "Image Metrology SPIP BCR-STM / BCRF `.bcr`, `.bcrf`",
    extensions: &["bcr", "bcrf"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` starts with a BCR-STM / BCRF `fileformat` line.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    encoding_of(head).is_some()
}

/// The first `chars` characters of the header as text.
fn decode_text(bytes: &[u8], encoding: Encoding, chars: usize) -> String {
    match encoding {
        Encoding::Latin1 => bytes.iter().take(chars).map(|&b| char::from(b)).collect(),
        Encoding::Utf16Le => {
            let units = bytes
                .chunks_exact(2)
                .take(chars)
                .map(|c| u16::from_le_bytes([c[0], c[1]]));
            char::decode_utf16(units)
                .map(|c| c.unwrap_or(char::REPLACEMENT_CHARACTER))
                .collect()
        }
    }
}

/// `key = value` pairs of the header; comment lines (`%`, `#`) and lines without `=` skipped.
fn header_fields(text: &str) -> BTreeMap<String, String> {
    text.lines()
        .map(|l| l.trim_matches(|c: char| c.is_whitespace() || c == '\0'))
        .filter(|l| !l.starts_with('%') && !l.starts_with('#'))
        .filter_map(|l| l.split_once('='))
        .map(|(k, v)| (k.trim().to_string(), v.trim().to_string()))
        .filter(|(k, v)| !k.is_empty() && !v.is_empty())
        .collect()
}

/// The header's `key = value` fields and its length in bytes.
fn read_header(bytes: &[u8]) -> Result<(BTreeMap<String, String>, usize), ParseError> {
    let encoding = encoding_of(bytes)
        .ok_or_else(|| ParseError::malformed("missing `fileformat = bcrstm/bcrf` first line"))?;
    let unit_bytes = if encoding == Encoding::Latin1 { 1 } else { 2 };
    let first = header_fields(&decode_text(bytes, encoding, DEFAULT_HEADER_CHARS));
    let header_chars = match first.get("headersize") {
        Some(v) => v
            .parse::<usize>()
            .ok()
            .filter(|&n| n <= MAX_HEADER_CHARS)
            .ok_or_else(|| {
                ParseError::malformed(format!(
                    "BCR headersize `{v}` is not a character count up to {MAX_HEADER_CHARS}"
                ))
            })?,
        None => DEFAULT_HEADER_CHARS,
    };
    let header_bytes = header_chars * unit_bytes;
    if bytes.len() < header_bytes {
        return Err(ParseError::truncated(format!(
            "BCR header of {header_bytes} bytes, the file has {}",
            bytes.len()
        )));
    }
    let fields = header_fields(&decode_text(bytes, encoding, header_chars));
    Ok((fields, header_bytes))
}

/// Parses a BCR-STM or BCRF file into heights in metres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let (fields, header_bytes) = read_header(bytes)?;
    let get = |key: &str| {
        fields
            .get(key)
            .ok_or_else(|| ParseError::malformed(format!("BCR header has no `{key}`")))
    };
    let number = |key: &str| -> Result<f64, ParseError> {
        let v = get(key)?;
        v.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| ParseError::malformed(format!("BCR {key} `{v}` is not a number")))
    };
    let count = |key: &str| -> Result<usize, ParseError> {
        let v = get(key)?;
        v.parse::<usize>().map_err(|_| {
            ParseError::malformed(format!("BCR {key} `{v}` is not a non-negative integer"))
        })
    };
    let sample = match get("fileformat")?.as_str() {
        "bcrstm" | "bcrstm_unicode" => SampleType::I16,
        "bcrf" | "bcrf_unicode" => SampleType::F32,
        other => {
            return Err(ParseError::unsupported(format!(
                "BCR fileformat `{other}` (only bcrstm and bcrf, plain or _unicode)"
            )))
        }
    };
    let (nx, ny) = (count("xpixels")?, count("ypixels")?);
    let n = check_points(nx, ny, "BCR header (xpixels × ypixels)")?;
    let endian = match fields.get("intelmode").map(String::as_str) {
        Some("0") => Endian::Big,
        _ => Endian::Little,
    };
    let unit = |key: &str| -> Result<f64, ParseError> {
        let name = fields.get(key).map_or("nm", String::as_str);
        length_unit_to_metres(name).ok_or_else(|| {
            ParseError::unsupported(format!(
                "BCR {key} `{name}` is not a length unit (a topography needs heights)"
            ))
        })
    };
    let dx = number("xlength")? * unit("xunit")? / nx.max(1) as f64;
    let dy = number("ylength")? * unit("yunit")? / ny.max(1) as f64;
    let bit2nm = fields.get("bit2nm").map_or(Ok(1.0), |_| number("bit2nm"))?;
    let z_factor = bit2nm * unit("zunit")?;
    let voids = fields
        .get("voidpixels")
        .and_then(|v| v.parse::<f64>().ok())
        .is_some_and(|v| v != 0.0);
    let raw = decode_samples(&bytes[header_bytes..], n, sample, endian, "BCR data")?;
    let is_void = |v: f64| match sample {
        SampleType::I16 => voids && v == 32767.0,
        _ => !v.is_finite() || (voids && v > 1.7e38),
    };
    let values = raw
        .into_iter()
        .map(|v| if is_void(v) { f64::NAN } else { v * z_factor })
        .collect();
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("BCR array shape: {e}")))?;
    let map =
        HeightMap::new(heights, dx, dy).map_err(|e| ParseError::malformed(format!("BCR: {e}")))?;
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: None,
        channels: Vec::new(),
        metadata: metadata(&fields),
    })
}

/// The header fields kept as metadata.
fn metadata(fields: &BTreeMap<String, String>) -> BTreeMap<String, String> {
    let mut metadata = BTreeMap::new();
    metadata.insert("vendor".into(), "Image Metrology (SPIP)".into());
    for key in [
        "fileformat",
        "xoffset",
        "yoffset",
        "xunit",
        "zunit",
        "bit2nm",
        "starttime",
    ] {
        if let Some(v) = fields.get(key) {
            metadata.insert(key.into(), v.clone());
        }
    }
    metadata
}
