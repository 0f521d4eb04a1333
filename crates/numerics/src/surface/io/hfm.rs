//! `.hfm` profile reader: semicolon-separated `x;z;valid` text from a stylus/optical
//! profilometer (the format SurfaceTopography's XYZ reader recognises by its header).
//!
//! Layout: the line `X;Y;valid`, a unit line such as `[mm];[mm];[1/0]` (x unit, height unit,
//! flag), then one `x;z;flag` line per point (CR LF or LF). A point whose flag is `0` is missing
//! (`NaN`); positions must increase strictly. The result is a [`LineScan`] with positions and
//! heights in metres, uniform or not as the file has it.

use std::collections::BTreeMap;

use super::limits::check_count;
use super::reader::{Parser, Reader};
use super::text_units::length_unit_to_metres;
use super::{LineScan, ParseError, ScaleSource, Topography, TopographyData};

const MAGIC: &[u8] = b"X;Y;valid";

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "hfm",
    description: "`X;Y;valid` profile text `.hfm` (a line scan)",
    extensions: &["hfm"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` when `head` starts with the `X;Y;valid` header line.
pub(super) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

/// Metres per unit of a `[unit]` column header.
fn unit(field: Option<&str>, what: &str) -> Result<f64, ParseError> {
    let name = field.unwrap_or("").trim();
    length_unit_to_metres(name).ok_or_else(|| {
        ParseError::malformed(format!(
            "HFM unit line: {what} unit `{name}` is not a length unit such as [mm] or [µm]"
        ))
    })
}

/// One `x;z;flag` data line (1-based `line` for messages).
fn data_line(text: &str, line: usize) -> Result<(f64, f64, bool), ParseError> {
    let bad = || {
        ParseError::malformed(format!(
            "HFM line {line} `{}` is not `x;z;valid` with numbers and a 0/1 flag",
            text.chars().take(60).collect::<String>()
        ))
    };
    let mut fields = text.split(';').map(str::trim);
    let mut number = || -> Result<f64, ParseError> {
        fields
            .next()
            .and_then(|f| f.parse::<f64>().ok())
            .filter(|v| v.is_finite())
            .ok_or_else(bad)
    };
    let (x, z) = (number()?, number()?);
    let valid = match fields.next() {
        Some("1") => true,
        Some("0") => false,
        _ => return Err(bad()),
    };
    if fields.next().is_some() {
        return Err(bad());
    }
    Ok((x, z, valid))
}

/// Parses an HFM profile into a line scan in metres.
fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    if !bytes.starts_with(MAGIC) {
        return Err(ParseError::malformed("missing `X;Y;valid` header line"));
    }
    let text = std::str::from_utf8(bytes).map_err(|e| {
        ParseError::malformed(format!("HFM: not UTF-8 text (byte {})", e.valid_up_to()))
    })?;
    let mut lines = text.lines();
    lines.next();
    let units = lines
        .next()
        .ok_or_else(|| ParseError::truncated("HFM unit line `[mm];[mm];[1/0]`"))?;
    let mut unit_fields = units
        .split(';')
        .map(|f| f.trim().trim_start_matches('[').trim_end_matches(']'));
    let x_unit = unit(unit_fields.next(), "x")?;
    let z_unit = unit(unit_fields.next(), "height")?;
    let (mut x, mut z) = (Vec::new(), Vec::new());
    for (index, line) in lines.enumerate() {
        let line_number = index + 3;
        if line.trim().is_empty() {
            continue;
        }
        let (xi, zi, valid) = data_line(line, line_number)?;
        let xi = xi * x_unit;
        if x.last().is_some_and(|&prev| xi <= prev) {
            return Err(ParseError::malformed(format!(
                "HFM line {line_number}: position {xi} m does not increase"
            )));
        }
        check_count(x.len() + 1, "HFM profile")?;
        x.push(xi);
        z.push(if valid { zi * z_unit } else { f64::NAN });
    }
    if x.len() < 2 {
        return Err(ParseError::truncated(format!(
            "HFM profile has {} points, a line scan needs at least 2",
            x.len()
        )));
    }
    let mut metadata = BTreeMap::new();
    metadata.insert("units".into(), units.trim().to_string());
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data: TopographyData::Line(LineScan { x, z }),
        channel: None,
        channels: Vec::new(),
        metadata,
    })
}
