//! NumPy `.npy` reader: a bare array of heights.
//!
//! Format (NumPy format versions 1–3): magic `\x93NUMPY`, version bytes, header length (u16
//! LE in version 1, u32 LE in versions 2 and 3), then a Python dict literal
//! `{'descr': '<f8', 'fortran_order': False, 'shape': (ny, nx), }` and the raw data.
//!
//! Conventions, since a plain `.npy` carries no physical metadata:
//! * heights are **metres** (asperity's convention for `.npy`; [`Topography::height_unit`] is
//!   [`ScaleSource::Assumed`] all the same); `NaN` and ±inf mark a missing point;
//! * a 2-D array is `[iy, ix]` (rows are y, x fastest in C order; Fortran order is honoured);
//! * **spacing: a placeholder of 1 pixel = 1 m** with [`Topography::spacing`] =
//!   [`ScaleSource::Assumed`], so that a caller (e.g. the surface node, which then requires
//!   `pixel_size` or `size`) knows it must supply the real spacing;
//! * a 1-D array is a line scan with x = i · 1 m (same flag).
//!
//! Supported `descr`: `f4`, `f8`, `i1`, `i2`, `i4`, `u1`, `u2`, `u4`, little (`<`), big (`>`)
//! or not applicable (`|`) byte order.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{check_block_size, decode_samples, ByteCursor, Endian, SampleType};
use super::reader::{Parser, Reader};
use super::{LineScan, ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"\x93NUMPY";

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "npy",
    description: "NumPy `.npy` (heights in metres, no lateral calibration)",
    extensions: &["npy"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` for the NumPy magic string.
pub(crate) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

/// Parses a `.npy` file (see the module docs for the spacing convention).
pub(crate) fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let le = Endian::Little;
    let mut c = ByteCursor::new(bytes);
    if c.take(MAGIC.len(), "npy magic")? != MAGIC {
        return Err(ParseError::malformed("npy: missing \\x93NUMPY magic"));
    }
    let major = c.u8("npy major version")?;
    let _minor = c.u8("npy minor version")?;
    let header_len = match major {
        1 => usize::from(c.u16(le, "npy header length")?),
        2 | 3 => c.u32(le, "npy header length")? as usize,
        v => return Err(ParseError::unsupported(format!("npy: format version {v}"))),
    };
    let header = c.take(header_len, "npy header")?;
    let header = std::str::from_utf8(header)
        .map_err(|_| ParseError::malformed("npy: header is not text"))?;
    let descr = dict_value(header, "descr")?;
    let descr = descr.trim().trim_matches(|ch| ch == '\'' || ch == '"');
    let (endian, sample) = parse_descr(descr)?;
    let fortran = match dict_value(header, "fortran_order")?.trim() {
        "True" => true,
        "False" => false,
        other => {
            return Err(ParseError::malformed(format!(
                "npy: fortran_order {other:?} is not True/False"
            )))
        }
    };
    let shape = parse_shape(dict_value(header, "shape")?)?;
    let n = shape
        .iter()
        .try_fold(1usize, |acc, &d| acc.checked_mul(d))
        .ok_or_else(|| ParseError::malformed("npy: shape overflows"))?;
    let block = check_block_size(n, sample.size(), c.remaining(), "npy data")?;
    let values: Vec<f64> = decode_samples(c.take(block, "npy data")?, n, sample, endian, "npy")?
        .into_iter()
        .map(|v| if v.is_finite() { v } else { f64::NAN })
        .collect();
    let mut metadata = BTreeMap::new();
    metadata.insert("npy_descr".to_string(), descr.to_string());
    let data = match shape.as_slice() {
        [len] => TopographyData::Line(LineScan {
            x: (0..*len).map(|i| i as f64).collect(),
            z: values,
        }),
        [ny, nx] => {
            let grid = if fortran {
                Array2::from_shape_vec((*nx, *ny), values).map(|a| a.reversed_axes())
            } else {
                Array2::from_shape_vec((*ny, *nx), values)
            }
            .map_err(|e| ParseError::malformed(format!("npy: shape: {e}")))?;
            let grid = grid.as_standard_layout().into_owned();
            TopographyData::Areal(
                HeightMap::new(grid, 1.0, 1.0)
                    .map_err(|e| ParseError::malformed(format!("npy: {e}")))?,
            )
        }
        other => {
            return Err(ParseError::unsupported(format!(
                "npy: {}-D array (only 1-D line scans and 2-D maps)",
                other.len()
            )))
        }
    };
    Ok(Topography {
        spacing: ScaleSource::Assumed,
        height_unit: ScaleSource::Assumed,
        data,
        channel: None,
        channels: Vec::new(),
        metadata,
    })
}

/// The raw text of `'key': value` in the header dict, up to the next top-level comma.
fn dict_value<'a>(header: &'a str, key: &str) -> Result<&'a str, ParseError> {
    let start = ["'", "\""]
        .iter()
        .find_map(|q| header.find(&format!("{q}{key}{q}")))
        .ok_or_else(|| ParseError::malformed(format!("npy: header lacks '{key}'")))?;
    let rest = &header[start + key.len() + 2..];
    let rest = rest
        .trim_start()
        .strip_prefix(':')
        .ok_or_else(|| ParseError::malformed(format!("npy: no ':' after '{key}'")))?;
    let mut depth = 0usize;
    for (i, ch) in rest.char_indices() {
        match ch {
            '(' => depth += 1,
            ')' => depth = depth.saturating_sub(1),
            ',' | '}' if depth == 0 => return Ok(&rest[..i]),
            _ => {}
        }
    }
    Err(ParseError::malformed(format!(
        "npy: value of '{key}' is not terminated"
    )))
}

fn parse_descr(descr: &str) -> Result<(Endian, SampleType), ParseError> {
    let unsupported = || ParseError::unsupported(format!("npy: dtype {descr:?}"));
    let mut chars = descr.chars();
    let endian = match chars.next() {
        Some('<' | '|' | '=') => Endian::Little,
        Some('>') => Endian::Big,
        _ => return Err(unsupported()),
    };
    let sample = match chars.as_str() {
        "f4" => SampleType::F32,
        "f8" => SampleType::F64,
        "i1" => SampleType::I8,
        "i2" => SampleType::I16,
        "i4" => SampleType::I32,
        "u1" => SampleType::U8,
        "u2" => SampleType::U16,
        "u4" => SampleType::U32,
        _ => return Err(unsupported()),
    };
    Ok((endian, sample))
}

fn parse_shape(text: &str) -> Result<Vec<usize>, ParseError> {
    let inner = text
        .trim()
        .strip_prefix('(')
        .and_then(|t| t.strip_suffix(')'))
        .ok_or_else(|| ParseError::malformed(format!("npy: shape {text:?} is not a tuple")))?;
    inner
        .split(',')
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .map(|t| {
            t.parse::<usize>()
                .map_err(|_| ParseError::malformed(format!("npy: shape entry {t:?}")))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn npy(descr: &str, shape: &str, fortran: bool, data: &[u8]) -> Vec<u8> {
        let dict = format!(
            "{{'descr': '{descr}', 'fortran_order': {}, 'shape': {shape}, }}",
            if fortran { "True" } else { "False" }
        );
        let mut out = MAGIC.to_vec();
        out.extend([1u8, 0]);
        out.extend((dict.len() as u16).to_le_bytes());
        out.extend(dict.as_bytes());
        out.extend(data);
        out
    }

    #[test]
    fn reads_big_endian_int16_in_fortran_order() {
        // Column-major 2 × 3 array [[1, 2, 3], [4, 5, 6]] stored as 1 4 2 5 3 6.
        let data: Vec<u8> = [1i16, 4, 2, 5, 3, 6]
            .iter()
            .flat_map(|v| v.to_be_bytes())
            .collect();
        let t = parse(&npy(">i2", "(2, 3)", true, &data)).unwrap();
        let TopographyData::Areal(m) = t.data else {
            panic!("expected an areal map")
        };
        assert_eq!((m.nx(), m.ny()), (3, 2));
        assert_eq!(m.heights()[[1, 0]], 4.0);
        assert_eq!(m.heights()[[0, 2]], 3.0);
        assert_eq!(t.spacing, ScaleSource::Assumed);
    }

    #[test]
    fn nan_is_missing_and_lying_shape_is_rejected() {
        let data: Vec<u8> = [0.5f32, f32::NAN, 1.0, 2.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let t = parse(&npy("<f4", "(2, 2)", false, &data)).unwrap();
        let TopographyData::Areal(m) = t.data else {
            panic!("expected an areal map")
        };
        assert_eq!(m.missing_count(), 1);
        let err = parse(&npy("<f4", "(100000, 100000)", false, &data)).unwrap_err();
        assert!(matches!(err, ParseError::Truncated { .. }), "{err}");
    }
}
