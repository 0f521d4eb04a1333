//! Bruker (Veeco/Digital Instruments) Nanoscope `.di` / `.spm` / `.001` reader.
//!
//! Layout (Bruker "NanoScope Software User Guide", file format appendix): a Latin-1 text header
//! of `\Key: value` lines grouped into `\*Section` blocks, ending at `\*File list end`, then
//! binary data. Each image channel is a `\*Ciao image list` section with `\Data offset`,
//! `\Data length`, `\Bytes/pixel` (2 or 4, little-endian signed), `\Samps/line` (nx),
//! `\Number of lines` (ny), `\Scan Size: Lx Ly unit` and the channel name in
//! `\@2:Image Data: S [ZSensor] "Height Sensor"`.
//!
//! Height scaling: `\@2:Z scale: V [Sens. ZsensSens] (… V/LSB) 24.576 V` gives the full-range
//! soft value `V_fs` (here in volts) and the name of a sensitivity `\@Sens. ZsensSens: V 842.6 nm/V`.
//! Then `z = raw · V_fs / 2^(8·bytes) · sensitivity`, in the sensitivity's numerator unit
//! (nm above). Using `V_fs / 2^(8·bytes)` rather than the rounded `V/LSB` printed in brackets
//! reproduces SurfaceTopography's asserted Sq to 1e-15.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::gsf::length_unit_factor;
use super::limits::check_points;
use super::reader::{pick_channel, Parser, Reader};
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"\\*File list";
const END_MARKER: &[u8] = b"\\*File list end";
/// Channels tried in order when none is requested (as SurfaceTopography does).
const DEFAULT_CHANNELS: [&str; 2] = ["ZSensor", "Height"];

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "nanoscope",
    description: "Bruker Nanoscope `.di` / `.spm`",
    extensions: &["di", "spm"],
    magic: Some(matches_magic),
    parser: Parser::Channels(parse_channel),
};

/// `true` when `head` starts with the Nanoscope header.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

/// One `\*Section` of the header with its `key → value` lines.
struct Section {
    name: String,
    fields: BTreeMap<String, String>,
}

fn parse_header(bytes: &[u8]) -> Result<Vec<Section>, ParseError> {
    if !bytes.starts_with(MAGIC) {
        return Err(ParseError::malformed("missing `\\*File list` header"));
    }
    let end = bytes
        .windows(END_MARKER.len())
        .position(|w| w == END_MARKER)
        .ok_or_else(|| ParseError::truncated("Nanoscope header (no `\\*File list end`)"))?;
    let text: String = bytes[..end].iter().map(|&b| char::from(b)).collect();
    let mut sections: Vec<Section> = Vec::new();
    for line in text.lines().map(str::trim_end) {
        if let Some(name) = line.strip_prefix("\\*") {
            sections.push(Section {
                name: name.to_string(),
                fields: BTreeMap::new(),
            });
        } else if let Some(rest) = line.strip_prefix('\\') {
            let (key, value) = rest
                .split_once(": ")
                .unwrap_or((rest.trim_end_matches(':'), ""));
            if let Some(section) = sections.last_mut() {
                section
                    .fields
                    .insert(key.trim().to_string(), value.trim().to_string());
            }
        }
    }
    Ok(sections)
}

/// Name of the channel in a `\*Ciao image list` section (`ZSensor` in `S [ZSensor] "…"`).
fn channel_name(section: &Section) -> Option<String> {
    let value = section
        .fields
        .iter()
        .find(|(k, _)| k.ends_with("Image Data"))
        .map(|(_, v)| v)?;
    Some(bracketed(value).unwrap_or(value).to_string())
}

fn bracketed(value: &str) -> Option<&str> {
    let start = value.find('[')? + 1;
    let end = start + value[start..].find(']')?;
    Some(&value[start..end])
}

/// The trailing `number unit` of a value such as `V [Sens. Zsens] (0.006 V/LSB) 24.576 V`.
fn trailing_quantity(value: &str) -> Option<(f64, String)> {
    let mut words = value.split_whitespace().rev();
    let last = words.next()?;
    if let Ok(x) = last.parse::<f64>() {
        return Some((x, String::new()));
    }
    let number = words.next()?.parse::<f64>().ok()?;
    Some((number, last.to_string()))
}

fn field<'a>(section: &'a Section, key: &str, channel: &str) -> Result<&'a str, ParseError> {
    section.fields.get(key).map(String::as_str).ok_or_else(|| {
        ParseError::malformed(format!("Nanoscope channel `{channel}` has no `\\{key}`"))
    })
}

fn usize_field(section: &Section, key: &str, channel: &str) -> Result<usize, ParseError> {
    let v = field(section, key, channel)?;
    v.parse::<usize>()
        .map_err(|_| ParseError::malformed(format!("Nanoscope `\\{key}: {v}` is not an integer")))
}

/// Parses the image channel named `channel` (or the default one for `None`), heights in metres.
fn parse_channel(bytes: &[u8], channel: Option<&str>) -> Result<Topography, ParseError> {
    let sections = parse_header(bytes)?;
    let images: Vec<(&Section, String)> = sections
        .iter()
        .filter(|s| s.name == "Ciao image list")
        .map(|s| (s, channel_name(s).unwrap_or_default()))
        .collect();
    let names: Vec<String> = images.iter().map(|(_, n)| n.clone()).collect();
    let (image, name) = &images[pick_channel(&names, channel, &DEFAULT_CHANNELS)?];
    let grid = image_grid(bytes, image, name)?;
    let (lsb, unit) = height_per_lsb(image, &sections, name, grid.bpp)?;
    let scan = scan_size_text(image, &sections)?;
    let (lx, ly) = scan_size(scan, image)?;
    let values: Vec<f64> = grid
        .data
        .chunks_exact(grid.bpp)
        .map(|c| {
            let raw = if grid.bpp == 2 {
                f64::from(i16::from_le_bytes([c[0], c[1]]))
            } else {
                f64::from(i32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            };
            raw * lsb
        })
        .collect();
    let (nx, ny) = (grid.nx, grid.ny);
    let heights = Array2::from_shape_vec((ny, nx), values)
        .map_err(|e| ParseError::malformed(format!("Nanoscope array shape: {e}")))?;
    let map = HeightMap::new(heights, lx / nx as f64, ly / ny as f64)
        .map_err(|e| ParseError::malformed(format!("Nanoscope: {e} (Scan Size `{scan}`)")))?;
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Areal(map),
        channel: Some(name.clone()),
        channels: names,
        metadata: metadata(&sections, unit),
    })
}

/// The grid of one image and its raw data.
struct ImageGrid<'a> {
    nx: usize,
    ny: usize,
    /// Bytes per sample, 2 or 4.
    bpp: usize,
    data: &'a [u8],
}

/// The size, sample width and data of the image `image` (channel `name`): `\Data length` must
/// hold the grid, and the file the data.
fn image_grid<'a>(
    bytes: &'a [u8],
    image: &Section,
    name: &str,
) -> Result<ImageGrid<'a>, ParseError> {
    let offset = usize_field(image, "Data offset", name)?;
    let bpp = usize_field(image, "Bytes/pixel", name)?;
    let nx = usize_field(image, "Samps/line", name)?;
    let ny = usize_field(image, "Number of lines", name)?;
    if bpp != 2 && bpp != 4 {
        return Err(ParseError::unsupported(format!(
            "Nanoscope data with {bpp} bytes/pixel"
        )));
    }
    let n_bytes = nx
        .checked_mul(ny)
        .and_then(|n| n.checked_mul(bpp))
        .ok_or_else(|| ParseError::malformed(format!("Nanoscope grid {nx} × {ny} overflows")))?;
    let data_length = usize_field(image, "Data length", name)?;
    if data_length < n_bytes {
        return Err(ParseError::malformed(format!(
            "Nanoscope channel `{name}`: Data length {data_length} B < {nx} × {ny} × {bpp} B"
        )));
    }
    let data = offset
        .checked_add(n_bytes)
        .and_then(|end| bytes.get(offset..end))
        .ok_or_else(|| {
            ParseError::truncated(format!(
                "Nanoscope channel `{name}`: {n_bytes} bytes at byte {offset}"
            ))
        })?;
    check_points(nx, ny, &format!("Nanoscope channel `{name}`"))?;
    Ok(ImageGrid { nx, ny, bpp, data })
}

/// Height per LSB (metres) from the image's Z scale and the sensitivity it names, with the
/// unit the scale was stated in.
fn height_per_lsb(
    image: &Section,
    sections: &[Section],
    name: &str,
    bpp: usize,
) -> Result<(f64, String), ParseError> {
    let (z_key, z_scale) = image
        .fields
        .iter()
        .find(|(k, _)| k.starts_with('@') && k.ends_with(":Z scale"))
        .ok_or_else(|| {
            ParseError::malformed(format!("Nanoscope channel `{name}` has no `\\@2:Z scale`"))
        })?;
    let (full_scale, z_unit) = trailing_quantity(z_scale).ok_or_else(|| {
        ParseError::malformed(format!("Nanoscope `\\{z_key}: {z_scale}` has no value"))
    })?;
    let (per_full_scale, unit) = match bracketed(z_scale) {
        Some(sens_name) => {
            let (value, numerator) = sensitivity(sections, sens_name)?;
            (full_scale * value, numerator)
        }
        None => (full_scale, z_unit),
    };
    let unit_factor = length_unit_factor(&unit).ok_or_else(|| {
        ParseError::unsupported(format!(
            "Nanoscope channel `{name}` is in `{unit}`, not a length"
        ))
    })?;
    let lsb = per_full_scale / 2f64.powi(8 * bpp as i32) * unit_factor;
    if !(lsb.is_finite() && lsb != 0.0) {
        return Err(ParseError::malformed(format!(
            "Nanoscope height per LSB {lsb} m is not usable"
        )));
    }
    Ok((lsb, unit))
}

/// The value of the sensitivity `\@<sens_name>` and the numerator of its unit (`nm` of `nm/V`).
fn sensitivity(sections: &[Section], sens_name: &str) -> Result<(f64, String), ParseError> {
    let sens_key = format!("@{sens_name}");
    let sens = sections
        .iter()
        .find_map(|s| s.fields.get(&sens_key))
        .ok_or_else(|| {
            ParseError::malformed(format!("Nanoscope sensitivity `\\{sens_key}` missing"))
        })?;
    let (value, sens_unit) = trailing_quantity(sens).ok_or_else(|| {
        ParseError::malformed(format!("Nanoscope `\\{sens_key}: {sens}` has no value"))
    })?;
    let numerator = sens_unit.split('/').next().unwrap_or("").to_string();
    Ok((value, numerator))
}

/// The image's own `\Scan Size`, else the scan list's; older headers write `\Scan size`.
fn scan_size_text<'a>(image: &'a Section, sections: &'a [Section]) -> Result<&'a str, ParseError> {
    std::iter::once(image)
        .chain(sections.iter())
        .find_map(|s| {
            s.fields
                .iter()
                .find(|(k, _)| k.eq_ignore_ascii_case("Scan Size"))
                .map(|(_, v)| v.as_str())
        })
        .ok_or_else(|| ParseError::malformed("Nanoscope header has no `\\Scan Size`"))
}

/// The instrument, date, version and operating mode of the header, and the height unit.
fn metadata(sections: &[Section], unit: String) -> BTreeMap<String, String> {
    let mut metadata = BTreeMap::new();
    metadata.insert("vendor".into(), "Bruker".into());
    for (section, key, meta) in [
        ("Equipment list", "Description", "instrument"),
        ("File list", "Date", "date"),
        ("File list", "Version", "version"),
        ("Ciao scan list", "Operating mode", "operating_mode"),
    ] {
        if let Some(v) = sections
            .iter()
            .find(|s| s.name == section)
            .and_then(|s| s.fields.get(key))
        {
            metadata.insert(meta.into(), v.clone());
        }
    }
    metadata.insert("original_z_unit".into(), unit);
    metadata
}

/// Physical size `(Lx, Ly)` in metres from `\Scan Size: Lx Ly unit` (or `L unit` with the
/// `\Aspect Ratio: a:b` giving `Ly = L · b / a`).
fn scan_size(value: &str, image: &Section) -> Result<(f64, f64), ParseError> {
    let words: Vec<&str> = value.split_whitespace().collect();
    let bad = || ParseError::malformed(format!("Nanoscope `\\Scan Size: {value}` not understood"));
    let (numbers, unit) = match words.as_slice() {
        [x, y, unit] => (vec![*x, *y], *unit),
        [x, unit] => (vec![*x], *unit),
        _ => return Err(bad()),
    };
    let factor = length_unit_factor(unit).ok_or_else(bad)?;
    let numbers: Vec<f64> = numbers
        .iter()
        .map(|s| s.parse::<f64>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    let lx = numbers[0] * factor;
    let ly = match numbers.get(1) {
        Some(y) => y * factor,
        None => {
            let ratio = image
                .fields
                .get("Aspect Ratio")
                .and_then(|r| r.split_once(':'))
                .and_then(|(a, b)| {
                    Some(b.trim().parse::<f64>().ok()? / a.trim().parse::<f64>().ok()?)
                })
                .unwrap_or(1.0);
            lx * ratio
        }
    };
    Ok((lx, ly))
}
