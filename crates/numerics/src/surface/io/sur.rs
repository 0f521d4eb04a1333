//! Digital Surf `.sur` reader (MountainsMap surface file, uncompressed, first object).
//!
//! Layout: a 512-byte little-endian header, then `comment_size` bytes of comment and
//! `private_size` bytes of private zone, then `xres × yres` signed integers of `pointsize` bits
//! (16 or 32), x fastest. Header fields used (byte offsets):
//!
//! | offset | field |
//! |---|---|
//! | 0 | signature `DIGITAL SURF` (`DSCOMPRESSED` = zlib-compressed variant, not read) |
//! | 12 | format (0 = PC byte order) |
//! | 86 | `special_points` (≠ 0: the file contains non-measured points) |
//! | 98, 100, 104 | `pointsize`, `zmin`, `zmax` (raw integers) |
//! | 108, 112, 116 | `xres`, `yres`, number of points |
//! | 120, 124, 128 | `dx`, `dy`, `dz` (float32, in the step units below) |
//! | 180, 196, 212 | step units of x, y, z (16 chars each, e.g. `µm`, `nm`) |
//! | 276 … 284 | ratios between step and length units (informative only) |
//! | 334, 336 | comment size, private-zone size |
//! | 474 | `ZOffset` (float32, z length unit) |
//!
//! Spacing = dx · unit(dx) (m); height = raw · dz · unit(dz) (m). As in MountainsMap, the raw
//! value `zmin − 2` marks a non-measured point when `special_points ≠ 0`; this reader treats
//! any raw value below `zmin` as non-measured (`NaN`), since it contradicts the header's own
//! minimum. `ZOffset` is reported in the metadata, not added to the heights.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{check_block_size, decode_samples, ByteCursor, Endian, SampleType};
use super::reader::{Parser, Reader};
use super::text_units::length_unit_to_metres;
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const HEADER_SIZE: usize = 512;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "sur",
    description: "Digital Surf `.sur` (uncompressed)",
    extensions: &["sur"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` for a Digital Surf signature.
pub(crate) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(b"DIGITAL SURF") || head.starts_with(b"DSCOMPRESSED")
}

/// The header fields the heights need (the rest goes to the metadata).
struct SurHeader {
    special_points: u16,
    sample: SampleType,
    zmin: i32,
    zmax: i32,
    xres: usize,
    yres: usize,
    /// `xres × yres`, equal to the header's own point count.
    points: usize,
    dx_m: f64,
    dy_m: f64,
    dz_m: f64,
    z_unit: String,
    comment_size: usize,
    private_size: usize,
}

/// Parses a Digital Surf `.sur` file.
pub(crate) fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let mut c = ByteCursor::new(bytes);
    check_signature(&mut c, bytes.len())?;
    let mut meta = BTreeMap::new();
    let header = read_header(&mut c, &mut meta)?;
    let heights = read_heights(&mut c, &header, &mut meta)?;
    meta.insert("z_unit".into(), header.z_unit);
    meta.insert("raw_zmin".into(), header.zmin.to_string());
    meta.insert("raw_zmax".into(), header.zmax.to_string());
    let grid = Array2::from_shape_vec((header.yres, header.xres), heights)
        .map_err(|e| ParseError::malformed(format!("sur: grid shape: {e}")))?;
    let map = HeightMap::new(grid, header.dx_m, header.dy_m)
        .map_err(|e| ParseError::malformed(format!("sur: {e}")))?;
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: None,
        channels: Vec::new(),
        metadata: meta,
    })
}

/// The signature (an uncompressed file), a whole header and the PC byte order.
fn check_signature(c: &mut ByteCursor<'_>, len: usize) -> Result<(), ParseError> {
    let signature = c.text(12, "sur signature")?;
    if signature == "DSCOMPRESSED" {
        return Err(ParseError::unsupported(
            "sur: compressed (DSCOMPRESSED) files",
        ));
    }
    if signature != "DIGITAL SURF" {
        return Err(ParseError::malformed(format!(
            "sur: signature {signature:?} is not \"DIGITAL SURF\""
        )));
    }
    if len < HEADER_SIZE {
        return Err(ParseError::truncated(format!(
            "sur: header needs {HEADER_SIZE} bytes, file has {len}"
        )));
    }
    let byte_order = c.u16(Endian::Little, "sur format")?;
    if byte_order != 0 {
        return Err(ParseError::unsupported(format!(
            "sur: format {byte_order} (only PC byte order 0 is read)"
        )));
    }
    Ok(())
}

/// The header after the byte order: descriptive fields into `meta`, the grid, the steps in
/// metres and the sizes of the zones before the heights.
fn read_header(
    c: &mut ByteCursor<'_>,
    meta: &mut BTreeMap<String, String>,
) -> Result<SurHeader, ParseError> {
    let le = Endian::Little;
    read_object_fields(c, meta)?;
    c.seek(86, "sur special points")?;
    let special_points = c.u16(le, "sur special points")?;
    c.seek(98, "sur point size")?;
    let point_size = c.u16(le, "sur point size")?;
    let zmin = c.i32(le, "sur zmin")?;
    let zmax = c.i32(le, "sur zmax")?;
    let xres = positive(c.i32(le, "sur xres")?, "xres")?;
    let yres = positive(c.i32(le, "sur yres")?, "yres")?;
    let n_points = c.u32(le, "sur number of points")? as usize;
    let dx = f64::from(c.f32(le, "sur dx")?);
    let dy = f64::from(c.f32(le, "sur dy")?);
    let dz = f64::from(c.f32(le, "sur dz")?);
    c.seek(180, "sur units")?;
    let x_unit = c.text(16, "sur x step unit")?;
    let y_unit = c.text(16, "sur y step unit")?;
    let z_unit = c.text(16, "sur z step unit")?;
    read_flags_and_date(c, meta)?;
    c.seek(334, "sur zone sizes")?;
    let comment_size = usize::from(c.u16(le, "sur comment size")?);
    let private_size = usize::from(c.u16(le, "sur private size")?);
    c.seek(474, "sur z offset")?;
    meta.insert("z_offset".into(), c.f32(le, "sur z offset")?.to_string());
    let sample = sample_type(point_size)?;
    let points = grid_points(xres, yres, n_points)?;
    Ok(SurHeader {
        special_points,
        sample,
        zmin,
        zmax,
        xres,
        yres,
        points,
        dx_m: step_in_metres(dx, &x_unit, "x")?,
        dy_m: step_in_metres(dy, &y_unit, "y")?,
        dz_m: step_in_metres(dz, &z_unit, "z")?,
        z_unit,
        comment_size,
        private_size,
    })
}

/// Object count, version, type, object and operator names, acquisition type.
fn read_object_fields(
    c: &mut ByteCursor<'_>,
    meta: &mut BTreeMap<String, String>,
) -> Result<(), ParseError> {
    let le = Endian::Little;
    let n_objects = c.u16(le, "sur object count")?;
    meta.insert("sur_objects".into(), n_objects.to_string());
    meta.insert("sur_version".into(), c.u16(le, "sur version")?.to_string());
    meta.insert(
        "sur_studiable_type".into(),
        c.u16(le, "sur type")?.to_string(),
    );
    meta.insert("object_name".into(), c.text(30, "sur object name")?);
    meta.insert("operator".into(), c.text(30, "sur operator name")?);
    c.seek(82, "sur acquisition type")?;
    meta.insert(
        "sur_acquisition".into(),
        c.u16(le, "sur acquisition")?.to_string(),
    );
    Ok(())
}

/// The imprint, inversion and levelling flags and the acquisition date.
fn read_flags_and_date(
    c: &mut ByteCursor<'_>,
    meta: &mut BTreeMap<String, String>,
) -> Result<(), ParseError> {
    let le = Endian::Little;
    c.seek(288, "sur flags")?;
    meta.insert("sur_imprint".into(), c.u16(le, "sur imprint")?.to_string());
    meta.insert(
        "sur_inversion".into(),
        c.u16(le, "sur inversion")?.to_string(),
    );
    meta.insert(
        "sur_leveling".into(),
        c.u16(le, "sur leveling")?.to_string(),
    );
    c.seek(306, "sur date")?;
    let mut date = [0u16; 6];
    for d in &mut date {
        *d = c.u16(le, "sur date")?;
    }
    let [sec, min, hour, day, month, year] = date;
    if year != 0 {
        meta.insert(
            "date".into(),
            format!("{year:04}-{month:02}-{day:02}T{hour:02}:{min:02}:{sec:02}"),
        );
    }
    Ok(())
}

/// The sample type of `point_size` bits.
fn sample_type(point_size: u16) -> Result<SampleType, ParseError> {
    match point_size {
        16 => Ok(SampleType::I16),
        32 => Ok(SampleType::I32),
        other => Err(ParseError::malformed(format!(
            "sur: point size {other} bits (expected 16 or 32)"
        ))),
    }
}

/// `xres × yres`, which must equal the header's point count.
fn grid_points(xres: usize, yres: usize, n_points: usize) -> Result<usize, ParseError> {
    let n = xres
        .checked_mul(yres)
        .ok_or_else(|| ParseError::malformed("sur: xres × yres overflows"))?;
    if n_points != n {
        return Err(ParseError::malformed(format!(
            "sur: header says {n_points} points, but xres × yres = {xres} × {yres} = {n}"
        )));
    }
    Ok(n)
}

/// The comment (into `meta`), the private zone, then the heights in metres: a raw value below
/// `zmin` is a non-measured point when the header announces special points.
fn read_heights(
    c: &mut ByteCursor<'_>,
    h: &SurHeader,
    meta: &mut BTreeMap<String, String>,
) -> Result<Vec<f64>, ParseError> {
    c.seek(HEADER_SIZE, "sur comment")?;
    let comment = c.take(h.comment_size, "sur comment")?;
    meta.insert(
        "comment".into(),
        String::from_utf8_lossy(comment).trim().to_string(),
    );
    c.take(h.private_size, "sur private zone")?;
    let block = check_block_size(h.points, h.sample.size(), c.remaining(), "sur height data")?;
    let raw = decode_samples(
        c.take(block, "sur height data")?,
        h.points,
        h.sample,
        Endian::Little,
        "sur",
    )?;
    let threshold = f64::from(h.zmin);
    Ok(raw
        .into_iter()
        .map(|r| {
            if h.special_points != 0 && r < threshold {
                f64::NAN
            } else {
                r * h.dz_m
            }
        })
        .collect())
}

fn positive(v: i32, name: &str) -> Result<usize, ParseError> {
    usize::try_from(v)
        .ok()
        .filter(|&v| v > 0)
        .ok_or_else(|| ParseError::malformed(format!("sur: {name} = {v} is not > 0")))
}

/// A step (`dx`, `dy`, `dz`) converted to metres with its unit name.
fn step_in_metres(step: f64, unit: &str, axis: &str) -> Result<f64, ParseError> {
    let factor = length_unit_to_metres(unit).ok_or_else(|| {
        ParseError::unsupported(format!("sur: {axis} unit {unit:?} is not a length unit"))
    })?;
    let v = step * factor;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(ParseError::malformed(format!(
            "sur: {axis} step {step} {unit} is not > 0"
        )))
    }
}
