//! The result of reading a topography file.

use std::collections::BTreeMap;

use crate::surface::HeightMap;

/// A 1-D line scan (stylus profile), possibly on a non-uniform x grid.
#[derive(Debug, Clone, PartialEq)]
pub struct LineScan {
    /// Positions along the scan in metres, strictly increasing.
    pub x: Vec<f64>,
    /// Heights in metres, `NaN` where missing.
    pub z: Vec<f64>,
}

/// Areal map or line scan.
#[derive(Debug, Clone, PartialEq)]
pub enum TopographyData {
    Areal(HeightMap),
    Line(LineScan),
}

/// Where a physical scale of a [`Topography`] came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScaleSource {
    /// Stated by the file.
    File,
    /// Not in the file: the reader used 1 m per pixel (spacing) or metres (heights), a
    /// placeholder the caller must replace with the real value (e.g. a surface node's
    /// `pixel_size`), never a result.
    Assumed,
}

/// A topography read from a file: data in SI units plus what the file says about itself.
#[derive(Debug, Clone, PartialEq)]
pub struct Topography {
    pub data: TopographyData,
    /// Where the lateral spacing (or the x positions of a line scan) came from.
    pub spacing: ScaleSource,
    /// Where the height unit came from.
    pub height_unit: ScaleSource,
    /// Name of the channel read (e.g. "ZSensor"); set by every reader of the registry
    /// ([`super::Reader::parse`]), the one channel of a single-channel file included.
    pub channel: Option<String>,
    /// Every channel of the file, in file order (filled by [`super::Reader::parse`]).
    pub channels: Vec<String>,
    /// Free-form metadata from the file header (date, original units, …); the keys
    /// [`METADATA_VENDOR`] and [`METADATA_INSTRUMENT`] name the maker and the instrument when
    /// the file says.
    pub metadata: BTreeMap<String, String>,
}

/// Metadata key of the instrument's maker ("Zygo", "Bruker").
pub const METADATA_VENDOR: &str = "vendor";
/// Metadata key of the instrument model or name, as the file states it.
pub const METADATA_INSTRUMENT: &str = "instrument";
