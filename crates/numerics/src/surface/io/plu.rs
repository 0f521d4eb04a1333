//! Sensofar `.plu` reader (PLu neox / S neox confocal and interferometric profilers).
//!
//! Layout (little endian): a 500-byte header, then `rows: u32`, `cols: u32` and
//! `rows × cols` float32 heights in µm (x fastest), followed by data this reader ignores
//! (statistics, a colour image). Header fields used (byte offsets):
//!
//! | offset | field |
//! |---|---|
//! | 0 | acquisition date, text (128 bytes) |
//! | 132 | user comment, text (256 bytes) |
//! | 388, 392 | `yres`, `xres` of the calibrated image (u32) |
//! | 404, 408 | `mppx`, `mppy`: pixel size along x, y in µm (float32) |
//! | 428 | measurement type (u32: 0 confocal image, 1 confocal profile, 3 topography …) |
//! | 440 | objective code (u32) |
//!
//! The value 1 000 001 µm marks a non-measured point (Sensofar's `NOT_MEASURED`); it and
//! non-finite values become `NaN`.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{check_block_size, decode_samples, ByteCursor, Endian, SampleType};
use super::reader::{Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

/// Byte offset of the `rows`, `cols` pair in front of the height data.
const DATA_DIMENSIONS_OFFSET: usize = 500;
/// Sensofar's marker for a non-measured point, in µm.
const NOT_MEASURED_UM: f64 = 1_000_001.0;
const MICROMETRE: f64 = 1e-6;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "plu",
    description: "Sensofar `.plu`",
    extensions: &["plu"],
    magic: None,
    parser: Parser::Single(parse),
};

/// Parses a Sensofar `.plu` file.
pub(crate) fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let le = Endian::Little;
    let mut c = ByteCursor::new(bytes);
    let mut meta = BTreeMap::new();
    let date = c.text(128, "plu date")?;
    if date.chars().any(|ch| ch.is_control()) {
        return Err(ParseError::malformed(
            "plu: header does not start with a date text",
        ));
    }
    meta.insert("date".into(), date);
    c.seek(132, "plu comment")?;
    meta.insert("comment".into(), c.text(256, "plu comment")?);
    let yres = c.u32(le, "plu calibration yres")? as usize;
    let xres = c.u32(le, "plu calibration xres")? as usize;
    c.seek(404, "plu pixel size")?;
    let mppx = f64::from(c.f32(le, "plu mppx")?);
    let mppy = f64::from(c.f32(le, "plu mppy")?);
    c.seek(428, "plu measurement block")?;
    meta.insert(
        "measurement_type".into(),
        c.u32(le, "plu measurement type")?.to_string(),
    );
    c.seek(440, "plu objective")?;
    meta.insert("objective".into(), c.u32(le, "plu objective")?.to_string());
    c.seek(DATA_DIMENSIONS_OFFSET, "plu data dimensions")?;
    let rows = c.u32(le, "plu rows")? as usize;
    let cols = c.u32(le, "plu cols")? as usize;
    if (rows, cols) != (yres, xres) {
        return Err(ParseError::malformed(format!(
            "plu: data block is {cols} × {rows}, calibration says {xres} × {yres}"
        )));
    }
    for (name, v) in [("mppx", mppx), ("mppy", mppy)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(ParseError::malformed(format!(
                "plu: pixel size {name} = {v} µm is not > 0"
            )));
        }
    }
    let n = rows
        .checked_mul(cols)
        .ok_or_else(|| ParseError::malformed("plu: rows × cols overflows"))?;
    let block = check_block_size(n, 4, c.remaining(), "plu height data")?;
    let raw = decode_samples(
        c.take(block, "plu height data")?,
        n,
        SampleType::F32,
        le,
        "plu",
    )?;
    let heights: Vec<f64> = raw
        .into_iter()
        .map(|v| {
            if v == NOT_MEASURED_UM || !v.is_finite() {
                f64::NAN
            } else {
                v * MICROMETRE
            }
        })
        .collect();
    let grid = Array2::from_shape_vec((rows, cols), heights)
        .map_err(|e| ParseError::malformed(format!("plu: grid shape: {e}")))?;
    let map = HeightMap::new(grid, mppx * MICROMETRE, mppy * MICROMETRE)
        .map_err(|e| ParseError::malformed(format!("plu: {e}")))?;
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: None,
        channels: Vec::new(),
        metadata: meta,
    })
}
