//! Nanosurf `.nid` / `.ezd` reader (easyScan / DriveAFM data files).
//!
//! Layout (as SurfaceTopography's `EZD.py` and Gwyddion's `nanosurf.c` read it): an INI-style
//! text header starting `[DataSet]`, then `#!` at the start of a line, then the binary data
//! sets back to back. `[DataSet]` names the data sets as `Gr<i>-Ch<j>=<section>`; each such
//! section gives `Points` (nx) and `Lines` (ny), `Frame` ("Scan forward"), `Dim0Range` /
//! `Dim1Range` (the scan size in `Dim0Unit` / `Dim1Unit`), `Dim2Name` / `Dim2Unit` / `Dim2Range`
//! / `Dim2Min` (the measured quantity) and `SaveBits` / `SaveSign` / `SaveOrder` (`Intel` =
//! little-endian). Each data set is `Points × Lines` integers, one scan line after the other;
//! the data sets follow in `(i, j)` order.
//!
//! A raw value `r` of `b` bits is `z = Dim2Min + (r − r_min) · Dim2Range / 2^b` with `r_min` the
//! smallest raw value (`−2^(b−1)` signed, 0 unsigned), so the raw range spans `[Dim2Min,
//! Dim2Min + Dim2Range)`. A channel is named `Frame (Dim2Name)`; the default is the first whose
//! `Dim2Unit` is a length.

use std::collections::BTreeMap;

use ndarray::Array2;

use super::limits::check_points;
use super::reader::{pick_channel, Parser, Reader};
use super::text_units::length_unit_to_metres;
use super::{ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

const MAGIC: &[u8] = b"[DataSet]";

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "nid",
    description: "Nanosurf `.nid` / `.ezd`",
    extensions: &["nid", "ezd"],
    magic: Some(matches_magic),
    parser: Parser::Channels(parse_channel),
};

/// `true` when `head` starts with the `[DataSet]` section.
fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(MAGIC)
}

type Sections = BTreeMap<String, BTreeMap<String, String>>;

/// The header's sections and the byte where the data start (after the `#!` line marker).
fn header(bytes: &[u8]) -> Result<(Sections, usize), ParseError> {
    let marker = bytes
        .windows(3)
        .position(|w| w == b"\n#!")
        .ok_or_else(|| ParseError::truncated("NID header: no `#!` line before the data"))?;
    let text = String::from_utf8_lossy(&bytes[..marker]);
    let mut sections = Sections::new();
    let mut current = String::new();
    for line in text.lines().map(str::trim) {
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            current = name.to_string();
        } else if let Some((key, value)) = line.split_once('=') {
            sections
                .entry(current.clone())
                .or_default()
                .insert(key.trim().to_string(), value.trim().to_string());
        }
    }
    Ok((sections, marker + 3))
}

/// One data set of the file.
struct DataSet<'h> {
    name: String,
    fields: &'h BTreeMap<String, String>,
    /// Byte offset from the start of the data.
    offset: usize,
    nx: usize,
    ny: usize,
    bits: usize,
}

impl DataSet<'_> {
    fn get(&self, key: &str) -> Result<&str, ParseError> {
        self.fields.get(key).map(String::as_str).ok_or_else(|| {
            ParseError::malformed(format!("NID data set `{}` has no `{key}`", self.name))
        })
    }

    fn float(&self, key: &str) -> Result<f64, ParseError> {
        let v = self.get(key)?;
        v.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| ParseError::malformed(format!("NID `{key}={v}` is not a number")))
    }
}

/// The data sets in storage order, with their byte offsets.
fn data_sets(sections: &Sections) -> Result<Vec<DataSet<'_>>, ParseError> {
    let top = sections
        .get("DataSet")
        .ok_or_else(|| ParseError::malformed("NID header has no [DataSet] section"))?;
    let mut refs: Vec<((u64, u64), &String)> = top
        .iter()
        .filter_map(|(k, v)| {
            let (g, c) = k.strip_prefix("Gr")?.split_once("-Ch")?;
            Some(((g.parse().ok()?, c.parse().ok()?), v))
        })
        .collect();
    refs.sort_by_key(|(ij, _)| *ij);
    let mut offset = 0usize;
    let mut sets = Vec::new();
    for (_, section) in refs {
        let fields = sections.get(section.as_str()).ok_or_else(|| {
            ParseError::malformed(format!("NID data set section [{section}] is missing"))
        })?;
        let int = |key: &str| -> Result<usize, ParseError> {
            let v = fields.get(key).map(String::as_str).unwrap_or_default();
            v.parse::<usize>().map_err(|_| {
                ParseError::malformed(format!("NID [{section}] `{key}={v}` is not a count"))
            })
        };
        let (nx, ny, bits) = (int("Points")?, int("Lines")?, int("SaveBits")?);
        if !matches!(bits, 8 | 16 | 32) {
            return Err(ParseError::unsupported(format!(
                "NID [{section}] SaveBits={bits} (8, 16 or 32 are read)"
            )));
        }
        let points = check_points(nx, ny, &format!("NID [{section}] (Points × Lines)"))?;
        let frame = fields.get("Frame").cloned().unwrap_or_default();
        let quantity = fields.get("Dim2Name").cloned().unwrap_or_default();
        sets.push(DataSet {
            name: format!("{frame} ({quantity})"),
            fields,
            offset,
            nx,
            ny,
            bits,
        });
        offset = points
            .checked_mul(bits / 8)
            .and_then(|n| n.checked_add(offset))
            .ok_or_else(|| ParseError::malformed("NID data sets overflow"))?;
    }
    Ok(sets)
}

/// Parses the channel named `channel` (default: the first with heights in a length unit).
fn parse_channel(bytes: &[u8], channel: Option<&str>) -> Result<Topography, ParseError> {
    let (sections, data_start) = header(bytes)?;
    let sets = data_sets(&sections)?;
    let total = sets
        .last()
        .map_or(0, |s| s.offset + s.nx * s.ny * s.bits / 8);
    if data_start
        .checked_add(total)
        .is_none_or(|end| end > bytes.len())
    {
        return Err(ParseError::truncated(format!(
            "NID data: {total} bytes for {} data sets after byte {data_start}, file of {} bytes",
            sets.len(),
            bytes.len()
        )));
    }
    let names: Vec<String> = sets.iter().map(|s| s.name.clone()).collect();
    let heights: Vec<&str> = sets
        .iter()
        .filter(|s| {
            s.fields
                .get("Dim2Unit")
                .is_some_and(|u| length_unit_to_metres(u).is_some())
        })
        .map(|s| s.name.as_str())
        .collect();
    let set = &sets[pick_channel(&names, channel, &heights)?];
    let z_unit = set.get("Dim2Unit")?;
    let z_factor = length_unit_to_metres(z_unit).ok_or_else(|| {
        ParseError::unsupported(format!(
            "NID channel `{}` is in `{z_unit}`, not a length: not a topography",
            set.name
        ))
    })?;
    let length = |range: &str, unit: &str| -> Result<f64, ParseError> {
        let u = set.get(unit)?;
        let f = length_unit_to_metres(u).ok_or_else(|| {
            ParseError::malformed(format!("NID `{unit}={u}` is not a length unit"))
        })?;
        Ok(set.float(range)? * f)
    };
    let (lx, ly) = (
        length("Dim0Range", "Dim0Unit")?,
        length("Dim1Range", "Dim1Unit")?,
    );
    let data = decode(bytes, data_start, set)?;
    let (range, min) = (set.float("Dim2Range")?, set.float("Dim2Min")?);
    let step = range / 2f64.powi(set.bits as i32);
    let values: Vec<f64> = data.iter().map(|r| (min + r * step) * z_factor).collect();
    let heights = Array2::from_shape_vec((set.ny, set.nx), values)
        .map_err(|e| ParseError::malformed(format!("NID array shape: {e}")))?;
    let map = HeightMap::new(heights, lx / set.nx as f64, ly / set.ny as f64)
        .map_err(|e| ParseError::malformed(format!("NID channel `{}`: {e}", set.name)))?;
    Ok(Topography {
        data: TopographyData::Areal(map),
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        channel: Some(set.name.clone()),
        channels: names,
        metadata: metadata(&sections),
    })
}

/// The raw values of `set`, shifted to start at 0 (`r − r_min`).
fn decode(bytes: &[u8], data_start: usize, set: &DataSet<'_>) -> Result<Vec<f64>, ParseError> {
    let size = set.bits / 8;
    let n_bytes = set.nx * set.ny * size;
    let block = data_start
        .checked_add(set.offset)
        .and_then(|start| Some((start, start.checked_add(n_bytes)?)))
        .and_then(|(start, end)| bytes.get(start..end))
        .ok_or_else(|| {
            ParseError::truncated(format!(
                "NID channel `{}`: {n_bytes} bytes at byte {} of the data",
                set.name, set.offset
            ))
        })?;
    let little = set.get("SaveOrder")? == "Intel";
    let signed = set.get("SaveSign")? == "Signed";
    let shift = if signed {
        2f64.powi(set.bits as i32 - 1)
    } else {
        0.0
    };
    Ok(block
        .chunks_exact(size)
        .map(|c| {
            let mut b = [0u8; 4];
            b[..size].copy_from_slice(c);
            if !little {
                b[..size].reverse();
            }
            let raw = u32::from_le_bytes(b);
            let value = if signed {
                // Sign-extend the `bits`-bit value.
                let s = 32 - set.bits as u32;
                f64::from(((raw << s) as i32) >> s)
            } else {
                f64::from(raw)
            };
            value + shift
        })
        .collect())
}

/// Instrument, date and operating mode from `[DataSet-Info]`.
fn metadata(sections: &Sections) -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    m.insert(super::METADATA_VENDOR.into(), "Nanosurf".into());
    if let Some(info) = sections.get("DataSet-Info") {
        for (key, meta) in [
            ("Head type", super::METADATA_INSTRUMENT),
            ("Controller S/N", "controller_serial"),
            ("Date", "date"),
            ("Time", "time"),
            ("Op. mode", "operating_mode"),
            ("Software ver.", "software_version"),
        ] {
            if let Some(v) = info.get(key) {
                m.insert(meta.into(), v.clone());
            }
        }
    }
    m
}
