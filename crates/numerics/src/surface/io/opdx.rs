//! Bruker OPDx reader (Vision software: Dektak stylus profilers and their 3D maps).
//!
//! The item tree is read by [`super::opdx_items`]. `/MetaData/DataKind` says what the file
//! holds:
//! * `Surface Profile`: line scans named in the list `/MetaData/1D_Channels/Height`; channel
//!   `C` has `/1D_Data/C/NumPoints` (n), `/1D_Data/C/Extent` (the x range, first to last point,
//!   a quantity), `/1D_Data/C/DataScale` (height per count, a quantity) and `/1D_Data/C/Array`
//!   (f64 counts). Point `i` lies at `x = i · Extent / (n − 1)`.
//! * `Surface Height`: the map `/MetaData/PrimaryData2D` = `M`, with `/2D_Data/M/Dimension1Points`
//!   (rows, y) and `Dimension2Points` (columns, x), `Dimension1Extent` / `Dimension2Extent`
//!   (Ly, Lx), `DataScale` and `Matrix` (f32 counts, one row after the other); non-finite
//!   counts are missing points.
//!
//! SurfaceTopography reports a profile's length as `n · dx` (49.983 µm for the 3001-point
//! example), one spacing more than the x range this reader keeps (49.967 µm).

use std::collections::BTreeMap;

use ndarray::Array2;

use super::limits::check_count;
use super::opdx_items::{manifest, Item};
use super::reader::{pick_channel, Parser, Reader};
use super::text_units::length_unit_to_metres;
use super::{LineScan, ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"VCA DATA\x01\x00\x00\x55";

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "opdx",
    description: "Bruker OPDx (Dektak profiles and maps)",
    extensions: &["opdx"],
    magic: Some(matches_magic),
    parser: Parser::Channels(parse_channel),
};

/// `true` when `head` starts with the OPDx magic `VCA DATA`.
fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

type Manifest = BTreeMap<String, Item>;

fn get<'m>(m: &'m Manifest, path: &str) -> Result<&'m Item, ParseError> {
    m.get(path)
        .ok_or_else(|| ParseError::malformed(format!("OPDx file has no `{path}`")))
}

fn text<'m>(m: &'m Manifest, path: &str) -> Result<&'m str, ParseError> {
    match get(m, path)? {
        Item::Text(t) => Ok(t),
        other => Err(ParseError::malformed(format!(
            "OPDx `{path}` is {other:?}, not a text"
        ))),
    }
}

fn count(m: &Manifest, path: &str) -> Result<usize, ParseError> {
    match get(m, path)? {
        Item::Int(n) if *n > 0 => check_count(*n as usize, &format!("OPDx `{path}`")),
        other => Err(ParseError::malformed(format!(
            "OPDx `{path}` is {other:?}, not a positive count"
        ))),
    }
}

/// A length quantity in metres.
fn length(m: &Manifest, path: &str) -> Result<f64, ParseError> {
    match get(m, path)? {
        Item::Quantity {
            value,
            name,
            symbol,
        } => {
            let factor = length_unit_to_metres(symbol)
                .or_else(|| length_unit_to_metres(name))
                .ok_or_else(|| {
                    ParseError::unsupported(format!("OPDx `{path}` is in `{symbol}`, not a length"))
                })?;
            Ok(value * factor)
        }
        other => Err(ParseError::malformed(format!(
            "OPDx `{path}` is {other:?}, not a quantity"
        ))),
    }
}

/// Parses the channel named `channel` (default: the first profile, or the primary map).
fn parse_channel(bytes: &[u8], channel: Option<&str>) -> Result<Topography, ParseError> {
    if !matches_magic(bytes) {
        return Err(ParseError::malformed("OPDx magic `VCA DATA` missing"));
    }
    let m = manifest(bytes, MAGIC.len())?;
    let kind = text(&m, "/MetaData/DataKind")?;
    let (data, name, names) = match kind {
        "Surface Profile" => profile(bytes, &m, channel)?,
        "Surface Height" => map(bytes, &m, channel)?,
        other => {
            return Err(ParseError::unsupported(format!(
                "OPDx data of kind `{other}` (profiles and height maps are read)"
            )))
        }
    };
    let mut metadata = BTreeMap::new();
    metadata.insert(super::METADATA_VENDOR.into(), "Bruker".into());
    for (path, key) in [
        (
            "/MetaData/MeasurementSettings/InstrumentName",
            super::METADATA_INSTRUMENT,
        ),
        (
            "/MetaData/MeasurementSettings/InstrumentType",
            "instrument_type",
        ),
        ("/MetaData/MeasurementSettings/StylusType", "stylus"),
        ("/MetaData/DataSetName", "dataset"),
        ("/MetaData/Date", "date"),
        ("/MetaData/Time", "time"),
    ] {
        if let Ok(v) = text(&m, path) {
            metadata.insert(key.into(), v.to_string());
        }
    }
    Ok(Topography {
        data,
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        channel: Some(name),
        channels: names,
        metadata,
    })
}

type Channel = (TopographyData, String, Vec<String>);

/// The f64 (or f32) values of an array item times `scale`, non-finite ones as `NaN`.
fn values(bytes: &[u8], start: usize, len: usize, size: usize, scale: f64) -> Vec<f64> {
    bytes[start..start + len]
        .chunks_exact(size)
        .map(|c| {
            let v = if size == 8 {
                f64::from_le_bytes(c.try_into().unwrap_or_default())
            } else {
                f64::from(f32::from_le_bytes(c.try_into().unwrap_or_default()))
            };
            if v.is_finite() {
                v * scale
            } else {
                f64::NAN
            }
        })
        .collect()
}

fn profile(bytes: &[u8], m: &Manifest, channel: Option<&str>) -> Result<Channel, ParseError> {
    let names = match get(m, "/MetaData/1D_Channels/Height")? {
        Item::TextList(l) => l.clone(),
        other => {
            return Err(ParseError::malformed(format!(
                "OPDx profile list is {other:?}"
            )))
        }
    };
    let name = names[pick_channel(&names, channel, &[])?].clone();
    let prefix = format!("/1D_Data/{name}");
    let n = count(m, &format!("{prefix}/NumPoints"))?;
    let extent = length(m, &format!("{prefix}/Extent"))?;
    let scale = length(m, &format!("{prefix}/DataScale"))?;
    let Item::Doubles { start, len } = *get(m, &format!("{prefix}/Array"))? else {
        return Err(ParseError::malformed(format!(
            "OPDx {prefix}/Array is not an array"
        )));
    };
    if len != n * 8 || n < 2 {
        return Err(ParseError::malformed(format!(
            "OPDx profile `{name}`: {len} bytes of data for {n} points (at least 2, 8 bytes each)"
        )));
    }
    if !(extent.is_finite() && extent > 0.0) {
        return Err(ParseError::malformed(format!(
            "OPDx profile `{name}`: extent {extent} m is not positive"
        )));
    }
    let z = values(bytes, start, len, 8, scale);
    let dx = extent / (n - 1) as f64;
    let x = (0..n).map(|i| i as f64 * dx).collect();
    Ok((TopographyData::Line(LineScan { x, z }), name, names))
}

fn map(bytes: &[u8], m: &Manifest, channel: Option<&str>) -> Result<Channel, ParseError> {
    let name = text(m, "/MetaData/PrimaryData2D")?.to_string();
    let names = vec![name.clone()];
    pick_channel(&names, channel, &[])?;
    let prefix = format!("/2D_Data/{name}");
    let ny = count(m, &format!("{prefix}/Dimension1Points"))?;
    let nx = count(m, &format!("{prefix}/Dimension2Points"))?;
    let ly = length(m, &format!("{prefix}/Dimension1Extent"))?;
    let lx = length(m, &format!("{prefix}/Dimension2Extent"))?;
    let scale = length(m, &format!("{prefix}/DataScale"))?;
    let Item::Matrix {
        start,
        len,
        rows,
        columns,
    } = *get(m, &format!("{prefix}/Matrix"))?
    else {
        return Err(ParseError::malformed(format!(
            "OPDx {prefix}/Matrix is not a matrix"
        )));
    };
    let points = super::limits::check_points(nx, ny, &format!("OPDx map `{name}`"))?;
    if (rows, columns) != (ny, nx) || len != points * 4 {
        return Err(ParseError::malformed(format!(
            "OPDx map `{name}`: a {columns} × {rows} matrix of {len} bytes for {nx} × {ny} f32"
        )));
    }
    let heights = Array2::from_shape_vec((ny, nx), values(bytes, start, len, 4, scale))
        .map_err(|e| ParseError::malformed(format!("OPDx array shape: {e}")))?;
    let map = HeightMap::new(heights, lx / nx as f64, ly / ny as f64)
        .map_err(|e| ParseError::malformed(format!("OPDx map `{name}`: {e}")))?;
    Ok((TopographyData::Areal(map), name, names))
}
