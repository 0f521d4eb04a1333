//! X3P reader (ISO 25178-72, the XML/zip container of ISO 5436-2).
//!
//! An X3P file is a zip archive holding `main.xml` (axes, matrix size, metadata) and the height
//! data, either as a little-endian binary file (`bindata/data.bin`, named by
//! `Record3/DataLink/PointDataLink`) or inline as `Record3/DataList/Datum` elements.
//!
//! * Lateral axes CX, CY must be incremental (`AxisType I`): x = Offset + i·Increment (m).
//!   Offsets (empty `<Offset/>` = 0) go to the metadata, since a [`HeightMap`] starts at 0.
//! * Heights: CZ `DataType` `I` (int16), `L` (int32), `F` (float32), `D` (float64). Integer
//!   heights are z = raw·Increment + Offset (m); float heights are stored in metres directly
//!   (CZ Increment/Offset are not applied to them, as ISO 5436-2 defines them for integer
//!   encodings).
//! * Invalid points: `NaN` in float data, an empty `<Datum/>` in a data list, or a 0 bit in the
//!   optional validity mask `ValidPointsLink` (bit k of byte k/8, least significant bit first,
//!   x fastest). All become `NaN`.
//! * Tolerated deviations seen in real files: `main.xml` in a sub-folder (paths in the
//!   archive are then relative to that folder), `__MACOSX/` entries, a root element without
//!   namespace, and any `Revision` text (kept in the metadata, not checked).
//! * A profile (`FeatureType PRF`, SizeY = 1) is returned as a [`LineScan`].
//! * Integrity: the MD5 sums the file records of `main.xml` and of its data members are checked
//!   ([`super::x3p_checksum`]).
//! * Bounded work: `main.xml` is read up to [`MAX_MAIN_XML_BYTES`], the matrix up to
//!   [`MAX_POINTS`], and every member only after its declared uncompressed size matched what the
//!   matrix needs, so a small hostile archive cannot make the reader inflate gigabytes.

use std::collections::BTreeMap;
use std::io::{Cursor, Read};

use ndarray::Array2;
use zip::ZipArchive;

use super::byte_cursor::{decode_samples, Endian, SampleType};
use super::limits::{check_points, MAX_POINTS};
use super::reader::{Parser, Reader};
use super::x3p_checksum::{checksum_file_sum, verify};
use super::x3p_xml::X3pDocument;
use super::{LineScan, ParseError, ScaleSource, Topography, TopographyData};
use crate::surface::HeightMap;

/// Largest ratio of uncompressed to compressed size that deflate can reach (about 1032:1);
/// any entry or matrix claiming more than this times the file size is a lie.
const MAX_DEFLATE_RATIO: usize = 1100;

/// Largest `main.xml` read: real ones are a few KiB; 64 MiB still holds an inline `DataList` of
/// two million points.
const MAX_MAIN_XML_BYTES: usize = 64 << 20;

/// Zip local-file-header magic.
const ZIP_MAGIC: &[u8] = b"PK\x03\x04";

/// The registry entry of this format ([`super::READERS`]).
pub(crate) const READER: Reader = Reader {
    name: "x3p",
    description: "ISO 25178-72 X3P (zip with `main.xml` and `bindata/`)",
    extensions: &["x3p"],
    magic: Some(matches_magic),
    parser: Parser::Single(parse),
};

/// `true` for a zip archive whose first entries look like an X3P container.
pub(crate) fn matches_magic(head: &[u8]) -> bool {
    head.starts_with(ZIP_MAGIC)
        && [&b"main.xml"[..], b"bindata/", b"md5checksum"]
            .iter()
            .any(|needle| head.windows(needle.len()).any(|w| w == *needle))
}

/// An opened X3P: the archive, the folder of `main.xml` (`""` or `"name/"`) and its document.
struct Opened<'a> {
    archive: ZipArchive<Cursor<&'a [u8]>>,
    folder: String,
    doc: X3pDocument,
}

/// Opens the archive and reads `main.xml`, checked against `md5checksum.hex`.
fn open(bytes: &[u8], max_len: usize) -> Result<Opened<'_>, ParseError> {
    let mut archive = ZipArchive::new(Cursor::new(bytes)).map_err(|e| {
        ParseError::malformed(format!(
            "x3p: not a readable zip archive (truncated or corrupted?): {e}"
        ))
    })?;
    let main_xml = find_main_xml(&archive)?;
    let folder = main_xml.trim_end_matches("main.xml").to_string();
    let xml_limit = max_len.min(MAX_MAIN_XML_BYTES);
    let xml = read_entry(&mut archive, &main_xml, EntrySize::AtMost(xml_limit))?;
    let doc = X3pDocument::parse(&xml)?;
    verify_main_xml(&mut archive, &doc, &folder, &xml, max_len)?;
    Ok(Opened {
        archive,
        folder,
        doc,
    })
}

/// SizeX × SizeY as `main.xml` declares them, without reading the point data.
pub(crate) fn declared_points(bytes: &[u8]) -> Option<usize> {
    let Opened { doc, .. } = open(bytes, bytes.len().saturating_mul(MAX_DEFLATE_RATIO)).ok()?;
    dimension(&doc, "SizeX")
        .ok()?
        .checked_mul(dimension(&doc, "SizeY").ok()?)
}

/// Parses an X3P file.
pub(crate) fn parse(bytes: &[u8]) -> Result<Topography, ParseError> {
    let max_len = bytes.len().saturating_mul(MAX_DEFLATE_RATIO);
    let mut opened = open(bytes, max_len)?;
    let doc = &opened.doc;
    let feature = doc.get("Record1/FeatureType").unwrap_or("SUR").to_string();
    if feature != "SUR" && feature != "PRF" {
        return Err(ParseError::unsupported(format!(
            "x3p: FeatureType {feature:?} (only SUR surfaces and PRF profiles are read)"
        )));
    }
    let (dx, x_offset) = incremental_axis(doc, "CX")?;
    let (nx, ny) = matrix_size(doc, bytes.len(), max_len)?;
    let z_axis = HeightEncoding::from_doc(doc)?;
    let mut heights = read_heights(&mut opened, nx * ny, &z_axis)?;
    apply_valid_points(&mut opened, &mut heights, max_len)?;
    let doc = &opened.doc;
    let mut metadata = metadata(doc);
    metadata.insert("x_offset_m".into(), x_offset.to_string());
    metadata.insert("z_data_type".into(), format!("{:?}", z_axis.sample));

    let data = if feature == "PRF" || ny == 1 {
        if ny != 1 {
            return Err(ParseError::unsupported(format!(
                "x3p: profile (PRF) with SizeY = {ny}; only single profiles are read"
            )));
        }
        let x = (0..nx).map(|i| i as f64 * dx).collect();
        TopographyData::Line(LineScan { x, z: heights })
    } else {
        let (dy, y_offset) = incremental_axis(doc, "CY")?;
        metadata.insert("y_offset_m".into(), y_offset.to_string());
        let grid = Array2::from_shape_vec((ny, nx), heights)
            .map_err(|e| ParseError::malformed(format!("x3p: matrix shape: {e}")))?;
        let map =
            HeightMap::new(grid, dx, dy).map_err(|e| ParseError::malformed(format!("x3p: {e}")))?;
        TopographyData::Areal(map)
    };
    Ok(Topography {
        spacing: ScaleSource::File,
        height_unit: ScaleSource::File,
        data,
        channel: None,
        channels: Vec::new(),
        metadata,
    })
}

/// SizeX and SizeY of one layer (SizeZ 1), at most [`MAX_POINTS`] and no more than a file of
/// `len` bytes can inflate to (`max_len`).
fn matrix_size(doc: &X3pDocument, len: usize, max_len: usize) -> Result<(usize, usize), ParseError> {
    let nx = dimension(doc, "SizeX")?;
    let ny = dimension(doc, "SizeY")?;
    let nz = doc
        .get("Record3/MatrixDimension/SizeZ")
        .map_or(Ok(1), |_| dimension(doc, "SizeZ"))?;
    if nz != 1 {
        return Err(ParseError::unsupported(format!(
            "x3p: {nz} layers (SizeZ); only single-layer files are read"
        )));
    }
    let n = check_points(nx, ny, "x3p: Record3/MatrixDimension")?;
    if n > max_len {
        return Err(ParseError::malformed(format!(
            "x3p: matrix {nx} × {ny} cannot fit in a {len} byte file"
        )));
    }
    Ok((nx, ny))
}

/// The `n` heights in metres, from the binary member `PointDataLink` (its MD5 sum checked) or
/// the inline `DataList` (an empty `Datum` is `NaN`).
fn read_heights(
    opened: &mut Opened<'_>,
    n: usize,
    z_axis: &HeightEncoding,
) -> Result<Vec<f64>, ParseError> {
    let doc = &opened.doc;
    if let Some(link) = doc.get("Record3/DataLink/PointDataLink") {
        let name = format!("{}{link}", opened.folder);
        let expected = n * z_axis.sample.size();
        let raw = read_entry(&mut opened.archive, &name, EntrySize::Exactly(expected))?;
        let recorded = doc.get("Record3/DataLink/MD5ChecksumPointData");
        verify(&name, &raw, recorded.unwrap_or(""), "MD5ChecksumPointData")?;
        let values = decode_samples(&raw, n, z_axis.sample, Endian::Little, "x3p point data")?;
        Ok(values.into_iter().map(|v| z_axis.to_metres(v)).collect())
    } else if let Some(list) = &doc.data_list {
        if list.len() != n {
            let (nx, ny) = (dimension(doc, "SizeX")?, dimension(doc, "SizeY")?);
            return Err(ParseError::malformed(format!(
                "x3p: DataList holds {} points, MatrixDimension says {nx} × {ny} = {n}",
                list.len()
            )));
        }
        Ok(list
            .iter()
            .map(|v| v.map_or(f64::NAN, |v| z_axis.to_metres(v)))
            .collect())
    } else {
        Err(ParseError::malformed(
            "x3p: Record3 has neither DataLink/PointDataLink nor DataList",
        ))
    }
}

/// Marks the points the member `ValidPointsLink` (when the file has one; its MD5 sum checked)
/// says are invalid as `NaN`.
fn apply_valid_points(
    opened: &mut Opened<'_>,
    heights: &mut [f64],
    max_len: usize,
) -> Result<(), ParseError> {
    let Some(link) = opened.doc.get("Record3/DataLink/ValidPointsLink") else {
        return Ok(());
    };
    let name = format!("{}{link}", opened.folder);
    let mask_limit = max_len.min(MAX_POINTS.div_ceil(8));
    let mask = read_entry(&mut opened.archive, &name, EntrySize::AtMost(mask_limit))?;
    let recorded = opened.doc.get("Record3/DataLink/MD5ChecksumValidPoints");
    verify(
        &name,
        &mask,
        recorded.unwrap_or(""),
        "MD5ChecksumValidPoints",
    )?;
    apply_validity_mask(heights, &mask, &name)
}

/// Checks `main.xml` against the MD5 sum in the checksum member (`Record4/ChecksumFile`, by
/// default `md5checksum.hex`), when the archive has one.
fn verify_main_xml(
    archive: &mut ZipArchive<Cursor<&[u8]>>,
    doc: &X3pDocument,
    folder: &str,
    xml: &[u8],
    max_len: usize,
) -> Result<(), ParseError> {
    let file = doc
        .get("Record4/ChecksumFile")
        .filter(|f| !f.is_empty())
        .unwrap_or("md5checksum.hex");
    let name = format!("{folder}{file}");
    if archive.index_for_name(&name).is_none() {
        return Ok(());
    }
    let content = read_entry(archive, &name, EntrySize::AtMost(max_len.min(4096)))?;
    verify(
        &format!("{folder}main.xml"),
        xml,
        &checksum_file_sum(&content),
        &name,
    )
}

/// How raw CZ values become heights in metres.
#[derive(Debug, Clone, Copy)]
struct HeightEncoding {
    sample: SampleType,
    increment: f64,
    offset: f64,
}

impl HeightEncoding {
    fn from_doc(doc: &X3pDocument) -> Result<Self, ParseError> {
        let code = doc.get("Record1/Axes/CZ/DataType").unwrap_or("D");
        let sample = match code {
            "I" => SampleType::I16,
            "L" => SampleType::I32,
            "F" => SampleType::F32,
            "D" => SampleType::F64,
            other => {
                return Err(ParseError::malformed(format!(
                    "x3p: CZ DataType {other:?} (expected I, L, F or D)"
                )))
            }
        };
        Ok(Self {
            sample,
            increment: number_or(doc, "Record1/Axes/CZ/Increment", 1.0)?,
            offset: number_or(doc, "Record1/Axes/CZ/Offset", 0.0)?,
        })
    }

    /// Height in metres for one stored value; non-finite values are invalid points (`NaN`).
    fn to_metres(self, raw: f64) -> f64 {
        let z = if self.sample.is_integer() {
            raw * self.increment + self.offset
        } else {
            raw
        };
        if z.is_finite() {
            z
        } else {
            f64::NAN
        }
    }
}

/// Increment and offset (m) of the incremental lateral axis `CX` or `CY`.
fn incremental_axis(doc: &X3pDocument, axis: &str) -> Result<(f64, f64), ParseError> {
    let kind = doc
        .get(&format!("Record1/Axes/{axis}/AxisType"))
        .unwrap_or("I");
    if kind != "I" {
        return Err(ParseError::unsupported(format!(
            "x3p: {axis} AxisType {kind:?}; only incremental (I) lateral axes are read"
        )));
    }
    let path = format!("Record1/Axes/{axis}/Increment");
    let inc_text = doc
        .get(&path)
        .ok_or_else(|| ParseError::malformed(format!("x3p: {path} is missing")))?;
    let increment: f64 = inc_text
        .parse()
        .ok()
        .filter(|v: &f64| v.is_finite() && *v > 0.0)
        .ok_or_else(|| {
            ParseError::malformed(format!("x3p: {path} = {inc_text:?} is not a spacing > 0"))
        })?;
    let offset = number_or(doc, &format!("Record1/Axes/{axis}/Offset"), 0.0)?;
    Ok((increment, offset))
}

/// The number at `path`; `default` when the element is absent or empty.
fn number_or(doc: &X3pDocument, path: &str, default: f64) -> Result<f64, ParseError> {
    match doc.get(path) {
        None | Some("") => Ok(default),
        Some(t) => t
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| ParseError::malformed(format!("x3p: {path} = {t:?} is not a number"))),
    }
}

fn dimension(doc: &X3pDocument, name: &str) -> Result<usize, ParseError> {
    let path = format!("Record3/MatrixDimension/{name}");
    let text = doc
        .get(&path)
        .ok_or_else(|| ParseError::malformed(format!("x3p: {path} is missing")))?;
    text.parse::<usize>()
        .ok()
        .filter(|&v| v > 0)
        .ok_or_else(|| ParseError::malformed(format!("x3p: {path} = {text:?} is not a count > 0")))
}

/// The `main.xml` entry: at the top level or in one sub-folder, ignoring `__MACOSX/` copies.
fn find_main_xml(archive: &ZipArchive<Cursor<&[u8]>>) -> Result<String, ParseError> {
    let mut candidates: Vec<String> = archive
        .file_names()
        .filter_map(Result::ok)
        .map(|n| n.into_owned())
        .filter(|n| !n.starts_with("__MACOSX/") && (n == "main.xml" || n.ends_with("/main.xml")))
        .collect();
    candidates.sort_by_key(|n| (n.matches('/').count(), n.clone()));
    candidates
        .into_iter()
        .next()
        .ok_or_else(|| ParseError::malformed("x3p: the archive has no main.xml"))
}

/// The size an archive entry must have.
#[derive(Debug, Clone, Copy)]
enum EntrySize {
    /// Exactly this many bytes (point data: matrix size × sample size).
    Exactly(usize),
    /// At most this many bytes (the deflate-ratio bound).
    AtMost(usize),
}

/// Largest buffer reserved before decompressing; bigger entries grow as real data arrives,
/// so a lying size field alone cannot trigger a huge allocation.
const MAX_RESERVE: usize = 1 << 26;

/// Decompresses one archive entry after checking its declared size.
fn read_entry(
    archive: &mut ZipArchive<Cursor<&[u8]>>,
    name: &str,
    size: EntrySize,
) -> Result<Vec<u8>, ParseError> {
    let index = archive
        .index_for_name(name)
        .ok_or_else(|| ParseError::malformed(format!("x3p: {name} is missing from the archive")))?;
    let mut file = archive
        .by_index(index)
        .map_err(|e| ParseError::malformed(format!("x3p: cannot open {name}: {e}")))?;
    let claimed = usize::try_from(file.size()).unwrap_or(usize::MAX);
    let limit = match size {
        EntrySize::Exactly(expected) if claimed != expected => {
            return Err(ParseError::malformed(format!(
                "x3p: {name} holds {claimed} bytes, the matrix size and data type need {expected}"
            )))
        }
        EntrySize::Exactly(expected) => expected,
        EntrySize::AtMost(max) if claimed > max => {
            return Err(ParseError::malformed(format!(
                "x3p: {name} claims {claimed} bytes uncompressed, impossible for this file size"
            )))
        }
        EntrySize::AtMost(max) => max,
    };
    let mut out = Vec::with_capacity(claimed.min(MAX_RESERVE));
    (&mut file)
        .take(limit as u64 + 1)
        .read_to_end(&mut out)
        .map_err(|e| {
            ParseError::malformed(format!("x3p: cannot decompress {name} (corrupted?): {e}"))
        })?;
    if out.len() != claimed {
        return Err(ParseError::truncated(format!(
            "x3p: {name} decompressed to {} bytes, the archive says {claimed}",
            out.len()
        )));
    }
    Ok(out)
}

/// Sets points whose bit in the validity mask is 0 to `NaN` (bit k of byte k/8, LSB first).
fn apply_validity_mask(heights: &mut [f64], mask: &[u8], name: &str) -> Result<(), ParseError> {
    let needed = heights.len().div_ceil(8);
    if mask.len() < needed {
        return Err(ParseError::truncated(format!(
            "x3p: validity mask {name} has {} bytes, {} points need {needed}",
            mask.len(),
            heights.len()
        )));
    }
    for (k, z) in heights.iter_mut().enumerate() {
        if mask[k / 8] & (1 << (k % 8)) == 0 {
            *z = f64::NAN;
        }
    }
    Ok(())
}

fn metadata(doc: &X3pDocument) -> BTreeMap<String, String> {
    let fields = [
        ("revision", "Record1/Revision"),
        ("feature_type", "Record1/FeatureType"),
        ("date", "Record2/Date"),
        ("creator", "Record2/Creator"),
        ("instrument_manufacturer", "Record2/Instrument/Manufacturer"),
        ("instrument_model", "Record2/Instrument/Model"),
        ("instrument_serial", "Record2/Instrument/Serial"),
        ("instrument_version", "Record2/Instrument/Version"),
        ("calibration_date", "Record2/CalibrationDate"),
        ("probing_system_type", "Record2/ProbingSystem/Type"),
        ("probing_system", "Record2/ProbingSystem/Identification"),
        ("comment", "Record2/Comment"),
    ];
    let mut out = BTreeMap::new();
    out.insert("x3p_root_element".to_string(), doc.root.clone());
    for (key, path) in fields {
        if let Some(v) = doc.get(path).filter(|v| !v.is_empty()) {
            out.insert(key.to_string(), v.to_string());
        }
    }
    out
}
