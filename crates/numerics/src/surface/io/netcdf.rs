//! netCDF classic (`CDF\x01`) and 64-bit-offset (`CDF\x02`) reader for topographies written the
//! SurfaceTopography way: a variable `heights(x, y)` with an optional `unit` attribute, and
//! optional coordinate variables `x`, `y` whose `length` attribute is the physical size along
//! that dimension (`dx = length / nx`; unit from `unit` or `length_unit`).
//!
//! Layout (Unidata, "The NetCDF Classic Format Specification"): big-endian throughout; magic,
//! record count, then the dimension, global-attribute and variable lists, each either absent
//! (8 zero bytes) or a tag (`0x0A`, `0x0C`, `0x0B`) and an element count. Names and attribute
//! values are padded to 4 bytes; a variable lists its dimension ids, its attributes, its type
//! (1 byte, 3 short, 4 int, 5 float, 6 double), its size and its data offset (4 bytes, 8 in the
//! 64-bit-offset variant). Data are row-major, the last dimension fastest, so `heights(x, y)` is
//! transposed into `[[iy, ix]]`. Every count is checked against the bytes left before anything is
//! allocated. netCDF-4 files are HDF5 files and are refused here; record (unlimited) variables
//! and CDF-5 are not read.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::byte_cursor::{decode_samples, ByteCursor, Endian, SampleType};
use super::limits::check_points;
use super::reader::{Parser, Reader};
use super::text_units::length_unit_to_metres;
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const BE: Endian = Endian::Big;

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "netcdf",
    description: "netCDF classic / 64-bit offset `.nc` with `heights(x, y)`",
    extensions: &["nc"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` starts with a classic or 64-bit-offset netCDF magic.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    matches!(head.get(..4), Some(b"CDF\x01" | b"CDF\x02"))
}

/// An attribute value: text or numbers.
#[derive(Debug, Clone)]
enum Value {
    Text(String),
    Numbers(Vec<f64>),
}

struct Variable {
    name: String,
    /// Dimension names and lengths, slowest first.
    dims: Vec<(String, usize)>,
    attributes: BTreeMap<String, Value>,
    sample: SampleType,
    begin: usize,
}

struct File {
    dims: Vec<(String, usize)>,
    variables: Vec<Variable>,
}

/// An element count, at most one per `min_size` bytes left (nothing is allocated for more).
fn count(c: &mut ByteCursor, min_size: usize, what: &str) -> Result<usize, ParseError> {
    let n = c.u32(BE, what)? as usize;
    if n.saturating_mul(min_size) > c.remaining() {
        return Err(ParseError::truncated(format!(
            "netCDF {what}: {n} elements do not fit in the {} bytes left",
            c.remaining()
        )));
    }
    Ok(n)
}

fn padded(c: &mut ByteCursor, n: usize, what: &str) -> Result<Vec<u8>, ParseError> {
    let raw = c.take(n, what)?.to_vec();
    c.take((4 - n % 4) % 4, what)?;
    Ok(raw)
}

fn name(c: &mut ByteCursor) -> Result<String, ParseError> {
    let n = count(c, 1, "name length")?;
    Ok(String::from_utf8_lossy(&padded(c, n, "name")?).into_owned())
}

fn sample_type(code: u32) -> Result<SampleType, ParseError> {
    Ok(match code {
        1 => SampleType::I8,
        3 => SampleType::I16,
        4 => SampleType::I32,
        5 => SampleType::F32,
        6 => SampleType::F64,
        2 => SampleType::U8,
        t => return Err(ParseError::malformed(format!("netCDF type {t} is unknown"))),
    })
}

/// A list header: `None` when absent, else the element count after checking the tag.
fn list(c: &mut ByteCursor, tag: u32, min_size: usize, what: &str) -> Result<usize, ParseError> {
    match c.u32(BE, what)? {
        0 => {
            c.u32(BE, what)?;
            Ok(0)
        }
        t if t == tag => count(c, min_size, what),
        t => Err(ParseError::malformed(format!(
            "netCDF {what}: tag {t:#x}, expected {tag:#x}"
        ))),
    }
}

fn attributes(c: &mut ByteCursor) -> Result<BTreeMap<String, Value>, ParseError> {
    let n = list(c, 0x0C, 12, "attribute list")?;
    let mut out = BTreeMap::new();
    for _ in 0..n {
        let key = name(c)?;
        let code = c.u32(BE, "attribute type")?;
        let len = count(c, 1, "attribute length")?;
        let value = if code == 2 {
            let raw = padded(c, len, "attribute text")?;
            Value::Text(
                String::from_utf8_lossy(&raw)
                    .trim_end_matches('\0')
                    .to_string(),
            )
        } else {
            let ty = sample_type(code)?;
            let raw = padded(c, len.saturating_mul(ty.size()), "attribute values")?;
            Value::Numbers(decode_samples(&raw, len, ty, BE, "attribute values")?)
        };
        out.insert(key, value);
    }
    Ok(out)
}

fn read_file(bytes: &[u8]) -> Result<File, ParseError> {
    let offset_size = match bytes.get(..4) {
        Some(b"CDF\x01") => 4,
        Some(b"CDF\x02") => 8,
        Some(b"CDF\x05") => return Err(ParseError::unsupported("netCDF CDF-5 (64-bit data)")),
        _ if bytes.starts_with(b"\x89HDF") => {
            return Err(ParseError::unsupported(
                "netCDF-4 (an HDF5 file); convert it with `nccopy -k classic`",
            ))
        }
        _ => return Err(ParseError::malformed("missing `CDF` magic")),
    };
    let mut c = ByteCursor::new(bytes);
    c.seek(8, "netCDF dimension list")?;
    let n_dims = list(&mut c, 0x0A, 8, "dimension list")?;
    let mut dims = Vec::with_capacity(n_dims);
    for _ in 0..n_dims {
        let dim_name = name(&mut c)?;
        dims.push((dim_name, c.u32(BE, "dimension length")? as usize));
    }
    attributes(&mut c)?;
    let n_vars = list(&mut c, 0x0B, 24, "variable list")?;
    let mut variables = Vec::with_capacity(n_vars);
    for _ in 0..n_vars {
        let var_name = name(&mut c)?;
        let rank = count(&mut c, 4, "variable rank")?;
        let mut var_dims = Vec::with_capacity(rank);
        for _ in 0..rank {
            let id = c.u32(BE, "dimension id")? as usize;
            let dim = dims.get(id).cloned().ok_or_else(|| {
                ParseError::malformed(format!("netCDF variable `{var_name}`: dimension id {id}"))
            })?;
            var_dims.push(dim);
        }
        let attributes = attributes(&mut c)?;
        let sample = sample_type(c.u32(BE, "variable type")?)?;
        c.u32(BE, "variable size")?;
        let begin = if offset_size == 8 {
            let hi = u64::from(c.u32(BE, "variable offset")?);
            usize::try_from((hi << 32) | u64::from(c.u32(BE, "variable offset")?))
                .unwrap_or(usize::MAX)
        } else {
            c.u32(BE, "variable offset")? as usize
        };
        variables.push(Variable {
            name: var_name,
            dims: var_dims,
            attributes,
            sample,
            begin,
        });
    }
    Ok(File { dims, variables })
}

fn text_attr<'a>(v: &'a Variable, key: &str) -> Option<&'a str> {
    match v.attributes.get(key)? {
        Value::Text(t) => Some(t),
        Value::Numbers(_) => None,
    }
}

/// Metres per unit of `v`'s `unit` / `length_unit` attribute; `None` when it has none.
fn unit_of(v: &Variable) -> Result<Option<f64>, ParseError> {
    let Some(unit) = text_attr(v, "unit").or_else(|| text_attr(v, "length_unit")) else {
        return Ok(None);
    };
    length_unit_to_metres(unit).map(Some).ok_or_else(|| {
        ParseError::unsupported(format!("netCDF `{}` unit `{unit}` is not a length", v.name))
    })
}

/// Spacing along the coordinate variable `axis`: `(metres per step, from the file)`.
fn spacing(file: &File, axis: &str, n: usize) -> Result<(f64, bool), ParseError> {
    let Some(v) = file.variables.iter().find(|v| v.name == axis) else {
        return Ok((1.0, false));
    };
    let length = match v.attributes.get("length") {
        Some(Value::Numbers(l)) => l.first().copied(),
        _ => None,
    };
    match (length, unit_of(v)?) {
        (Some(l), unit) => Ok((l * unit.unwrap_or(1.0) / n as f64, unit.is_some())),
        (None, _) => Ok((1.0, false)),
    }
}

/// Parses the `heights` variable into heights in metres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let file = read_file(bytes)?;
    let heights = file
        .variables
        .iter()
        .find(|v| v.name == "heights")
        .ok_or_else(|| ParseError::unsupported("netCDF file without a `heights` variable"))?;
    let [(first, n0), (_, n1)] = &heights.dims[..] else {
        return Err(ParseError::unsupported(format!(
            "netCDF `heights` has {} dimensions (a topography map has 2)",
            heights.dims.len()
        )));
    };
    // `heights(x, y)` (SurfaceTopography) unless the first dimension is named `y`.
    let x_first = first != "y";
    let (nx, ny) = if x_first { (*n0, *n1) } else { (*n1, *n0) };
    if file.variables.iter().any(|v| v.name == "mask") {
        return Err(ParseError::unsupported("netCDF `mask` variable"));
    }
    let n = check_points(nx, ny, "netCDF heights(x, y)")?;
    let mut c = ByteCursor::new(bytes);
    c.seek(heights.begin, "netCDF heights data")?;
    let raw = decode_samples(
        c.take(c.remaining(), "netCDF heights")?,
        n,
        heights.sample,
        BE,
        "netCDF heights",
    )?;
    let z_unit = unit_of(heights)?;
    let z = z_unit.unwrap_or(1.0);
    // Last dimension fastest: (x, y) puts (ix, iy) at ix·ny + iy, (y, x) at iy·nx + ix.
    let grid = Array2::from_shape_fn((ny, nx), |(iy, ix)| {
        let v = raw[if x_first { ix * ny + iy } else { iy * nx + ix }];
        if v.is_finite() {
            v * z
        } else {
            f64::NAN
        }
    });
    let (dx, x_known) = spacing(&file, "x", nx)?;
    let (dy, y_known) = spacing(&file, "y", ny)?;
    let map =
        HeightMap::new(grid, dx, dy).map_err(|e| ParseError::malformed(format!("netCDF: {e}")))?;
    let mut metadata = BTreeMap::new();
    let dim_names: Vec<&str> = file.dims.iter().map(|d| d.0.as_str()).collect();
    metadata.insert("dimensions".into(), dim_names.join(", "));
    let source = |known| {
        if known {
            ScaleSource::File
        } else {
            ScaleSource::Assumed
        }
    };
    Ok(Topography {
        spacing: source(x_known && y_known),
        height_unit: source(z_unit.is_some()),
        data: TopographyData::Areal(map),
        channel: None,
        channels: Vec::new(),
        metadata,
    })
}
