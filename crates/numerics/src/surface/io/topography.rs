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
    /// Name of the channel read, for multi-channel files (e.g. "ZSensor").
    pub channel: Option<String>,
    /// Free-form metadata from the file header (instrument, date, original units, …).
    pub metadata: BTreeMap<String, String>,
}
